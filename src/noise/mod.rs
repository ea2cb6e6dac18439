//! The Appendix of the paper, *Estimator signal-to-noise ratio*: the noise
//! model and the moments of a sample ([`model`]), the closed forms of the
//! estimators' biases and variances as printed and exact ([`appendix`]), the
//! worked examples ([`example`]), the exact variance over any window of bins
//! ([`window_variance`]), and the Monte Carlo of noisy interferograms that
//! checks them ([`simulation`]); [`report`] is the answer of `v2ref snr` and
//! Python's `v2ref.snr`.
//!
//! Everything of [`model`], [`appendix`] and [`example`] is also reachable
//! as `v2ref::noise::X`.

pub mod appendix;
pub mod calibrated;
pub mod example;
pub mod model;
pub mod report;
pub mod simulation;
pub mod snr_value;
pub mod window_variance;

pub use appendix::*;
pub use example::*;
pub use model::*;
