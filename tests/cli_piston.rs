//! `v2ref piston` from the outside: JSON fields, the table, determinism
//! across thread counts, bad input (one line, status 2).

use std::process::Command;
use v2ref_core::assert_abs_eq;
use v2ref_core::tolerance::PRINTED_2_DECIMALS_ABS;

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

#[test]
fn fringe_hz_ranges_give_their_values_and_bad_ranges_are_one_line() {
    let mut args = SMALL[..5].to_vec();
    args.extend([
        "--fringe-hz",
        "100:400:4",
        "--fringe-hz",
        "1000:4000:3:log",
        "--fringe-hz",
        "50",
        "--quiet",
        "--json",
    ]);
    let out = v2ref(&args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let got: Vec<f64> = v["results"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["fringe_hz"].as_f64().unwrap())
        .collect();
    assert_eq!(
        got,
        [100.0, 200.0, 300.0, 400.0, 1000.0, 2000.0, 4000.0, 50.0]
    );
    for bad in [
        "100:400",
        "100:400:1",
        "100:400:x",
        "0:400:3:log",
        "1:2:3:cubic",
        "a:b:c",
    ] {
        let mut args = SMALL[..5].to_vec();
        args.extend(["--fringe-hz", bad, "--quiet"]);
        let out = v2ref(&args);
        assert_eq!(out.status.code(), Some(2), "{bad}");
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(err.trim_end().lines().count(), 1, "{bad}: {err}");
        assert!(
            err.contains("--fringe-hz") && err.contains("A:B:N:log"),
            "{bad}: {err}"
        );
    }
}

#[test]
fn the_answer_names_the_spectrum_model_and_the_source_visibility() {
    // A 2 mas disk on 18 m at 2.2 um: V = 2J1(z)/z, z = π θ B/λ.
    let mut args = SMALL.to_vec();
    args[2] = "ud";
    args.extend([
        "--diameter-mas",
        "2",
        "--baseline-m",
        "18",
        "--psd",
        "three-slope",
        "--json",
    ]);
    let out = v2ref(&args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["psd"], "three-slope");
    let corners = v["psd_corners_hz"].as_array().unwrap();
    // tol: the same products of the inputs, printed to 17 digits: rounding only, on values of order 0.1 to 10.
    assert_abs_eq!(corners[0].as_f64().unwrap(), 0.2 * 10.0 / 18.0, 1e-9);
    // tol: as above.
    assert_abs_eq!(corners[1].as_f64().unwrap(), 0.3 * 10.0 / 0.45, 1e-9);
    let z = std::f64::consts::PI * 2e-3 / 206_264.806_247 * 18.0 / 2.2e-6;
    let vis = v["visibility"].as_f64().unwrap();
    // σ_eff of the flat 2.0-2.4 um band is near 1/2.2 um: V to 1e-3.
    let jinc = 1.0 - z * z / 8.0 + z.powi(4) / 192.0 - z.powi(6) / 9216.0;
    // tol: σ_eff of the flat band is 1/2.2 µm only to ~1e-3 relative, and the series stops at z^6.
    assert_abs_eq!(vis, jinc, 1e-3);
    // The human table prints V beside the bias and scatter.
    let mut args = SMALL.to_vec();
    args.extend(["--wind-angle-deg", "90"]);
    let text = String::from_utf8(v2ref(&args).stdout).unwrap();
    assert!(
        text.contains("source V = 1.000000") && text.contains("wind 90 deg"),
        "{text}"
    );
    // The three-slope spectrum has no wind direction: one line, status 2.
    let mut args = SMALL.to_vec();
    args.extend(["--psd", "three-slope", "--wind-angle-deg", "30"]);
    let out = v2ref(&args);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8(out.stderr)
        .unwrap()
        .contains("wind-angle-deg"));
}
