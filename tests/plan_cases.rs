//! The planner on three instruments not tuned for: a CHARA-like H-band
//! 330 m baseline on a 0.5 mas star of H = 6, a PIONIER-like 2 mas disk near
//! its first null on 183.7 m, and a visible 0.7 µm, 50 nm band on 50 m.
//!
//! - **Seed-stable**: the recommendation (estimator, fringe frequency,
//!   stroke) is the same for five seeds, in the slow tier on two cases: a
//!   bright, piston-dominated star whose observation is short (about 2 000
//!   scans) and the CHARA-like case near its optimum (the observation's
//!   cost is now the atmosphere's, not n's); by hand on the three full
//!   grids.
//! - **Independent numbers**: the bandwidth bias of V1² and V2² of the
//!   recommended point against a Simpson quadrature written here, with
//!   2J1(x)/x from Bessel's integral (no code of the crate), over the band
//!   flat per unit wavenumber.

use v2ref_commands::plan::photometry::{Band2Mass, Magnitude};
use v2ref_commands::plan::{default_grid, plan, Estimator, PlanInputs, PlanPoint, Target};
use v2ref_core::piston::PistonReference;
use v2ref_core::piston::DEFAULT_SUB_SAMPLES;
use v2ref_core::simulator::{Inputs, PistonInputs, SourceInput, SpectrumInput};

/// One case: its inputs on the default grid.
struct Case {
    name: &'static str,
    inputs: PlanInputs,
}

fn atmosphere(
    wavelength_um: f64,
    seeing_05: f64,
    aperture_m: f64,
    l0: Option<f64>,
) -> PistonInputs {
    PistonInputs {
        fringe_hz: 1.0,
        wavelength_um,
        // Seeing given at 0.5 µm, r0 ∝ λ^{6/5}: seeing ∝ λ^{-1/5}.
        seeing_arcsec: seeing_05 * (wavelength_um / 0.5).powf(-0.2),
        wind_mps: 10.0,
        aperture_m,
        outer_scale_m: l0,
        reference: PistonReference::Mean,
        sub_samples: DEFAULT_SUB_SAMPLES,
    }
}

fn case(
    name: &'static str,
    band: (f64, f64),
    source: SourceInput,
    baseline_m: f64,
    atmosphere: PistonInputs,
    photon_rate_per_s: f64,
    target: f64,
) -> Case {
    let (fringe_hz, stroke_um) = default_grid();
    Case {
        name,
        inputs: PlanInputs {
            instrument: Inputs {
                spectrum: SpectrumInput::Flat {
                    wavelength_um: band.0,
                    bandwidth_nm: band.1,
                },
                source,
                baseline_m,
                read_noise: 1.0,
                photon_noise: true,
                ..Inputs::default()
            },
            atmosphere,
            samples_per_fringe: 4.0,
            photon_rate_per_s,
            dead_time_s: 0.0,
            frame_rate_hz: None,
            fringe_hz,
            stroke_um,
            target: Target::SigmaV2(target),
            scans: 16_000,
            seed: 1,
            diameter_err_mas: 0.0,
            bias: v2ref_core::conformance::estimate::BiasConvention::Model,
        },
    }
}

fn rate(magnitude: f64, aperture_m: f64, throughput: f64) -> f64 {
    let m = Magnitude {
        magnitude,
        band: Band2Mass::H,
        aperture_m,
        throughput,
    };
    m.photon_rate_per_s(1.65, 0.3).unwrap()
}

fn cases() -> [Case; 3] {
    [
        case(
            "CHARA-like",
            (1.65, 300.0),
            SourceInput::Ud { diameter_mas: 0.5 },
            330.0,
            atmosphere(1.65, 1.0, 1.0, None),
            rate(6.0, 1.0, 0.05),
            1e-4,
        ),
        case(
            "PIONIER-like",
            (1.65, 300.0),
            SourceInput::Ud { diameter_mas: 2.0 },
            183.7,
            atmosphere(1.65, 0.8, 1.8, Some(25.0)),
            rate(4.0, 1.8, 0.01),
            1e-4,
        ),
        case(
            "visible",
            (0.7, 50.0),
            SourceInput::Point,
            50.0,
            atmosphere(0.7, 1.0, 1.0, Some(25.0)),
            1e7,
            1e-3,
        ),
    ]
}

/// (estimator, fringe frequency, stroke) of the recommendation.
fn choice(p: &PlanPoint) -> (Estimator, u64, u64) {
    (
        p.estimator,
        (p.fringe_hz * 10.0).round() as u64,
        (p.stroke_um * 1000.0).round() as u64,
    )
}

fn recommendations(inputs: &PlanInputs) -> Vec<Option<(Estimator, u64, u64)>> {
    (1..=5)
        .map(|seed| {
            let i = PlanInputs {
                seed,
                ..inputs.clone()
            };
            plan(&i, 0, &|_| {})
                .unwrap()
                .recommended
                .as_ref()
                .map(choice)
        })
        .collect()
}

#[test]
#[ignore = "slow tier: five plans of the CHARA-like case near its optimum, each solving its fastest settings for the mean of consecutive scans (about 2 min for both seed tests on 2 loaded cores)"]
fn recommendation_is_seed_stable_near_the_optimum() {
    // The optimum's neighbourhood (found on the full grid with seed 1 in
    // the slow tier; here the CHARA-like case's, measured: V1² near
    // 2000 Hz and a 16 µm stroke).
    for c in cases().iter().take(1) {
        let grid = PlanInputs {
            fringe_hz: default_grid().0[17..].to_vec(),
            stroke_um: vec![16.0, 32.0],
            ..c.inputs.clone()
        };
        let recs = recommendations(&grid);
        assert!(recs[0].is_some(), "{}: no recommendation", c.name);
        assert!(recs.iter().all(|r| *r == recs[0]), "{}: {recs:?}", c.name);
    }
}

#[test]
#[ignore = "by hand: three full default grids (160 points) for five seeds each, each plan now solving its fastest settings for the mean of consecutive scans (well over the 3 min it took before); not run by CI"]
fn recommendation_is_seed_stable_on_the_full_grid() {
    for c in cases() {
        let recs = recommendations(&c.inputs);
        assert!(recs[0].is_some(), "{}: no recommendation", c.name);
        assert!(recs.iter().all(|r| *r == recs[0]), "{}: {recs:?}", c.name);
        println!("{}: {:?}", c.name, recs[0]);
    }
}

/// A bright star (H = 3, 1 % throughput) through 8 m apertures on 130 m
/// in H with a 22 m outer scale, the README's verified plan: piston
/// dominated, and its observation short (about 2 000 consecutive scans,
/// 10 s), so each plan solves it in seconds; on the neighbours of its
/// optimum (V1² at 2000 Hz, 16 µm).
fn bright_short_observation() -> PlanInputs {
    let bright = case(
        "bright",
        (1.65, 300.0),
        SourceInput::Ud { diameter_mas: 1.0 },
        130.0,
        atmosphere(1.65, 0.8, 8.0, Some(22.0)),
        rate(3.0, 8.0, 0.01),
        1e-4,
    );
    PlanInputs {
        fringe_hz: default_grid().0[18..].to_vec(),
        stroke_um: vec![16.0, 32.0],
        ..bright.inputs
    }
}

/// The recommendation of a piston-dominated plan whose observation is
/// short is the same for five seeds (the cheap case of the seed-stability
/// tests above, which CI runs: about 100 core-seconds).
#[test]
#[ignore = "slow tier: five plans of a bright star near its optimum, each solving its observation (about 20 core-seconds each)"]
fn seed_stable_recommendation_on_a_short_observation() {
    let recs = recommendations(&bright_short_observation());
    assert!(recs[0].is_some(), "bright: no recommendation");
    assert!(recs.iter().all(|r| *r == recs[0]), "bright: {recs:?}");
}

/// 2J1(x)/x from Bessel's integral J1(x) = (1/π)∫₀^π cos(τ − x sin τ) dτ
/// (composite Simpson, 2000 intervals: smooth periodic integrand, error far
/// below 1e-12 for x < 30).
fn jinc(x: f64) -> f64 {
    // tol: not a tolerance: the limit x → 0 of 2J1(x)/x, taken where the integral's 0/0 would round.
    if x.abs() < 1e-8 {
        return 1.0 - x * x / 8.0;
    }
    let n = 2000;
    let h = std::f64::consts::PI / n as f64;
    let f = |t: f64| (t - x * t.sin()).cos();
    let mut sum = f(0.0) + f(std::f64::consts::PI);
    for i in 1..n {
        sum += f(i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    2.0 * (sum * h / 3.0 / std::f64::consts::PI) / x
}

/// V1² − V_mono², V2² − V_mono² of a uniform disk over a band flat per unit
/// wavenumber, by Simpson over σ.
fn bandwidth_bias(theta_mas: f64, baseline_m: f64, band: (f64, f64)) -> (f64, f64) {
    let (l0, dl) = (band.0 * 1e-6, band.1 * 1e-9);
    let (s_lo, s_hi) = (1.0 / (l0 + dl / 2.0), 1.0 / (l0 - dl / 2.0));
    let theta = theta_mas * 1e-3 / 206_264.806_247_096_36;
    let v = |s: f64| jinc(std::f64::consts::PI * theta * baseline_m * s);
    let n = 400;
    let h = (s_hi - s_lo) / n as f64;
    let mut sum = [0.0; 2];
    for i in 0..=n {
        let w = if i == 0 || i == n {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        let vi = v(s_lo + i as f64 * h);
        sum[0] += w * vi * vi;
        sum[1] += w * vi;
    }
    let mean = |x: f64| x * h / 3.0 / (s_hi - s_lo);
    let v_mono = v((s_lo + s_hi) / 2.0);
    (
        mean(sum[0]) - v_mono * v_mono,
        mean(sum[1]).powi(2) - v_mono * v_mono,
    )
}

#[test]
fn bandwidth_bias_of_the_pionier_like_disk_is_the_independent_integral() {
    // Two frequencies, one stroke: the deterministic terms do not depend on
    // the piston run.
    let c = &cases()[1];
    let i = PlanInputs {
        fringe_hz: vec![200.0, 2000.0],
        stroke_um: vec![64.0],
        scans: 64,
        ..c.inputs.clone()
    };
    let result = plan(&i, 0, &|_| {}).unwrap();
    let (v1, v2) = bandwidth_bias(2.0, 183.7, (1.65, 300.0));
    for p in &result.points {
        let want = match p.estimator {
            Estimator::V1 => v1,
            Estimator::V2 => v2,
            other => panic!("no expected bias for {other:?}"),
        };
        assert!(
            // tol: a bias from the same quadratures in another order, relative to max(|bias|, 1e-3) (the bias's scale): ~1e-13, 1e-9 a margin.
            (p.bias_bandwidth_dispersion - want).abs() < 1e-9 * want.abs().max(1e-3),
            "{:?}: {} vs {want}",
            p.estimator,
            p.bias_bandwidth_dispersion
        );
        // Far above the target: the plan says it must be corrected.
        assert!(p.bandwidth_bias_over_target > 1.0);
    }
    // Near the first null the bias is a large part of V² (issue 26: 29%).
    assert!(v1 > 0.1 * result.points[0].v_mono_sq, "{v1}");
}
