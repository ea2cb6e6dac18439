//! The answers per spectral channel of `bias`, `snr` and `simulate`
//! (docs/conventions.md §16), built once here from the physical inputs'
//! channels ([`Physical::channels`]): the CLI prints them, Python returns
//! them as dictionaries shaped as the JSON.
//!
//! Each channel's line starts with its place in the band
//! ([`ChannelPlace`](crate::report::channels::ChannelPlace)). Combinations across channels are the photon-weighted
//! mean `Σ_j q_j x_j` (q_j the channel's photon share): the weights of the
//! band's own photons, the same in `snr` and `simulate`.

use crate::bias::channels::channel_biases;
use crate::error::{Error, Result};
use crate::formalism::channels::Channels;
use crate::formalism::estimator::BinWindow;
use crate::noise::Formula;
use crate::parameters::Physical;
use crate::report::channels::{
    places, ChannelBiasLine, ChannelSnrLine, MeanSigma, SnrChannels, SnrCombination,
    COMBINATION_WEIGHTS, INDEPENDENT_NOTE,
};
use crate::simulator::channels::{channel_expectations, channel_models};

pub use crate::parameters::CHANNEL_INPUTS;

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
