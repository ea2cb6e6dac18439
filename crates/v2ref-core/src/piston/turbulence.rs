//! Atmospheric turbulence: Kolmogorov phase statistics, the Fried parameter r0
//! and the seeing (paper, Section "Effect of differential piston"; r0 in m,
//! OPD in µm, seeing in arcsec). The temporal spectrum of the differential
//! piston between two apertures is in [`crate::piston::spectrum`] (re-exported
//! here).
//!
//! # Phase statistics
//!
//! Kolmogorov turbulence with Fried parameter r0 (given at the observing
//! wavelength λ0) has the phase structure function
//! `D_φ(ρ) = C_D (ρ/r0)^{5/3}` rad², `C_D = 2 [24/5 Γ(6/5)]^{5/6} ≈ 6.8839`,
//! and the two-dimensional phase power spectrum
//! `Φ_φ(f) = C_Φ r0^{−5/3} (f² + L0^{−2})^{−11/6}` rad² m², with
//! `C_Φ = Γ(11/6)² / (2 π^{11/3}) [24/5 Γ(6/5)]^{5/6} ≈ 0.022896` and f in
//! cycles/m (Roddier 1981, Prog. Opt. 19, 281; von Kármán outer scale L0 as
//! an option, L0 = ∞ by default). The OPD spectrum is `(λ0/2π)² Φ_φ` in
//! µm² m²; it does not depend on λ0 since r0 ∝ λ^{6/5}.
//!
//! Seeing is λ0/r0 at the observing wavelength (`docs/conventions.md`): 1 arcsec
//! at 2.2 µm gives r0 = 45.4 cm. The coherence time is r0/v.

use crate::error::{self, Error, Result};
use std::f64::consts::PI;

/// Radians per arcsecond.
pub const RAD_PER_ARCSEC: f64 = PI / 648_000.0;

/// Metres per micrometre (unit conversion).
const M_PER_UM: f64 = 1e-6;

/// Γ(x) for x > 0 (Lanczos, g = 7, 9 terms; relative error ~2e-15 for
/// every x > 0, the pole at 0 included through the c₁/x term, so no
/// reflection is needed: checked against mpmath through the constants and
/// the profile integrals, down to x = 0.25).
fn gamma(x: f64) -> f64 {
    const G: f64 = 7.0;
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    let x = x - 1.0;
    let mut a = C[0];
    let t = x + G + 0.5;
    for (i, c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    (2.0 * PI).sqrt() * t.powf(x + 0.5) * (-t).exp() * a
}

/// `[24/5 Γ(6/5)]^{5/6}`, the constant shared by the Kolmogorov forms.
fn kolmogorov_core() -> f64 {
    (24.0 / 5.0 * gamma(6.0 / 5.0)).powf(5.0 / 6.0)
}

/// `C_D = 2 [24/5 Γ(6/5)]^{5/6} ≈ 6.8839`: `D_φ(ρ) = C_D (ρ/r0)^{5/3}`.
pub fn structure_coefficient() -> f64 {
    2.0 * kolmogorov_core()
}

/// `C_Φ = Γ(11/6)²/(2π^{11/3}) [24/5 Γ(6/5)]^{5/6} ≈ 0.022896`:
/// `Φ_φ(f) = C_Φ r0^{−5/3} f^{−11/3}` (f in cycles/m).
pub fn psd_coefficient() -> f64 {
    gamma(11.0 / 6.0).powi(2) / (2.0 * PI.powf(11.0 / 3.0)) * kolmogorov_core()
}

/// `I(a) = ∫_{−∞}^{∞} (1 + u²)^{−a} du = √π Γ(a − ½)/Γ(a)` (a > ½).
pub fn profile_integral(a: f64) -> f64 {
    PI.sqrt() * gamma(a - 0.5) / gamma(a)
}

/// Fried parameter r0 (m) from the seeing λ/r0 (arcsec) at wavelength λ (µm):
/// `r0 = λ / seeing`. Zero seeing means no turbulence (r0 = ∞).
pub fn r0_from_seeing_m(seeing_arcsec: f64, wavelength_um: f64) -> Result<f64> {
    crate::bounds::check_seeing_arcsec(seeing_arcsec)?;
    crate::bounds::check_wavelength_um(wavelength_um)?;
    if seeing_arcsec == 0.0 {
        return Ok(f64::INFINITY);
    }
    Ok(wavelength_um * M_PER_UM / (seeing_arcsec * RAD_PER_ARCSEC))
}

/// The seeing λ/r0 (arcsec) at wavelength `to_um` (µm) of turbulence whose
/// seeing is `seeing_arcsec` at `from_um` (µm): seeing is usually quoted at
/// 0.5 µm, while the piston depends on r0 at the observing wavelength.
///
/// In Kolmogorov turbulence r0 = [0.423 k² ∫C_n²(h) dh]^(−3/5) with
/// k = 2π/λ, so r0 ∝ λ^(6/5) and the seeing λ/r0 ∝ λ^(−1/5):
///
/// `seeing(to) = seeing(from) · (to / from)^(−1/5)`.
///
/// Domain: seeing ≥ 0 (0 stays 0: no turbulence), both wavelengths > 0.
/// Reference: Fried (1966), JOSA 56, 1372; Roddier (1981), Progress in
/// Optics 19, 281, eq. (3.18).
///
/// # Example
///
/// ```
/// use v2ref_core::piston::turbulence::seeing_at_wavelength_arcsec;
/// // 1″ at 0.5 µm is 0.74″ in K: r0 grows from 10.3 cm to 61 cm.
/// let k = seeing_at_wavelength_arcsec(1.0, 0.5, 2.2)?;
/// assert!((k - 4.4f64.powf(-0.2)).abs() < 1e-15);
/// # Ok::<(), v2ref_core::Error>(())
/// ```
pub fn seeing_at_wavelength_arcsec(seeing_arcsec: f64, from_um: f64, to_um: f64) -> Result<f64> {
    crate::bounds::check_seeing_arcsec(seeing_arcsec)?;
    crate::bounds::check_wavelength_um(to_um)?;
    if from_um != to_um {
        // Quoted elsewhere than the observing wavelength: where seeing is
        // measured (at the observing wavelength itself any band is fine).
        crate::bounds::check_seeing_wavelength_um(from_um)?;
    }
    Ok(seeing_arcsec * (to_um / from_um).powf(-0.2))
}

/// τ0 / (r0/v): 0.314 = (6.88)^(-3/5) (Roddier 1981).
pub const TAU0_PER_R0_OVER_V: f64 = 0.314;

/// The turbulent atmosphere above the interferometer, at the observing
/// wavelength.
///
/// # Example
///
/// ```
/// use v2ref_core::prelude::*;
/// // The paper's seeing: 1 arcsec at 2.2 µm gives r0 = λ/seeing ≈ 45 cm.
/// let t = Turbulence::from_seeing(1.0, 2.2, 10.0, None)?;
/// assert!((t.r0_m() - 0.454).abs() < 1e-3);
/// // The same seeing quoted at 1.65 µm means a smaller r0 (r0 = λ/seeing).
/// let h = Turbulence::from_seeing(1.0, 1.65, 10.0, None)?;
/// assert!((h.r0_m() / t.r0_m() - 1.65 / 2.2).abs() < 1e-12);
/// # Ok::<(), v2ref_core::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Turbulence {
    wavelength_um: f64,
    r0_m: f64,
    wind_mps: f64,
    outer_scale_m: Option<f64>,
}

impl Turbulence {
    /// Turbulence of Fried parameter `r0_m` (m, > 0; ∞ for none) at
    /// `wavelength_um`, frozen flow at `wind_mps` (> 0), optional von Kármán
    /// outer scale `outer_scale_m` (> 0; None for Kolmogorov).
    pub fn new(
        r0_m: f64,
        wavelength_um: f64,
        wind_mps: f64,
        outer_scale_m: Option<f64>,
    ) -> Result<Turbulence> {
        crate::bounds::check_wavelength_um(wavelength_um)?;
        crate::bounds::check_wind_mps(wind_mps)?;
        if r0_m.is_nan() || r0_m <= 0.0 {
            return Err(Error::OutOfRange {
                param: "r0",
                value: r0_m,
                accepted: "> 0".into(),
            });
        }
        if let Some(l0) = outer_scale_m {
            error::positive("outer_scale_m", l0)?;
        }
        Ok(Turbulence {
            wavelength_um,
            r0_m,
            wind_mps,
            outer_scale_m,
        })
    }

    /// Turbulence given by its seeing λ/r0 (arcsec, ≥ 0; 0 = none) at
    /// `wavelength_um`.
    pub fn from_seeing(
        seeing_arcsec: f64,
        wavelength_um: f64,
        wind_mps: f64,
        outer_scale_m: Option<f64>,
    ) -> Result<Turbulence> {
        let r0 = r0_from_seeing_m(seeing_arcsec, wavelength_um)?;
        Turbulence::new(r0, wavelength_um, wind_mps, outer_scale_m)
    }

    /// λ0, µm.
    pub fn wavelength_um(&self) -> f64 {
        self.wavelength_um
    }
    /// r0 at λ0, m.
    pub fn r0_m(&self) -> f64 {
        self.r0_m
    }
    /// Wind speed, m/s.
    pub fn wind_mps(&self) -> f64 {
        self.wind_mps
    }
    /// Outer scale, m (None: infinite).
    pub fn outer_scale_m(&self) -> Option<f64> {
        self.outer_scale_m
    }
    /// The paper's coherence time r0/v, s (the field's usual τ0 is
    /// [`tau0_s`](Self::tau0_s)).
    pub fn coherence_time_s(&self) -> f64 {
        self.r0_m / self.wind_mps
    }
    /// The adaptive-optics coherence time τ0 = 0.314 r0/v, s (Roddier 1981,
    /// Progress in Optics 19, 281: the time over which the phase structure
    /// function stays below 1 rad² for a frozen screen moving at v).
    pub fn tau0_s(&self) -> f64 {
        TAU0_PER_R0_OVER_V * self.r0_m / self.wind_mps
    }
    /// The same turbulence with another wind speed.
    pub fn with_wind(&self, wind_mps: f64) -> Result<Turbulence> {
        Turbulence::new(self.r0_m, self.wavelength_um, wind_mps, self.outer_scale_m)
    }

    /// `K = (λ0/2π)² C_Φ r0^{−5/3}`, µm² m^{−5/3}: the OPD spectrum is
    /// `K (f² + L0^{−2})^{−11/6}`.
    pub fn opd_psd_scale(&self) -> f64 {
        if self.r0_m.is_infinite() {
            return 0.0;
        }
        let k = self.wavelength_um / (2.0 * PI);
        k * k * psd_coefficient() * self.r0_m.powf(-5.0 / 3.0)
    }

    /// OPD power spectrum `Φ_opd(f)`, µm² m², at spatial frequency
    /// `f_per_m` (cycles/m, > 0).
    pub fn opd_psd(&self, f_per_m: f64) -> f64 {
        let inv_l0_sq = self.outer_scale_m.map_or(0.0, |l| 1.0 / (l * l));
        self.opd_psd_scale() * (f_per_m * f_per_m + inv_l0_sq).powf(-11.0 / 6.0)
    }

    /// Kolmogorov OPD structure function `(λ0/2π)² C_D (ρ/r0)^{5/3}`, µm²
    /// (the outer scale is ignored: this is the infinite-L0 form).
    pub fn opd_structure_function_um2(&self, rho_m: f64) -> f64 {
        if self.r0_m.is_infinite() {
            return 0.0;
        }
        let k = self.wavelength_um / (2.0 * PI);
        k * k * structure_coefficient() * (rho_m / self.r0_m).powf(5.0 / 3.0)
    }
}
