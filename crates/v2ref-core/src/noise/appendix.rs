//! The Appendix's closed forms (*Estimator signal-to-noise ratio*): the
//! noise bias and the variances of V1² and V2² built from all N Fourier
//! bins, as printed (`published`) and exact, the SNRs, the paper's window
//! factor, the crossover of SNR_1 and SNR_2, and the ABCD (Colavita)
//! variances. The noise model and the per-sample moments are in
//! `noise::model`; the worked examples' interferogram in
//! `noise::example`.
//!
//! # Estimators over all bins
//!
//! With `B_k = Σ_i M_i e^{−2πi ik/N}` and all N bins, Parseval gives
//! `V1²_raw = Σ_k |B_k|² = N Σ_i M_i²` and `V2²_raw = |Σ_k B_k|² = N² M_0²`,
//! so that (samples independent)
//!
//! - `⟨V1²_raw⟩ = N Σ (m_i² + κ2_i)`, `var V1²_raw = N² Σ var(M_i²)`;
//! - `⟨V2²_raw⟩ = N² (m_0² + κ2_0)`, `var V2²_raw = N⁴ var(M_0²)`;
//! - `var(M²) = 4m²κ2 + 4mκ3 + κ4 + 2κ2²`.
//!
//! The `exact` bias to subtract is therefore `N Σ κ2_i` and `N² κ2_0`: with
//! photon noise it involves `n_i`, the mean total count.
//!
//! # What the paper prints (`published`)
//!
//! - Detector noise: `⟨M⁴⟩ = m⁴ + 6m²σ² + 3σ⁴`, `⟨M²⟩ = m² + σ²` and the
//!   variances `2N²σ²[2Σm² + Nσ²]`, `2N⁴σ²[2m_0² + σ²]` — all exact.
//! - Photon noise: `⟨M⁴⟩ = n⁴ + 6n³ + 7n² + n`, `⟨M²⟩ = n² + n`: these are
//!   the raw moments of the Poisson count I itself (mean n), not of
//!   `M = I − c`. The variances built on them,
//!   `N² Σ n_i(4n_i² + 6n_i + 1)` and `N⁴ n_0(4n_0² + 6n_0 + 1)`, are the
//!   variances of `I²`, not of `M²`. Exact: `var(M²) = 4m²n + 4mn + 2n² + n`.
//! - Photon bias: the paper subtracts `N Σ m_i` and `N² m_0`; the noise
//!   power is `N Σ n_i` and `N² n_0`.
//! - Both noises: the paper adds the detector-only and photon-only
//!   variances; the exact `var(M²)` has the cross term `4σ_det² n` from
//!   `2κ2²` with `κ2 = σ_det² + n`.
//!
//! Each of these is confirmed by the Monte Carlo of `tests/noise_mc.rs`
//! (and the claims `appendix.*`).
//!
//! # SNR and the window factor
//!
//! `SNR_1 = ⟨V1²⟩ / √var V1²` and `SNR_2 = ⟨V2²⟩ / √var V2²` over all bins
//! ([`AppendixStats`]); the paper's white-noise gain of keeping only the
//! fringe-peak bins, `√(Δσ/Δσ_0)` with `Δσ = 1/δx`, is kept apart
//! ([`paper_window_factor`]); [`crate::noise::window_variance`] gives the exact
//! windowed variance instead.
//!
//! In the Appendix case (all bins, project interferogram) the exact photon
//! SNRs are 4.09 and 1.02 instead of the printed 1.35 (1.33) and 0.54: the
//! printed variance counts the continuum's photons as signal.
//!
//! # The window factor, exactly
//!
//! For detector noise σ_det = 0.2 n, the two-sided band window (the 6
//! positive band bins and their 6 mirror images, keeping the whole fringe)
//! divides var V1² by 1.20 and var V2² by 10.5, where the paper's factor
//! Δσ/Δσ_0 is 24: SNR gains 1.09 and 3.35 instead of √24 = 4.90
//! ([`crate::noise::window_variance`] explains why). The crossover of SNR_1 and
//! SNR_2 (the fringe packet read with more and more empty samples) comes at
//! N ≈ 6245 for detector noise, 5876 for exact photon noise, 968 with the
//! printed photon variances ([`crossover_samples`]).

use crate::error::{Error, Result};
use crate::noise::model::{var_m2, NoiseModel};
use serde::Serialize;

/// Which version of a formula: as printed in the paper, or derived and
/// confirmed by Monte Carlo.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
pub enum Formula {
    /// As printed in the paper's Appendix.
    Published,
    /// Derived from the cumulants of the noise (confirmed by Monte Carlo).
    Exact,
}

impl crate::words::Words for Formula {
    const WORDS: &'static [crate::words::Word<Self>] = &[
        crate::words::Word {
            word: "published",
            value: Formula::Published,
            help: "As printed in the paper's Appendix",
        },
        crate::words::Word {
            word: "exact",
            value: Formula::Exact,
            help: "Derived from the cumulants of the noise (confirmed by Monte Carlo)",
        },
    ];
}

/// The formulas as printed in the Appendix.
pub mod published {
    /// Detector noise: `⟨M⁴⟩ = m⁴ + 6m²σ² + 3σ⁴` (Appendix "Detector noise").
    pub fn gaussian_m4(m: f64, sigma: f64) -> f64 {
        m.powi(4) + 6.0 * m * m * sigma * sigma + 3.0 * sigma.powi(4)
    }
    /// Detector noise: `⟨M²⟩ = m² + σ²`.
    pub fn gaussian_m2(m: f64, sigma: f64) -> f64 {
        m * m + sigma * sigma
    }
    /// Photon noise as printed: `n⁴ + 6n³ + 7n² + n` (the fourth raw moment
    /// of a Poisson count of mean n; Appendix "Photon noise").
    pub fn photon_m4(n: f64) -> f64 {
        n.powi(4) + 6.0 * n.powi(3) + 7.0 * n * n + n
    }
    /// Photon noise as printed: `n² + n`.
    pub fn photon_m2(n: f64) -> f64 {
        n * n + n
    }
    /// Per-sample photon term of the printed variances, `n(4n² + 6n + 1)`.
    pub fn photon_var_term(n: f64) -> f64 {
        n * (4.0 * n * n + 6.0 * n + 1.0)
    }
    /// Per-sample detector term of the printed variances (divided by N²):
    /// `2σ²(2m² + σ²)` = `4m²σ² + 2σ⁴`.
    pub fn detector_var_term(m: f64, sigma: f64) -> f64 {
        2.0 * sigma * sigma * (2.0 * m * m + sigma * sigma)
    }
}

/// `var(M_i²)` per sample in the chosen formula: `exact` from the
/// cumulants; `published` the sum of the printed detector and photon terms.
pub fn sample_var_m2(formula: Formula, noise: &NoiseModel, m: f64, mean_count: f64) -> f64 {
    match formula {
        Formula::Exact => var_m2(noise, m, mean_count),
        Formula::Published => {
            published::detector_var_term(m, noise.read_noise)
                + if noise.photon {
                    published::photon_var_term(mean_count)
                } else {
                    0.0
                }
        }
    }
}

/// The noise power subtracted from sample i (the bias per sample, photons²):
/// `exact` κ2 = σ_det² + n_i; `published` σ_det² + m_i (Appendix,
/// "Sampled interferogram formalism").
pub fn sample_bias(formula: Formula, noise: &NoiseModel, m: f64, mean_count: f64) -> f64 {
    let s2 = noise.read_noise * noise.read_noise;
    match (formula, noise.photon) {
        (_, false) => s2,
        (Formula::Exact, true) => s2 + mean_count,
        (Formula::Published, true) => s2 + m,
    }
}

/// Closed-form statistics of V1² and V2² over all N bins (raw DFT units).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AppendixStats {
    /// Which formula.
    pub formula: Formula,
    /// N.
    pub samples: usize,
    /// Σ m_i², photons².
    pub sum_m2: f64,
    /// m_0, photons.
    pub m0: f64,
    /// Signal of V1²: `N Σ m_i²` (the expectation once the bias is removed).
    pub signal_v1_sq: f64,
    /// Signal of V2²: `N² m_0²`.
    pub signal_v2_sq: f64,
    /// Bias subtracted from V1²_raw: `N Σ b_i`.
    pub bias_v1_sq: f64,
    /// Bias subtracted from V2²_raw: `N² b_0`.
    pub bias_v2_sq: f64,
    /// Expectation of the bias-subtracted V1² (exact noise, this formula's
    /// bias): equals the signal when the bias is right.
    pub expectation_v1_sq: f64,
    /// Same for V2².
    pub expectation_v2_sq: f64,
    /// var V1²: `N² Σ var(M_i²)`.
    pub var_v1_sq: f64,
    /// var V2²: `N⁴ var(M_0²)`.
    pub var_v2_sq: f64,
    /// SNR_1 without the window factor: signal / √var.
    pub snr1: f64,
    /// SNR_2 without the window factor.
    pub snr2: f64,
}

/// The Appendix's closed forms for samples of mean `modulated[i]` = m_i and
/// continuum `continuum[i]` = c_i (photons), all N bins, in `formula`.
///
/// # Example
///
/// ```
/// use v2ref_core::prelude::*;
/// use v2ref_core::formalism::estimator::{all_bins, positive_bins};
/// // The exact bias makes both estimators unbiased: expectation = signal.
/// let (m, c) = (vec![5.0, 3.0, -1.0, -4.0], vec![10.0; 4]);
/// let s = appendix_stats(&m, &c, &NoiseModel::new(1.0, true)?, Formula::Exact)?;
/// assert!((s.expectation_v1_sq - s.signal_v1_sq).abs() < 1e-9 * s.signal_v1_sq);
/// assert!((s.expectation_v2_sq - s.signal_v2_sq).abs() < 1e-9 * s.signal_v2_sq);
/// # Ok::<(), v2ref_core::Error>(())
/// ```
pub fn appendix_stats(
    modulated: &[f64],
    continuum: &[f64],
    noise: &NoiseModel,
    formula: Formula,
) -> Result<AppendixStats> {
    let n = modulated.len();
    if n == 0 || continuum.len() != n {
        return Err(Error::Invalid {
            param: "samples",
            reason: format!("{} modulated and {} continuum values", n, continuum.len()),
        });
    }
    let counts: Vec<f64> = modulated
        .iter()
        .zip(continuum)
        .map(|(m, c)| m + c)
        .collect();
    let max = crate::bounds::MEAN_COUNT_MAX;
    let bad = |v: f64| v.is_nan() || v.abs() > max || (noise.photon && v < 0.0);
    if let Some(&bad) = counts.iter().find(|&&v| bad(v)) {
        return Err(Error::OutOfRange {
            param: "photons",
            value: bad,
            accepted: format!(
                "mean counts c + m within {max} in every sample, >= 0 with photon noise (|visibility| <= 1)"
            ),
        });
    }
    let nf = n as f64;
    let sum_m2: f64 = modulated.iter().map(|m| m * m).sum();
    let m0 = modulated[0];
    let bias_each: Vec<f64> = modulated
        .iter()
        .zip(&counts)
        .map(|(&m, &k)| sample_bias(formula, noise, m, k))
        .collect();
    let true_bias: f64 = modulated
        .iter()
        .zip(&counts)
        .map(|(&m, &k)| sample_bias(Formula::Exact, noise, m, k))
        .sum();
    let bias_v1 = nf * bias_each.iter().sum::<f64>();
    let bias_v2 = nf * nf * bias_each[0];
    let var1: f64 = modulated
        .iter()
        .zip(&counts)
        .map(|(&m, &k)| sample_var_m2(formula, noise, m, k))
        .sum::<f64>()
        * nf
        * nf;
    let var2 = nf.powi(4) * sample_var_m2(formula, noise, m0, counts[0]);
    let signal1 = nf * sum_m2;
    let signal2 = nf * nf * m0 * m0;
    let exp1 = signal1 + nf * true_bias - bias_v1;
    let exp2 = signal2 + nf * nf * sample_bias(Formula::Exact, noise, m0, counts[0]) - bias_v2;
    Ok(AppendixStats {
        formula,
        samples: n,
        sum_m2,
        m0,
        signal_v1_sq: signal1,
        signal_v2_sq: signal2,
        bias_v1_sq: bias_v1,
        bias_v2_sq: bias_v2,
        expectation_v1_sq: exp1,
        expectation_v2_sq: exp2,
        var_v1_sq: var1,
        var_v2_sq: var2,
        snr1: signal1 / var1.sqrt(),
        snr2: signal2 / var2.sqrt(),
    })
}

/// The paper's white-noise window factor `√(Δσ/Δσ_0)` with `Δσ = 1/δx`
/// and Δσ_0 the width of the band in wavenumber (Appendix, "Variance of
/// estimators with filtered samples").
pub fn paper_window_factor(dx_um: f64, band_width_per_um: f64) -> f64 {
    ((1.0 / dx_um) / band_width_per_um).sqrt()
}

/// SNR_1 and SNR_2 (all bins, no window factor) when the scan is extended
/// with `extra` samples that carry no fringe (m = 0, continuum c): the same
/// fringe packet read with more noise.
pub fn snr_with_extra_samples(
    modulated: &[f64],
    continuum: &[f64],
    noise: &NoiseModel,
    formula: Formula,
    extra: usize,
) -> Result<(f64, f64)> {
    let c = continuum.iter().sum::<f64>() / continuum.len().max(1) as f64;
    let mut m = modulated.to_vec();
    let mut cc = continuum.to_vec();
    m.extend(std::iter::repeat_n(0.0, extra));
    cc.extend(std::iter::repeat_n(c, extra));
    let s = appendix_stats(&m, &cc, noise, formula)?;
    Ok((s.snr1, s.snr2))
}

/// The smallest total number of samples at which SNR_1 ≤ SNR_2 when the
/// fringe packet of `modulated` is read with more and more empty samples
/// (doubling, then bisection, on the number of extra samples; None if not
/// reached with 2^26 extra samples).
pub fn crossover_samples(
    modulated: &[f64],
    continuum: &[f64],
    noise: &NoiseModel,
    formula: Formula,
) -> Result<Option<usize>> {
    let below = |extra: usize| -> Result<bool> {
        let (a, b) = snr_with_extra_samples(modulated, continuum, noise, formula, extra)?;
        Ok(a <= b)
    };
    let limit = 1usize << 26;
    if below(0)? {
        return Ok(Some(modulated.len()));
    }
    // Doubling to the first power of two past the crossover (each step costs
    // one evaluation on as many samples), then bisection in that octave:
    // `below(lo)` is false and `below(hi)` true throughout.
    let mut hi = 1usize;
    while !below(hi)? {
        if hi >= limit {
            return Ok(None);
        }
        hi *= 2;
    }
    let mut lo = hi / 2;
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if below(mid)? {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Ok(Some(modulated.len() + hi))
}

/// ABCD (four samples per fringe, Colavita 1999) with detector noise σ per
/// sample and `photons` = ⟨N⟩ total photons in the four samples: the exact
/// variance of the squared-modulus estimator `(A − C)² + (B − D)²` for a
/// sampling detector (fringe phase constant within a sample),
/// `2⟨N⟩²V²σ² + 16σ⁴` — the form the paper says Colavita's result needs.
pub fn abcd_detector_variance(photons: f64, visibility: f64, sigma: f64) -> f64 {
    2.0 * photons * photons * visibility * visibility * sigma * sigma
        + colavita_detector_variance(sigma)
}

/// The detector-noise variance of the ABCD estimator as Colavita (1999)
/// gives it, `16σ⁴` (no signal-noise cross term).
pub fn colavita_detector_variance(sigma: f64) -> f64 {
    16.0 * sigma.powi(4)
}

/// The noise bias of both raw estimators over the window `bins`, in
/// `formula`: [`crate::formalism::estimator::noise_bias`] of the per-sample noise
/// power of [`sample_bias`] (`N Σ b_i`, `N² b_0` for all bins).
pub fn window_bias(
    formula: Formula,
    noise: &NoiseModel,
    modulated: &[f64],
    continuum: &[f64],
    bins: &[usize],
) -> crate::formalism::estimator::Pair {
    let per_sample: Vec<f64> = modulated
        .iter()
        .zip(continuum)
        .map(|(&m, &c)| sample_bias(formula, noise, m, m + c))
        .collect();
    crate::formalism::estimator::noise_bias_sums(&per_sample, bins)
}
