//! `synth`: a test set of interferograms and its truth. The rows are
//! handed to the edge's sink block by block (the CLI writes them to files,
//! Python collects them in an array), and the sidecar that states the
//! truth is built here once.

use crate::conformance::sidecar::{DataFiles, Sidecar, Truth, FORMAT};
use crate::conformance::truth::{truth_laid_out, TruthSize};
use crate::error::Result;
use crate::simulator::{Model, RowTiming};

/// The size of a set and how its rows are given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SetSize {
    /// Rows (scans).
    pub rows: u64,
    /// Seed of the set (its reference run's seeds derive from it).
    pub seed: u64,
    /// Blocks of the reference run.
    pub reference_blocks: u64,
    /// Worker threads (0: all); the rows and truth do not depend on it.
    pub threads: usize,
    /// The counts `c_i + M_i` rather than the continuum-subtracted `M_i`.
    pub keep_continuum: bool,
    /// How the rows lie in time through the piston (the layout, and the
    /// observation layout's observations and dead time).
    pub layout: RowTiming,
}

/// Units generated at once while streaming the rows.
pub(crate) const STREAM_BATCH_UNITS: u64 = 8;

/// Computes the truth of the set, then streams its rows (row-major,
/// `model.samples()` per row) to `sink`; returns the sidecar, whose data
/// files are named `npy` and `csv`. `progress` counts rows, the reference
/// run's and the set's.
pub fn synthesize(
    model: &Model,
    size: &SetSize,
    (npy, csv): (String, Option<String>),
    sink: &mut dyn FnMut(&[f64]) -> Result<()>,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Sidecar> {
    let truth_size = TruthSize {
        rows: size.rows,
        seed: size.seed,
        reference_blocks: size.reference_blocks,
        threads: size.threads,
    };
    let truth = truth_laid_out(model, truth_size, size.layout, progress)?;
    synthesize_with_truth(model, size, truth, (npy, csv), sink, progress)
}

/// [`synthesize`] with the set's truth already computed (its reference
/// run split in ranges of units elsewhere: `v2ref_commands::units::truth`).
pub fn synthesize_with_truth(
    model: &Model,
    size: &SetSize,
    truth: Truth,
    (npy, csv): (String, Option<String>),
    sink: &mut dyn FnMut(&[f64]) -> Result<()>,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Sidecar> {
    let inputs = &model.inputs;
    let set = model.rows_in(size.layout, size.rows, size.seed, size.threads)?;
    let continuum = &model.signal.continuum;
    let mut shifted = Vec::new();
    set.stream(size.threads, STREAM_BATCH_UNITS, |block: &[f64]| {
        let rows: &[f64] = if size.keep_continuum {
            shifted.clear();
            shifted.extend(
                block
                    .iter()
                    .zip(continuum.iter().cycle())
                    .map(|(m, c)| m + c),
            );
            &shifted
        } else {
            block
        };
        sink(rows)?;
        progress((block.len() / inputs.samples) as u64);
        Ok(())
    })?;
    Ok(Sidecar {
        format: FORMAT.to_owned(),
        version: env!("CARGO_PKG_VERSION").to_owned(),
        data: DataFiles {
            npy,
            csv,
            rows: size.rows,
            samples: inputs.samples,
            channels: None,
        },
        seed: size.seed,
        layout: set.layout(),
        continuum_subtracted: !size.keep_continuum,
        sample_opd_um: model.sample_opd_um(),
        continuum_photons: continuum.clone(),
        mean_counts_photons: model.signal.mean_counts(),
        inputs: inputs.clone(),
        truth,
        members: None,
        channels: None,
    })
}
