//! The registry of the paper's figures: each area provides the figures it
//! computes; `golden/` and `v2ref reproduce` take them from here.

use crate::cases::Effort;
use crate::error::Result;
use crate::table::Figure;

pub(crate) mod bias;
pub(crate) mod piston;

pub use bias::fig3;
pub use piston::fig5_runs;

/// Every figure (0 to 5), in order, at the given effort.
pub fn all(effort: Effort) -> Result<Vec<Figure>> {
    // Side by side: the figures are independent and each deterministic.
    let (bias, piston) = rayon::join(|| bias::figures(effort), || piston::figures(effort));
    let mut out = bias?;
    out.extend(piston?);
    out.sort_by(|a, b| a.id.cmp(&b.id));
    Ok(out)
}
