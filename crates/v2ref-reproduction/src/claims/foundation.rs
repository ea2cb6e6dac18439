//! Claims of the general formalism and the introduction.

use super::{Computed, Find};
use crate::formalism::dynamic_range::dynamic_range;
use crate::formalism::spectrum::{Band, Spectrum};
use crate::tolerance::IDENTITY_REL;

/// The paper's bound on the fringes of the coherence envelope in J, H
/// and K-like bands ("below 10").
const FEW_FRINGES: f64 = 10.0;

/// The usual near-infrared filters: name, centre and width (µm).
const NIR_BANDS: [(&str, f64, f64); 3] = [("J", 1.25, 0.3), ("H", 1.65, 0.3), ("K", 2.2, 0.4)];

/// The claims this area computes.
pub(super) fn claims(_find: &Find<'_>) -> Vec<Computed> {
    vec![fringe_count_claim(), dynamic_range_claim()]
}

/// `formalism.fringe_count`: σ_eff/Δσ of flat J, H, K bands, all below
/// [`FEW_FRINGES`].
fn fringe_count_claim() -> Computed {
    let counts: Vec<(&str, f64)> = NIR_BANDS
        .iter()
        .map(|&(name, l, w)| {
            let sp = Spectrum::flat(Band::new(l, w).expect("valid band"));
            (name, sp.sigma_eff_per_um() / sp.width_per_um())
        })
        .collect();
    let worst = counts.iter().map(|c| c.1).fold(0.0, f64::max);
    let holds = worst < FEW_FRINGES;
    Computed::statement(
        "formalism.fringe_count",
        Some(worst),
        holds,
        format!(
            "sigma_eff / delta-sigma for flat bands: {}; the largest is {} {FEW_FRINGES}",
            counts
                .iter()
                .map(|(n, c)| format!("{n} {c:.2}"))
                .collect::<Vec<_>>()
                .join(", "),
            if holds { "below" } else { "not below" }
        ),
    )
}

/// The scalings the dynamic-range laws are checked with: the number of
/// visibilities times 4 (the range times √4 = 2), the error times 2 (the
/// range over 2), and a modulus and a phase error of 3 and 4 times dv
/// (5 dv in quadrature: the range over 5).
const MORE_VISIBILITIES: f64 = 4.0;
const LARGER_ERROR: f64 = 2.0;
const QUADRATURE_PAIR: (f64, f64) = (3.0, 4.0);

/// `dynamic_range.formula`: the formula sqrt(N_vis / ((dV/V)² + dφ²))
/// holds its three laws (√N_vis, 1/error, errors in quadrature),
/// evaluated at 100 visibilities and a 1e-5 visibility accuracy.
fn dynamic_range_claim() -> Computed {
    let (n_vis, dv, dphi) = (100.0, 1e-5, 0.0);
    let (q1, q2) = QUADRATURE_PAIR;
    // What the laws say: the range grows by √4 and shrinks by the error's
    // factor, 2, and by the quadrature sum, 5.
    let (growth, shrink_error, shrink_quadrature) =
        (MORE_VISIBILITIES.sqrt(), LARGER_ERROR, q1.hypot(q2));
    let laws = || -> crate::Result<(f64, [f64; 3])> {
        let dr = dynamic_range(n_vis, dv, dphi)?;
        Ok((
            dr,
            [
                dynamic_range(MORE_VISIBILITIES * n_vis, dv, dphi)? / dr / growth,
                dynamic_range(n_vis, LARGER_ERROR * dv, dphi)? / dr * shrink_error,
                dynamic_range(n_vis, q1 * dv, q2 * dv)? / dr * shrink_quadrature,
            ],
        ))
    };
    match laws() {
        Ok((dr, ratios)) => {
            let holds = ratios.iter().all(|r| (r - 1.0).abs() <= IDENTITY_REL);
            Computed::statement(
                "dynamic_range.formula",
                Some(dr),
                holds,
                format!(
                    "dynamic_range::dynamic_range: {n_vis} visibilities at dV/V = {dv:e} and dphi = {dphi} give {dr:.3e}; {MORE_VISIBILITIES}x the visibilities, {LARGER_ERROR}x the error and errors ({q1}, {q2}) x dv in quadrature scale it by the law's {}, 1/{} and 1/{} to {:.1e}, {:.1e}, {:.1e} (relative)",
                    growth,
                    shrink_error,
                    shrink_quadrature,
                    ratios[0] - 1.0,
                    ratios[1] - 1.0,
                    ratios[2] - 1.0
                ),
            )
        }
        Err(e) => Computed::failed("dynamic_range.formula", &e),
    }
}
