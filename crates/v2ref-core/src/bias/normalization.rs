//! The V2 normalization factor against the OPD stroke (paper, Section
//! "Effect of spectral bandwidth", Fig. 0).
//!
//! eq. `eq:estimateurs` divides V2² by `[Σ_k W(kδσ) δσ]²`, which tends to
//! (∫W dσ)² = 1 for long scans. Read for a real, sampled scan, the factor is
//! that sum over the bins the estimator actually sums (the positive
//! frequencies `k = 1 … ⌈N/2⌉ − 1`, [`crate::bias::finite_scan::WINDOW`]) of the
//! spectrum as the scan measures it — W convolved with the scan's sinc,
//! eq. `eq:sampled_V`. It equals the unnormalized V2 of an unresolved
//! source,
//!
//! `u(Δx) = |2 Σ_{k=1}^{⌈N/2⌉−1} B_k| / (N c)`,
//!
//! (B_k the DFT of the noise-free interferogram, c the continuum per
//! sample); with the factor, V2 of a 100% visibility source is exactly 1,
//! so Fig. 0 plots `|1 − u(Δx)|`. The sum of all bins is `N m_0 = N c`
//! exactly, so u differs from 1 only by what leaks into k = 0, the Nyquist
//! bin and the negative frequencies: the tails of the fringe packet cut by
//! the scan, which decay slowest for a spectrum with sharp edges (a flat
//! band, the paper's "most extreme example").
//!
//! A second reading, the factor as a Riemann sum of the unconvolved W on the
//! grid kδσ ([`crate::formalism::spectrum::Spectrum::grid_sums`]), is kept for
//! comparison: for a flat band it errs by up to δσ/Δσ_band, far above 0.2%
//! for any stroke of the figure, so it cannot be what Fig. 0 shows.

use crate::error::Result;
use crate::formalism::estimator::dft;
use crate::formalism::interferogram::SpectralNodes;
use crate::formalism::observation::{Frequency, Observation};
use crate::formalism::phase::SpectralPhase;
use crate::formalism::source::Source;
use crate::formalism::spectrum::Spectrum;
use num_complex::Complex64;

/// `|1 − u|` for every number of samples `n` in `samples` at spacing
/// `dx_um`, point source through `spectrum`. Stroke of entry i:
/// `samples[i] · dx_um`.
pub fn deviation_curve(spectrum: &Spectrum, dx_um: f64, samples: &[usize]) -> Result<Vec<f64>> {
    let obs = Observation::new(
        spectrum.clone(),
        Source::Point,
        Frequency::BaselineM(0.0),
        SpectralPhase::zero(),
    )?;
    if let Some(&n) = samples.iter().find(|&&n| n < 2) {
        return Err(crate::Error::OutOfRange {
            param: "samples",
            value: n as f64,
            accepted: "scans of 2 samples or more".into(),
        });
    }
    let n_max = samples.iter().copied().max().unwrap_or(2);
    let sampling = crate::formalism::interferogram::Sampling::new(n_max.max(2), dx_um, false)?;
    sampling.check_aliasing(&obs)?;
    // Every scan samples x = j δx, |j| ≤ N/2: one set of nodes for the
    // longest serves all, and the fringe at each j is computed once.
    let j_max = n_max / 2 + 1;
    let nodes = SpectralNodes::new(&obs, j_max as f64 * dx_um, None)?;
    let fringe: Vec<f64> = (0..=2 * j_max)
        .map(|i| nodes.fringe((i as f64 - j_max as f64) * dx_um))
        .collect();
    let at = |j: i64| fringe[(j + j_max as i64) as usize];
    Ok(samples
        .iter()
        .map(|&n| {
            let m: Vec<f64> = (0..n)
                .map(|i| {
                    let j = if i < n.div_ceil(2) {
                        i as i64
                    } else {
                        i as i64 - n as i64
                    };
                    at(j)
                })
                .collect();
            let b = dft(&m);
            let sum: Complex64 = (1..n.div_ceil(2)).map(|k| b[k]).sum();
            (1.0 - 2.0 * sum.norm() / n as f64).abs()
        })
        .collect())
}

/// The Riemann-sum reading: `|1 − Σ_k W(kδσ) δσ|` with δσ = 1/(N δx).
pub fn riemann_deviation(spectrum: &Spectrum, dx_um: f64, samples: &[usize]) -> Result<Vec<f64>> {
    samples
        .iter()
        .map(|&n| {
            let (s1, _) = spectrum.grid_sums(1.0 / (n as f64 * dx_um))?;
            Ok((1.0 - s1).abs())
        })
        .collect()
}

/// The smallest stroke from which the deviation stays below `threshold`
/// up to the end of the curve: `strokes[i]` for the first i after the last
/// point at or above it. `None` if the last point is at or above it.
pub fn threshold_stroke(strokes_um: &[f64], deviation: &[f64], threshold: f64) -> Option<f64> {
    match deviation.iter().rposition(|&d| d >= threshold) {
        None => strokes_um.first().copied(),
        Some(i) if i + 1 < strokes_um.len() => Some(strokes_um[i + 1]),
        Some(_) => None,
    }
}
