//! Throughput of the noisy Monte Carlo (issue: Monte Carlo engine,
//! performance): 128-sample interferograms per second with both estimators,
//! beside the cost of drawing the same noise alone, for Gaussian detector
//! noise and Poisson photon noise, all bins and the positive-frequency
//! window, on one thread and on all cores.
//!
//! Run: `cargo bench --bench montecarlo`. The NumPy comparison is
//! `python3 benches/numpy_baseline.py`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::hint::black_box;
use v2ref_core::formalism::estimator::BinWindow;
use v2ref_core::formalism::spectrum::{Band, Spectrum};
use v2ref_core::noise::simulation::{
    draw_noise_only, simulate_noisy, NoisySpec, WindowedEstimators,
};
use v2ref_core::noise::{example_interferogram, NoiseModel};
use v2ref_reproduction::cases::appendix_setup;

const TRIALS: u64 = 1 << 16;

fn spec(noise: NoiseModel, window: BinWindow) -> NoisySpec {
    let ifg = example_interferogram(&appendix_setup()).expect("the Appendix case");
    NoisySpec {
        bins: window.bins(128, 0.5, &Spectrum::flat(Band::k())).unwrap(),
        modulated: ifg.modulated,
        continuum: ifg.continuum,
        noise,
    }
}

fn throughput(c: &mut Criterion) {
    let mut g = c.benchmark_group("interferograms_128");
    g.throughput(Throughput::Elements(TRIALS));
    g.sample_size(10);
    g.measurement_time(std::time::Duration::from_secs(4));
    let cases = [
        ("gaussian", NoiseModel::detector(2.0).expect("valid")),
        ("poisson", NoiseModel::photon()),
    ];
    for (name, noise) in cases {
        for (wname, window) in [("all", BinWindow::All), ("positive", BinWindow::Positive)] {
            let s = spec(noise, window);
            for threads in [1usize, 2] {
                let id = format!("{name}/{wname}/threads{threads}");
                g.bench_function(BenchmarkId::new("simulate", &id), |b| {
                    b.iter(|| {
                        black_box(simulate_noisy(&s, TRIALS, 1, threads, &|_| {}).expect("runs"))
                    })
                });
            }
        }
        let s = spec(noise, BinWindow::All);
        for threads in [1usize, 2] {
            let id = format!("{name}/threads{threads}");
            g.bench_function(BenchmarkId::new("noise_only", &id), |b| {
                b.iter(|| black_box(draw_noise_only(&s, TRIALS, 1, threads).expect("runs")))
            });
        }
    }
    g.finish();

    // The estimators alone on a fixed interferogram (per evaluation).
    let mut e = c.benchmark_group("estimators_128");
    e.sample_size(20);
    let ifg = example_interferogram(&appendix_setup()).expect("the Appendix case");
    for (wname, window) in [
        ("all", BinWindow::All),
        ("positive", BinWindow::Positive),
        ("band", BinWindow::Band),
    ] {
        let est = WindowedEstimators::new(
            128,
            &window.bins(128, 0.5, &Spectrum::flat(Band::k())).unwrap(),
        );
        let mut scratch = Vec::new();
        e.bench_function(wname, |b| {
            b.iter(|| black_box(est.raw(black_box(&ifg.modulated), &mut scratch)))
        });
    }
    e.finish();
}

criterion_group!(benches, throughput);
criterion_main!(benches);
