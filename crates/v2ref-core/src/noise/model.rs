//! The noise model of the Appendix (*Estimator signal-to-noise ratio*):
//! additive noise on the modulated samples, its cumulants, and the raw and
//! central moments of one noisy sample `M_i = m_i + e_i`.
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
//! The estimators' closed forms built on these moments are in
//! [`crate::noise::appendix`].

use crate::error::Result;
use serde::Serialize;

/// The noise on the modulated samples (`docs/conventions.md`, noise).
///
/// # Example
///
/// ```
/// use v2ref_core::prelude::*;
/// use v2ref_core::formalism::estimator::{all_bins, positive_bins};
/// // Read noise 2 photons plus photon noise: the variance of a sample of mean
/// // count 10 is 4 + 10.
/// let noise = NoiseModel::new(2.0, true)?;
/// let c = noise.cumulants(10.0)?;
/// assert!((c.k2 - 14.0).abs() < 1e-12);
/// // A negative read noise is refused, naming the parameter.
/// assert_eq!(NoiseModel::new(-1.0, false).unwrap_err().param(), Some("read_noise"));
/// # Ok::<(), v2ref_core::Error>(())
/// ```
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
        crate::bounds::non_negative_at_most("read_noise", read_noise, crate::bounds::PHOTONS_MAX)?;
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
    /// noise, where it must be ≥ 0 and finite: a count's variance is not
    /// negative).
    pub fn cumulants(&self, mean_count: f64) -> Result<Cumulants> {
        if self.photon {
            // (Beyond the library's photon bound, κ2² overflows f64.)
            crate::bounds::non_negative_at_most(
                "mean_count",
                mean_count,
                crate::bounds::MEAN_COUNT_MAX,
            )?;
        }
        Ok(self.cumulants_at(mean_count))
    }

    /// [`NoiseModel::cumulants`] of a count the caller has checked.
    pub(crate) fn cumulants_at(&self, mean_count: f64) -> Cumulants {
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
    let c = noise.cumulants_at(mean_count);
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
/// `m` must be finite, `mean_count` as in [`NoiseModel::cumulants`].
pub fn moments(noise: &NoiseModel, m: f64, mean_count: f64) -> Result<Moments> {
    let max = crate::bounds::PHOTONS_MAX;
    crate::bounds::check("m", m, -max, max)?;
    Ok(moments_of(m, noise.cumulants(mean_count)?))
}

/// [`moments`] from the sample's cumulants.
pub(crate) fn moments_of(m: f64, c: Cumulants) -> Moments {
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
    let c = noise.cumulants_at(mean_count);
    4.0 * m * m * c.k2 + 4.0 * m * c.k3 + c.k4 + 2.0 * c.k2 * c.k2
}
