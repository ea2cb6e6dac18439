//! `simulate`: the running statistics of the normalized estimators over a
//! set's rows, beside their closed forms where there are closed forms.
//!
//! Without piston and with the `model` bias convention the rows are
//! reduced by the fast path of [`crate::noise::calibrated::calibrated_run`]
//! (raw moments, normalized exactly at the end); otherwise each row is
//! estimated ([`RowEstimator`]) and its normalized values accumulated. The
//! tests hold the two paths to each other.

use crate::error::{Error, Result};
use crate::formalism::estimator::BinWindow;
use crate::montecarlo::{replicated_summary, RunningStats, Steps, Summary};
use crate::noise::calibrated::{calibrated_run, expectation, CalibratedExpectation, Trials};
use crate::noise::Formula;
use crate::simulator::estimate::{BiasConvention, RowEstimator};
use crate::simulator::rows::{PistonFacts, Rows};
use crate::simulator::Model;
use serde::Serialize;

/// The piston's effect on V (not V²) in a noiseless set: the quantities
/// `v2ref piston` reports.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PistonEffect {
    /// V1 of the piston-free scan (normalized).
    pub v1_no_piston: f64,
    /// V2 of the piston-free scan.
    pub v2_no_piston: f64,
    /// V1(piston) − V1(no piston) over the scans: mean = bias, std = scatter.
    pub v1: Summary,
    /// V2(piston) − V2(no piston).
    pub v2: Summary,
}

/// The result of [`simulate`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SimulationRun {
    /// The window.
    pub window: BinWindow,
    /// The bias convention.
    pub bias: BiasConvention,
    /// Number of rows.
    pub rows: u64,
    /// Seed.
    pub seed: u64,
    /// Normalized, bias-subtracted V1² over the rows.
    pub v1_sq: Summary,
    /// Normalized, bias-subtracted V2².
    pub v2_sq: Summary,
    /// The closed forms (without piston).
    pub expected: Option<CalibratedExpectation>,
    /// The piston sequence, if any.
    pub piston: Option<PistonFacts>,
    /// With piston and no noise: its effect on V1 and V2.
    pub piston_effect: Option<PistonEffect>,
}

/// Simulates `size.trials` rows of `model` from `size.seed` and reduces the
/// estimators of `window` under the `bias` convention; `progress` is called
/// with the number of rows done since its last call. `formula` is the
/// bias subtracted by the noise-only `model` run (the paper's printed one
/// or the exact one); every other run subtracts the exact bias.
///
/// # Example
///
/// ```
/// use v2ref_core::conformance::estimate::BiasConvention;
/// use v2ref_core::formalism::estimator::BinWindow;
/// use v2ref_core::noise::calibrated::Trials;
/// use v2ref_core::noise::Formula;
/// use v2ref_core::simulator::{simulate, Inputs, Model};
/// let model = Model::new(&Inputs { samples: 32, ..Inputs::default() })?;
/// let size = Trials { trials: 20_000, seed: 3, threads: 0 };
/// let run = simulate(&model, BinWindow::Positive, BiasConvention::Counts, Formula::Exact, size, &|_| {})?;
/// let expected = run.expected.unwrap().mean_v1_sq;
/// assert!((run.v1_sq.mean - expected).abs() < 5.0 * run.v1_sq.stderr_mean);
/// # Ok::<(), v2ref_core::Error>(())
/// ```
pub fn simulate(
    model: &Model,
    window: BinWindow,
    bias: BiasConvention,
    formula: Formula,
    size: Trials,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<SimulationRun> {
    let rows = model
        .rows(size.trials, size.seed, size.threads)
        .map_err(|e| e.renamed("rows", "trials"))?;
    let setup = model.calibrated_setup(window);
    let expected = match rows.piston_facts() {
        None => Some(expectation(&setup, &model.noise, formula)?),
        Some(_) => None,
    };
    let fast = expected.is_some() && bias == BiasConvention::Model;
    if !fast && formula != Formula::Exact {
        return Err(Error::Invalid {
            param: "formula",
            reason: "the paper's printed bias applies to the noise-only run with the model bias convention; use the exact formula with piston or --bias counts".into(),
        });
    }
    let (v1_sq, v2_sq, piston_effect) = if fast {
        let run = calibrated_run(&setup, &model.noise, formula, size, progress)?;
        (run.v1_sq, run.v2_sq, None)
    } else {
        let est = RowEstimator::new(model, window, bias, true)?;
        reduce_rows(&rows, &est, size.threads, progress)?
    };
    Ok(SimulationRun {
        window,
        bias,
        rows: size.trials,
        seed: size.seed,
        v1_sq,
        v2_sq,
        expected,
        piston: rows.piston_facts(),
        piston_effect,
    })
}

/// Running statistics of one unit's rows: V1², V2², and V1, V2 minus their
/// piston-free values.
#[derive(Clone, Copy, Default)]
struct UnitStats {
    v1_sq: RunningStats,
    v2_sq: RunningStats,
    v1: RunningStats,
    v2: RunningStats,
}

/// The general path: every row estimated, its normalized values
/// accumulated; with piston and no noise, V − V(no piston) as well.
fn reduce_rows(
    rows: &Rows,
    est: &RowEstimator,
    threads: usize,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<(Summary, Summary, Option<PistonEffect>)> {
    let noiseless = !rows_noisy(rows);
    let piston_free = est.estimate(&rows.piston_free_row());
    let v0 = (piston_free.v1_sq.sqrt(), piston_free.v2_sq.sqrt());
    let n = rows.samples();
    // One accumulator per piston sequence: the rows of one sequence are
    // correlated, so the errors come from the spread between sequences.
    let mut total = vec![UnitStats::default(); rows.sequences()];
    let work = |first_row: u64, block: &[f64]| {
        let mut s = vec![UnitStats::default(); rows.sequences()];
        let mut steps = Steps::new(progress, n);
        for (i, row) in block.chunks_exact(n).enumerate() {
            let acc = &mut s[rows.sequence_of(first_row + i as u64)];
            let e = est.estimate(row);
            acc.v1_sq.push(e.v1_sq);
            acc.v2_sq.push(e.v2_sq);
            acc.v1.push(e.v1_sq.sqrt() - v0.0);
            acc.v2.push(e.v2_sq.sqrt() - v0.1);
            steps.step()?;
        }
        steps.finish()?;
        Ok(s)
    };
    rows.fold_units(threads, work, |p: Vec<UnitStats>| {
        for (t, p) in total.iter_mut().zip(&p) {
            t.v1_sq.merge(&p.v1_sq);
            t.v2_sq.merge(&p.v2_sq);
            t.v1.merge(&p.v1);
            t.v2.merge(&p.v2);
        }
    })?;
    let summary = |pick: fn(&UnitStats) -> RunningStats| {
        let groups: Vec<RunningStats> = total.iter().map(pick).collect();
        if groups.len() > 1 {
            replicated_summary(&groups)
        } else {
            groups[0].summary()
        }
    };
    let effect = (noiseless && rows.piston_facts().is_some()).then(|| PistonEffect {
        v1_no_piston: v0.0,
        v2_no_piston: v0.1,
        v1: summary(|s| s.v1),
        v2: summary(|s| s.v2),
    });
    Ok((summary(|s| s.v1_sq), summary(|s| s.v2_sq), effect))
}

fn rows_noisy(rows: &Rows) -> bool {
    let noise = rows.model().noise;
    noise.photon || noise.read_noise > 0.0
}
