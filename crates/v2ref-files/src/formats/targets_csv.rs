//! The target list of `plan --targets` / `plan_targets`, read at the edge:
//! `v2ref-core` parses its text ([`parse_targets`]).

use crate::{Error, Result};
use std::path::Path;
use v2ref_core::target_list::{parse_targets, RowFault, Target};

/// Largest target list read, bytes (100 000 targets of a few hundred bytes).
pub const MAX_TARGETS_CSV_BYTES: u64 = 64 << 20;

/// Reads the target list at `path` ([`parse_targets`]): a regular file
/// (a FIFO or device is refused without waiting on it, from the file as
/// opened), at most [`MAX_TARGETS_CSV_BYTES`] and within the memory
/// budget ([`super::memory_budget`]); read only.
pub fn read_targets(path: &Path) -> Result<Vec<std::result::Result<Target, RowFault>>> {
    let most = MAX_TARGETS_CSV_BYTES.min(super::memory_budget()?);
    let text = super::read_text(path, "targets", most, "a CSV target list within that")?;
    parse_targets(&text).map_err(|e| Error::data("targets", path, "", e.detail()))
}
