//! From a catalogue magnitude to the photon rate at the detector: the
//! planner's optional helper for users who know their source's 2MASS
//! magnitude rather than its count rate.
//!
//! A star of magnitude m in a 2MASS band has the flux density
//! `F_ν = F_ν,0 · 10^(−m/2.5)` at the band's isophotal wavelength, with the
//! zero-magnitude flux F_ν,0 of Cohen, Wheaton & Megeath (2003, AJ 126,
//! 1090, Table 2): J 1594 Jy at 1.235 µm, H 1024 Jy at 1.662 µm, Ks 666.7 Jy
//! at 2.159 µm (1 Jy = 10⁻²⁶ W m⁻² Hz⁻¹). Taking F_ν constant over the
//! observing band [λ0 − Δλ/2, λ0 + Δλ/2] (the source's colour across the
//! band is neglected), the photons per second and per m² are
//!
//! `∫ F_ν dν / (h ν) = F_ν · ln(λ_max/λ_min) / h ≈ F_ν (Δλ/λ0) / h`,
//!
//! and the rate at the detector is that times the collecting area of the
//! two telescopes, `2 · π D²/4`, times the throughput T: the fraction of
//! those photons counted in the sampled interferogram (atmosphere,
//! telescopes, relay, beam combiner, the share of the combiner's outputs
//! that is sampled, and the detector's quantum efficiency). T is the user's:
//! instruments differ by orders of magnitude, so it has no default.
//!
//! (`ln(λ_max/λ_min)` is exact for a flat F_ν, since ∫dν/ν = ln(ν_max/ν_min)).
//! Cross-check: Ks = 0 gives F_ν/(h λ) = 4.66 × 10⁹ photons s⁻¹ m⁻² µm⁻¹
//! at 2.159 µm.

use crate::error::{self, Error, Result};
use serde::Serialize;
use std::f64::consts::PI;

/// Planck's constant, J s (exact in the SI since 2019).
pub const PLANCK_J_S: f64 = 6.626_070_15e-34;
/// One jansky, W m⁻² Hz⁻¹.
pub const JANSKY_W_PER_M2_HZ: f64 = 1e-26;

pub use v2ref_core::photometric_band::{Band2Mass, PhotometricBand, MAGNITUDE_RANGE};

/// A source's brightness given as a magnitude, and the instrument that
/// collects it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Magnitude {
    /// The magnitude, in `band`.
    pub magnitude: f64,
    /// The 2MASS band the magnitude is in.
    pub band: Band2Mass,
    /// Telescope aperture diameter D, m (two telescopes).
    pub aperture_m: f64,
    /// Throughput T to the sampled interferogram, detector QE included, 0 to 1.
    pub throughput: f64,
}

impl Magnitude {
    fn check(&self) -> Result<()> {
        let (lo, hi) = MAGNITUDE_RANGE;
        if !(lo..=hi).contains(&self.magnitude) {
            return Err(Error::OutOfRange {
                param: "magnitude",
                value: self.magnitude,
                accepted: format!("{lo} to {hi}"),
            });
        }
        error::positive("aperture_m", self.aperture_m)?;
        if !(self.throughput > 0.0 && self.throughput <= 1.0) {
            return Err(Error::OutOfRange {
                param: "throughput",
                value: self.throughput,
                accepted: "0 < throughput <= 1".into(),
            });
        }
        Ok(())
    }

    /// Collecting area of the two telescopes, m².
    pub fn collecting_area_m2(&self) -> f64 {
        2.0 * PI * self.aperture_m * self.aperture_m / 4.0
    }

    /// Photons per second at the detector in the band
    /// [λ0 − Δλ/2, λ0 + Δλ/2] (`centre_um` = λ0, `bandwidth_um` = Δλ,
    /// 0 < Δλ < 2 λ0): `F_ν,0 10^(−m/2.5) ln(λ_max/λ_min)/h · 2πD²/4 · T`.
    ///
    /// # Example
    ///
    /// ```
    /// use v2ref_commands::plan::photometry::{Band2Mass, Magnitude};
    /// // H = 5 on two 1.8 m telescopes with 1 % throughput, full H band.
    /// let m = Magnitude { magnitude: 5.0, band: Band2Mass::H, aperture_m: 1.8, throughput: 0.01 };
    /// let rate = m.photon_rate_per_s(1.65, 0.3)?;
    /// assert!(rate > 1e6 && rate < 1e7);
    /// # Ok::<(), v2ref_core::Error>(())
    /// ```
    pub fn photon_rate_per_s(&self, centre_um: f64, bandwidth_um: f64) -> Result<f64> {
        self.check()?;
        error::positive("wavelength_um", centre_um)?;
        self.band.check_covers(centre_um)?;
        if !(bandwidth_um > 0.0 && bandwidth_um < 2.0 * centre_um) {
            return Err(Error::OutOfRange {
                param: "bandwidth_nm",
                value: bandwidth_um * 1e3,
                accepted: format!("0 < bandwidth < {} nm", 2e3 * centre_um),
            });
        }
        let f_nu =
            self.band.zero_point_jy() * JANSKY_W_PER_M2_HZ * 10f64.powf(-self.magnitude / 2.5);
        let log_width = ((centre_um + bandwidth_um / 2.0) / (centre_um - bandwidth_um / 2.0)).ln();
        Ok(f_nu * log_width / PLANCK_J_S * self.collecting_area_m2() * self.throughput)
    }
}
