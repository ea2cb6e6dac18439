//! The numbers of the plan's figure (`plan --svg`): the σ(V²) each
//! estimator reaches against fringe frequency, at the best stroke of each,
//! in the plan's time — computed by the planner's own
//! [`sigma_reached_in`], the piston terms at the
//! upper ends of their intervals, so that the figure and the table cannot
//! disagree (the figure once recomputed σ from the central values).

use super::{sigma_reached_in, Estimator, Plan, PlanInputs, Target};

/// Time the figure is drawn at when a target plan recommends nothing, s.
pub const FALLBACK_TIME_S: f64 = 3600.0;

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
/// `e`, in the grid's order of frequencies; a frequency where no stroke
/// reaches a finite σ is left out.
pub fn sigma_curve(plan: &Plan, inputs: &PlanInputs, e: Estimator, time_s: f64) -> Vec<(f64, f64)> {
    inputs
        .fringe_hz
        .iter()
        .filter_map(|&f| {
            plan.points
                .iter()
                .filter(|p| p.estimator == e && p.fringe_hz == f)
                .filter_map(|p| sigma_reached_in(p, inputs, time_s))
                .min_by(f64::total_cmp)
                .map(|s| (f, s))
        })
        .collect()
}
