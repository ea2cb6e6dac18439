//! Each command's answer, built once: from the physical inputs
//! ([`crate::parameters::Physical`]) and the command's own options, the
//! typed answer (inputs echoed, results, units) that the CLI prints as a
//! table or JSON and Python returns as a dictionary. The edges only parse,
//! convert and print; nothing here reads a flag, writes a file or prints.

#[cfg(feature = "internals")]
pub mod bias;
// The cost laws were timed on one machine: the edges' (the CLI's notice,
// Python's warning), not the numerics'.
#[cfg(any(feature = "cli", feature = "python"))]
pub mod cost;
#[cfg(feature = "internals")]
pub mod estimate;
#[cfg(feature = "internals")]
pub mod piston;
#[cfg(feature = "internals")]
pub mod plan;
#[cfg(feature = "internals")]
pub mod snr;
// The one the stable surface uses ([`crate::oracle`]'s sets in memory).
pub mod synth;

#[cfg(feature = "internals")]
pub use crate::simulator::estimate::ESTIMATE_COLUMNS;
