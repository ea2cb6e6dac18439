//! # v2ref-core — the numerics behind `v2ref`
//!
//! The paper's formalism, biases, noise and piston, the simulator, the
//! conformance truth and score and the oracle route, with every helper
//! public for the workspace's own crates (the commands and the planner,
//! files, OIFITS, the reproduction, Python, the command line) and its test
//! suite. **Not stable**: a pipeline and a reader of the paper use the
//! crate `v2ref`, which re-exports the stable surface of these items (its
//! docs map each equation of the paper to its function and test).
//!
//! The modules follow the paper: [`formalism`] (§§1–2), [`bias`] (§§3–5),
//! [`piston`] (§6), [`noise`] (the appendix), [`simulator`] (all effects at
//! once), [`conformance`] (the conformance kit), [`oracle`] (a pipeline's
//! `cargo test`); with [`math`], [`montecarlo`], [`bounds`],
//! [`tolerance`] (one home for tolerances, and the assertion macros) and
//! [`Error`].
//!
//! ## Levels
//!
//! The crates form levels, and so do the modules of this one: a module uses
//! only modules of its own level or below (`tests/architecture.rs` checks every
//! `use` of `crates/v2ref-core/src/`, and the crate graph does the rest), so that
//! each can be read, tested and changed with only what is under it in mind:
//!
//! 1. foundation: `error` ([`Error`]), [`tolerance`], [`bounds`], [`math`], [`montecarlo`], [`words`] (the words that name each choice), [`manifest`] (the member list of a set of files), [`text`] (text from data made safe to show), [`photometric_band`] (the bands a magnitude is in), [`target_list`] (the target list's CSV, read below the file readers and the planner);
//! 2. [`formalism`];
//! 3. [`record`] (the inputs of a computation as plain values);
//! 4. [`bias`];
//! 5. [`noise`], [`piston`];
//! 6. [`simulator`];
//! 7. [`conformance`];
//! 8. the oracle's gathering modules: [`prelude`], [`oracle`] (a pipeline's `cargo test`);
//! 9. the crates above this one, each using only crates below it: `v2ref` (the stable surface, re-exports only), `v2ref-commands` (the commands' answers and the planner) and `v2ref-files` (files in and out), side by side on this crate alone; then `v2ref-reproduction` (on `v2ref-files`) and `v2ref-oifits` (on both); then the edges, `v2ref-python` and the command line.
//!

#![warn(missing_docs)]
// A type a public item shows (a field, an argument, a return) is public too.
#![warn(unnameable_types)]

// The modules; the stable surface is the crate `v2ref`'s re-exports.
pub mod bias;
pub mod bounds;
pub mod conformance;
pub mod csv_lines;
pub mod error;
pub mod formalism;
pub mod manifest;
pub mod math;
pub mod montecarlo;
pub mod noise;
pub mod oracle;
pub mod photometric_band;
pub mod piston;
pub mod prelude;
pub mod record;
pub mod simulator;
pub mod target_list;
pub mod text;
pub mod tolerance;
pub mod words;

pub use error::{Error, Result};
