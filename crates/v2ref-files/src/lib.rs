//! # v2ref-files — files in and out for the command line and Python
//!
//! - [`atomic`]: each output placed whole, by one rename of a complete,
//!   synced temporary held under its writer's lock; a reader never writes;
//!   no link found in a folder is followed (the repository's
//!   `docs/threat-model.md`);
//! - [`cleanup`]: the stale temporaries a writer may sweep;
//! - [`formats`]: NumPy `.npy`, CSV, the spectrum table, the memory budget.
//!
//! Unstable: this crate serves the workspace's command line and Python
//! bindings; a pipeline's route is `v2ref` (its `oracle`).

#![warn(missing_docs)]
#![warn(unnameable_types)]

// The oracle's modules under their own names, so that a path reads the same
// in every crate of the workspace (`crate::formalism::…`).
#[allow(unused_imports)]
pub(crate) use v2ref_core::{
    bounds, conformance, csv_lines, error, formalism, manifest, noise, simulator, Error, Result,
};

pub mod atomic;
pub mod cleanup;
pub mod formats;
