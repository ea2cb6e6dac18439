//! The one way v2ref opens a file it reads (a set's member, an estimates
//! file, a sidecar, a spectrum table, a target list, a calibrator, an
//! OIFITS file), from the command line, Python and Rust alike: read-only,
//! without waiting (`O_NONBLOCK`: a FIFO someone left in a shared folder
//! is seen at once, not waited on for ever), and refused unless a regular
//! file (a FIFO, a device, a socket or a folder), looked at on the file as
//! opened. Text files are read within a bound, refused beyond it.

use crate::{Error, Result};
use std::fs::File;
use std::io::Read;
use std::path::Path;

/// Largest sidecar read, bytes (v2ref writes a few kB), from the command
/// line and Python alike.
pub const MAX_SIDECAR_BYTES: u64 = 16 << 20;

/// Opens the input file `path` (named by `param` in errors): read-only,
/// without waiting, refused unless a regular file. A reader never writes,
/// renames or removes anything.
pub fn open(path: &Path, param: &'static str) -> Result<File> {
    open_input(path, param, false)
}

/// As [`open`], and never through a symbolic link: for a name v2ref found
/// in a folder or in a file rather than one the user gave.
pub fn open_found(path: &Path, param: &'static str) -> Result<File> {
    open_input(path, param, true)
}

fn open_input(path: &Path, param: &'static str, found: bool) -> Result<File> {
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        let no_follow = if found { libc::O_NOFOLLOW } else { 0 };
        std::os::unix::fs::OpenOptionsExt::custom_flags(
            &mut options,
            libc::O_NONBLOCK | libc::O_CLOEXEC | no_follow,
        );
    }
    let file = match options.open(path) {
        Ok(file) => file,
        #[cfg(unix)]
        Err(e) if found && e.raw_os_error() == Some(libc::ELOOP) => return Err(Error::data(
            param,
            path,
            "",
            "a symbolic link, not followed (its name was found, not given); give the file itself",
        )),
        Err(e) => return Err(Error::file(Some(param), path, e)),
    };
    let kind = file
        .metadata()
        .map_err(|e| Error::file(Some(param), path, e))?
        .file_type();
    if kind.is_file() {
        return Ok(file);
    }
    let what = if kind.is_dir() {
        "a folder"
    } else if is_fifo(&kind) {
        "a FIFO (named pipe)"
    } else {
        "a device or socket"
    };
    Err(Error::data(
        param,
        path,
        "",
        format!("{what}, not a regular file; give a regular file"),
    ))
}

#[cfg(unix)]
fn is_fifo(kind: &std::fs::FileType) -> bool {
    std::os::unix::fs::FileTypeExt::is_fifo(kind)
}

#[cfg(not(unix))]
fn is_fifo(_: &std::fs::FileType) -> bool {
    false
}

/// The UTF-8 text of the input file `path` ([`open`]), refused when
/// longer than `max_bytes`, naming the bound and `accepted` (what the
/// file must be).
pub fn read_text(
    path: &Path,
    param: &'static str,
    max_bytes: u64,
    accepted: &str,
) -> Result<String> {
    let bytes = read_bounded(open(path, param)?, path, param, max_bytes, accepted)?;
    utf8_text(bytes, path, param)
}

/// As [`read_text`], for a file whose name v2ref found in a folder
/// ([`open_found`]: never through a link).
pub fn read_found_text(
    path: &Path,
    param: &'static str,
    max_bytes: u64,
    accepted: &str,
) -> Result<String> {
    let bytes = read_bounded(open_found(path, param)?, path, param, max_bytes, accepted)?;
    utf8_text(bytes, path, param)
}

/// The bytes of a file whose name v2ref found in a folder ([`open_found`]),
/// refused when longer than `max_bytes`, naming the bound and `accepted`.
pub fn read_found_bytes(
    path: &Path,
    param: &'static str,
    max_bytes: u64,
    accepted: &str,
) -> Result<Vec<u8>> {
    read_bounded(open_found(path, param)?, path, param, max_bytes, accepted)
}

fn read_bounded(
    file: File,
    path: &Path,
    param: &'static str,
    max_bytes: u64,
    accepted: &str,
) -> Result<Vec<u8>> {
    let mut bytes = Vec::new();
    // One byte more than the bound tells a file at the bound from a longer
    // one (or an endless one).
    file.take(max_bytes.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(|e| Error::file(Some(param), path, e))?;
    if bytes.len() as u64 > max_bytes {
        return Err(Error::data(
            param,
            path,
            "",
            format!("larger than {max_bytes} bytes; accepted: {accepted}"),
        ));
    }
    Ok(bytes)
}

/// Text that is not UTF-8 is bad input (status 2), not a failed read.
fn utf8_text(bytes: Vec<u8>, path: &Path, param: &'static str) -> Result<String> {
    String::from_utf8(bytes).map_err(|e| {
        let at = e.utf8_error().valid_up_to();
        let line = line_of_byte(&e.as_bytes()[..at]);
        Error::data(
            param,
            path,
            "",
            format!("line {line} (byte {at}) is not UTF-8 text; save the file as UTF-8"),
        )
    })
}

/// The line (from 1) that follows `before`, its line ends counted as the
/// text parsers count them: LF, CRLF, or CR alone.
fn line_of_byte(before: &[u8]) -> usize {
    let ends = before
        .iter()
        .enumerate()
        .filter(|&(i, &b)| b == b'\n' || (b == b'\r' && before.get(i + 1) != Some(&b'\n')));
    1 + ends.count()
}

/// The text of the sidecar `path`, at most [`MAX_SIDECAR_BYTES`].
pub fn read_sidecar_text(path: &Path) -> Result<String> {
    read_text(
        path,
        "sidecar",
        MAX_SIDECAR_BYTES,
        "the sidecar written by v2ref synth",
    )
}
