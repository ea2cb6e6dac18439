//! The answers per spectral channel of `bias`, `snr` and `simulate`
//! (docs/conventions.md §16), built once here from the physical inputs'
//! channels ([`Physical::channels`]): the CLI prints them, Python returns
//! them as dictionaries shaped as the JSON.
//!
//! Each channel's line starts with its place in the band
//! ([`ChannelPlace`]). Combinations across channels are the photon-weighted
//! mean `Σ_j q_j x_j` (q_j the channel's photon share): the weights of the
//! band's own photons, the same in `snr` and `simulate`.

use crate::bias::channels::{channel_biases, ChannelBiases};
use crate::error::{Error, Result};
use crate::formalism::channels::Channels;
use crate::formalism::estimator::BinWindow;
use crate::noise::snr_value::serialize_snr;
use crate::noise::Formula;
use crate::parameters::Physical;
use crate::simulator::channels::{channel_expectations, channel_models};
use serde::Serialize;

pub use crate::parameters::CHANNEL_INPUTS;

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

/// The channels of `p` and the name of the input that gave them, or None
/// (the wide band). A refusal of the channels by a later check names that
/// input (`renamed`).
pub fn given(p: &Physical) -> Result<Option<(Channels, &'static str)>> {
    let channels = p.channels()?;
    Ok(channels.map(|c| (c, p.channel_input().expect("channels were given"))))
}

/// `e` naming the channel input `input` where it names `channels`.
pub fn renamed(e: Error, input: &'static str) -> Error {
    crate::parameters::renamed_channels(e, input)
}

/// One channel's line of `bias`: its place and its biases
/// ([`channel_biases`]).
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

/// The lines of `bias` for `p`'s channels, or None without channels; the
/// finite-scan bias of each channel is its scan's (`p.sampling()`).
pub fn bias_lines(p: &Physical) -> Result<Option<Vec<ChannelBiasLine>>> {
    let Some((channels, input)) = given(p)? else {
        return Ok(None);
    };
    let obs = p.observation()?;
    let sampling = p.sampling()?;
    let biases = channel_biases(&obs, &channels, &sampling).map_err(|e| renamed(e, input))?;
    let lines = places(&channels)
        .into_iter()
        .zip(biases)
        .map(|(place, biases)| ChannelBiasLine { place, biases })
        .collect();
    Ok(Some(lines))
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
    fn new(mean: f64, variance: Option<f64>) -> MeanSigma {
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

/// The channels' part of `snr` for `p` over `window`, `formula`'s bias
/// subtracted ([`channel_expectations`]), or None without channels.
pub fn snr_lines(p: &Physical, window: BinWindow, formula: Formula) -> Result<Option<SnrChannels>> {
    let Some((channels, input)) = given(p)? else {
        return Ok(None);
    };
    let inputs = p.inputs()?;
    let models = channel_models(&inputs, &channels).map_err(|e| renamed(e, input))?;
    let expected = channel_expectations(&models, window, formula)?;
    let lines: Vec<ChannelSnrLine> = places(&channels)
        .into_iter()
        .zip(&expected)
        .map(|(place, e)| ChannelSnrLine {
            place,
            v1_sq: MeanSigma::new(e.mean_v1_sq, e.var_v1_sq),
            v2_sq: MeanSigma::new(e.mean_v2_sq, e.var_v2_sq),
        })
        .collect();
    let q = channels.photon_shares();
    let combine = |pick: fn(&ChannelSnrLine) -> MeanSigma| {
        let mean = lines.iter().zip(q).map(|(l, q)| q * pick(l).mean).sum();
        let variance: Option<f64> = lines
            .iter()
            .zip(q)
            .map(|(l, q)| pick(l).sigma.map(|s| (q * s).powi(2)))
            .sum();
        MeanSigma::new(mean, variance)
    };
    let combined = SnrCombination {
        weights: COMBINATION_WEIGHTS,
        v1_sq: combine(|l| l.v1_sq),
        v2_sq: combine(|l| l.v2_sq),
        note: INDEPENDENT_NOTE,
    };
    Ok(Some(SnrChannels {
        channels: lines,
        combined,
    }))
}
