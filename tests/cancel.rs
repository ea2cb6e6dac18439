//! Cancellation returns through `Result` (`v2ref_core::montecarlo::cancel`): a Monte Carlo
//! cancelled midway returns `Error::Cancelled` from the call that ran it,
//! with no panic unwound (so that a crate built with `panic = "abort"`
//! gets the error too, not an abort).

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};
use v2ref_core::conformance::estimate::BiasConvention;
use v2ref_core::formalism::estimator::BinWindow;
use v2ref_core::montecarlo::cancel::{self, run_cancellable, Token};
use v2ref_core::noise::calibrated::Trials;
use v2ref_core::noise::simulation::{simulate_noisy, NoisySpec};
use v2ref_core::noise::Formula;
use v2ref_core::simulator::{simulate, Inputs, Model};
use v2ref_core::Error;

/// Trials enough for hours of work: only a cancellation ends the run soon.
const ENDLESS_TRIALS: u64 = 1 << 40;

fn model() -> Model {
    Model::new(&Inputs {
        samples: 32,
        read_noise: 1.5,
        ..Inputs::default()
    })
    .unwrap()
}

/// Runs `run` with `token` held by the calling thread (and so by the
/// threads of the pools it builds), outside `run_cancellable`, which would
/// catch an unwind: a panic reaches `catch_unwind` here.
fn held<T>(token: &Token, run: impl FnOnce() -> T) -> std::thread::Result<T> {
    cancel::hold(Some(token.clone()));
    let out = catch_unwind(AssertUnwindSafe(run));
    cancel::hold(None);
    out
}

#[test]
fn a_monte_carlo_cancelled_midway_returns_the_error_and_unwinds_nothing() {
    let model = model();
    let spec = NoisySpec {
        modulated: model.signal.modulated.clone(),
        continuum: model.signal.continuum.clone(),
        noise: model.noise,
        bins: model.bins(BinWindow::Positive),
    };
    let token = Token::new();
    let reports = AtomicU64::new(0);
    // The first progress report cancels the run (as Python's Ctrl-C does).
    let progress = |_: u64| {
        reports.fetch_add(1, Ordering::Relaxed);
        token.cancel();
    };
    let noisy = held(&token, || {
        simulate_noisy(&spec, ENDLESS_TRIALS, 1, 2, &progress)
    });
    assert!(
        matches!(noisy, Ok(Err(Error::Cancelled))),
        "the noise Monte Carlo: {:?}",
        noisy.map(|r| r.map(|_| ()))
    );
    // Each unit stops at its first report: a handful, not 2^40 trials' worth.
    assert!(reports.load(Ordering::Relaxed) < 1000);

    // The rows' Monte Carlo (every row estimated: `--bias counts`).
    let token = Token::new();
    let size = Trials {
        trials: ENDLESS_TRIALS,
        seed: 2,
        threads: 2,
    };
    let cancel_it = |_: u64| token.cancel();
    let rows = held(&token, || {
        let r = simulate(
            &model,
            BinWindow::Positive,
            BiasConvention::Counts,
            Formula::Exact,
            size,
            &cancel_it,
        );
        r.map(|_| ())
    });
    assert!(
        matches!(rows, Ok(Err(Error::Cancelled))),
        "the rows' Monte Carlo: {rows:?}"
    );
}

#[test]
fn a_run_cancelled_from_another_thread_returns_the_error_within_a_second() {
    let model = model();
    let token = Token::new();
    let size = Trials {
        trials: ENDLESS_TRIALS,
        seed: 3,
        threads: 2,
    };
    let canceller = token.clone();
    let started = Instant::now();
    let stopper = std::thread::spawn(move || {
        std::thread::sleep(Duration::from_millis(100));
        canceller.cancel();
    });
    let out = run_cancellable(&token, || {
        simulate(
            &model,
            BinWindow::Band,
            BiasConvention::Counts,
            Formula::Exact,
            size,
            &|_| {},
        )
        .map(|_| ())
    });
    stopper.join().unwrap();
    assert_eq!(out, Err(Error::Cancelled));
    assert!(
        started.elapsed() < Duration::from_secs(2),
        "{:?}",
        started.elapsed()
    );
    // The token cancelled before the run: the error at once, no work.
    assert_eq!(run_cancellable(&token, || Ok(())), Err(Error::Cancelled));
}

#[test]
fn an_uncancelled_token_changes_no_bit() {
    let model = model();
    let size = Trials {
        trials: 4000,
        seed: 4,
        threads: 2,
    };
    let run = || {
        simulate(
            &model,
            BinWindow::Positive,
            BiasConvention::Counts,
            Formula::Exact,
            size,
            &|_| {},
        )
        .map(|r| (r.v1_sq.mean.to_bits(), r.v2_sq.mean.to_bits()))
    };
    let plain = run().unwrap();
    let under_token = run_cancellable(&Token::new(), run).unwrap();
    assert_eq!(plain, under_token);
}

#[test]
fn the_runners_stop_between_units_and_the_kernels_need_no_check() {
    use v2ref_core::montecarlo::{map_items, run_units};
    let token = Token::new();
    token.cancel();
    let ran = AtomicU64::new(0);
    // A cancelled run: the runners return the error before a unit runs.
    let out = held(&token, || {
        let units = run_units(1, 1000, 2, |_, _| ran.fetch_add(1, Ordering::Relaxed));
        let items = map_items(1000, 1, |i| i);
        (units.map(|_| ()), items.map(|_| ()))
    });
    assert_eq!(out.unwrap(), (Err(Error::Cancelled), Err(Error::Cancelled)));
    assert_eq!(ran.load(Ordering::Relaxed), 0);
    // A kernel (here the FFT) runs to its end under a cancelled token:
    // only the runner around it decides.
    let x = vec![num_complex::Complex64::new(1.0, 0.0); 64];
    let spectrum = held(&token, || v2ref_core::math::fft::inverse_dft(&x));
    assert_eq!(spectrum.unwrap().len(), 64);
}
