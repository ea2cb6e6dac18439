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
//!   is `sqrt(σ²_scan/n)`;
//! - **the observation**: consecutive scans share the atmosphere, so in
//!   target mode the fastest [`CANDIDATES`] settings of each
//!   estimator are solved again with σ of the mean of n consecutive scans
//!   from the autocovariance of the per-scan errors on contiguous piston
//!   sequences spanning a few correlation times (`correlation`: the cost
//!   is the atmosphere's, not n's; n on both sides), with the bias
//!   convention's offset ([`PlanInputs::bias`]); a setting whose noise
//!   alone needs longer than the best solved one is not simulated, and the
//!   plan recommends among the solved; [`verify`] simulates the
//!   recommended observation;
//! - **the detector**: with [`PlanInputs::frame_rate_hz`] no fringe is
//!   faster than frame rate / samples per fringe ([`detector_grid`]), and
//!   a recommendation there is the detector's edge
//!   ([`Plan::at_detector_edge`]).
//!
//! - **honest piston terms**: the piston Monte Carlo cuts its scans from up
//!   to 16 independent sequences, each spanning two piston correlation
//!   times B/v ([`crate::piston::sequences::sequence_split`]); its
//!   standard errors come from the spread between sequences, and a point
//!   reaches the target only with the piston scatter and bias at the upper
//!   ends of their [`CONFIDENCE`] intervals;
//! - **a seed-stable choice**: points whose optimistic time is within the
//!   best's stated time are equally good to the Monte Carlo's precision
//!   (16 000 scans by default, at most [`POINT_SAMPLES`] samples per
//!   point); among them the plan takes the highest fringe frequency,
//!   whose piston terms are known best, so the recommendation does not
//!   flip with the seed (`tests/plan_cases.rs`).
//!
//! Model choices, stated: the per-scan noise is that of the exact model
//! bias (`model` convention, positive bins; the observation's uses the
//! convention asked for); the piston packet is centred on the scan-mean
//! piston (a perfect group-delay tracker); no dead time unless given.

pub(crate) mod answer;
mod candidates;
mod correlation;
pub mod figure;
pub mod instrument;
pub(crate) mod observation;
pub mod photometry;
mod point;
mod reach;
mod scans;
pub mod verify;

pub use answer::{human_duration, inflation_words, no_recommendation_reason, SeeingGiven};
pub use candidates::CANDIDATES;
pub use observation::{
    observation_piston, ObservationError, ObservationPiston, BLOCKS_PER_SEQUENCE,
};
use point::grid_point;
pub use point::{point_scans, POINT_SAMPLES};
pub use reach::sigma_reached_in;
use reach::{best, choose, reach, Bounds};
pub use scans::{MAX_OBSERVATION_SAMPLES, SEQUENCES};

use crate::conformance::estimate::BiasConvention;
use crate::error::{self, Error, Result};
use crate::formalism::estimator::{wide_band, BinWindow};
use crate::montecarlo::{derive_seed, replicated_t_quantile};
use crate::noise::calibrated::{expectation, Trials};
use crate::noise::Formula;
use crate::piston::spectrum::PistonSpectrum;
use crate::piston::{FringeTables, SharedSequences};
use crate::simulator::{simulate, Inputs, Model, PistonInputs};
use rayon::prelude::*;
use serde::Serialize;

/// The confidence level of the piston terms' intervals: a point reaches
/// the target only when it does with the piston scatter and bias at the
/// upper ends of their two-sided 90% intervals (one-sided 95%), with the
/// Student-t factor of the Monte Carlo's independent sequences.
pub const CONFIDENCE: f64 = 0.90;

/// One night, s (10 h): a plan longer than this is flagged.
pub const ONE_NIGHT_S: f64 = 36_000.0;

/// Fewest samples per scan a grid point may have (two fringes at four
/// samples per fringe: fewer leave the positive window nearly empty).
pub const MIN_SAMPLES: usize = 8;

/// The two estimators.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
pub enum Estimator {
    /// V1² (sum of squared moduli).
    V1,
    /// V2² (squared modulus of the sum).
    V2,
}

impl From<Estimator> for crate::conformance::score::Estimator {
    fn from(e: Estimator) -> Self {
        match e {
            Estimator::V1 => crate::conformance::score::Estimator::V1Sq,
            Estimator::V2 => crate::conformance::score::Estimator::V2Sq,
        }
    }
}

/// What to reach.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum Target {
    /// σ(V²) of the averaged measurement.
    SigmaV2(f64),
    /// A time budget, s.
    TimeBudgetS(f64),
}

impl Target {
    /// The σ(V²) to reach, when that is the target (not a time budget).
    pub fn sigma_v2(self) -> Option<f64> {
        match self {
            Target::SigmaV2(s) => Some(s),
            Target::TimeBudgetS(_) => None,
        }
    }
}

/// Everything a plan needs.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlanInputs {
    /// The instrument, source and noise: spectrum, source, baseline,
    /// dispersion, detector, read noise, visibility (`samples`, `dx_um`,
    /// `photons` and `piston.fringe_hz` are set per grid point, and the
    /// answer's echo leaves them out).
    #[serde(serialize_with = "answer::echo_instrument")]
    pub instrument: Inputs,
    /// The atmosphere and telescopes (`fringe_hz` is set per grid point:
    /// left out of the echo; the seeing is at the observing wavelength).
    #[serde(serialize_with = "answer::echo_atmosphere")]
    pub atmosphere: PistonInputs,
    /// Samples per fringe at λ0 (δx = λ0/this).
    pub samples_per_fringe: f64,
    /// Continuum photons per second at the detector in the band.
    pub photon_rate_per_s: f64,
    /// Dead time between scans, s.
    pub dead_time_s: f64,
    /// The detector's maximum sample (frame) rate, Hz: the fringe
    /// frequencies of the grid are at most this over `samples_per_fringe`
    /// (None: no detector limit).
    pub frame_rate_hz: Option<f64>,
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
    /// The 1σ uncertainty of the source's angular diameter, mas (0: known
    /// exactly): its effect on V² is reported beside each correction.
    pub diameter_err_mas: f64,
    /// Where the user's pipeline takes the photon-noise bias's counts from
    /// (the predicted mean and the noise σ of the observation follow it).
    pub bias: BiasConvention,
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

/// The fringe frequencies of a grid bounded by a detector whose fastest
/// fringe is `most` Hz (frame rate / samples per fringe): the default grid
/// (`given` empty) runs from 20 Hz (or `most`/100 when that is lower) up to
/// `most`, 20 frequencies in log, beyond 2000 Hz when the detector allows;
/// a given grid loses its frequencies above `most` and gains `most` when
/// it lost any, so its top is the detector's edge.
pub fn detector_grid(given: &[f64], most: f64) -> Vec<f64> {
    if given.is_empty() {
        return log_grid(20.0_f64.min(most / 100.0), most, 20);
    }
    let mut kept: Vec<f64> = given.iter().copied().filter(|&f| f <= most).collect();
    if kept.len() < given.len() && !kept.contains(&most) {
        kept.push(most);
    }
    kept
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
    /// Independent piston sequences of the Monte Carlo (its errors have
    /// one degree of freedom fewer).
    pub piston_sequences: usize,
    /// The upper end of the piston scatter's confidence interval
    /// ([`CONFIDENCE`]): σ_piston + t·se.
    pub sigma_piston_upper: f64,
    /// The upper end of |piston bias|'s confidence interval.
    pub bias_piston_upper: f64,
    /// Scans needed for the target σ, with the piston terms at the upper
    /// ends of their confidence intervals (None: unreachable, the bias's
    /// upper end ≥ target): consecutive scans through one atmosphere when
    /// `observation` is present (the observation's own σ, n on both
    /// sides), else σ²_scan/(target² − bias²), which assumes independent
    /// scans (the points not among the fastest [`CANDIDATES`]
    /// of their estimator).
    pub scans_needed: Option<f64>,
    /// Time for them, s.
    pub time_s: Option<f64>,
    /// The time with the piston terms at the lower ends of their intervals,
    /// s: the point is indistinguishable from another whose `time_s` is
    /// above this.
    pub time_lower_s: Option<f64>,
    /// The time with the detector and photon noise alone, s (deterministic:
    /// the tie-breaker between indistinguishable points).
    pub time_noise_only_s: Option<f64>,
    /// Whether `time_s` exceeds one night ([`ONE_NIGHT_S`]).
    pub exceeds_one_night: bool,
    /// |bandwidth and dispersion bias| / target σ: above 1, the user must
    /// correct it (it is deterministic) to reach the target.
    pub bandwidth_bias_over_target: f64,
    /// |finite scan and detector bias| / target σ (in budget mode both
    /// ratios are to the σ reached).
    pub scan_bias_over_target: f64,
    /// The V² error from the uncertainty of the source diameter
    /// (`diameter_err_mas`), |dV²/dθ|·δθ at the monochromatic visibility.
    pub v_sq_error_from_diameter: f64,
    /// σ(V²) reached in the time budget (budget mode).
    pub sigma_reached: Option<f64>,
    /// Why this point's null fields are null, in words (None: none is).
    pub why_null: Option<&'static str>,
    /// The observation of `scans_needed` consecutive scans, measured on
    /// contiguous piston sequences (target mode, the fastest
    /// [`CANDIDATES`] points of each estimator; None elsewhere).
    pub observation: Option<ObservationError>,
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
    /// Why V1² has no best point (None when it has one).
    pub no_v1_reason: Option<String>,
    /// Why V2² has no best point.
    pub no_v2_reason: Option<String>,
    /// The confidence level of the piston terms' intervals ([`CONFIDENCE`]).
    pub confidence: f64,
    /// When the recommendation sits on an edge of the grid: which, and
    /// what to do (`answer::grid_edge_note`).
    pub grid_edge: Option<String>,
    /// Whether the recommended fringe frequency is the detector's fastest
    /// (`frame_rate_hz` / samples per fringe): the edge is the detector's,
    /// not the grid's.
    pub at_detector_edge: bool,
}

impl PlanInputs {
    /// Checks every input against its accepted range before any
    /// computation (also before a cost is predicted from them).
    pub fn validate(&self) -> Result<()> {
        use crate::bounds::{positive_at_most, PLAN_SAMPLES_PER_FRINGE_MAX as SPF};
        use crate::bounds::{PHOTON_RATE_MAX_PER_S, PLAN_SIGMA_V2_MIN, PLAN_TIME_MAX_S};
        error::in_range("samples_per_fringe", self.samples_per_fringe, 2.0, SPF)?;
        positive_at_most(
            "photon_rate_per_s",
            self.photon_rate_per_s,
            PHOTON_RATE_MAX_PER_S,
        )?;
        error::in_range("dead_time_s", self.dead_time_s, 0.0, PLAN_TIME_MAX_S)?;
        self.validate_frame_rate()?;
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
        self.validate_scans()?;
        error::non_negative("diameter_err_mas", self.diameter_err_mas)?;
        Ok(())
    }

    /// The frame rate in its range, and no fringe frequency of the grid
    /// faster than the detector samples it.
    fn validate_frame_rate(&self) -> Result<()> {
        let Some(rate) = self.frame_rate_hz else {
            return Ok(());
        };
        error::in_range("frame_rate_hz", rate, 1e-3, 1e9)?;
        let most = self.fringe_hz_max().unwrap_or(f64::INFINITY);
        if let Some(&f) = self.fringe_hz.iter().find(|&&f| f > most * (1.0 + 1e-12)) {
            return Err(Error::OutOfRange {
                param: "fringe_hz",
                value: f,
                accepted: format!(
                    "at most {most} Hz: frame_rate_hz {rate} / samples_per_fringe {}",
                    self.samples_per_fringe
                ),
            });
        }
        Ok(())
    }

    /// The fastest fringe the detector samples at `samples_per_fringe`:
    /// frame rate / samples per fringe, Hz (None: no detector limit).
    pub fn fringe_hz_max(&self) -> Option<f64> {
        self.frame_rate_hz.map(|r| r / self.samples_per_fringe)
    }

    /// `scans` from 32 (two independent piston sequences: the fewest that
    /// give the piston terms an error) to what the memory limit allows at
    /// the grid's longest stroke; checked before any computation, and the
    /// same whatever the thread count.
    fn validate_scans(&self) -> Result<()> {
        let dx_um = self.wavelength_um() / self.samples_per_fringe;
        let longest = self.stroke_um.iter().fold(0.0_f64, |a, &b| a.max(b));
        let samples = ((longest / dx_um).round() as usize).max(MIN_SAMPLES);
        let most = crate::piston::sequences::max_scans(samples) as u64;
        let least = 2 * crate::piston::sequences::MIN_SCANS_PER_SEQUENCE as u64;
        if !(least..=most).contains(&self.scans) {
            return Err(Error::OutOfRange {
                param: "scans",
                value: self.scans as f64,
                accepted: format!(
                    "{least} to {most} (at the grid's longest stroke, {samples} samples per scan)"
                ),
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

/// Plans over the grid of `inputs`, on `threads` threads (0: all); the
/// answer does not depend on the thread count. `progress` is called once
/// per grid point done.
pub fn plan(inputs: &PlanInputs, threads: usize, progress: &(dyn Fn(u64) + Sync)) -> Result<Plan> {
    inputs.validate()?;
    let sky = inputs.atmosphere.spectrum(inputs.instrument.baseline_m)?;
    // The spectrum's tables on the whole pool first: built on first use
    // inside the grid, by one point while the others wait (5.8e9 of the
    // 11.4e9 instructions of a one-frequency plan).
    crate::montecarlo::in_pool(threads, || {
        sky.tabulate();
        Ok(())
    })?;
    // One fringe table per rung of range for the whole grid, not one per
    // setting (their building was 59 % of a visible plan's time).
    let tables = FringeTables::new();
    // The strokes of one fringe frequency read the same piston sequences
    // (grid_point), drawn once: one frequency's at a time in memory.
    let frequency = |f: f64| -> Result<Vec<[PlanPoint; 2]>> {
        let shared = SharedSequences::new();
        let point = |s: f64| {
            let r = grid_point(inputs, (&sky, &tables, &shared), f, s);
            progress(1);
            crate::montecarlo::cancel::check()?;
            r
        };
        // The first stroke alone draws the sequences (on the threads the
        // other frequencies leave free); the others then read them side by
        // side.
        let mut group = Vec::with_capacity(inputs.stroke_um.len());
        if let Some((first, rest)) = inputs.stroke_um.split_first() {
            group.push(point(*first)?);
            group.extend(
                rest.par_iter()
                    .map(|&s| point(s))
                    .collect::<Result<Vec<_>>>()?,
            );
        }
        Ok(group)
    };
    let groups = crate::montecarlo::in_pool(threads, || {
        inputs
            .fringe_hz
            .par_iter()
            .map(|&f| frequency(f))
            .collect::<Result<Vec<_>>>()
    })?;
    let mut points: Vec<PlanPoint> = groups.into_iter().flatten().flatten().collect();
    if let Target::SigmaV2(target) = inputs.target {
        crate::montecarlo::in_pool(threads, || {
            candidates::resolve_candidates(inputs, (&sky, &tables), &mut points, target)
        })?;
    }
    let (best_v1, best_v2) = (best(&points, Estimator::V1), best(&points, Estimator::V2));
    let bests: Vec<PlanPoint> = [best_v1, best_v2].into_iter().flatten().collect();
    let recommended = choose(bests.iter());
    let mut plan = Plan {
        points,
        best_v1,
        best_v2,
        recommended,
        no_v1_reason: None,
        no_v2_reason: None,
        confidence: CONFIDENCE,
        grid_edge: None,
        at_detector_edge: false,
    };
    plan.at_detector_edge = match (plan.recommended, inputs.fringe_hz_max()) {
        (Some(p), Some(most)) => p.fringe_hz >= most * (1.0 - 1e-12),
        _ => false,
    };
    plan.grid_edge = answer::grid_edge_note(&plan, inputs);
    plan.no_v1_reason = no_recommendation_reason(&plan, Estimator::V1);
    plan.no_v2_reason = no_recommendation_reason(&plan, Estimator::V2);
    Ok(plan)
}
