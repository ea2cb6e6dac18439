//! The promise checked: simulated observations at the recommended setting,
//! each n consecutive scans through one atmosphere with photon and
//! detector noise, estimated with the plan's bias convention; their spread
//! and mean beside what the plan promised.
//!
//! The observations are consecutive blocks of n scans cut from
//! [`SEQUENCES`] independent piston sequences, each scanned at the scan
//! period (as many blocks per sequence as the requested number of
//! observations needs, and a sequence spans at least two piston
//! correlation times); the confidence intervals come from the spread
//! between the sequences (batch means, valid however correlated
//! neighbouring blocks are), with `SEQUENCES − 1` degrees of freedom.

use super::observation::{scans_per_sequence, stride_samples, ContiguousScans};
pub(crate) use super::scans::SEQUENCES;
use super::{Estimator, PlanInputs, PlanPoint, CONFIDENCE};
use crate::conformance::estimate::BiasConvention;
use crate::error::{Error, Result};
use crate::montecarlo::{derive_seed, replicated_t_quantile, Summary};
use crate::piston::series::MAX_SERIES;
use crate::piston::spectrum::PistonSpectrum;
use crate::simulator::Model;
use serde::Serialize;

/// Fewest observations a verification simulates (its intervals need
/// some blocks per sequence).
pub const MIN_OBSERVATIONS: u64 = 32;

/// Most observations a verification simulates.
pub const MAX_OBSERVATIONS: u64 = 1_000_000;

/// Observations simulated by default: the achieved σ to about ±5 % (one
/// standard error) when the blocks of a sequence are nearly independent.
pub const DEFAULT_OBSERVATIONS: u64 = 256;

/// The shape of a verification's simulation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VerificationSize {
    /// Samples per scan, N.
    pub samples: usize,
    /// Scans of each of the [`SEQUENCES`] sequences.
    pub scans_per_sequence: usize,
    /// Samples from one scan's start to the next.
    pub stride: usize,
    /// Sample interval, s.
    pub sample_time_s: f64,
    /// n, scans per observation.
    pub scans_per_observation: u64,
    /// The observations asked for (`observations` of [`size_at`]).
    pub observations_requested: u64,
}

impl VerificationSize {
    /// Scans simulated in all.
    pub fn scans(&self) -> u64 {
        (SEQUENCES * self.scans_per_sequence) as u64
    }

    /// The observations the simulation delivers: [`SEQUENCES`] × the
    /// blocks of n consecutive scans one sequence holds. More than asked
    /// when the asked number is not a multiple of [`SEQUENCES`] or a
    /// sequence spans its correlation times; fewer when one sequence
    /// cannot hold the blocks asked ([`VerificationSize::fewer_why`]).
    pub fn observations(&self) -> u64 {
        let n = self.scans_per_observation.max(1);
        SEQUENCES as u64 * (self.scans_per_sequence as u64 / n)
    }

    /// Why the simulation delivers fewer observations than asked, in one
    /// line (None when it delivers at least as many): one simulated piston
    /// sequence holds at most [`MAX_SERIES`] samples (the piston's memory
    /// bound), so at most that many scans, hence blocks of n, per sequence.
    pub fn fewer_why(&self) -> Option<String> {
        let delivered = self.observations();
        (delivered < self.observations_requested).then(|| {
            format!(
                "{delivered} of the {} observations asked: one simulated piston sequence holds at most {MAX_SERIES} samples (the piston's memory bound), here {} scans of {} samples ({} with the dead time), so {} observations of {} scans per sequence x {SEQUENCES} sequences; more observations need fewer scans per observation (a larger target sigma(V^2)) or shorter scans",
                self.observations_requested,
                self.scans_per_sequence,
                self.samples,
                self.stride,
                delivered / SEQUENCES as u64,
                self.scans_per_observation,
            )
        })
    }
}

/// The size of the verification of `p` with `observations` observations;
/// refuses a point without scans and observations longer than one
/// simulated sequence can hold.
pub fn verification_size(
    inputs: &PlanInputs,
    sky: &PistonSpectrum,
    p: &PlanPoint,
    observations: u64,
) -> Result<VerificationSize> {
    let n = p.scans_needed.ok_or_else(|| Error::Invalid {
        param: "verify",
        reason: "the plan has no recommended number of scans to verify".into(),
    })? as u64;
    size_at(inputs, sky, (p.fringe_hz, p.stroke_um, n), observations)
}

/// [`verification_size`] at fringe frequency f (Hz) and stroke Δx (µm)
/// with n scans per observation, `(f, Δx, n)`.
pub fn size_at(
    inputs: &PlanInputs,
    sky: &PistonSpectrum,
    (fringe_hz, stroke_um, n): (f64, f64, u64),
    observations: u64,
) -> Result<VerificationSize> {
    crate::error::in_range(
        "verify_observations",
        observations as f64,
        MIN_OBSERVATIONS as f64,
        MAX_OBSERVATIONS as f64,
    )?;
    let model = Model::new(&inputs.point_inputs(fringe_hz, stroke_um, false, false)?)?;
    let t_s = 1.0 / (inputs.samples_per_fringe * fringe_hz);
    let stride = stride_samples(inputs, &model, fringe_hz);
    let blocks = observations.div_ceil(SEQUENCES as u64);
    let shape = (model.samples(), stride, t_s);
    let per_sequence =
        scans_per_sequence(sky, shape, (n.saturating_mul(blocks), n), (0, false)).unwrap_or(0);
    if (per_sequence as u64) < n {
        return Err(Error::Invalid {
            param: "verify",
            reason: format!(
                "an observation of {n} scans of {} samples does not fit in one simulated piston sequence (at most {per_sequence} scans)",
                model.samples()
            ),
        });
    }
    Ok(VerificationSize {
        samples: model.samples(),
        scans_per_sequence: per_sequence,
        stride,
        sample_time_s: t_s,
        scans_per_observation: n,
        observations_requested: observations,
    })
}

/// What the simulated observations achieved beside the promise.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Verification {
    /// The estimator verified.
    pub estimator: Estimator,
    /// f, Hz.
    pub fringe_hz: f64,
    /// Δx, µm.
    pub stroke_um: f64,
    /// The bias convention the observations were estimated with.
    pub bias: BiasConvention,
    /// n, consecutive scans per observation.
    pub scans_per_observation: u64,
    /// Observations simulated (delivered).
    pub observations: u64,
    /// Observations asked for.
    pub observations_requested: u64,
    /// Why fewer were delivered than asked (None: at least as many):
    /// [`VerificationSize::fewer_why`].
    pub fewer_observations_why: Option<String>,
    /// Independent piston sequences they were cut from.
    pub sequences: usize,
    /// Seed of the simulation.
    pub seed: u64,
    /// The level of the intervals below.
    pub confidence: f64,
    /// The plan's promise: σ(V²) of the observation's mean.
    pub promised_sigma: f64,
    /// What the independent-scan formula σ_scan/√n would promise.
    pub sigma_if_independent: f64,
    /// σ(V²) over the simulated observations.
    pub achieved_sigma: f64,
    /// Its standard error (spread between the sequences).
    pub achieved_sigma_stderr: f64,
    /// Its interval.
    pub achieved_sigma_interval: [f64; 2],
    /// The mean the plan predicts (V²_sampled + piston bias + the
    /// convention's offset).
    pub predicted_mean: f64,
    /// The mean over the simulated observations.
    pub achieved_mean: f64,
    /// Its standard error.
    pub achieved_mean_stderr: f64,
    /// Its interval.
    pub achieved_mean_interval: [f64; 2],
    /// The standard error of the prediction (the Monte Carlo's).
    pub predicted_mean_stderr: f64,
    /// The predicted bias: predicted_mean − V²_sampled.
    pub predicted_bias: f64,
    /// The achieved bias: achieved_mean − V²_sampled.
    pub achieved_bias: f64,
    /// Achieved σ / promised σ: 1 when the promise is exact, below 1 when
    /// it is pessimistic.
    pub sigma_ratio: f64,
    /// Its [`CONFIDENCE`] interval (the achieved σ's over the promise, the
    /// promise being a fixed number once planned): a promise is
    /// optimistic by the amount the lower end exceeds 1.
    pub sigma_ratio_interval: [f64; 2],
    /// Whether the achieved σ's interval reaches down to the promise
    /// (`sigma_ratio_interval[0] <= 1`): not a proof that the promise
    /// holds, only that the simulation does not contradict it; read the
    /// ratio and its interval.
    pub sigma_kept: bool,
    /// Whether the achieved and predicted means agree within the interval
    /// of their difference (both standard errors).
    pub mean_kept: bool,
}

/// The seed of the verification at fringe frequency f (Hz) and stroke Δx (µm).
pub fn verify_seed(inputs: &PlanInputs, fringe_hz: f64, stroke_um: f64) -> u64 {
    derive_seed(inputs.seed, "plan-verify", &[fringe_hz, stroke_um])
}

/// The noisy model with piston that a verification at f (Hz), Δx (µm) scans.
pub fn verify_model(
    inputs: &PlanInputs,
    sky: &PistonSpectrum,
    fringe_hz: f64,
    stroke_um: f64,
) -> Result<Model> {
    Model::with_piston_spectrum(
        &inputs.point_inputs(fringe_hz, stroke_um, true, true)?,
        sky.clone(),
    )
}

/// Simulates the observations of `size` at point `p` (with its
/// observation-level promise) from `seed`; `progress` counts scans.
pub fn verify(
    inputs: &PlanInputs,
    sky: &PistonSpectrum,
    p: &PlanPoint,
    size: &VerificationSize,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Verification> {
    promise(p)?;
    let model = verify_model(inputs, sky, p.fringe_hz, p.stroke_um)?;
    let seed = verify_seed(inputs, p.fringe_hz, p.stroke_um);
    let layout = (size.scans_per_sequence, size.stride, size.sample_time_s);
    let scans = ContiguousScans::simulate(&model, None, inputs.bias, layout, seed, progress)?;
    let n = size.scans_per_observation as usize;
    verification_of(inputs, p, size, scans.block_means(n, false))
}

/// The observation-level promise of `p`, or why it has none.
fn promise(p: &PlanPoint) -> Result<super::observation::ObservationError> {
    p.observation.ok_or_else(|| Error::Invalid {
        param: "verify",
        reason: "the point has no observation-level promise (a time budget plan?)".into(),
    })
}

/// The verification of `p` from the means of the simulated observations
/// of V1² and V2² (`block_means`: each observation's mean, errors from the
/// spread between the sequences), computed here or reduced from the units
/// of [`crate::units::verify::VerifyJob`].
pub fn verification_of(
    inputs: &PlanInputs,
    p: &PlanPoint,
    size: &VerificationSize,
    block_means: [Summary; 2],
) -> Result<Verification> {
    let o = promise(p)?;
    let n = size.scans_per_observation as usize;
    let e = match p.estimator {
        Estimator::V1 => 0,
        Estimator::V2 => 1,
    };
    let s = block_means[e];
    let t = replicated_t_quantile(CONFIDENCE, SEQUENCES);
    let sigma_interval = [s.std - t * s.stderr_std, s.std + t * s.stderr_std];
    let mean_interval = [s.mean - t * s.stderr_mean, s.mean + t * s.stderr_mean];
    Ok(Verification {
        estimator: p.estimator,
        fringe_hz: p.fringe_hz,
        stroke_um: p.stroke_um,
        bias: inputs.bias,
        scans_per_observation: size.scans_per_observation,
        observations: s.count,
        observations_requested: size.observations_requested,
        fewer_observations_why: size.fewer_why(),
        sequences: SEQUENCES,
        seed: verify_seed(inputs, p.fringe_hz, p.stroke_um),
        confidence: CONFIDENCE,
        promised_sigma: o.sigma,
        sigma_if_independent: p.sigma_per_scan / (n as f64).sqrt(),
        achieved_sigma: s.std,
        achieved_sigma_stderr: s.stderr_std,
        achieved_sigma_interval: sigma_interval,
        predicted_mean: o.predicted_mean,
        achieved_mean: s.mean,
        achieved_mean_stderr: s.stderr_mean,
        achieved_mean_interval: mean_interval,
        predicted_mean_stderr: o.bias_stderr,
        predicted_bias: o.bias,
        achieved_bias: s.mean - p.v_sq_sampled,
        sigma_ratio: s.std / o.sigma,
        sigma_ratio_interval: sigma_interval.map(|v| v / o.sigma),
        sigma_kept: sigma_interval[0] <= o.sigma,
        mean_kept: (s.mean - o.predicted_mean).abs() <= t * s.stderr_mean.hypot(o.bias_stderr),
    })
}
