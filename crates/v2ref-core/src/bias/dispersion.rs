//! The dispersion of an unbalanced length of fluoride glass (paper, Section
//! "Effect of chromatic dispersion": 1 K of temperature difference over 1 km
//! of fluoride fibre is said to give 10 mm of glass optical path difference
//! and 1.2 rad of peak-to-peak phase at 2.2 µm).
//!
//! An extra glass length L (µm) adds the phase `φ(σ) = 2π σ n(σ) L`. Its
//! constant and linear parts only move the fringe packet (the scan is
//! re-centred on it); the quadratic part is the paper's dispersion,
//! `D = d²φ/dσ² = 2π L (2 n'(σ) + σ n''(σ))` at the band centre σ0
//! (derivatives in wavenumber), and its peak-to-peak value over a band of
//! width Δσ is `P = ½ D (Δσ/2)²` (`docs/conventions.md`).
//!
//! The refractive index of ZBLAN is the two-term Sellmeier formula of
//! F. Gan, "Optical properties of fluoride glasses: a review", J. Non-Cryst.
//! Solids 184, 9–20 (1995), as tabulated by the refractiveindex.info
//! database (`glass/misc/ZBLAN/nk/Gan.yml`, valid 0.365–3.5 µm, room
//! temperature): `n² = 1 + B1 λ²/(λ² − C1²) + B2 λ²/(λ² − C2²)`.
//!
//! The thermal step (how much glass path 1 K over 1 km makes, which needs
//! dn/dT and the expansion coefficient of the fibre) is not computed: no
//! citable thermo-optic data for ZBLAN fibre was at hand, so the paper's
//! 10 mm is taken as the input.

use crate::error::{self, Result};
use std::f64::consts::PI;

/// Sellmeier B1 of ZBLAN (Gan 1995).
pub const ZBLAN_B1: f64 = 1.22514;
/// Sellmeier C1 of ZBLAN, µm (Gan 1995).
pub const ZBLAN_C1_UM: f64 = 0.08969;
/// Sellmeier B2 of ZBLAN (Gan 1995).
pub const ZBLAN_B2: f64 = 1.52898;
/// Sellmeier C2 of ZBLAN, µm (Gan 1995).
pub const ZBLAN_C2_UM: f64 = 21.3825;

/// Refractive index of ZBLAN at wavenumber `sigma_per_um` (µm⁻¹), Gan (1995).
pub fn zblan_index(sigma_per_um: f64) -> f64 {
    let l2 = 1.0 / (sigma_per_um * sigma_per_um);
    let term = |b: f64, c: f64| b * l2 / (l2 - c * c);
    (1.0 + term(ZBLAN_B1, ZBLAN_C1_UM) + term(ZBLAN_B2, ZBLAN_C2_UM)).sqrt()
}

/// Step (µm⁻¹) of the five-point second difference in
/// [`dispersion_coefficient`]: the index varies on scales of 1 µm⁻¹, so the
/// truncation error h⁴ is ~1e-12 relative, while the rounding error
/// ε|φ|/h² stays ~1e-8 relative (a smaller step trades one for the other).
const D2_STEP_PER_UM: f64 = 1e-3;

/// Step (µm⁻¹) of the central first difference that removes the slope in
/// [`residual_peak_to_peak`]: truncation h² ~ 1e-8 relative of a phase
/// slope, far below the peak-to-peak being measured.
const SLOPE_STEP_PER_UM: f64 = 1e-4;

/// `D = d²φ/dσ²` (rad µm²) at `sigma0_per_um` for an extra glass length
/// `length_um` of index `index(σ)`: `φ = 2π σ n(σ) L`, differentiated by a
/// five-point central difference with step `D2_STEP_PER_UM` (the index
/// varies on scales of 1 µm⁻¹, so the truncation error is ~1e-12 relative).
pub fn dispersion_coefficient(
    index: impl Fn(f64) -> f64,
    sigma0_per_um: f64,
    length_um: f64,
) -> Result<f64> {
    error::positive("sigma0_per_um", sigma0_per_um)?;
    error::finite("length_um", length_um)?;
    let phi = |s: f64| 2.0 * PI * s * index(s) * length_um;
    let h = D2_STEP_PER_UM;
    let (s, f0) = (sigma0_per_um, phi(sigma0_per_um));
    let d2 = (-phi(s + 2.0 * h) + 16.0 * phi(s + h) - 30.0 * f0 + 16.0 * phi(s - h)
        - phi(s - 2.0 * h))
        / (12.0 * h * h);
    // An index that is not a number (or a σ0 where φ overflows) leaves none.
    error::finite("index", d2)
}

/// The glass phase over a band, with its value and slope at σ0 removed:
/// `φ(σ) − φ(σ0) − φ'(σ0)(σ − σ0)`, largest value over `[lo, hi]` minus
/// smallest (the peak-to-peak of everything beyond the linear term, higher
/// orders included), sampled on 2001 points. The band must be
/// `0 < lo < hi` (µm⁻¹) and the index finite on it.
pub fn residual_peak_to_peak(
    index: impl Fn(f64) -> f64,
    lo_per_um: f64,
    hi_per_um: f64,
    length_um: f64,
) -> Result<f64> {
    error::positive("lo_per_um", lo_per_um)?;
    error::positive("hi_per_um", hi_per_um)?;
    error::in_range("hi_per_um", hi_per_um, lo_per_um, f64::MAX)?;
    error::finite("length_um", length_um)?;
    let phi = |s: f64| 2.0 * PI * s * index(s) * length_um;
    let s0 = 0.5 * (lo_per_um + hi_per_um);
    let h = SLOPE_STEP_PER_UM;
    let slope = (phi(s0 + h) - phi(s0 - h)) / (2.0 * h);
    let f0 = phi(s0);
    let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
    for k in 0..=2000 {
        let s = lo_per_um + (hi_per_um - lo_per_um) * k as f64 / 2000.0;
        let r = phi(s) - f0 - slope * (s - s0);
        min = min.min(r);
        max = max.max(r);
    }
    error::finite("index", max - min)
}

/// The quadratic peak-to-peak phase `P = ½ |D| (Δσ/2)²` of `length_um` of
/// ZBLAN over the band `[lo, hi]` (µm⁻¹), D at the band centre.
pub fn zblan_peak_to_peak_rad(lo_per_um: f64, hi_per_um: f64, length_um: f64) -> Result<f64> {
    error::positive("lo_per_um", lo_per_um)?;
    error::in_range("hi_per_um", hi_per_um, lo_per_um, f64::MAX)?;
    let d = dispersion_coefficient(zblan_index, 0.5 * (lo_per_um + hi_per_um), length_um)?;
    let half = 0.5 * (hi_per_um - lo_per_um);
    // A band so wide that the quadratic phase overflows leaves none.
    error::finite("hi_per_um", 0.5 * d.abs() * half * half)
}
