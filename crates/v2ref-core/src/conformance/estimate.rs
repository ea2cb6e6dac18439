//! Per-row estimates: what a pipeline computes from each interferogram —
//! V1² and V2² raw, bias-subtracted and normalized, under a window of bins,
//! a [`BiasConvention`] and a calibrator ([`RowEstimator`], and its slow
//! oracle [`estimate_row_oracle`]).
//!
//! The estimator is the simulator's own (`simulator::estimate`,
//! where it is defined and documented: `simulate` reduces rows with it),
//! re-exported here as the conformance kit's reference.

pub use crate::simulator::estimate::*;
