//! The piston Monte Carlo's standard errors are honest where consecutive
//! scans are correlated: on a CHARA-like case (330 m baseline in H, 10 m/s
//! wind: the piston's correlation time B/v is 33 s, hundreds of scans), the
//! spread of the bias and scatter over 30 seeds matches the errors the run
//! states (from the spread between its independent piston sequences), and
//! does not match the naive errors that treat the scans as independent.
//!
//! The test: R = (variance of the 30 values) / (mean of the 30 stated
//! squared errors). If the errors are right, 29 R follows χ² with 29
//! degrees of freedom (the stated errors are themselves averaged over 30
//! runs of 15 degrees of freedom each: their own noise, 7%, is small beside
//! the bounds). The bounds are the χ²₂₉ quantiles at a false-alarm rate of
//! 1e-6 per quantity (R in [0.20, 2.64]): the test rejects errors wrong by
//! a factor 1.6 or more (R off by 2.6), which the naive error is.

use v2ref_core::formalism::estimator::BinWindow;
use v2ref_core::formalism::observation::{Frequency, Observation};
use v2ref_core::formalism::phase::SpectralPhase;
use v2ref_core::formalism::source::Source;
use v2ref_core::formalism::spectrum::{Band, Spectrum};
use v2ref_core::montecarlo::{replicated_summary, RunningStats, Summary};
use v2ref_core::piston::spectrum::PistonSpectrum;
use v2ref_core::piston::turbulence::Turbulence;
use v2ref_core::piston::{
    simulate_consecutive, simulate_piston, Detector, PistonReference, PistonRun, RunSize, ScanSetup,
};

use statrs::distribution::{ChiSquared, ContinuousCDF};

const SEEDS: u64 = 30;
const SCANS: usize = 512;
/// False-alarm rate per quantity tested.
const FALSE_ALARM: f64 = 1e-6;

/// The CHARA-like case of issue 26: λ 1.65 µm, 300 nm, a 0.5 mas disk on
/// 330 m, 1 m apertures, 1″ seeing at 0.5 µm (r0 ∝ λ^{6/5}), 10 m/s.
fn chara_like() -> (Observation, PistonSpectrum, ScanSetup) {
    let obs = Observation::new(
        Spectrum::flat(Band::new(1.65, 0.3).unwrap()),
        Source::uniform_disk(0.5).unwrap(),
        Frequency::BaselineM(330.0),
        SpectralPhase::zero(),
    )
    .unwrap();
    let seeing_h = 1.0 * (1.65f64 / 0.5).powf(-0.2);
    let turb = Turbulence::from_seeing(seeing_h, 1.65, 10.0, None).unwrap();
    let spectrum = PistonSpectrum::new(turb, 1.0, 330.0).unwrap();
    let setup = ScanSetup {
        samples: 128,
        dx_um: 0.5,
        wavelength_um: 1.65,
        fringe_hz: 300.0,
        reference: PistonReference::Mean,
    };
    (obs, spectrum, setup)
}

/// The four quantities of each seed: (value, stated error, naive error).
fn quantities(s: &Summary, scans: usize) -> [(f64, f64, f64); 2] {
    let n = scans as f64;
    [
        (s.mean, s.stderr_mean, s.std / n.sqrt()),
        // Naive error of a standard deviation of n independent values
        // (normal): s/√(2n).
        (s.std, s.stderr_std, s.std / (2.0 * n).sqrt()),
    ]
}

/// R for each of the four quantities, with the stated and the naive errors,
/// over the runs `run(seed)`.
fn ratios(run: &dyn Fn(u64) -> PistonRun) -> Vec<(&'static str, f64, f64)> {
    let mut per_seed = Vec::new();
    for seed in 1..=SEEDS {
        let run = run(seed);
        let w = run.window(BinWindow::Positive);
        let [b1, s1] = quantities(&w.v1, SCANS);
        let [b2, s2] = quantities(&w.v2, SCANS);
        per_seed.push([b1, b2, s1, s2]);
    }
    let names = ["bias V1", "bias V2", "scatter V1", "scatter V2"];
    (0..4)
        .map(|q| {
            let values: Vec<f64> = per_seed.iter().map(|s| s[q].0).collect();
            let spread = RunningStats::from_values(&values).variance();
            let mean_sq = |pick: fn(&(f64, f64, f64)) -> f64| {
                per_seed.iter().map(|s| pick(&s[q]).powi(2)).sum::<f64>() / SEEDS as f64
            };
            (
                names[q],
                spread / mean_sq(|t| t.1),
                spread / mean_sq(|t| t.2),
            )
        })
        .collect()
}

/// The acceptance interval of R.
fn bounds() -> (f64, f64) {
    let dof = (SEEDS - 1) as f64;
    let chi2 = ChiSquared::new(dof).unwrap();
    (
        chi2.inverse_cdf(FALSE_ALARM / 2.0) / dof,
        chi2.inverse_cdf(1.0 - FALSE_ALARM / 2.0) / dof,
    )
}

#[test]
fn stated_errors_match_the_spread_over_seeds_and_naive_ones_do_not() {
    let (lo, hi) = bounds();
    // tol: a bracket of the chi-squared bounds themselves (not a tolerance): with these seeds they must be neither degenerate nor so wide that the test has no power.
    assert!(lo > 0.15 && hi < 3.0, "bounds [{lo}, {hi}]");
    let (obs, spectrum, setup) = chara_like();
    let size = |seed| RunSize {
        scans: SCANS,
        seed,
        threads: 0,
    };
    let det = [Detector::Sampled];
    let r = ratios(&|seed| {
        simulate_piston(&obs, &spectrum, &setup, &det, &size(seed), None).unwrap()[0].clone()
    });
    for (name, stated, _) in &r {
        assert!(
            (lo..=hi).contains(stated),
            "{name}: spread / stated error squared = {stated:.2}, outside [{lo:.2}, {hi:.2}]"
        );
    }
    // The former method: consecutive scans of one sequence, with errors
    // that treat them as independent. The same test fails.
    let naive = ratios(&|seed| {
        simulate_consecutive(&obs, &spectrum, &setup, &det, &size(seed)).unwrap()[0].clone()
    });
    let failed: Vec<_> = naive
        .iter()
        .filter(|(_, _, r)| !(lo..=hi).contains(r))
        .collect();
    println!("stated: {r:?}\nnaive: {naive:?}");
    assert!(failed.len() >= 2, "naive errors pass: {naive:?}");
}

#[test]
fn replicated_errors_by_hand() {
    // Two groups: {1, 3} (mean 2) and {5, 7, 9} (mean 7); pooled mean
    // 5, N = 5, weights 2/5 and 3/5.
    let groups = [
        RunningStats::from_values(&[1.0, 3.0]),
        RunningStats::from_values(&[5.0, 7.0, 9.0]),
    ];
    let s = replicated_summary(&groups);
    assert_eq!(s.count, 5);
    assert!((s.mean - 5.0).abs() < v2ref_core::tolerance::ULPS);
    // K/(K−1) Σ w²(m − m̄)² = 2 [(0.4·−3)² + (0.6·2)²] = 2 (1.44 + 1.44).
    assert!((s.stderr_mean - (2.0f64 * 2.88).sqrt()).abs() < v2ref_core::tolerance::ROUNDING_REL);
    // q_j about the pooled mean: group 1: (16 + 4)/2 = 10; group 2:
    // (0 + 4 + 16)/3 = 20/3; q̄ = 0.4·10 + 0.6·20/3 = 8; var = 8·5/4 = 10.
    // tol: a variance of a few small integers, tens of roundings of numbers up to 100.
    assert!((s.var - 10.0).abs() < 1e-13);
    let se_var = (2.0f64 * ((0.4f64 * 2.0).powi(2) + (0.6f64 * (20.0 / 3.0 - 8.0)).powi(2))).sqrt()
        * 5.0
        / 4.0;
    assert!(
        // tol: a variance of a few small integers, tens of roundings of numbers up to 100.
        (s.stderr_var - se_var).abs() < 1e-13,
        "{} {se_var}",
        s.stderr_var
    );
    // tol: a variance of a few small integers, tens of roundings of numbers up to 100.
    assert!((s.stderr_std - se_var / (2.0 * 10f64.sqrt())).abs() < 1e-13);
    // One group: no spread to measure.
    assert!(replicated_summary(&groups[..1]).stderr_mean.is_nan());
}
