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
    let mut bytes = Vec::new();
    // One byte more than the limit tells a file at the limit from a longer one.
    file.take(most + 1).read_to_end(&mut bytes).map_err(io)?;
    if bytes.len() as u64 > most {
        return Err(Error::data(
            "targets",
            path,
            "",
            format!("larger than {most} bytes; accepted: a CSV target list within that"),
        ));
    }
    // Text that is not UTF-8 is bad input (status 2), not a failed read.
    let text = String::from_utf8(bytes).map_err(|e| {
        let at = e.utf8_error().valid_up_to();
        let before = &e.as_bytes()[..at];
        // Line ends as the parser counts them: LF, CRLF, or CR alone.
        let ends = before
            .iter()
            .enumerate()
            .filter(|&(i, &b)| b == b'\n' || (b == b'\r' && before.get(i + 1) != Some(&b'\n')));
        let line = 1 + ends.count();
        Error::data(
            "targets",
            path,
            "",
            format!("line {line} (byte {at}) is not UTF-8 text; save the list as UTF-8"),
        )
    })?;
    parse_targets(&text).map_err(|e| Error::data("targets", path, "", e.detail()))
}
