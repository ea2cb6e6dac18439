//! The Appendix of the paper, *Estimator signal-to-noise ratio*: the noise
//! moments of a sample, the closed forms of the estimators' biases and
//! variances (as printed and exact), the exact variance over any window of
//! bins, and the Monte Carlo of noisy interferograms that checks them.

pub mod calibrated;
pub mod moments;
pub mod simulation;
pub mod window_variance;

pub use moments::*;
