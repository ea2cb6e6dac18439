//! # v2ref-commands — each command's answer, built once, and the planner
//!
//! The command line and the Python package of v2ref only parse, convert and
//! print; what they print is built here, once, from the physical inputs
//! ([`parameters::Physical`]) and each command's own options:
//!
//! - [`commands`]: the answers of `bias`, `snr`, `simulate`, `piston`,
//!   `estimate`, `synth` and `plan` (inputs echoed, results, units);
//! - [`report`]: the reports those answers hold;
//! - [`record`]: the `inputs` object each answer carries;
//! - [`parameters`]: the physical inputs, declared once (unit, range, help);
//! - [`plan`]: the observation planner — which estimator, fringe frequency
//!   and stroke reach a target σ(V²), with how many scans, for a named
//!   instrument or any other.
//!
//! The planner lives here rather than in the oracle library `v2ref`: its
//! audience is the observer at the command line or in Python, not a
//! pipeline's `cargo test`, and it is made of the same inputs' table,
//! reports and progress as the other commands. It is built on `v2ref`'s
//! public numerics alone.
//!
//! Unstable: this crate serves the workspace's command line and Python
//! bindings; a pipeline's route is `v2ref` (its `oracle`).

#![warn(missing_docs)]
#![warn(unnameable_types)]

// The oracle's modules under their own names, so that a path reads the same
// in every crate of the workspace (`crate::formalism::…`).
#[allow(unused_imports)]
pub(crate) use v2ref_core::{
    bias, bounds, conformance, error, formalism, math, montecarlo, noise, piston, simulator,
    tolerance, words, Error, Result,
};

pub mod commands;
pub mod parameters;
pub mod plan;
pub mod record;
pub mod report;
pub mod text;
pub mod units;
