//! `simulate` per spectral channel: the shared-piston Monte Carlo of
//! every channel at once ([`simulate_channels`]), each channel's
//! statistics, the correlation of the channels' errors and the honest σ
//! of their combination against the σ that independent channels would
//! give (docs/conventions.md §16).

use super::channels::renamed;
use crate::error::{Error, Result};
use crate::formalism::channels::Channels;
use crate::montecarlo::Summary;
use crate::noise::calibrated::Trials;
use crate::noise::Formula;
use crate::parameters::Physical;
use crate::report::channels::{places, ChannelPlace, COMBINATION_WEIGHTS};
use crate::report::simulator::{check_trials, Estimation};
use crate::simulator::channel_moments::ChannelMoments;
use crate::simulator::channels::{channel_models, simulate_channels};
use crate::simulator::estimate::BiasConvention;
use crate::simulator::Inputs;
use serde::Serialize;

/// One channel's line of `simulate`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChannelSimulateLine {
    /// Where the channel is.
    #[serde(flatten)]
    pub place: ChannelPlace,
    /// Its calibrated V1² over the rows (errors from the spread between
    /// piston sequences when there is piston).
    pub v1_sq: Summary,
    /// Its calibrated V2².
    pub v2_sq: Summary,
}

/// One estimator across the channels: their correlation and the
/// photon-weighted combination.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Combined {
    /// The correlation matrix of the channels' values per row, C × C.
    pub correlation: Vec<Vec<f64>>,
    /// `Σ q_j mean_j`.
    pub mean: f64,
    /// The combination's variance per row, measured: `qᵀ Σ q` with Σ the
    /// channels' covariance.
    pub variance: f64,
    /// Its jackknife standard error over the groups of rows.
    pub stderr_variance: f64,
    /// √variance: the honest σ of the combination.
    pub sigma: f64,
    /// The variance if the channels were independent, `Σ q_j² Σ_jj`
    /// (σ²/C for C equal channels).
    pub independent_variance: f64,
    /// √independent_variance: what ignoring the shared piston claims.
    pub independent_sigma: f64,
    /// sigma / independent_sigma: 1 for independent channels, up to √C
    /// when the piston dominates.
    pub sigma_ratio: f64,
}

impl Combined {
    fn new(moments: &ChannelMoments, per_channel: &[Summary], q: &[f64]) -> Combined {
        let (variance, stderr_variance) = moments.combined_variance(q);
        let independent_variance = moments.independent_variance(q);
        Combined {
            correlation: moments.correlation(),
            mean: per_channel.iter().zip(q).map(|(s, q)| q * s.mean).sum(),
            variance,
            stderr_variance,
            sigma: variance.sqrt(),
            independent_variance,
            independent_sigma: independent_variance.sqrt(),
            sigma_ratio: (variance / independent_variance).sqrt(),
        }
    }
}

/// What the combination's σ is, in the answer.
pub const MEASURED_NOTE: &str = "sigma is measured with the channels' correlation (the \
     differential piston is shared by every channel); independent_sigma is what independent \
     channels would give (sigma/sqrt(C) for C equal channels)";

/// The answer of `simulate` with channels.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChannelSimulateReport {
    /// Formula of the subtracted bias (exact).
    pub formula: Formula,
    /// The bins summed.
    pub bins: String,
    /// Where the photon bias takes the mean counts from.
    pub bias: BiasConvention,
    /// N.
    pub samples: usize,
    /// Rows per channel.
    pub trials: u64,
    /// Seed.
    pub seed: u64,
    /// One line per channel.
    pub channels: Vec<ChannelSimulateLine>,
    /// How the channels are combined ([`COMBINATION_WEIGHTS`]).
    pub weights: &'static str,
    /// V1² across the channels.
    pub combined_v1_sq: Combined,
    /// V2² across the channels.
    pub combined_v2_sq: Combined,
    /// What the combined σ is ([`MEASURED_NOTE`]).
    pub note: &'static str,
    /// Every physical input of the whole band.
    pub inputs: Inputs,
}

/// Runs `simulate` over the `channels` of `p` (given by the input
/// `input`), estimated as `estimation`, `size.trials` rows per channel.
/// The channels' Monte Carlo subtracts the exact bias: the `published`
/// formula is refused, not ignored.
pub fn simulate(
    p: &Physical,
    (channels, input): (&Channels, &'static str),
    estimation: Estimation,
    size: Trials,
) -> Result<ChannelSimulateReport> {
    check_trials(size.trials)?;
    if estimation.formula != Formula::Exact {
        return Err(Error::Invalid {
            param: "formula",
            reason: format!(
                "the channels' Monte Carlo subtracts the exact bias; give formula exact with {input}"
            ),
        });
    }
    let inputs = p.inputs()?;
    let models = channel_models(&inputs, channels).map_err(|e| renamed(e, input))?;
    let run = simulate_channels(&models, estimation.window, estimation.bias, size)?;
    let q = channels.photon_shares();
    let lines = places(channels)
        .into_iter()
        .zip(run.v1_sq.iter().zip(&run.v2_sq))
        .map(|(place, (v1, v2))| ChannelSimulateLine {
            place,
            v1_sq: *v1,
            v2_sq: *v2,
        })
        .collect();
    Ok(ChannelSimulateReport {
        formula: estimation.formula,
        bins: estimation.window.name().to_owned(),
        bias: estimation.bias,
        samples: inputs.samples,
        trials: run.rows,
        seed: run.seed,
        channels: lines,
        weights: COMBINATION_WEIGHTS,
        combined_v1_sq: Combined::new(&run.v1_sq_moments, &run.v1_sq, q),
        combined_v2_sq: Combined::new(&run.v2_sq_moments, &run.v2_sq, q),
        note: MEASURED_NOTE,
        inputs,
    })
}
