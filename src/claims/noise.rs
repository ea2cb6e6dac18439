//! Claims computed by the `noise` work (placeholder until its issue lands).

use super::{Computed, Effort, Find};

/// The claims this area computes.
pub(super) fn claims(_find: &Find<'_>, _effort: Effort) -> Vec<Computed> {
    Vec::new()
}
