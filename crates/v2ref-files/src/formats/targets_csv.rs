//! The target list of `plan --targets` / `plan_targets`, read at the edge:
//! the library parses its text ([`parse_targets`]).

use crate::{Error, Result};
use std::io::Read;
use std::path::Path;
use v2ref_commands::commands::targets::{parse_targets, RowFault, Target};

/// Largest target list read, bytes (100 000 targets of a few hundred bytes).
pub const MAX_TARGETS_CSV_BYTES: u64 = 64 << 20;

/// Reads the target list at `path` ([`parse_targets`]): a regular file
/// (a FIFO or device is refused without waiting on it, from the file as
/// opened), at most [`MAX_TARGETS_CSV_BYTES`] and within the memory
/// budget ([`super::memory_budget`]); read only.
pub fn read_targets(path: &Path) -> Result<Vec<std::result::Result<Target, RowFault>>> {
    let io = |e| Error::file(Some("targets"), path, e);
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    std::os::unix::fs::OpenOptionsExt::custom_flags(&mut options, libc::O_NONBLOCK);
    let file = options.open(path).map_err(io)?;
    if !file.metadata().map_err(io)?.is_file() {
        return Err(Error::data(
            "targets",
            path,
            "",
            "not a regular file (a folder, FIFO, device or socket); give a CSV file",
        ));
    }
    let most = MAX_TARGETS_CSV_BYTES.min(super::memory_budget()?);
    let mut text = String::new();
    // One byte more than the limit tells a file at the limit from a longer one.
    file.take(most + 1).read_to_string(&mut text).map_err(io)?;
    if text.len() as u64 > most {
        return Err(Error::data(
            "targets",
            path,
            "",
            format!("larger than {most} bytes; accepted: a CSV target list within that"),
        ));
    }
    parse_targets(&text).map_err(|e| Error::data("targets", path, "", e.detail()))
}
