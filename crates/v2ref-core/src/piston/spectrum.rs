//! The temporal spectrum of the differential piston between two apertures
//! (paper, Section "Effect of differential piston"): P(ν) in µm²/Hz of
//! frequency ν in Hz, from the turbulence of [`crate::piston::turbulence`].
//!
//! # Differential piston
//!
//! The piston of one circular aperture of diameter D is the OPD averaged over
//! the pupil, which filters the spectrum by `A(f) = [2J1(πDf)/(πDf)]²`; the
//! difference between two apertures on baseline **B** multiplies it by
//! `2[1 − cos(2π **B**·**f**)]`. Under frozen flow at wind speed v along the
//! baseline, the temporal (two-sided) power spectrum of the differential
//! piston is
//!
//! `P(ν) = (1/v) · 2[1 − cos(2πBν/v)] · G(ν/v)`, with
//! `G(f_x) = ∫ Φ_opd(√(f_x² + f_y²)) A(√(f_x² + f_y²)) df_y`  (µm² m),
//!
//! P in µm²/Hz, `∫_{−∞}^{∞} P dν = σ_p²` (Conan, Rousset & Madec 1995,
//! JOSA A 12, 1559; Perrin 1997, A&AS 121, 553 for its use in simulating
//! scanned interferograms). G is computed by adaptive quadrature and
//! tabulated against ln(f_x D) once per (r0, D, L0)
//! ([`crate::piston::transverse`]); P at any ν then costs one interpolation.
//!
//! Kolmogorov asymptotes (checked in `tests/turbulence.rs`), with
//! `I(a) = ∫(1+u²)^{−a} du = √π Γ(a − ½)/Γ(a)` and `K = (λ0/2π)² C_Φ r0^{−5/3}`:
//!
//! - ν ≪ v/B: `P ≈ (2πB)² K I(11/6) v^{−1/3} ν^{−2/3}` — slope −2/3;
//! - v/B ≪ ν ≪ v/D: `P ≈ 2 K I(11/6) v^{5/3} ν^{−8/3}` (the cosine averaged) — slope −8/3;
//! - ν ≫ v/D: `P ≈ 2 K I(10/3) 4/(π⁴D³) v^{14/3} ν^{−17/3}` (the Bessel
//!   oscillation averaged) — slope −17/3.
//!
//! The low/middle asymptotes cross at `ν = v/(√2 π B) ≈ 0.225 v/B`, the
//! middle/high ones at `ν = [4 I(10/3)/(π⁴ I(11/6))]^{1/3} v/D ≈ 0.299 v/D`.
//!
//! # Wind direction
//!
//! With the wind at angle θ to the baseline, the baseline term reads
//! `2[1 − cos 2π(f_x B cos θ + f_y B sin θ)]` (f_x = ν/v along the wind).
//! The part odd in f_y integrates to zero, so with `a = 2πνB cos θ / v`,
//!
//! `P(ν) = (1/v) [4 sin²(a/2) G(f_x) + 2 cos a · S(f_x)]`,
//! `S(f_x) = ∫ Φ_opd A · 2 sin²(π f_y B sin θ) df_y`,
//!
//! which is the along-baseline form when θ = 0 (S = 0, computed by the same
//! code as before, bit for bit) and `2S/v` across it (θ = 90°). For
//! f_x ≪ 1/B both terms go as ν^{−2/3}: the low asymptote becomes
//! `(cos²θ + 3/2 sin²θ)` times the along-baseline one, since
//! `∫u²(1+u²)^{−11/6}du = I(5/6) − I(11/6) = (3/2) I(11/6)`. Above v/B,
//! S → G and the middle and high asymptotes do not depend on θ; neither
//! does the variance (the two-dimensional integral over **f**).
//!
//! # Models
//!
//! [`PistonPsdModel`] selects this two-aperture integral or the three-slope
//! model of [`crate::piston::three_slope`] normalized to the same variance.

use crate::error::{self, Result};
use crate::math::quadrature::integrate_pieces;
use crate::math::special::bessel_j0;
use crate::piston::three_slope::ThreeSlope;
use crate::piston::transverse::{tol, F_MAX_TIMES_D};
use crate::piston::turbulence::{profile_integral, Turbulence};
use std::f64::consts::PI;

// The crate's shorthand for the transverse integrals (their one public path
// is `piston::transverse`).
pub use crate::piston::transverse::{aperture_filter, transverse_integral, TransverseTable};

/// Below this z, `2(1 − J0(z))` is summed from its series to z⁶: the next
/// term, z⁸/73728 < 2e-21 relative to z²/2 ≈ 5e-5, is below an ulp, and
/// `1 − J0(z)` would lose ~log10(4/z²) digits to cancellation.
const SMALL_Z_SERIES_BELOW: f64 = 1e-2;

/// Where the piston integral splits off its low-frequency piece (with the
/// f = u³ substitution for the f^{−2/3} behaviour), in units of
/// 1/max(B, D): three decades below the first Bessel/aperture scale, where
/// the integrand is still on its power law.
const LOW_SPLIT_TIMES_SCALE: f64 = 1e-3;

/// The temporal power spectrum of the differential piston between two
/// apertures of diameter D on baseline B, wind along the baseline.
///
/// # Example
///
/// ```
/// use v2ref_core::prelude::*;
/// // The differential piston of two 45 cm apertures 18 m apart: its rms grows
/// // with the baseline, and a finite outer scale lowers it.
/// let t = Turbulence::from_seeing(1.0, 2.2, 10.0, None)?;
/// let b18 = PistonSpectrum::new(t, 0.45, 18.0)?;
/// let b36 = PistonSpectrum::new(t, 0.45, 36.0)?;
/// assert!(b36.rms_um() > b18.rms_um());
/// let l0 = PistonSpectrum::new(Turbulence::from_seeing(1.0, 2.2, 10.0, Some(25.0))?, 0.45, 18.0)?;
/// assert!(l0.rms_um() < b18.rms_um());
/// assert!(b18.corner_low_hz() < b18.corner_high_hz());
/// # Ok::<(), v2ref_core::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct PistonSpectrum {
    table: std::sync::Arc<TransverseTable>,
    baseline_m: f64,
    wind_mps: f64,
    /// θ, the wind direction from the baseline, rad.
    wind_angle_rad: f64,
    /// The table of S for `B sin θ` (None when sin θ = 0).
    crosswind: Option<std::sync::Arc<TransverseTable>>,
    /// The three-slope model, when it is the one selected.
    three_slope: Option<ThreeSlope>,
}

/// Which differential-piston spectrum the sequences are drawn from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
#[non_exhaustive]
pub enum PistonPsdModel {
    /// The two-aperture spectral integral of this module (Kolmogorov, or von
    /// Kármán with an outer scale; any wind direction).
    TwoAperture,
    /// The three-slope model of [`crate::piston::three_slope`] (Conan et al.
    /// 1995 asymptotes, as in Perrin 1997), normalized to the same variance;
    /// wind along the baseline only.
    ThreeSlope,
}

impl crate::words::Words for PistonPsdModel {
    const WORDS: &'static [crate::words::Word<Self>] = &[
        crate::words::Word {
            word: "two-aperture",
            value: PistonPsdModel::TwoAperture,
            help: "The two-aperture spectral integral of this module (Kolmogorov, or von Kármán with an outer scale; any wind direction)",
        },
        crate::words::Word {
            word: "three-slope",
            value: PistonPsdModel::ThreeSlope,
            help: "The three-slope model of [`crate::piston::three_slope`] (Conan et al. 1995 asymptotes, as in Perrin 1997), normalized to the same variance; wind along the baseline only",
        },
    ];
}

impl PistonPsdModel {
    /// Kebab-case name, as `--psd` takes it.
    pub fn name(&self) -> &'static str {
        crate::words::Words::word(*self)
    }
}

impl PistonSpectrum {
    /// The spectrum for `turb`, apertures `aperture_m` (> 0) and baseline
    /// `baseline_m` (≥ 0; 0 gives no piston).
    pub fn new(turb: Turbulence, aperture_m: f64, baseline_m: f64) -> Result<PistonSpectrum> {
        let table = std::sync::Arc::new(TransverseTable::new(turb, aperture_m)?);
        PistonSpectrum::from_table(table, baseline_m)
    }

    /// The spectrum on `baseline_m` sharing an existing table (G does not
    /// depend on B).
    pub fn from_table(
        table: std::sync::Arc<TransverseTable>,
        baseline_m: f64,
    ) -> Result<PistonSpectrum> {
        error::non_negative("baseline_m", baseline_m)?;
        let wind_mps = table.turb.wind_mps();
        Ok(PistonSpectrum {
            table,
            baseline_m,
            wind_mps,
            wind_angle_rad: 0.0,
            crosswind: None,
            three_slope: None,
        })
    }

    /// The same spectrum at another wind speed (> 0), sharing the tables (G
    /// and S do not depend on the wind).
    pub fn with_wind(&self, wind_mps: f64) -> Result<PistonSpectrum> {
        crate::bounds::check_wind_mps(wind_mps)?;
        let mut out = self.clone();
        out.wind_mps = wind_mps;
        if out.three_slope.is_some() {
            out.three_slope = Some(out.three_slope_model()?);
        }
        Ok(out)
    }

    /// The same turbulence and geometry with the wind at `angle_deg` (finite,
    /// degrees) from the baseline; 0 is the along-baseline spectrum. Only
    /// the two-aperture model has a wind direction: the three-slope model
    /// refuses any angle whose sine is not 0.
    pub fn with_wind_angle_deg(&self, angle_deg: f64) -> Result<PistonSpectrum> {
        self.with_wind_angle_deg_from(angle_deg, |across_m| {
            TransverseTable::crosswind(self.table.turb, self.table.aperture_m, across_m)
        })
    }

    /// [`PistonSpectrum::with_wind_angle_deg`] with the table of S made by
    /// `crosswind_table(B |sin θ|)` (tests give one of known values,
    /// [`TransverseTable::from_ln_values`]).
    #[doc(hidden)]
    pub fn with_wind_angle_deg_from(
        &self,
        angle_deg: f64,
        crosswind_table: impl FnOnce(f64) -> Result<TransverseTable>,
    ) -> Result<PistonSpectrum> {
        error::in_range("wind_angle_deg", angle_deg, -360.0, 360.0)?;
        let theta = angle_deg.to_radians();
        let across = self.baseline_m * theta.sin().abs();
        // sin θ of 180° is 1.2e-16, not 0: treat |sin θ| below 1e-12 as along.
        let along = theta.sin().abs() < 1e-12;
        if !along && self.three_slope.is_some() {
            return Err(three_slope_angle_error(angle_deg));
        }
        let crosswind = if along || across == 0.0 {
            None
        } else {
            Some(std::sync::Arc::new(crosswind_table(across)?))
        };
        let mut out = self.clone();
        out.wind_angle_rad = theta;
        out.crosswind = crosswind;
        Ok(out)
    }

    /// The same turbulence and geometry with the spectrum of `model`.
    pub fn with_model(&self, model: PistonPsdModel) -> Result<PistonSpectrum> {
        let mut out = self.clone();
        out.three_slope = match model {
            PistonPsdModel::TwoAperture => None,
            PistonPsdModel::ThreeSlope => {
                if self.crosswind.is_some() {
                    return Err(three_slope_angle_error(self.wind_angle_rad.to_degrees()));
                }
                Some(self.three_slope_model()?)
            }
        };
        Ok(out)
    }

    /// The model selected.
    pub fn model(&self) -> PistonPsdModel {
        if self.three_slope.is_some() {
            PistonPsdModel::ThreeSlope
        } else {
            PistonPsdModel::TwoAperture
        }
    }

    /// The three-slope model of this spectrum's variance, wind and geometry.
    fn three_slope_model(&self) -> Result<ThreeSlope> {
        ThreeSlope::new(
            self.variance_um2(),
            self.wind_mps,
            self.baseline_m,
            self.table.aperture_m,
        )
    }

    /// The three-slope model, when selected (its corners and scale).
    pub fn three_slope(&self) -> Option<&ThreeSlope> {
        self.three_slope.as_ref()
    }

    /// θ, the wind direction from the baseline, degrees.
    pub fn wind_angle_deg(&self) -> f64 {
        self.wind_angle_rad.to_degrees()
    }

    /// Wind speed, m/s.
    pub fn wind_mps(&self) -> f64 {
        self.wind_mps
    }

    /// The shared table.
    pub fn table(&self) -> &std::sync::Arc<TransverseTable> {
        &self.table
    }
    /// The turbulence of the table (its wind speed may differ from
    /// [`PistonSpectrum::wind_mps`], which is the one used).
    pub fn turbulence(&self) -> &Turbulence {
        &self.table.turb
    }
    /// D, m.
    pub fn aperture_m(&self) -> f64 {
        self.table.aperture_m
    }
    /// B, m.
    pub fn baseline_m(&self) -> f64 {
        self.baseline_m
    }

    /// `2[1 − cos(2πBν/v)]`, computed without cancellation.
    fn baseline_factor(&self, nu_hz: f64) -> f64 {
        let s = (PI * self.baseline_m * nu_hz / self.wind_mps).sin();
        4.0 * s * s
    }

    /// Computes the tables of the two-aperture spectrum now, on the current
    /// rayon pool, instead of on first use (nothing for the three-slope
    /// model, which needs none). A run calls it before it spreads its work
    /// over the threads: a table first needed inside a parallel loop is
    /// built by one thread while the others wait for it (1.2 s of the 10 s
    /// of the full Fig. 5 on 2 threads, measured).
    pub fn tabulate(&self) {
        if self.three_slope.is_none() {
            self.table.tabulate();
            if let Some(t) = &self.crosswind {
                t.tabulate();
            }
        }
    }

    /// Two-sided temporal PSD P(ν), µm²/Hz, of the model selected (the
    /// two-aperture integral from its tables, or the three-slope model):
    /// the one spectrum the piston sequences are synthesised from.
    pub fn psd_um2_per_hz(&self, nu_hz: f64) -> f64 {
        if let Some(m) = &self.three_slope {
            return m.psd_um2_per_hz(nu_hz);
        }
        let nu = nu_hz.abs();
        let v = self.wind_mps;
        let Some(s_table) = &self.crosswind else {
            let bf = self.baseline_factor(nu);
            if bf == 0.0 {
                return 0.0;
            }
            return bf * self.table.g(nu / v) / v;
        };
        // P v = 4 sin²(a/2) G + 2 cos(a) S, a = 2πνB cos θ / v.
        let half_a = PI * self.baseline_m * self.wind_angle_rad.cos() * nu / v;
        let s = half_a.sin();
        let fx = nu / v;
        (4.0 * s * s * self.table.g(fx) + 2.0 * (2.0 * half_a).cos() * s_table.g(fx)) / v
    }

    /// Two-sided temporal PSD P(ν), µm²/Hz, of the two-aperture integral
    /// with the wind along the baseline, by direct quadrature (slow; the
    /// reference for the table).
    pub fn psd_direct_um2_per_hz(&self, nu_hz: f64) -> f64 {
        let nu = nu_hz.abs();
        let v = self.wind_mps;
        let bf = self.baseline_factor(nu);
        if bf == 0.0 {
            return 0.0;
        }
        bf * transverse_integral(&self.table.turb, self.table.aperture_m, nu / v) / v
    }

    /// Variance of the differential piston σ_p², µm², from the radial
    /// spectral integral `∫ 2πf Φ_opd A 2[1 − J0(2πBf)] df` (the angular
    /// average of the two-aperture term).
    pub fn variance_um2(&self) -> f64 {
        let turb = &self.table.turb;
        let k = turb.opd_psd_scale();
        let (d, b) = (self.table.aperture_m, self.baseline_m);
        if k == 0.0 || b == 0.0 {
            return 0.0;
        }
        let radial = |f: f64| {
            2.0 * PI
                * f
                * turb.opd_psd(f)
                * aperture_filter(f, d)
                * two_one_minus_j0(2.0 * PI * b * f)
        };
        // Near 0 the Kolmogorov integrand goes as f^{−2/3}: substitute f = u³.
        let f_a = LOW_SPLIT_TIMES_SCALE / b.max(d);
        let u_a = f_a.cbrt();
        let low = integrate_pieces(
            &|u: f64| radial(u * u * u) * 3.0 * u * u,
            &[0.0, u_a],
            tol(),
        );
        let f_max = F_MAX_TIMES_D / d;
        let mut br = vec![f_a];
        while br[br.len() - 1] * 2.0 < f_max {
            let x = br[br.len() - 1] * 2.0;
            br.push(x);
        }
        br.push(f_max);
        let body = integrate_pieces(&radial, &br, tol());
        // Tail: A → 4/(π⁴D³f³), 2(1 − J0) → 2.
        let tail = 2.0 * PI * k * 2.0 * 4.0 / (PI.powi(4) * d.powi(3))
            * (3.0 / 14.0)
            * f_max.powf(-14.0 / 3.0);
        low + body + tail
    }

    /// σ_p, µm.
    pub fn rms_um(&self) -> f64 {
        self.variance_um2().sqrt()
    }

    /// Low-frequency Kolmogorov asymptote of the two-aperture integral,
    /// `(cos²θ + 3/2 sin²θ) (2πB)² K I(11/6) v^{−1/3} ν^{−2/3}`.
    pub fn asymptote_low(&self, nu_hz: f64) -> f64 {
        let t = &self.table.turb;
        let v = self.wind_mps;
        let (sin, cos) = self.wind_angle_rad.sin_cos();
        (cos * cos + 1.5 * sin * sin)
            * (2.0 * PI * self.baseline_m).powi(2)
            * t.opd_psd_scale()
            * profile_integral(11.0 / 6.0)
            * v.powf(-1.0 / 3.0)
            * nu_hz.abs().powf(-2.0 / 3.0)
    }

    /// Middle Kolmogorov asymptote `2 K I(11/6) v^{5/3} ν^{−8/3}` (the
    /// two-aperture cosine averaged).
    pub fn asymptote_mid(&self, nu_hz: f64) -> f64 {
        let t = &self.table.turb;
        2.0 * t.opd_psd_scale()
            * profile_integral(11.0 / 6.0)
            * self.wind_mps.powf(5.0 / 3.0)
            * nu_hz.abs().powf(-8.0 / 3.0)
    }

    /// High-frequency asymptote `2 K I(10/3) 4/(π⁴D³) v^{14/3} ν^{−17/3}`
    /// (the Bessel oscillation and the cosine averaged).
    pub fn asymptote_high(&self, nu_hz: f64) -> f64 {
        let t = &self.table.turb;
        let d = self.table.aperture_m;
        2.0 * t.opd_psd_scale() * profile_integral(10.0 / 3.0) * 4.0 / (PI.powi(4) * d.powi(3))
            * self.wind_mps.powf(14.0 / 3.0)
            * nu_hz.abs().powf(-17.0 / 3.0)
    }

    /// Where the low and middle asymptotes cross: `v/(√2 π B)`, Hz.
    pub fn corner_low_hz(&self) -> f64 {
        self.wind_mps / (2f64.sqrt() * PI * self.baseline_m)
    }

    /// Where the middle and high asymptotes cross:
    /// `[4 I(10/3)/(π⁴ I(11/6))]^{1/3} v/D`, Hz.
    pub fn corner_high_hz(&self) -> f64 {
        let c = (4.0 * profile_integral(10.0 / 3.0) / (PI.powi(4) * profile_integral(11.0 / 6.0)))
            .cbrt();
        c * self.wind_mps / self.table.aperture_m
    }
}

/// `2[1 − J0(z)]`, the two-aperture factor `2[1 − cos(2π **B**·**f**)]`
/// averaged over the direction of **f**, at `z = 2πBf` (≥ 0): from its
/// series `z²/2 − z⁴/32 + z⁶/1152` below z = 10⁻², where `1 − J0(z)` would
/// lose ~log10(4/z²) digits to cancellation.
///
/// ```
/// use v2ref_core::piston::spectrum::two_one_minus_j0;
/// assert!((two_one_minus_j0(1e-3) / 5e-7 - 1.0).abs() < 1e-6);
/// assert!((two_one_minus_j0(1.0) - 2.0 * (1.0 - 0.765_197_686_557_966_6)).abs() < 1e-15);
/// ```
pub fn two_one_minus_j0(z: f64) -> f64 {
    if z < SMALL_Z_SERIES_BELOW {
        let z2 = z * z;
        2.0 * (z2 / 4.0 - z2 * z2 / 64.0 + z2 * z2 * z2 / 2304.0)
    } else {
        2.0 * (1.0 - bessel_j0(z))
    }
}

/// Variance of the differential piston σ_p² (µm²) for Kolmogorov turbulence
/// from the aperture-averaged structure function, computed in the pupil
/// plane independently of the spectrum:
///
/// `σ_p² = ∫ T(ρ) [D(|ρ + B|) − D(|ρ|)] d²ρ`,
///
/// T the pupil autocorrelation normalized to unit integral,
/// `T(ρ) = (2/π)[arccos u − u√(1−u²)] / (πD²/4)`, u = ρ/D (ρ ≤ D), and D the
/// OPD structure function (infinite outer scale only).
pub fn differential_piston_variance_from_structure_um2(
    turb: &Turbulence,
    aperture_m: f64,
    baseline_m: f64,
) -> f64 {
    let d = aperture_m;
    let area = PI * d * d / 4.0;
    let t_of = |rho: f64| {
        let u = (rho / d).min(1.0);
        (2.0 / PI) * (u.acos() - u * (1.0 - u * u).sqrt()) / area
    };
    let sf = |r: f64| turb.opd_structure_function_um2(r);
    let outer = |rho: f64| {
        let inner = |theta: f64| {
            let r = (rho * rho + baseline_m * baseline_m + 2.0 * rho * baseline_m * theta.cos())
                .max(0.0)
                .sqrt();
            sf(r) - sf(rho)
        };
        let ring = 2.0 * integrate_pieces(&inner, &[0.0, 0.5 * PI, PI], tol());
        rho * t_of(rho) * ring
    };
    integrate_pieces(&outer, &[0.0, 0.25 * d, 0.5 * d, 0.75 * d, d], tol())
}

/// The refusal of a wind direction for the three-slope model.
fn three_slope_angle_error(angle_deg: f64) -> crate::error::Error {
    crate::error::Error::Invalid {
        param: "wind_angle_deg",
        reason: format!(
            "the three-slope piston spectrum is defined for a wind along the baseline (0 or 180 deg), not {angle_deg} deg: use the two-aperture spectrum for other directions"
        ),
    }
}
