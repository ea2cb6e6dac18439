//! §6: the fringe of a source per unit continuum, m(x) (x the OPD in µm),
//! tabulated so that the piston Monte Carlo can read it at any OPD the
//! piston pushes a sample to.
//!
//! # Tabulated fringe
//!
//! The fringe `m(x) = Re Σ_j a_j e^{2πiσ_j x}` ([`SpectralNodes`]) is written
//! `Re[e^{2πiσ_c x} a(x)]` with the slowly varying complex envelope
//! `a(x) = Σ_j a_j e^{2πi(σ_j − σ_c)x}`, tabulated with its derivative and
//! interpolated by cubic Hermite polynomials ([`FringeTable`]); the grid step
//! bounds the interpolation error below 1e-12 of the fringe amplitude.

use crate::error::{self, Result};
use crate::formalism::interferogram::SpectralNodes;
use crate::formalism::observation::Observation;
use num_complex::Complex64;
use std::f64::consts::PI;

/// Largest OPD (µm) a scan may reach with its piston: beyond, the fringe
/// table would cost more memory and time than any realistic case needs.
pub const MAX_OPD_UM: f64 = 5000.0;

/// The fringe per unit continuum, `m(x) = Re Σ_j a_j e^{2πiσ_j x}`, tabulated
/// for fast evaluation on |x| ≤ `max_opd_um` (see the module docs).
#[derive(Debug, Clone)]
pub struct FringeTable {
    nodes: SpectralNodes,
    sigma_c: f64,
    x0: f64,
    h: f64,
    value: Vec<Complex64>,
    slope: Vec<Complex64>,
    carrier: Vec<Complex64>,
}

/// Largest carrier phase 2πσ_c h across one grid step, rad: the step's
/// carrier rotation is evaluated by its Taylor series to θ⁷, whose error
/// θ⁸/8! stays below 1e-15 there.
const MAX_STEP_PHASE: f64 = 0.06;

/// Interpolation error target of [`FringeTable`], relative to Σ|a_j|.
const TABLE_REL: f64 = crate::tolerance::FRINGE_TABLE_REL;

impl FringeTable {
    /// The table of the (unfiltered) fringe of `obs` over |x| ≤ `max_opd_um`.
    pub fn new(obs: &Observation, max_opd_um: f64) -> Result<FringeTable> {
        error::positive("max_opd", max_opd_um)?;
        // SpectralNodes sizes its Gauss–Legendre panels (16 points) to a
        // quarter fringe at the largest OPD it is given; a whole fringe per
        // panel already integrates e^{2πiσx} to ~1e-20 (the error of the
        // 16-point rule on one cycle is ~π³²/32!), so ask for a quarter of
        // the range: four times fewer nodes (checked against the full set
        // and the adaptive oracle in tests/piston.rs).
        let nodes = SpectralNodes::new(obs, 0.25 * max_opd_um, None)?;
        let (lo, hi) = nodes
            .sigma_per_um
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &s| {
                (a.min(s), b.max(s))
            });
        let sigma_c = if lo.is_finite() { 0.5 * (lo + hi) } else { 0.0 };
        let dmax = if lo.is_finite() { 0.5 * (hi - lo) } else { 0.0 };
        // Cubic Hermite error ≤ h⁴/384 · max|a''''| ≤ h⁴/384 · (2π dmax)⁴ Σ|a_j|.
        let h = if dmax > 0.0 {
            ((384.0 * TABLE_REL).powf(0.25) / (2.0 * PI * dmax)).min(0.5)
        } else {
            0.5
        };
        let h = if sigma_c > 0.0 {
            h.min(MAX_STEP_PHASE / (2.0 * PI * sigma_c))
        } else {
            h
        };
        let n = (2.0 * max_opd_um / h).ceil() as usize + 1;
        let h = 2.0 * max_opd_um / (n - 1) as f64;
        let x0 = -max_opd_um;
        let mut value = vec![Complex64::new(0.0, 0.0); n];
        let mut slope = vec![Complex64::new(0.0, 0.0); n];
        // Per node, march e^{2πiδ_j x} along the grid by complex
        // multiplication, re-anchored exactly every RESYNC steps.
        const RESYNC: usize = 128;
        let every = crate::montecarlo::cancel::stride(n);
        for (j, (&s, &a)) in nodes.sigma_per_um.iter().zip(&nodes.amplitude).enumerate() {
            if j % every == 0 {
                crate::montecarlo::cancel::check()?;
            }
            let d = s - sigma_c;
            let w = 2.0 * PI * d;
            let step = Complex64::from_polar(1.0, w * h);
            let da = a * Complex64::new(0.0, w);
            let mut phase = Complex64::new(0.0, 0.0);
            for i in 0..n {
                if i % RESYNC == 0 {
                    phase = Complex64::from_polar(1.0, w * (x0 + i as f64 * h));
                } else {
                    phase *= step;
                }
                value[i] += a * phase;
                slope[i] += da * phase;
            }
        }
        let carrier = (0..n)
            .map(|i| Complex64::from_polar(1.0, 2.0 * PI * sigma_c * (x0 + i as f64 * h)))
            .collect();
        Ok(FringeTable {
            nodes,
            sigma_c,
            x0,
            h,
            value,
            slope,
            carrier,
        })
    }

    /// The nodes the table was built from.
    pub fn nodes(&self) -> &SpectralNodes {
        &self.nodes
    }

    /// Half-width of the tabulated OPD range, µm.
    pub fn max_opd_um(&self) -> f64 {
        -self.x0
    }

    /// m(x) per unit continuum at OPD `x_um` (beyond the table, the direct
    /// node sum).
    #[inline]
    pub fn fringe(&self, x_um: f64) -> f64 {
        let t = (x_um - self.x0) / self.h;
        let n = self.value.len();
        if !(t >= 0.0 && t < (n - 1) as f64) {
            return self.nodes.fringe(x_um);
        }
        let i = t as usize;
        let u = t - i as f64;
        let u2 = u * u;
        let u3 = u2 * u;
        let h00 = 2.0 * u3 - 3.0 * u2 + 1.0;
        let h10 = (u3 - 2.0 * u2 + u) * self.h;
        let h01 = 3.0 * u2 - 2.0 * u3;
        let h11 = (u3 - u2) * self.h;
        let a = self.value[i] * h00
            + self.slope[i] * h10
            + self.value[i + 1] * h01
            + self.slope[i + 1] * h11;
        // e^{2πiσ_c x} = carrier_i · e^{iθ}, θ = 2πσ_c u h ≤ MAX_STEP_PHASE.
        let th = 2.0 * PI * self.sigma_c * u * self.h;
        let t2 = th * th;
        let cos = 1.0 - t2 / 2.0 * (1.0 - t2 / 12.0 * (1.0 - t2 / 30.0 * (1.0 - t2 / 56.0)));
        let sin = th * (1.0 - t2 / 6.0 * (1.0 - t2 / 20.0 * (1.0 - t2 / 42.0)));
        let c = self.carrier[i];
        let (zr, zi) = (c.re * cos - c.im * sin, c.re * sin + c.im * cos);
        a.re * zr - a.im * zi
    }
}
