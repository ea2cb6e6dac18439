//! Each command's answer, built once: from the physical inputs
//! ([`crate::parameters::Physical`]) and the command's own options, the
//! typed answer (inputs echoed, results, units) that the CLI prints as a
//! table or JSON and Python returns as a dictionary. The edges only parse,
//! convert and print; nothing here reads a flag, writes a file or prints.

pub mod bias;
pub mod channels;
pub mod channels_simulate;
pub mod estimate;
pub mod piston;
pub mod plan;
pub mod snr;
pub mod targets;
mod targets_table;
// The oracle's, where its sets in memory are built (`v2ref_core::oracle`).
pub use crate::conformance::synth;

pub use crate::simulator::estimate::ESTIMATE_COLUMNS;
