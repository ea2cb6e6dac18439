//! Claims of the general formalism and the introduction.

use super::{Computed, Find, Status};
use crate::formalism::dynamic_range::dynamic_range;
use crate::formalism::spectrum::{Band, Spectrum};

/// The claims this area computes.
pub(super) fn claims(_find: &Find<'_>) -> Vec<Computed> {
    let mut out = Vec::new();
    // Number of fringes in the coherence envelope, σ_eff/Δσ, for J, H, K
    // bands (centres and widths of the usual near-infrared filters).
    let bands = [("J", 1.25, 0.3), ("H", 1.65, 0.3), ("K", 2.2, 0.4)];
    let counts: Vec<(String, f64)> = bands
        .iter()
        .map(|&(name, l, w)| {
            let sp = Spectrum::flat(Band::new(l, w).expect("valid band"));
            (name.to_owned(), sp.sigma_eff_per_um() / sp.width_per_um())
        })
        .collect();
    let worst = counts.iter().map(|c| c.1).fold(0.0, f64::max);
    out.push(Computed::with_status(
        "formalism.fringe_count",
        Some(worst),
        if worst < 10.0 {
            Status::Qualitative
        } else {
            Status::Differs
        },
        format!(
            "sigma_eff / delta-sigma for flat bands: {} (all below 10)",
            counts
                .iter()
                .map(|(n, c)| format!("{n} {c:.2}"))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    ));
    // Dynamic range: the formula, evaluated at a 1e-5 visibility accuracy.
    let n_vis = 100.0;
    let dr = dynamic_range(n_vis, 1e-5, 0.0).expect("valid");
    out.push(Computed::with_status(
        "dynamic_range.formula",
        Some(dr),
        Status::Qualitative,
        format!("implemented as dynamic_range::dynamic_range; {n_vis} visibilities at dV/V = 1e-5 and no phase error give {dr:.3e}"),
    ));
    out
}
