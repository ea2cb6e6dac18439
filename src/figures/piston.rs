//! Figures of the piston work (placeholder until its issue lands).

use crate::claims::Effort;
use crate::error::Result;
use crate::figure::Figure;

/// The figures this area computes.
pub(super) fn figures(_effort: Effort) -> Result<Vec<Figure>> {
    Ok(Vec::new())
}
