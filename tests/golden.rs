//! Golden data: `golden/` matches the code, and the checker finds every
//! kind of difference (so that a passing check means something).

use std::path::{Path, PathBuf};
use std::process::Command;
use v2ref_reproduction::golden::{check_figures, write_figures};
use v2ref_reproduction::table::{Column, Figure, Table};

fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("golden")
}

#[test]
#[ignore = "slow tier: every golden table regenerated and compared (16 s)"]
fn golden_data_matches_the_code() {
    // What `v2ref golden --check` runs: every figure at full effort.
    let figures =
        v2ref_reproduction::figures::all(v2ref_reproduction::cases::Effort::Full).unwrap();
    let report = check_figures(&golden_dir(), &figures);
    let tables: usize = figures.iter().map(|f| f.tables.len()).sum();
    assert_eq!(report.checked, tables);
    assert!(report.checked >= 9, "{} tables", report.checked);
    assert!(report.mismatches.is_empty(), "{:#?}", report.mismatches);
}

fn toy(id: &str, monte_carlo: bool) -> Figure {
    Figure {
        id: id.into(),
        caption: "toy".into(),
        monte_carlo,
        parameters: serde_json::json!({"a": 0.1 + 0.2, "b": [1.0, 2.5]}),
        tables: vec![Table {
            name: format!("{id}_t"),
            columns: vec![Column::new("x", "um"), Column::new("y", "")],
            rows: vec![
                vec![0.0, 1.0 / 3.0],
                vec![1.0, -2.0e-300],
                vec![2.0, std::f64::consts::PI],
            ],
        }],
    }
}

#[test]
fn write_then_check_round_trips_exactly() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("golden");
    let figs = vec![toy("figa", false), toy("figb", true)];
    let files = write_figures(&dir, &figs).unwrap();
    assert_eq!(files.len(), 4);
    let report = check_figures(&dir, &figs);
    assert_eq!(report.checked, 2);
    assert!(report.mismatches.is_empty(), "{:?}", report.mismatches);
    // The header carries names and units.
    let csv = std::fs::read_to_string(dir.join("figa_t.csv")).unwrap();
    assert!(csv.starts_with("x [um],y\n"), "{csv}");
    let meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("figa.json")).unwrap()).unwrap();
    assert_eq!(meta["generator"], "cargo run --release -- golden --update");
    assert_eq!(meta["crate_version"], env!("CARGO_PKG_VERSION"));
    // Rewriting replaces everything and leaves no temporary directory.
    write_figures(&dir, &figs[..1]).unwrap();
    assert!(!dir.join("figb.json").exists());
    let leftovers: Vec<_> = std::fs::read_dir(tmp.path())
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name())
        .collect();
    assert_eq!(leftovers.len(), 1, "{leftovers:?}");
}

#[test]
fn every_kind_of_difference_is_reported() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("g");
    let figs = vec![toy("figa", false), toy("figb", true)];
    write_figures(&dir, &figs).unwrap();

    // Within tolerance for deterministic tables: a relative 1e-15 change.
    let mut near = figs.clone();
    near[0].tables[0].rows[0][1] *= 1.0 + 1e-15;
    assert!(check_figures(&dir, &near).mismatches.is_empty());

    // Beyond it: 1e-10 relative, named by table, row and column.
    let mut far = figs.clone();
    far[0].tables[0].rows[2][1] *= 1.0 + 1e-10;
    let m = check_figures(&dir, &far).mismatches;
    assert_eq!(m.len(), 1, "{m:?}");
    assert_eq!(m[0].table, "figa_t");
    assert!(
        m[0].detail.contains("row 3") && m[0].detail.contains("column y"),
        "{}",
        m[0].detail
    );

    // Monte Carlo tables are compared exactly: one ulp is a mismatch.
    let mut ulp = figs.clone();
    let v = ulp[1].tables[0].rows[0][1];
    ulp[1].tables[0].rows[0][1] = f64::from_bits(v.to_bits() + 1);
    assert_eq!(check_figures(&dir, &ulp).mismatches.len(), 1);

    // Changed parameters, a new table, a figure no longer computed.
    let mut params = figs.clone();
    params[0].parameters = serde_json::json!({"a": 1.0, "b": [1.0, 2.5]});
    assert!(check_figures(&dir, &params)
        .mismatches
        .iter()
        .any(|m| m.detail.contains("parameters")));
    let mut extra = figs.clone();
    extra[0].tables.push(Table {
        name: "figa_new".into(),
        columns: vec![Column::new("x", "")],
        rows: vec![],
    });
    assert!(check_figures(&dir, &extra)
        .mismatches
        .iter()
        .any(|m| m.table == "figa_new"));
    let m = check_figures(&dir, &figs[..1]).mismatches;
    assert!(m.iter().any(|m| m.table == "figb"), "{m:?}");

    // A missing file and a malformed one.
    std::fs::remove_file(dir.join("figa_t.csv")).unwrap();
    std::fs::write(dir.join("figb_t.csv"), "x [um],y\n1,zz\n").unwrap();
    let m = check_figures(&dir, &figs).mismatches;
    assert!(
        m.iter().any(|m| m.table == "figa_t") && m.iter().any(|m| m.table == "figb_t"),
        "{m:?}"
    );
}

/// The CLI's figure check at full effort (22 s: the slow tier). Its
/// comparison is the library's, tested on toy figures above and on the real
/// ones by `golden_data_matches_the_code`; the CLI's reporting of a mismatch
/// is tested quickly on the vectors (tests/conformance_cli.rs).
#[test]
#[ignore = "slow tier: every figure at full effort through the CLI (22 s)"]
fn cli_check_names_each_mismatch_and_exits_non_zero() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("golden");
    std::fs::create_dir(&dir).unwrap();
    // The figures' files (the vectors have their own test, tests/conformance_cli.rs).
    for e in std::fs::read_dir(golden_dir()).unwrap() {
        let e = e.unwrap();
        if e.path().is_file() {
            std::fs::copy(e.path(), dir.join(e.file_name())).unwrap();
        }
    }
    // Tamper with one cell of Fig. 1.
    let path = dir.join("fig1_v1.csv");
    let text = std::fs::read_to_string(&path).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    let mut cells: Vec<String> = lines[101].split(',').map(str::to_owned).collect();
    cells[3] = "1.0e0".into();
    lines[101] = cells.join(",");
    std::fs::write(&path, lines.join("\n") + "\n").unwrap();

    let out = Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(["golden", "--check", "--only", "figures", "--json", "--dir"])
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["mismatched"], 1, "{json}");
    assert!(json["checked"].as_u64().unwrap() >= 9);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("fig1_v1") && stderr.contains("row 101"),
        "{stderr}"
    );
    crate::cli::assert_no_duplicate_keys(&["golden", "--check", "--only", "figures"], &{
        String::from_utf8_lossy(&out.stdout).into_owned()
    });
}

#[test]
fn golden_needs_exactly_one_of_check_and_update() {
    // Neither or both flags: bad input, one line, status 2.
    for args in [vec!["golden"], vec!["golden", "--check", "--update"]] {
        let out = Command::new(env!("CARGO_BIN_EXE_v2ref"))
            .args(&args)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert_eq!(
            String::from_utf8_lossy(&out.stderr).trim().lines().count(),
            1
        );
    }
}

/// The CLI's check names a mismatching file and exits 1 (the vectors: 3 s,
/// where the figures take 22 s; the two share the report and its printing).
#[test]
#[ignore = "slow tier: golden --check of the vectors with one planted mismatch (7 s)"]
fn cli_check_of_the_vectors_names_the_mismatch_and_exits_1() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("golden");
    std::fs::create_dir_all(dir.join("vectors")).unwrap();
    for sub in ["", "vectors"] {
        for e in std::fs::read_dir(golden_dir().join(sub)).unwrap() {
            let e = e.unwrap();
            if e.path().is_file() {
                std::fs::copy(e.path(), dir.join(sub).join(e.file_name())).unwrap();
            }
        }
    }
    // One bit of the last sample of one vector set.
    let path = dir.join("vectors").join("dispersion.npy");
    let mut bytes = std::fs::read(&path).unwrap();
    *bytes.last_mut().unwrap() ^= 1;
    std::fs::write(&path, bytes).unwrap();

    // The text answer (the JSON one: tests/conformance_cli.rs).
    let out = Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(["golden", "--check", "--only", "vectors", "--dir"])
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("checked 19 tables") && stdout.contains("1 mismatch"),
        "{stdout}"
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        stderr.trim_end().lines().collect::<Vec<_>>(),
        ["mismatch: vectors/dispersion.npy: differs from what the code writes (512128 bytes stored, 512128 computed)"],
        "{stderr}"
    );
}

/// `golden --update --only figures` replaces the folder whole, so it must
/// carry `vectors/` over: each vector file comes back byte for byte (it
/// deleted them all before). 22 s of figures at full effort: the slow tier.
#[test]
#[ignore = "slow tier: every figure at full effort through the CLI (22 s)"]
fn updating_only_the_figures_keeps_the_vectors() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("golden");
    let vectors = dir.join("vectors");
    std::fs::create_dir_all(&vectors).unwrap();
    let mut kept = Vec::new();
    for e in std::fs::read_dir(golden_dir().join("vectors")).unwrap() {
        let e = e.unwrap();
        std::fs::copy(e.path(), vectors.join(e.file_name())).unwrap();
        kept.push((e.file_name(), std::fs::read(e.path()).unwrap()));
    }
    assert!(kept.len() >= 3, "{} vector files", kept.len());
    let out = Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(["golden", "--update", "--only", "figures", "--dir"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(dir.join("fig1_v1.csv").is_file(), "the figures are written");
    for (name, bytes) in &kept {
        let now = std::fs::read(vectors.join(name)).unwrap();
        assert!(&now == bytes, "{name:?} changed or vanished");
    }
}
