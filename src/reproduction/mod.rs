//! The paper's reproduction: its cases (parameters, seeds, effort), its
//! figures as data tables, the claims ledger computed, the golden files and
//! the plots.

pub mod cases;
pub mod claims;
pub mod figures;
pub mod golden;
#[cfg(feature = "cli")]
pub mod plot;
pub mod table;
