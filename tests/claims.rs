//! The claims ledger: every claim is answered honestly, and the
//! foundation's claims hold. (That the project's ledger lists the same
//! claims as the steering ledger is checked by `.ci/run`, where that ledger
//! is available.)

use v2ref::reproduction::claims::{ledger, ClaimResult, Status};
use v2ref::tolerance::ROUNDING_REL;
use v2ref::{assert_abs_eq, assert_rel_eq};

/// `v2ref claims --quick --json`, the code path a user runs (the CLI calls
/// `evaluate(Effort::Quick)`), run once for every test of the suite that
/// reads the claims: 10 s of Monte Carlo each time.
pub(crate) fn quick_claims_json() -> &'static str {
    static ANSWER: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    ANSWER.get_or_init(|| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_v2ref"))
            .args(["claims", "--quick", "--json"])
            .output()
            .expect("the binary runs");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8(out.stdout).expect("UTF-8")
    })
}

/// The claims of [`quick_claims_json`], read back.
pub(crate) fn quick_claims() -> &'static [ClaimResult] {
    static CLAIMS: std::sync::OnceLock<Vec<ClaimResult>> = std::sync::OnceLock::new();
    CLAIMS.get_or_init(|| serde_json::from_str(quick_claims_json()).expect("the claims' JSON"))
}

#[test]
fn every_claim_is_answered_honestly() {
    let results = quick_claims();
    assert_eq!(results.len(), ledger().len());
    for r in results {
        assert!(!r.note.is_empty(), "{}: no note", r.id);
        match r.status {
            Status::Reproduced => {
                // Reproduced means computed and within the paper's rounding.
                let spec = ledger().into_iter().find(|s| s.id == r.id).unwrap();
                let (p, t, c) = (spec.paper.unwrap(), spec.tol.unwrap(), r.computed.unwrap());
                assert!((c - p).abs() <= t, "{}: {c} vs {p} ± {t}", r.id);
            }
            Status::Differs => assert!(r.computed.is_some(), "{}: differs without a value", r.id),
            Status::Erratum => assert!(
                r.published.is_some() || r.exact.is_some() || r.computed.is_some(),
                "{}",
                r.id
            ),
            _ => {}
        }
    }
    // The whole table, compactly, for review: any drift shows in the diff.
    let sig = |v: Option<f64>| v.map_or_else(|| "-".to_owned(), |x| format!("{x:.4e}"));
    let table: String = results
        .iter()
        .map(|r| {
            format!(
                "{:<36} {:<11} paper {:<11} computed {}\n",
                r.id,
                r.status.as_str(),
                sig(r.paper),
                sig(r.computed)
            )
        })
        .collect();
    insta::assert_snapshot!("claims_table_quick", table);
}

#[test]
fn foundation_claims_are_computed() {
    let results = quick_claims();
    let get = |id: &str| results.iter().find(|r| r.id == id).unwrap();
    for id in [
        "formalism.fringe_count",
        "integration.sinc_min_nyquist",
        "integration.norm_factor_4spf",
        "resolution.fts_100um_2um",
        "line.width_in_elements",
        "bandwidth.v1_max_diff_400nm",
        "bandwidth.v2_max_diff_400nm",
        "dispersion.v1_invariant",
        "dispersion.v2_point_1rad",
        "dispersion.v2_point_1p5rad",
        "dispersion.v2_point_2rad",
        "piston.baseline_18m_cpas",
        "dynamic_range.formula",
    ] {
        assert_ne!(get(id).status, Status::Pending, "{id}");
        assert!(get(id).computed.is_some(), "{id}");
    }
    // V2 of a point source falls as the dispersion grows.
    let v = |id| get(id).computed.unwrap();
    assert!(1.0 > v("dispersion.v2_point_1rad"));
    assert!(v("dispersion.v2_point_1rad") > v("dispersion.v2_point_1p5rad"));
    assert!(v("dispersion.v2_point_1p5rad") > v("dispersion.v2_point_2rad"));
}

#[test]
fn dynamic_range_formula_holds_its_scaling_laws() {
    use v2ref::formalism::dynamic_range::dynamic_range;
    let a = dynamic_range(100.0, 1e-3, 0.0).unwrap();
    assert_abs_eq!(
        dynamic_range(400.0, 1e-3, 0.0).unwrap() / a,
        2.0,
        ROUNDING_REL
    );
    assert_abs_eq!(
        dynamic_range(100.0, 2e-3, 0.0).unwrap() / a,
        0.5,
        ROUNDING_REL
    );
    // Modulus and phase errors add in quadrature.
    let b = dynamic_range(100.0, 3e-3, 4e-3).unwrap();
    assert_rel_eq!(b, (100.0f64 / 25e-6).sqrt(), ROUNDING_REL);
    assert!(dynamic_range(0.5, 1e-3, 0.0).is_err());
    assert!(dynamic_range(10.0, 0.0, 0.0).is_err());
}

#[test]
fn reproduction_notes_cover_every_claim() {
    let notes = include_str!("../paper/reproduction.md");
    let generated = include_str!("../paper/reproduction/claims.md");
    for spec in ledger() {
        let tag = format!("`{}`", spec.id);
        assert!(
            notes.contains(&tag),
            "paper/reproduction.md does not mention {}",
            spec.id
        );
        assert!(
            generated.contains(&tag),
            "paper/reproduction/claims.md lacks {}",
            spec.id
        );
    }
}
