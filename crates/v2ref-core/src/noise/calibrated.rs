//! Bias-subtracted, calibrated estimators: what an observer computes from a
//! noisy interferogram. Each estimate of the window is reduced by the noise
//! bias (in the chosen [`Formula`]) and divided by the noise-free estimate of
//! a calibrator (point source, V = 1, same photons), so that an unbiased
//! estimator of a source of visibility V has mean V².
//!
//! [`expectation`] gives the closed forms (no Monte Carlo):
//!
//! * mean: `(signal + true_bias − bias) / calib`, with `signal` the
//!   noise-free estimate of the window, `true_bias` the exact noise bias and
//!   `bias` the one subtracted (equal to `true_bias` for [`Formula::Exact`]);
//! * variance: the exact windowed variance
//!   ([`window_stats`]) over
//!   `calib²`, computed up to [`MAX_WINDOW_SAMPLES`] samples.
//!
//! [`calibrated_run`] adds the Monte Carlo and normalizes its accumulated
//! moments exactly (an affine map of each trial).

use crate::error::{Error, Result};
use crate::formalism::estimator::{dft, raw_sums, BinWindow, Pair};
use crate::formalism::interferogram::{Interferogram, Sampling};
use crate::formalism::observation::Observation;
use crate::montecarlo::{RunningStats, Summary};
use crate::noise::simulation::{simulate_noisy, NoisyRun, NoisySpec};
use crate::noise::window_variance::window_stats;
use crate::noise::{scaled_interferogram, window_bias, Formula, NoiseModel};
use serde::Serialize;

/// Largest N for which the exact windowed variance (N × N matrices) is
/// computed.
pub const MAX_WINDOW_SAMPLES: usize = 4096;

/// The noise-free interferograms of a calibrated measurement and the bins
/// its estimators sum.
#[derive(Debug, Clone)]
pub struct CalibratedSetup {
    /// The source's interferogram, fringe scaled by the visibility.
    pub signal: Interferogram,
    /// The calibrator's (point source, V = 1, same photons).
    pub calibrator: Interferogram,
    /// The window's bins.
    pub bins: Vec<usize>,
}

impl CalibratedSetup {
    /// The source of `obs` with `photons` continuum photons per sample and
    /// its fringe scaled by `visibility` (0 to 1), its calibrator, and the
    /// bins of `window`.
    pub fn new(
        obs: &Observation,
        sampling: &Sampling,
        photons: f64,
        visibility: f64,
        window: BinWindow,
    ) -> Result<CalibratedSetup> {
        crate::bounds::non_negative_at_most("photons", photons, crate::bounds::PHOTONS_MAX)?;
        let signal = scaled_interferogram(obs, sampling, photons, visibility)?;
        let calibrator = scaled_interferogram(&obs.calibrator(), sampling, photons, 1.0)?;
        let bins = window.bins(sampling.samples(), sampling.dx_um(), &obs.spectrum)?;
        Ok(CalibratedSetup {
            signal,
            calibrator,
            bins,
        })
    }

    /// The calibrator's noise-free estimates over the window; refused when
    /// either is not > 0 (nothing to normalize by).
    pub fn calibration(&self) -> Result<Pair> {
        let calib = raw_sums(&dft(&self.calibrator.modulated), &self.bins);
        if calib.v1_sq > 0.0 && calib.v2_sq > 0.0 {
            Ok(calib)
        } else {
            Err(Error::Invalid {
                param: "bins",
                reason: "the window holds no fringe of the calibrator (nothing to normalize by); choose the all or positive window, or more photons".into(),
            })
        }
    }
}

/// Closed-form expectations of the calibrated estimators.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CalibratedExpectation {
    /// The calibrator's noise-free estimates (the divisors).
    pub calibration: Pair,
    /// The source's noise-free estimates over the window.
    pub signal: Pair,
    /// The exact noise bias of the window.
    pub true_bias: Pair,
    /// The bias subtracted (the chosen formula's).
    pub subtracted_bias: Pair,
    /// Expected calibrated V1²: `(signal + true_bias − bias) / calib`.
    pub mean_v1_sq: f64,
    /// Same for V2².
    pub mean_v2_sq: f64,
    /// Exact variance of the calibrated V1² (None above
    /// [`MAX_WINDOW_SAMPLES`] samples).
    pub var_v1_sq: Option<f64>,
    /// Same for V2².
    pub var_v2_sq: Option<f64>,
}

/// The closed-form mean and variance of the calibrated estimators of
/// `setup` under `noise`, with the `formula`'s bias subtracted.
pub fn expectation(
    setup: &CalibratedSetup,
    noise: &NoiseModel,
    formula: Formula,
) -> Result<CalibratedExpectation> {
    let calibration = setup.calibration()?;
    let ifg = &setup.signal;
    let bias_of = |f| window_bias(f, noise, &ifg.modulated, &ifg.continuum, &setup.bins);
    let subtracted_bias = bias_of(formula);
    let true_bias = bias_of(Formula::Exact);
    let signal = raw_sums(&dft(&ifg.modulated), &setup.bins);
    let exact = if ifg.modulated.len() <= MAX_WINDOW_SAMPLES {
        Some(window_stats(
            &ifg.modulated,
            &ifg.mean_counts(),
            noise,
            &setup.bins,
        )?)
    } else {
        None
    };
    let mean = |s: f64, t: f64, b: f64, c: f64| (s + t - b) / c;
    Ok(CalibratedExpectation {
        calibration,
        signal,
        true_bias,
        subtracted_bias,
        mean_v1_sq: mean(
            signal.v1_sq,
            true_bias.v1_sq,
            subtracted_bias.v1_sq,
            calibration.v1_sq,
        ),
        mean_v2_sq: mean(
            signal.v2_sq,
            true_bias.v2_sq,
            subtracted_bias.v2_sq,
            calibration.v2_sq,
        ),
        var_v1_sq: exact
            .as_ref()
            .map(|w| w.var_v1_sq / (calibration.v1_sq * calibration.v1_sq)),
        var_v2_sq: exact
            .as_ref()
            .map(|w| w.var_v2_sq / (calibration.v2_sq * calibration.v2_sq)),
    })
}

/// The size of a Monte Carlo run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Trials {
    /// Number of noisy interferograms (≥ 2).
    pub trials: u64,
    /// Seed of the generators.
    pub seed: u64,
    /// Worker threads (0 = all cores); the answer does not depend on it.
    pub threads: usize,
}

/// A Monte Carlo of the calibrated estimators beside their expectations.
#[derive(Debug, Clone, PartialEq)]
pub struct CalibratedRun {
    /// Calibrated, bias-subtracted V1² over the trials.
    pub v1_sq: Summary,
    /// Same for V2².
    pub v2_sq: Summary,
    /// The closed forms.
    pub expected: CalibratedExpectation,
}

/// Runs `size.trials` noisy interferograms of `setup` under `noise`,
/// subtracts the `formula`'s bias and divides by the calibration;
/// `progress` is called with the number of trials done since its last call.
pub fn calibrated_run(
    setup: &CalibratedSetup,
    noise: &NoiseModel,
    formula: Formula,
    size: Trials,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<CalibratedRun> {
    let expected = expectation(setup, noise, formula)?;
    let spec = noisy_spec(setup, noise);
    let run = simulate_noisy(&spec, size.trials, size.seed, size.threads, progress)?;
    Ok(normalize(&run, expected))
}

/// The noisy interferograms [`calibrated_run`] simulates.
pub fn noisy_spec(setup: &CalibratedSetup, noise: &NoiseModel) -> NoisySpec {
    NoisySpec {
        modulated: setup.signal.modulated.clone(),
        continuum: setup.signal.continuum.clone(),
        noise: *noise,
        bins: setup.bins.clone(),
    }
}

/// The calibrated run of the raw statistics `run`: `(x − bias)/calibration`
/// of `expected`, exactly, on the accumulated moments.
pub fn normalize(run: &NoisyRun, expected: CalibratedExpectation) -> CalibratedRun {
    let normalized = |raw: &RunningStats, bias: f64, scale: f64| {
        raw.affine(1.0 / scale, -bias / scale).summary()
    };
    let (bias, calib) = (expected.subtracted_bias, expected.calibration);
    CalibratedRun {
        v1_sq: normalized(&run.v1_sq, bias.v1_sq, calib.v1_sq),
        v2_sq: normalized(&run.v2_sq, bias.v2_sq, calib.v2_sq),
        expected,
    }
}
