//! `snr`: the closed-form expectations, variances and SNRs of V1² and V2²
//! under detector and photon noise.

use crate::error::{Error, Result};
use crate::formalism::estimator::BinWindow;
use crate::noise::Formula;
use crate::parameters::Physical;
use crate::report::noise::{Light, SnrReport};

/// The answer of `snr` for `p`, the exact statistics over `bins`, the
/// Appendix's by `formula`, per spectral channel when channels are given.
pub fn answer(p: &Physical, bins: BinWindow, formula: Formula) -> Result<SnrReport> {
    let noise = p.noise()?;
    let obs = p.observation()?;
    let sampling = p.sampling()?;
    let light = Light {
        photons: p.photons,
        visibility: p.visibility,
        noise,
    };
    let mut answer = SnrReport::new(&obs, p.record(&obs), &sampling, bins, light, formula)?;
    if let Some(w) = answer.window_exact.as_ref().filter(|w| w.stats.bins == 0) {
        return Err(Error::OutOfRange {
            param: "samples",
            value: sampling.samples() as f64,
            accepted: format!(
                "at least 3 samples: {} samples leave the {} window no bin, and its SNR has no meaning",
                sampling.samples(),
                w.window
            ),
        });
    }
    answer.channels = crate::commands::channels::snr_lines(p, bins, formula)?;
    Ok(answer)
}
