//! Image dynamic range from visibility accuracy (paper, Introduction, eq.
//! `eq:dynamique`, after Baldwin & Haniff 2002):
//!
//! `DR = √(N_vis / ((δV/V)² + δφ²))`.

use crate::error::{self, Error, Result};

/// Dynamic range of an image reconstructed from `n_vis` visibilities with
/// relative modulus error `dv_over_v` and phase error `dphi_rad` (rad).
/// Requires `n_vis ≥ 1` and errors ≥ 0, not both zero.
pub fn dynamic_range(n_vis: f64, dv_over_v: f64, dphi_rad: f64) -> Result<f64> {
    error::in_range("n_vis", n_vis, 1.0, f64::MAX)?;
    error::non_negative("dv_over_v", dv_over_v)?;
    error::non_negative("dphi_rad", dphi_rad)?;
    let e2 = dv_over_v * dv_over_v + dphi_rad * dphi_rad;
    if e2 == 0.0 {
        return Err(Error::Invalid {
            param: "dv_over_v",
            reason: "the visibility and phase errors cannot both be zero (infinite dynamic range)"
                .into(),
        });
    }
    // Errors so small that n_vis over their square overflows leave none.
    error::finite("dv_over_v", (n_vis / e2).sqrt())
}
