//! Claims of the differential-piston study.

use super::{Computed, Effort, Find};
use crate::spectrum::{Band, Spectrum, CPAS_PER_M_PER_INV_UM};

/// The claims this area computes.
pub(super) fn claims(find: &Find<'_>, _effort: Effort) -> Vec<Computed> {
    let spec = |id: &str| find(id).expect("id in ledger");
    let sigma_eff = Spectrum::flat(Band::k()).sigma_eff_per_um();
    let s = 18.0 * sigma_eff * CPAS_PER_M_PER_INV_UM;
    vec![Computed::numeric(
        spec("piston.baseline_18m_cpas"),
        "piston.baseline_18m_cpas",
        s,
        format!("S = B sigma_eff = 18 m x {sigma_eff:.6} per um = {s:.3} cycles/arcsec (flat 2.0-2.4 um band)"),
    )]
}
