//! The oracle route for a dispersed set: C spectral channels per scan
//! ([`Channels`]), each row C × N values channel after channel, a truth
//! and a verdict per channel under one family-wise threshold
//! ([`crate::conformance::channels`], [`crate::conformance::channel_score`]).

use super::{check_set_memory, Set};
use crate::conformance::channel_score::{score_channels, ChannelScoreReport};
use crate::conformance::channels::synthesize_channels;
use crate::conformance::estimate::{BiasConvention, RowEstimate, RowEstimator};
use crate::conformance::score::{Estimates, DEFAULT_ALPHA};
use crate::conformance::sidecar::ConventionTruth;
use crate::conformance::synth::SetSize;
use crate::conformance::truth::default_reference_blocks;
use crate::error::{Error, Result};
use crate::formalism::channels::Channels;
use crate::formalism::estimator::BinWindow;
use crate::simulator::channels::channel_models;
use crate::simulator::{Inputs, Model, RowLayout};

/// A dispersed set's channels and the model of each.
#[derive(Debug, Clone)]
pub(super) struct Dispersed {
    channels: Channels,
    models: Vec<Model>,
}

impl Set {
    /// `rows` scans of `inputs` recorded in `channels` (cut from the
    /// inputs' spectrum), drawn with `seed`, continuum subtracted: each row
    /// holds C × N values, channel after channel; each channel has its own
    /// truth (the default reference run per channel: 8 blocks, 16 with
    /// piston). The same bits as `v2ref synth` of the same inputs,
    /// channels, rows and seed, whatever the thread count; one channel over
    /// the whole band ([`Channels::whole`]) is [`Set::synthesize`] bit for
    /// bit. Refuses what [`Set::synthesize`] refuses (with C × N values a
    /// row), channels of another spectrum, and a scan that leaves a channel
    /// without a DFT bin.
    ///
    /// ```
    /// use v2ref_core::oracle::{BiasConvention, BinWindow, Channels, Estimates, Inputs, Set};
    ///
    /// let inputs = Inputs { samples: 128, photons: 200.0, ..Inputs::default() };
    /// let three = Channels::equal(&inputs.spectrum.spectrum()?, 3)?;
    /// let set = Set::synthesize_channels(&inputs, &three, 500, 7)?;
    /// assert_eq!((set.channels(), set.rows().next().unwrap().len()), (3, 3 * 128));
    ///
    /// // v2ref's own estimates, channel by channel, pass the set's test.
    /// let (window, bias) = (BinWindow::Band, BiasConvention::Model);
    /// let per_channel = set.reference_channel_estimates(window, bias)?;
    /// let v2_sq: Vec<Vec<f64>> =
    ///     per_channel.iter().map(|c| c.iter().map(|r| r.v2_sq).collect()).collect();
    /// let estimates: Vec<Estimates> =
    ///     v2_sq.iter().map(|x| Estimates::default().v2_sq(x)).collect();
    /// let report = set.score_channels(window, bias, &estimates)?;
    /// assert!(report.pass, "{report}");
    /// assert_eq!(report.tests, 3 * 2); // 3 channels × (mean, variance) of V2²
    /// # Ok::<(), v2ref_core::Error>(())
    /// ```
    pub fn synthesize_channels(
        inputs: &Inputs,
        channels: &Channels,
        rows: u64,
        seed: u64,
    ) -> Result<Set> {
        let model = Model::new(inputs)?;
        let models = channel_models(inputs, channels)?;
        let width = channels.count() * inputs.samples;
        let blocks = default_reference_blocks(inputs.piston.is_some());
        crate::bounds::check_set_size(rows, width, blocks)?;
        check_set_memory(rows, width)?;
        let size = SetSize {
            rows,
            seed,
            reference_blocks: blocks,
            threads: 0,
            keep_continuum: false,
            layout: RowLayout::default().into(),
        };
        let mut values = Vec::new();
        let count = (rows * width as u64) as usize; // at most SET_MAX_VALUES
        let what = || format!("values of {rows} rows of {width} values");
        crate::bounds::reserve(&mut values, count, "rows", &what)?;
        let mut sink = |block: &[f64]| {
            values.extend_from_slice(block);
            Ok(())
        };
        let names = ("set.npy".to_owned(), None);
        let sidecar = synthesize_channels(inputs, channels, &size, names, &mut sink, &|_| {})?;
        Ok(Set {
            model,
            values,
            sidecar,
            dispersed: Some(Dispersed {
                channels: channels.clone(),
                models,
            }),
        })
    }

    /// C, the spectral channels of each row: 1 for a wide-band set.
    pub fn channels(&self) -> usize {
        self.dispersed.as_ref().map_or(1, |d| d.models.len())
    }

    /// The channels of a dispersed set (None for a wide-band set).
    pub fn spectral_channels(&self) -> Option<&Channels> {
        self.dispersed.as_ref().map(|d| &d.channels)
    }

    /// Channel `j`'s samples of each row (N values each; j from 0, in
    /// increasing wavenumber); refuses (parameter `channel`) a channel the
    /// set does not have.
    pub fn channel_rows(&self, j: usize) -> Result<impl Iterator<Item = &[f64]> + '_> {
        crate::bounds::check_index("channel", j as u64, self.channels() as u64, "channels")?;
        let n = self.samples();
        Ok(self.rows().map(move |row| &row[j * n..(j + 1) * n]))
    }

    /// The truth of channel `j` (from 0) under `window` and `bias`: for a
    /// wide-band set, channel 0 is the set ([`Set::expected`]). Refuses
    /// (parameter `channel`) a channel the set does not have, and (parameter
    /// `window`) a window the channel's truth lacks.
    pub fn expected_channel(
        &self,
        j: usize,
        window: BinWindow,
        bias: BiasConvention,
    ) -> Result<&ConventionTruth> {
        crate::bounds::check_index("channel", j as u64, self.channels() as u64, "channels")?;
        let Some(list) = &self.sidecar.channels else {
            return self.expected(window, bias);
        };
        list[j].truth.windows.iter().find(|w| w.bins == window).and_then(|w| w.conventions.iter().find(|c| c.bias == bias)).ok_or_else(|| Error::Invalid {
            param: "window",
            reason: format!(
                "channel {} has no truth for the {} window under the {} convention (its calibrator has no fringe in those bins)",
                j + 1,
                window.name(),
                bias.name()
            ),
        })
    }

    /// v2ref's own per-row estimates of each channel under `window` and
    /// `bias` (one list per channel, in channel order; channel j's model
    /// from [`channel_models`]).
    pub fn reference_channel_estimates(
        &self,
        window: BinWindow,
        bias: BiasConvention,
    ) -> Result<Vec<Vec<RowEstimate>>> {
        let Some(d) = &self.dispersed else {
            return Ok(vec![self.reference_estimates(window, bias)?]);
        };
        let mut out = Vec::with_capacity(d.models.len());
        for (j, model) in d.models.iter().enumerate() {
            let est = RowEstimator::new(model, window, bias, true)?;
            let rows: Vec<f64> = self.channel_rows(j)?.flatten().copied().collect();
            out.push(est.estimate_rows(&rows, 0)?);
        }
        Ok(out)
    }

    /// Scores a pipeline's per-row estimates of each channel
    /// (`estimates[j]` for channel j, each naming V1², V2² or both)
    /// against each channel's truth of `window` under `bias`, at
    /// [`DEFAULT_ALPHA`] shared by every test of every channel
    /// ([`score_channels`]). Refuses a number of estimates other than
    /// [`Set::channels`] and a channel with no estimator.
    pub fn score_channels(
        &self,
        window: BinWindow,
        bias: BiasConvention,
        estimates: &[Estimates<'_>],
    ) -> Result<ChannelScoreReport> {
        let truths = (0..self.channels())
            .map(|j| self.expected_channel(j, window, bias))
            .collect::<Result<Vec<_>>>()?;
        score_channels(estimates, &truths, self.len() as u64, DEFAULT_ALPHA)
    }

    /// Refuses a dispersed set of more than one channel where the
    /// wide-band methods are called on it.
    pub(super) fn check_wide_band(&self) -> Result<()> {
        match self.channels() {
            1 => Ok(()),
            c => Err(Error::Invalid {
                param: "channels",
                reason: format!(
                    "the set has {c} channels; use expected_channel, reference_channel_estimates and score_channels"
                ),
            }),
        }
    }
}
