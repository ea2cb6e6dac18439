//! The lines per spectral channel of `bias`, `snr` and `simulate`
//! (built by [`crate::commands::channels`]): each channel's place in the
//! band, its biases, its closed-form mean, σ and SNR, and their
//! combination across channels.

use crate::bias::channels::ChannelBiases;
use crate::formalism::channels::Channels;
use crate::noise::snr_value::serialize_snr;
use serde::Serialize;

/// What the combinations across channels are, in the answers.
pub const COMBINATION_WEIGHTS: &str =
    "photon-weighted mean of the channels, weights q_j (each channel's share of the photons)";

/// One channel's place in the band.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ChannelPlace {
    /// Channel number, 1 at the shortest wavenumber (longest wavelength).
    pub channel: usize,
    /// Shortest wavelength of the channel, µm (1/σ⁺).
    pub wavelength_lo_um: f64,
    /// Longest wavelength of the channel, µm (1/σ⁻).
    pub wavelength_hi_um: f64,
    /// σ⁻, µm⁻¹.
    pub wavenumber_lo_per_um: f64,
    /// σ⁺, µm⁻¹.
    pub wavenumber_hi_per_um: f64,
    /// r_j, the channel's response as given (1 unless from a table).
    pub response: f64,
    /// q_j, the channel's share of the photons (Σ q_j = 1).
    pub photon_share: f64,
}

/// The place of each channel of `channels`.
pub fn places(channels: &Channels) -> Vec<ChannelPlace> {
    channels
        .edges_per_um()
        .iter()
        .zip(channels.responses())
        .zip(channels.photon_shares())
        .enumerate()
        .map(
            |(j, ((&(lo, hi), &response), &photon_share))| ChannelPlace {
                channel: j + 1,
                wavelength_lo_um: 1.0 / hi,
                wavelength_hi_um: 1.0 / lo,
                wavenumber_lo_per_um: lo,
                wavenumber_hi_per_um: hi,
                response,
                photon_share,
            },
        )
        .collect()
}

/// One channel's line of `bias`: its place and its biases
/// ([`channel_biases`](crate::bias::channels::channel_biases)).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ChannelBiasLine {
    /// Where the channel is.
    #[serde(flatten)]
    pub place: ChannelPlace,
    /// Its noise-free numbers: the infinite-scan estimates, the bandwidth,
    /// dispersion, finite-scan and integrating-detector biases.
    #[serde(flatten)]
    pub biases: ChannelBiases,
}

/// One estimator's closed-form mean, σ and SNR.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MeanSigma {
    /// Expected calibrated V² (the subtracted bias's formula).
    pub mean: f64,
    /// Its standard deviation per scan (None above the exact window's
    /// sample limit).
    pub sigma: Option<f64>,
    /// mean / σ ("infinite" without noise, "undefined" unknown).
    #[serde(serialize_with = "serialize_snr")]
    pub snr: f64,
}

impl MeanSigma {
    /// The mean, and σ and the SNR from the `variance` (None: unknown).
    pub fn new(mean: f64, variance: Option<f64>) -> MeanSigma {
        let sigma = variance.map(f64::sqrt);
        MeanSigma {
            mean,
            sigma,
            snr: sigma.map_or(f64::NAN, |s| mean / s),
        }
    }
}

/// One channel's line of `snr`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ChannelSnrLine {
    /// Where the channel is.
    #[serde(flatten)]
    pub place: ChannelPlace,
    /// The calibrated V1² of the channel under its photons.
    pub v1_sq: MeanSigma,
    /// The calibrated V2².
    pub v2_sq: MeanSigma,
}

/// The combination of the channels in `snr`, closed form.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SnrCombination {
    /// How the channels are combined ([`COMBINATION_WEIGHTS`]).
    pub weights: &'static str,
    /// `Σ q_j mean_j` and `σ = √(Σ q_j² σ_j²)`, the channels independent.
    pub v1_sq: MeanSigma,
    /// The same for V2².
    pub v2_sq: MeanSigma,
    /// What the σ assumes.
    pub note: &'static str,
}

/// What the closed-form combination's σ assumes.
pub const INDEPENDENT_NOTE: &str = "sigma assumes independent channels, as their photon and \
     detector noises are; the differential piston, shared by every channel, correlates them: \
     `simulate` with a fringe frequency measures the correlation and the honest sigma";

/// The channels' part of `snr`'s answer.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SnrChannels {
    /// One line per channel.
    pub channels: Vec<ChannelSnrLine>,
    /// Their combination.
    pub combined: SnrCombination,
}
