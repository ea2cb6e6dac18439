//! The transverse integrals behind the differential-piston spectrum of
//! [`crate::piston::spectrum`]: `G(f_x) = ∫ Φ_opd A df_y` and, for a wind
//! across the baseline, `S(f_x) = ∫ Φ_opd A 2 sin²(π f_y B sin θ) df_y`
//! (µm² m), by adaptive quadrature ([`transverse_integral`],
//! [`crosswind_integral`]), and their table against ln(f_x D) with its
//! cubic interpolation ([`TransverseTable`]): computed once per (r0, D, L0),
//! so that P(ν) at any ν costs one interpolation.

use crate::error::{self, Result};
use crate::math::quadrature::{integrate_pieces, Tolerance};
use crate::math::special::jinc;
use crate::piston::turbulence::Turbulence;
use std::f64::consts::PI;

/// The single-aperture piston filter `A(f) = [2J1(πDf)/(πDf)]²`.
pub fn aperture_filter(f_per_m: f64, aperture_m: f64) -> f64 {
    let j = jinc(PI * aperture_m * f_per_m);
    j * j
}

/// Upper limit of the numerical spectral integrals, in units of 1/D; the
/// rest is added from the averaged high-frequency asymptote. At 100/D the
/// neglected oscillation of the Bessel envelope is below 1e-12 of G.
pub(super) const F_MAX_TIMES_D: f64 = 100.0;

/// Integration tolerance of the spectral integrals.
pub(super) fn tol() -> Tolerance {
    Tolerance {
        abs: 0.0,
        rel: crate::tolerance::TURBULENCE_QUADRATURE_REL,
    }
}

/// Geometric breaks from `a` to `b` (ratio 2), starting with [0, a].
fn breaks_from_zero(a: f64, b: f64) -> Vec<f64> {
    let mut out = vec![0.0, a];
    let mut x = a;
    while x * 2.0 < b {
        x *= 2.0;
        out.push(x);
    }
    out.push(b);
    out
}

/// `G(f_x) = ∫_{−∞}^{∞} Φ_opd(f) A(f) df_y`, µm² m, `f = √(f_x² + f_y²)`,
/// by adaptive quadrature (the slow, direct form; the tabulated one is in
/// [`PistonSpectrum`](crate::piston::spectrum::PistonSpectrum)).
pub fn transverse_integral(turb: &Turbulence, aperture_m: f64, fx_per_m: f64) -> f64 {
    let k = turb.opd_psd_scale();
    if k == 0.0 {
        return 0.0;
    }
    let f_max = (F_MAX_TIMES_D / aperture_m).max(F_MAX_TIMES_D * fx_per_m);
    let integrand = |fy: f64| {
        let f = (fx_per_m * fx_per_m + fy * fy).sqrt();
        turb.opd_psd(f) * aperture_filter(f, aperture_m)
    };
    let body = integrate_pieces(&integrand, &breaks_from_zero(fx_per_m, f_max), tol());
    // Tail: A averaged to 4/(π⁴D³f³), f ≈ f_y, Φ ≈ K f^{−11/3}.
    let tail = k * 4.0 / (PI.powi(4) * aperture_m.powi(3)) * (3.0 / 17.0) * f_max.powf(-17.0 / 3.0);
    2.0 * (body + tail)
}

/// Beyond `f_x B sin θ` = this, `S(f_x) = G(f_x)` to double precision: the
/// cosine transform `G − S` of the smooth profile of width f_x decays as
/// `exp(−2π f_x B sin θ)` (< 1e-16 here).
const CROSSWIND_EQUALS_G_BEYOND: f64 = 6.0;

/// Half periods of `sin²(π f_y b)` integrated piece by piece; beyond them
/// the factor `2 sin²` is replaced by its mean 1 (the neglected cosine
/// integral is ~1/(2π · this) of the part beyond, which is below ~1e-4 of
/// S: ~1e-6 relative).
const CROSSWIND_HALF_PERIODS: usize = 64;

/// `S(f_x) = ∫_{−∞}^{∞} Φ_opd(f) A(f) 2 sin²(π f_y b) df_y`, µm² m, with
/// `b = B sin θ` > 0 the baseline across the wind (see the module doc).
pub fn crosswind_integral(turb: &Turbulence, aperture_m: f64, fx_per_m: f64, b_m: f64) -> f64 {
    if fx_per_m * b_m > CROSSWIND_EQUALS_G_BEYOND {
        return transverse_integral(turb, aperture_m, fx_per_m);
    }
    let f_max = (F_MAX_TIMES_D / aperture_m).max(F_MAX_TIMES_D * fx_per_m);
    let profile = |fy: f64| {
        let f = (fx_per_m * fx_per_m + fy * fy).sqrt();
        turb.opd_psd(f) * aperture_filter(f, aperture_m)
    };
    let half_period = 0.5 / b_m;
    let y_cut = (CROSSWIND_HALF_PERIODS as f64 * half_period).min(f_max);
    let mut br = breaks_from_zero(fx_per_m.min(y_cut), y_cut);
    br.extend((1..CROSSWIND_HALF_PERIODS).map(|k| k as f64 * half_period));
    br.retain(|&x| x <= y_cut);
    br.sort_by(f64::total_cmp);
    br.dedup();
    let oscillating = |fy: f64| {
        let s = (PI * fy * b_m).sin();
        profile(fy) * 2.0 * s * s
    };
    let body = integrate_pieces(&oscillating, &br, tol());
    let beyond = if y_cut < f_max {
        integrate_pieces(&profile, &breaks_between(y_cut, f_max), tol())
    } else {
        0.0
    };
    let k = turb.opd_psd_scale();
    let tail = k * 4.0 / (PI.powi(4) * aperture_m.powi(3)) * (3.0 / 17.0) * f_max.powf(-17.0 / 3.0);
    2.0 * (body + beyond + tail)
}

/// Geometric breaks from `a` > 0 to `b` (ratio 2).
fn breaks_between(a: f64, b: f64) -> Vec<f64> {
    let mut out = breaks_from_zero(a, b);
    out.remove(0);
    out
}

/// Points per decade of the G table.
const TABLE_PER_DECADE: usize = 80;
/// Table range in log10(f_x D).
const TABLE_LOG10_MIN: f64 = -7.0;
const TABLE_LOG10_MAX: f64 = 2.0;
/// Grid points of a computed table, both ends included (721).
const TABLE_POINTS: usize = (TABLE_LOG10_MAX - TABLE_LOG10_MIN) as usize * TABLE_PER_DECADE + 1;

/// The transverse integral G(f_x) tabulated for one (turbulence, aperture):
/// ln G on a uniform grid of ln(f_x D), cubic (Catmull–Rom) interpolation,
/// power-law extrapolation with the end slopes.
#[derive(Debug, Clone, PartialEq)]
pub struct TransverseTable {
    pub(super) turb: Turbulence,
    pub(super) aperture_m: f64,
    /// 0 for G; `B sin θ` (m) for the crosswind integral S.
    crosswind_m: f64,
    ln_g: std::sync::OnceLock<Vec<f64>>,
    s0: f64,
    h: f64,
}

impl TransverseTable {
    /// The table of G for `turb` and apertures of diameter `aperture_m`
    /// (> 0), computed on first use: the points are independent
    /// quadratures, computed in parallel (each the same whatever the thread
    /// count).
    pub fn new(turb: Turbulence, aperture_m: f64) -> Result<TransverseTable> {
        crate::bounds::check_aperture_m(aperture_m)?;
        Ok(TransverseTable {
            turb,
            aperture_m,
            crosswind_m: 0.0,
            ln_g: std::sync::OnceLock::new(),
            s0: TABLE_LOG10_MIN * std::f64::consts::LN_10,
            h: std::f64::consts::LN_10 / TABLE_PER_DECADE as f64,
        })
    }

    /// The table of the crosswind integral S ([`crosswind_integral`]) for
    /// the baseline `crosswind_m` (> 0, m) across the wind, on the same grid.
    pub fn crosswind(
        turb: Turbulence,
        aperture_m: f64,
        crosswind_m: f64,
    ) -> Result<TransverseTable> {
        error::positive("crosswind_m", crosswind_m)?;
        let mut t = TransverseTable::new(turb, aperture_m)?;
        t.crosswind_m = crosswind_m;
        Ok(t)
    }

    /// A table holding the given values of ln G (or ln S) on the grid of
    /// [`TransverseTable::grid_fx_per_m`] instead of computed ones: at least
    /// two values (none gives the table of zero turbulence). For tests of
    /// the interpolation and of the spectrum built on it without the 721
    /// quadratures of a real table (seconds at opt-level 0).
    #[doc(hidden)]
    pub fn from_ln_values(
        turb: Turbulence,
        aperture_m: f64,
        ln_values: Vec<f64>,
    ) -> Result<TransverseTable> {
        if ln_values.len() == 1 {
            return Err(crate::error::Error::Invalid {
                param: "ln_values",
                reason: "a table needs no value or at least two".into(),
            });
        }
        let table = TransverseTable::new(turb, aperture_m)?;
        table.ln_g.get_or_init(|| ln_values);
        Ok(table)
    }

    /// The grid point `i`: f_x (m⁻¹) with `ln(f_x D) = ln(10⁻⁷) + i ln(10)/80`,
    /// 80 points per decade of f_x D from 10⁻⁷ to 10² (the last at i = 720).
    pub fn grid_fx_per_m(&self, i: usize) -> f64 {
        (self.s0 + i as f64 * self.h).exp() / self.aperture_m
    }

    /// The integral tabulated at `fx` (G, or S when `crosswind_m` > 0).
    fn integral(&self, fx_per_m: f64) -> f64 {
        if self.crosswind_m > 0.0 {
            crosswind_integral(&self.turb, self.aperture_m, fx_per_m, self.crosswind_m)
        } else {
            transverse_integral(&self.turb, self.aperture_m, fx_per_m)
        }
    }

    /// ln G on the grid, computed on first use.
    fn values(&self) -> &[f64] {
        self.ln_g.get_or_init(|| {
            if self.turb.opd_psd_scale() == 0.0 {
                return Vec::new();
            }
            use rayon::prelude::*;
            (0..TABLE_POINTS)
                .into_par_iter()
                .map(|i| self.integral(self.grid_fx_per_m(i)).ln())
                .collect()
        })
    }

    /// Computes the table now, on the current rayon pool, if it is not
    /// computed yet (see [`PistonSpectrum::tabulate`](crate::piston::spectrum::PistonSpectrum::tabulate)).
    pub fn tabulate(&self) {
        self.values();
    }

    /// The turbulence tabulated.
    pub fn turbulence(&self) -> &Turbulence {
        &self.turb
    }
    /// D, m.
    pub fn aperture_m(&self) -> f64 {
        self.aperture_m
    }

    /// G(f_x), µm² m, interpolated.
    pub fn g(&self, fx_per_m: f64) -> f64 {
        let y = self.values();
        let n = y.len();
        if n == 0 || fx_per_m <= 0.0 {
            return if n == 0 { 0.0 } else { f64::INFINITY };
        }
        let s = (fx_per_m * self.aperture_m).ln();
        let t = (s - self.s0) / self.h;
        if t <= 0.0 {
            return (y[0] + (y[1] - y[0]) * t).exp();
        }
        let last = (n - 1) as f64;
        if t >= last {
            return (y[n - 1] + (y[n - 1] - y[n - 2]) * (t - last)).exp();
        }
        let i = (t.floor() as usize).min(n - 2);
        let u = t - i as f64;
        let p1 = y[i];
        let p2 = y[i + 1];
        let p0 = if i == 0 { 2.0 * p1 - p2 } else { y[i - 1] };
        let p3 = if i + 2 < n { y[i + 2] } else { 2.0 * p2 - p1 };
        // Catmull–Rom cubic Hermite.
        let u2 = u * u;
        let u3 = u2 * u;
        let v = 0.5
            * ((2.0 * p1)
                + (-p0 + p2) * u
                + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * u2
                + (-p0 + 3.0 * p1 - 3.0 * p2 + p3) * u3);
        v.exp()
    }
}
