//! The truth of a synth set gives a valid score at the smallest accepted
//! reference run (issue 26): v2ref's own estimates of its own sets, over
//! many seeds, fail the score no more often than its stated false-alarm
//! rate; the stated spreads of a set match the spread over seeds; and the
//! same count catches a planted 2 % error and the old scoring (a normal
//! quantile on a spread over 2 blocks).
//!
//! The score is run at `ALPHA = 0.1` (not the default 10⁻³) so that false
//! alarms are frequent enough to count: with Bonferroni the rate of a
//! failing set is at most `ALPHA`, so the failures over `SEEDS` sets are
//! below the binomial quantile `B(SEEDS, ALPHA)` at `1 − FALSE_ALARM`
//! (FALSE_ALARM shared by the verdicts checked).

use statrs::distribution::{Binomial, ChiSquared, ContinuousCDF, DiscreteCDF};
use v2ref_core::bounds::{check_set_size, SET_MIN_REFERENCE_BLOCKS};
use v2ref_core::conformance::estimate::{BiasConvention, RowEstimator, BIAS_CONVENTIONS};
use v2ref_core::conformance::score::score_report;
use v2ref_core::conformance::sidecar::{ConventionTruth, EstimatorTruth, Truth};
use v2ref_core::conformance::truth::{reference_seed, truth, TruthSize};
use v2ref_core::formalism::estimator::BinWindow;
use v2ref_core::montecarlo::RunningStats;
use v2ref_core::simulator::{Inputs, Model, PistonInputs, SourceInput};

/// The score's family-wise rate in these tests.
const ALPHA: f64 = 0.1;
/// The false-alarm rate of each test below (of its bounds together).
const FALSE_ALARM: f64 = 1e-6;
/// Rows of each set: the example.
const ROWS: u64 = 100;
/// A planted relative error of both estimators.
const PLANTED: f64 = 0.02;

/// A bright point source (10⁴ photons per sample) on a small scan (N =
/// 32), so that a 2 % error of 100 rows is far outside their scatter.
fn inputs(piston: bool) -> Inputs {
    Inputs {
        samples: 32,
        source: SourceInput::Point,
        photons: 1e4,
        read_noise: 3.0,
        visibility: 0.7,
        piston: piston.then(|| PistonInputs::paper(500.0)),
        ..Inputs::default()
    }
}

/// The rows of a set, row-major.
fn rows_of(model: &Model, rows: u64, seed: u64) -> Vec<f64> {
    let mut out = Vec::new();
    let set = model.rows(rows, seed, 0).unwrap();
    set.stream(0, 8, |b: &[f64]| {
        out.extend_from_slice(b);
        Ok(())
    })
    .unwrap();
    out
}

/// v2ref's own (V1², V2²) of every row of a set.
fn estimates(model: &Model, rows: &[f64], bias: BiasConvention) -> (Vec<f64>, Vec<f64>) {
    let est = RowEstimator::new(model, BinWindow::Positive, bias, true).unwrap();
    let e = est.estimate_rows(rows, 0).unwrap();
    (
        e.iter().map(|r| r.v1_sq).collect(),
        e.iter().map(|r| r.v2_sq).collect(),
    )
}

fn convention(t: &Truth, bias: BiasConvention) -> ConventionTruth {
    let w = t.windows.iter().find(|w| w.bins == BinWindow::Positive);
    w.unwrap()
        .conventions
        .iter()
        .find(|c| c.bias == bias)
        .unwrap()
        .clone()
}

/// Most failing sets out of `seeds` at a true rate `ALPHA`, at false-alarm
/// `FALSE_ALARM / checks`.
fn max_failures(seeds: u64, checks: usize) -> u64 {
    let b = Binomial::new(ALPHA, seeds).unwrap();
    b.inverse_cdf(1.0 - FALSE_ALARM / checks as f64)
}

/// Per seed and convention: the set's estimates and its truth at the
/// smallest accepted block count.
struct Scored {
    failures: [u64; 2],
    planted_failures: [u64; 2],
    /// Per convention and estimator: (set variance, stated set_stderr_var).
    var_spread: [[Vec<(f64, f64)>; 2]; 2],
    /// The `model` convention scored as before issue 26 (2 replicates,
    /// their spread, a normal quantile), and the same with t₁.
    old_failures: u64,
    old_t_failures: u64,
}

/// The `model` truth as the reference run of 2 replicates gave it before
/// issue 26: closed-form mean and variance, the set's variance scattering
/// as the spread of the 2 replicates' variances; `dof` as given.
fn two_block_truth(
    model: &Model,
    seed: u64,
    c: &ConventionTruth,
    dof: Option<u64>,
) -> ConventionTruth {
    let mut vars = [RunningStats::default(), RunningStats::default()];
    for b in 0..2 {
        let rows = rows_of(model, ROWS, reference_seed(seed, b));
        let (v1, v2) = estimates(model, &rows, BiasConvention::Model);
        vars[0].push(RunningStats::from_values(&v1).variance());
        vars[1].push(RunningStats::from_values(&v2).variance());
    }
    let old = |t: &EstimatorTruth, v: &RunningStats| EstimatorTruth {
        set_stderr_var: Some(v.std()),
        stderr_dof: dof,
        ..*t
    };
    ConventionTruth {
        v1_sq: old(&c.v1_sq, &vars[0]),
        v2_sq: old(&c.v2_sq, &vars[1]),
        ..*c
    }
}

fn run(piston: bool, seeds: u64) -> Scored {
    let model = Model::new(&inputs(piston)).unwrap();
    let mut s = Scored {
        failures: [0; 2],
        planted_failures: [0; 2],
        var_spread: Default::default(),
        old_failures: 0,
        old_t_failures: 0,
    };
    for seed in 1..=seeds {
        let size = TruthSize {
            rows: ROWS,
            seed,
            reference_blocks: SET_MIN_REFERENCE_BLOCKS,
            threads: 0,
        };
        let t = truth(&model, size, &|_| {}).unwrap();
        let rows = rows_of(&model, ROWS, seed);
        for (ci, &bias) in BIAS_CONVENTIONS.iter().enumerate() {
            let c = convention(&t, bias);
            let (v1, v2) = estimates(&model, &rows, bias);
            let r = score_report(Some(&v1), Some(&v2), &c, ROWS, ALPHA).unwrap();
            s.failures[ci] += u64::from(!r.pass);
            if seed == 1 {
                for e in &r.estimators {
                    let e = &e.score;
                    println!(
                        "{bias:?}: mdb mean {:.4} var {:.4}, dof {:?}",
                        e.min_detectable_rel_bias_mean, e.min_detectable_rel_bias_var, e.dof
                    );
                }
            }
            let off = |x: &[f64]| x.iter().map(|v| v * (1.0 + PLANTED)).collect::<Vec<_>>();
            let r = score_report(Some(&off(&v1)), Some(&off(&v2)), &c, ROWS, ALPHA).unwrap();
            s.planted_failures[ci] += u64::from(!r.pass);
            for (k, (x, et)) in [(&v1, &c.v1_sq), (&v2, &c.v2_sq)].into_iter().enumerate() {
                let var = RunningStats::from_values(x).variance();
                s.var_spread[ci][k].push((var, et.set_stderr_var.unwrap()));
            }
            if bias == BiasConvention::Model && !piston {
                for (dof, count) in [
                    (None, &mut s.old_failures),
                    (Some(1), &mut s.old_t_failures),
                ] {
                    let old = two_block_truth(&model, seed, &c, dof);
                    let r = score_report(Some(&v1), Some(&v2), &old, ROWS, ALPHA).unwrap();
                    *count += u64::from(!r.pass);
                }
            }
        }
    }
    s
}

/// Seed-variance of a set's variance over the mean stated square of its
/// standard error, and its χ² acceptance interval at `FALSE_ALARM / 4`.
fn spread_ratio(pairs: &[(f64, f64)]) -> (f64, f64, f64) {
    let values: Vec<f64> = pairs.iter().map(|p| p.0).collect();
    let spread = RunningStats::from_values(&values).variance();
    let stated = pairs.iter().map(|p| p.1 * p.1).sum::<f64>() / pairs.len() as f64;
    let dof = (pairs.len() - 1) as f64;
    let chi2 = ChiSquared::new(dof).unwrap();
    let fa = FALSE_ALARM / 8.0;
    let lo = chi2.inverse_cdf(fa) / dof;
    let hi = chi2.inverse_cdf(1.0 - fa) / dof;
    (spread / stated, lo, hi)
}

fn check(s: &Scored, seeds: u64, what: &str) {
    let max = max_failures(seeds, 2);
    for (ci, bias) in BIAS_CONVENTIONS.iter().enumerate() {
        let f = s.failures[ci];
        println!("{what} {bias:?}: {f}/{seeds} sets fail at alpha {ALPHA} (bound {max})");
        assert!(
            f <= max,
            "{what} {bias:?}: {f} of {seeds} fail; at most {max}"
        );
        // Power: the planted 2 % error fails (almost) every set.
        let p = s.planted_failures[ci];
        println!("{what} {bias:?}: planted {PLANTED}: {p}/{seeds} fail");
        assert!(
            p >= seeds * 9 / 10,
            "{what} {bias:?}: planted error: {p}/{seeds}"
        );
        for (k, name) in ["V1²", "V2²"].iter().enumerate() {
            let (r, lo, hi) = spread_ratio(&s.var_spread[ci][k]);
            println!("{what} {bias:?} {name}: var spread/stated² = {r:.3} in [{lo:.3}, {hi:.3}]");
            assert!((lo..=hi).contains(&r), "{what} {bias:?} {name}: {r}");
        }
    }
}

/// The smallest accepted count, and the refusals around it.
#[test]
fn smallest_block_count_is_checked() {
    assert_eq!(SET_MIN_REFERENCE_BLOCKS, 8);
    for bad in [1, 2, SET_MIN_REFERENCE_BLOCKS - 1, 1001] {
        let e = check_set_size(100, 32, bad).unwrap_err();
        assert_eq!(e.param(), Some("reference_blocks"), "{bad}: {e}");
    }
    for good in [0, SET_MIN_REFERENCE_BLOCKS, 1000] {
        check_set_size(100, 32, good).unwrap();
    }
}

/// Without piston: pooled reference rows, normal scores. 100 sets (10 s):
/// the bound is 27 failures where the old scoring fails about half.
#[test]
#[ignore = "slow tier: sets of the conformance truth without piston at the smallest block count (12 s)"]
fn no_piston_false_alarms_at_the_smallest_block_count() {
    no_piston_false_alarms(100);
}

/// The same on 200 sets (20 s): bound 43, the old scoring fails 103.
#[test]
#[ignore = "slow tier: 200 sets of the conformance truth without piston (20 s)"]
fn no_piston_false_alarms_on_200_sets() {
    no_piston_false_alarms(200);
}

fn no_piston_false_alarms(seeds: u64) {
    let s = run(false, seeds);
    check(&s, seeds, "no piston");
    // The test's power: the old scoring fails it, and t₁ on the same
    // 2-block spread passes it (valid, if nearly blind).
    let max = max_failures(seeds, 2);
    let (old, old_t) = (s.old_failures, s.old_t_failures);
    println!("2 blocks: normal {old}/{seeds} fail, t1 {old_t}/{seeds} (bound {max})");
    assert!(old > max, "the old scoring: {old} of {seeds} fail");
    assert!(old_t <= max, "t1 on 2 blocks: {old_t} of {seeds} fail");
}

/// With piston: blocks replicate the set, scores are Student-t with 7
/// degrees of freedom.
#[test]
#[ignore = "slow tier: sets of the conformance truth with piston at the smallest block count (6 s)"]
fn piston_false_alarms_at_the_smallest_block_count() {
    const SEEDS: u64 = 60;
    let s = run(true, SEEDS);
    check(&s, SEEDS, "piston");
}
