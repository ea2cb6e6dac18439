//! The calibrated, bias-subtracted estimators (`noise::calibrated`): closed
//! forms, and the Monte Carlo against them (as `v2ref simulate` runs it).

use v2ref_core::formalism::estimator::{dft, raw_estimates, BinWindow};
use v2ref_core::formalism::interferogram::Sampling;
use v2ref_core::formalism::observation::{Frequency, Observation};
use v2ref_core::formalism::phase::SpectralPhase;
use v2ref_core::formalism::source::Source;
use v2ref_core::formalism::spectrum::{Band, Spectrum};
use v2ref_core::noise::calibrated::{calibrated_run, expectation, CalibratedSetup, Trials};
use v2ref_core::noise::window_variance::window_stats;
use v2ref_core::noise::{window_bias, Formula, NoiseModel};

const VISIBILITY: f64 = 0.7;

fn setup(window: BinWindow) -> CalibratedSetup {
    let obs = Observation::new(
        Spectrum::flat(Band::k()),
        Source::Point,
        Frequency::SpatialFreqCpas(40.0),
        SpectralPhase::zero(),
    )
    .unwrap();
    let sampling = Sampling::new(32, 0.5, false).unwrap();
    CalibratedSetup::new(&obs, &sampling, 50.0, VISIBILITY, window).unwrap()
}

fn noise() -> NoiseModel {
    NoiseModel::new(2.0, true).unwrap()
}

#[test]
fn the_exact_formula_gives_v_squared_and_the_window_variance_over_calib_squared() {
    for window in [BinWindow::Positive, BinWindow::All] {
        let s = setup(window);
        let e = expectation(&s, &noise(), Formula::Exact).unwrap();
        // A point source's fringe scaled by V: signal = V² calib, and the
        // exact bias is the one subtracted.
        let v2 = VISIBILITY * VISIBILITY;
        assert!(
            // tol: closed forms against the same closed forms rescaled by V² and the calibration: a few roundings of order-one values.
            (e.mean_v1_sq - v2).abs() < 1e-12,
            "{window:?}: {}",
            e.mean_v1_sq
        );
        assert!(
            // tol: closed forms against the same closed forms rescaled by V² and the calibration: a few roundings of order-one values.
            (e.mean_v2_sq - v2).abs() < 1e-12,
            "{window:?}: {}",
            e.mean_v2_sq
        );
        assert_eq!(e.true_bias, e.subtracted_bias);
        let calib = raw_estimates(&dft(&s.calibrator.modulated), &s.bins).unwrap();
        assert_eq!(e.calibration, calib);
        let w = window_stats(
            &s.signal.modulated,
            &s.signal.mean_counts(),
            &noise(),
            &s.bins,
        )
        .unwrap();
        let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
        assert!(
            rel(
                e.var_v1_sq.unwrap(),
                w.var_v1_sq / (calib.v1_sq * calib.v1_sq)
            ) < 1e-12 // tol: the same quadratic form rescaled by the calibration squared: a few roundings.
        );
        assert!(
            rel(
                e.var_v2_sq.unwrap(),
                w.var_v2_sq / (calib.v2_sq * calib.v2_sq)
            ) < 1e-12 // tol: the same quadratic form rescaled by the calibration squared: a few roundings.
        );
    }
}

#[test]
fn the_published_formula_leaves_the_bias_difference_over_calib() {
    let s = setup(BinWindow::Positive);
    let e = expectation(&s, &noise(), Formula::Published).unwrap();
    let ifg = &s.signal;
    let bias = |f| window_bias(f, &noise(), &ifg.modulated, &ifg.continuum, &s.bins);
    let (exact, published) = (bias(Formula::Exact), bias(Formula::Published));
    let v2 = VISIBILITY * VISIBILITY;
    let want1 = v2 + (exact.v1_sq - published.v1_sq) / e.calibration.v1_sq;
    let want2 = v2 + (exact.v2_sq - published.v2_sq) / e.calibration.v2_sq;
    assert!(
        // tol: closed forms against the same closed forms rescaled by V² and the calibration: a few roundings of order-one values.
        (e.mean_v1_sq - want1).abs() < 1e-12,
        "{} vs {want1}",
        e.mean_v1_sq
    );
    assert!(
        // tol: closed forms against the same closed forms rescaled by V² and the calibration: a few roundings of order-one values.
        (e.mean_v2_sq - want2).abs() < 1e-12,
        "{} vs {want2}",
        e.mean_v2_sq
    );
}

#[test]
fn a_window_without_the_calibrators_fringe_is_refused() {
    let obs = Observation::new(
        Spectrum::flat(Band::k()),
        Source::Point,
        Frequency::SpatialFreqCpas(40.0),
        SpectralPhase::zero(),
    )
    .unwrap();
    let sampling = Sampling::new(32, 0.5, false).unwrap();
    let s = CalibratedSetup::new(&obs, &sampling, 0.0, 1.0, BinWindow::Positive).unwrap();
    let e = expectation(&s, &noise(), Formula::Exact).unwrap_err();
    assert_eq!(e.param(), Some("bins"));
}

#[test]
fn the_monte_carlo_mean_and_variance_match_the_expectation() {
    let s = setup(BinWindow::Positive);
    let size = Trials {
        trials: 40_000,
        seed: 7,
        threads: 0,
    };
    let run = calibrated_run(&s, &noise(), Formula::Exact, size, &|_| {}).unwrap();
    let e = run.expected;
    for (name, mc, mean, var) in [
        ("V1²", run.v1_sq, e.mean_v1_sq, e.var_v1_sq.unwrap()),
        ("V2²", run.v2_sq, e.mean_v2_sq, e.var_v2_sq.unwrap()),
    ] {
        let z = (mc.mean - mean) / mc.stderr_mean;
        assert!(
            z.abs() < v2ref_core::tolerance::MC_SIGMAS,
            "{name}: mean {} vs {mean} (z = {z})",
            mc.mean
        );
        // Power: a 2 % error in the expectation would be caught.
        let z_wrong = (mc.mean - 1.02 * mean) / mc.stderr_mean;
        assert!(
            z_wrong.abs() > 5.0,
            "{name}: cannot tell 1.02 x (z = {z_wrong})"
        );
        let z_var = (mc.var - var) / mc.stderr_var;
        assert!(
            z_var.abs() < v2ref_core::tolerance::MC_SIGMAS,
            "{name}: var {} vs {var} (z = {z_var})",
            mc.var
        );
    }
}
