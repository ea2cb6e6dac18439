//! Spectral phase, and the chromatic-dispersion phase of the paper
//! (Section "Effect of chromatic dispersion": `φ(σ) = ½ D (σ − σ0)²`).
//!
//! A [`SpectralPhase`] is a polynomial in `(σ − σ0)`, σ0 the centre of the
//! band in wavenumber. The paper's dispersion is the quadratic term; its
//! strength is given as the peak-to-peak phase P over the band, with
//! `P = ½ D (Δσ/2)²` (`docs/conventions.md`), so that φ runs from 0 at the band
//! centre to P at both edges.

use crate::error::Result;
use crate::formalism::spectrum::Spectrum;

/// `φ(σ) = Σ_k a_k (σ − σ0)^k`, radians, σ in µm⁻¹.
///
/// # Example
///
/// ```
/// use v2ref_core::prelude::*;
/// use v2ref_core::formalism::estimator::{all_bins, positive_bins};
/// // Quadratic dispersion of 1 rad peak to peak over K: φ is 0 at the band
/// // centre and 1 rad at both edges.
/// let k = Spectrum::flat(Band::k());
/// let phi = SpectralPhase::dispersion_peak_to_peak(&k, 1.0)?;
/// let (lo, hi) = k.support();
/// assert!(phi.at(0.5 * (lo + hi)).abs() < 1e-15);
/// assert!((phi.at(lo) - 1.0).abs() < 1e-12 && (phi.at(hi) - 1.0).abs() < 1e-12);
/// # Ok::<(), v2ref_core::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SpectralPhase {
    /// σ0, µm⁻¹.
    pub sigma0_per_um: f64,
    /// a_k, rad µm^k.
    pub coefficients: Vec<f64>,
}

impl SpectralPhase {
    /// No phase.
    pub fn zero() -> SpectralPhase {
        SpectralPhase::default()
    }

    /// The quadratic dispersion phase `½ D (σ − σ0)²` whose peak-to-peak
    /// value over the band of `spectrum` is `peak_to_peak_rad`:
    /// `D = 8 P / Δσ²`, σ0 and Δσ the centre and width of the band.
    pub fn dispersion_peak_to_peak(spectrum: &Spectrum, peak_to_peak_rad: f64) -> Result<Self> {
        let max = crate::bounds::DISPERSION_PP_MAX_RAD;
        crate::bounds::check("peak_to_peak_rad", peak_to_peak_rad, -max, max)?;
        let width = spectrum.width_per_um();
        let d = if width > 0.0 {
            8.0 * peak_to_peak_rad / (width * width)
        } else {
            0.0
        };
        Ok(Self::dispersion(spectrum.sigma_centre_per_um(), d))
    }

    /// `½ D (σ − σ0)²` with D in rad µm² (the second derivative of the phase).
    pub fn dispersion(sigma0_per_um: f64, d_rad_um2: f64) -> Self {
        SpectralPhase {
            sigma0_per_um,
            coefficients: vec![0.0, 0.0, 0.5 * d_rad_um2],
        }
    }

    /// φ(σ), radians.
    pub fn at(&self, sigma_per_um: f64) -> f64 {
        let u = sigma_per_um - self.sigma0_per_um;
        self.coefficients
            .iter()
            .rev()
            .fold(0.0, |acc, &a| acc * u + a)
    }

    /// Whether φ is identically zero.
    pub fn is_zero(&self) -> bool {
        self.coefficients.iter().all(|&a| a == 0.0)
    }
}
