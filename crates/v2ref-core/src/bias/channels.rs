//! The deterministic biases of each spectral channel: the wide-band
//! formulas of §§3–5 applied to the channel's own spectrum
//! ([`crate::formalism::channels`]), one piece of code for both.
//!
//! Channel j is observed as `Observation { W_j, V, B, φ }`: its own
//! weight W_j, the same source and baseline, and the same spectral phase
//! φ(σ) — the instrument's dispersion at each wavenumber, not one
//! re-centred on the channel, so a channel away from σ0 sees the slope of
//! φ there as well as its curvature. Then, per channel,
//!
//! - bandwidth: `√V1²_j − |V(σ_eff,j)|`, `√V2²_j − |V(σ_eff,j)|`, with
//!   `V1²_j = ∫W_j²|V|²/∫W_j²`, `V2²_j = |∫W_j V e^{iφ}|²`
//!   ([`crate::formalism::estimator::wide_band`]). For a flat channel of
//!   width Δσ_j and a real visibility without phase, to second order,
//!   `V1²_j − V_mono² = g''(σ_j) Δσ_j²/24` (g = |V|²) and
//!   `V2²_j − V_mono² = V V''(σ_j) Δσ_j²/12` — the bias falls as Δσ_j²
//!   ([`second_order_bandwidth_bias`]);
//! - dispersion: the same two numbers with φ ≠ 0 against φ = 0;
//! - finite scan: [`crate::bias::finite_scan::finite_scan_bias`] on the
//!   channel's observation;
//! - integrating detector: [`crate::bias::integration::calibrated_bias`].
//!
//! The piston's bias has no closed form (§6 is a Monte Carlo): per channel
//! it comes from the simulator's shared-piston run.

use crate::bias::finite_scan::{finite_scan_bias, Bias, Method};
use crate::bias::integration::calibrated_bias;
use crate::error::Result;
use crate::formalism::channels::Channels;
use crate::formalism::estimator::{wide_band, WideBand};
use crate::formalism::interferogram::Sampling;
use crate::formalism::observation::{Frequency, Observation};
use crate::formalism::phase::SpectralPhase;
use serde::Serialize;

/// One channel's noise-free numbers.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ChannelBiases {
    /// The infinite-scan estimates of the channel (with its phase).
    pub wide_band: WideBand,
    /// Bandwidth bias (no phase): `√V²_j − |V(σ_eff,j)|`.
    pub bandwidth: Bias,
    /// Dispersion bias: `√V²_j(φ) − √V²_j(0)`.
    pub dispersion: Bias,
    /// Finite-scan bias of the channel's scan.
    pub finite_scan: Bias,
    /// Integrating-detector bias (zero for a sampling detector).
    pub integrating: Bias,
}

/// The observation of each channel of `obs` (see the module docs); the
/// channels must split `obs`'s spectrum ([`Channels::check_parent`]).
pub fn channel_observations(obs: &Observation, channels: &Channels) -> Result<Vec<Observation>> {
    channels.check_parent(&obs.spectrum)?;
    channels
        .spectra()
        .iter()
        .map(|spectrum| {
            Observation::new(
                spectrum.clone(),
                obs.source.clone(),
                Frequency::BaselineM(obs.baseline_m),
                obs.phase.clone(),
            )
        })
        .collect()
}

/// Every channel's biases for `obs` through `channels`, scanned by
/// `sampling` (the channels must split `obs`'s spectrum and the scan
/// resolve every channel, [`Channels::check_sampling`]).
pub fn channel_biases(
    obs: &Observation,
    channels: &Channels,
    sampling: &Sampling,
) -> Result<Vec<ChannelBiases>> {
    channels.check_parent(&obs.spectrum)?;
    channels.check_sampling(sampling)?;
    sampling.check_aliasing(obs)?;
    channel_observations(obs, channels)?
        .iter()
        .map(|o| one_channel(o, sampling))
        .collect()
}

fn one_channel(obs: &Observation, sampling: &Sampling) -> Result<ChannelBiases> {
    let with_phase = wide_band(obs);
    let no_phase = match obs.phase.is_zero() {
        true => with_phase,
        false => wide_band(&Observation {
            phase: SpectralPhase::zero(),
            ..obs.clone()
        }),
    };
    let integrating = match sampling.integrating() {
        true => calibrated_bias(obs, sampling.dx_um())?,
        false => Bias::default(),
    };
    Ok(ChannelBiases {
        wide_band: with_phase,
        bandwidth: Bias {
            v1: no_phase.v1 - no_phase.v_mono,
            v2: no_phase.v2 - no_phase.v_mono,
        },
        dispersion: Bias {
            v1: with_phase.v1 - no_phase.v1,
            v2: with_phase.v2 - no_phase.v2,
        },
        finite_scan: finite_scan_bias(obs, sampling, Method::Dft, None)?,
        integrating,
    })
}

/// The second-order bandwidth bias of a flat channel `[lo, hi]` (µm⁻¹) of
/// a source with real visibility `v(σ)` (no phase), on the squares:
/// `(V1² − V_mono², V2² − V_mono²) ≈ (g'' Δσ²/24, V V'' Δσ²/12)` at the
/// channel's centre, derivatives by central differences of step
/// `Δσ/8` (their error is of the order of the neglected Δσ⁴ term).
pub fn second_order_bandwidth_bias(v: impl Fn(f64) -> f64, lo: f64, hi: f64) -> (f64, f64) {
    let (c, w) = (0.5 * (lo + hi), hi - lo);
    let h = w / 8.0;
    let second = |f: &dyn Fn(f64) -> f64| (f(c + h) - 2.0 * f(c) + f(c - h)) / (h * h);
    let g2 = second(&|s| v(s) * v(s));
    let v2 = second(&|s| v(s));
    (g2 * w * w / 24.0, v(c) * v2 * w * w / 12.0)
}
