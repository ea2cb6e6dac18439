//! The observation's piston variance for any number of consecutive scans,
//! from sequences that span a few of the atmosphere's correlation times.
//!
//! The variance of the mean of n consecutive scans is a sum over the
//! autocovariance γ_k of the per-scan piston error,
//!
//! `σ²_obs(n) = (1/n) [γ_0 + 2 Σ_{k=1}^{n−1} (1 − k/n) γ_k]`,
//!
//! and γ_k dies out once k scan periods exceed the time over which the
//! piston's wander is correlated (B/v, or the outer scale over the wind).
//! So the planner does not simulate n scans (n reaches 10⁵ for a faint
//! V2² setting): it simulates [`SEQUENCES`](super::SEQUENCES) independent
//! sequences of L scans spanning [`SPAN_CORRELATION_TIMES`] correlation
//! times, estimates γ_k on each up to lag 2W with W = L/4 ([`WINDOW_FRACTION`]),
//! and sums the terms up to W. For n − 1 ≤ W the sum is complete (the
//! same quantity the block means of n scans estimate, from every
//! overlapping pair instead of disjoint blocks). For longer observations
//! the terms beyond W are taken as zero, and the size of what that
//! leaves out is stated: the terms between W and 2W, which enter the
//! intervals as an error of their own (`tail`). Each sequence gives its
//! own estimate; their spread gives the standard error with K − 1 degrees
//! of freedom (batch means: valid however correlated the scans of one
//! sequence are). The lags are summed about the mean of all sequences
//! (they share one true mean), so a sequence's own mean is not subtracted
//! from it and the slow part of its wander is kept.

use super::scans::{affordable_scans, ContiguousScans, SEQUENCES};
use crate::piston::sequences::correlation_time_s;
use crate::piston::series::MAX_SERIES;
use crate::piston::spectrum::PistonSpectrum;
use num_complex::Complex64;
use rustfft::FftPlanner;

/// Correlation times B/v of lags summed (the window W, where a sequence
/// holds four windows): the lags from W to 2W measure what is left beyond.
pub const WINDOW_CORRELATION_TIMES: f64 = 2.0;

/// Correlation times B/v one sequence of the observation's Monte Carlo
/// spans at least (where [`super::MAX_OBSERVATION_SAMPLES`] allows): four
/// windows.
pub const SPAN_CORRELATION_TIMES: f64 = 4.0 * WINDOW_CORRELATION_TIMES;

/// The window W is at most a sequence's scans L over this.
pub const WINDOW_FRACTION: usize = 4;

/// Fewest scans of one sequence (a window of 16 lags).
pub const MIN_SCANS: usize = 64;

/// Samples (scans × N, all sequences) a setting's observation Monte Carlo
/// fills at least when the span needs fewer (longer sequences: more
/// pairs of scans at every lag), about 0.4 core-seconds.
pub const FILL_SAMPLES: usize = 1 << 22;

/// Scans of each sequence of a setting's observation Monte Carlo, whatever
/// the n it is asked about: [`SPAN_CORRELATION_TIMES`] correlation times
/// (B/v) of scans `stride` samples apart, at least [`MIN_SCANS`] and the
/// plan's `budget` / K, within [`super::MAX_OBSERVATION_SAMPLES`] simulated
/// samples and one sequence within [`MAX_SERIES`].
pub(crate) fn scans_per_sequence(
    sky: &PistonSpectrum,
    (samples, stride, sample_time_s): (usize, usize, f64),
    budget: u64,
) -> usize {
    let span = SPAN_CORRELATION_TIMES * correlation_time_s(sky) / (sample_time_s * stride as f64);
    let fill = FILL_SAMPLES / (SEQUENCES * samples.max(1));
    let wanted = span
        .ceil()
        .max(MIN_SCANS as f64)
        .max(fill as f64)
        .max((budget / SEQUENCES as u64) as f64);
    let fits = MAX_SERIES.saturating_sub(samples + 4) / stride.max(1);
    let affordable = affordable_scans(samples);
    (wanted as usize).min(fits).min(affordable).max(1)
}

/// Per sequence, the autocovariance γ_k of one estimator's per-scan error
/// for k = 0..=2W, about the mean of all sequences, as prefix sums.
pub(crate) struct ScanCorrelation {
    /// Per sequence: γ_0 and, for m = 0..=2W, Σ_{k=1}^{m} γ_k and
    /// Σ_{k=1}^{m} k γ_k (so σ²_obs(n) costs K operations).
    lags: Vec<Prefix>,
    /// W, the lags summed.
    window: usize,
}

/// The piston variance of the mean of n consecutive scans, with its
/// errors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PistonVariance {
    /// σ²_obs(n), the mean of the sequences' estimates (lags up to W).
    pub(crate) var: f64,
    /// Its standard error (the spread between the sequences).
    pub(crate) var_stderr: f64,
    /// The terms between lags W and 2W (0 when n − 1 ≤ W): what the
    /// truncation at W leaves out, estimated.
    pub(crate) tail: f64,
    /// Its standard error.
    pub(crate) tail_stderr: f64,
    /// σ² of one scan (γ_0).
    pub(crate) var_per_scan: f64,
    /// Independent sequences behind the errors (K − 1 degrees of freedom).
    pub(crate) sequences: usize,
}

impl ScanCorrelation {
    /// The autocovariances of estimator `e` (0: V1², 1: V2²) over the
    /// sequences of `scans`, summed up to `correlation_scans` lags (the
    /// window W, at most a quarter of a sequence); `with_offset` adds the
    /// `model` convention's offset to each scan.
    pub(crate) fn new(
        scans: &ContiguousScans,
        (e, with_offset): (usize, bool),
        correlation_scans: f64,
    ) -> ScanCorrelation {
        let value = |s: &super::scans::ScanValues| {
            s.v_sq[e] + if with_offset { s.model_offset[e] } else { 0.0 }
        };
        let count: usize = scans.sequences.iter().map(Vec::len).sum();
        let mean = scans.sequences.iter().flatten().map(value).sum::<f64>() / count.max(1) as f64;
        let length = scans.per_sequence();
        let window = ((WINDOW_CORRELATION_TIMES * correlation_scans).ceil() as usize)
            .max(16)
            .min(length / WINDOW_FRACTION)
            .max(1);
        let most_lag = (2 * window).min(length.saturating_sub(1));
        let mut planner = FftPlanner::new();
        let size = (2 * length).max(2);
        let forward = planner.plan_fft_forward(size);
        let inverse = planner.plan_fft_inverse(size);
        let lags = scans
            .sequences
            .iter()
            .map(|seq| {
                let mut buf: Vec<Complex64> = seq
                    .iter()
                    .map(|s| Complex64::new(value(s) - mean, 0.0))
                    .chain(std::iter::repeat(Complex64::new(0.0, 0.0)))
                    .take(size)
                    .collect();
                forward.process(&mut buf);
                buf.iter_mut()
                    .for_each(|c| *c = Complex64::new(c.norm_sqr(), 0.0));
                inverse.process(&mut buf);
                let gamma = |k: usize| buf[k].re / size as f64 / (length - k) as f64;
                Prefix::of(&(0..=most_lag).map(gamma).collect::<Vec<_>>())
            })
            .collect();
        ScanCorrelation { lags, window }
    }

    /// W: lags summed.
    pub(crate) fn window(&self) -> usize {
        self.window
    }

    /// σ²_obs(n) of the piston, lags up to W, and the terms from W to 2W.
    pub(crate) fn piston_variance(&self, n: u64) -> PistonVariance {
        let n_f = n.max(1) as f64;
        let last = (n.max(1) - 1).min(self.window as u64) as usize;
        let (mut sums, mut tails, mut scan) = (Vec::new(), Vec::new(), Vec::new());
        for g in &self.lags {
            let last = last.min(g.sum.len() - 1);
            // Σ_{k=a+1}^{b} 2 (1 − k/n) γ_k.
            let terms = |a: usize, b: usize| {
                2.0 * ((g.sum[b] - g.sum[a]) - (g.weighted[b] - g.weighted[a]) / n_f)
            };
            let beyond = ((n.max(1) - 1) as usize).min(g.sum.len() - 1).max(last);
            sums.push((g.gamma0 + terms(0, last)) / n_f);
            tails.push(terms(last, beyond) / n_f);
            scan.push(g.gamma0);
        }
        let ((var, var_stderr), (tail, tail_stderr)) = (mean_stderr(&sums), mean_stderr(&tails));
        PistonVariance {
            var,
            var_stderr,
            tail,
            tail_stderr,
            var_per_scan: mean_stderr(&scan).0,
            sequences: self.lags.len(),
        }
    }
}

/// One sequence's autocovariance as prefix sums.
struct Prefix {
    gamma0: f64,
    /// sum[m] = Σ_{k=1}^{m} γ_k (sum[0] = 0).
    sum: Vec<f64>,
    /// weighted[m] = Σ_{k=1}^{m} k γ_k.
    weighted: Vec<f64>,
}

impl Prefix {
    fn of(gamma: &[f64]) -> Prefix {
        let (mut sum, mut weighted) = (vec![0.0], vec![0.0]);
        for (k, g) in gamma.iter().enumerate().skip(1) {
            sum.push(sum[k - 1] + g);
            weighted.push(weighted[k - 1] + k as f64 * g);
        }
        Prefix {
            gamma0: gamma[0],
            sum,
            weighted,
        }
    }
}

/// The mean of independent estimates and its standard error, s/√K (NaN
/// with fewer than two).
fn mean_stderr(values: &[f64]) -> (f64, f64) {
    let k = values.len() as f64;
    let mean = values.iter().sum::<f64>() / k;
    let ss: f64 = values.iter().map(|v| (v - mean) * (v - mean)).sum();
    (mean, (ss / (k - 1.0) / k).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::scans::ScanValues;

    /// K sequences of L values of an AR(1) process of correlation `rho`
    /// and unit variance (γ_k = ρ^k), as the V1² of scans.
    fn ar1(rho: f64, (k, l): (usize, usize), seed: u64) -> ContiguousScans {
        let mut rng = crate::montecarlo::unit_rng(seed, 0);
        let mut normal = || -> f64 { rng.standard_normal() };
        let sequences = (0..k)
            .map(|_| {
                let mut x = normal();
                (0..l)
                    .map(|_| {
                        x = rho * x + (1.0 - rho * rho).sqrt() * normal();
                        ScanValues {
                            v_sq: [x, 0.0],
                            model_offset: [0.0; 2],
                        }
                    })
                    .collect()
            })
            .collect();
        ContiguousScans {
            sequences,
            scan_period_s: 1.0,
        }
    }

    /// The variance of the mean of n values of that process, closed form:
    /// (1/n) [(1+ρ)/(1−ρ) − 2ρ(1−ρⁿ)/(n(1−ρ)²)].
    fn exact(rho: f64, n: u64) -> f64 {
        let n = n as f64;
        ((1.0 + rho) / (1.0 - rho) - 2.0 * rho * (1.0 - rho.powf(n)) / (n * (1.0 - rho).powi(2)))
            / n
    }

    /// The estimate agrees with the closed form within 5 standard errors
    /// at observations shorter and far longer than the window, and those
    /// errors are small enough to reject a variance 2 % off (power); the
    /// terms beyond the window are 0 when none is left out, and tiny when
    /// the correlation has died out within it.
    #[test]
    fn variance_of_the_mean_matches_an_ar1_process() {
        let rho = 0.5;
        let scans = ar1(rho, (16, 1 << 19), 7);
        // Window 2 × 8 = 16 lags: ρ^16 = 1.5e-5.
        let c = ScanCorrelation::new(&scans, (0, false), 8.0);
        assert_eq!(c.window(), 16);
        for n in [1_u64, 5, 16, 17, 1000, 1_000_000] {
            let v = c.piston_variance(n);
            let truth = exact(rho, n);
            let se = v.var_stderr.hypot(v.tail_stderr);
            let z = (v.var + v.tail - truth) / se;
            assert!(z.abs() < 5.0, "n = {n}: {} vs {truth} (z = {z})", v.var);
            assert!(
                5.0 * se < 0.02 * truth,
                "n = {n}: no power ({se} of {truth})"
            );
            if n <= 17 {
                assert_eq!(v.tail, 0.0, "n = {n}");
            } else {
                let z = v.tail / v.tail_stderr;
                assert!(z.abs() < 5.0, "n = {n}: tail {} (z = {z})", v.tail);
            }
        }
    }

    /// An estimate that forgot the correlation (independent scans, 1/n)
    /// is rejected by the same test: (1+ρ)/(1−ρ) = 3 times too small.
    #[test]
    fn independent_scan_variance_is_rejected() {
        let rho = 0.5;
        let scans = ar1(rho, (16, 1 << 16), 11);
        let c = ScanCorrelation::new(&scans, (0, false), 8.0);
        let n = 1000;
        let v = c.piston_variance(n);
        let independent = v.var_per_scan / n as f64;
        assert!((v.var - independent) / v.var_stderr > 5.0);
    }
}
