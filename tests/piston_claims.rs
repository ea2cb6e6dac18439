//! Every `piston.*` claim is computed (no `pending`), by the code path the
//! user runs, at the quick effort; errata carry both values.

use v2ref_core::tolerance::{ROUNDING_REL, VISIBILITY_SCALING_REL};
use v2ref_core::{assert_abs_eq, assert_rel_eq};
use v2ref_reproduction::claims::Status;

#[test]
fn every_piston_claim_is_answered() {
    let all = crate::claims::quick_claims();
    let piston: Vec<_> = all.iter().filter(|c| c.id.starts_with("piston.")).collect();
    assert!(piston.len() >= 18, "{} piston claims", piston.len());
    for c in &piston {
        assert_ne!(c.status, Status::Pending, "{} is pending: {}", c.id, c.note);
        assert!(!c.note.is_empty(), "{} has no evidence", c.id);
        if c.status == Status::Erratum {
            assert!(c.published.is_some() && c.exact.is_some(), "{}", c.id);
        }
        if let Some(v) = c.computed {
            assert!(v.is_finite(), "{}", c.id);
        }
    }
    let get = |id: &str| piston.iter().find(|c| c.id == id).unwrap();
    // The closed forms: r0 = lambda / seeing (2.2 um over 1 arcsec, in
    // cm), tau0 = r0 / v (10 m/s, in ms).
    let r0_cm = 100.0 * 2.2e-6 / (1.0f64 / 3600.0).to_radians();
    assert_rel_eq!(get("piston.r0_k_cm").computed.unwrap(), r0_cm, ROUNDING_REL);
    let tau_ms = get("piston.coherence_time_ms").computed.unwrap();
    assert_rel_eq!(tau_ms, r0_cm / 100.0 / 10.0 * 1e3, ROUNDING_REL);
    // The swapped OPD-per-coherence-time pair: each exact value is the
    // other's published reading (up to the printed tau's rounding).
    let o300 = get("piston.opd_per_tau_300hz_um");
    let o1000 = get("piston.opd_per_tau_1000hz_um");
    assert_rel_eq!(
        o300.exact.unwrap(),
        300.0 * 2.2 * tau_ms * 1e-3,
        ROUNDING_REL
    );
    assert_rel_eq!(
        o300.published.unwrap(),
        1000.0 * 2.2 * 45.0 * 1e-3,
        ROUNDING_REL
    );
    assert_rel_eq!(
        o1000.published.unwrap(),
        300.0 * 2.2 * 45.0 * 1e-3,
        ROUNDING_REL
    );
    // Grey visibility: bias ratio 0.5 to rounding.
    let m = get("piston.multiplicative");
    assert_abs_eq!(m.computed.unwrap(), 0.5, VISIBILITY_SCALING_REL);
}
