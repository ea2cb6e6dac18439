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
use crate::montecarlo::{fold_units, replicated_summary, Rng, RunningStats, Steps, Summary};
use crate::noise::calibrated::{expectation, noisy_spec, normalize, CalibratedExpectation, Trials};
use crate::noise::simulation::{NoisyRun, NoisyUnits};
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
    let units = SimulationUnits::new(model, window, bias, formula, size)?;
    let mut total = units.empty();
    units.fold(0..units.units(), progress, |p| merge(&mut total, &p))?;
    Ok(units.finish(&total))
}

/// Running statistics of one unit's rows: V1², V2², and V1, V2 minus their
/// piston-free values (the last two unused on the noise-only fast path).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct UnitStats {
    /// Normalized V1² (raw V1² on the fast path).
    pub v1_sq: RunningStats,
    /// Normalized V2² (raw V2² on the fast path).
    pub v2_sq: RunningStats,
    /// V1 − V1(no piston).
    pub v1: RunningStats,
    /// V2 − V2(no piston).
    pub v2: RunningStats,
}

/// Merges a unit's accumulators (one per piston sequence) into `total`:
/// [`simulate`]'s reduction, applied in unit order.
pub fn merge(total: &mut [UnitStats], part: &[UnitStats]) {
    for (t, p) in total.iter_mut().zip(part) {
        t.v1_sq.merge(&p.v1_sq);
        t.v2_sq.merge(&p.v2_sq);
        t.v1.merge(&p.v1);
        t.v2.merge(&p.v2);
    }
}

/// [`simulate`]'s work: its units one by one (for a run split over
/// processes) and the answer from their merged results. Merging the
/// results of [`SimulationUnits::fold`] over any split of the units, in
/// unit order, gives [`simulate`]'s bits.
pub struct SimulationUnits<'m> {
    rows: Rows<'m>,
    window: BinWindow,
    bias: BiasConvention,
    size: Trials,
    expected: Option<CalibratedExpectation>,
    path: UnitPath,
}

/// Without piston and with the `model` convention the raw moments are
/// accumulated and normalized at the end; otherwise each row is estimated.
enum UnitPath {
    Fast(NoisyUnits),
    Rows { est: RowEstimator, v0: (f64, f64) },
}

impl<'m> SimulationUnits<'m> {
    /// The units of [`simulate`]'s run (same arguments, same errors).
    pub fn new(
        model: &'m Model,
        window: BinWindow,
        bias: BiasConvention,
        formula: Formula,
        size: Trials,
    ) -> Result<SimulationUnits<'m>> {
        let rows = model
            .rows(size.trials, size.seed, size.threads)
            .map_err(|e| e.renamed("rows", "trials"))?;
        let setup = model.calibrated_setup(window);
        let expected = match rows.has_piston() {
            false => Some(expectation(&setup, &model.noise, formula)?),
            true => None,
        };
        let fast = expected.is_some() && bias == BiasConvention::Model;
        if !fast && formula != Formula::Exact {
            return Err(Error::Invalid {
                param: "formula",
                reason: "the paper's printed bias applies to the noise-only run with the model bias convention; use the exact formula with piston or --bias counts".into(),
            });
        }
        let path = if fast {
            UnitPath::Fast(NoisyUnits::new(
                &noisy_spec(&setup, &model.noise),
                size.trials,
            )?)
        } else {
            let est = RowEstimator::new(model, window, bias, true)?;
            let piston_free = est.estimate_checked_row(&rows.piston_free_row());
            let v0 = (piston_free.v1_sq.sqrt(), piston_free.v2_sq.sqrt());
            UnitPath::Rows { est, v0 }
        };
        Ok(SimulationUnits {
            rows,
            window,
            bias,
            size,
            expected,
            path,
        })
    }

    /// Number of work units.
    pub fn units(&self) -> u64 {
        match &self.path {
            UnitPath::Fast(noisy) => noisy.units(),
            UnitPath::Rows { .. } => self.rows.units(),
        }
    }

    /// Empty accumulators, one per piston sequence (one without piston):
    /// the length of every unit's result.
    pub fn empty(&self) -> Vec<UnitStats> {
        let groups = match &self.path {
            UnitPath::Fast(_) => 1,
            UnitPath::Rows { .. } => self.rows.sequences(),
        };
        vec![UnitStats::default(); groups]
    }

    /// Runs the units of `range` and hands each one's accumulators to
    /// `merge` in unit order.
    pub fn fold(
        &self,
        range: std::ops::Range<u64>,
        progress: &(dyn Fn(u64) + Sync),
        merge: impl FnMut(Vec<UnitStats>) + Send,
    ) -> Result<()> {
        let threads = self.size.threads;
        match &self.path {
            UnitPath::Fast(noisy) => {
                let work = |u, rng: &mut Rng| {
                    let r = noisy.unit(u, rng, progress)?;
                    let (v1_sq, v2_sq) = (r.v1_sq, r.v2_sq);
                    Ok(vec![UnitStats {
                        v1_sq,
                        v2_sq,
                        ..UnitStats::default()
                    }])
                };
                fold_units(self.size.seed, range, threads, work, merge)
            }
            UnitPath::Rows { est, v0 } => {
                let work = |first_row, block: &[f64]| {
                    self.estimate_rows(est, *v0, first_row, block, progress)
                };
                self.rows.fold_unit_range(range, threads, work, merge)
            }
        }
    }

    /// One unit's rows estimated, their normalized values accumulated per
    /// piston sequence (the rows of one sequence are correlated, so the
    /// errors come from the spread between sequences).
    fn estimate_rows(
        &self,
        est: &RowEstimator,
        v0: (f64, f64),
        first_row: u64,
        block: &[f64],
        progress: &(dyn Fn(u64) + Sync),
    ) -> Result<Vec<UnitStats>> {
        let n = self.rows.samples();
        let mut s = self.empty();
        let mut steps = Steps::new(progress, n);
        for (i, row) in block.chunks_exact(n).enumerate() {
            let acc = &mut s[self.rows.sequence_of_own_row(first_row + i as u64)];
            let e = est.estimate_checked_row(row);
            acc.v1_sq.push(e.v1_sq);
            acc.v2_sq.push(e.v2_sq);
            acc.v1.push(e.v1_sq.sqrt() - v0.0);
            acc.v2.push(e.v2_sq.sqrt() - v0.1);
            steps.step()?;
        }
        steps.finish()?;
        Ok(s)
    }

    /// The answer from the accumulators of every unit merged in unit order
    /// ([`merge`] into [`SimulationUnits::empty`]).
    pub fn finish(&self, total: &[UnitStats]) -> SimulationRun {
        let (v1_sq, v2_sq, piston_effect) = match (&self.path, self.expected) {
            (UnitPath::Fast(_), Some(expected)) => {
                let raw = NoisyRun {
                    v1_sq: total[0].v1_sq,
                    v2_sq: total[0].v2_sq,
                };
                let run = normalize(&raw, expected);
                (run.v1_sq, run.v2_sq, None)
            }
            (_, _) => self.summaries(total),
        };
        SimulationRun {
            window: self.window,
            bias: self.bias,
            rows: self.size.trials,
            seed: self.size.seed,
            v1_sq,
            v2_sq,
            expected: self.expected,
            piston: self.rows.piston_facts(),
            piston_effect,
        }
    }

    /// The general path's summaries: over the sequences when there are
    /// several; with piston and no noise, V − V(no piston) as well.
    fn summaries(&self, total: &[UnitStats]) -> (Summary, Summary, Option<PistonEffect>) {
        let summary = |pick: fn(&UnitStats) -> RunningStats| {
            let groups: Vec<RunningStats> = total.iter().map(pick).collect();
            if groups.len() > 1 {
                replicated_summary(&groups)
            } else {
                groups[0].summary()
            }
        };
        let noiseless = !rows_noisy(&self.rows);
        let effect = match &self.path {
            UnitPath::Rows { v0, .. } if noiseless && self.rows.has_piston() => {
                Some(PistonEffect {
                    v1_no_piston: v0.0,
                    v2_no_piston: v0.1,
                    v1: summary(|s| s.v1),
                    v2: summary(|s| s.v2),
                })
            }
            _ => None,
        };
        (summary(|s| s.v1_sq), summary(|s| s.v2_sq), effect)
    }
}

fn rows_noisy(rows: &Rows) -> bool {
    let noise = rows.model().noise;
    noise.photon || noise.read_noise > 0.0
}
