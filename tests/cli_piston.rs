//! `v2ref piston` from the outside: JSON fields, the table, determinism
//! across thread counts, bad input (one line, status 2).

use std::process::Command;
use v2ref::assert_abs_eq;
use v2ref::tolerance::PRINTED_2_DECIMALS_ABS;

fn v2ref(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(args)
        .output()
        .expect("runs")
}

const SMALL: [&str; 8] = [
    "piston",
    "--source",
    "point",
    "--scans",
    "60",
    "--fringe-hz",
    "400",
    "--quiet",
];

#[test]
fn json_has_the_contract_fields_per_frequency() {
    let mut args = SMALL.to_vec();
    args.extend(["--fringe-hz", "900", "--json"]);
    let out = v2ref(&args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let rows = v["results"].as_array().unwrap();
    assert_eq!(rows.len(), 2);
    for (row, f) in rows.iter().zip([400.0, 900.0]) {
        assert_eq!(row["fringe_hz"].as_f64(), Some(f));
        for key in [
            "bias_v1",
            "bias_v2",
            "scatter_v1",
            "scatter_v2",
            "bias_v1_stderr",
            "bias_v2_stderr",
            "scatter_v1_stderr",
            "scatter_v2_stderr",
        ] {
            assert!(row[key].as_f64().unwrap().is_finite(), "{key}");
        }
        assert!(row["scatter_v1"].as_f64().unwrap() > 0.0);
        assert_eq!(row["scans"].as_u64(), Some(60));
    }
    // 40 cycles/arcsec by default: the 18 m baseline.
    assert_abs_eq!(
        v["baseline_m"].as_f64().unwrap(),
        18.0,
        PRINTED_2_DECIMALS_ABS
    );
    assert_eq!(v["bins"], "positive");
    assert_eq!(v["detector"], "sampled");
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    let run = |threads: &str| {
        let mut args = SMALL.to_vec();
        args.extend(["--json", "--integrating", "--threads", threads]);
        v2ref(&args).stdout
    };
    let (a, b) = (run("1"), run("2"));
    assert!(!a.is_empty());
    assert_eq!(a, b);
}

#[test]
fn human_table_and_quiet_stderr() {
    let out = v2ref(&SMALL);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("bias V1") && text.contains("400.00"));
    assert!(out.stderr.is_empty(), "quiet run wrote to stderr");
}

#[test]
fn no_turbulence_answers_zero() {
    let mut args = SMALL.to_vec();
    args.extend(["--seeing-arcsec", "0", "--json"]);
    let out = v2ref(&args);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let row = &v["results"][0];
    for key in ["bias_v1", "bias_v2", "scatter_v1", "scatter_v2"] {
        assert_eq!(row[key].as_f64(), Some(0.0), "{key}");
    }
}

#[test]
fn bad_input_is_one_line_and_status_2() {
    for (flag, value) in [
        ("--wind-mps", "0"),
        ("--seeing-arcsec", "-1"),
        ("--aperture-m", "0"),
        ("--fringe-hz", "0"),
        ("--scans", "1"),
        ("--outer-scale-m", "-5"),
        ("--sub-samples", "0"),
        ("--dx-um", "2"),
        ("--wind-mps", "nan"),
    ] {
        let pair = format!("{flag}={value}");
        let mut args = SMALL.to_vec();
        args.extend(["--integrating", &pair]);
        let out = v2ref(&args);
        assert_eq!(out.status.code(), Some(2), "{flag} {value}");
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(err.trim_end().lines().count(), 1, "{flag}: {err}");
        let name = flag.trim_start_matches("--");
        assert!(
            err.contains(name) || (flag == "--dx-um" && err.contains("dx-um")),
            "{flag}: {err}"
        );
    }
}
