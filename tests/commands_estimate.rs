//! `v2ref_commands::commands::estimate`, the one answer of `estimate` behind the
//! CLI and Python: its configuration against the rows' shape, its
//! refusals named as each edge names its rows, its calibration by a
//! calibrator's rows against the slow oracle, and the CLI's one changed
//! refusal (other rows than a set's must have the set's N).

use std::path::Path;
use v2ref_commands::commands::estimate::{
    check_rows, estimate_rows, estimator, CalibratorRows, Configuration, RowsName,
};
use v2ref_commands::parameters::Physical;
use v2ref_core::conformance::estimate::{estimate_row_oracle, BiasConvention};
use v2ref_core::formalism::estimator::{BinWindow, Pair};
use v2ref_core::simulator::Model;
use v2ref_core::Error;

const ARRAY: RowsName<'static> = RowsName {
    param: "interferograms",
    path: None,
};

fn physical(samples: usize) -> Physical {
    Physical {
        samples,
        ..Physical::default()
    }
}

/// Noise-free rows of the model (continuum subtracted), each scaled.
fn rows(model: &Model, scales: &[f64]) -> Vec<f64> {
    let m = &model.signal.modulated;
    scales
        .iter()
        .flat_map(|s| m.iter().map(move |v| s * v))
        .collect()
}

#[test]
fn physical_inputs_take_n_from_the_rows_and_a_sidecars_do_not() {
    let config = Configuration::from_physical(&physical(128), true).unwrap();
    assert_eq!(config.inputs_for(ARRAY, 3, 64).unwrap().samples, 64);
    let set = Configuration {
        set_rows: Some(3),
        samples_from_rows: false,
        ..config.clone()
    };
    assert_eq!(set.inputs_for(ARRAY, 3, 128).unwrap().samples, 128);
    let narrow = set.inputs_for(ARRAY, 3, 64).unwrap_err();
    assert_eq!(
        narrow.to_string(),
        "interferograms: 64 columns; the configuration has 128 samples per row"
    );
    let fewer = set.inputs_for(ARRAY, 2, 128).unwrap_err();
    assert_eq!(
        fewer.to_string(),
        "interferograms: 2 rows; its sidecar says 3"
    );
    // A modelled piston fixes N too (its sequence is drawn at N).
    let piston = Configuration::from_physical(
        &Physical {
            fringe_hz: Some(100.0),
            ..physical(128)
        },
        true,
    )
    .unwrap();
    assert!(piston.inputs_for(ARRAY, 3, 64).is_err());
    // The inputs are checked once N is known: 1 sample is refused.
    assert!(config.inputs_for(ARRAY, 3, 1).is_err());
}

#[test]
fn a_refusal_names_the_file_or_the_argument_and_the_row() {
    let file = RowsName {
        param: "input",
        path: Some(Path::new("scans.npy")),
    };
    let mut data = vec![1.0; 4 * 8];
    data[2 * 8 + 5] = f64::NAN;
    let at_file = check_rows(file, &data, 8, 100).unwrap_err();
    assert!(matches!(at_file, Error::Data { param: "input", .. }));
    assert_eq!(
        at_file.detail(),
        "scans.npy: row 103, column 6 (1-based): NaN is not a finite number; every value must be finite"
    );
    data[2 * 8 + 5] = 1.0;
    data[3 * 8..].fill(0.0);
    let dark = check_rows(ARRAY, &data, 8, 0).unwrap_err();
    assert!(
        dark.to_string()
            .starts_with("interferograms: row 4 (1-based): every sample is 0"),
        "{dark}"
    );
    data[3 * 8] = 1e-300;
    assert_eq!(check_rows(ARRAY, &data, 8, 0), Ok(()));
}

/// `estimate_rows` checks each row as it estimates it, blocks of rows on
/// several threads: it refuses what `check_rows` refuses, with the same
/// message (a non-finite value anywhere before an earlier dark row; the
/// earliest of each, whichever thread met it), and its estimates of good
/// rows are those of one row at a time, to the bit, for any thread count.
#[test]
fn one_pass_estimate_refuses_what_check_rows_refuses_and_keeps_the_bits() {
    let (n, count) = (16, 2000);
    let inputs = Configuration::from_physical(&physical(n), true)
        .unwrap()
        .inputs_for(ARRAY, count, n)
        .unwrap();
    let model = Model::new(&inputs).unwrap();
    let scales: Vec<f64> = (0..count).map(|r| 1.0 + (r % 7) as f64 * 0.25).collect();
    let mut data = rows(&model, &scales);
    let options = (BinWindow::Positive, BiasConvention::Model);
    let est = estimator(&inputs, options, true, None, 1).unwrap();
    let one_by_one: Vec<_> = data
        .chunks(n)
        .map(|row| est.estimate(row).unwrap())
        .collect();
    for threads in [1, 2, 3] {
        let all = estimate_rows(&est, ARRAY, (&data, 0), threads).unwrap();
        assert_eq!(all, one_by_one, "{threads} threads");
    }
    // A dark row in the first block, non-finite values in later blocks
    // (rows 1500 and 1800): the first non-finite one is refused.
    data[300 * n..301 * n].fill(0.0);
    data[1800 * n + 3] = f64::INFINITY;
    data[1500 * n + 9] = f64::NAN;
    let by_check = check_rows(ARRAY, &data, n, 10).unwrap_err();
    assert_eq!(
        by_check.to_string(),
        "interferograms: row 1511, column 10 (1-based): NaN is not a finite number; every value must be finite"
    );
    for threads in [1, 2, 3] {
        let got = estimate_rows(&est, ARRAY, (&data, 10), threads).unwrap_err();
        assert_eq!(got, by_check, "{threads} threads");
    }
    // Without them: the earliest of the dark rows 301 and 1901 (1-based).
    data[1500 * n + 9] = 1.0;
    data[1800 * n + 3] = 1.0;
    data[1900 * n..1901 * n].fill(0.0);
    let dark = check_rows(ARRAY, &data, n, 0).unwrap_err();
    assert!(dark
        .to_string()
        .starts_with("interferograms: row 301 (1-based): every sample is 0"));
    for threads in [1, 2, 3] {
        assert_eq!(
            estimate_rows(&est, ARRAY, (&data, 0), threads).unwrap_err(),
            dark
        );
    }
}

/// The estimates through the command equal the slow oracle's (naive DFT,
/// the bias by its definition), normalized by the model or by a
/// calibrator's rows (the point source's, twice as bright): the
/// calibration is the mean of their raw estimates less their bias.
#[test]
fn estimates_match_the_oracle_with_the_model_or_a_calibrators_rows() {
    let inputs = Configuration::from_physical(&physical(64), true)
        .unwrap()
        .inputs_for(ARRAY, 3, 64)
        .unwrap();
    let model = Model::new(&inputs).unwrap();
    let data = rows(&model, &[1.0, 0.5, 2.0]);
    let options = (BinWindow::Positive, BiasConvention::Model);
    let by_model = estimator(&inputs, options, true, None, 1).unwrap();
    let got = estimate_rows(&by_model, ARRAY, (&data, 0), 1).unwrap();
    assert_eq!(got.len(), 3);
    let bins = model.bins(BinWindow::Positive);
    let variance = model.sample_variance();
    for (r, e) in got.iter().enumerate() {
        let row = &data[r * 64..(r + 1) * 64];
        let oracle = estimate_row_oracle(row, &bins, &variance, by_model.calibration()).unwrap();
        assert!(
            // tol: the oracle sums the same products over 64 samples in another order (~1e-14 relative); 1e-9 is a margin a wrong bin or bias, O(1) relative, cannot pass.
            (e.v1_sq - oracle.v1_sq).abs() <= 1e-9 * oracle.v1_sq.abs()
                // tol: as above.
                && (e.v2_sq - oracle.v2_sq).abs() <= 1e-9 * oracle.v2_sq.abs(),
            "row {r}: {e:?} against {oracle:?}"
        );
    }
    let cal_model = model.calibrator_model().unwrap();
    let cal_data = rows(&cal_model, &[2.0, 2.0]);
    let cal = CalibratorRows {
        name: RowsName {
            param: "calibrator",
            path: None,
        },
        rows: &cal_data,
        cols: 64,
    };
    let by_cal = estimator(&inputs, options, true, Some(cal), 1).unwrap();
    // The calibration by its definition: the mean of the calibrator rows'
    // raw estimates less their bias, by the oracle.
    let unit = Pair {
        v1_sq: 1.0,
        v2_sq: 1.0,
    };
    let cal_variance = cal_model.sample_variance();
    let mut expected = Pair {
        v1_sq: 0.0,
        v2_sq: 0.0,
    };
    for row in cal_data.chunks(64) {
        let o = estimate_row_oracle(row, &bins, &cal_variance, unit).unwrap();
        expected.v1_sq += (o.v1_sq_raw - o.v1_sq_bias) / 2.0;
        expected.v2_sq += (o.v2_sq_raw - o.v2_sq_bias) / 2.0;
    }
    let c = by_cal.calibration();
    assert!(
        // tol: the oracle sums the same products over 64 samples in another order (~1e-14 relative); 1e-9 is a margin a wrong bin or bias, O(1) relative, cannot pass.
        (c.v1_sq - expected.v1_sq).abs() <= 1e-9 * expected.v1_sq
            // tol: as above.
            && (c.v2_sq - expected.v2_sq).abs() <= 1e-9 * expected.v2_sq,
        "{c:?} against {expected:?}"
    );
    let scaled = estimate_rows(&by_cal, ARRAY, (&data, 0), 1).unwrap();
    for (r, e) in scaled.iter().enumerate() {
        let row = &data[r * 64..(r + 1) * 64];
        let oracle = estimate_row_oracle(row, &bins, &variance, expected).unwrap();
        assert!(
            // tol: the oracle sums the same products over 64 samples in another order (~1e-14 relative); 1e-9 is a margin a wrong bin or bias, O(1) relative, cannot pass.
            (e.v1_sq - oracle.v1_sq).abs() <= 1e-9 * oracle.v1_sq.abs(),
            "row {r}: {e:?} against {oracle:?}"
        );
    }
    let narrow = CalibratorRows {
        cols: 32,
        rows: &cal_data[..64],
        ..cal
    };
    let refused = estimator(&inputs, options, true, Some(narrow), 1).unwrap_err();
    assert_eq!(
        refused.to_string(),
        "calibrator: 32 columns; the interferograms have 64"
    );
    let dark = vec![0.0; 64];
    let dark = CalibratorRows { rows: &dark, ..cal };
    let refused = estimator(&inputs, options, true, Some(dark), 1).unwrap_err();
    assert!(
        refused
            .to_string()
            .starts_with("calibrator: row 1 (1-based)"),
        "{refused}"
    );
}

/// The CLI with a set's sidecar and other rows (`--input`): any number of
/// rows, but the set's N (it used to take N from the file and keep the
/// set's other inputs, which Python refused).
#[test]
fn the_cli_refuses_other_rows_of_another_n_than_the_sets() {
    let dir = tempfile::tempdir().unwrap();
    let run = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_v2ref"))
            .args(args)
            .current_dir(dir.path())
            .output()
            .unwrap()
    };
    let synth = ["synth", "--rows", "40", "--samples", "32", "--out", "set"];
    assert!(
        run(&[&synth[..], &["--reference-blocks", "8", "--quiet"]].concat())
            .status
            .success()
    );
    let other = ["synth", "--rows", "7", "--samples", "16", "--out", "other"];
    assert!(
        run(&[&other[..], &["--reference-blocks", "8", "--quiet"]].concat())
            .status
            .success()
    );
    let fewer = run(&["estimate", "--sidecar", "set.json", "--input", "other.npy"]);
    assert_eq!(fewer.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&fewer.stderr),
        "error: --input: other.npy: 16 columns; the configuration has 32 samples per row\n"
    );
    let own = run(&["estimate", "--sidecar", "set.json"]);
    assert!(own.status.success());
    assert_eq!(String::from_utf8_lossy(&own.stdout).lines().count(), 41);
}
