//! The integrating detector (paper, Section "Sampled signals" and the
//! normalization paragraph of "Effect of spectral bandwidth").
//!
//! A detector that integrates each sample over its own OPD step δx
//! multiplies the fringe spectrum by `s(σ) = sinc(σ δx)`
//! ([`crate::formalism::interferogram::sinc`]), whose smallest value within the
//! sampled band is 2/π at the Nyquist frequency σ δx = ½. For
//! monochromatic light at p samples per fringe (δx = λ/p) the fringe
//! contrast falls by `sinc(1/p)` and the squared estimators must be
//! multiplied by `(π/p / sin(π/p))²`, π²/8 at p = 4.
//!
//! For a wide band the loss differs between the estimators, because they
//! weight the band differently (infinite scan, eq. `eq:estimateurs`):
//!
//! - V1²: `∫ W² s² |V|² dσ / ∫ W² |V|² dσ`,
//! - V2²: `|∫ W s V e^{iφ} dσ|² / |∫ W V e^{iφ} dσ|²`.
//!
//! Calibrated on a point source seen by the same detector, the loss cancels
//! to first order; what remains is the tilt that s(σ) gives W — a small
//! bias that grows where V changes fast across the band
//! ([`calibrated_bias`]).

use crate::bias::finite_scan::Bias;
use crate::error::{self, Error, Result};
use crate::formalism::estimator::Pair;
use crate::formalism::interferogram::sinc;
use crate::formalism::observation::Observation;
use num_complex::Complex64;

/// Monochromatic contrast of an integrating detector at `samples_per_fringe`:
/// `sinc(1/p)`.
pub fn monochromatic_contrast(samples_per_fringe: f64) -> f64 {
    sinc(1.0 / samples_per_fringe)
}

/// The factor that restores the squared estimators for monochromatic light:
/// `1/sinc²(1/p) = (π/p / sin(π/p))²`.
pub fn monochromatic_norm_factor(samples_per_fringe: f64) -> f64 {
    monochromatic_contrast(samples_per_fringe).powi(-2)
}

/// The squared-estimator loss factors (integrating over sampling detector)
/// of `obs` for sample spacing `dx_um` (> 0), infinite scan; refused where
/// the detector's sinc(σδx) washes the band's fringe out (no finite ratio).
pub fn wide_band_loss(obs: &Observation, dx_um: f64) -> Result<Pair> {
    error::positive("dx_um", dx_um)?;
    let features = obs.source.features_per_um();
    let vis2 = |s: f64| obs.source.visibility(s, obs.baseline_m).norm_sqr();
    let [num1, den1] = obs.spectrum.mean_w2_split(
        |s| {
            let v = vis2(s);
            [sinc(s * dx_um).powi(2) * v, v]
        },
        &features,
    );
    let amp = |with: bool| -> Complex64 {
        obs.spectrum.mean_w_split(
            |s| {
                let f = if with { sinc(s * dx_um) } else { 1.0 };
                obs.fringe_amplitude(s) * f
            },
            &features,
        )
    };
    finite_pair(Pair {
        v1_sq: num1 / den1,
        v2_sq: amp(true).norm_sqr() / amp(false).norm_sqr(),
    })
}

/// The pair, or the refusal of a spacing that leaves no finite ratio.
fn finite_pair(pair: Pair) -> Result<Pair> {
    if pair.v1_sq.is_finite() && pair.v2_sq.is_finite() {
        return Ok(pair);
    }
    Err(Error::Invalid {
        param: "dx_um",
        reason: "the integrating detector's sinc(σ δx) washes the fringe out at this spacing"
            .into(),
    })
}

/// `(V1²_int, V2²_int)`: the estimators of an integrating detector
/// calibrated on a point source seen by the same detector (infinite scan):
/// `∫W²s²|V|²/∫W²s²` and `|∫W s V e^{iφ}|²/(∫W s)²`; `dx_um` as in
/// [`wide_band_loss`].
pub fn calibrated(obs: &Observation, dx_um: f64) -> Result<Pair> {
    error::positive("dx_um", dx_um)?;
    let features = obs.source.features_per_um();
    let [num1, den1] = obs.spectrum.mean_w2_split(
        |s| {
            let f2 = sinc(s * dx_um).powi(2);
            [f2 * obs.source.visibility(s, obs.baseline_m).norm_sqr(), f2]
        },
        &features,
    );
    let num2 = obs
        .spectrum
        .mean_w_split(|s| obs.fringe_amplitude(s) * sinc(s * dx_um), &features);
    let den2 = obs.spectrum.mean_w(|s| sinc(s * dx_um));
    finite_pair(Pair {
        v1_sq: num1 / den1,
        v2_sq: num2.norm_sqr() / (den2 * den2),
    })
}

/// The bias of the calibrated integrating-detector estimators against the
/// sampling detector's, in visibility: `(√V1²_int − V1, √V2²_int − V2)`.
pub fn calibrated_bias(obs: &Observation, dx_um: f64) -> Result<Bias> {
    let int = calibrated(obs, dx_um)?;
    let wb = crate::formalism::estimator::wide_band(obs);
    Ok(Bias {
        v1: int.v1_sq.sqrt() - wb.v1,
        v2: int.v2_sq.sqrt() - wb.v2,
    })
}
