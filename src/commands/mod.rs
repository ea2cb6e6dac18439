//! Each command's answer, built once: from the physical inputs
//! ([`crate::parameters::Physical`]) and the command's own options, the
//! typed answer (inputs echoed, results, units) that the CLI prints as a
//! table or JSON and Python returns as a dictionary. The edges only parse,
//! convert and print; nothing here reads a flag, writes a file or prints.

pub mod bias;
pub mod piston;
pub mod plan;
pub mod snr;

/// The columns of `estimate`'s answer, in order (the CLI's CSV header,
/// Python's `ESTIMATE_COLUMNS`).
pub const ESTIMATE_COLUMNS: [&str; 6] = [
    "v1_sq_raw",
    "v2_sq_raw",
    "v1_sq_bias",
    "v2_sq_bias",
    "v1_sq",
    "v2_sq",
];
