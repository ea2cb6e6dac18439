//! `v2ref reproduce --quick` writes every figure and the claims table.

use std::process::Command;

#[test]
#[ignore = "slow tier: the quick reproduction through the CLI (10 s)"]
fn quick_reproduction_writes_every_expected_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("repro");
    // The folder is one v2ref wrote (its marker inside): it is replaced, and
    // the leftovers of a killed run go (tests/robustness_cli.rs: a user's
    // folder is refused).
    std::fs::create_dir(&out).unwrap();
    std::fs::write(out.join(".v2ref-output"), "written by v2ref\n").unwrap();
    std::fs::write(out.join("old.csv"), "stale\n").unwrap();
    let stale = dir.path().join(".v2ref-tmp-4000000000-0-repro");
    std::fs::create_dir(&stale).unwrap();
    std::fs::write(
        stale.join(".v2ref-temporary"),
        "a temporary folder of v2ref; removed when its run is gone\n",
    )
    .unwrap();
    // Named as a killed run's temporary, of a process that is gone, but
    // without v2ref's marker inside: the user's, kept.
    let users = dir.path().join(".v2ref-tmp-4000000001-0-repro");
    std::fs::create_dir(&users).unwrap();
    std::fs::write(users.join("thesis.tex"), "mine\n").unwrap();
    let run = Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(["reproduce", "--quick", "--quiet", "--json", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let stdout = String::from_utf8_lossy(&run.stdout);
    crate::cli::assert_no_duplicate_keys(&["reproduce", "--quick", "--json"], &stdout);
    let answer: serde_json::Value = serde_json::from_str(&stdout).expect("JSON answer");
    assert!(out.join(".v2ref-output").is_file());
    assert!(!out.join("old.csv").exists(), "the old content stayed");
    assert!(!out.join(".v2ref-temporary").exists());
    assert!(!stale.exists(), "v2ref's own leftover stayed");
    assert!(
        users.join("thesis.tex").is_file(),
        "the user's folder was removed"
    );

    // Every figure, each table as CSV (with the header its metadata declares) and SVG.
    for id in ["fig0", "fig1", "fig2", "fig3", "fig4", "fig5"] {
        let meta: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join(format!("{id}.json"))).unwrap())
                .unwrap();
        let tables = meta["tables"].as_array().expect("tables");
        assert!(!tables.is_empty(), "{id}: no tables");
        for t in tables {
            let name = t["name"].as_str().unwrap();
            let csv = std::fs::read_to_string(out.join(format!("{name}.csv"))).unwrap();
            let mut lines = csv.lines();
            let header: Vec<&str> = lines.next().unwrap().split(',').collect();
            let declared: Vec<&str> = t["columns"]
                .as_array()
                .unwrap()
                .iter()
                .map(|c| c.as_str().unwrap())
                .collect();
            assert_eq!(header, declared, "{name}: header");
            let mut rows = 0;
            for line in lines {
                let cells: Vec<f64> = line
                    .split(',')
                    .map(|c| c.parse().expect("a number"))
                    .collect();
                assert_eq!(cells.len(), header.len(), "{name}: row width");
                rows += 1;
            }
            assert!(rows >= 3, "{name}: {rows} rows");
            let svg = std::fs::read_to_string(out.join(format!("{name}.svg"))).unwrap();
            assert!(
                svg.starts_with("<svg") && svg.contains("</svg>"),
                "{name}.svg"
            );
            assert!(
                svg.contains("<polyline") || svg.contains("<path"),
                "{name}.svg draws no curve"
            );
        }
    }
    // The claims table: Markdown and JSON, nothing pending, same as the answer.
    let md = std::fs::read_to_string(out.join("claims.md")).unwrap();
    let claims: Vec<serde_json::Value> =
        serde_json::from_str(&std::fs::read_to_string(out.join("claims.json")).unwrap()).unwrap();
    assert_eq!(claims.len(), v2ref_reproduction::claims::ledger().len());
    for c in &claims {
        let id = c["id"].as_str().unwrap();
        assert_ne!(c["status"], "pending", "{id} is pending");
        assert!(
            md.contains(&format!("`{id}`")),
            "{id} missing from claims.md"
        );
    }
    assert_eq!(answer["claims"].as_array().unwrap().len(), claims.len());
    assert!(answer["files"].as_array().unwrap().len() >= 30);
    // The Fig. 5 sensitivity table: 2 spectra x 2 references x 3 windows x
    // 2 samplings, each with the four thresholds inside the simulated range
    // (or NaN for "V1 unbiased from" when V1 is biased at every frequency).
    let csv = std::fs::read_to_string(out.join("fig5_sensitivity.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    // Per threshold: value, its interval (lo, hi), the paper's.
    assert_eq!(header.len(), 21, "{header:?}");
    assert_eq!(header[6], "v1_biased_1pct_below_hz_lo");
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 24);
    for r in &rows {
        for t in [5, 9, 13, 17] {
            let v: f64 = r[t].parse().unwrap();
            let (lo, hi): (f64, f64) = (r[t + 1].parse().unwrap(), r[t + 2].parse().unwrap());
            assert!(
                v.is_nan() || (50.0 - 1e-9..=2000.0 + 1e-9).contains(&v),
                "{r:?}"
            );
            // The interval holds the value (or both are NaN); the CSV
            // rounds to 0.1 Hz.
            assert!(
                v.is_nan() && lo.is_nan() && hi.is_nan() || (lo <= v + 0.05 && v <= hi + 0.05),
                "{r:?}"
            );
        }
    }
    let md = std::fs::read_to_string(out.join("fig5_sensitivity.md")).unwrap();
    assert_eq!(md.matches("| three-slope |").count(), 12);
    // No staging directory is left behind, the killed run's is gone, the
    // user's stays.
    let mut leftovers: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    leftovers.sort();
    assert_eq!(
        leftovers,
        [".v2ref-tmp-4000000001-0-repro", "repro"],
        "{leftovers:?}"
    );
}

#[test]
fn reproduce_refuses_to_write_into_golden() {
    let run = Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(["reproduce", "--quick", "--quiet", "--out", "golden"])
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        stderr.contains("--out") && stderr.contains("golden"),
        "{stderr}"
    );
}
