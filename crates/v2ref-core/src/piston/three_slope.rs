//! The three-slope model of the differential-piston temporal spectrum: three
//! power laws joined continuously at two corner frequencies and scaled to a
//! given piston variance — the form used to synthesise piston sequences in
//! the method of Perrin (1997, A&AS 121, 553) that the paper cites.
//!
//! # The model
//!
//! Conan, Rousset & Madec (1995, JOSA A 12, 1559, §4 on the differential
//! piston of two apertures, infinite outer scale) give the asymptotic slopes
//! of the differential-piston spectrum: ν^{−2/3} below a corner near
//! `0.2 v/B`, ν^{−8/3} between it and a corner near `0.3 v/D`, ν^{−17/3}
//! above. The model keeps only these asymptotes:
//!
//! `P(ν) = A g(|ν|)`, `g(ν) = ν^{−2/3}` (ν < ν1),
//! `ν1² ν^{−8/3}` (ν1 ≤ ν < ν2), `ν1² ν2³ ν^{−17/3}` (ν ≥ ν2),
//!
//! with `ν1 = 0.2 v/B` and `ν2 = 0.3 v/D` (ν1 is lowered to ν2 when
//! B < 2D/3, leaving two slopes). The same piecewise form — continuity
//! factors at the corners, total power set to a given variance — is written
//! out in the public simulator cophaSIM (github.com/cpannet/cophaSIM, function
//! `MakeAtmosphereCoherence`, which puts its low corner at 0.2 v/L0); here it
//! is derived and coded from the asymptotes above.
//!
//! # Normalization
//!
//! `∫_{−∞}^{∞} P dν = σ_p²`, the two-aperture piston variance of
//! [`crate::piston::spectrum::PistonSpectrum::variance_um2`] (so a finite
//! outer scale lowers the variance but not the slopes). With
//! `∫_0^∞ g dν = (18/5) ν1^{1/3} − (27/70) ν1² ν2^{−5/3}`,
//! `A = σ_p² / (2 ∫_0^∞ g dν)`.
//!
//! Where this differs from the two-aperture integral
//! ([`crate::piston::spectrum`]): the exact asymptotes cross at 0.225 v/B and
//! 0.299 v/D and the true spectrum is rounded at the corners and modulated by
//! the two-aperture cosine around v/B; the model puts the same variance in
//! sharp corners.

use crate::error::{self, Error, Result};

/// Low corner `ν1 = LOW_CORNER_TIMES_V_OVER_B · v/B` (Conan et al. 1995).
pub const LOW_CORNER_TIMES_V_OVER_B: f64 = 0.2;
/// High corner `ν2 = HIGH_CORNER_TIMES_V_OVER_D · v/D` (Conan et al. 1995).
pub const HIGH_CORNER_TIMES_V_OVER_D: f64 = 0.3;

/// The three-slope spectrum for one variance, wind, baseline and aperture.
///
/// # Example
///
/// ```
/// use v2ref_core::piston::three_slope::ThreeSlope;
/// // 20 µm rms of piston on 18 m with 45 cm apertures and a 10 m/s wind.
/// let m = ThreeSlope::new(400.0, 10.0, 18.0, 0.45)?;
/// assert!((m.corner_low_hz() - 0.2 * 10.0 / 18.0).abs() < 1e-15);
/// assert!((m.corner_high_hz() - 0.3 * 10.0 / 0.45).abs() < 1e-12);
/// assert!((m.variance_um2() - 400.0).abs() < 1e-9);
/// # Ok::<(), v2ref_core::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThreeSlope {
    corner_low_hz: f64,
    corner_high_hz: f64,
    /// A, µm² Hz^{−1/3}.
    scale: f64,
}

/// `∫_0^∞ g dν` for corners ν1 ≤ ν2, Hz^{1/3}.
fn shape_integral(nu1: f64, nu2: f64) -> f64 {
    18.0 / 5.0 * nu1.cbrt() - 27.0 / 70.0 * nu1 * nu1 * nu2.powf(-5.0 / 3.0)
}

impl ThreeSlope {
    /// The model of variance `variance_um2` (≥ 0, µm²) for wind speed
    /// `wind_mps` (> 0), baseline `baseline_m` (≥ 0) and aperture
    /// `aperture_m` (> 0). A zero variance or baseline gives P = 0.
    pub fn new(
        variance_um2: f64,
        wind_mps: f64,
        baseline_m: f64,
        aperture_m: f64,
    ) -> Result<ThreeSlope> {
        error::non_negative("variance_um2", variance_um2)?;
        error::positive("wind_mps", wind_mps)?;
        error::non_negative("baseline_m", baseline_m)?;
        error::positive("aperture_m", aperture_m)?;
        let corner_high_hz = HIGH_CORNER_TIMES_V_OVER_D * wind_mps / aperture_m;
        if !corner_high_hz.is_finite() {
            return Err(Error::Invalid {
                param: "aperture_m",
                reason: format!(
                    "{aperture_m:e} m makes the high corner (wind over aperture) infinite; accepted: an aperture whose corner frequency is finite"
                ),
            });
        }
        if variance_um2 == 0.0 || baseline_m == 0.0 {
            return Ok(ThreeSlope {
                corner_low_hz: corner_high_hz,
                corner_high_hz,
                scale: 0.0,
            });
        }
        let corner_low_hz = (LOW_CORNER_TIMES_V_OVER_B * wind_mps / baseline_m).min(corner_high_hz);
        let shape = shape_integral(corner_low_hz, corner_high_hz);
        // Corners so low (apertures or baseline of astronomical size for
        // the wind) that the shape's integral overflows: no finite scale
        // gives the variance asked.
        if !(shape.is_finite() && shape > 0.0) {
            return Err(Error::Invalid {
                param: "aperture_m",
                reason: format!(
                    "the spectrum's corners ({corner_low_hz:e} and {corner_high_hz:e} Hz) are too low for a finite spectrum; accepted: a baseline and an aperture whose corner frequencies (wind over baseline and over aperture) give a finite spectrum"
                ),
            });
        }
        let scale = variance_um2 / (2.0 * shape);
        Ok(ThreeSlope {
            corner_low_hz,
            corner_high_hz,
            scale,
        })
    }

    /// ν1, Hz.
    pub fn corner_low_hz(&self) -> f64 {
        self.corner_low_hz
    }
    /// ν2, Hz.
    pub fn corner_high_hz(&self) -> f64 {
        self.corner_high_hz
    }

    /// Two-sided P(ν), µm²/Hz (infinite at ν = 0 unless the variance is 0).
    pub fn psd_um2_per_hz(&self, nu_hz: f64) -> f64 {
        if self.scale == 0.0 {
            return 0.0;
        }
        let nu = nu_hz.abs();
        let (nu1, nu2) = (self.corner_low_hz, self.corner_high_hz);
        let shape = if nu < nu1 {
            nu.powf(-2.0 / 3.0)
        } else if nu < nu2 {
            nu1 * nu1 * nu.powf(-8.0 / 3.0)
        } else {
            nu1 * nu1 * nu2.powi(3) * nu.powf(-17.0 / 3.0)
        };
        self.scale * shape
    }

    /// `∫_{−∞}^{∞} P dν`, µm² (the variance it was built with, from the
    /// closed form of the shape integral).
    pub fn variance_um2(&self) -> f64 {
        if self.scale == 0.0 {
            return 0.0;
        }
        2.0 * self.scale * shape_integral(self.corner_low_hz, self.corner_high_hz)
    }
}
