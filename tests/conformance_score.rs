//! `conformance::score`: exact answers on hand-made sets, the threshold
//! against independent quantiles, the power statement, refusals.
//!
//! Reference quantiles come from Python's standard library
//! (`statistics.NormalDist().inv_cdf`, CPython 3, Wichura's AS241), not
//! from statrs:
//!
//! - Φ⁻¹(1 − 10⁻³/4) = 3.4807564043462422 (one estimator, 2 tests)
//! - Φ⁻¹(1 − 10⁻³/8) = 3.662259930887615 (two estimators, 4 tests)
//! - Φ⁻¹(1 − 0.05/4) = 2.2414027276049464
//! - Φ⁻¹(0.9) = 1.2815515655446008

use v2ref_core::assert_rel_eq;
use v2ref_core::conformance::estimate::BiasConvention;
use v2ref_core::conformance::score::{
    critical_z, score, score_report, Estimator, VarStderrSource, DEFAULT_ALPHA,
};
use v2ref_core::conformance::sidecar::{ConventionTruth, EstimatorTruth, TruthSource};
use v2ref_core::Error;

const Z_2_TESTS: f64 = 3.4807564043462422;
const Z_4_TESTS: f64 = 3.662259930887615;
const Z_005_2_TESTS: f64 = 2.2414027276049464;
const Z_POWER: f64 = 1.2815515655446008;
/// statrs' erfc_inv against AS241: agreement to well below this.
const QUANTILE_REL: f64 = 1e-12;

fn truth(
    mean: f64,
    var: f64,
    set_se_mean: f64,
    se_mean: f64,
    set_se_var: Option<f64>,
    se_var: f64,
) -> EstimatorTruth {
    EstimatorTruth {
        mean,
        var,
        mean_source: TruthSource::ReferenceRun,
        var_source: TruthSource::ReferenceRun,
        stderr_mean: se_mean,
        stderr_var: se_var,
        set_stderr_mean: set_se_mean,
        set_stderr_var: set_se_var,
        stderr_dof: None,
    }
}

#[test]
fn threshold_is_the_bonferroni_normal_quantile() {
    assert_rel_eq!(critical_z(1e-3, 2).unwrap(), Z_2_TESTS, QUANTILE_REL);
    assert_rel_eq!(critical_z(1e-3, 4).unwrap(), Z_4_TESTS, QUANTILE_REL);
    assert_rel_eq!(critical_z(0.05, 2).unwrap(), Z_005_2_TESTS, QUANTILE_REL);
    assert_eq!(DEFAULT_ALPHA, 1e-3);
    for bad in [0.0, 1.0, -0.1, f64::NAN] {
        let e = critical_z(bad, 2).unwrap_err();
        assert_eq!(e.param(), Some("alpha"), "{bad}: {e}");
    }
}

#[test]
fn exact_scores_of_a_four_row_set() {
    // x = 1, 2, 3, 4: mean 5/2, unbiased variance (9/4 + 1/4 + 1/4 + 9/4)/3 = 5/3.
    // se_mean = √(0.4² + 0.3²) = 0.5, so z_mean = (2.5 − 2)/0.5 = 1.
    // se_var = √(0.6² + 0.8²) = 1, so z_var = (5/3 − 1)/1 = 2/3.
    let t = truth(2.0, 1.0, 0.4, 0.3, Some(0.6), 0.8);
    let s = score(&[1.0, 2.0, 3.0, 4.0], &t, 4, 1e-3).unwrap();
    assert_eq!(s.rows, 4);
    assert_rel_eq!(s.mean, 2.5, v2ref_core::tolerance::ULPS);
    assert_rel_eq!(s.var, 5.0 / 3.0, v2ref_core::tolerance::ULPS);
    assert_rel_eq!(s.stderr_mean_combined, 0.5, v2ref_core::tolerance::ULPS);
    assert_rel_eq!(s.stderr_var_combined, 1.0, v2ref_core::tolerance::ULPS);
    assert_eq!(s.stderr_var_source, VarStderrSource::Truth);
    assert_rel_eq!(s.z_mean, 1.0, v2ref_core::tolerance::ROUNDING_REL);
    assert_rel_eq!(s.z_var, 2.0 / 3.0, v2ref_core::tolerance::ROUNDING_REL);
    assert_rel_eq!(s.z_crit, Z_2_TESTS, QUANTILE_REL);
    // (z_crit + Φ⁻¹(0.9)) · 0.5/2 and (z_crit + Φ⁻¹(0.9)) · 1/1.
    assert_rel_eq!(
        s.min_detectable_rel_bias_mean,
        (Z_2_TESTS + Z_POWER) * 0.25,
        QUANTILE_REL
    );
    assert_rel_eq!(
        s.min_detectable_rel_bias_var,
        Z_2_TESTS + Z_POWER,
        QUANTILE_REL
    );
    assert!(s.pass_mean && s.pass_var && s.pass);
}

/// One name, one meaning: the truth's own standard errors are
/// `stderr_mean` and `stderr_var` in the sidecar; the score's denominators
/// combine them with the set's scatter and must not take those names.
#[test]
fn the_score_does_not_reuse_the_truths_stderr_names() {
    let t = truth(2.0, 1.0, 0.4, 0.3, Some(0.6), 0.8);
    let s = score(&[1.0, 2.0, 3.0, 4.0], &t, 4, 1e-3).unwrap();
    let score_json = serde_json::to_value(s).unwrap();
    let truth_json = serde_json::to_value(t).unwrap();
    for name in ["stderr_mean", "stderr_var"] {
        assert!(truth_json.get(name).is_some(), "the sidecar names {name}");
        assert!(score_json.get(name).is_none(), "the score reuses {name}");
        assert!(score_json.get(format!("{name}_combined")).is_some());
    }
}

#[test]
fn variance_stderr_falls_back_to_the_sample() {
    // x = 1, 2, 3, 4: Σ(x − x̄)⁴ = 2·(3/2)⁴ + 2·(1/2)⁴ = 41/4, μ4 = 41/16;
    // se² = (μ4 − (n−3)/(n−1)·s⁴)/n = (41/16 − (1/3)(25/9))/4 = 707/1728.
    let t = truth(2.5, 1.0, 0.5, 0.0, None, 0.0);
    let s = score(&[1.0, 2.0, 3.0, 4.0], &t, 4, 1e-3).unwrap();
    assert_eq!(s.stderr_var_source, VarStderrSource::Sample);
    let se = (707.0f64 / 1728.0).sqrt();
    assert_rel_eq!(
        s.stderr_var_combined,
        se,
        v2ref_core::tolerance::ROUNDING_REL
    );
    assert_rel_eq!(
        s.z_var,
        (2.0 / 3.0) / se,
        v2ref_core::tolerance::ROUNDING_REL
    );
    assert_eq!(s.z_mean, 0.0);
}

#[test]
fn report_shares_alpha_over_every_test_made() {
    let t1 = truth(2.0, 1.0, 0.4, 0.3, Some(0.6), 0.8);
    // V2²: mean 10 expected 11, se 0.25 → z = −4 (beyond 3.66: fails).
    let t2 = truth(11.0, 5.0 / 3.0, 0.25, 0.0, Some(1.0), 0.0);
    let x1 = [1.0, 2.0, 3.0, 4.0];
    let x2 = [8.5, 9.5, 10.5, 11.5];
    let c = ConventionTruth {
        bias: BiasConvention::Model,
        v1_sq: t1,
        v2_sq: t2,
    };
    let r = score_report(Some(&x1), Some(&x2), &c, 4, 1e-3).unwrap();
    assert_eq!(r.tests, 4);
    assert_rel_eq!(r.z_crit, Z_4_TESTS, QUANTILE_REL);
    assert_eq!(r.estimators.len(), 2);
    assert_eq!(r.estimators[0].estimator, Estimator::V1Sq);
    assert!(r.estimators[0].score.pass);
    assert_rel_eq!(
        r.estimators[1].score.z_mean,
        -4.0,
        v2ref_core::tolerance::ROUNDING_REL
    );
    assert!(r.estimators[1].score.z_var.abs() < v2ref_core::tolerance::ROUNDING_REL);
    assert!(!r.estimators[1].score.pass_mean && r.estimators[1].score.pass_var);
    assert!(!r.pass);
    // One estimator alone: 2 tests.
    let r = score_report(None, Some(&x1), &c, 4, 1e-3).unwrap();
    assert_eq!(r.tests, 2);
    assert_eq!(r.estimators[0].estimator, Estimator::V2Sq);
    assert_rel_eq!(r.z_crit, Z_2_TESTS, QUANTILE_REL);
    // Neither: refused.
    assert_eq!(
        score_report(None, None, &c, 4, 1e-3).unwrap_err().param(),
        Some("estimates")
    );
    // JSON field names.
    let json = serde_json::to_value(&r).unwrap();
    for key in ["alpha", "tests", "z_crit", "estimators", "pass"] {
        assert!(json.get(key).is_some(), "{key}");
    }
    let e = &json["estimators"][0];
    for key in [
        "estimator",
        "mean",
        "expected_mean",
        "z_mean",
        "var",
        "expected_var",
        "z_var",
        "min_detectable_rel_bias_mean",
        "min_detectable_rel_bias_var",
        "pass",
    ] {
        assert!(e.get(key).is_some(), "{key}");
    }
    assert_eq!(e["estimator"], "v2_sq");
}

/// n rows alternating mean ± d: mean exactly `mean` (n even), unbiased
/// variance d² n/(n − 1).
fn alternating(n: usize, mean: f64, d: f64) -> Vec<f64> {
    (0..n)
        .map(|i| if i % 2 == 0 { mean + d } else { mean - d })
        .collect()
}

#[test]
fn verdict_flips_beyond_the_stated_power() {
    let n = 1000;
    let d = 0.1;
    let var = d * d * n as f64 / (n - 1) as f64;
    let t = truth(1.0, var, 0.01, 0.002, Some(1e-3), 0.0);
    let unbiased = score(&alternating(n, 1.0, d), &t, n as u64, 1e-3).unwrap();
    assert!(unbiased.pass, "{unbiased:?}");
    let mdb = unbiased.min_detectable_rel_bias_mean;
    // A bias just above the stated power: z = 1.01 (z_crit + 1.28) > z_crit.
    let biased = score(&alternating(n, 1.0 + 1.01 * mdb, d), &t, n as u64, 1e-3).unwrap();
    assert!(!biased.pass_mean && !biased.pass, "{biased:?}");
    // A bias just inside the threshold (z = 0.99 z_crit): passes.
    let inside = 0.99 * unbiased.z_crit * unbiased.stderr_mean_combined;
    let small = score(&alternating(n, 1.0 - inside, d), &t, n as u64, 1e-3).unwrap();
    assert!(small.pass, "{small:?}");
    // The same for the variance: scale the spread.
    let mdb_var = unbiased.min_detectable_rel_bias_var;
    let wide = score(
        &alternating(n, 1.0, d * (1.0 + 1.01 * mdb_var).sqrt()),
        &t,
        n as u64,
        1e-3,
    )
    .unwrap();
    assert!(wide.pass_mean && !wide.pass_var && !wide.pass, "{wide:?}");
}

#[test]
fn refusals_name_the_parameter() {
    let t = truth(2.0, 1.0, 0.4, 0.3, Some(0.6), 0.8);
    let x = [1.0, 2.0, 3.0, 4.0];
    // Length other than the set's.
    let e = score(&x, &t, 5, 1e-3).unwrap_err();
    assert_eq!(e.param(), Some("estimates"));
    assert!(
        e.to_string().contains("4 rows") && e.to_string().contains("5 rows"),
        "{e}"
    );
    let e = score(&x[..3], &t, 4, 1e-3).unwrap_err();
    assert_eq!(e.param(), Some("estimates"));
    // A NaN, named by its row.
    let e = score(&[1.0, f64::NAN, 3.0, 4.0], &t, 4, 1e-3).unwrap_err();
    assert!(
        matches!(
            e,
            Error::Invalid {
                param: "estimates",
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("row 2"), "{e}");
    // Too few rows for a variance.
    assert_eq!(
        score(&[1.0], &t, 1, 1e-3).unwrap_err().param(),
        Some("estimates")
    );
    // A truth that cannot make a z-score.
    let zero = truth(2.0, 1.0, 0.0, 0.0, Some(0.6), 0.8);
    assert_eq!(
        score(&x, &zero, 4, 1e-3).unwrap_err().param(),
        Some("truth")
    );
    let nan = truth(f64::NAN, 1.0, 0.4, 0.3, Some(0.6), 0.8);
    assert_eq!(score(&x, &nan, 4, 1e-3).unwrap_err().param(), Some("truth"));
    let neg = truth(2.0, 1.0, -0.4, 0.3, Some(0.6), 0.8);
    assert_eq!(score(&x, &neg, 4, 1e-3).unwrap_err().param(), Some("truth"));
    // Alpha.
    assert_eq!(score(&x, &t, 4, 0.0).unwrap_err().param(), Some("alpha"));
}

/// Student-t thresholds t_ν(1 − 10⁻³/8) for ν = 1, 3, 7, 15 (blocks 2, 4,
/// 8, 16): ν = 1 in closed form, 1/tan(π·1.25e-4); the others by
/// numerical integration of the t density (Python, 2·10⁵-point midpoint
/// rule in tan-substitution, bisection), independent of statrs.
const T_4_TESTS: [(u64, f64); 4] = [
    (1, 2546.47895857063),
    (3, 20.604087145083604),
    (7, 6.8140354792789335),
    (15, 4.766061725339178),
];

/// A ratio that is t_ν is reported as the normal deviate of the same tail:
/// at the t threshold it equals the normal threshold; t₁ at 1 (tail 1/4
/// exactly) gives Φ⁻¹(3/4); without ν the ratio is unchanged.
#[test]
fn t_ratios_are_reported_as_their_normal_equivalents() {
    use v2ref_core::conformance::score::normal_equivalent;
    const PHI_INV_3_4: f64 = 0.6744897501960817;
    assert_rel_eq!(normal_equivalent(1.0, Some(1)), PHI_INV_3_4, QUANTILE_REL);
    assert_rel_eq!(normal_equivalent(-1.0, Some(1)), -PHI_INV_3_4, QUANTILE_REL);
    assert_eq!(normal_equivalent(0.0, Some(5)), 0.0);
    assert_eq!(normal_equivalent(2.5, None), 2.5);
    for (nu, t) in T_4_TESTS {
        // tol: The integration is good to about 1e-6 of the quantile.
        assert_rel_eq!(normal_equivalent(t, Some(nu)), Z_4_TESTS, 1e-5);
    }
}

/// With ν given, the score divides by the same errors but tests the t
/// ratio: a ratio of 4 fails as normal and passes as t₇ (threshold 6.8),
/// and the power figure uses t quantiles (larger).
#[test]
fn a_spread_over_few_blocks_widens_the_threshold() {
    // x = 1, 2, 3, 4: mean 2.5; se_mean = 0.5, so the ratio is 4 at mean 0.5.
    let normal = truth(0.5, 5.0 / 3.0, 0.4, 0.3, Some(0.6), 0.8);
    let t7 = EstimatorTruth {
        stderr_dof: Some(7),
        ..normal
    };
    let a = score(&[1.0, 2.0, 3.0, 4.0], &normal, 4, 1e-3).unwrap();
    let b = score(&[1.0, 2.0, 3.0, 4.0], &t7, 4, 1e-3).unwrap();
    assert_rel_eq!(a.z_mean, 4.0, v2ref_core::tolerance::ROUNDING_REL);
    assert!(!a.pass_mean && b.pass_mean, "{} {}", a.z_mean, b.z_mean);
    // tol: a bracket, not a tolerance: the normal equivalent of a t(7) ratio of 4 lies well below 4 and above 2.
    assert!(b.z_mean < 3.0 && b.z_mean > 2.0, "{}", b.z_mean);
    assert_eq!((a.dof, b.dof), (None, Some(7)));
    assert!(b.min_detectable_rel_bias_mean > 1.5 * a.min_detectable_rel_bias_mean);
    let zero = EstimatorTruth {
        stderr_dof: Some(0),
        ..normal
    };
    let e = score(&[1.0, 2.0, 3.0, 4.0], &zero, 4, 1e-3).unwrap_err();
    assert_eq!(e.param(), Some("truth"), "{e}");
}
