//! `bias`: the noise-free wide-band V1 and V2 of one configuration, at an
//! infinite scan and, when asked (or when a stroke is given), from the
//! sampled finite scan.

use crate::error::Result;
use crate::formalism::estimator::BinWindow;
use crate::parameters::Physical;
use crate::report::bias::BiasReport;

/// Whether `bias` computes the finite scan: asked for, or implied by a
/// stroke.
pub fn wants_finite_scan(p: &Physical, finite_scan: bool) -> bool {
    finite_scan || p.stroke_um.is_some()
}

/// The answer of `bias` for `p`, the finite scan summed over `bins` when
/// [`wants_finite_scan`], with a line per spectral channel when channels
/// are given.
pub fn answer(p: &Physical, bins: BinWindow, finite_scan: bool) -> Result<BiasReport> {
    let obs = p.observation()?;
    let sampling = if wants_finite_scan(p, finite_scan) {
        Some(p.sampling()?)
    } else {
        None
    };
    let mut report = BiasReport::new(&obs, p.record(&obs), sampling.as_ref().map(|s| (s, bins)))?;
    report.channels = crate::commands::channels::bias_lines(p)?;
    Ok(report)
}
