//! The oracle route (`v2ref_core::oracle`): the golden vectors regenerated in
//! memory bit for bit, and the powered sets' power. The route's use from a
//! dependent crate, with its planted bugs, is `examples/downstream/`.

use std::path::Path;
use v2ref_core::oracle::{
    catalogue, powered_rows, worst_min_detectable, BiasConvention, BinWindow, Estimates, Set,
    BIAS_CONVENTIONS, BIN_WINDOWS, POWERED_REL_ERROR,
};

/// The float64 values of a version-1 `.npy` file (magic, version, a
/// little-endian u16 header length, the header, then the data), as bytes.
fn npy_data(path: &Path) -> Vec<u8> {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..8], b"\x93NUMPY\x01\x00", "{}", path.display());
    let header = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    bytes[10 + header..].to_vec()
}

/// Every golden vector, made in memory by `Set::golden`, is bit for bit
/// the committed one: its rows are the `.npy` file's data, its sidecar's
/// JSON the `.json` file. A dependent crate can use the vectors without
/// the repository's files.
#[test]
fn golden_vectors_regenerate_bit_for_bit_in_memory() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("golden/vectors");
    for v in catalogue() {
        let set = Set::golden(v.name).unwrap();
        let mine: Vec<u8> = set.values().iter().flat_map(|x| x.to_le_bytes()).collect();
        let stored = npy_data(&dir.join(format!("{}.npy", v.name)));
        assert!(mine == stored, "{}: rows differ from the .npy", v.name);
        let json = std::fs::read_to_string(dir.join(format!("{}.json", v.name))).unwrap();
        assert!(set.sidecar_json() == json, "{}: sidecar differs", v.name);
        assert_eq!(set.rows().count(), set.len());
    }
}

/// A name outside the catalogue is refused, naming the parameter and the
/// vectors; a powered set of a piston vector is refused, naming the
/// piston-free ones; a set of one row is refused as `synth` refuses it.
#[test]
fn the_route_refuses_unknown_and_piston_vectors() {
    let e = Set::golden("noise").unwrap_err();
    assert_eq!(e.param(), Some("name"));
    assert!(e.to_string().contains("noise_gaussian"), "{e}");
    let piston = catalogue()
        .into_iter()
        .find(|v| v.name == "piston_low")
        .unwrap();
    let e = powered_rows(&piston).unwrap_err();
    assert_eq!(e.param(), Some("name"));
    assert!(e.to_string().contains("noise_both"), "{e}");
    let e = Set::synthesize(&v2ref_core::oracle::Inputs::default(), 1, 3).unwrap_err();
    assert_eq!(e.param(), Some("rows"), "{e}");
}

/// The powered set of `noise_both` (photon and detector noise, N = 64)
/// has the power it is made for: under every window and convention, the
/// smallest relative error of either estimator's mean or variance caught
/// with probability 0.9 is at most 2 % — and below 2 % only by the
/// rounding of its row count (more than 1.5 %: a set far larger than
/// needed would hide a wrong row count). Shown on the set itself: v2ref's
/// own estimates pass, and each estimator's mean or variance made 2 %
/// larger, or the other window's bins, fails.
#[test]
fn a_powered_set_catches_a_two_percent_error() {
    let set = Set::powered("noise_both").unwrap();
    let worst = worst_min_detectable(set.truth()).unwrap().unwrap();
    println!(
        "noise_both powered: {} rows, worst smallest error {worst:.4}",
        set.len()
    );
    assert!((0.015..=POWERED_REL_ERROR).contains(&worst), "{worst}");
    for window in BIN_WINDOWS {
        for bias in BIAS_CONVENTIONS {
            let Ok(est) = set.reference_estimates(window, bias) else {
                continue;
            };
            let v1: Vec<f64> = est.iter().map(|r| r.v1_sq).collect();
            let v2: Vec<f64> = est.iter().map(|r| r.v2_sq).collect();
            let pass = |a: &[f64], b: &[f64]| {
                let given = Estimates::default().v1_sq(a).v2_sq(b);
                set.score(window, bias, given).unwrap().pass
            };
            assert!(
                pass(&v1, &v2),
                "{window:?} {bias:?}: v2ref's own estimates fail"
            );
            let mean_up = |x: &[f64]| {
                x.iter()
                    .map(|v| v * (1.0 + POWERED_REL_ERROR))
                    .collect::<Vec<_>>()
            };
            let var_up = |x: &[f64]| {
                let m = x.iter().sum::<f64>() / x.len() as f64;
                let s = (1.0 + POWERED_REL_ERROR).sqrt();
                x.iter().map(|v| m + (v - m) * s).collect::<Vec<_>>()
            };
            assert!(
                !pass(&mean_up(&v1), &v2),
                "{window:?} {bias:?}: V1² mean +2 %"
            );
            assert!(
                !pass(&v1, &mean_up(&v2)),
                "{window:?} {bias:?}: V2² mean +2 %"
            );
            assert!(
                !pass(&var_up(&v1), &v2),
                "{window:?} {bias:?}: V1² variance +2 %"
            );
            assert!(
                !pass(&v1, &var_up(&v2)),
                "{window:?} {bias:?}: V2² variance +2 %"
            );
        }
    }
    // A wrong bin set: the all-bins estimates scored as the positive window's.
    let (right, wrong) = (BinWindow::Positive, BinWindow::All);
    let est = set
        .reference_estimates(wrong, BiasConvention::Model)
        .unwrap();
    let v1: Vec<f64> = est.iter().map(|r| r.v1_sq).collect();
    let v2: Vec<f64> = est.iter().map(|r| r.v2_sq).collect();
    assert!(
        !set.score(
            right,
            BiasConvention::Model,
            Estimates::default().v1_sq(&v1).v2_sq(&v2)
        )
        .unwrap()
        .pass
    );
}

/// A verdict prints on one screen (at most 12 lines of at most 100
/// characters for both estimators), says FAIL, and marks the test out.
#[test]
fn a_score_report_displays_on_one_screen() {
    use v2ref_core::oracle::{Inputs, SourceInput};
    let source = SourceInput::Point;
    let inputs = Inputs {
        samples: 32,
        source,
        visibility: 0.6,
        photons: 50.0,
        ..Inputs::default()
    };
    let set = Set::synthesize(&inputs, 2000, 7).unwrap();
    let (window, bias) = (BinWindow::Positive, BiasConvention::Model);
    let est = set.reference_estimates(window, bias).unwrap();
    let v1: Vec<f64> = est.iter().map(|r| r.v1_sq).collect();
    let v2: Vec<f64> = est.iter().map(|r| 1.1 * r.v2_sq).collect();
    let report = set
        .score(window, bias, Estimates::default().v1_sq(&v1).v2_sq(&v2))
        .unwrap();
    let text = report.to_string();
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines.len() <= 12, "{text}");
    assert!(lines.iter().all(|l| l.chars().count() <= 100), "{text}");
    assert!(lines[0].starts_with("FAIL"), "{text}");
    let v2_lines = &lines[lines.iter().position(|l| l.contains("v2_sq")).unwrap()..];
    assert!(v2_lines[0].contains("<- out"), "{text}");
    assert!(!lines[1].contains("<- out"), "{text}");
    // Neither estimator given is refused, naming the parameter.
    let none = set.score(window, bias, Estimates::default()).unwrap_err();
    assert!(none.to_string().contains("estimates"), "{none}");
}
