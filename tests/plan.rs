//! The planner, end to end: the recommended setting simulated with every
//! effect on (the kit's simulator) gives the predicted per-scan σ within
//! 10 % and the predicted piston bias within its standard error; the
//! paper's conclusions come out as cases.

use v2ref_commands::plan::{plan, Estimator, PlanInputs, PlanPoint, Target};
use v2ref_core::conformance::estimate::BiasConvention;
use v2ref_core::formalism::estimator::BinWindow;
use v2ref_core::noise::calibrated::Trials;
use v2ref_core::noise::Formula;
use v2ref_core::simulator::{simulate, Inputs, Model, PistonInputs, SourceInput, SpectrumInput};
use v2ref_core::tolerance::MC_SIGMAS;

fn h_band(source: SourceInput, baseline_m: f64, read_noise: f64, photon_noise: bool) -> Inputs {
    Inputs {
        spectrum: SpectrumInput::Flat {
            wavelength_um: 1.65,
            bandwidth_nm: 300.0,
        },
        source,
        baseline_m,
        read_noise,
        photon_noise,
        ..Inputs::default()
    }
}

fn inputs(instrument: Inputs, seeing: f64, rate: f64, fringe_hz: Vec<f64>) -> PlanInputs {
    PlanInputs {
        instrument,
        atmosphere: PistonInputs {
            wavelength_um: 1.65,
            seeing_arcsec: seeing,
            ..PistonInputs::paper(1.0)
        },
        samples_per_fringe: 4.0,
        photon_rate_per_s: rate,
        dead_time_s: 0.0,
        frame_rate_hz: None,
        fringe_hz,
        stroke_um: vec![24.0],
        target: Target::SigmaV2(1e-3),
        scans: 2000,
        seed: 3,
        diameter_err_mas: 0.0,
        bias: BiasConvention::Model,
    }
}

/// Simulates `p`'s setting with noise and piston and compares.
fn validate(case: &str, inputs: &PlanInputs, p: &PlanPoint) {
    let sim_inputs = inputs
        .point_inputs(
            p.fringe_hz,
            p.stroke_um,
            true,
            inputs.atmosphere.seeing_arcsec > 0.0,
        )
        .unwrap();
    let model = Model::new(&sim_inputs).unwrap();
    let size = Trials {
        trials: 4000,
        seed: 77,
        threads: 0,
    };
    let run = simulate(
        &model,
        BinWindow::Positive,
        BiasConvention::Model,
        Formula::Exact,
        size,
        &|_| {},
    )
    .unwrap();
    let s = match p.estimator {
        Estimator::V1 => run.v1_sq,
        Estimator::V2 => run.v2_sq,
        other => panic!("no simulated statistics for {other:?}"),
    };
    let rel = s.std / p.sigma_per_scan - 1.0;
    let bias = s.mean - p.v_sq_sampled;
    let se = (s.stderr_mean.powi(2) + p.bias_piston_stderr.powi(2)).sqrt();
    eprintln!(
        "{case}: {:?} at {} Hz: sigma/scan predicted {:.4e}, simulated {:.4e} ({:+.1} %); bias predicted {:+.3e} ± {:.1e}, simulated {:+.3e} ± {:.1e}",
        p.estimator, p.fringe_hz, p.sigma_per_scan, s.std, 100.0 * rel, p.bias_piston, p.bias_piston_stderr, bias, s.stderr_mean
    );
    assert!(
        // tol: 4000 trials give the simulated σ to ~1 % (more with the piston's heavy tails) and the planner states the upper end of a 90 % interval of its own Monte Carlo: 10 % allows both.
        rel.abs() < 0.10,
        "{case}: sigma off by {:.1} %",
        100.0 * rel
    );
    assert!(
        (bias - p.bias_piston).abs() < MC_SIGMAS * se,
        "{case}: bias"
    );
}

#[test]
fn bright_source_with_strong_piston() {
    // 1″ seeing with a 25 m outer scale (piston rms a few µm on 100 m): with
    // an infinite outer scale the piston wanders over tens of µm on ~10 s,
    // and a few thousand scans hold too few independent stretches of it for
    // a 10 % comparison of two Monte Carlo runs.
    let mut i = inputs(
        h_band(SourceInput::Point, 100.0, 0.0, true),
        1.0,
        1e8,
        vec![100.0, 300.0, 1000.0],
    );
    i.atmosphere.outer_scale_m = Some(25.0);
    let result = plan(&i, 0, &|_| {}).unwrap();
    let p = result.recommended.expect("a setting reaches the target");
    validate("bright, strong piston", &i, &p);
    // The other estimator's best setting, where one reaches the target.
    for p in [result.best_v1, result.best_v2].into_iter().flatten() {
        validate("bright, strong piston", &i, &p);
    }
}

#[test]
fn faint_read_noise_limited_source_prefers_v1() {
    let i = inputs(
        h_band(SourceInput::Point, 100.0, 10.0, true),
        0.0,
        2e4,
        vec![50.0, 200.0],
    );
    let result = plan(&i, 0, &|_| {}).unwrap();
    for p in result.points.chunks_exact(2) {
        let (v1, v2) = (&p[0], &p[1]);
        assert!(
            v1.sigma_noise_per_scan < v2.sigma_noise_per_scan,
            "{v1:?} {v2:?}"
        );
    }
    let p = result.recommended.expect("a setting reaches the target");
    assert_eq!(p.estimator, Estimator::V1);
    validate("faint, read-noise limited", &i, &p);
}

#[test]
fn resolved_disk_near_a_null() {
    // A 2 mas disk on 180 m in H: first null near 1.22 λ/θ ≈ 210 m, V² ≈ 0.02.
    let i = inputs(
        h_band(SourceInput::Ud { diameter_mas: 2.0 }, 180.0, 2.0, true),
        0.5,
        1e7,
        vec![300.0, 1000.0],
    );
    let result = plan(&i, 0, &|_| {}).unwrap();
    let p = result.recommended.expect("a setting reaches the target");
    // tol: not a tolerance: the recommended point sits near the null (V² below a tenth of its peak).
    assert!(p.v_sq_sampled < 0.1, "near the null: {}", p.v_sq_sampled);
    validate("disk near a null", &i, &p);
}

/// The paper's conclusion, with piston only (its K band, 18 m, 1″ seeing,
/// point source, 64 µm scans): in a fixed time, V1² reaches the better
/// accuracy at a low fringe frequency (its piston bias is smaller) and V2²
/// at a high one (its piston scatter is smaller).
#[test]
fn piston_only_v1_low_v2_high() {
    let k_band = Inputs {
        source: SourceInput::Point,
        baseline_m: 18.0,
        read_noise: 0.0,
        photon_noise: false,
        ..Inputs::default()
    };
    let i = PlanInputs {
        atmosphere: PistonInputs::paper(1.0),
        stroke_um: vec![64.0],
        target: Target::TimeBudgetS(100.0),
        ..inputs(k_band, 1.0, 1e6, vec![30.0, 1000.0])
    };
    let result = plan(&i, 0, &|_| {}).unwrap();
    let reached = |k: usize| result.points[k].sigma_reached.unwrap();
    // points: [V1 30 Hz, V2 30 Hz, V1 1000 Hz, V2 1000 Hz]
    assert!(
        reached(0) < reached(1),
        "30 Hz: V1 {} vs V2 {}",
        reached(0),
        reached(1)
    );
    assert!(
        reached(3) < reached(2),
        "1000 Hz: V2 {} vs V1 {}",
        reached(3),
        reached(2)
    );
}

/// `v2ref plan` answers from the command line, writes its JSON and its SVG.
#[test]
fn cli_plan_writes_json_and_svg() {
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("plan.svg");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args([
            "plan",
            "--wavelength-um",
            "1.65",
            "--bandwidth-nm",
            "300",
            "--source",
            "ud",
            "--diameter-mas",
            "2",
            "--baseline-m",
            "100",
            "--fringe-hz",
            "100",
            "--fringe-hz",
            "1000",
            "--stroke-um",
            "32",
            "--scans",
            "300",
            "--json",
            "--svg",
        ])
        .arg(&svg)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["points"].as_array().unwrap().len(), 4);
    assert!(
        json["recommended"]["fringe_hz"].as_f64().is_some(),
        "{json}"
    );
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(
        text.starts_with("<svg") && text.contains("target"),
        "an SVG with the target"
    );
    // Bad input: one line naming the flag, exit 2.
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(["plan", "--photon-rate-per-s", "-5"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--photon-rate-per-s"));
}

// --- The magnitude helper (`v2ref_commands::plan::photometry`) --------------------

use v2ref_commands::plan::photometry::{Band2Mass, Magnitude};
use v2ref_core::tolerance::{HAND_10_DIGITS_REL, ROUNDING_REL};

fn ks_zero(aperture_m: f64, throughput: f64) -> Magnitude {
    Magnitude {
        magnitude: 0.0,
        band: Band2Mass::Ks,
        aperture_m,
        throughput,
    }
}

#[test]
fn magnitude_gives_the_hand_computed_photon_rate() {
    // Ks = 0 (666.7 Jy), K band 2.0–2.4 µm, two 1 m telescopes, T = 1:
    // 666.7e-26 / 6.62607015e-34 × ln(2.4/2.0) × 2π/4, worked out by hand
    // (Python, float64) as 2.881590895e9 photons/s.
    let rate = ks_zero(1.0, 1.0).photon_rate_per_s(2.2, 0.4).unwrap();
    v2ref_core::assert_rel_eq!(rate, 2.881_590_895e9, HAND_10_DIGITS_REL);
    // The narrow-band limit: F_ν Δλ/(h λ) per m², 4.660384867e9 photons
    // s⁻¹ m⁻² µm⁻¹ at 2.159 µm (by hand as above; ln(λmax/λmin) differs
    // from Δλ/λ by (Δλ/λ)²/12 = 2e-10 here).
    let area = ks_zero(1.0, 1.0).collecting_area_m2();
    let narrow = ks_zero(1.0, 1.0).photon_rate_per_s(2.159, 1e-4).unwrap() / area / 1e-4;
    v2ref_core::assert_rel_eq!(narrow, 4.660_384_867e9, HAND_10_DIGITS_REL);
}

#[test]
fn magnitude_scaling_laws() {
    let base = ks_zero(1.8, 0.02).photon_rate_per_s(2.2, 0.4).unwrap();
    // Five magnitudes are a factor 100 exactly; the rate is linear in T and D².
    let faint = Magnitude {
        magnitude: 5.0,
        ..ks_zero(1.8, 0.02)
    };
    v2ref_core::assert_rel_eq!(
        faint.photon_rate_per_s(2.2, 0.4).unwrap(),
        base / 100.0,
        ROUNDING_REL
    );
    v2ref_core::assert_rel_eq!(
        ks_zero(1.8, 0.04).photon_rate_per_s(2.2, 0.4).unwrap(),
        2.0 * base,
        ROUNDING_REL
    );
    v2ref_core::assert_rel_eq!(
        ks_zero(3.6, 0.02).photon_rate_per_s(2.2, 0.4).unwrap(),
        4.0 * base,
        ROUNDING_REL
    );
    // The zero points in Jy order as published: J > H > Ks.
    assert!(Band2Mass::J.zero_point_jy() > Band2Mass::H.zero_point_jy());
    assert!(Band2Mass::H.zero_point_jy() > Band2Mass::Ks.zero_point_jy());
}

#[test]
fn magnitude_refuses_bad_input() {
    for (m, what) in [
        (
            Magnitude {
                magnitude: 31.0,
                ..ks_zero(1.0, 0.1)
            },
            "magnitude",
        ),
        (ks_zero(1.0, 0.0), "throughput"),
        (ks_zero(1.0, 1.5), "throughput"),
        (ks_zero(-1.0, 0.5), "aperture_m"),
    ] {
        let e = m.photon_rate_per_s(2.2, 0.4).unwrap_err();
        assert_eq!(e.param(), Some(what), "{e}");
    }
    let e = ks_zero(1.0, 0.1).photon_rate_per_s(2.2, 4.4).unwrap_err();
    assert_eq!(e.param(), Some("bandwidth_nm"), "{e}");
}

#[test]
fn cli_plan_from_a_magnitude_echoes_the_photometry() {
    let run = |extra: &[&str]| {
        let mut args = vec![
            "plan",
            "--wavelength-um",
            "1.65",
            "--bandwidth-nm",
            "300",
            "--fringe-hz",
            "500",
            "--stroke-um",
            "32",
            "--scans",
            "50",
            "--json",
        ];
        args.extend_from_slice(extra);
        std::process::Command::new(env!("CARGO_BIN_EXE_v2ref"))
            .args(&args)
            .output()
            .unwrap()
    };
    let out = run(&[
        "--magnitude",
        "5",
        "--magnitude-band",
        "h",
        "--throughput",
        "0.01",
        "--aperture-m",
        "1.8",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let rate = json["photometry"]["photon_rate_per_s"].as_f64().unwrap();
    // 1024 Jy × 10^-2 / h × ln(1.8/1.5) × 2π 1.8²/4 × 0.01, by hand.
    v2ref_core::assert_rel_eq!(rate, 1.433_992_352e6, HAND_10_DIGITS_REL);
    assert_eq!(json["inputs"]["photon_rate_per_s"].as_f64(), Some(rate));
    assert_eq!(json["photometry"]["band"], "H");
    // Without the band or the throughput: refused, exit 2.
    let out = run(&["--magnitude", "5"]);
    assert_eq!(out.status.code(), Some(2));
    // With a rate as well: refused.
    let out = run(&[
        "--magnitude",
        "5",
        "--magnitude-band",
        "h",
        "--throughput",
        "0.01",
        "--photon-rate-per-s",
        "1e6",
    ]);
    assert_eq!(out.status.code(), Some(2));
}

/// Every null of a plan point comes with its reason in words
/// (`why_null`), in target mode (reachable or not) and in budget mode
/// (a budget that fits scans, and one that fits none); and the table says
/// what its "-" stands for.
#[test]
#[ignore = "slow tier: plans whose every null is explained (6 s)"]
fn every_null_of_a_plan_has_its_reason_in_words() {
    let run = |extra: &[&str]| {
        let mut args = vec![
            "plan",
            "--fringe-hz",
            "300",
            "--stroke-um",
            "16",
            "--scans",
            "200",
            "--quiet",
        ];
        args.extend_from_slice(extra);
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_v2ref"))
            .args(&args)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8(out.stdout).unwrap()
    };
    // (flags, the reason's words, whether the table shows a "-").
    let cases: [(&[&str], &str, bool); 4] = [
        (&[], "time budget reaches", true),
        (&["--target-sigma-v2", "1e-9"], "unreachable", true),
        (
            &["--time-budget-s", "3600"],
            "they are the times to a target",
            false,
        ),
        (
            &["--time-budget-s", "5e-324"],
            "shorter than one scan",
            true,
        ),
    ];
    for (extra, words, dash) in cases {
        let mut json_args = extra.to_vec();
        json_args.push("--json");
        let v: serde_json::Value = serde_json::from_str(&run(&json_args)).unwrap();
        for p in v["points"].as_array().unwrap() {
            let nulls: Vec<&String> = p
                .as_object()
                .unwrap()
                .iter()
                .filter(|(k, x)| x.is_null() && k.as_str() != "why_null")
                .map(|(k, _)| k)
                .collect();
            let why = p["why_null"].as_str().unwrap_or("");
            assert!(why.contains(words), "{extra:?}: {why}");
            for k in nulls {
                assert!(
                    why.contains(k.as_str()),
                    "{extra:?}: {k} null, reason: {why}"
                );
            }
        }
        let table = run(extra);
        let explained = table.contains("  -: ") && table.contains(words);
        assert_eq!(explained, dash, "{extra:?}: {table}");
    }
}

// --- The plan's figure (`plan --svg`) draws the planner's numbers --------

use v2ref_commands::plan::figure::{drawn_as, figure_time_s, sigma_curve, Drawn};
use v2ref_commands::plan::sigma_reached_in;

/// One computation for the figure and the table. With a time budget the
/// figure's σ at each fringe frequency is the least `sigma_reached` of the
/// table over the strokes, exactly; with a target, the recommended setting
/// reaches the target in the plan's scans on the figure's own formula and
/// not in one scan fewer (so a figure drawn from the central values of the
/// piston terms, below their upper ends, fails it).
#[test]
fn the_plan_figure_draws_the_planners_numbers() {
    let k_band = Inputs {
        source: SourceInput::Point,
        baseline_m: 18.0,
        read_noise: 1.0,
        ..Inputs::default()
    };
    let grid = || inputs(k_band.clone(), 1.0, 2e5, vec![100.0, 300.0, 1000.0]);
    let budget = PlanInputs {
        stroke_um: vec![24.0, 48.0],
        target: Target::TimeBudgetS(60.0),
        scans: 400,
        ..grid()
    };
    let result = plan(&budget, 0, &|_| {}).unwrap();
    let time_s = figure_time_s(&result, &budget);
    assert_eq!(time_s, 60.0);
    for e in [Estimator::V1, Estimator::V2] {
        let curve = sigma_curve(&result, &budget, (e, Drawn::Promise), time_s);
        assert_eq!(curve.len(), 3, "{e:?}");
        for (f, sigma) in curve {
            let table = result
                .points
                .iter()
                .filter(|p| p.estimator == e && p.fringe_hz == f)
                .filter_map(|p| p.sigma_reached)
                .min_by(f64::total_cmp)
                .unwrap();
            assert_eq!(sigma, table, "{e:?} at {f} Hz");
        }
    }
    let target = 2e-3;
    let aimed = PlanInputs {
        target: Target::SigmaV2(target),
        scans: 400,
        ..grid()
    };
    let result = plan(&aimed, 0, &|_| {}).unwrap();
    let rec = result.recommended.expect("a recommendation");
    let n = rec.scans_needed.unwrap();
    let per_scan_s = rec.scan_time_s + aimed.dead_time_s;
    assert!(n > 1.0, "{n} scans: nothing to tell apart");
    let at = |scans: f64| sigma_reached_in(&rec, &aimed, scans * per_scan_s).unwrap();
    assert!(at(n) <= target, "{} in {n} scans", at(n));
    match &rec.observation {
        // Solved for the mean of consecutive scans: the figure states the
        // observation's own promise at its n.
        Some(o) => assert_eq!(at(n), o.sigma, "the observation's promise"),
        None => assert!(at(n - 1.0) > target, "{} in {} scans", at(n - 1.0), n - 1.0),
    }
    let time_s = figure_time_s(&result, &aimed);
    let curve = sigma_curve(&result, &aimed, (rec.estimator, Drawn::Promise), time_s);
    let (_, drawn) = curve.iter().find(|(f, _)| *f == rec.fringe_hz).unwrap();
    assert!(
        *drawn <= at(n),
        "the figure draws {drawn} at the recommendation"
    );
    // The promise is drawn only from settings solved for the observation,
    // the others apart (open circles).
    let solved = |e: Estimator, f: f64| {
        result
            .points
            .iter()
            .any(|p| p.estimator == e && p.fringe_hz == f && p.observation.is_some())
    };
    for e in [Estimator::V1, Estimator::V2] {
        let promise = sigma_curve(&result, &aimed, (e, Drawn::Promise), time_s);
        assert!(
            promise.iter().all(|&(f, _)| solved(e, f)),
            "{e:?}: {promise:?}"
        );
    }
    let apart = |e| sigma_curve(&result, &aimed, (e, Drawn::IndependentScans), time_s);
    assert!(
        !apart(Estimator::V1).is_empty() && !apart(Estimator::V2).is_empty(),
        "every setting solved: nothing drawn apart"
    );
    assert!(
        result
            .points
            .iter()
            .all(|p| (drawn_as(p, &aimed) == Drawn::Promise) == p.observation.is_some()),
        "a setting not solved for the observation drawn as the promise"
    );
}
