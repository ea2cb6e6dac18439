//! The claims ledger: every status is the deciding function's verdict on
//! the computed numbers, and moves when they are perturbed; the README's
//! counts are the ledger's; the foundation's claims hold. (That the project's ledger lists the same
//! claims as the steering ledger is checked by `.ci/run`, where that ledger
//! is available.)

use v2ref_core::tolerance::ROUNDING_REL;
use v2ref_core::{assert_abs_eq, assert_rel_eq};
use v2ref_reproduction::cases::Effort;
use v2ref_reproduction::claims::{
    compute, decide, ledger, summary, ClaimResult, ClaimSpec, Computed, Finding, Status,
};

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

/// What the library's providers compute at the quick effort (the numbers
/// the statuses are decided from), computed once for the tests below.
fn quick_findings() -> &'static [Computed] {
    static FINDINGS: std::sync::OnceLock<Vec<Computed>> = std::sync::OnceLock::new();
    FINDINGS.get_or_init(|| compute(Effort::Quick))
}

/// Each claim of the ledger with what was computed for it.
fn records() -> Vec<(ClaimSpec, &'static Computed)> {
    ledger()
        .into_iter()
        .map(|spec| {
            let c = quick_findings()
                .iter()
                .find(|c| c.id == spec.id)
                .unwrap_or_else(|| panic!("{} is not computed", spec.id));
            (spec, c)
        })
        .collect()
}

/// The size of the error planted in a computed value.
const PLANTED_ERROR_REL: f64 = 0.01;

#[test]
fn every_status_is_the_verdict_of_its_numbers() {
    let results = quick_claims();
    assert_eq!(results.len(), ledger().len());
    for ((spec, computed), r) in records().iter().zip(results) {
        assert_eq!(spec.id, r.id);
        assert!(!r.note.is_empty(), "{}: no note", r.id);
        // The CLI's status is the deciding function's, and no claim fails
        // or is left pending.
        assert_eq!(r.status, decide(spec, &computed.finding), "{}", r.id);
        assert!(
            !matches!(r.status, Status::Failed | Status::Pending),
            "{}: {} ({})",
            r.id,
            r.status.as_str(),
            r.note
        );
        match r.status {
            Status::Reproduced => {
                if let (Some(p), Some(t), Some(c)) = (spec.paper, spec.tol, r.computed) {
                    assert!((c - p).abs() <= t, "{}: {c} vs {p} ± {t}", r.id);
                }
            }
            Status::Differs => assert!(r.computed.is_some() || r.paper.is_some(), "{}", r.id),
            Status::Erratum => {
                let (p, e) = (r.published.unwrap(), r.exact.unwrap());
                assert!(p != e && r.computed == Some(e), "{}: {p} vs {e}", r.id);
            }
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

/// The status of `spec` when its finding is `f`.
fn verdict(spec: &ClaimSpec, f: Finding) -> Status {
    decide(spec, &f)
}

/// Every claim's status moves when its numbers are perturbed: a planted
/// error in a reproduced or checked value, an exact value made equal to
/// the printed one, a published formula made exact, a threshold interval
/// moved, a predicate reversed. Run on the real computed records.
#[test]
#[ignore = "slow tier: every claim re-evaluated with its numbers perturbed (11 s)"]
fn every_status_changes_when_its_numbers_are_perturbed() {
    for (spec, computed) in records() {
        let id = &spec.id;
        let status = decide(&spec, &computed.finding);
        match computed.finding.clone() {
            Finding::Number {
                exact,
                published,
                checks,
            } => {
                let with = |exact: f64, published: Option<f64>| Finding::Number {
                    exact,
                    published,
                    checks: checks.clone(),
                };
                // A planted error: 1 %, or past the printed rounding where
                // that is coarser.
                let planted = |paper: f64, tol: f64| {
                    let error = (PLANTED_ERROR_REL * exact.abs()).max(2.0 * tol);
                    if exact >= paper {
                        exact + error
                    } else {
                        exact - error
                    }
                };
                match (status, spec.paper.zip(spec.tol)) {
                    (Status::Reproduced, Some((p, t))) => {
                        let moved = verdict(&spec, with(planted(p, t), published));
                        assert_ne!(moved, Status::Reproduced, "{id}: planted error");
                    }
                    (Status::Differs | Status::Erratum, Some((p, _))) if checks.is_empty() => {
                        let moved = verdict(&spec, with(p, published));
                        assert_eq!(moved, Status::Reproduced, "{id}: exact = printed");
                    }
                    (Status::Differs | Status::Erratum, Some((p, _))) => {
                        // The printed value is not what the checks confirm.
                        let moved = verdict(&spec, with(p, published));
                        assert_eq!(moved, Status::Failed, "{id}: exact = printed");
                    }
                    (Status::Qualitative, None) => {
                        // A value without a printed number is checked by a
                        // second route that a 1 % error breaks.
                        assert!(!checks.is_empty(), "{id}: an unchecked number");
                        let moved = verdict(&spec, with(exact * (1.0 + PLANTED_ERROR_REL), None));
                        assert_eq!(moved, Status::Failed, "{id}: planted error");
                    }
                    (Status::Erratum, None) => {
                        let moved = verdict(&spec, with(exact, Some(exact)));
                        assert_eq!(moved, Status::Qualitative, "{id}: published = exact");
                    }
                    other => panic!("{id}: no perturbation for {other:?}"),
                }
                if status == Status::Erratum {
                    // A published formula equal to the exact value is no
                    // erratum.
                    let moved = verdict(&spec, with(exact, Some(exact)));
                    assert_ne!(moved, Status::Erratum, "{id}: published = exact");
                }
            }
            Finding::Interval { value, lo, hi, .. } => {
                let p = spec.paper.expect("a located threshold has a printed value");
                let moved = if status == Status::Reproduced {
                    // The interval moved by a planted error past the printed value.
                    let shift = (p - lo).max(hi - p) * (1.0 + PLANTED_ERROR_REL);
                    Finding::Interval {
                        value: value + shift,
                        lo: lo + shift,
                        hi: hi + shift,
                        resolved: true,
                    }
                } else {
                    Finding::Interval {
                        value: p,
                        lo: p * (1.0 - PLANTED_ERROR_REL),
                        hi: p * (1.0 + PLANTED_ERROR_REL),
                        resolved: true,
                    }
                };
                assert_ne!(verdict(&spec, moved), status, "{id}: interval moved");
            }
            Finding::Statement { value, holds } => {
                let moved = Finding::Statement {
                    value,
                    holds: !holds,
                };
                assert_ne!(verdict(&spec, moved), status, "{id}: predicate reversed");
            }
            Finding::Unavailable => {
                assert_eq!(status, Status::Unavailable, "{id}");
                assert_eq!(verdict(&spec, Finding::Failed), Status::Failed);
            }
            Finding::Failed => panic!("{id} failed: {}", computed.note),
            other => panic!("{id}: no perturbation for {other:?}"),
        }
    }
}

/// README.md states the counts of the committed reproduction (which CI
/// compares with a fresh `reproduce`), and the quick effort decides every
/// claim as the full one did.
#[test]
fn the_readme_states_the_ledger_counts() {
    let committed: Vec<ClaimResult> =
        serde_json::from_str(include_str!("../paper/reproduction/claims.json"))
            .expect("the committed claims' JSON");
    let readme = include_str!("../README.md")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    let sentence = summary(&committed);
    assert!(
        readme.contains(&sentence),
        "README.md does not state the ledger's counts: {sentence}"
    );
    for (full, quick) in committed.iter().zip(quick_claims()) {
        assert_eq!((&full.id, full.status), (&quick.id, quick.status));
    }
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
    use v2ref_core::formalism::dynamic_range::dynamic_range;
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
