//! OIFITS: `estimate --out FILE.fits` holds the same numbers as the CSV
//! and gets the same verdict from `score`; files written independently of
//! v2ref's writer (OIFITS v1 and v2, with the tests' own plain writer, `tests/fits_plain.rs`) are read, their
//! FLAGged rows left out and counted; mismatched files are refused with
//! the flag named; `synth --oifits` and `plan --oifits` write files the
//! reader takes back.

use crate::fits_plain::{self, Card, Column};
use std::path::Path;
use v2ref_oifits::read_vis2_tables;

use crate::run::v2ref;

fn ok(args: &[&str]) -> String {
    let (code, out, err) = v2ref(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    out
}

/// A refusal: status 2, one line naming `flag`, no panic.
fn refused(args: &[&str], flag: &str, words: &str) {
    let (code, _, err) = v2ref(args);
    assert_eq!(code, 2, "{args:?}: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(
        err.contains(flag) && err.contains(words),
        "{flag} / {words}: {err}"
    );
    assert!(!err.contains("panicked"), "{err}");
}

const ROWS: usize = 300;

fn synth(dir: &Path, extra: &[&str]) -> String {
    let stem = dir.join("set").display().to_string();
    let rows = ROWS.to_string();
    let mut args = vec![
        "synth",
        "--out",
        &stem,
        "--rows",
        &rows,
        "--samples",
        "32",
        "--source",
        "point",
        "--visibility",
        "0.6",
        "--photons",
        "30",
        "--reference-blocks",
        "8",
        "--quiet",
    ];
    args.extend_from_slice(extra);
    ok(&args);
    format!("{stem}.json")
}

/// `score --json` with the estimates, as (exit status, JSON).
fn score(sidecar: &str, est: &str, extra: &[&str]) -> (i32, serde_json::Value) {
    let mut args = vec!["score", "--sidecar", sidecar, "--estimates", est, "--json"];
    args.extend_from_slice(extra);
    let (code, out, err) = v2ref(&args);
    assert!(code == 0 || code == 1, "{args:?}: {err}");
    (code, serde_json::from_str(&out).unwrap())
}

fn csv_column(path: &Path, name: &str) -> Vec<f64> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let k = lines
        .next()
        .unwrap()
        .split(',')
        .position(|c| c == name)
        .unwrap();
    lines
        .map(|l| l.split(',').nth(k).unwrap().parse().unwrap())
        .collect()
}

#[test]
fn csv_and_oifits_hold_the_same_estimates_and_get_the_same_verdict() {
    let dir = tempfile::tempdir().unwrap();
    let sidecar = synth(dir.path(), &[]);
    let csv = dir.path().join("est.csv");
    let fits = dir.path().join("est.fits");
    ok(&[
        "estimate",
        "--sidecar",
        &sidecar,
        "--out",
        csv.to_str().unwrap(),
    ]);
    ok(&[
        "estimate",
        "--sidecar",
        &sidecar,
        "--out",
        fits.to_str().unwrap(),
    ]);
    let tables = read_vis2_tables(&fits, "estimates").unwrap();
    assert_eq!(tables.len(), 2);
    for (t, col, key) in [(&tables[0], "v1_sq", "V1SQ"), (&tables[1], "v2_sq", "V2SQ")] {
        assert_eq!(t.estimator.as_deref(), Some(key));
        assert_eq!((t.rows, t.nwave, t.revn), (ROWS, 1, 2));
        assert_eq!(t.vis2data, csv_column(&csv, col));
        assert!(t.flag.iter().all(|f| !f));
        assert!(t.vis2err.iter().all(|e| *e > 0.0 && e.is_finite()));
        // K band: 1/σ_eff lies within 2.0–2.4 µm.
        assert!(
            (2.0e-6..2.4e-6).contains(&t.eff_wave_m[0]),
            "{:?}",
            t.eff_wave_m
        );
    }
    let (c1, j1) = score(&sidecar, csv.to_str().unwrap(), &[]);
    let (c2, j2) = score(&sidecar, fits.to_str().unwrap(), &[]);
    assert_eq!(c1, c2);
    assert_eq!(j1["estimators"], j2["estimators"]);
    assert_eq!(j1["pass"], j2["pass"]);
    assert_eq!(j2["flagged"], 0);
}

/// Writes an OIFITS file the way another pipeline would (not v2ref's
/// writer): `revn` 1 or 2, one OI_WAVELENGTH per INSNAME, one OI_VIS2
/// table per entry of `tables` (INSNAME, values, flags), no v2ref keyword.
fn external(path: &Path, revn: i64, eff_wave_m: f32, tables: &[(&str, &[f64], &[bool])]) {
    let mut hdus = Vec::new();
    for (ins, vals, flags) in tables {
        let keys = || vec![("OI_REVN", Card::Int(revn)), ("INSNAME", Card::Str(ins))];
        hdus.push((
            "OI_WAVELENGTH",
            keys(),
            vec![Column::F32("EFF_WAVE", vec![eff_wave_m])],
        ));
        hdus.push((
            "OI_VIS2",
            keys(),
            vec![
                Column::I16("TARGET_ID", vec![1; vals.len()]),
                Column::F64("VIS2DATA", vals.to_vec()),
                Column::F64("VIS2ERR", vec![0.1; vals.len()]),
                Column::Logical("FLAG", flags.to_vec()),
            ],
        ));
    }
    fits_plain::write(path, &hdus);
}

#[test]
fn a_pipelines_v1_file_is_scored_with_its_flags_left_out() {
    let dir = tempfile::tempdir().unwrap();
    let sidecar = synth(dir.path(), &[]);
    let csv = dir.path().join("est.csv");
    ok(&[
        "estimate",
        "--sidecar",
        &sidecar,
        "--out",
        csv.to_str().unwrap(),
    ]);
    let mut v2 = csv_column(&csv, "v2_sq");
    let mut flags = vec![false; ROWS];
    for r in [3, 50, 51, 299] {
        flags[r] = true;
        v2[r] = f64::NAN; // a flagged value need not be a number
    }
    let file = dir.path().join("pipe.oifits");
    external(&file, 1, 2.2e-6, &[("PIPE", &v2, &flags)]);
    let f = file.to_str().unwrap();
    refused(
        &["score", "--sidecar", &sidecar, "--estimates", f],
        "--estimator",
        "V2R_EST",
    );
    let (_, j) = score(&sidecar, f, &["--estimator", "v2_sq"]);
    assert_eq!(j["flagged"], 4);
    assert_eq!(j["rows"], (ROWS - 4) as u64);
    let e = &j["estimators"][0];
    assert_eq!(e["estimator"], "v2_sq");
    let kept: Vec<f64> = v2.iter().copied().filter(|x| x.is_finite()).collect();
    let mean = kept.iter().sum::<f64>() / kept.len() as f64;
    // tol: a mean of at most a few hundred values, through the FITS double column and JSON's 17 digits: ~1e-13 relative.
    assert!((e["mean"].as_f64().unwrap() - mean).abs() <= 1e-12 * mean.abs().max(1.0));
}

#[test]
fn a_biased_pipeline_fails_the_same_way_in_csv_and_oifits() {
    let dir = tempfile::tempdir().unwrap();
    let sidecar = synth(dir.path(), &[]);
    let csv = dir.path().join("est.csv");
    ok(&[
        "estimate",
        "--sidecar",
        &sidecar,
        "--out",
        csv.to_str().unwrap(),
    ]);
    let v2: Vec<f64> = csv_column(&csv, "v2_sq")
        .iter()
        .map(|x| 1.3 * x + 0.05)
        .collect();
    let biased = dir.path().join("biased.csv");
    let text: String = std::iter::once("v2_sq".to_string())
        .chain(v2.iter().map(|x| format!("{x:?}")))
        .collect::<Vec<_>>()
        .join("\n");
    std::fs::write(&biased, text + "\n").unwrap();
    let fits = dir.path().join("biased.fits");
    external(&fits, 2, 2.2e-6, &[("PIPE", &v2, &[false; ROWS])]);
    let (c1, j1) = score(&sidecar, biased.to_str().unwrap(), &[]);
    let (c2, j2) = score(&sidecar, fits.to_str().unwrap(), &["--estimator", "v2_sq"]);
    assert_eq!((c1, c2), (1, 1), "{j1} {j2}");
    assert_eq!(j1["estimators"], j2["estimators"]);
}

#[test]
fn mismatched_files_are_refused_naming_the_flag() {
    let dir = tempfile::tempdir().unwrap();
    let sidecar = synth(dir.path(), &[]);
    let p = |n: &str| dir.path().join(n).display().to_string();
    let v = vec![0.3; ROWS];
    let clean = vec![false; ROWS];
    external(
        Path::new(&p("short.fits")),
        2,
        2.2e-6,
        &[("P", &v[1..], &clean[1..])],
    );
    external(Path::new(&p("wave.fits")), 2, 1.6e-6, &[("P", &v, &clean)]);
    external(
        Path::new(&p("two.fits")),
        2,
        2.2e-6,
        &[("A", &v, &clean), ("B", &v, &clean)],
    );
    let r = |f: &str, extra: &[&str], flag: &str, words: &str| {
        let path = p(f);
        let mut a = vec!["score", "--sidecar", &sidecar, "--estimates", &path];
        a.extend_from_slice(extra);
        refused(&a, flag, words)
    };
    r(
        "short.fits",
        &["--estimator", "v2_sq"],
        "--estimates",
        "299 rows",
    );
    r(
        "wave.fits",
        &["--estimator", "v2_sq"],
        "--estimates",
        "EFF_WAVE",
    );
    r("two.fits", &["--estimator", "v2_sq"], "--insname", "A, B");
    r(
        "two.fits",
        &["--estimator", "v2_sq", "--insname", "C"],
        "--insname",
        "A, B",
    );
    let (_, j) = score(
        &sidecar,
        &p("two.fits"),
        &["--estimator", "v2_sq", "--insname", "B"],
    );
    assert_eq!(j["rows"], ROWS as u64);
    // A flag of the other format is refused, not silently ignored.
    r(
        "two.fits",
        &[
            "--estimator",
            "v2_sq",
            "--insname",
            "B",
            "--columns",
            "v2_sq",
        ],
        "--columns",
        ".npy",
    );
    std::fs::write(p("est.csv"), "v1_sq,v2_sq\n").unwrap();
    r("est.csv", &["--insname", "B"], "--insname", "OIFITS");
    r(
        "est.csv",
        &["--estimator", "v2_sq"],
        "--estimator",
        "OIFITS",
    );
}

#[test]
fn an_extension_that_is_not_the_format_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let sidecar = synth(dir.path(), &[]);
    let out = dir.path().join("est.txt");
    refused(
        &[
            "estimate",
            "--sidecar",
            &sidecar,
            "--out",
            out.to_str().unwrap(),
        ],
        "--out",
        ".fits",
    );
    assert!(!out.exists());
}

#[test]
fn synth_and_plan_write_files_the_reader_takes_back() {
    let dir = tempfile::tempdir().unwrap();
    let sidecar = synth(dir.path(), &["--oifits"]);
    let truth = dir.path().join("set.truth.fits");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&sidecar).unwrap()).unwrap();
    let conv = &json["truth"]["windows"][0]["conventions"][0];
    assert_eq!(json["truth"]["windows"][0]["bins"], "positive");
    assert_eq!(conv["bias"], "model");
    let tables = read_vis2_tables(&truth, "estimates").unwrap();
    for (t, k) in tables.iter().zip(["v1_sq", "v2_sq"]) {
        assert_eq!(t.rows, ROWS);
        assert!(t
            .vis2data
            .iter()
            .all(|&x| x == conv[k]["mean"].as_f64().unwrap()));
    }
    let plan = dir.path().join("plan.fits");
    let p = plan.to_str().unwrap();
    ok(&[
        "plan",
        "--quiet",
        "--fringe-hz",
        "300",
        "--stroke-um",
        "32",
        "--scans",
        "64",
        "--seeing-arcsec",
        "0.8",
        "--oifits",
        p,
    ]);
    let t = &read_vis2_tables(&plan, "oifits").unwrap()[0];
    assert_eq!((t.rows, t.nwave), (1, 1));
    assert!(t.vis2data[0] > 0.0 && t.vis2err[0] > 0.0);
    refused(
        &[
            "plan",
            "--quiet",
            "--fringe-hz",
            "300",
            "--stroke-um",
            "32",
            "--oifits",
            "plan.csv",
        ],
        "--oifits",
        ".fits",
    );
}
