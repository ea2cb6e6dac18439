//! Scoring a pipeline's per-row estimates against a synth set's truth.
//!
//! For one estimator and a set of n rows `x_1 … x_n` (the pipeline's
//! normalized V1² or V2², one per interferogram), with the sample mean
//! `x̄` and the unbiased sample variance `s² = Σ (x_r − x̄)²/(n − 1)`
//! ([`RunningStats`]), and the truth `T` of the set ([`EstimatorTruth`]):
//!
//! - `z_mean = (x̄ − T.mean) / √(T.set_stderr_mean² + T.stderr_mean²)`:
//!   the scatter a set of n rows is expected to have, plus the
//!   uncertainty of the truth itself;
//! - `z_var = (s² − T.var) / √(se_set_var² + T.stderr_var²)`, where
//!   `se_set_var` is `T.set_stderr_var`, or, when the sidecar has none, the
//!   sample's own standard error of the variance
//!   `√((μ4 − (n−3)/(n−1) s⁴)/n)` ([`RunningStats::stderr_variance`]).
//!
//! **Degrees of freedom.** When the truth's standard errors were measured
//! as a spread over B reference blocks (`T.stderr_dof = Some(B − 1)`, with
//! piston), each ratio above is Student-t with `ν = B − 1` degrees of
//! freedom, not normal: the spread that divides it is itself uncertain
//! (with B = 2, one degree of freedom, it can be ten times too small). The
//! ratio `t` is then reported as its normal equivalent
//! `z = sign(t) · Φ⁻¹(1 − F_ν(−|t|))`, the normal deviate with the same
//! tail probability, so that one threshold holds for every test and the
//! false-alarm rate stays `alpha` at every block count. Without
//! `stderr_dof`, `z = t`.
//!
//! **Threshold.** Each z is tested two-sided; with `m` tests made (2 per
//! estimator scored) the family-wise false-alarm rate is held at `alpha`
//! by Bonferroni: `z_crit = Φ⁻¹(1 − alpha/(2m))`. The default
//! `alpha` is [`DEFAULT_ALPHA`] = 10⁻³: a correct pipeline fails one
//! set in a thousand. The verdict passes when every `|z| ≤ z_crit`.
//!
//! **Power.** A pipeline whose mean is off by a relative bias ε has
//! `E z_mean = ε |T.mean| / se_mean`; it is caught with probability
//! 0.9 when `ε ≥ (z_crit + Φ⁻¹(0.9)) · se_mean / |T.mean|`
//! ([`EstimatorScore::min_detectable_rel_bias_mean`], with
//! `se_mean = √(T.set_stderr_mean² + T.stderr_mean²)`); likewise for
//! the variance with its denominator. With ν degrees of freedom the two
//! quantiles are those of t_ν (`F_ν⁻¹(Φ(z_crit)) + F_ν⁻¹(0.9)`, the
//! approximate reach of a shifted t). A set too small to see the bias one
//! cares about must be made larger.
//!
//! The truth is stated for a set of a given size (the sidecar's
//! `data.rows`): the scores refuse estimates of any other length.

use crate::conformance::sidecar::{ConventionTruth, EstimatorTruth};
use crate::error::{Error, Result};
use crate::montecarlo::RunningStats;
use serde::Serialize;
use statrs::distribution::{ContinuousCDF, Normal, StudentsT};

/// The default family-wise false-alarm rate of the verdict: 10⁻³.
pub const DEFAULT_ALPHA: f64 = 1e-3;

/// The detection probability the power figures are stated for.
pub const POWER: f64 = 0.9;

/// Tests made per estimator scored (mean and variance).
pub const TESTS_PER_ESTIMATOR: usize = 2;

/// Φ⁻¹(p), the standard normal quantile (statrs).
fn normal_quantile(p: f64) -> f64 {
    // Normal::new(0, 1) cannot fail; standard() is the same distribution.
    Normal::standard().inverse_cdf(p)
}

/// Student t with `dof` degrees of freedom (≥ 1).
fn students_t(dof: u64) -> StudentsT {
    // Location 0, scale 1 and a positive dof are always accepted.
    StudentsT::new(0.0, 1.0, dof.max(1) as f64).expect("t with dof >= 1")
}

/// The normal equivalent of a ratio `t` that is Student-t with `dof`
/// degrees of freedom: `sign(t) Φ⁻¹(1 − F(−|t|))`, the same tail
/// probability; `t` itself when `dof` is None.
pub fn normal_equivalent(t: f64, dof: Option<u64>) -> f64 {
    match dof {
        None => t,
        // Φ⁻¹ of the lower tail keeps its precision far out (no 1 − p).
        Some(nu) => -normal_quantile(students_t(nu).cdf(-t.abs())) * t.signum(),
    }
}

/// The reach `q(Φ(z_crit)) + q(POWER)` of a test, with q the quantile of
/// t_dof (normal when `dof` is None): the expected ratio at which a bias
/// is caught with probability [`POWER`].
fn reach(z_crit: f64, dof: Option<u64>) -> f64 {
    match dof {
        None => z_crit + normal_quantile(POWER),
        Some(nu) => {
            let t = students_t(nu);
            // Φ(z_crit) from its upper tail, for precision.
            let tail = Normal::standard().sf(z_crit);
            -t.inverse_cdf(tail) + t.inverse_cdf(POWER)
        }
    }
}

/// Smallest `alpha` accepted: the threshold's quantile `1 − alpha/(2·tests)`
/// still holds `alpha` to 3 significant digits (at 10⁻²⁰ it is exactly 1
/// and the threshold infinite).
pub const MIN_ALPHA: f64 = 1e-12;

/// The two-sided Bonferroni threshold `z_crit = Φ⁻¹(1 − alpha/(2·tests))`.
///
/// Refuses `alpha` outside [[`MIN_ALPHA`], 1) and `tests == 0`.
pub fn critical_z(alpha: f64, tests: usize) -> Result<f64> {
    crate::error::finite("alpha", alpha)?;
    if !((MIN_ALPHA..1.0).contains(&alpha)) {
        return Err(Error::OutOfRange {
            param: "alpha",
            value: alpha,
            accepted: format!(
                "{MIN_ALPHA:e} <= alpha < 1 (below, 1 - alpha/(2 tests) is 1 to double precision and the threshold is not resolved)"
            ),
        });
    }
    if tests == 0 {
        return Err(Error::Invalid {
            param: "estimates",
            reason: "no estimator to score".into(),
        });
    }
    Ok(normal_quantile(1.0 - alpha / (2.0 * tests as f64)))
}

/// Where the standard error of a set's variance comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum VarStderrSource {
    /// `EstimatorTruth::set_stderr_var` (the reference run's blocks).
    Truth,
    /// The sample's own standard error of the variance (no reference run).
    Sample,
}

/// The score of one estimator.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EstimatorScore {
    /// n, rows scored.
    pub rows: u64,
    /// x̄, the sample mean of the estimates.
    pub mean: f64,
    /// T.mean, the expected mean.
    pub expected_mean: f64,
    /// `se_mean = √(T.set_stderr_mean² + T.stderr_mean²)`, the denominator
    /// of `z_mean`: the scatter of a set's mean and the truth's own
    /// uncertainty combined (not the truth's `stderr_mean`, which is only
    /// the second).
    pub stderr_mean_combined: f64,
    /// `(x̄ − T.mean)/se_mean`, as its normal equivalent when
    /// `dof` is given.
    pub z_mean: f64,
    /// s², the unbiased sample variance of the estimates.
    pub var: f64,
    /// T.var, the expected variance.
    pub expected_var: f64,
    /// `se_var = √(se_set_var² + T.stderr_var²)`, the denominator of
    /// `z_var`: the scatter of a set's variance and the truth's own
    /// uncertainty combined (not the truth's `stderr_var`, which is only
    /// the second).
    pub stderr_var_combined: f64,
    /// Where `se_set_var` came from.
    pub stderr_var_source: VarStderrSource,
    /// `(s² − T.var)/se_var`, as its normal equivalent when `dof` is
    /// given.
    pub z_var: f64,
    /// The degrees of freedom of both ratios (`T.stderr_dof`); None:
    /// normal.
    pub dof: Option<u64>,
    /// The threshold both z are held to.
    pub z_crit: f64,
    /// `(z_crit + Φ⁻¹(0.9)) · se_mean/|T.mean|` (t quantiles with `dof`):
    /// the smallest relative bias of the mean caught with probability 0.9
    /// (infinite when T.mean = 0).
    pub min_detectable_rel_bias_mean: f64,
    /// `(z_crit + Φ⁻¹(0.9)) · se_var/|T.var|`, the same for the variance.
    pub min_detectable_rel_bias_var: f64,
    /// `|z_mean| ≤ z_crit`.
    pub pass_mean: bool,
    /// `|z_var| ≤ z_crit`.
    pub pass_var: bool,
    /// Both.
    pub pass: bool,
}

/// Largest |mean| and variance of a truth scored: beyond it the z-scores
/// of ordinary estimates overflow (the estimators' own rows are refused
/// above the same scale, where their squares overflow).
pub const MAX_TRUTH_SCALE: f64 = 1e150;

fn check_truth(truth: &EstimatorTruth) -> Result<()> {
    let bad = |what: &str, v: f64| Error::Invalid {
        param: "truth",
        reason: format!("{what} is {v}; a finite number is needed"),
    };
    for (what, v) in [("mean", truth.mean), ("var", truth.var)] {
        if !v.is_finite() {
            return Err(bad(what, v));
        }
    }
    // A truth beyond any scale a set's estimates have (a variance of 1e307
    // scored a z of -inf against ordinary estimates): refused as the rows
    // are above 1e150, whose squares overflow.
    for (what, v) in [("mean", truth.mean), ("var", truth.var)] {
        if v.abs() > MAX_TRUTH_SCALE {
            return Err(Error::OutOfRange {
                param: "truth",
                value: v,
                accepted: format!("|{what}| <= {MAX_TRUTH_SCALE:e}"),
            });
        }
    }
    // A variance below 0 is no variance: scored, its z would compare the
    // set's spread with nothing a set can have.
    if truth.var < 0.0 {
        return Err(Error::Invalid {
            param: "truth",
            reason: format!("var is {}; a variance is a finite number >= 0", truth.var),
        });
    }
    if truth.stderr_dof == Some(0) {
        return Err(Error::Invalid {
            param: "truth",
            reason: "stderr_dof is 0; a spread needs at least 1 degree of freedom".into(),
        });
    }
    let mut errs = vec![
        ("stderr_mean", truth.stderr_mean),
        ("stderr_var", truth.stderr_var),
        ("set_stderr_mean", truth.set_stderr_mean),
    ];
    if let Some(v) = truth.set_stderr_var {
        errs.push(("set_stderr_var", v));
    }
    for (what, v) in errs {
        if !(v.is_finite() && v >= 0.0) {
            return Err(Error::Invalid {
                param: "truth",
                reason: format!("{what} is {v}; a finite number >= 0 is needed"),
            });
        }
    }
    Ok(())
}

/// Scores one estimator's `estimates` (one per row) against `truth`, made
/// for a set of `expected_rows` rows, at the threshold `z_crit` (see
/// [`critical_z`]). Formulas in the [module documentation](self).
///
/// Refuses (parameter `estimates`) a length other than `expected_rows`,
/// fewer than 2 rows (4 when the variance's standard error must come from
/// the sample), and a non-finite estimate (naming its 1-based row);
/// (parameter `truth`) a non-finite or negative truth, a mean or
/// variance beyond [`MAX_TRUTH_SCALE`], or a zero denominator.
pub fn score_with_threshold(
    estimates: &[f64],
    truth: &EstimatorTruth,
    expected_rows: u64,
    z_crit: f64,
) -> Result<EstimatorScore> {
    check_truth(truth)?;
    if estimates.len() as u64 != expected_rows {
        return Err(Error::Invalid {
            param: "estimates",
            reason: format!(
                "{} rows, but the truth is for a set of {expected_rows} rows; \
                 score the whole set, one estimate per row",
                estimates.len()
            ),
        });
    }
    let min_rows = if truth.set_stderr_var.is_some() { 2 } else { 4 };
    if estimates.len() < min_rows {
        return Err(Error::Invalid {
            param: "estimates",
            reason: format!(
                "{} rows; at least {min_rows} are needed for a variance and its standard error",
                estimates.len()
            ),
        });
    }
    if let Some(r) = estimates.iter().position(|x| !x.is_finite()) {
        return Err(Error::Invalid {
            param: "estimates",
            reason: format!(
                "row {} (1-based) is {}; every estimate must be a finite number",
                r + 1,
                estimates[r]
            ),
        });
    }
    let stats = RunningStats::from_values(estimates);
    let mean = stats.mean;
    let var = stats.variance();
    let se_mean = truth.set_stderr_mean.hypot(truth.stderr_mean);
    let (se_set_var, stderr_var_source) = match truth.set_stderr_var {
        Some(v) => (v, VarStderrSource::Truth),
        None => (stats.stderr_variance(), VarStderrSource::Sample),
    };
    let se_var = se_set_var.hypot(truth.stderr_var);
    for (what, v) in [("mean", se_mean), ("variance", se_var)] {
        if !(v > 0.0 && v.is_finite()) {
            return Err(Error::Invalid {
                param: "truth",
                reason: format!("the standard error of the {what} is {v}; a z-score needs one > 0"),
            });
        }
    }
    // The sample's own error of the variance is taken as exact (n rows).
    let dof = truth.stderr_dof;
    let var_dof = dof.filter(|_| stderr_var_source == VarStderrSource::Truth);
    let z_mean = normal_equivalent((mean - truth.mean) / se_mean, dof);
    let z_var = normal_equivalent((var - truth.var) / se_var, var_dof);
    let pass_mean = z_mean.abs() <= z_crit;
    let pass_var = z_var.abs() <= z_crit;
    Ok(EstimatorScore {
        rows: stats.count,
        mean,
        expected_mean: truth.mean,
        stderr_mean_combined: se_mean,
        z_mean,
        var,
        expected_var: truth.var,
        stderr_var_combined: se_var,
        stderr_var_source,
        z_var,
        dof,
        z_crit,
        min_detectable_rel_bias_mean: min_detectable(z_crit, dof, se_mean, truth.mean),
        min_detectable_rel_bias_var: min_detectable(z_crit, var_dof, se_var, truth.var),
        pass_mean,
        pass_var,
        pass: pass_mean && pass_var,
    })
}

/// The smallest relative error of a value `expected` whose test divides by
/// `se` that is caught with probability [`POWER`] at `z_crit`:
/// `reach · se/|expected|` (infinite when `expected` is 0).
fn min_detectable(z_crit: f64, dof: Option<u64>, se: f64, expected: f64) -> f64 {
    reach(z_crit, dof) * se / expected.abs()
}

/// The power of a set before any estimate is made: the smallest relative
/// error of the mean and of the variance of one estimator that its
/// `truth` lets a score at `z_crit` catch with probability [`POWER`] —
/// [`EstimatorScore::min_detectable_rel_bias_mean`] and
/// [`EstimatorScore::min_detectable_rel_bias_var`], which a score reports
/// with the same numbers. Needs the truth's `set_stderr_var` (a set whose
/// truth has none takes the variance's error from its estimates, and its
/// power is known only once scored): None without it.
pub fn min_detectable_rel_bias(truth: &EstimatorTruth, z_crit: f64) -> Option<(f64, f64)> {
    let se_mean = truth.set_stderr_mean.hypot(truth.stderr_mean);
    let se_var = truth.set_stderr_var?.hypot(truth.stderr_var);
    let dof = truth.stderr_dof;
    Some((
        min_detectable(z_crit, dof, se_mean, truth.mean),
        min_detectable(z_crit, dof, se_var, truth.var),
    ))
}

/// Scores one estimator alone (2 tests: `z_crit = Φ⁻¹(1 − alpha/4)`); see
/// [`score_with_threshold`].
pub fn score(
    estimates: &[f64],
    truth: &EstimatorTruth,
    expected_rows: u64,
    alpha: f64,
) -> Result<EstimatorScore> {
    let z_crit = critical_z(alpha, TESTS_PER_ESTIMATOR)?;
    score_with_threshold(estimates, truth, expected_rows, z_crit)
}

/// Which estimator a score is of.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum Estimator {
    /// Normalized V1².
    V1Sq,
    /// Normalized V2².
    V2Sq,
}

impl Estimator {
    /// `v1_sq` or `v2_sq`.
    pub fn name(&self) -> &'static str {
        self.pick("v1_sq", "v2_sq")
    }

    /// Of a pair given V1² first, the one of this estimator: a dependent
    /// crate chooses through it rather than matching on a non-exhaustive
    /// enum.
    ///
    /// ```
    /// use v2ref_core::conformance::score::Estimator;
    /// assert_eq!(Estimator::V2Sq.pick(1.0, 2.0), 2.0);
    /// ```
    pub fn pick<T>(self, v1_sq: T, v2_sq: T) -> T {
        match self {
            Estimator::V1Sq => v1_sq,
            Estimator::V2Sq => v2_sq,
        }
    }
}

/// One estimator's score, named.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct NamedScore {
    /// The estimator.
    pub estimator: Estimator,
    /// Its score.
    #[serde(flatten)]
    pub score: EstimatorScore,
}

/// The scores of the estimators given, under one Bonferroni threshold.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ScoreReport {
    /// The family-wise false-alarm rate.
    pub alpha: f64,
    /// Tests made: 2 per estimator scored.
    pub tests: usize,
    /// `Φ⁻¹(1 − alpha/(2·tests))`.
    pub z_crit: f64,
    /// One entry per estimator given, V1² first.
    pub estimators: Vec<NamedScore>,
    /// Every |z| ≤ z_crit.
    pub pass: bool,
}

/// Scores the estimators given (at least one) against `truth`, for a set
/// of `expected_rows` rows, with the family-wise rate `alpha` shared
/// among all the tests made (Bonferroni).
pub fn score_report(
    v1_sq: Option<&[f64]>,
    v2_sq: Option<&[f64]>,
    truth: &ConventionTruth,
    expected_rows: u64,
    alpha: f64,
) -> Result<ScoreReport> {
    let given = Estimates { v1_sq, v2_sq }.given(truth);
    let tests = TESTS_PER_ESTIMATOR * given.len();
    let z_crit = critical_z(alpha, tests)?;
    let estimators = given
        .into_iter()
        .map(|(estimator, x, t)| {
            Ok(NamedScore {
                estimator,
                score: score_with_threshold(x, t, expected_rows, z_crit)?,
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let pass = estimators.iter().all(|s| s.score.pass);
    Ok(ScoreReport {
        alpha,
        tests,
        z_crit,
        estimators,
        pass,
    })
}

/// A pipeline's per-row estimates of one set (or one channel of a
/// dispersed set), each given by name (`Estimates::default().v1_sq(&a)
/// .v2_sq(&b)`), so that V1² and V2² cannot be swapped by their position.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Estimates<'a> {
    pub(crate) v1_sq: Option<&'a [f64]>,
    pub(crate) v2_sq: Option<&'a [f64]>,
}

impl<'a> Estimates<'a> {
    /// With the normalized V1² of every row.
    pub fn v1_sq(self, v1_sq: &'a [f64]) -> Self {
        Estimates {
            v1_sq: Some(v1_sq),
            ..self
        }
    }

    /// With the normalized V2² of every row.
    pub fn v2_sq(self, v2_sq: &'a [f64]) -> Self {
        Estimates {
            v2_sq: Some(v2_sq),
            ..self
        }
    }

    /// The estimators given, V1² first, each with its truth in `truth`.
    pub(crate) fn given<'t>(
        &self,
        truth: &'t ConventionTruth,
    ) -> Vec<(Estimator, &'a [f64], &'t EstimatorTruth)> {
        [
            (Estimator::V1Sq, self.v1_sq, &truth.v1_sq),
            (Estimator::V2Sq, self.v2_sq, &truth.v2_sq),
        ]
        .into_iter()
        .filter_map(|(e, x, t)| x.map(|x| (e, x, t)))
        .collect()
    }
}

/// One screen: the verdict, then a line per estimator with its mean and
/// variance against the truth, their z-scores and the smallest relative
/// error the set catches (what a failing assertion should print).
impl std::fmt::Display for ScoreReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let verdict = if self.pass { "pass" } else { "FAIL" };
        writeln!(
            f,
            "{verdict}: alpha {:e} over {} tests, every |z| <= {:.3} needed",
            self.alpha, self.tests, self.z_crit
        )?;
        for e in &self.estimators {
            let s = &e.score;
            let mark = |pass: bool| if pass { "" } else { "  <- out" };
            writeln!(
                f,
                "  {} ({} rows): mean {:.6e} expected {:.6e} ± {:.2e}, z {:+.2}{}",
                e.estimator.name(),
                s.rows,
                s.mean,
                s.expected_mean,
                s.stderr_mean_combined,
                s.z_mean,
                mark(s.pass_mean)
            )?;
            writeln!(
                f,
                "  {} variance {:.6e} expected {:.6e} ± {:.2e}, z {:+.2}{}",
                " ".repeat(e.estimator.name().len()),
                s.var,
                s.expected_var,
                s.stderr_var_combined,
                s.z_var,
                mark(s.pass_var)
            )?;
            writeln!(
                f,
                "  {} catches a relative error of {:.2} % of the mean, {:.2} % of the variance",
                " ".repeat(e.estimator.name().len()),
                100.0 * s.min_detectable_rel_bias_mean,
                100.0 * s.min_detectable_rel_bias_var
            )?;
        }
        Ok(())
    }
}
