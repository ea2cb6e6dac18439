//! The truth of a synth set: what each estimator should give, under every
//! window of bins and bias convention, and how much a set of this size
//! scatters around it.
//!
//! - Closed forms where they exist (no piston): the mean of both
//!   conventions (`(signal + exact bias − subtracted bias)/C`, and the
//!   counts convention subtracts an unbiased estimate of the exact bias, so
//!   its mean is the same), and the variance of the `model` convention (the
//!   exact windowed variance, [`crate::noise::window_variance`]).
//! - Everything else from an independent reference run of `blocks`
//!   blocks (seeds [`reference_seed`]`(seed, b)`, an independent piston
//!   sequence each), estimated the same way. What the run is for, and so
//!   how it is sized, depends on whether the rows are independent:
//!   - **Without piston** the rows are independent, so nothing needs
//!     blocks the size of the set: the run's rows are pooled
//!     (`blocks × max(rows, ⌈`[`POOLED_MIN_ROWS`]`/blocks⌉)` rows). The
//!     pool gives the variance where there is no closed form (the `counts`
//!     convention with photon noise; its own standard error
//!     `√((μ4 − s⁴)/R)` over R pooled rows is `1/√blocks` of a set's), and
//!     the fourth central moment μ4, from which a set of n rows' variance
//!     scatters by `√((μ4 − (n−3)/(n−1) σ⁴)/n)` — a standard error known
//!     to the precision of the pool, not estimated from a few block
//!     variances. The score treats these as exact (normal quantiles).
//!   - **With piston** consecutive scans are correlated (the naive
//!     `var/rows` would miss it), so the spread of a set must be measured
//!     on replicates of the set itself: each block is one replicate (same
//!     size), the mean of the block means and of the block variances are
//!     the truth, and their spread `s_B` over the B blocks is the spread of
//!     a set. Then `(x − T)/(s_B √(1 + 1/B))` — the score's ratio — is
//!     Student-t with `B − 1` degrees of freedom, recorded as
//!     [`EstimatorTruth::stderr_dof`] for the score to use: with 2 blocks a
//!     normal quantile would take a one-degree-of-freedom spread at face
//!     value (the issue-26 set: `z_var = −6.47` from a spread 10 times too
//!     small).
//!
//! The block count is checked against
//! [`SET_MIN_REFERENCE_BLOCKS`](crate::bounds::SET_MIN_REFERENCE_BLOCKS)
//! (below it the t quantile at the score's Bonferroni level runs away and
//! the test sees nothing); [`default_reference_blocks`] sizes the run by
//! the precision it needs.

use crate::conformance::estimate::{BiasConvention, RowEstimator, BIAS_CONVENTIONS};
use crate::conformance::sidecar::{
    ConventionTruth, EstimatorTruth, ReferenceRun, Truth, TruthSource, WindowTruth,
};
use crate::error::Result;
use crate::formalism::estimator::{
    dft, noise_bias_sums, raw_sums, wide_band, BinWindow, Pair, BIN_WINDOWS,
};
use crate::montecarlo::{derive_seed, variance_stderr, RunningStats, Steps};
use crate::noise::calibrated::{expectation, CalibratedExpectation};
use crate::noise::Formula;
use crate::simulator::{Model, RowLayout, RowTiming, ROWS_PER_UNIT};
use std::ops::Range;

/// The size of a set and of its reference run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TruthSize {
    /// Rows of the set.
    pub rows: u64,
    /// The set's seed.
    pub seed: u64,
    /// Replicates of the set in the reference run (0: none).
    pub reference_blocks: u64,
    /// Worker threads (0: all); the truth does not depend on it.
    pub threads: usize,
}

/// Fewest rows of a pooled (piston-free) reference run: enough for its
/// fourth moment, and so a set's stated standard error of the variance, to
/// be known to about 1 % (2^16 rows; a fraction of a second at N = 64).
pub const POOLED_MIN_ROWS: u64 = 1 << 16;

/// Default blocks with piston: 16 replicates of the set. The score's ratio
/// is then t with 15 degrees of freedom: at the default alpha and 4 tests
/// its threshold is 4.77 instead of the normal 3.66, and the smallest
/// bias caught is about 1.3 times what an exact spread would allow (1.12
/// times with 32 blocks, at twice the cost: the reference run is nearly
/// all of a piston `synth`).
pub const REFERENCE_BLOCKS_PISTON: u64 = 16;

/// Default blocks without piston: 8. The truth's own error of a pooled
/// variance is then `1/√8` of a set's, widening the variance test's
/// denominator by `√(1 + 1/8)` = 1.06 (32 blocks: 1.016, at four times
/// the cost); every other truth is a closed form.
pub const REFERENCE_BLOCKS_INDEPENDENT: u64 = 8;

/// The reference blocks a set needs by default:
/// [`REFERENCE_BLOCKS_PISTON`] or [`REFERENCE_BLOCKS_INDEPENDENT`].
pub fn default_reference_blocks(piston: bool) -> u64 {
    if piston {
        REFERENCE_BLOCKS_PISTON
    } else {
        REFERENCE_BLOCKS_INDEPENDENT
    }
}

/// Rows per block of the reference run of a set of `rows` rows: the set's
/// size with piston (each block is a replicate), else at least
/// [`POOLED_MIN_ROWS`] over all `blocks` (0 when there are no blocks).
pub fn reference_rows_per_block(rows: u64, blocks: u64, piston: bool) -> u64 {
    match blocks {
        0 => 0,
        _ if piston => rows,
        b => rows.max(POOLED_MIN_ROWS.div_ceil(b)),
    }
}

/// The seed of replicate `block` of the reference run of a set of seed
/// `seed`.
pub fn reference_seed(seed: u64, block: u64) -> u64 {
    derive_seed(seed, "reference", &[block as f64])
}

/// One estimator of one window and convention, over the blocks: the mean
/// and variance of each block, and all rows pooled.
#[derive(Debug, Clone, Default)]
struct BlockMoments {
    means: RunningStats,
    vars: RunningStats,
    pooled: RunningStats,
}

/// The windows whose calibrator has a fringe (others are left out of the
/// truth).
pub fn usable_windows(model: &Model) -> Vec<BinWindow> {
    BIN_WINDOWS
        .iter()
        .copied()
        .filter(|&w| model.calibrated_setup(w).calibration().is_ok())
        .collect()
}

/// The truth of a set of `size.rows` rows of `model`; `progress` is called
/// with the rows of the reference run done since its last call.
pub fn truth(model: &Model, size: TruthSize, progress: &(dyn Fn(u64) + Sync)) -> Result<Truth> {
    truth_laid_out(model, size, RowLayout::Sequences, progress)
}

/// [`truth`] of a set whose rows lie in time as `layout` says: with
/// piston, each replicate of the reference run is laid out as the set is.
pub fn truth_laid_out(
    model: &Model,
    size: TruthSize,
    layout: impl Into<RowTiming>,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Truth> {
    let layout = layout.into();
    let units = truth_unit_count(model, size)?;
    let stats = truth_units(model, size, layout, 0..units, progress)?;
    truth_from_units(model, size, &stats)
}

/// The work units of the truth's reference run (blocks × units a block);
/// refuses, before any run, the truth of a set that could not be made
/// (its reference run would run without end on 2^40 rows).
pub fn truth_unit_count(model: &Model, size: TruthSize) -> Result<u64> {
    crate::bounds::check_set_size(size.rows, model.samples(), size.reference_blocks)?;
    let piston = model.inputs.piston.is_some();
    let rows_per_block = reference_rows_per_block(size.rows, size.reference_blocks, piston);
    Ok(size.reference_blocks * rows_per_block.div_ceil(ROWS_PER_UNIT))
}

/// The statistics of the truth's reference-run units `range` (within
/// `0..truth_unit_count`), as [`reference_units`].
pub fn truth_units(
    model: &Model,
    size: TruthSize,
    layout: RowTiming,
    range: Range<u64>,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Vec<UnitStats>> {
    let piston = model.inputs.piston.is_some();
    let rows_per_block = reference_rows_per_block(size.rows, size.reference_blocks, piston);
    let blocks = (rows_per_block, layout);
    reference_units(model, &usable_windows(model), size, blocks, range, progress)
}

/// The truth from the statistics of every unit of its reference run, in
/// unit order ([`truth_units`], in one range or many).
pub fn truth_from_units(model: &Model, size: TruthSize, units: &[UnitStats]) -> Result<Truth> {
    let count = truth_unit_count(model, size)?;
    let windows = usable_windows(model);
    if units.len() as u64 != count || units.iter().any(|u| u.len() != windows.len()) {
        return Err(crate::error::Error::Invalid {
            param: "partial",
            reason: format!("not the {count} units of this truth's reference run"),
        });
    }
    let obs = &model.observation;
    let wb = wide_band(obs);
    let v2 = model.inputs.visibility * model.inputs.visibility;
    let piston = model.inputs.piston.is_some();
    let rows_per_block = reference_rows_per_block(size.rows, size.reference_blocks, piston);
    let per_block = rows_per_block.div_ceil(ROWS_PER_UNIT);
    let reference = reduce_reference(units, per_block, windows.len());
    let mut out = Vec::new();
    for (w, blocks) in windows.iter().zip(&reference) {
        out.push(window_truth(model, *w, blocks, size, piston)?);
    }
    Ok(Truth {
        sigma_eff_per_um: wb.sigma_eff_per_um,
        spatial_freq_cpas: wb.spatial_freq_cpas,
        v_sigma_eff: model.inputs.visibility * wb.v_mono,
        v1_sq_spectral: v2 * wb.v1_sq,
        v2_sq_spectral: v2 * wb.v2_sq,
        windows: out,
        reference_run: ReferenceRun {
            seed: reference_seed(size.seed, 0),
            blocks: size.reference_blocks,
            rows_per_block,
        },
    })
}

/// Per window, per convention: the block moments of V1² and V2².
type Reference = Vec<Vec<[BlockMoments; 2]>>;

/// One work unit's statistics in the reference run: per window, per
/// convention, of V1² and V2².
pub type UnitStats = Vec<Vec<[RunningStats; 2]>>;

/// The statistics of the reference run's work units `range` (block `b`'s
/// unit `u` is unit `b × units per block + u`), in order: the run split in
/// ranges (one process or many) and reduced in unit order gives the same
/// bits as the run in one range.
pub fn reference_units(
    model: &Model,
    windows: &[BinWindow],
    size: TruthSize,
    (rows_per_block, layout): (u64, RowTiming),
    range: Range<u64>,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Vec<UnitStats>> {
    let estimators = windows
        .iter()
        .map(|&w| {
            BIAS_CONVENTIONS
                .iter()
                .map(|&c| RowEstimator::new(model, w, c, true))
                .collect::<Result<Vec<_>>>()
        })
        .collect::<Result<Vec<_>>>()?;
    let per_block = rows_per_block.div_ceil(ROWS_PER_UNIT).max(1);
    let n = model.samples();
    let mut out = Vec::with_capacity((range.end - range.start) as usize);
    for b in range.start / per_block..range.end.div_ceil(per_block) {
        let first = range.start.max(b * per_block) - b * per_block;
        let last = range.end.min((b + 1) * per_block) - b * per_block;
        let seed = reference_seed(size.seed, b);
        let rows = model.rows_in(layout, rows_per_block, seed, size.threads)?;
        out.extend(rows.map_units(first..last, size.threads, |_, block| {
            let mut s =
                vec![vec![[RunningStats::default(); 2]; BIAS_CONVENTIONS.len()]; windows.len()];
            let mut steps = Steps::new(progress, n);
            for row in block.chunks_exact(n) {
                for (sw, ew) in s.iter_mut().zip(&estimators) {
                    for (sc, e) in sw.iter_mut().zip(ew) {
                        let r = e.estimate_checked_row(row);
                        sc[0].push(r.v1_sq);
                        sc[1].push(r.v2_sq);
                    }
                }
                steps.step()?;
            }
            steps.finish()?;
            Ok(s)
        })?);
    }
    Ok(out)
}

/// The block moments from every unit's statistics, in unit order,
/// `per_block` units a block.
fn reduce_reference(units: &[UnitStats], per_block: u64, windows: usize) -> Reference {
    let mut acc: Reference = vec![vec![Default::default(); BIAS_CONVENTIONS.len()]; windows];
    for parts in units.chunks(per_block.max(1) as usize) {
        for (wi, aw) in acc.iter_mut().enumerate() {
            for (ci, ac) in aw.iter_mut().enumerate() {
                for (k, moments) in ac.iter_mut().enumerate() {
                    let mut total = RunningStats::default();
                    for p in parts {
                        total.merge(&p[wi][ci][k]);
                    }
                    moments.means.push(total.mean);
                    moments.vars.push(total.variance());
                    moments.pooled.merge(&total);
                }
            }
        }
    }
    acc
}

fn window_truth(
    model: &Model,
    window: BinWindow,
    blocks: &[[BlockMoments; 2]],
    size: TruthSize,
    piston: bool,
) -> Result<WindowTruth> {
    let setup = model.calibrated_setup(window);
    let calibration = setup.calibration()?;
    let signal = raw_sums(&dft(&setup.signal.modulated), &setup.bins);
    let closed = if piston {
        None
    } else {
        Some(expectation(&setup, &model.noise, Formula::Exact)?)
    };
    // Without photon noise the counts convention subtracts the model's bias.
    let same_estimator = !model.noise.photon;
    let mut conventions = Vec::new();
    for (&bias, moments) in BIAS_CONVENTIONS.iter().zip(blocks) {
        let var_closed = |c: &CalibratedExpectation, k: usize| {
            let v = if k == 0 { c.var_v1_sq } else { c.var_v2_sq };
            v.filter(|_| bias == BiasConvention::Model || same_estimator)
        };
        let mean_closed =
            |c: &CalibratedExpectation, k: usize| if k == 0 { c.mean_v1_sq } else { c.mean_v2_sq };
        let one = |k: usize| {
            estimator_truth(
                closed.as_ref().map(|c| mean_closed(c, k)),
                closed.as_ref().and_then(|c| var_closed(c, k)),
                &moments[k],
                size.rows,
                !piston,
            )
        };
        if let (Some(v1_sq), Some(v2_sq)) = (one(0), one(1)) {
            conventions.push(ConventionTruth { bias, v1_sq, v2_sq });
        }
    }
    Ok(WindowTruth {
        bins: window,
        bin_indices: setup.bins.clone(),
        calibration,
        noise_free: Pair {
            v1_sq: signal.v1_sq / calibration.v1_sq,
            v2_sq: signal.v2_sq / calibration.v2_sq,
        },
        model_bias: noise_bias_sums(&model.sample_variance(), &setup.bins),
        conventions,
    })
}

/// Combines the closed forms (where given) with the reference run: pooled
/// when the rows are independent, block by block otherwise (see the
/// [module documentation](self)); None when neither gives a value.
fn estimator_truth(
    mean_closed: Option<f64>,
    var_closed: Option<f64>,
    blocks: &BlockMoments,
    rows: u64,
    independent_rows: bool,
) -> Option<EstimatorTruth> {
    if independent_rows {
        pooled_truth(mean_closed, var_closed, &blocks.pooled, rows)
    } else {
        block_truth(mean_closed, var_closed, blocks)
    }
}

/// Independent rows: closed forms, else the pooled reference rows `pool`.
///
/// A set of n rows scatters by `√(σ²/n)` in its mean and by
/// `√((μ4 − (n−3)/(n−1) σ⁴)/n)` in its variance (μ4 the fourth central
/// moment of one row's estimate, from the pool); the truth's own errors
/// are those of the pool's mean and variance. All are stated as exact
/// (`stderr_dof` None): the pool is at least [`POOLED_MIN_ROWS`] rows.
fn pooled_truth(
    mean_closed: Option<f64>,
    var_closed: Option<f64>,
    pool: &RunningStats,
    rows: u64,
) -> Option<EstimatorTruth> {
    let have_pool = pool.count >= 4;
    let (mean, mean_source, stderr_mean) = match mean_closed {
        Some(m) => (m, TruthSource::ClosedForm, 0.0),
        None if have_pool => (pool.mean, TruthSource::ReferenceRun, pool.stderr_mean()),
        None => return None,
    };
    let (var, var_source, stderr_var) = match var_closed {
        Some(v) => (v, TruthSource::ClosedForm, 0.0),
        None if have_pool => (
            pool.variance(),
            TruthSource::ReferenceRun,
            pool.stderr_variance(),
        ),
        None => return None,
    };
    let n = rows as f64;
    let set_stderr_var = have_pool.then(|| variance_stderr(pool.m4 / pool.count as f64, var, rows));
    Some(EstimatorTruth {
        mean,
        var,
        mean_source,
        var_source,
        stderr_mean,
        stderr_var,
        set_stderr_mean: (var / n).sqrt(),
        set_stderr_var,
        stderr_dof: None,
    })
}

/// Correlated rows (piston): each block is a replicate of the set; the
/// truth is the mean over the B blocks, the set's scatter their spread
/// `s_B`, the truth's own error `s_B/√B`, with `B − 1` degrees of freedom.
fn block_truth(
    mean_closed: Option<f64>,
    var_closed: Option<f64>,
    blocks: &BlockMoments,
) -> Option<EstimatorTruth> {
    let b = blocks.means.count;
    if b < 2 {
        return None;
    }
    let sqrt_b = (b as f64).sqrt();
    let (mean, mean_source, stderr_mean) = match mean_closed {
        Some(m) => (m, TruthSource::ClosedForm, 0.0),
        None => (
            blocks.means.mean,
            TruthSource::ReferenceRun,
            blocks.means.std() / sqrt_b,
        ),
    };
    let (var, var_source, stderr_var) = match var_closed {
        Some(v) => (v, TruthSource::ClosedForm, 0.0),
        None => (
            blocks.vars.mean,
            TruthSource::ReferenceRun,
            blocks.vars.std() / sqrt_b,
        ),
    };
    Some(EstimatorTruth {
        mean,
        var,
        mean_source,
        var_source,
        stderr_mean,
        stderr_var,
        set_stderr_mean: blocks.means.std(),
        set_stderr_var: Some(blocks.vars.std()),
        stderr_dof: Some(b - 1),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulator::Inputs;

    #[test]
    fn the_reference_run_in_ranges_of_units_reduces_to_the_same_bits() {
        let model = Model::new(&Inputs {
            samples: 32,
            ..Inputs::default()
        })
        .unwrap();
        // 8 blocks of 3 units (the last one short): ranges cut inside blocks.
        let size = TruthSize {
            rows: 2 * ROWS_PER_UNIT + 5,
            seed: 11,
            reference_blocks: 8,
            threads: 1,
        };
        let layout: RowTiming = RowLayout::Sequences.into();
        let whole = truth(&model, size, &|_| {}).unwrap();
        assert_eq!(truth_unit_count(&model, size).unwrap(), 24);
        let mut units = Vec::new();
        for range in [0..2, 2..3, 3..7, 7..24] {
            units.extend(truth_units(&model, size, layout, range, &|_| {}).unwrap());
        }
        let split = truth_from_units(&model, size, &units).unwrap();
        assert_eq!(format!("{split:?}"), format!("{whole:?}"));
        assert!(truth_from_units(&model, size, &units[1..]).is_err());
        // Power: another seed changes the bits.
        let other = truth(&model, TruthSize { seed: 12, ..size }, &|_| {}).unwrap();
        assert_ne!(format!("{other:?}"), format!("{whole:?}"));
    }
}
