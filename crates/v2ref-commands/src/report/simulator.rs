//! The answer of `v2ref simulate` (its JSON document) and of Python's
//! `v2ref.simulate`: built here, once, so that the command line and the
//! Python package cannot drift apart.

use crate::error::{Error, Result};
use crate::formalism::estimator::BinWindow;
use crate::noise::calibrated::Trials;
use crate::noise::Formula;
use crate::simulator::estimate::BiasConvention;
use crate::simulator::rows::PistonFacts;
use crate::simulator::run::{PistonEffect, SimulationRun};
use crate::simulator::Inputs;
use serde::Serialize;

/// Largest number of trials a simulation accepts (2^40: its statistics are
/// merged in batches, so memory does not grow with it).
pub const MAX_TRIALS: u64 = 1 << 40;

/// Fewest trials a simulation accepts: the standard error of a sample
/// variance needs the fourth moment of at least 4 draws (with 2 or 3 it is
/// undefined, and a report would hold no number where one belongs).
pub const MIN_TRIALS: u64 = 4;

/// Refuses fewer than [`MIN_TRIALS`] or more than [`MAX_TRIALS`] trials.
pub fn check_trials(trials: u64) -> Result<()> {
    if (MIN_TRIALS..=MAX_TRIALS).contains(&trials) {
        Ok(())
    } else {
        Err(Error::OutOfRange {
            param: "trials",
            value: trials as f64,
            accepted: format!(
                "{MIN_TRIALS} to {MAX_TRIALS} (the standard error of the variance needs at least {MIN_TRIALS} trials)"
            ),
        })
    }
}

/// How each row was estimated: the bins summed, where the photon bias takes
/// its counts from, and the formula of the bias subtracted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Estimation {
    /// The bins the estimators sum.
    pub window: BinWindow,
    /// Model counts or each row's own.
    pub bias: BiasConvention,
    /// As printed in the paper, or exact.
    pub formula: Formula,
}

/// The running statistics of the calibrated V1² and V2² over the trials,
/// beside their closed-form expectations, and every input.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SimulateReport {
    /// Formula of the subtracted bias.
    pub formula: Formula,
    /// The bins summed.
    pub bins: String,
    /// Where the photon bias takes the mean counts from.
    pub bias: BiasConvention,
    /// N.
    pub samples: usize,
    /// Mean of V1² over the trials.
    pub mean_v1_sq: f64,
    /// Mean of V2².
    pub mean_v2_sq: f64,
    /// Variance of V1² (n − 1).
    pub var_v1_sq: f64,
    /// Variance of V2².
    pub var_v2_sq: f64,
    /// Standard error of the mean of V1².
    pub stderr_mean_v1_sq: f64,
    /// Standard error of the mean of V2².
    pub stderr_mean_v2_sq: f64,
    /// Standard error of the variance of V1².
    pub stderr_var_v1_sq: f64,
    /// Standard error of the variance of V2².
    pub stderr_var_v2_sq: f64,
    /// Closed-form expectation of the normalized V1² (None with piston).
    pub expected_mean_v1_sq: Option<f64>,
    /// Same for V2².
    pub expected_mean_v2_sq: Option<f64>,
    /// Exact closed-form variance of the normalized V1² over the window.
    pub expected_var_v1_sq: Option<f64>,
    /// Same for V2².
    pub expected_var_v2_sq: Option<f64>,
    /// Number of trials.
    pub trials: u64,
    /// Seed.
    pub seed: u64,
    /// The piston sequence (None without a fringe frequency).
    pub piston: Option<PistonFacts>,
    /// With piston and no noise: V − V(no piston) (what `piston` reports).
    pub piston_effect: Option<PistonEffect>,
    /// Every physical input.
    pub inputs: Inputs,
}

impl SimulateReport {
    /// The report of `run`, a simulation of `inputs` estimated as
    /// `estimation` with `size` trials.
    pub fn new(
        inputs: Inputs,
        estimation: Estimation,
        size: Trials,
        run: &SimulationRun,
    ) -> SimulateReport {
        let (v1, v2, e) = (&run.v1_sq, &run.v2_sq, run.expected.as_ref());
        SimulateReport {
            formula: estimation.formula,
            bins: estimation.window.name().to_owned(),
            bias: estimation.bias,
            samples: inputs.samples,
            mean_v1_sq: v1.mean,
            mean_v2_sq: v2.mean,
            var_v1_sq: v1.var,
            var_v2_sq: v2.var,
            stderr_mean_v1_sq: v1.stderr_mean,
            stderr_mean_v2_sq: v2.stderr_mean,
            stderr_var_v1_sq: v1.stderr_var,
            stderr_var_v2_sq: v2.stderr_var,
            expected_mean_v1_sq: e.map(|e| e.mean_v1_sq),
            expected_mean_v2_sq: e.map(|e| e.mean_v2_sq),
            expected_var_v1_sq: e.and_then(|e| e.var_v1_sq),
            expected_var_v2_sq: e.and_then(|e| e.var_v2_sq),
            trials: size.trials,
            seed: size.seed,
            piston: run.piston,
            piston_effect: run.piston_effect,
            inputs,
        }
    }
}
