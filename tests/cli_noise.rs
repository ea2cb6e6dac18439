//! `v2ref snr` and `v2ref simulate` against the CLI contract.

use serde_json::Value;
use v2ref_core::assert_within_sigmas;
use v2ref_core::tolerance::{IDENTITY_REL, MC_SIGMAS};

use crate::run::v2ref;

fn json(args: &[&str]) -> Value {
    let (code, out, err) = v2ref(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    serde_json::from_str(&out).expect("one JSON document")
}

#[test]
fn snr_json_has_the_contract_fields_and_the_appendix_numbers() {
    let v = json(&[
        "snr",
        "--source",
        "point",
        "--read-noise",
        "2",
        "--no-photon-noise",
        "--bins",
        "all",
        "--json",
    ]);
    for f in ["sum_m2", "var_v1_sq", "var_v2_sq", "snr1", "snr2"] {
        assert!(v[f].is_number(), "{f}");
    }
    // SNR2 = 1/√(0.08·2.04) for σ_det = 0.2 n, m0 = n.
    let snr2 = v["snr2"].as_f64().unwrap();
    assert!((snr2 - 1.0 / (0.08f64 * 2.04).sqrt()).abs() < IDENTITY_REL);
    // SNR1 from the reported Σm²: s/√(0.08(2s + 0.04 N)), s = Σm²/n².
    let s = v["sum_m2"].as_f64().unwrap() / 100.0;
    let snr1 = v["snr1"].as_f64().unwrap();
    assert!((snr1 - s / (0.08 * (2.0 * s + 0.04 * 128.0)).sqrt()).abs() < IDENTITY_REL);
    // The exact window statistics for all bins equal the closed form.
    let w = v["window_exact"]["snr1"].as_f64().unwrap();
    assert!((w / snr1 - 1.0).abs() < IDENTITY_REL);
}

#[test]
fn snr_published_and_exact_photon() {
    let p = json(&[
        "snr",
        "--source",
        "point",
        "--formula",
        "published",
        "--json",
    ]);
    let e = json(&["snr", "--source", "point", "--json"]);
    assert!((p["snr2"].as_f64().unwrap() - 100.0 / 34420f64.sqrt()).abs() < IDENTITY_REL);
    assert!((e["snr2"].as_f64().unwrap() - 100.0 / 9620f64.sqrt()).abs() < IDENTITY_REL);
    assert_eq!(e["formula"], "exact");
}

#[test]
fn simulate_is_identical_for_one_and_two_threads() {
    let base = [
        "simulate",
        "--source",
        "point",
        "--read-noise",
        "1",
        "--trials",
        "30000",
        "--seed",
        "5",
        "--json",
        "--quiet",
    ];
    let one: Vec<&str> = base.iter().copied().chain(["--threads", "1"]).collect();
    let two: Vec<&str> = base.iter().copied().chain(["--threads", "2"]).collect();
    let (c1, o1, _) = v2ref(&one);
    let (c2, o2, _) = v2ref(&two);
    assert_eq!((c1, c2), (0, 0));
    assert_eq!(o1, o2);
    let v: Value = serde_json::from_str(&o1).unwrap();
    for f in [
        "mean_v1_sq",
        "mean_v2_sq",
        "var_v1_sq",
        "var_v2_sq",
        "stderr_mean_v1_sq",
        "stderr_mean_v2_sq",
        "stderr_var_v1_sq",
        "stderr_var_v2_sq",
        "trials",
        "seed",
    ] {
        assert!(v[f].is_number(), "{f}");
    }
    // Normalized: a point source of V = 1 reads 1 within 5 standard errors.
    for e in ["v1_sq", "v2_sq"] {
        let m = v[format!("mean_{e}")].as_f64().unwrap();
        let se = v[format!("stderr_mean_{e}")].as_f64().unwrap();
        assert_within_sigmas!(m, 1.0, se, MC_SIGMAS, "{e}");
    }
}

#[test]
fn bad_input_exits_2_with_one_line_naming_the_flag() {
    let cases: &[(&[&str], &str)] = &[
        (&["snr", "--read-noise", "-1"], "--read-noise"),
        (&["snr", "--visibility", "2"], "--visibility"),
        (&["snr", "--photons", "-3"], "--photons"),
        (&["simulate", "--trials", "1"], "--trials"),
        (&["simulate", "--formula", "bogus"], "--formula"),
        (&["simulate", "--dx-um", "3"], "--dx-um"),
        (&["snr", "--photons", "nan"], "--photons"),
    ];
    for (args, flag) in cases {
        let (code, out, err) = v2ref(args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(out.is_empty(), "{args:?}");
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(flag), "{args:?}: {err}");
    }
}

#[test]
fn claims_of_the_appendix_are_all_computed() {
    let v: Value = serde_json::from_str(crate::claims::quick_claims_json()).unwrap();
    let arr = v.as_array().unwrap();
    let mine: Vec<&Value> = arr
        .iter()
        .filter(|c| {
            let id = c["id"].as_str().unwrap();
            id.starts_with("appendix.") || id.starts_with("snr.") || id.starts_with("sensitivity.")
        })
        .collect();
    assert!(mine.len() >= 16);
    for c in &mine {
        assert_ne!(c["status"], "pending", "{}", c["id"]);
    }
    // The errata's evidence reaches the JSON: the published formula's
    // value beside the exact one (the status itself is the deciding
    // function's, checked in tests/claims.rs).
    for c in mine.iter().filter(|c| c["status"] == "erratum") {
        let (p, e) = (c["published"].as_f64(), c["exact"].as_f64());
        assert!(p.is_some() && e.is_some() && p != e, "{}", c["id"]);
        assert_eq!(c["computed"].as_f64(), e, "{}", c["id"]);
    }
}
