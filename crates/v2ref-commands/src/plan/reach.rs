//! How a grid point reaches the target, and which point the plan
//! recommends: the piston terms at the ends of their confidence intervals,
//! and a choice that does not flip with the seed.

use super::{Estimator, PlanInputs, PlanPoint, Target, ONE_NIGHT_S};

/// Why a target-mode point has no scans or time.
pub const UNREACHABLE: &str = "unreachable: the piston bias (upper end of its interval) is at or above the target sigma(V^2), so no number of scans reaches it: scans_needed and time_s are null (and time_lower_s where even the lower end of the bias is at or above the target), sigma_reached is the sigma(V^2) a time budget reaches, and observation (the error of the consecutive scans' mean) is null";

/// Why a reachable target-mode point has `sigma_reached` null.
pub const TARGET_MODE: &str = "sigma_reached is null: it is the sigma(V^2) a time budget reaches, and this plan has a target instead; observation is null on the settings not solved for the mean of consecutive scans (all but the 5 fastest of each estimator by the per-scan estimate, and those of the 5 whose noise alone needs longer than the best solved setting of their estimator: their scans assume independent scans)";

/// Why a budget-mode point has the lower and noise-only times null.
pub const BUDGET_MODE: &str = "time_lower_s and time_noise_only_s are null: they are the times to a target sigma(V^2), and this plan has a time budget instead; observation is null too (it is solved for a target)";

/// Why a budget-mode point has no scans at all.
pub const SHORT_BUDGET: &str = "the time budget is shorter than one scan and its dead time: no scan fits, so scans_needed, time_s and sigma_reached are null, time_lower_s and time_noise_only_s are times to a target sigma(V^2) (this plan has a budget), and the biases have no sigma to be compared with (bandwidth_bias_over_target, scan_bias_over_target null); observation is null (it belongs to a target sigma(V^2))";

/// The lower ends of the piston terms' intervals.
pub(super) struct Bounds {
    pub(super) sigma_piston: f64,
    pub(super) bias: f64,
}

/// Scans for σ(V²) = target with per-scan σ `sigma` and bias `bias` (None:
/// unreachable).
pub(super) fn scans_for(target: f64, sigma: f64, bias: f64) -> Option<f64> {
    let room = target * target - bias * bias;
    (bias < target && sigma.is_finite() && room > 0.0)
        .then(|| (sigma * sigma / room).ceil().max(1.0))
        .filter(|n| n.is_finite())
}

/// Fills the scans and time (or the σ reached) of `p`: with the piston
/// terms at the upper ends of their intervals (the stated plan), at the
/// lower ends (`time_lower_s`) and without piston (`time_noise_only_s`).
pub(super) fn reach(p: &mut PlanPoint, inputs: &PlanInputs, lower: Bounds) {
    let per_scan_s = p.scan_time_s + inputs.dead_time_s;
    let var_noise = p.sigma_noise_per_scan * p.sigma_noise_per_scan;
    let sigma_at = |sp: f64| (var_noise + sp * sp).sqrt();
    match inputs.target {
        Target::SigmaV2(target) => {
            let upper = scans_for(target, sigma_at(p.sigma_piston_upper), p.bias_piston_upper);
            p.scans_needed = upper;
            p.time_s = upper.map(|n| n * per_scan_s);
            p.time_lower_s =
                scans_for(target, sigma_at(lower.sigma_piston), lower.bias).map(|n| n * per_scan_s);
            p.time_noise_only_s =
                scans_for(target, p.sigma_noise_per_scan, 0.0).map(|n| n * per_scan_s);
            p.exceeds_one_night = p.time_s.is_some_and(|t| t > ONE_NIGHT_S);
            p.why_null = Some(if upper.is_some() {
                TARGET_MODE
            } else {
                UNREACHABLE
            });
        }
        Target::TimeBudgetS(budget) => {
            let n = (budget / per_scan_s).floor();
            if n >= 1.0 {
                p.sigma_reached = sigma_reached_in(p, inputs, budget);
                p.scans_needed = Some(n);
                p.time_s = Some(n * per_scan_s);
                p.exceeds_one_night = n * per_scan_s > ONE_NIGHT_S;
                // The biases to correct, against the σ the budget reaches.
                let reached = p.sigma_reached.unwrap_or(f64::NAN);
                p.bandwidth_bias_over_target = p.bias_bandwidth_dispersion.abs() / reached;
                p.scan_bias_over_target = p.bias_scan_detector.abs() / reached;
                p.why_null = Some(BUDGET_MODE);
            } else {
                p.why_null = Some(SHORT_BUDGET);
            }
        }
    }
}

/// The σ(V²) point `p` reaches in `time_s` seconds, as the plan states it:
/// the scans that fit (dead time included), n. A point solved for the
/// mean of consecutive scans ([`PlanPoint::observation`], target mode)
/// states its observation's σ, `√(σ²_noise/n + σ²_piston,obs,upper)`, at its
/// own n, and elsewhere that piston variance carried as 1/n from it (as
/// `observation` carries a measured block to a longer one); any
/// other point `√((σ²_noise + σ²_piston,upper)/n + bias²_upper)`, its scans
/// taken as independent. None when no scan fits or σ is not finite. The one
/// computation behind a budget plan's `sigma_reached` and the plan's figure.
pub fn sigma_reached_in(p: &PlanPoint, inputs: &PlanInputs, time_s: f64) -> Option<f64> {
    let scans = time_s / (p.scan_time_s + inputs.dead_time_s);
    let n = scans.floor();
    let sigma = match &p.observation {
        // The planner's own time: its own promise (the division may round
        // n·period/period just below n).
        Some(o) if (scans - o.scans as f64).abs() <= OWN_TIME_REL * scans => Some(o.sigma),
        Some(o) => {
            let piston = o.sigma_piston_upper * o.sigma_piston_upper * o.scans as f64 / n;
            let noise = o.sigma_noise_per_scan * o.sigma_noise_per_scan / n;
            Some((noise + piston).sqrt())
        }
        None => {
            let var_scan = p.sigma_noise_per_scan * p.sigma_noise_per_scan
                + p.sigma_piston_upper * p.sigma_piston_upper;
            Some((var_scan / n + p.bias_piston_upper * p.bias_piston_upper).sqrt())
        }
    }?;
    (n >= 1.0 && sigma.is_finite()).then_some(sigma)
}

/// Relative distance of a time from a point's own observation time below
/// which it is that time (a few rounding errors of a product and a quotient).
const OWN_TIME_REL: f64 = 1e-12;

/// The figure of merit of a point: the time for the target, or the σ
/// reached in the budget (lower is better).
pub(super) fn merit(p: &PlanPoint) -> Option<f64> {
    p.sigma_reached.or(p.time_s).filter(|v| v.is_finite())
}

/// The point's merit at the lower ends of the piston intervals (the best
/// it could be): the lower time, or the σ reached (budget mode, where the
/// plan's own value is used).
pub(super) fn merit_lower(p: &PlanPoint) -> Option<f64> {
    p.sigma_reached.or(p.time_lower_s).filter(|v| v.is_finite())
}

/// The recommended point among `points`. The least merit (time, or σ
/// reached, with the piston terms at the upper ends of their intervals) is
/// known only to the Monte Carlo's precision: every point whose optimistic
/// merit ([`merit_lower`]) is within the best's is as good. Among those the
/// plan takes the highest fringe frequency (the least piston, whose terms
/// are known best), then the shortest stroke, then the least merit: the
/// points at the edge of that set are the slow-fringe ones whose piston
/// terms are uncertain, so the choice does not hang on them and does not
/// flip with the seed.
pub(super) fn choose<'a>(points: impl Iterator<Item = &'a PlanPoint> + Clone) -> Option<PlanPoint> {
    let best = points.clone().filter_map(merit).min_by(f64::total_cmp)?;
    points
        .filter_map(|p| merit(p).map(|m| (m, p)))
        .filter(|(_, p)| merit_lower(p).is_some_and(|m| m <= best))
        .min_by(|(ma, a), (mb, b)| {
            b.fringe_hz
                .total_cmp(&a.fringe_hz)
                .then(a.stroke_um.total_cmp(&b.stroke_um))
                .then(ma.total_cmp(mb))
        })
        .map(|(_, p)| *p)
}

/// The best point of estimator `e`: among the points re-solved at the
/// observation level when there are any (target mode).
pub(super) fn best(points: &[PlanPoint], e: Estimator) -> Option<PlanPoint> {
    let ours = || points.iter().filter(move |p| p.estimator == e);
    if ours().any(|p| p.observation.is_some()) {
        choose(ours().filter(|p| p.observation.is_some()))
    } else {
        choose(ours())
    }
}
