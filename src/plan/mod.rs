//! The planner: which estimator, fringe frequency and stroke reach a target
//! accuracy on V², and with how many scans — from the physics of the
//! trade-off, on the end-to-end simulator's model.
//!
//! For each estimator (V1², V2²), fringe frequency f and stroke Δx of a
//! grid, with samples of δx = λ0/(samples per fringe) and N = Δx/δx:
//!
//! - **photons per sample** `c = rate · t_s`, `t_s = 1/(samples per fringe ·
//!   f)`: a faster scan gets fewer photons per sample;
//! - **deterministic terms** (computable, hence correctable, and reported
//!   with their size): bandwidth and dispersion, `V²_spectral − V_mono²`;
//!   finite scan and detector, `V²_sampled − V²_spectral`, with
//!   `V²_sampled` the noise-free, piston-free normalized estimate of the
//!   configuration (positive bins);
//! - **random terms per scan**: the detector and photon noise, the exact
//!   variance of the normalized estimator ([`crate::noise::calibrated`]);
//!   the piston scatter, from a deterministic Monte Carlo of `scans`
//!   noiseless scans through one piston sequence ([`crate::simulator`]);
//! - **the piston bias** `⟨V²⟩_piston − V²_sampled`, from the same Monte
//!   Carlo (not correctable: it depends on the turbulence of the night);
//! - **scans and time**: with `σ²_scan = σ²_noise + σ²_piston`, reaching
//!   σ(V²) = target takes `n = σ²_scan/target²` scans of
//!   `N t_s + dead time` each; a target below |piston bias| is unreachable;
//!   with a time budget T instead, `n = T/(N t_s + dead)` and the σ reached
//!   is `sqrt(σ²_scan/n)`.
//!
//! Model choices, stated: scans are treated as independent (consecutive
//! piston scans are correlated at low fringe frequency, so the time is a
//! lower bound there); the bias is subtracted with the exact model
//! (`model` convention, positive bins); the piston packet is centred on the
//! scan-mean piston.

pub mod photometry;

use crate::conformance::estimate::BiasConvention;
use crate::error::{self, Error, Result};
use crate::formalism::estimator::{wide_band, BinWindow};
use crate::montecarlo::derive_seed;
use crate::noise::calibrated::{expectation, Trials};
use crate::noise::Formula;
use crate::piston::turbulence::PistonSpectrum;
use crate::simulator::{simulate, Inputs, Model, PistonInputs};
use rayon::prelude::*;
use serde::Serialize;

/// Fewest samples per scan a grid point may have (two fringes at four
/// samples per fringe: fewer leave the positive window nearly empty).
pub const MIN_SAMPLES: usize = 8;

/// The two estimators.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Estimator {
    /// V1² (sum of squared moduli).
    V1,
    /// V2² (squared modulus of the sum).
    V2,
}

/// What to reach.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Target {
    /// σ(V²) of the averaged measurement.
    SigmaV2(f64),
    /// A time budget, s.
    TimeBudgetS(f64),
}

/// Everything a plan needs.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlanInputs {
    /// The instrument, source and noise: spectrum, source, baseline,
    /// dispersion, detector, read noise, visibility (`samples`, `dx_um`,
    /// `photons` and `piston.fringe_hz` are set per grid point).
    pub instrument: Inputs,
    /// The atmosphere and telescopes (`fringe_hz` is set per grid point).
    pub atmosphere: PistonInputs,
    /// Samples per fringe at λ0 (δx = λ0/this).
    pub samples_per_fringe: f64,
    /// Continuum photons per second at the detector in the band.
    pub photon_rate_per_s: f64,
    /// Dead time between scans, s.
    pub dead_time_s: f64,
    /// Fringe frequencies of the grid, Hz.
    pub fringe_hz: Vec<f64>,
    /// Strokes of the grid, µm.
    pub stroke_um: Vec<f64>,
    /// The target.
    pub target: Target,
    /// Scans of each piston Monte Carlo.
    pub scans: u64,
    /// Seed of the piston Monte Carlo.
    pub seed: u64,
}

/// `count` frequencies from `lo` to `hi` Hz, evenly spaced in log.
pub fn log_grid(lo: f64, hi: f64, count: usize) -> Vec<f64> {
    let n = count.max(2);
    (0..n)
        .map(|i| lo * (hi / lo).powf(i as f64 / (n - 1) as f64))
        .collect()
}

/// The default grid: 20 fringe frequencies from 20 to 2000 Hz (log) and
/// strokes of 16, 32, 64 and 128 µm.
pub fn default_grid() -> (Vec<f64>, Vec<f64>) {
    (log_grid(20.0, 2000.0, 20), vec![16.0, 32.0, 64.0, 128.0])
}

/// One estimator at one grid point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PlanPoint {
    /// The estimator.
    pub estimator: Estimator,
    /// f, Hz.
    pub fringe_hz: f64,
    /// Δx, µm (N δx).
    pub stroke_um: f64,
    /// N.
    pub samples: usize,
    /// δx, µm.
    pub dx_um: f64,
    /// Continuum photons per sample.
    pub photons_per_sample: f64,
    /// One scan, s (N t_s).
    pub scan_time_s: f64,
    /// V_mono² at σ_eff.
    pub v_mono_sq: f64,
    /// Bandwidth and dispersion: V²_spectral − V_mono² (correctable).
    pub bias_bandwidth_dispersion: f64,
    /// Finite scan and detector: V²_sampled − V²_spectral (correctable).
    pub bias_scan_detector: f64,
    /// V²_sampled: the noise-free, piston-free estimate.
    pub v_sq_sampled: f64,
    /// σ of one scan from detector and photon noise.
    pub sigma_noise_per_scan: f64,
    /// σ of one scan from the piston.
    pub sigma_piston_per_scan: f64,
    /// Standard error of `sigma_piston_per_scan` (Monte Carlo).
    pub sigma_piston_stderr: f64,
    /// ⟨V²⟩ with piston − V²_sampled (not correctable).
    pub bias_piston: f64,
    /// Standard error of `bias_piston`.
    pub bias_piston_stderr: f64,
    /// sqrt(σ²_noise + σ²_piston).
    pub sigma_per_scan: f64,
    /// Scans needed for the target σ (None: unreachable, |bias| ≥ target).
    pub scans_needed: Option<f64>,
    /// Time for them, s.
    pub time_s: Option<f64>,
    /// σ(V²) reached in the time budget (budget mode).
    pub sigma_reached: Option<f64>,
}

/// The plan.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Plan {
    /// Every estimator × fringe frequency × stroke.
    pub points: Vec<PlanPoint>,
    /// The best point of each estimator (least time, or least σ with a budget).
    pub best_v1: Option<PlanPoint>,
    /// The best point of V2².
    pub best_v2: Option<PlanPoint>,
    /// The better of the two, if any reaches the target.
    pub recommended: Option<PlanPoint>,
}

impl PlanInputs {
    fn validate(&self) -> Result<()> {
        use crate::bounds::{positive_at_most, PLAN_SAMPLES_PER_FRINGE_MAX as SPF};
        use crate::bounds::{PHOTON_RATE_MAX_PER_S, PLAN_SIGMA_V2_MIN, PLAN_TIME_MAX_S};
        error::in_range("samples_per_fringe", self.samples_per_fringe, 2.0, SPF)?;
        positive_at_most(
            "photon_rate_per_s",
            self.photon_rate_per_s,
            PHOTON_RATE_MAX_PER_S,
        )?;
        error::in_range("dead_time_s", self.dead_time_s, 0.0, PLAN_TIME_MAX_S)?;
        match self.target {
            Target::SigmaV2(s) => error::in_range("target_sigma_v2", s, PLAN_SIGMA_V2_MIN, 1.0)?,
            Target::TimeBudgetS(t) => positive_at_most("time_budget_s", t, PLAN_TIME_MAX_S)?,
        };
        if self.fringe_hz.is_empty() || self.stroke_um.is_empty() {
            return Err(Error::Invalid {
                param: "fringe_hz",
                reason: "the grid needs at least one fringe frequency and one stroke".into(),
            });
        }
        if self.scans < 2 {
            return Err(Error::OutOfRange {
                param: "scans",
                value: self.scans as f64,
                accepted: ">= 2".into(),
            });
        }
        Ok(())
    }

    /// λ0 of the fringe frequency.
    fn wavelength_um(&self) -> f64 {
        self.atmosphere.wavelength_um
    }

    /// The simulator's inputs at one grid point, with or without noise and
    /// piston.
    pub fn point_inputs(
        &self,
        fringe_hz: f64,
        stroke_um: f64,
        noise: bool,
        piston: bool,
    ) -> Result<Inputs> {
        error::in_range("fringe_hz", fringe_hz, 1e-3, 1e7)?;
        error::positive("stroke_um", stroke_um)?;
        let dx_um = self.wavelength_um() / self.samples_per_fringe;
        let samples = (stroke_um / dx_um).round();
        if samples < MIN_SAMPLES as f64 {
            return Err(Error::OutOfRange {
                param: "stroke_um",
                value: stroke_um,
                accepted: format!(
                    ">= {} um ({MIN_SAMPLES} samples of {dx_um} um: a scan must hold a fringe)",
                    MIN_SAMPLES as f64 * dx_um
                ),
            });
        }
        let samples = samples as usize;
        let sample_time_s = 1.0 / (self.samples_per_fringe * fringe_hz);
        let i = &self.instrument;
        Ok(Inputs {
            samples,
            dx_um,
            photons: self.photon_rate_per_s * sample_time_s,
            read_noise: if noise { i.read_noise } else { 0.0 },
            photon_noise: noise && i.photon_noise,
            piston: piston.then_some(PistonInputs {
                fringe_hz,
                ..self.atmosphere
            }),
            ..i.clone()
        })
    }
}

/// The two estimators' points at one grid point.
fn grid_point(
    inputs: &PlanInputs,
    sky: &PistonSpectrum,
    fringe_hz: f64,
    stroke_um: f64,
) -> Result<[PlanPoint; 2]> {
    let noisy = Model::new(&inputs.point_inputs(fringe_hz, stroke_um, true, false)?)?;
    let window = BinWindow::Positive;
    let closed = expectation(
        &noisy.calibrated_setup(window),
        &noisy.noise,
        Formula::Exact,
    )?;
    let wb = wide_band(&noisy.observation);
    let vis2 = noisy.inputs.visibility * noisy.inputs.visibility;
    let piston_model = Model::with_piston_spectrum(
        &inputs.point_inputs(fringe_hz, stroke_um, false, true)?,
        sky.clone(),
    )?;
    let size = Trials {
        trials: inputs.scans,
        seed: derive_seed(inputs.seed, "plan", &[fringe_hz, stroke_um]),
        threads: 1,
    };
    let mc = simulate(
        &piston_model,
        window,
        BiasConvention::Model,
        Formula::Exact,
        size,
        &|_| {},
    )?;
    let t_s = 1.0 / (inputs.samples_per_fringe * fringe_hz);
    let point = |estimator: Estimator| {
        let (spectral, sampled, var_noise, piston) = match estimator {
            Estimator::V1 => (wb.v1_sq, closed.mean_v1_sq, closed.var_v1_sq, &mc.v1_sq),
            Estimator::V2 => (wb.v2_sq, closed.mean_v2_sq, closed.var_v2_sq, &mc.v2_sq),
        };
        let var_noise = var_noise.unwrap_or(f64::NAN);
        let sigma = (var_noise + piston.var).sqrt();
        let mut p = PlanPoint {
            estimator,
            fringe_hz,
            stroke_um: noisy.sampling.stroke_um(),
            samples: noisy.samples(),
            dx_um: noisy.sampling.dx_um(),
            photons_per_sample: noisy.inputs.photons,
            scan_time_s: noisy.samples() as f64 * t_s,
            v_mono_sq: vis2 * wb.v_mono * wb.v_mono,
            bias_bandwidth_dispersion: vis2 * (spectral - wb.v_mono * wb.v_mono),
            bias_scan_detector: sampled - vis2 * spectral,
            v_sq_sampled: sampled,
            sigma_noise_per_scan: var_noise.sqrt(),
            sigma_piston_per_scan: piston.std,
            sigma_piston_stderr: piston.stderr_std,
            bias_piston: piston.mean - sampled,
            bias_piston_stderr: piston.stderr_mean,
            sigma_per_scan: sigma,
            scans_needed: None,
            time_s: None,
            sigma_reached: None,
        };
        reach(&mut p, inputs);
        p
    };
    Ok([point(Estimator::V1), point(Estimator::V2)])
}

/// Fills the scans and time (or the σ reached) of `p`.
fn reach(p: &mut PlanPoint, inputs: &PlanInputs) {
    let per_scan_s = p.scan_time_s + inputs.dead_time_s;
    match inputs.target {
        Target::SigmaV2(target) => {
            if p.bias_piston.abs() < target && p.sigma_per_scan.is_finite() {
                // σ² of the mean plus the bias² within the target.
                let room = target * target - p.bias_piston * p.bias_piston;
                let n = (p.sigma_per_scan * p.sigma_per_scan / room).ceil().max(1.0);
                p.scans_needed = Some(n);
                p.time_s = Some(n * per_scan_s);
            }
        }
        Target::TimeBudgetS(budget) => {
            let n = (budget / per_scan_s).floor();
            if n >= 1.0 {
                let s2 = p.sigma_per_scan * p.sigma_per_scan / n;
                p.sigma_reached = Some((s2 + p.bias_piston * p.bias_piston).sqrt());
                p.scans_needed = Some(n);
                p.time_s = Some(n * per_scan_s);
            }
        }
    }
}

/// The figure of merit of a point: the time for the target, or the σ
/// reached in the budget (lower is better).
fn merit(p: &PlanPoint) -> Option<f64> {
    p.sigma_reached.or(p.time_s).filter(|v| v.is_finite())
}

fn best(points: &[PlanPoint], e: Estimator) -> Option<PlanPoint> {
    points
        .iter()
        .filter(|p| p.estimator == e)
        .filter_map(|p| merit(p).map(|m| (m, *p)))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, p)| p)
}

/// Plans over the grid of `inputs`, on `threads` threads (0: all); the
/// answer does not depend on the thread count. `progress` is called once
/// per grid point done.
pub fn plan(inputs: &PlanInputs, threads: usize, progress: &(dyn Fn(u64) + Sync)) -> Result<Plan> {
    inputs.validate()?;
    let sky = inputs.atmosphere.spectrum(inputs.instrument.baseline_m)?;
    let grid: Vec<(f64, f64)> = inputs
        .fringe_hz
        .iter()
        .flat_map(|&f| inputs.stroke_um.iter().map(move |&s| (f, s)))
        .collect();
    let points = crate::montecarlo::in_pool(threads, || {
        grid.par_iter()
            .map(|&(f, s)| {
                let r = grid_point(inputs, &sky, f, s);
                progress(1);
                r
            })
            .collect::<Result<Vec<_>>>()
    })?;
    let points: Vec<PlanPoint> = points.into_iter().flatten().collect();
    let (best_v1, best_v2) = (best(&points, Estimator::V1), best(&points, Estimator::V2));
    let recommended = [best_v1, best_v2]
        .into_iter()
        .flatten()
        .filter_map(|p| merit(&p).map(|m| (m, p)))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, p)| p);
    Ok(Plan {
        points,
        best_v1,
        best_v2,
        recommended,
    })
}
