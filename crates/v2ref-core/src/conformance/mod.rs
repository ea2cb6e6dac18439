//! The conformance kit: a pipeline's own estimator checked against v2ref.
//!
//! - [`crate::simulator`] makes test interferograms with every effect of the
//!   paper at once; `v2ref synth` writes them with a sidecar ([`sidecar`])
//!   that carries the inputs and the truth ([`truth`]);
//! - [`estimate`] computes, per row, V1² and V2² raw, bias-subtracted and
//!   normalized, under a chosen window of bins, bias convention and
//!   calibrator — what a pipeline is expected to compute;
//! - [`score`] compares a pipeline's per-row estimates with the truth: mean
//!   and variance as z-scores, a verdict at a stated threshold, and the
//!   power of the test.
//!
//! - [`channels`] and [`channel_score`]: the same for a dispersed set, C
//!   spectral channels per scan — the rows, the truth and the verdict per
//!   channel, under one family-wise threshold over every channel.
//!
//! What a pipeline must match (sample positions, bins for even and odd N,
//! normalization, bias) is written out in `docs/conventions.md`.

pub mod channel_score;
pub mod channels;
pub mod estimate;
pub mod score;
pub mod sidecar;
pub mod synth;
pub mod truth;
pub mod vectors;
