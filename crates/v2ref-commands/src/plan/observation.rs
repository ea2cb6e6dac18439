//! The error of an observation: the mean of n consecutive scans through
//! one atmosphere, from contiguous simulated piston sequences.
//!
//! Consecutive scans share the piston's slow wander, so their piston
//! errors are correlated and σ of their mean is not σ_scan/√n: it can be
//! larger (errors that persist over many scans) or smaller (errors that
//! alternate in sign). The planner therefore measures it directly. K
//! independent piston sequences ([`SEQUENCES`]) are each scanned by L
//! consecutive scans one scan period apart (the scan and its dead time:
//! an observation's own cadence), L ≥ [`BLOCKS_PER_SEQUENCE`] n where the
//! cost allows, and spanning at least
//! [`crate::piston::sequences::SPAN_CORRELATION_TIMES`] correlation times
//! B/v. Each sequence is cut into ⌊L/n⌋ blocks of n consecutive scans; the
//! block means of the per-scan V² are the means of simulated observations,
//! and
//!
//! `σ²_obs(n) = σ²_noise/n + Var(block means of the noise-free V²)`
//!
//! (the detector and photon noise is independent from scan to scan; the
//! piston part is measured). Its standard error is the spread between the
//! K sequences ([`crate::montecarlo::replicated_summary`]: batch means,
//! valid however correlated the blocks of one sequence are), with K − 1
//! degrees of freedom. When n consecutive scans do not fit in one
//! sequence (the memory limit [`crate::piston::series::MAX_SERIES`]
//! samples), the
//! longest block that fits, n′, is measured and the piston variance is
//! carried to n as 1/n (`extrapolated_from_scans`: it assumes the scans
//! further apart than n′ scan periods are uncorrelated).

use super::correlation::ScanCorrelation;
use super::scans::{affordable_scans, SEQUENCES};
pub(crate) use super::scans::{ContiguousScans, ScanValues};
use super::{PlanInputs, PlanPoint, CONFIDENCE};
use crate::conformance::estimate::{BiasConvention, RowEstimator};
use crate::error::Result;
use crate::formalism::estimator::BinWindow;
use crate::montecarlo::{derive_seed, replicated_summary, replicated_t_quantile, RunningStats};
use crate::montecarlo::{Steps, Summary};
use crate::piston::sequences::{correlation_time_s, SPAN_CORRELATION_TIMES};
use crate::piston::series::MAX_SERIES;
use crate::piston::spectrum::PistonSpectrum;
use crate::simulator::Model;
use serde::Serialize;

/// Samples from one scan's start to the next: the scan and its dead time.
pub(crate) fn stride_samples(inputs: &PlanInputs, model: &Model, fringe_hz: f64) -> usize {
    let t_s = 1.0 / (inputs.samples_per_fringe * fringe_hz);
    model.samples() + (inputs.dead_time_s / t_s).round() as usize
}

/// Blocks of n consecutive scans each sequence of the plan's observation
/// Monte Carlo holds at least (when [`super::MAX_OBSERVATION_SAMPLES`] allows):
/// the sequence then also holds the piston's wander slower than the
/// observation (an FFT sequence has nothing below one over its length),
/// and the K sequences give 4K observations. Measured in the bright case of
/// `tests/plan_observation.rs` (V1², 130 m, n = 1866): sequences of 1.4 n
/// (two correlation times, one block each) promised 6.2e-5 where the
/// verification's 16-block sequences achieved 7.4e-5 ± 0.4e-5.
pub const BLOCKS_PER_SEQUENCE: u64 = 4;

/// Scans per sequence that hold `scans` scans (the blocks wanted), span
/// [`SPAN_CORRELATION_TIMES`] correlation times and hold `budget / K` (the
/// plan's `scans`); at most what one sequence within the memory limit
/// holds and, with `capped`, what [`super::MAX_OBSERVATION_SAMPLES`] allows (but
/// `least`); None when not even one scan fits.
pub(crate) fn scans_per_sequence(
    sky: &PistonSpectrum,
    (samples, stride, sample_time_s): (usize, usize, f64),
    (scans, least): (u64, u64),
    (budget, capped): (u64, bool),
) -> Option<usize> {
    let span = SPAN_CORRELATION_TIMES * correlation_time_s(sky) / sample_time_s / stride as f64;
    let wanted = (scans as f64)
        .max(span.ceil())
        .max((budget / SEQUENCES as u64) as f64);
    // One sequence at a time at most (the sequences are simulated in
    // batches that fit the memory limit together).
    let mut most = MAX_SERIES.saturating_sub(samples + 4) / stride;
    if capped {
        most = most.min(affordable_scans(samples).max(least as usize));
    }
    (most >= 1).then(|| wanted.min(most as f64) as usize)
}

/// Sequences of `per_sequence` scans of `samples` samples, `stride`
/// apart, simulated at a time: as many as the memory limit
/// ([`MAX_SERIES`] samples together) allows.
pub(crate) fn sequences_per_batch(samples: usize, per_sequence: usize, stride: usize) -> usize {
    let length = (per_sequence - 1) * stride + samples + 4;
    (MAX_SERIES / length).clamp(1, SEQUENCES)
}

/// The rows of the batch of `k` sequences from sequence `first` of a run
/// from `seed` (each batch its own seed, keyed by its first sequence):
/// what [`ContiguousScans::simulate`] and the verification's Dask units
/// both draw.
pub(crate) fn batch_rows(
    model: &Model,
    seed: u64,
    first: usize,
    (k, per_sequence, stride): (usize, usize, usize),
) -> Result<crate::simulator::Rows<'_>> {
    let rows = (k * per_sequence) as u64;
    let batch_seed = derive_seed(seed, "observation-batch", &[first as f64]);
    model.rows_with_layout(rows, batch_seed, 0, Some((k, stride)))
}

impl ContiguousScans {
    /// Simulates `SEQUENCES × per_sequence` scans of `model` (with piston),
    /// `stride` samples apart, from `seed` (in batches of sequences that fit
    /// [`MAX_SERIES`] samples together), estimated under `bias`;
    /// `offsets` (noise-free scans of a model whose noise is `noisy`) also
    /// records the `model` convention's offset.
    pub(crate) fn simulate(
        model: &Model,
        noisy: Option<&Model>,
        bias: BiasConvention,
        (per_sequence, stride, sample_time_s): (usize, usize, f64),
        seed: u64,
        progress: &(dyn Fn(u64) + Sync),
    ) -> Result<ContiguousScans> {
        let window = BinWindow::Positive;
        let est = RowEstimator::new(model, window, bias, true)?;
        let pair = match noisy {
            Some(m) => Some((
                RowEstimator::new(m, window, BiasConvention::Model, true)?,
                RowEstimator::new(m, window, BiasConvention::Counts, true)?,
            )),
            None => None,
        };
        let n = model.samples();
        let mut values = Vec::with_capacity(SEQUENCES * per_sequence);
        let per_batch = sequences_per_batch(n, per_sequence, stride);
        for first in (0..SEQUENCES).step_by(per_batch) {
            let k = per_batch.min(SEQUENCES - first);
            let set = batch_rows(model, seed, first, (k, per_sequence, stride))?;
            set.fold_units(
                0,
                |_, block| {
                    let mut steps = Steps::new(progress, n);
                    let out = block
                        .chunks_exact(n)
                        .map(|row| {
                            steps.step()?;
                            scan_values(&est, pair.as_ref(), row)
                        })
                        .collect::<Result<Vec<ScanValues>>>()?;
                    steps.finish()?;
                    Ok(out)
                },
                |block: Vec<ScanValues>| values.extend(block),
            )?;
        }
        Ok(ContiguousScans {
            sequences: values.chunks(per_sequence).map(<[_]>::to_vec).collect(),
            scan_period_s: stride as f64 * sample_time_s,
        })
    }

    /// Scans of each sequence.
    pub(crate) fn per_sequence(&self) -> usize {
        self.sequences.first().map_or(0, Vec::len)
    }

    /// The block means of `n` consecutive scans, V1² and V2², each over
    /// every block of every sequence with errors from the spread between
    /// sequences; `with_offset` adds the `model` convention's offset.
    pub(crate) fn block_means(&self, n: usize, with_offset: bool) -> [Summary; 2] {
        let n = n.clamp(1, self.per_sequence().max(1));
        [0, 1].map(|e| {
            let groups: Vec<RunningStats> = self
                .sequences
                .iter()
                .map(|seq| {
                    let mut g = RunningStats::default();
                    for block in seq.chunks_exact(n) {
                        let sum: f64 = block
                            .iter()
                            .map(|s| s.v_sq[e] + if with_offset { s.model_offset[e] } else { 0.0 })
                            .sum();
                        g.push(sum / n as f64);
                    }
                    g
                })
                .collect();
            replicated_summary(&groups)
        })
    }

    /// The mean `model` convention offset of V1², V2² over every scan, with
    /// its standard error from the spread between sequences.
    pub(crate) fn offset(&self) -> [Summary; 2] {
        [0, 1].map(|e| {
            let groups: Vec<RunningStats> = self
                .sequences
                .iter()
                .map(|seq| {
                    let mut g = RunningStats::default();
                    seq.iter().for_each(|s| g.push(s.model_offset[e]));
                    g
                })
                .collect();
            replicated_summary(&groups)
        })
    }
}

fn scan_values(
    est: &RowEstimator,
    pair: Option<&(RowEstimator, RowEstimator)>,
    row: &[f64],
) -> Result<ScanValues> {
    let e = est.estimate(row)?;
    let model_offset = match pair {
        None => [0.0; 2],
        Some((model, counts)) => {
            let (m, c) = (model.estimate(row)?, counts.estimate(row)?);
            [m.v1_sq - c.v1_sq, m.v2_sq - c.v2_sq]
        }
    };
    Ok(ScanValues {
        v_sq: [e.v1_sq, e.v2_sq],
        model_offset,
    })
}

/// The error of an observation of `scans` consecutive scans at one
/// setting: what the plan promises, and how it was measured.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ObservationError {
    /// n, consecutive scans of the observation.
    pub scans: u64,
    /// One scan and its dead time, s.
    pub scan_period_s: f64,
    /// Independent piston sequences simulated ([`SEQUENCES`]).
    pub sequences: usize,
    /// Consecutive scans simulated in each sequence (L: they span
    /// 8 correlation times B/v, the plan's correlation module's span,
    /// where [`super::MAX_OBSERVATION_SAMPLES`] allows, whatever n).
    pub scans_per_sequence: u64,
    /// Disjoint blocks of n consecutive scans the sequences hold (0 when n
    /// is longer than a sequence: the variance then comes from the scans'
    /// correlation, not from simulated observations).
    pub simulated_observations: u64,
    /// W: the per-scan errors' autocovariance is summed up to W scans
    /// apart (a quarter of a sequence).
    pub correlation_window_scans: u64,
    /// σ of the mean of n consecutive scans from the piston alone.
    pub sigma_piston: f64,
    /// Its standard error (spread between the sequences).
    pub sigma_piston_stderr: f64,
    /// The terms of the variance between W and 2W scans apart (0 when
    /// n − 1 ≤ W): what summing only up to W leaves out, estimated; its
    /// size widens the interval both ways.
    pub variance_beyond_window: f64,
    /// The upper end of σ_piston's [`CONFIDENCE`] interval (with the terms
    /// beyond the window): the promise's piston term.
    pub sigma_piston_upper: f64,
    /// The lower end of that interval.
    pub sigma_piston_lower: f64,
    /// What independent scans would give: σ_piston per scan / √n.
    pub sigma_piston_if_independent: f64,
    /// σ_piston(n)² · n / σ²_piston per scan: 1 for independent scans,
    /// above 1 when consecutive scans share the piston's errors, below 1
    /// when they cancel over the observation (each scan's error follows
    /// the piston's drift within it, and the drifts of n scans add up to
    /// the observation's bounded net drift: [`super::inflation_words`]).
    pub variance_inflation: f64,
    /// σ of one scan from detector and photon noise under the convention
    /// (the upper end of its interval for `counts`, from a Monte Carlo).
    pub sigma_noise_per_scan: f64,
    /// The lower end of that interval (the exact value for `model`).
    pub sigma_noise_per_scan_lower: f64,
    /// σ_noise per scan / √n (independent from scan to scan).
    pub sigma_noise: f64,
    /// The promise: sqrt(σ_noise² + σ_piston_upper²), the σ(V²) of the
    /// observation's mean.
    pub sigma: f64,
    /// With the `model` convention: its photon-bias offset on the mean
    /// (0 with `counts`).
    pub convention_offset: f64,
    /// Standard error of `convention_offset`.
    pub convention_offset_stderr: f64,
    /// The mean of the observation expected, V²: the noise-free,
    /// piston-free estimate + the piston bias + the convention's offset.
    pub predicted_mean: f64,
    /// The uncorrectable bias, predicted_mean − V²_sampled (the target
    /// must stay above the upper end of its |interval|).
    pub bias: f64,
    /// The standard error of `bias` (the piston bias's and the offset's).
    pub bias_stderr: f64,
    /// The upper end of |bias|'s [`CONFIDENCE`] interval.
    pub bias_upper: f64,
    /// W + 1 when n is longer: the scans more than W apart were taken as
    /// uncorrelated, and `variance_beyond_window` states what that leaves
    /// out.
    pub extrapolated_from_scans: Option<u64>,
}

/// The inputs of [`observation_error`] at one grid point.
pub(crate) struct AtPoint<'a> {
    pub(crate) scans: &'a ContiguousScans,
    /// The per-scan errors' autocovariance of the point's estimator.
    pub(crate) correlation: &'a ScanCorrelation,
    pub(crate) point: &'a PlanPoint,
    pub(crate) convention: BiasConvention,
    /// σ per scan of the noise under the convention: the lower and upper
    /// ends of its interval.
    pub(crate) sigma_noise_per_scan: [f64; 2],
}

/// The error of an observation of `n` consecutive scans at `at`.
/// With `upper`, the piston and noise terms at the upper ends of their
/// [`CONFIDENCE`] intervals (the promise); else at the lower ends (the best
/// the setting could be, for the time's interval).
pub(crate) fn observation_error(at: &AtPoint, n: u64, upper: bool) -> ObservationError {
    let p = at.point;
    let s = at.scans;
    let model = at.convention == BiasConvention::Model;
    let fits = s.per_sequence() as u64;
    let e = match p.estimator {
        super::Estimator::V1 => 0,
        super::Estimator::V2 => 1,
    };
    let offset = if model {
        s.offset()[e]
    } else {
        Summary::default()
    };
    let t = replicated_t_quantile(CONFIDENCE, s.sequences.len());
    let v = at.correlation.piston_variance(n);
    let measured = v.var.max(0.0);
    let spread = t * v.var_stderr.hypot(v.tail_stderr) + v.tail.abs();
    let sigma_piston = measured.sqrt();
    let sigma_piston_upper = (measured + spread).sqrt();
    let sigma_piston_lower = (v.var - spread).max(0.0).sqrt();
    let [noise_lower, noise_upper] = at.sigma_noise_per_scan;
    let noise_per_scan = if upper { noise_upper } else { noise_lower };
    let sigma_noise = noise_per_scan / (n as f64).sqrt();
    let piston_used = if upper {
        sigma_piston_upper
    } else {
        sigma_piston_lower
    };
    let per_scan = p.sigma_piston_per_scan;
    let bias = p.bias_piston + offset.mean;
    let bias_se = p.bias_piston_stderr.hypot(offset.stderr_mean);
    let signed_t = if upper { t } else { -t };
    let window = at.correlation.window() as u64;
    ObservationError {
        scans: n,
        scan_period_s: s.scan_period_s,
        sequences: s.sequences.len(),
        scans_per_sequence: fits,
        simulated_observations: (fits / n.max(1)) * s.sequences.len() as u64,
        correlation_window_scans: window,
        sigma_piston,
        sigma_piston_stderr: if sigma_piston > 0.0 {
            v.var_stderr / (2.0 * sigma_piston)
        } else {
            v.var_stderr.sqrt()
        },
        variance_beyond_window: v.tail,
        sigma_piston_upper,
        sigma_piston_lower,
        sigma_piston_if_independent: per_scan / (n as f64).sqrt(),
        variance_inflation: measured * n as f64 / (per_scan * per_scan),
        sigma_noise_per_scan: noise_upper,
        sigma_noise_per_scan_lower: noise_lower,
        sigma_noise,
        sigma: sigma_noise.hypot(piston_used),
        convention_offset: offset.mean,
        convention_offset_stderr: offset.stderr_mean,
        predicted_mean: p.v_sq_sampled + bias,
        bias,
        bias_stderr: bias_se,
        bias_upper: (bias.abs() + signed_t * bias_se).max(0.0),
        extrapolated_from_scans: (n > window + 1).then_some(window + 1),
    }
}

/// The fewest consecutive scans whose observation reaches σ(V²) =
/// `target` with the bias's upper end (n enters both sides: the piston
/// variance of the mean is computed at each n tried), from the
/// independent-scan estimate `start`; None when the bias's upper end is at
/// or above the target.
pub(crate) fn solve_scans(
    at: &AtPoint,
    target: f64,
    start: f64,
    upper: bool,
) -> Option<ObservationError> {
    let reaches =
        |o: &ObservationError| o.bias_upper < target && o.sigma.hypot(o.bias_upper) <= target;
    let mut n = (start.max(1.0)) as u64;
    let first = observation_error(at, n, upper);
    if first.bias_upper >= target {
        return None;
    }
    // Fixed point of n = n σ²_obs(n) / (target² − bias²): σ²_obs ∝ 1/n
    // locally; a few steps settle it.
    for _ in 0..20 {
        let o = observation_error(at, n, upper);
        let room = target * target - o.bias_upper * o.bias_upper;
        let next = ((n as f64) * o.sigma * o.sigma / room).ceil().max(1.0);
        if !next.is_finite() || next > 1e15 {
            return None;
        }
        let next = next as u64;
        if next == n || (reaches(&o) && next < n && n - next <= n / 100 + 1) {
            break;
        }
        n = next;
    }
    // σ²_obs(n)·n is not constant in n: step up until the promise holds,
    // then back down to the fewest scans that keep it.
    for _ in 0..400 {
        let o = observation_error(at, n, upper);
        if reaches(&o) {
            return Some(fewest(at, target, upper, o));
        }
        n = (n + n / 50).max(n + 1);
    }
    None
}

/// From an n that reaches the target, the fewest scans that still do (by
/// halving the step down), so the answer does not depend on where the
/// search came from.
fn fewest(at: &AtPoint, target: f64, upper: bool, mut best: ObservationError) -> ObservationError {
    let reaches =
        |o: &ObservationError| o.bias_upper < target && o.sigma.hypot(o.bias_upper) <= target;
    let mut step = (best.scans / 50).max(1);
    loop {
        let down = best.scans.saturating_sub(step).max(1);
        let o = observation_error(at, down, upper);
        if down < best.scans && reaches(&o) {
            best = o;
        } else if step == 1 {
            return best;
        } else {
            step /= 2;
        }
    }
}

/// The seed of the observation Monte Carlo of the settings at fringe
/// frequency f (Hz): the strokes of one frequency scan one atmosphere (and
/// draw it once when solved together).
pub(crate) fn observation_seed(seed: u64, fringe_hz: f64) -> u64 {
    derive_seed(seed, "plan-observation", &[fringe_hz])
}

/// σ of the mean of n consecutive noise-free scans (the piston alone) at
/// one fringe frequency: what `v2ref piston --observation-scans` reports.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ObservationPiston {
    /// f, Hz.
    pub fringe_hz: f64,
    /// n, consecutive scans (no dead time between them).
    pub scans: u64,
    /// The observation's length, n scans, s.
    pub duration_s: f64,
    /// Independent piston sequences simulated ([`SEQUENCES`]).
    pub sequences: usize,
    /// Consecutive scans simulated in each.
    pub scans_per_sequence: u64,
    /// Blocks of n consecutive scans (simulated observations) in all.
    pub simulated_observations: u64,
    /// σ of V1² per scan (the same scans).
    pub sigma_v1_sq_per_scan: f64,
    /// σ of V2² per scan.
    pub sigma_v2_sq_per_scan: f64,
    /// σ of the mean of n consecutive scans of V1².
    pub sigma_v1_sq: f64,
    /// Its standard error (spread between the sequences).
    pub sigma_v1_sq_stderr: f64,
    /// σ of the mean of n consecutive scans of V2².
    pub sigma_v2_sq: f64,
    /// Its standard error.
    pub sigma_v2_sq_stderr: f64,
    /// n σ²(mean)/σ²(scan) for V1²: 1 for independent scans.
    pub variance_inflation_v1: f64,
    /// The same for V2².
    pub variance_inflation_v2: f64,
    /// n′ when n consecutive scans do not fit in one simulated sequence:
    /// measured at n′ and carried to n as 1/n.
    pub extrapolated_from_scans: Option<u64>,
}

/// The [`ObservationPiston`] of `model` (noise-free, with piston on the
/// spectrum `sky`) for observations of `n` consecutive scans, from `seed`.
pub fn observation_piston(
    model: &Model,
    sky: &PistonSpectrum,
    n: u64,
    seed: u64,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<ObservationPiston> {
    let setup = model
        .inputs
        .scan_setup()
        .ok_or_else(|| crate::Error::Invalid {
            param: "fringe_hz",
            reason: "an observation's piston needs a fringe frequency".into(),
        })?;
    crate::error::in_range("observation_scans", n as f64, 1.0, 1e12)?;
    let t_s = setup.sample_time_s();
    let samples = model.samples();
    let shape = (samples, samples, t_s);
    let wanted = (n.saturating_mul(BLOCKS_PER_SEQUENCE), n);
    let per_sequence = scans_per_sequence(sky, shape, wanted, (0, true)).unwrap_or(1);
    let scans = ContiguousScans::simulate(
        model,
        None,
        BiasConvention::Model,
        (per_sequence, samples, t_s),
        seed,
        progress,
    )?;
    let measured = n.min(per_sequence as u64);
    let carry = (measured as f64 / n as f64).sqrt();
    let [b1, b2] = scans.block_means(measured as usize, false);
    let [s1, s2] = scans.block_means(1, false);
    let inflation = |b: &Summary, s: &Summary| b.var * carry * carry * n as f64 / s.var;
    Ok(ObservationPiston {
        fringe_hz: setup.fringe_hz,
        scans: n,
        duration_s: n as f64 * setup.scan_time_s(),
        sequences: SEQUENCES,
        scans_per_sequence: per_sequence as u64,
        simulated_observations: b1.count,
        sigma_v1_sq_per_scan: s1.std,
        sigma_v2_sq_per_scan: s2.std,
        sigma_v1_sq: b1.std * carry,
        sigma_v1_sq_stderr: b1.stderr_std * carry,
        sigma_v2_sq: b2.std * carry,
        sigma_v2_sq_stderr: b2.stderr_std * carry,
        variance_inflation_v1: inflation(&b1, &s1),
        variance_inflation_v2: inflation(&b2, &s2),
        extrapolated_from_scans: (measured < n).then_some(measured),
    })
}
