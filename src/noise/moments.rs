//! Additive noise on the modulated samples and the closed-form statistics of
//! the two estimators built from all N Fourier bins (paper, Appendix
//! "Estimator signal-to-noise ratio").
//!
//! # Per-sample model
//!
//! Sample i reads `M_i = m_i + e_i`, with `m_i` the noise-free modulated
//! signal (photons per sample) and `e_i` independent between samples:
//!
//! - detector noise: Gaussian, variance `σ_det²` (photons²);
//! - photon noise: the total count `I_i` is Poisson with mean
//!   `n_i = c_i + m_i`, the continuum `c_i` is removed without noise, so
//!   `M_i = I_i − c_i` and `e_i = I_i − n_i`;
//! - both: the sum of the two, independent.
//!
//! Everything follows from the cumulants of `e_i` ([`Cumulants`]):
//! `κ2 = σ_det² + n_i`, `κ_r = n_i` for r ≥ 3 (a Poisson variable has all its
//! cumulants equal to its mean; a Gaussian one has none beyond the second).
//! Moments of any order come from the cumulants by the standard recursion
//! `μ'_r = Σ_{k=1}^{r} C(r−1, k−1) κ_k μ'_{r−k}` ([`raw_moment`]).
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
//!
//! # The worked examples: which 128-sample interferogram
//!
//! The Appendix gives SNR_1 = 7.63 and SNR_2 = 2.48 (detector noise
//! σ_det = 0.2 n) and 1.33 / 0.54 (photon noise, n = 10) for 128 samples at
//! δx = 0.5 µm in a flat 2.0–2.4 µm band with `m_0 = n V`, V = 1. SNR_2
//! depends on m_0 only; SNR_1 on `Σ m_i²/n²` and, for photon noise, on the
//! distribution of the m_i. With the paper's (published) formulas and
//! `c = n`, `n_i = c + m_i`:
//!
//! | interferogram | Σm²/n² | SNR1 det | SNR2 det | SNR1 phot | SNR2 phot |
//! |---|---|---|---|---|---|
//! | centred scan, sampling detector (**project**) | 11.566 | 7.693 | 2.475 | 1.350 | 0.539 |
//! | centred scan, integrating detector, m_0 = c·∫W sinc | 9.698 | 6.925 | 2.262 | 1.150 | 0.481 |
//! | centred scan, integrating detector rescaled to m_0 = n | 11.568 | 7.694 | 2.475 | 1.350 | 0.539 |
//! | scan starting at zero OPD, sampling detector | 6.383 | 5.336 | 2.475 | 0.775 | 0.539 |
//! | scan starting at zero OPD, integrating detector | 5.351 | 4.756 | 2.262 | 0.656 | 0.481 |
//! | what 7.63 and 1.33 both need | ≈ 11.41 | 7.63 | | 1.33 | |
//!
//! The project uses the first row: the scan is centred on the white-light
//! fringe (as the Appendix's V2 requires sample 0 on it, and as the
//! sampled-signal section's window Π(x/Δx) describes), the detector samples
//! (the paper states it neglects integration, Section "Sampled signals"),
//! W is flat in wavenumber, and the continuum equals n (so `m_0 = n` for
//! V = 1 and `n_0 = 2n`, which is what SNR_2 = 0.54 requires). The
//! one-sided scan halves the fringe power and cannot give 7.63; the
//! integrating detector lowers m_0 below n, against the stated `m_0 = nV`.
//! The residual 0.8 % in SNR_1 is a fringe power 1.4 % lower than ours in
//! the paper's interferogram (Σm²/n² ≈ 11.41 reproduces both 7.63 and 1.33
//! at once, i.e. one common cause, e.g. a band ≈ 1.4 % wider in
//! wavenumber). [`worked_example`] computes these numbers from
//! [`crate::formalism::interferogram::Interferogram::synthesize`].

use crate::error::{self, Error, Result};
use crate::formalism::interferogram::{Interferogram, Sampling};
use crate::formalism::observation::{Frequency, Observation};
use crate::formalism::source::Source;
use crate::formalism::spectrum::{Band, Spectrum};
use serde::Serialize;

/// Which version of a formula: as printed in the paper, or derived and
/// confirmed by Monte Carlo.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Formula {
    /// As printed in the paper's Appendix.
    Published,
    /// Derived from the cumulants of the noise (confirmed by Monte Carlo).
    Exact,
}

/// The noise on the modulated samples (`CONVENTIONS.md`, Noise).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct NoiseModel {
    /// Detector (read) noise standard deviation σ_det, photons per sample (≥ 0).
    pub read_noise: f64,
    /// Whether the counts carry Poisson photon noise.
    pub photon: bool,
}

impl NoiseModel {
    /// Read noise `read_noise` (photons, ≥ 0) and, if `photon`, Poisson
    /// photon noise.
    pub fn new(read_noise: f64, photon: bool) -> Result<NoiseModel> {
        error::non_negative("read-noise", read_noise)?;
        Ok(NoiseModel { read_noise, photon })
    }

    /// Detector noise only.
    pub fn detector(read_noise: f64) -> Result<NoiseModel> {
        Self::new(read_noise, false)
    }

    /// Photon noise only.
    pub fn photon() -> NoiseModel {
        NoiseModel {
            read_noise: 0.0,
            photon: true,
        }
    }

    /// Cumulants of the noise `e = M − m` of a sample whose mean total count
    /// is `mean_count` (`n_i = c_i + m_i`, photons; used only with photon
    /// noise).
    pub fn cumulants(&self, mean_count: f64) -> Cumulants {
        let p = if self.photon { mean_count } else { 0.0 };
        Cumulants {
            k2: self.read_noise * self.read_noise + p,
            k3: p,
            k4: p,
        }
    }
}

/// Cumulants κ2, κ3, κ4 of a zero-mean per-sample noise (photons², ³, ⁴).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Cumulants {
    /// κ2, the variance.
    pub k2: f64,
    /// κ3 (third central moment).
    pub k3: f64,
    /// κ4 (fourth cumulant: μ4 − 3κ2²).
    pub k4: f64,
}

/// All cumulants κ_1 … κ_order of `M = m + e` for the noise model: κ1 = m,
/// κ2 = σ_det² + n, κ_r = n for r ≥ 3 (n counted only with photon noise).
pub fn cumulants_of_sample(noise: &NoiseModel, m: f64, mean_count: f64, order: usize) -> Vec<f64> {
    let c = noise.cumulants(mean_count);
    (1..=order)
        .map(|r| match r {
            1 => m,
            2 => c.k2,
            _ => c.k3,
        })
        .collect()
}

/// Raw moments `⟨M^r⟩`, r = 0 … `order`, from the cumulants `κ_1 … κ_order`
/// (`cumulants[r−1] = κ_r`), by `μ'_r = Σ_{k=1}^{r} C(r−1, k−1) κ_k μ'_{r−k}`.
pub fn raw_moments_from_cumulants(cumulants: &[f64]) -> Vec<f64> {
    let order = cumulants.len();
    let mut mu = vec![1.0; order + 1];
    for r in 1..=order {
        let mut binom = 1.0; // C(r−1, k−1) for k = 1
        let mut acc = 0.0;
        for k in 1..=r {
            acc += binom * cumulants[k - 1] * mu[r - k];
            binom *= (r - k) as f64 / k as f64;
        }
        mu[r] = acc;
    }
    mu
}

/// `⟨M^r⟩` for one sample of mean `m` and mean total count `mean_count`.
pub fn raw_moment(noise: &NoiseModel, m: f64, mean_count: f64, r: usize) -> f64 {
    raw_moments_from_cumulants(&cumulants_of_sample(noise, m, mean_count, r.max(1)))[r]
}

/// Raw and central moments of one sample up to order 4.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Moments {
    /// `⟨M^r⟩`, r = 0 … 4.
    pub raw: [f64; 5],
    /// `⟨(M − m)^r⟩`, r = 0 … 4.
    pub central: [f64; 5],
}

/// Raw and central moments up to order 4 of `M = m + e` (closed forms:
/// `⟨M²⟩ = m² + κ2`, `⟨M³⟩ = m³ + 3mκ2 + κ3`,
/// `⟨M⁴⟩ = m⁴ + 6m²κ2 + 4mκ3 + κ4 + 3κ2²`; central `κ2, κ3, κ4 + 3κ2²`).
pub fn moments(noise: &NoiseModel, m: f64, mean_count: f64) -> Moments {
    let c = noise.cumulants(mean_count);
    let raw = [
        1.0,
        m,
        m * m + c.k2,
        m.powi(3) + 3.0 * m * c.k2 + c.k3,
        m.powi(4) + 6.0 * m * m * c.k2 + 4.0 * m * c.k3 + c.k4 + 3.0 * c.k2 * c.k2,
    ];
    let central = [1.0, 0.0, c.k2, c.k3, c.k4 + 3.0 * c.k2 * c.k2];
    Moments { raw, central }
}

/// `var(M²) = ⟨M⁴⟩ − ⟨M²⟩² = 4m²κ2 + 4mκ3 + κ4 + 2κ2²` (exact).
pub fn var_m2(noise: &NoiseModel, m: f64, mean_count: f64) -> f64 {
    let c = noise.cumulants(mean_count);
    4.0 * m * m * c.k2 + 4.0 * m * c.k3 + c.k4 + 2.0 * c.k2 * c.k2
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
    if noise.photon {
        if let Some(bad) = counts.iter().find(|&&v| v < 0.0 || v.is_nan()) {
            return Err(Error::OutOfRange {
                param: "photons",
                value: *bad,
                accepted: "mean counts c + m >= 0 in every sample (|visibility| <= 1)".into(),
            });
        }
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

/// The interferogram of the Appendix's worked examples (or a variant of it).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ExampleSetup {
    /// N.
    pub samples: usize,
    /// δx, µm.
    pub dx_um: f64,
    /// Integrating detector.
    pub integrating: bool,
    /// Scan starting at zero OPD (`x_i = i δx`) instead of centred.
    pub zero_start: bool,
    /// Continuum photons per sample, n (m_0 = n V).
    pub photons: f64,
    /// V.
    pub visibility: f64,
}

impl ExampleSetup {
    /// The project's reading of the Appendix: 128 samples, δx = 0.5 µm,
    /// centred scan, sampling detector, n = 10, V = 1.
    pub fn appendix() -> ExampleSetup {
        ExampleSetup {
            samples: 128,
            dx_um: 0.5,
            integrating: false,
            zero_start: false,
            photons: 10.0,
            visibility: 1.0,
        }
    }
}

/// The four SNRs of the Appendix's worked examples for one setup.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WorkedExample {
    /// The setup.
    pub setup: ExampleSetup,
    /// Σ m_i² / n².
    pub sum_m2_over_n2: f64,
    /// Detector noise σ_det = 0.2 n: SNR_1, SNR_2 (no window factor).
    pub detector: (f64, f64),
    /// Photon noise only: SNR_1, SNR_2 (no window factor).
    pub photon: (f64, f64),
}

/// The K-band point-source observation of the worked examples: flat
/// 2.0–2.4 µm band, unresolved source, no dispersion.
pub fn example_observation() -> Observation {
    // Constants of the paper: a valid band and a zero frequency.
    let spectrum = Spectrum::flat(Band::new(2.2, 0.4).expect("the K band is valid"));
    Observation::new(
        spectrum,
        Source::Point,
        Frequency::SpatialFreqCpas(0.0),
        crate::formalism::phase::SpectralPhase::zero(),
    )
    .expect("zero spatial frequency is valid")
}

/// Samples m_i, c_i of a setup (synthesized by
/// [`Interferogram::synthesize`]; the zero-start variant shifts the OPDs by
/// `+N/2 δx` for the negative half, i.e. `x_i = i δx`).
pub fn example_interferogram(setup: &ExampleSetup) -> Result<Interferogram> {
    let obs = example_observation();
    let sampling = Sampling::new(setup.samples, setup.dx_um, setup.integrating)?;
    let perturbation: Option<Vec<f64>> = setup.zero_start.then(|| {
        (0..setup.samples)
            .map(|i| i as f64 * setup.dx_um - sampling.opd_um(i))
            .collect()
    });
    let mut ifg =
        Interferogram::synthesize(&obs, &sampling, setup.photons, perturbation.as_deref())?;
    for m in &mut ifg.modulated {
        *m *= setup.visibility;
    }
    Ok(ifg)
}

/// The four SNRs of the worked examples in `formula` (detector noise
/// σ_det = 0.2 n without photon noise; photon noise alone).
pub fn worked_example(setup: &ExampleSetup, formula: Formula) -> Result<WorkedExample> {
    let ifg = example_interferogram(setup)?;
    let det = appendix_stats(
        &ifg.modulated,
        &ifg.continuum,
        &NoiseModel::detector(0.2 * setup.photons)?,
        formula,
    )?;
    let phot = appendix_stats(
        &ifg.modulated,
        &ifg.continuum,
        &NoiseModel::photon(),
        formula,
    )?;
    Ok(WorkedExample {
        setup: *setup,
        sum_m2_over_n2: det.sum_m2 / (setup.photons * setup.photons),
        detector: (det.snr1, det.snr2),
        photon: (phot.snr1, phot.snr2),
    })
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
    m.extend(std::iter::repeat(0.0).take(extra));
    cc.extend(std::iter::repeat(c).take(extra));
    let s = appendix_stats(&m, &cc, noise, formula)?;
    Ok((s.snr1, s.snr2))
}

/// The smallest total number of samples at which SNR_1 ≤ SNR_2 when the
/// fringe packet of `modulated` is read with more and more empty samples
/// (bisection on the number of extra samples; None if not reached below
/// 2^26 samples).
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
    if !below(limit)? {
        return Ok(None);
    }
    let (mut lo, mut hi) = (0usize, limit);
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
    crate::formalism::estimator::noise_bias(&per_sample, bins)
}

/// The noise-free interferogram of `obs` with `photons` continuum photons
/// per sample and its modulated part scaled by `visibility` (so that an
/// unresolved source has `m_0 = n V`, the Appendix's convention).
pub fn scaled_interferogram(
    obs: &Observation,
    sampling: &Sampling,
    photons: f64,
    visibility: f64,
) -> Result<Interferogram> {
    error::in_range("visibility", visibility, 0.0, 1.0)?;
    let mut ifg = Interferogram::synthesize(obs, sampling, photons, None)?;
    for m in &mut ifg.modulated {
        *m *= visibility;
    }
    Ok(ifg)
}
