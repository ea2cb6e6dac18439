//! A dispersed synth set: the scan recorded in C spectral channels at once
//! ([`Channels`], `docs/conventions.md` §16), each channel a detector of
//! its own behind one optical path difference.
//!
//! - **The rows**: each scan is one row of C × N values, channel after
//!   channel (channel j's N samples at `j·N … (j+1)·N`, DFT order as a
//!   wide-band row): a `.npy` of shape (rows, C, N). Channel j's rows are
//!   drawn exactly as [`simulate_channels`](crate::simulator::channels::simulate_channels)
//!   draws them: in work unit u the channels draw one after the other, in
//!   channel order, from the unit's one generator `unit_rng(seed, u)`,
//!   through the piston sequences they share.
//! - **The sidecar** keeps the configuration's `inputs` (the whole band) and
//!   adds `channels`, one [`ChannelSidecar`] per channel: its wavenumber
//!   edges and response (which rebuild the [`Channels`] from the inputs'
//!   spectrum, [`Sidecar::channels`]), its effective wavelength and width,
//!   photon share, continuum, mean counts, and its own [`Truth`], made as a
//!   wide-band set's truth is, from the channel's model
//!   ([`channel_models`]) and a reference run of its own.
//! - **The top-level truth** is the whole band's: for one channel over the
//!   whole band it is that channel's (the set is then the wide-band set, bit
//!   for bit); for C > 1 the rows are not the whole band's, so it holds the
//!   whole band's closed forms alone (`reference_run.blocks` = 0), for
//!   reference: a dispersed set is scored channel by channel.

use crate::conformance::sidecar::{ChannelSidecar, DataFiles, Sidecar, Truth, FORMAT};
use crate::conformance::synth::{SetSize, STREAM_BATCH_UNITS};
use crate::conformance::truth::{truth_laid_out, TruthSize};
use crate::error::Result;
use crate::formalism::channels::Channels;
use crate::montecarlo::{try_run_unit_range, Rng};
use crate::simulator::channels::channel_models;
use crate::simulator::{Inputs, Model, Rows};

/// Computes each channel's truth (and the whole band's, see the module
/// docs), then streams the set's rows to `sink`, each row C × N values
/// channel after channel (the counts `c_i + M_i` of each channel with
/// `size.keep_continuum`); returns the sidecar, whose data files are named
/// `npy` and `csv`. `progress` counts rows: every channel's reference run,
/// then the set's rows.
///
/// One channel over the whole band ([`Channels::whole`]) is
/// [`synthesize`](crate::conformance::synth::synthesize) of `inputs`: the
/// same rows and truth, bit for bit. Refuses what `synth` refuses, the
/// channels of another spectrum than the inputs', a scan that does not
/// resolve every channel ([`channel_models`]), and a set of more than
/// [`SET_MAX_VALUES`](crate::bounds::SET_MAX_VALUES) values (C × N a row).
pub fn synthesize_channels(
    inputs: &Inputs,
    channels: &Channels,
    size: &SetSize,
    (npy, csv): (String, Option<String>),
    sink: &mut dyn FnMut(&[f64]) -> Result<()>,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Sidecar> {
    let models = channel_models(inputs, channels)?;
    let n = inputs.samples;
    crate::bounds::check_set_size(size.rows, models.len() * n, size.reference_blocks)?;
    let truth_size = TruthSize {
        rows: size.rows,
        seed: size.seed,
        reference_blocks: size.reference_blocks,
        threads: size.threads,
    };
    let truths = models
        .iter()
        .map(|m| truth_laid_out(m, truth_size, size.layout, progress))
        .collect::<Result<Vec<Truth>>>()?;
    let whole = Model::new(inputs)?;
    let truth = match truths.len() {
        1 => truths[0].clone(),
        _ => {
            let closed_only = TruthSize {
                reference_blocks: 0,
                ..truth_size
            };
            truth_laid_out(&whole, closed_only, size.layout, &|_| {})?
        }
    };
    let sets = models
        .iter()
        .map(|m| m.rows_in(size.layout, size.rows, size.seed, size.threads))
        .collect::<Result<Vec<Rows>>>()?;
    stream_channel_rows(&sets, size, sink, progress)?;
    let entries = channel_entries(&models, channels, truths);
    Ok(Sidecar {
        format: FORMAT.to_owned(),
        version: env!("CARGO_PKG_VERSION").to_owned(),
        data: DataFiles {
            npy,
            csv,
            rows: size.rows,
            samples: n,
            channels: Some(models.len()),
        },
        seed: size.seed,
        layout: sets[0].layout(),
        continuum_subtracted: !size.keep_continuum,
        sample_opd_um: whole.sample_opd_um(),
        continuum_photons: whole.signal.continuum.clone(),
        mean_counts_photons: whole.signal.mean_counts(),
        inputs: inputs.clone(),
        truth,
        members: None,
        channels: Some(entries),
    })
}

/// Each channel's entry of the sidecar.
fn channel_entries(
    models: &[Model],
    channels: &Channels,
    truths: Vec<Truth>,
) -> Vec<ChannelSidecar> {
    models
        .iter()
        .zip(truths)
        .enumerate()
        .map(|(j, (m, truth))| {
            let (lo, hi) = channels.edges_per_um()[j];
            ChannelSidecar {
                wavenumber_edges_per_um: [lo, hi],
                response: channels.responses()[j],
                wavelength_eff_um: 1.0 / truth.sigma_eff_per_um,
                bandwidth_um: 1.0 / lo - 1.0 / hi,
                photon_share: channels.photon_shares()[j],
                continuum_photons: m.signal.continuum.clone(),
                mean_counts_photons: m.signal.mean_counts(),
                truth,
            }
        })
        .collect()
}

/// Hands the rows of every channel to `sink` in row order, C × N values a
/// row, [`STREAM_BATCH_UNITS`] units at a time (generated in parallel;
/// the same bits whatever the thread count).
fn stream_channel_rows(
    sets: &[Rows],
    size: &SetSize,
    sink: &mut dyn FnMut(&[f64]) -> Result<()>,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<()> {
    let units = sets[0].units();
    let width = sets.len() * sets[0].samples();
    let mut first = 0;
    while first < units {
        let last = (first + STREAM_BATCH_UNITS).min(units);
        let blocks = try_run_unit_range(size.seed, first..last, size.threads, |u, rng| {
            unit_rows(sets, u, rng, size.keep_continuum)
        })?;
        for block in blocks {
            sink(&block)?;
            progress((block.len() / width) as u64);
        }
        first = last;
    }
    Ok(())
}

/// The rows of unit `u` of every channel, drawn in channel order from the
/// unit's generator `rng`, laid out row by row, channel after channel in
/// each row (the continuum of each channel added when `keep_continuum`).
fn unit_rows(sets: &[Rows], u: u64, rng: &mut Rng, keep_continuum: bool) -> Result<Vec<f64>> {
    let mut drawn = Vec::with_capacity(sets.len());
    for set in sets {
        let mut block = Vec::new();
        set.fill_unit(u, rng, &mut block)?;
        drawn.push(block);
    }
    let n = sets[0].samples();
    let rows = drawn[0].len() / n;
    let mut out = Vec::with_capacity(rows * n * sets.len());
    for i in 0..rows {
        for (set, block) in sets.iter().zip(&drawn) {
            let row = &block[i * n..(i + 1) * n];
            match keep_continuum {
                true => {
                    let continuum = &set.model().signal.continuum;
                    out.extend(row.iter().zip(continuum).map(|(m, c)| m + c));
                }
                false => out.extend_from_slice(row),
            }
        }
    }
    Ok(out)
}
