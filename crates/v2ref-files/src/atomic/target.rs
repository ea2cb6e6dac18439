//! What an output path may be, checked before anything is computed and
//! again before a finished file takes the target's place: v2ref writes a
//! new regular file, or replaces a regular file only when asked
//! (`--force`); it never writes through a symbolic link and never replaces
//! a folder, a device, a FIFO or a socket.

use crate::{Error, Result};
use std::fs::FileType;
use std::io;
use std::path::{Path, PathBuf};

/// The folder `path` would be written in (`.` for a bare name).
pub(crate) fn parent_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// What kind of entry `t` is, in words, when it is not a regular file.
fn special(t: &FileType) -> Option<&'static str> {
    if t.is_symlink() {
        Some("a symbolic link (v2ref does not write through links; give the file it points to, or a new name)")
    } else if t.is_dir() {
        Some("a folder; give a file name")
    } else if t.is_file() {
        None
    } else {
        Some(other_kind(t))
    }
}

#[cfg(unix)]
fn other_kind(t: &FileType) -> &'static str {
    use std::os::unix::fs::FileTypeExt as _;
    if t.is_block_device() || t.is_char_device() {
        "a device; give a regular file name"
    } else if t.is_fifo() {
        "a FIFO (named pipe); give a regular file name"
    } else if t.is_socket() {
        "a socket; give a regular file name"
    } else {
        "not a regular file; give a regular file name"
    }
}

#[cfg(not(unix))]
fn other_kind(_: &FileType) -> &'static str {
    "not a regular file; give a regular file name"
}

fn refuse(param: Option<&'static str>, path: &Path, reason: String) -> Error {
    Error::Invalid {
        param: param.unwrap_or("out"),
        reason: format!("{}: {reason}", path.display()),
    }
}

/// Checks that the parent folder of `path` exists and is a folder (bad
/// input otherwise, stated as such).
pub fn check_parent(path: &Path, param: Option<&'static str>) -> Result<()> {
    let dir = parent_of(path);
    match std::fs::metadata(&dir) {
        Ok(m) if m.is_dir() => Ok(()),
        Ok(_) => Err(refuse(
            param,
            path,
            format!(
                "{} is not a folder; give a path in an existing folder",
                dir.display()
            ),
        )),
        Err(e) if e.kind() == io::ErrorKind::NotFound => Err(refuse(
            param,
            path,
            format!(
                "the folder {} does not exist; create it first",
                dir.display()
            ),
        )),
        Err(e) => Err(Error::file(param, &dir, e)),
    }
}

/// Refuses a target that is not a regular file or absent (a link, a
/// folder, a device, a FIFO, a socket): these are never replaced.
pub(crate) fn check_replaceable(path: &Path, param: Option<&'static str>) -> Result<()> {
    match std::fs::symlink_metadata(path) {
        Ok(m) => match special(&m.file_type()) {
            Some(what) => Err(refuse(param, path, format!("is {what}"))),
            None => Ok(()),
        },
        Err(e) if e.kind() == io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(Error::file(param, path, e)),
    }
}

/// Checks an output file before any work: its parent folder exists, the
/// path is not a link or a special file, and an existing regular file is
/// replaced only with `force`.
pub fn check_output_file(path: &Path, param: &'static str, force: bool) -> Result<()> {
    check_file_name(path, param)?;
    check_parent(path, Some(param))?;
    check_replaceable(path, Some(param))?;
    if !force && std::fs::symlink_metadata(path).is_ok() {
        return Err(refuse(
            Some(param),
            path,
            "exists and would be replaced; give a new name or --force".into(),
        ));
    }
    Ok(())
}

/// Refuses an output path that names a folder rather than a file: one
/// that ends with a separator or `.`/`..` (`--out DIR/` would otherwise
/// write `DIR.npy` beside the folder).
pub fn check_file_name(path: &Path, param: &'static str) -> Result<()> {
    let text = path.as_os_str().to_string_lossy();
    let ends_as_folder = text.ends_with(std::path::is_separator)
        || path.file_name().is_none()
        || text.ends_with("/.");
    if ends_as_folder {
        return Err(refuse(
            Some(param),
            path,
            "names a folder (it ends with a slash, `.` or `..`); give a file name in it".into(),
        ));
    }
    Ok(())
}
