//! The paper's reproduction: its cases (parameters, seeds, effort), its
//! figures as data tables, the claims ledger computed, the golden files and
//! the plots.

#![warn(missing_docs)]
#![warn(unnameable_types)]

// The modules of the crates below under their own names, so that a path
// reads the same in every crate of the workspace (`crate::formalism::…`).
#[allow(unused_imports)]
pub(crate) use v2ref_core::{
    bias, bounds, csv_lines, error, formalism, math, montecarlo, noise, piston, tolerance, Error,
    Result,
};
#[allow(unused_imports)]
pub(crate) use v2ref_files::atomic;

pub mod cases;
pub mod claims;
pub mod figures;
pub mod golden;
pub mod plot;
pub mod table;
