//! Why the three-slope spectrum gives less piston bias and scatter than
//! the two-aperture spectrum of the same site when the outer scale is
//! finite — a difference of the models, not of their normalization.
//!
//! Both spectra carry the same piston variance σ_p² (the three-slope model
//! is scaled to the two-aperture variance, [`crate::piston::three_slope`];
//! `tests/piston_models.rs` checks both against a pupil-plane quadrature
//! of the von Kármán variance). But a finite outer scale L0 lowers the
//! two-aperture spectrum only below about v/L0, where the turbulence loses
//! power, while the three-slope model keeps the slopes of an infinite outer
//! scale and scales the whole curve down to the lower variance: its high
//! frequencies — what moves the piston *within* a scan and makes the bias
//! and scatter of V² — lose as much as the variance does. On 18 m with
//! 0.45 m apertures and L0 = 25 m the variance is 24 times below the
//! Kolmogorov one, and so is the three-slope spectrum's power above 1 Hz.
//!
//! Measured with `v2ref piston --source point --fringe-hz 100:1000:3:log
//! --wind-mps 15 --seeing-arcsec 0.8 --seeing-wavelength-um 0.5
//! --outer-scale-m 25 --aperture-m 1.8 --baseline-m 40 --scans 2000` and
//! `--psd three-slope`: the structure function over a scan is 33, 49 and
//! 53 times less at 100, 316 and 1000 Hz; the V2 bias 49, 47 and 65 times
//! less, the V1 scatter 7.0, 7.5 and 8.1 times (√ of 33–53: 5.7–7.3).
//!
//! The measure used is the piston's structure function over one scan,
//! `D_p(T) = ⟨[p(t + T) − p(t)]²⟩ = ∫ 2[1 − cos 2πνT] P(ν) dν` (two-sided
//! P): how far the piston moves during a scan of duration T.

use crate::error::Result;
use crate::math::quadrature::{integrate_pieces, Tolerance};
use crate::piston::spectrum::{PistonPsdModel, PistonSpectrum};
use std::f64::consts::PI;

/// Decades below the lowest scale (the low corner, 1/T) where the
/// integral of `D_p(T)` starts: its integrand goes as ν^{4/3} there, so
/// the part left out is below 1e-8 of it.
const LOW_DECADES: f64 = 6.0;

/// Decades above the highest scale (the high corner, 1/T) where the
/// integral stops and the ν^{−17/3} tail is added in closed form.
const HIGH_DECADES: f64 = 3.0;

/// The two models of one site compared over one scan.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct PsdComparison {
    /// σ_p², µm², the variance both spectra carry.
    pub variance_um2: f64,
    /// The outer scale, m (None: infinite).
    pub outer_scale_m: Option<f64>,
    /// T, the duration of one scan, s.
    pub scan_time_s: f64,
    /// `D_p(T)` of the two-aperture spectrum, µm².
    pub two_aperture_within_scan_um2: f64,
    /// `D_p(T)` of the three-slope spectrum, µm².
    pub three_slope_within_scan_um2: f64,
}

impl PsdComparison {
    /// Both models of `spectrum`'s site (its wind along the baseline) over
    /// a scan of `scan_time_s` (> 0) seconds.
    pub fn new(spectrum: &PistonSpectrum, scan_time_s: f64) -> Result<PsdComparison> {
        crate::error::positive("scan_time_s", scan_time_s)?;
        let two = spectrum.with_model(PistonPsdModel::TwoAperture)?;
        let three = spectrum.with_model(PistonPsdModel::ThreeSlope)?;
        let corners = three
            .three_slope()
            .map_or([1.0, 1.0], |m| [m.corner_low_hz(), m.corner_high_hz()]);
        let within = |s: &PistonSpectrum| {
            structure_over_lag_um2(&|nu| s.psd_um2_per_hz(nu), scan_time_s, corners)
        };
        Ok(PsdComparison {
            variance_um2: two.variance_um2(),
            outer_scale_m: spectrum.turbulence().outer_scale_m(),
            scan_time_s,
            two_aperture_within_scan_um2: within(&two),
            three_slope_within_scan_um2: within(&three),
        })
    }

    /// How many times less the piston moves within a scan (in variance)
    /// under the three-slope model.
    pub fn ratio(&self) -> f64 {
        self.two_aperture_within_scan_um2 / self.three_slope_within_scan_um2
    }

    /// One line that says why, with the numbers.
    pub fn note(&self) -> String {
        let l0 = self
            .outer_scale_m
            .map_or("an infinite outer scale".to_owned(), |l| {
                format!("a {l:.3} m outer scale")
            });
        format!(
            "three-slope spectrum: the same piston variance as the two-aperture spectrum \
             ({:.4} um^2 with {l0}), but with the slopes of an infinite outer scale scaled \
             down to it, where the outer scale lowers only the slow piston: within one scan \
             ({:.4} s) its piston moves by {:.3e} um^2 (structure function) against {:.3e} \
             um^2, {:.3} times less: the piston's bias of V goes down about as much and its \
             scatter as the square root; the two-aperture spectrum is the physical one for a \
             finite outer scale",
            self.variance_um2,
            self.scan_time_s,
            self.three_slope_within_scan_um2,
            self.two_aperture_within_scan_um2,
            self.ratio()
        )
    }
}

/// `∫ 2[1 − cos 2πνT] P(ν) dν` over all ν (two-sided `psd`, µm²/Hz) for
/// the lag `lag_s`, by quadrature over log-spaced pieces (a factor 2 each)
/// around the spectrum's corners `[ν1, ν2]` and 1/T, with the ν^{−17/3}
/// tail beyond in closed form.
pub fn structure_over_lag_um2(psd: &dyn Fn(f64) -> f64, lag_s: f64, corners: [f64; 2]) -> f64 {
    let scales = [corners[0], corners[1], 1.0 / lag_s];
    let lowest = scales.iter().copied().fold(f64::INFINITY, f64::min);
    let highest = scales.iter().copied().fold(0.0, f64::max);
    let (lo, hi) = (
        lowest * 10f64.powf(-LOW_DECADES),
        highest * 10f64.powf(HIGH_DECADES),
    );
    let mut breaks = vec![lo];
    while breaks[breaks.len() - 1] * 2.0 < hi {
        breaks.push(breaks[breaks.len() - 1] * 2.0);
    }
    breaks.push(hi);
    let tol = Tolerance {
        abs: 0.0,
        rel: crate::tolerance::TURBULENCE_QUADRATURE_REL,
    };
    let one_sided = |nu: f64| {
        let s = (PI * nu * lag_s).sin();
        2.0 * 4.0 * s * s * psd(nu)
    };
    // Beyond hi the cosine averages out: 2 · 2 ∫_hi^∞ P, P ∝ ν^{−17/3}.
    let tail = 4.0 * psd(hi) * hi * 3.0 / 14.0;
    integrate_pieces(&one_sided, &breaks, tol) + tail
}
