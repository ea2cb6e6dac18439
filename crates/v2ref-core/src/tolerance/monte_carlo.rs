//! Tolerances of Monte Carlo checks: standard errors and power.

/// Number of standard errors a Monte Carlo test allows (≥ 5 by policy:
/// a 5σ two-sided excursion has probability 5.7e-7 per test).
pub const MC_SIGMAS: f64 = 5.0;

/// Standard errors at which the claims table calls a Monte Carlo bias
/// "significant" or "consistent with" a bound. This is a reporting
/// convention for the reproduction (3σ: 0.27% two-sided per point, so over
/// ~100 points a few chance excursions are expected and counted), not a
/// pass/fail tolerance; tests use [`MC_SIGMAS`].
pub const SIGNIFICANCE_SIGMAS: f64 = 3.0;

/// A check has power when the wrong answer it must reject lies at least
/// this many tolerances (or standard errors) away: 100, so that the
/// rejection cannot be an accident of the tolerance's margin or of a 5σ
/// fluctuation.
pub const POWER_FACTOR: f64 = 100.0;

/// Standard errors by which a Monte Carlo must reject a known-wrong
/// formula whose error is itself a smaller effect (the published variance
/// against the exact one): 50σ, ten times [`MC_SIGMAS`], so neither a
/// fluctuation nor the error of the standard error (a few % at the sample
/// sizes used) can fake the rejection.
pub const MC_POWER_SIGMAS: f64 = 50.0;

/// Standard errors within which a plan's predicted mean V² must agree with
/// the mean of its simulated observations (`tests/plan_observation.rs`):
/// 3, the acceptance of the planner's bias-convention check (issue 33),
/// stricter than [`MC_SIGMAS`]; the seeds are fixed (the check is
/// deterministic), and the error is that of the difference (the
/// prediction's and the simulation's standard errors combined).
pub const PLAN_MEAN_SIGMAS: f64 = 3.0;
