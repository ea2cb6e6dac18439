//! Piston Monte Carlo throughput: scans simulated per second (the fringe
//! synthesis, the FFT and both estimators over the three bin windows), for
//! the sampled and the integrating detector, and the sequence synthesis.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use v2ref_core::formalism::observation::{Frequency, Observation};
use v2ref_core::formalism::phase::SpectralPhase;
use v2ref_core::formalism::source::Source;
use v2ref_core::formalism::spectrum::{Band, Spectrum};
use v2ref_core::piston::spectrum::PistonSpectrum;
use v2ref_core::piston::turbulence::Turbulence;
use v2ref_core::piston::{
    simulate_piston, synthesize_series, Detector, RunSize, ScanSetup, DEFAULT_SUB_SAMPLES,
};

fn bench(c: &mut Criterion) {
    let turb = Turbulence::from_seeing(1.0, 2.2, 10.0, None).unwrap();
    let spectrum = PistonSpectrum::new(turb, 0.45, 18.0).unwrap();
    // Build the table outside the timed loop.
    let _ = spectrum.psd_um2_per_hz(1.0);
    let obs = Observation::new(
        Spectrum::flat(Band::k()),
        Source::Point,
        Frequency::BaselineM(18.0),
        SpectralPhase::zero(),
    )
    .unwrap();
    let scans = 2000;
    let mut g = c.benchmark_group("piston_scans");
    g.throughput(Throughput::Elements(scans as u64));
    g.sample_size(10);
    for (name, det) in [
        ("sampled", Detector::Sampled),
        (
            "integrating_default",
            Detector::Integrating {
                sub_samples: DEFAULT_SUB_SAMPLES,
            },
        ),
    ] {
        g.bench_function(name, |b| {
            b.iter(|| {
                simulate_piston(
                    &obs,
                    &spectrum,
                    &ScanSetup::paper(300.0),
                    &[det],
                    &RunSize {
                        scans,
                        seed: 1,
                        threads: 1,
                    },
                    None,
                )
                .unwrap()
            })
        });
    }
    g.finish();
    let mut g = c.benchmark_group("piston_sequence");
    let len = 1 << 20;
    g.throughput(Throughput::Elements(len as u64));
    g.sample_size(10);
    g.bench_function("synthesize_2^20", |b| {
        b.iter(|| synthesize_series(&|nu| spectrum.psd_um2_per_hz(nu), 1e-3, len, 1, 1).unwrap())
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
