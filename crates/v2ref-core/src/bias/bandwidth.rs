//! The effect of spectral bandwidth (paper, Section "Effect of spectral
//! bandwidth", Fig. 1): wide-band V1 and V2 against the monochromatic
//! visibility at the effective wavenumber, as functions of spatial frequency.

use crate::error::Result;
use crate::formalism::estimator::{wide_band, WideBand};
use crate::formalism::observation::{Frequency, Observation};
use crate::formalism::phase::SpectralPhase;
use crate::formalism::source::Source;
use crate::formalism::spectrum::Spectrum;

/// The noise-free estimates at each spatial frequency of `s_grid_cpas`.
pub fn curve(
    spectrum: &Spectrum,
    source: &Source,
    phase: &SpectralPhase,
    s_grid_cpas: &[f64],
) -> Result<Vec<WideBand>> {
    s_grid_cpas
        .iter()
        .map(|&s| {
            let obs = Observation::new(
                spectrum.clone(),
                source.clone(),
                Frequency::SpatialFreqCpas(s),
                phase.clone(),
            )?;
            Ok(wide_band(&obs))
        })
        .collect()
}

/// The largest value of `f` over `[lo, hi]`: a scan on `points` equally
/// spaced points, then golden-section refinement on the bracket around the
/// best one (to a bracket width of `tolerance::MINIMIZE_BRACKET_REL` (1e-9)
/// of the interval). Returns (x, f(x)).
/// Assumes `f` is unimodal within one grid step of its maximum, which the
/// caller ensures by a grid finer than the features of `f`.
pub fn locate_max(f: impl Fn(f64) -> f64, lo: f64, hi: f64, points: usize) -> (f64, f64) {
    let points = points.max(3);
    let step = (hi - lo) / (points - 1) as f64;
    let (mut best_i, mut best) = (0, f64::NEG_INFINITY);
    for i in 0..points {
        let v = f(lo + i as f64 * step);
        if v > best {
            best = v;
            best_i = i;
        }
    }
    let mut a = (lo + (best_i as f64 - 1.0) * step).max(lo);
    let mut b = (lo + (best_i as f64 + 1.0) * step).min(hi);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut c, mut d) = (b - g * (b - a), a + g * (b - a));
    let (mut fc, mut fd) = (f(c), f(d));
    while b - a > crate::tolerance::MINIMIZE_BRACKET_REL * (hi - lo) {
        if fc > fd {
            b = d;
            d = c;
            fd = fc;
            c = b - g * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + g * (b - a);
            fd = f(d);
        }
    }
    let x = 0.5 * (a + b);
    let fx = f(x);
    if fx >= best {
        (x, fx)
    } else {
        (lo + best_i as f64 * step, best)
    }
}
