//! The numbers of the plan's figure (`plan --svg`): the σ(V²) each
//! estimator reaches against fringe frequency, at the best stroke of each,
//! in the plan's time — computed by the planner's own
//! [`sigma_reached_in`], the piston terms at the
//! upper ends of their intervals, so that the figure and the table cannot
//! disagree (the figure once recomputed σ from the central values).
//!
//! With a target, only the settings solved for the observation of
//! consecutive scans carry the plan's promise; the others' σ assumes
//! independent scans (the table's `*`), which consecutive scans through
//! one atmosphere may not keep, so they are drawn apart ([`Drawn`]): one
//! such point once sat below the recommendation (V1² at 177 Hz, 9.5e-4
//! against 9.7e-4 at 467 Hz) and contradicted it.

use super::{sigma_reached_in, Estimator, Plan, PlanInputs, PlanPoint, Target};

/// Time the figure is drawn at when a target plan recommends nothing, s.
pub const FALLBACK_TIME_S: f64 = 3600.0;

/// What a point of the figure states.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Drawn {
    /// The plan's number: the observation of consecutive scans solved
    /// (target), or the σ a time budget reaches (the table's own).
    Promise,
    /// A target plan's setting not solved for the observation: σ_scan/√n,
    /// which assumes independent scans and is no promise.
    IndependentScans,
}

/// How the plan draws point `p`.
pub fn drawn_as(p: &PlanPoint, inputs: &PlanInputs) -> Drawn {
    match (inputs.target, p.observation) {
        (Target::SigmaV2(_), None) => Drawn::IndependentScans,
        _ => Drawn::Promise,
    }
}

/// The time the figure is drawn at, s: the budget, or the recommended
/// point's time for the target ([`FALLBACK_TIME_S`] without one).
pub fn figure_time_s(plan: &Plan, inputs: &PlanInputs) -> f64 {
    match inputs.target {
        Target::TimeBudgetS(t) => t,
        Target::SigmaV2(_) => plan
            .recommended
            .and_then(|p| p.time_s)
            .unwrap_or(FALLBACK_TIME_S),
    }
}

/// (f, the least σ(V²) reached in `time_s` over the strokes) for estimator
/// `e` among the points drawn as `drawn`, in the grid's order of
/// frequencies; a frequency where no such stroke reaches a finite σ is left
/// out.
pub fn sigma_curve(
    plan: &Plan,
    inputs: &PlanInputs,
    (e, drawn): (Estimator, Drawn),
    time_s: f64,
) -> Vec<(f64, f64)> {
    inputs
        .fringe_hz
        .iter()
        .filter_map(|&f| {
            plan.points
                .iter()
                .filter(|p| p.estimator == e && p.fringe_hz == f)
                .filter(|p| drawn_as(p, inputs) == drawn)
                .filter_map(|p| sigma_reached_in(p, inputs, time_s))
                .min_by(f64::total_cmp)
                .map(|s| (f, s))
        })
        .collect()
}
