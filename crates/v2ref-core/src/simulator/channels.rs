//! The simulator in spectral channels: one model per channel, one optical
//! path difference for all of them.
//!
//! Channel j is the configuration's [`Inputs`] with the channel's own
//! spectrum ([`Channels::spectrum`]), its share of the photons
//! (`photons · q_j`, [`Channels::photon_shares`]) and the configuration's
//! spectral phase φ(σ) read on the channel's wavenumbers
//! ([`crate::bias::channels`]); everything else — source, baseline, scan,
//! detector, noise, piston — is the configuration's.
//!
//! **The shared piston.** The piston is a property of the optical path,
//! not of the wavelength: every channel's model draws the same piston
//! sequences (same spectrum, seed and scan speed, drawn once through
//! [`SharedSequences`]; one piston spectrum, tabulated once), and each
//! reads its fringe at its own wavenumbers through them. So the channels'
//! errors correlate.
//!
//! **The noise** is each pixel's own: in work unit u the channels draw
//! their photon and read noise one after the other from the unit's one
//! generator `unit_rng(seed, u)`, so channel 0 draws what a lone
//! [`simulate`](crate::simulator::simulate) of it draws, the channels'
//! noises are independent, and the answer is the same bits whatever the
//! thread count.

use crate::bias::channels::channel_observations;
use crate::error::{Error, Result};
use crate::formalism::channels::Channels;
use crate::formalism::estimator::BinWindow;
use crate::montecarlo::{fold_units, replicated_summary, Rng, RunningStats, Summary};
use crate::noise::calibrated::{expectation, CalibratedExpectation, Trials};
use crate::noise::scaled_interferogram;
use crate::noise::Formula;
use crate::piston::sequences::SharedSequences;
use crate::simulator::channel_moments::{ChannelMoments, NOISE_GROUPS};
use crate::simulator::estimate::{BiasConvention, RowEstimate, RowEstimator};
use crate::simulator::inputs::{Inputs, SpectrumInput};
use crate::simulator::rows::{Rows, ROWS_PER_UNIT};
use crate::simulator::Model;
use serde::Serialize;

/// The model of each channel of `inputs` split by `channels` (see the
/// module docs); the scan must resolve every channel
/// ([`Channels::check_sampling`]). One channel over the whole band is
/// `Model::new(inputs)` itself.
pub fn channel_models(inputs: &Inputs, channels: &Channels) -> Result<Vec<Model>> {
    inputs.validate()?;
    channels.check_parent(&inputs.spectrum.spectrum()?)?;
    channels.check_sampling(&inputs.sampling()?)?;
    let shared = SharedSequences::new();
    if channels.count() == 1 && channels.spectrum(0) == channels.parent() {
        return Ok(vec![Model::new(inputs)?.sharing_piston_sequences(&shared)]);
    }
    let parent = inputs.observation()?;
    // One piston spectrum for every channel (it depends on the baseline,
    // not the wavelength): its tables, seconds of quadratures, are
    // computed once for the run instead of once per channel.
    let piston_spectrum = match &inputs.piston {
        Some(p) => Some(p.spectrum(parent.baseline_m)?),
        None => None,
    };
    let observations = channel_observations(&parent, channels)?;
    observations
        .into_iter()
        .zip(channels.photon_shares())
        .map(|(obs, share)| {
            let (sigma, weight) = obs.spectrum.table().unwrap_or_default();
            let channel = Inputs {
                spectrum: SpectrumInput::Table {
                    wavenumber_per_um: sigma.to_vec(),
                    weight: weight.to_vec(),
                },
                photons: inputs.photons * share,
                // The phase is the configuration's, set on the observation
                // below (a channel's own peak-to-peak would re-centre it).
                dispersion_pp_rad: 0.0,
                ..inputs.clone()
            };
            let mut model = match &piston_spectrum {
                Some(spectrum) => Model::with_piston_spectrum(&channel, spectrum.clone())?,
                None => Model::new(&channel)?,
            };
            if !obs.phase.is_zero() {
                model.signal = scaled_interferogram(
                    &obs,
                    &model.sampling,
                    channel.photons,
                    channel.visibility,
                )?;
                model.observation = obs;
            }
            Ok(model.sharing_piston_sequences(&shared))
        })
        .collect()
}

/// Each channel's closed forms — mean and variance of its calibrated V1²
/// and V2² under its own photons and noise, without piston (their ratio is
/// the channel's SNR) — over `window`, with `formula`'s bias subtracted:
/// [`expectation`] on each model of [`channel_models`].
pub fn channel_expectations(
    models: &[Model],
    window: BinWindow,
    formula: Formula,
) -> Result<Vec<CalibratedExpectation>> {
    models
        .iter()
        .map(|m| expectation(&m.calibrated_setup(window), &m.noise, formula))
        .collect()
}

/// The answer of [`simulate_channels`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChannelRun {
    /// Rows per channel.
    pub rows: u64,
    /// Seed.
    pub seed: u64,
    /// Normalized V1² of each channel over the rows (errors from the spread
    /// between piston sequences when there is piston).
    pub v1_sq: Vec<Summary>,
    /// Normalized V2² of each channel.
    pub v2_sq: Vec<Summary>,
    /// V1² across channels: covariance, correlation, combinations.
    pub v1_sq_moments: ChannelMoments,
    /// V2² across channels.
    pub v2_sq_moments: ChannelMoments,
}

/// One unit's accumulators: per channel, per piston sequence (as
/// [`simulate`](crate::simulator::simulate) keeps them), and the sums
/// across channels.
#[derive(Clone)]
struct UnitPart {
    v1_sq: Vec<Vec<RunningStats>>,
    v2_sq: Vec<Vec<RunningStats>>,
    v1_moments: ChannelMoments,
    v2_moments: ChannelMoments,
}

/// Simulates `size.trials` rows of every channel of `models` (from
/// [`channel_models`]) from `size.seed`, estimates each over `window`
/// under `bias`, and reduces them per channel and across channels.
pub fn simulate_channels(
    models: &[Model],
    window: BinWindow,
    bias: BiasConvention,
    size: Trials,
) -> Result<ChannelRun> {
    check_models(models)?;
    let rows: Vec<Rows> = models
        .iter()
        .map(|m| m.rows(size.trials, size.seed, size.threads))
        .collect::<Result<_>>()
        .map_err(|e| e.renamed("rows", "trials"))?;
    let estimators: Vec<RowEstimator> = models
        .iter()
        .map(|m| RowEstimator::new(m, window, bias, true))
        .collect::<Result<_>>()?;
    let noise_free: Vec<_> = estimators
        .iter()
        .zip(&rows)
        .map(|(e, r)| e.estimate(&r.piston_free_row()))
        .collect::<Result<_>>()?;
    let piston = rows[0].has_piston();
    let groups = if piston {
        rows[0].sequences()
    } else {
        NOISE_GROUPS
    };
    let shifts = |pick: fn(&RowEstimate) -> f64| noise_free.iter().map(pick).collect();
    let empty = UnitPart {
        v1_sq: vec![vec![RunningStats::default(); rows[0].sequences()]; rows.len()],
        v2_sq: vec![vec![RunningStats::default(); rows[0].sequences()]; rows.len()],
        v1_moments: ChannelMoments::new(shifts(|e| e.v1_sq), groups),
        v2_moments: ChannelMoments::new(shifts(|e| e.v2_sq), groups),
    };
    let mut total = empty.clone();
    let work = |u: u64, rng: &mut Rng| {
        let mut part = empty.clone();
        estimate_unit(&rows, &estimators, u, rng, &mut part)?;
        crate::montecarlo::cancel::check()?;
        Ok(part)
    };
    fold_units(size.seed, 0..rows[0].units(), size.threads, work, |p| {
        total.merge(&p)
    })?;
    let summary = |g: &Vec<RunningStats>| match g.len() {
        1 => g[0].summary(),
        _ => replicated_summary(g),
    };
    Ok(ChannelRun {
        rows: size.trials,
        seed: size.seed,
        v1_sq: total.v1_sq.iter().map(summary).collect(),
        v2_sq: total.v2_sq.iter().map(summary).collect(),
        v1_sq_moments: total.v1_moments,
        v2_sq_moments: total.v2_moments,
    })
}

/// One row's values across the channels, kept from row to row of a unit
/// (the hot loop allocates nothing per row).
#[derive(Default)]
struct RowScratch {
    /// Each channel's estimates of the row.
    estimates: Vec<RowEstimate>,
    /// V1² − its shift, per channel.
    v1_deviations: Vec<f64>,
    /// V2² − its shift, per channel.
    v2_deviations: Vec<f64>,
}

/// Unit `u` of every channel: the channels draw their rows in channel
/// order from the unit's generator `rng`, then each row is estimated in
/// every channel and accumulated into `part`.
fn estimate_unit(
    rows: &[Rows],
    estimators: &[RowEstimator],
    u: u64,
    rng: &mut Rng,
    part: &mut UnitPart,
) -> Result<()> {
    let n = rows[0].samples();
    let unit_rows = rows[0].unit_rows(u)? as usize;
    let blocks: Vec<Vec<f64>> = rows
        .iter()
        .map(|r| {
            let mut block = Vec::with_capacity(unit_rows * n);
            r.fill_unit(u, rng, &mut block)?;
            Ok(block)
        })
        .collect::<Result<_>>()?;
    let first = u * ROWS_PER_UNIT;
    let mut scratch = RowScratch::default();
    for i in 0..unit_rows {
        let sequence = rows[0].sequence_of(first + i as u64)?;
        // Without piston the rows are independent: grouped by unit for the jackknife.
        let group = match rows[0].has_piston() {
            true => sequence,
            false => (u as usize) % NOISE_GROUPS,
        };
        scratch.estimates.clear();
        // The blocks hold whole rows of N samples, the estimators' length.
        let estimates = estimators.iter().zip(&blocks);
        scratch
            .estimates
            .extend(estimates.map(|(est, b)| est.estimate_checked_row(&b[i * n..(i + 1) * n])));
        part.push(sequence, group, &mut scratch);
    }
    Ok(())
}

impl UnitPart {
    /// One row's estimates, one per channel (`scratch.estimates`).
    fn push(&mut self, sequence: usize, group: usize, scratch: &mut RowScratch) {
        let e = &scratch.estimates;
        for (c, ec) in e.iter().enumerate() {
            self.v1_sq[c][sequence].push(ec.v1_sq);
            self.v2_sq[c][sequence].push(ec.v2_sq);
        }
        let v1 = e.iter().map(|x| x.v1_sq);
        let v2 = e.iter().map(|x| x.v2_sq);
        self.v1_moments
            .deviations_into(v1, &mut scratch.v1_deviations);
        self.v2_moments
            .deviations_into(v2, &mut scratch.v2_deviations);
        self.v1_moments
            .push_deviations(group, &scratch.v1_deviations);
        self.v2_moments
            .push_deviations(group, &scratch.v2_deviations);
    }

    /// Adds a later unit's accumulators (in unit order: the same bits
    /// whatever the thread count).
    fn merge(&mut self, p: &UnitPart) {
        let pairs = self.v1_sq.iter_mut().zip(&p.v1_sq);
        for (t, q) in pairs.chain(self.v2_sq.iter_mut().zip(&p.v2_sq)) {
            t.iter_mut().zip(q).for_each(|(a, b)| a.merge(b));
        }
        self.v1_moments.merge(&p.v1_moments);
        self.v2_moments.merge(&p.v2_moments);
    }
}

/// Refuses models that are not the channels of one configuration: none,
/// or differing in their scan or piston (their rows would not line up).
fn check_models(models: &[Model]) -> Result<()> {
    let Some(first) = models.first() else {
        return Err(Error::Invalid {
            param: "models",
            reason: "no channel: give the models of channel_models".into(),
        });
    };
    let same = |m: &Model| m.sampling == first.sampling && m.inputs.piston == first.inputs.piston;
    match models.iter().position(|m| !same(m)) {
        None => Ok(()),
        Some(j) => Err(Error::Invalid {
            param: "models",
            reason: format!(
                "channel {} has another scan or piston than channel 1: give the models of channel_models",
                j + 1
            ),
        }),
    }
}
