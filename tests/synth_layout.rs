//! `synth --layout`: where a set's rows lie in time through the piston.
//! The sidecar records the layout (sequences, rows of each, stride, scan
//! time), and in the `observation` layout the mean of n consecutive rows
//! scatters as n consecutive scans through one atmosphere do — not as
//! σ²/n — where the atmosphere is slow.

use std::process::Command;
use v2ref_core::conformance::estimate::{BiasConvention, RowEstimator};
use v2ref_core::formalism::estimator::BinWindow;
use v2ref_core::montecarlo::{derive_seed, RunningStats};
use v2ref_core::piston::PistonReference;
use v2ref_core::simulator::{Inputs, Model, PistonInputs, RowLayout, RowTiming, SourceInput};
use v2ref_core::tolerance::MC_SIGMAS;

fn synth_sidecar(dir: &std::path::Path, name: &str, extra: &[&str]) -> serde_json::Value {
    let stem = dir.join(name).display().to_string();
    let mut args = vec![
        "synth",
        "--out",
        &stem,
        "--rows",
        "40",
        "--samples",
        "32",
        "--reference-blocks",
        "0",
        "--quiet",
    ];
    args.extend_from_slice(extra);
    let out = Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(&args)
        .output()
        .expect("the binary runs");
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(format!("{stem}.json")).unwrap();
    serde_json::from_str(&text).unwrap()
}

/// The sidecar states each layout: one sequence of every row back to back
/// (stride N samples, one scan period N·δx/(f·λ0)) in the observation
/// layout; in the default, the 2 sequences of 20 rows that 40 rows are cut
/// into, their scans spread out (stride > N); no layout without piston
/// (the rows are independent).
#[test]
fn the_sidecar_records_the_layout() {
    let dir = tempfile::tempdir().unwrap();
    let piston = ["--fringe-hz", "250", "--wavelength-um", "2.2"];
    let with = |name: &str, layout: &[&str]| {
        let extra: Vec<&str> = piston.iter().chain(layout).copied().collect();
        synth_sidecar(dir.path(), name, &extra)["layout"].clone()
    };
    // 32 samples of 0.5 µm of OPD, scanned at f·λ0 = 250 Hz · 2.2 µm.
    let scan_time_s = 32.0 * 0.5 / (250.0 * 2.2);
    let obs = with("obs", &["--layout", "observation"]);
    assert_eq!(obs["layout"], "observation");
    assert_eq!(obs["sequences"], 1);
    assert_eq!(obs["rows_per_sequence"], serde_json::json!([40]));
    assert_eq!(obs["stride_samples"], 32);
    let rel = |a: &serde_json::Value, b: f64| (a.as_f64().unwrap() - b).abs() / b;
    // tol: a time printed to 17 digits in the sidecar's JSON: a few roundings.
    assert!(rel(&obs["scan_time_s"], scan_time_s) < 1e-12, "{obs}");
    // tol: a time printed to 17 digits in the sidecar's JSON: a few roundings.
    assert!(rel(&obs["stride_s"], scan_time_s) < 1e-12, "{obs}");

    let seq = with("seq", &[]);
    assert_eq!(seq["layout"], "sequences");
    assert_eq!(seq["sequences"], 2);
    assert_eq!(seq["rows_per_sequence"], serde_json::json!([20, 20]));
    assert!(seq["stride_samples"].as_u64().unwrap() > 32, "{seq}");
    assert_eq!(seq, with("seq_named", &["--layout", "sequences"]));

    let none = synth_sidecar(dir.path(), "none", &["--layout", "observation"]);
    assert!(none.get("layout").is_none(), "{none}");
}

/// Each row's start follows from the recorded layout: row r of sequence j
/// starts `(r − first row of j) · stride_s` after the start of j.
#[test]
fn row_starts_follow_from_the_layout() {
    let model = Model::new(&slow_sky(32)).unwrap();
    for layout in [RowLayout::Sequences, RowLayout::Observation] {
        let rows = model.rows_in(layout, 100, 5, 1).unwrap();
        let set = rows.layout().unwrap();
        assert_eq!(set.layout, layout);
        assert_eq!(set.rows_per_sequence.iter().sum::<u64>(), 100);
        assert_eq!(set.sequences, rows.sequences());
        for r in 0..100 {
            let (j, start_s) = set.row_start(r).unwrap();
            assert_eq!(j, rows.sequence_of(r).unwrap(), "row {r}");
            let first: u64 = set.rows_per_sequence[..j].iter().sum();
            let expected = (r - first) as f64 * set.stride_s;
            // tol: a row's start, a product of integers and the stride: a few roundings.
            assert!((start_s - expected).abs() <= 1e-12 * expected, "row {r}");
        }
        assert_eq!(set.row_start(100), None);
    }
}

/// A slow atmosphere against the scans: 1 m/s over 1.8 m apertures (the
/// piston's velocity changes over D/v = 1.8 s, about 12 scans of
/// 0.145 s at 100 Hz), no noise, so the rows carry the piston alone.
fn slow_sky(samples: usize) -> Inputs {
    Inputs {
        source: SourceInput::Point,
        samples,
        photon_noise: false,
        read_noise: 0.0,
        piston: Some(PistonInputs {
            fringe_hz: 100.0,
            wavelength_um: 2.2,
            seeing_arcsec: 1.0,
            wind_mps: 1.0,
            aperture_m: 1.8,
            outer_scale_m: None,
            reference: PistonReference::Mean,
            sub_samples: v2ref_core::piston::DEFAULT_SUB_SAMPLES,
        }),
        ..Inputs::default()
    }
}

/// Normalized V1² of every row of a set, in row order.
fn v1_sq_of_rows(model: &Model, layout: RowLayout, rows: u64, seed: u64) -> Vec<f64> {
    let estimator =
        RowEstimator::new(model, BinWindow::Positive, BiasConvention::Model, true).unwrap();
    let set = model.rows_in(layout, rows, seed, 0).unwrap();
    let n = model.samples();
    let mut out = Vec::with_capacity(rows as usize);
    set.stream(0, 8, |block: &[f64]| {
        out.extend(
            block
                .chunks_exact(n)
                .map(|r| estimator.estimate(r).unwrap().v1_sq),
        );
        Ok(())
    })
    .unwrap();
    out
}

/// Consecutive scans through one slow atmosphere: the mean of n = 64
/// consecutive rows of one `observation` set (its 200 blocks of 64 rows)
/// scatters as the means of 200 independent observations of 64 rows do,
/// within their standard errors (each from its fourth moment), and far
/// more than the σ²/n that independent scans would give. Measured:
/// 2.45e-5 ± 0.23e-5 within one observation, 2.22e-5 ± 0.20e-5 across
/// observations, σ²/n = 0.093e-5 (26 times less). The test's power: an
/// observation synthesized only as long as its 64 scans (without the
/// piston's slow wander) gave 7.9e-8 across observations, and failed it.
#[test]
fn consecutive_rows_of_one_observation_have_the_correlated_variance() {
    const N_ROWS: u64 = 64;
    const BLOCKS: u64 = 200;
    let model = Model::new(&slow_sky(64)).unwrap();
    let long = v1_sq_of_rows(&model, RowLayout::Observation, N_ROWS * BLOCKS, 11);
    let (mut rows, mut block_means) = (RunningStats::default(), RunningStats::default());
    for block in long.chunks_exact(N_ROWS as usize) {
        block.iter().for_each(|&v| rows.push(v));
        block_means.push(block.iter().sum::<f64>() / N_ROWS as f64);
    }
    let mut observations = RunningStats::default();
    for k in 0..BLOCKS {
        let seed = derive_seed(12, "observation", &[k as f64]);
        let obs = v1_sq_of_rows(&model, RowLayout::Observation, N_ROWS, seed);
        observations.push(obs.iter().sum::<f64>() / N_ROWS as f64);
    }
    let independent = rows.variance() / N_ROWS as f64;
    let (within, across) = (block_means.variance(), observations.variance());
    let (se_within, se_across) = (
        block_means.stderr_variance(),
        observations.stderr_variance(),
    );
    let report = format!(
        "var of 64-row means: one observation {within:.4e} ± {se_within:.2e}, \
         independent observations {across:.4e} ± {se_across:.2e}; σ²/n {independent:.4e} \
         (inflation {:.1})",
        within / independent
    );
    eprintln!("{report}");
    let se = se_within.hypot(se_across);
    assert!((within - across).abs() <= MC_SIGMAS * se, "{report}");
    // Power: σ²/n lies many standard errors below both.
    assert!(within - independent > MC_SIGMAS * se_within, "{report}");
    assert!(across - independent > MC_SIGMAS * se_across, "{report}");
}

/// Normalized V1² of every row of a set, in row order.
fn v1_sq_of(model: &Model, set: &v2ref_core::simulator::Rows<'_>) -> Vec<f64> {
    let estimator =
        RowEstimator::new(model, BinWindow::Positive, BiasConvention::Model, true).unwrap();
    let n = model.samples();
    let mut out = Vec::new();
    set.stream(0, 8, |block: &[f64]| {
        out.extend(
            block
                .chunks_exact(n)
                .map(|r| estimator.estimate(r).unwrap().v1_sq),
        );
        Ok(())
    })
    .unwrap();
    out
}

/// The variance of the means of consecutive blocks of `n` values, with
/// its standard error.
fn block_mean_variance(values: &[f64], n: usize) -> (f64, f64) {
    let mut means = RunningStats::default();
    for block in values.chunks_exact(n) {
        means.push(block.iter().sum::<f64>() / n as f64);
    }
    (means.variance(), means.stderr_variance())
}

/// Observations longer than 2B/v (64 scans of 0.145 s, 9.3 s, through a
/// 1 m/s wind on 3 m: B/v = 3 s): 200 observations of one `synth
/// --observations 200` set scatter in their mean as the 64-scan blocks of
/// one long observation do. Before the observation layout read each
/// observation from a sequence several times its length, a sequence only
/// as long as the observation (its drift forced to zero; built here as the
/// 200 sequences of 64 scans the planner's explicit layout makes) is what
/// an observation got: measured 3.80e-6 ± 0.33e-6 for the long
/// observation's blocks, 3.55e-6 ± 0.33e-6 across the 200 observations,
/// and 0.10e-6 from the short sequences — 35 times less, far outside: the
/// test's power, and the failure of the layout before issue 44.
#[test]
fn observations_longer_than_the_correlation_time_keep_their_drift() {
    const N_ROWS: u64 = 64;
    const K: u64 = 200;
    let mut inputs = slow_sky(64);
    inputs.baseline_m = 3.0;
    let model = Model::new(&inputs).unwrap();
    let long = model
        .rows_in(RowLayout::Observation, N_ROWS * K, 21, 0)
        .unwrap();
    let (within, se_within) = block_mean_variance(&v1_sq_of(&model, &long), N_ROWS as usize);
    let timing = RowTiming::observation(K, 0.0).unwrap();
    let many = model.rows_in(timing, N_ROWS * K, 22, 0).unwrap();
    assert_eq!(many.sequences(), K as usize);
    let (across, se_across) = block_mean_variance(&v1_sq_of(&model, &many), N_ROWS as usize);
    let short = model
        .rows_with_layout(N_ROWS * K, 23, 0, Some((K as usize, 64)))
        .unwrap();
    let (periodic, se_periodic) = block_mean_variance(&v1_sq_of(&model, &short), N_ROWS as usize);
    let report = format!(
        "var of 64-scan means: one long observation {within:.3e} ± {se_within:.1e}, \
         {K} observations {across:.3e} ± {se_across:.1e}, sequences as long as the \
         observation {periodic:.3e} ± {se_periodic:.1e}"
    );
    eprintln!("{report}");
    let se = se_within.hypot(se_across);
    assert!((within - across).abs() <= MC_SIGMAS * se, "{report}");
    // Power: the sequences only as long as an observation lie far below.
    assert!(
        across - periodic > MC_SIGMAS * se_across.hypot(se_periodic),
        "{report}"
    );
}

/// Observation j of a set is keyed by its index: its atmosphere is the same
/// whatever the number of observations after it, so are its rows (to the
/// fringe table's rounding: the table spans the largest excursion of all
/// the set's observations, so its samples move by ~1e-14); the dead time sets
/// the stride (N + dead time / sample time) and the sidecar's layout says
/// how long each observation's sequence is.
#[test]
fn observations_are_keyed_by_their_index_and_take_the_dead_time() {
    let model = Model::new(&slow_sky(32)).unwrap();
    let rows = |k: u64, dead: f64| {
        let set = model
            .rows_in(RowTiming::observation(k, dead).unwrap(), 10 * k, 9, 1)
            .unwrap();
        let mut out = Vec::new();
        set.fill_unit(0, &mut v2ref_core::montecarlo::unit_rng(9, 0), &mut out)
            .unwrap();
        (out, set.layout().unwrap())
    };
    let (two, _) = rows(2, 0.01);
    let (three, layout) = rows(3, 0.01);
    let scale = two.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let moved = two
        .iter()
        .zip(&three)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    // tol: the fringe table's interpolation over a different OPD span: a
    // few roundings of the rows' scale (measured 1e-13 of 10).
    assert!(moved <= 1e-10 * scale, "{moved} of {scale}");
    // 32 samples of 0.5 µm at 100 Hz · 2.2 µm: t_s = 0.5 / 220 s.
    let t_s: f64 = 0.5 / 220.0;
    assert_eq!(layout.stride_samples, 32 + (0.01 / t_s).round() as usize);
    assert_eq!(layout.rows_per_sequence, vec![10, 10, 10]);
    let read = 9 * layout.stride_samples + 32;
    assert!(
        layout.sequence_samples.unwrap() >= 4 * read as u64,
        "{layout:?}"
    );
    assert!(layout.note.unwrap().contains("not forced to zero"));
    let (other, _) = rows(2, 0.02);
    assert_ne!(two, other);
}

/// The observation layout's own refusals name the flag and its range.
#[test]
fn the_observation_flags_are_checked() {
    let dir = tempfile::tempdir().unwrap();
    let stem = dir.path().join("x").display().to_string();
    let run = |extra: &[&str]| {
        let mut args = vec![
            "synth",
            "--out",
            &stem,
            "--rows",
            "40",
            "--samples",
            "32",
            "--fringe-hz",
            "250",
            "--reference-blocks",
            "0",
            "--quiet",
        ];
        args.extend_from_slice(extra);
        crate::run::v2ref(&args)
    };
    for (extra, flag) in [
        (
            &["--layout", "observation", "--observations", "3"][..],
            "--observations",
        ),
        (
            &["--layout", "observation", "--observations", "0"][..],
            "--observations",
        ),
        (&["--observations", "2"][..], "--observations"),
        (&["--dead-time-s", "0.1"][..], "--dead-time-s"),
        (
            &["--layout", "observation", "--dead-time-s", "-1"][..],
            "--dead-time-s",
        ),
        (
            &["--layout", "observation", "--dead-time-s", "1e6"][..],
            "--rows",
        ),
    ] {
        let (code, _, err) = run(extra);
        assert_eq!(code, 2, "{extra:?}: {err}");
        assert!(
            err.starts_with(&format!("error: {flag}")),
            "{extra:?}: {err}"
        );
        assert!(!std::path::Path::new(&format!("{stem}.npy")).exists());
    }
}
