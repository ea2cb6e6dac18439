//! The Appendix of the paper, *Estimator signal-to-noise ratio*: the noise
//! model and the moments of a sample (`model`), the closed forms of the
//! estimators' biases and variances as printed and exact (`appendix`), the
//! worked examples (`example`), the exact variance over any window of bins
//! ([`window_variance`]), and the Monte Carlo of noisy interferograms that
//! checks them ([`simulation`]); `report` (internal) is the answer of `v2ref snr` and
//! Python's `v2ref.snr`.
//!
//! The items of `model`, `appendix` and `example` are public here, as
//! `v2ref_core::noise::X` (their one path).

pub mod appendix;
pub mod calibrated;
pub(crate) mod example;
pub(crate) mod model;
pub mod simulation;
pub mod snr_value;
pub mod window_variance;

pub use appendix::*;
pub use example::*;
pub use model::*;
