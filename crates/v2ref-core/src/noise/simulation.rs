//! Monte Carlo of noisy sampled interferograms (Appendix): the noise of each
//! sample drawn from its law, both raw estimators accumulated over a fixed
//! window of Fourier bins, on the deterministic parallel driver of
//! [`crate::montecarlo`].

use crate::formalism::estimator::dft_phase;
use crate::montecarlo::{fold_units, run_units, Rng, RunningStats, Steps};

/// Both raw estimators over a fixed window of Fourier bins, evaluated
/// without a full FFT where possible:
///
/// - V1²_K: for real samples `|B_k| = |B_{N−k}|`, so the window folds onto
///   bins 0 … N/2 with multiplicities w_k; with Parseval
///   (`N Σ M² = Σ_k f_k |B_k|²`, f_k the multiplicity of the full set),
///   `V1²_K = c N Σ M² + Σ_k (w_k − c f_k) |B_k|²` with c ∈ {0, ½, 1}
///   chosen to leave the fewest bins to evaluate: none for all bins, DC
///   and Nyquist for the positive half, the band bins for a band window;
///   those are evaluated by direct DFT, or by FFT when cheaper;
/// - V2²_K: `|Σ_i u_i M_i|²` with `u_i = Σ_{k∈K} e^{−2πi ik/N}` precomputed.
///
/// Checked against [`crate::formalism::estimator::raw_estimates`] of the FFT in
/// `tests/montecarlo_noise.rs`.
#[derive(Clone)]
pub struct WindowedEstimators {
    n: usize,
    parseval: f64,
    /// (weight, cos table, sin table) of the bins evaluated directly; the
    /// sine table is dropped where it vanishes (k = 0 and N/2).
    direct: Vec<(f64, Vec<f64>, Option<Vec<f64>>)>,
    /// Bins and weights evaluated by FFT instead (when many).
    fft_bins: Vec<(usize, f64)>,
    fft: Option<std::sync::Arc<dyn rustfft::Fft<f64>>>,
    u_re: Vec<f64>,
    u_im: Vec<f64>,
    /// The non-zero u_i when few (all bins: only u_0 = N).
    u_sparse: Option<Vec<(usize, f64, f64)>>,
}

impl std::fmt::Debug for WindowedEstimators {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("WindowedEstimators")
            .field("n", &self.n)
            .field("parseval", &self.parseval)
            .field("direct_bins", &self.direct.len())
            .field("fft_bins", &self.fft_bins.len())
            .finish()
    }
}

impl WindowedEstimators {
    /// The estimators of window `bins` (each < `n`) for `n` samples.
    pub fn new(n: usize, bins: &[usize]) -> WindowedEstimators {
        let half = n / 2;
        let mut mult = vec![0.0; half + 1];
        let mut seen = vec![false; n];
        for &k in bins.iter().filter(|&&k| k < n) {
            if !seen[k] {
                seen[k] = true;
                mult[k.min(n - k)] += 1.0;
            }
        }
        let full: Vec<f64> = (0..=half)
            .map(|k| if k == 0 || 2 * k == n { 1.0 } else { 2.0 })
            .collect();
        let count = |c: f64| {
            (0..=half)
                .filter(|&k| (mult[k] - c * full[k]).abs() > 0.0)
                .count()
        };
        let parseval = [0.0, 0.5, 1.0]
            .into_iter()
            .min_by_key(|&c| count(c))
            .unwrap_or(0.0);
        let weighted: Vec<(usize, f64)> = (0..=half)
            .map(|k| (k, mult[k] - parseval * full[k]))
            .filter(|&(_, w)| w != 0.0)
            .collect();
        // A direct bin costs 2N multiply-adds; a complex FFT ≈ 5 N log2 N flops.
        let fft_cheaper = weighted.len() as f64 * 2.0 > 5.0 * (n as f64).log2().max(1.0) && n >= 16;
        let table = |k: usize| -> (Vec<f64>, Vec<f64>) {
            (0..n)
                .map(|i| {
                    let ph = dft_phase(i, k, n);
                    (ph.cos(), ph.sin())
                })
                .unzip()
        };
        let (direct, fft_bins, fft) = if fft_cheaper {
            let plan = rustfft::FftPlanner::new().plan_fft_forward(n);
            (Vec::new(), weighted, Some(plan))
        } else {
            let d = weighted
                .iter()
                .map(|&(k, w)| {
                    let (c, s) = table(k);
                    // sin(2π ik/N) is 0 for k = 0 and N/2 up to rounding.
                    let s = (k != 0 && 2 * k != n).then_some(s);
                    (w, c, s)
                })
                .collect();
            (d, Vec::new(), None)
        };
        let (mut u_re, mut u_im) = (vec![0.0; n], vec![0.0; n]);
        for (i, (re, im)) in u_re.iter_mut().zip(u_im.iter_mut()).enumerate() {
            for &k in bins.iter().filter(|&&k| k < n) {
                let ph = dft_phase(i, k, n);
                *re += ph.cos();
                *im += ph.sin();
            }
        }
        // A Dirichlet-type kernel: entries below KERNEL_ZERO_REL |K| are rounding
        // residues of exact zeros (all bins: u_i = N δ_i0).
        let floor = crate::tolerance::KERNEL_ZERO_REL * bins.len().max(1) as f64;
        let significant: Vec<(usize, f64, f64)> = (0..n)
            .filter(|&i| u_re[i].hypot(u_im[i]) > floor)
            .map(|i| (i, u_re[i], u_im[i]))
            .collect();
        let u_sparse = (significant.len() * 8 <= n).then_some(significant);
        WindowedEstimators {
            n,
            parseval,
            direct,
            fft_bins,
            fft,
            u_re,
            u_im,
            u_sparse,
        }
    }

    /// N.
    pub fn samples(&self) -> usize {
        self.n
    }

    /// `(V1²_K, V2²_K)` of `samples` (length N). `scratch` is reused
    /// between calls (FFT buffers).
    #[inline]
    pub fn raw(
        &self,
        samples: &[f64],
        scratch: &mut Vec<num_complex::Complex64>,
    ) -> crate::formalism::estimator::Pair {
        let n = self.n;
        let samples = &samples[..n];
        let p = dot(samples, samples);
        let (sr, si) = match &self.u_sparse {
            Some(entries) => entries.iter().fold((0.0, 0.0), |(a, b), &(i, ur, ui)| {
                (a + samples[i] * ur, b + samples[i] * ui)
            }),
            None => (dot(samples, &self.u_re), dot(samples, &self.u_im)),
        };
        let mut v1 = self.parseval * n as f64 * p;
        for (w, c, s) in &self.direct {
            let re = dot(samples, c);
            let im = s.as_ref().map_or(0.0, |s| dot(samples, s));
            v1 += w * (re * re + im * im);
        }
        if let Some(fft) = &self.fft {
            scratch.clear();
            scratch.extend(samples.iter().map(|&x| num_complex::Complex64::new(x, 0.0)));
            fft.process(scratch);
            for &(k, w) in &self.fft_bins {
                v1 += w * scratch[k].norm_sqr();
            }
        }
        crate::formalism::estimator::Pair {
            v1_sq: v1,
            v2_sq: sr * sr + si * si,
        }
    }
}

/// `Σ a_i b_i` with sixteen partial sums (breaks the addition latency
/// chain so that the loop vectorizes; the order is fixed, so results are
/// reproducible).
#[inline]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    const L: usize = 16;
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut acc = [0.0f64; L];
    let (ca, cb) = (a.chunks_exact(L), b.chunks_exact(L));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for j in 0..L {
            acc[j] += x[j] * y[j];
        }
    }
    let tail: f64 = ra.iter().zip(rb).map(|(x, y)| x * y).sum();
    let mut w = L;
    while w > 1 {
        w /= 2;
        for j in 0..w {
            acc[j] += acc[j + w];
        }
    }
    acc[0] + tail
}

/// A batch of noisy sampled interferograms: mean samples, noise, window.
#[derive(Debug, Clone)]
pub struct NoisySpec {
    /// m_i, photons per sample.
    pub modulated: Vec<f64>,
    /// c_i, photons per sample (removed without noise).
    pub continuum: Vec<f64>,
    /// The noise.
    pub noise: crate::noise::NoiseModel,
    /// The window of Fourier bins.
    pub bins: Vec<usize>,
}

/// Raw-estimator statistics of a noisy Monte Carlo.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NoisyRun {
    /// Statistics of V1²_raw over the trials.
    pub v1_sq: RunningStats,
    /// Statistics of V2²_raw.
    pub v2_sq: RunningStats,
}

/// Trials per work unit of [`simulate_noisy`] (fixed, so that the answer does
/// not depend on the thread count).
pub const TRIALS_PER_UNIT: u64 = 8192;

/// Largest total size of the alias tables of [`PoissonSampler`] for one
/// simulation (entries); beyond it the samples use `rand_distr::Poisson`.
pub(crate) const ALIAS_BUDGET: usize = 1 << 20;

/// Poisson counts of one fixed mean λ.
///
/// Two exact samplers, both from rand_distr: `Alias` draws from the
/// probability table of the Poisson law by Walker's alias method
/// (`rand_distr::WeightedAliasIndex`; two uniform draws per count, about
/// five times faster than `rand_distr::Poisson` at λ ≈ 10–20), the table
/// covering `λ ± (12√λ + 20)` so the mass left out is below 1e−32 for
/// any λ in 1e−4 … 1e6 (checked with scipy.stats.poisson);
/// `Direct` uses `rand_distr::Poisson` (for very large λ or long scans).
/// The choice depends only on the inputs, never on the thread count.
///
/// Internal to [`simulate_noisy`]; public only for `tests/montecarlo_noise.rs`.
#[doc(hidden)]
#[derive(Debug, Clone)]
#[non_exhaustive]
pub enum PoissonSampler {
    /// λ = 0: always 0.
    Zero,
    /// Alias table over counts `offset …`.
    Alias {
        /// The table.
        table: rand_distr::WeightedAliasIndex<f64>,
        /// The count of table entry 0.
        offset: f64,
    },
    /// rand_distr's Poisson sampler.
    Direct(rand_distr::Poisson<f64>),
}

impl PoissonSampler {
    /// Table entries an alias sampler of mean `lambda` needs.
    pub(crate) fn table_len(lambda: f64) -> usize {
        let (lo, hi) = Self::support(lambda);
        (hi - lo + 1.0) as usize
    }

    /// The counts `lo ..= hi` an alias table of mean `lambda` covers:
    /// `λ ± (12√λ + 20)`, clipped at 0 (public for the test of the mass it
    /// leaves out, `tests/montecarlo_noise.rs`).
    #[doc(hidden)]
    pub fn support(lambda: f64) -> (f64, f64) {
        let w = 12.0 * lambda.sqrt() + 20.0;
        ((lambda - w).floor().max(0.0), (lambda + w).ceil())
    }

    /// A sampler of mean `lambda` (finite, ≥ 0); `alias` selects the table.
    pub fn new(lambda: f64, alias: bool) -> crate::Result<PoissonSampler> {
        crate::error::non_negative("photons", lambda)?;
        if lambda == 0.0 {
            return Ok(PoissonSampler::Zero);
        }
        let bad = |e: String| crate::Error::Invalid {
            param: "photons",
            reason: format!("Poisson sampler of mean {lambda}: {e}"),
        };
        if alias {
            let (lo, hi) = Self::support(lambda);
            // Weights relative to the mode, by the ratio p(k+1)/p(k) = λ/(k+1).
            let mode = lambda.floor().clamp(lo, hi);
            let len = (hi - lo + 1.0) as usize;
            let im = (mode - lo) as usize;
            let mut w = vec![0.0; len];
            w[im] = 1.0;
            for i in im + 1..len {
                w[i] = w[i - 1] * lambda / (lo + i as f64);
            }
            for i in (0..im).rev() {
                w[i] = w[i + 1] * (lo + i as f64 + 1.0) / lambda;
            }
            let table = rand_distr::WeightedAliasIndex::new(w).map_err(|e| bad(e.to_string()))?;
            Ok(PoissonSampler::Alias { table, offset: lo })
        } else {
            rand_distr::Poisson::new(lambda)
                .map(PoissonSampler::Direct)
                .map_err(|e| bad(e.to_string()))
        }
    }

    /// One count.
    #[inline]
    pub fn sample(&self, rng: &mut Rng) -> f64 {
        use rand_distr::Distribution;
        match self {
            PoissonSampler::Zero => 0.0,
            PoissonSampler::Alias { table, offset } => {
                offset + table.sample(rng.rand_core()) as f64
            }
            PoissonSampler::Direct(d) => d.sample(rng.rand_core()),
        }
    }
}

/// Per-sample noise generator of a [`NoisySpec`] (rand_distr draws).
pub(crate) struct SampleNoise {
    sigma: f64,
    poisson: Vec<PoissonSampler>,
    offset: Vec<f64>,
    modulated: Vec<f64>,
}

impl SampleNoise {
    pub(crate) fn new(spec: &NoisySpec) -> crate::Result<SampleNoise> {
        let n = spec.modulated.len();
        if n < 2 || spec.continuum.len() != n {
            return Err(crate::Error::Invalid {
                param: "samples",
                reason: format!(
                    "{} modulated and {} continuum values (need >= 2, equal)",
                    n,
                    spec.continuum.len()
                ),
            });
        }
        if let Some(&k) = spec.bins.iter().find(|&&k| k >= n) {
            return Err(crate::Error::OutOfRange {
                param: "bins",
                value: k as f64,
                accepted: format!("0 to {}", n - 1),
            });
        }
        let mut poisson = Vec::with_capacity(n);
        if spec.noise.photon {
            let means: Vec<f64> = spec
                .modulated
                .iter()
                .zip(&spec.continuum)
                .map(|(&m, &c)| m + c)
                .collect();
            if let Some(&bad) = means.iter().find(|v| !(v.is_finite() && **v >= 0.0)) {
                return Err(crate::Error::OutOfRange {
                    param: "photons",
                    value: bad,
                    accepted: "mean counts c + m >= 0 in every sample (|visibility| <= 1)".into(),
                });
            }
            let table: usize = means.iter().map(|&l| PoissonSampler::table_len(l)).sum();
            let alias = table <= ALIAS_BUDGET;
            for &l in &means {
                poisson.push(PoissonSampler::new(l, alias)?);
            }
        }
        Ok(SampleNoise {
            sigma: spec.noise.read_noise,
            poisson,
            offset: spec.continuum.clone(),
            modulated: spec.modulated.clone(),
        })
    }

    /// Fills `out` with one noisy interferogram M_i.
    #[inline]
    pub(crate) fn draw(&self, rng: &mut Rng, out: &mut [f64]) {
        if self.poisson.is_empty() {
            for (o, &m) in out.iter_mut().zip(&self.modulated) {
                let z: f64 = rng.standard_normal();
                *o = m + self.sigma * z;
            }
        } else {
            for ((o, p), &c) in out.iter_mut().zip(&self.poisson).zip(&self.offset) {
                *o = p.sample(rng) - c;
            }
            if self.sigma > 0.0 {
                for o in out.iter_mut() {
                    let z: f64 = rng.standard_normal();
                    *o += self.sigma * z;
                }
            }
        }
    }
}

fn unit_trials(trials: u64, unit: u64) -> u64 {
    (trials - unit * TRIALS_PER_UNIT).min(TRIALS_PER_UNIT)
}

/// Most trials of [`simulate_noisy`]: 2^40 (the simulator's own bound,
/// `simulator::report::MAX_TRIALS`), days of work on any machine.
pub const MAX_NOISY_TRIALS: u64 = 1 << 40;

/// Simulates `trials` noisy interferograms of `spec` and accumulates both raw
/// estimators (seeded per unit of [`TRIALS_PER_UNIT`] trials from
/// (`seed`, unit); bit-identical for any `threads`). `progress(done)` is
/// called with the number of trials just finished, every few milliseconds
/// of work ([`Steps`]). Refuses `trials` outside 1 to [`MAX_NOISY_TRIALS`].
///
/// # Example
///
/// ```
/// use v2ref_core::prelude::*;
/// use v2ref_core::formalism::estimator::{all_bins, positive_bins};
/// // 20 000 noisy interferograms; same seed, same bits, any thread count.
/// let spec = NoisySpec {
///     modulated: vec![5.0, 3.0, -1.0, -4.0],
///     continuum: vec![10.0; 4],
///     noise: NoiseModel::new(1.0, true)?,
///     bins: all_bins(4)?,
/// };
/// let one = simulate_noisy(&spec, 20_000, 7, 1, &|_| {})?;
/// let two = simulate_noisy(&spec, 20_000, 7, 2, &|_| {})?;
/// assert_eq!(one, two);
/// // The mean of V1²_raw is its signal plus the exact bias, within 5 standard errors.
/// let s = appendix_stats(&spec.modulated, &spec.continuum, &spec.noise, Formula::Exact)?;
/// let expected = s.signal_v1_sq + s.bias_v1_sq;
/// assert!((one.v1_sq.mean - expected).abs() < 5.0 * one.v1_sq.stderr_mean());
/// # Ok::<(), v2ref_core::Error>(())
/// ```
pub fn simulate_noisy(
    spec: &NoisySpec,
    trials: u64,
    seed: u64,
    threads: usize,
    progress: &(dyn Fn(u64) + Sync),
) -> crate::Result<NoisyRun> {
    let units = NoisyUnits::new(spec, trials)?;
    let mut total = NoisyRun::default();
    let work = |u, rng: &mut Rng| units.unit(u, rng, progress);
    fold_units(seed, 0..units.units(), threads, work, |p: NoisyRun| {
        total.v1_sq.merge(&p.v1_sq);
        total.v2_sq.merge(&p.v2_sq);
    })?;
    Ok(total)
}

/// The work units of [`simulate_noisy`] one by one, for a run split over
/// processes (each unit drawn from `unit_rng(seed, u)`; the results
/// merged in unit order give [`simulate_noisy`]'s bits).
pub struct NoisyUnits {
    noise: SampleNoise,
    est: WindowedEstimators,
    trials: u64,
}

impl NoisyUnits {
    /// The units of `trials` interferograms of `spec`; refuses `trials`
    /// outside 1 to [`MAX_NOISY_TRIALS`].
    pub fn new(spec: &NoisySpec, trials: u64) -> crate::Result<NoisyUnits> {
        if !(1..=MAX_NOISY_TRIALS).contains(&trials) {
            return Err(crate::Error::OutOfRange {
                param: "trials",
                value: trials as f64,
                accepted: format!("1 to {MAX_NOISY_TRIALS}"),
            });
        }
        Ok(NoisyUnits {
            noise: SampleNoise::new(spec)?,
            est: WindowedEstimators::new(spec.modulated.len(), &spec.bins),
            trials,
        })
    }

    /// Number of units ([`TRIALS_PER_UNIT`] trials each, the last fewer).
    pub fn units(&self) -> u64 {
        self.trials.div_ceil(TRIALS_PER_UNIT)
    }

    /// Unit `u`'s raw statistics; `rng` must be `unit_rng(seed, u)`.
    pub fn unit(
        &self,
        u: u64,
        rng: &mut Rng,
        progress: &(dyn Fn(u64) + Sync),
    ) -> crate::Result<NoisyRun> {
        let n = self.est.samples();
        let mut run = NoisyRun::default();
        let mut buf = vec![0.0; n];
        let mut scratch = Vec::new();
        let mut steps = Steps::new(progress, n);
        for _ in 0..unit_trials(self.trials, u) {
            self.noise.draw(rng, &mut buf);
            let r = self.est.raw(&buf, &mut scratch);
            run.v1_sq.push(r.v1_sq);
            run.v2_sq.push(r.v2_sq);
            steps.step()?;
        }
        steps.finish()?;
        Ok(run)
    }
}

/// The noise draws of [`simulate_noisy`] alone (same generators, same
/// samples, no estimator): the baseline of the throughput benchmark. Returns
/// the sum of all samples so that nothing is optimized away. Public only
/// for `benches/montecarlo.rs`.
#[doc(hidden)]
pub fn draw_noise_only(
    spec: &NoisySpec,
    trials: u64,
    seed: u64,
    threads: usize,
) -> crate::Result<f64> {
    let noise = SampleNoise::new(spec)?;
    let units = trials.div_ceil(TRIALS_PER_UNIT);
    let n = spec.modulated.len();
    let parts = run_units(seed, units, threads, |u, rng| {
        let mut buf = vec![0.0; n];
        let mut acc = 0.0;
        for _ in 0..unit_trials(trials, u) {
            noise.draw(rng, &mut buf);
            acc += buf[0];
        }
        acc
    })?;
    Ok(parts.iter().sum())
}

/// Monte Carlo of one scalar per-sample variable `M = m + e` under `noise`
/// (continuum `c`): accumulates M, M², M³, M⁴ as sample means (tests of the
/// closed-form moments). Returns one [`RunningStats`] per power 1 … 4.
pub fn sample_moments(
    m: f64,
    c: f64,
    noise: &crate::noise::NoiseModel,
    trials: u64,
    seed: u64,
    threads: usize,
) -> crate::Result<[RunningStats; 4]> {
    let spec = NoisySpec {
        modulated: vec![m, 0.0],
        continuum: vec![c, c],
        noise: *noise,
        bins: vec![0],
    };
    let sn = SampleNoise::new(&spec)?;
    let units = trials.div_ceil(TRIALS_PER_UNIT);
    let mut total = [RunningStats::default(); 4];
    let work = |u, rng: &mut Rng| {
        let mut acc = [RunningStats::default(); 4];
        let mut buf = [0.0; 2];
        for _ in 0..unit_trials(trials, u) {
            sn.draw(rng, &mut buf);
            let x = buf[0];
            let mut p = 1.0;
            for a in acc.iter_mut() {
                p *= x;
                a.push(p);
            }
        }
        Ok(acc)
    };
    fold_units(seed, 0..units, threads, work, |p: [RunningStats; 4]| {
        for (t, a) in total.iter_mut().zip(&p) {
            t.merge(a);
        }
    })?;
    Ok(total)
}
