//! Speed of the bias studies' inner loops (release, criterion).

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use v2ref_core::bias::finite_scan::{self, Kernel, Method};
use v2ref_core::formalism::estimator::wide_band;
use v2ref_core::formalism::interferogram::Sampling;
use v2ref_core::formalism::observation::{Frequency, Observation};
use v2ref_core::formalism::phase::SpectralPhase;
use v2ref_core::formalism::source::Source;
use v2ref_core::formalism::spectrum::{Band, Spectrum};
use v2ref_core::math::special::fresnel_cs;
use v2ref_reproduction::cases::DX_UM;

fn disk_at(s: f64) -> Observation {
    Observation::new(
        Spectrum::flat(Band::k()),
        Source::UniformDisk { diameter_mas: 43.0 },
        Frequency::SpatialFreqCpas(s),
        SpectralPhase::zero(),
    )
    .unwrap()
}

fn benches(c: &mut Criterion) {
    let obs = disk_at(28.0);
    c.bench_function("wide_band (V1, V2 infinite scan), one S", |b| {
        b.iter(|| wide_band(black_box(&obs)))
    });
    for stroke in [64.0, 256.0] {
        let sampling = Sampling::from_stroke(stroke, DX_UM, false).unwrap();
        let cal = finite_scan::calibrator_raw(&obs, &sampling, Method::Dft).unwrap();
        c.bench_function(&format!("finite-scan bias, DFT path, {stroke} um"), |b| {
            b.iter(|| {
                finite_scan::finite_scan_bias(black_box(&obs), &sampling, Method::Dft, Some(cal))
                    .unwrap()
            })
        });
        let method = Method::Convolution(Kernel::Dirichlet);
        let cal = finite_scan::calibrator_raw(&obs, &sampling, method).unwrap();
        c.bench_function(
            &format!("finite-scan bias, convolution path, {stroke} um"),
            |b| {
                b.iter(|| {
                    finite_scan::finite_scan_bias(black_box(&obs), &sampling, method, Some(cal))
                        .unwrap()
                })
            },
        );
    }
    let flat = Spectrum::flat(Band::k());
    let samples: Vec<usize> = (2..=930).collect();
    c.bench_function("Fig. 0 curve, 929 strokes", |b| {
        b.iter(|| {
            v2ref_core::bias::normalization::deviation_curve(black_box(&flat), DX_UM, &samples)
                .unwrap()
        })
    });
    c.bench_function("Fresnel C, S at x = 0.9 and 3.7", |b| {
        b.iter(|| (fresnel_cs(black_box(0.9)), fresnel_cs(black_box(3.7))))
    });
}

criterion_group! {
    name = bias;
    config = Criterion::default().sample_size(20).measurement_time(std::time::Duration::from_secs(2)).warm_up_time(std::time::Duration::from_millis(500));
    targets = benches
}
criterion_main!(bias);
