//! Who is writing an output, and what a process that died left behind.
//!
//! - An output is written under a lock: an `flock` on `.v2ref-lock-HASH`
//!   beside it (HASH names the target), a regular file of this user opened
//!   without following a link ([`super::own`]); a second writer of the
//!   same target, in another process or another thread, is refused with
//!   the process that holds it. The kernel releases the lock of a process
//!   that ends however it ends.
//! - A temporary (`.v2ref-tmp-PID-K-NAME`, a file, or a folder holding the
//!   marker [`FOLDER_MARKER`]) is held under an `flock` by
//!   its writer for as long as it lives: [`remove_stale_temporaries`]
//!   removes only the temporaries of this user whose lock it can take, so
//!   it never removes a live writer's, whatever host or container that
//!   writer runs in, and never decides by a process id.

use super::own::{self, Folder};
use crate::{Error, Result};
use std::fs::File;
use std::io::{self, Read, Seek, Write};
use std::path::Path;
#[cfg(test)]
use std::path::PathBuf;

/// The file a temporary folder holds from its start, held under its
/// writer's `flock`: a temporary folder is removed by a later run only
/// when it holds this file, of this user, with its lock free.
pub(crate) const FOLDER_MARKER: &str = ".v2ref-temporary";

/// The prefix of every temporary file v2ref makes beside an output.
pub(crate) const TEMP_PREFIX: &str = ".v2ref-tmp-";

/// The prefix of the lock file of an output.
pub(crate) const LOCK_PREFIX: &str = ".v2ref-lock-";

/// The longest file name (bytes) on the file systems v2ref writes to
/// (`NAME_MAX` of Linux, the BSDs and macOS).
pub(crate) const NAME_MAX: usize = 255;

/// The bytes of a file name as given (any bytes on Unix).
#[cfg(unix)]
pub(crate) fn name_bytes(name: &std::ffi::OsStr) -> Vec<u8> {
    use std::os::unix::ffi::OsStrExt as _;
    name.as_bytes().to_vec()
}

#[cfg(not(unix))]
pub(crate) fn name_bytes(name: &std::ffi::OsStr) -> Vec<u8> {
    name.to_string_lossy().into_owned().into_bytes()
}

/// A file name made of `bytes` (any bytes on Unix).
#[cfg(unix)]
pub(crate) fn name_from_bytes(bytes: Vec<u8>) -> std::ffi::OsString {
    use std::os::unix::ffi::OsStringExt as _;
    std::ffi::OsString::from_vec(bytes)
}

#[cfg(not(unix))]
pub(crate) fn name_from_bytes(bytes: Vec<u8>) -> std::ffi::OsString {
    String::from_utf8_lossy(&bytes).into_owned().into()
}

/// FNV-1a of `bytes`: a name for a target that does not lengthen it and is
/// the same in every build (the standard hasher's keys may change).
pub(crate) fn fnv1a(bytes: &[u8], h: u64) -> u64 {
    bytes
        .iter()
        .fold(h, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3))
}

/// FNV-1a's starting value.
pub(crate) const FNV_START: u64 = 0xcbf2_9ce4_8422_2325;

/// A held lock on an output; released (and its file removed) on drop.
pub(crate) struct OutputLock {
    folder: Folder,
    name: std::ffi::OsString,
    // Holds the flock; closed after the file is removed.
    _file: File,
}

/// Refuses a lock or temporary name that holds something v2ref does not
/// use (a link, a FIFO, a folder, another user's file), naming it.
pub(crate) fn not_own(param: &'static str, path: &Path, e: &io::Error) -> Error {
    Error::Invalid {
        param,
        reason: format!(
            "{}: not a file v2ref made: {e}; v2ref neither uses nor removes it: remove it or write elsewhere",
            path.display()
        ),
    }
}

impl OutputLock {
    /// Takes the lock of `target` (named `param` in errors), or refuses
    /// with the process that holds it.
    pub(crate) fn acquire(target: &Path, param: &'static str) -> Result<OutputLock> {
        let dir = super::target::parent_of(target);
        let folder = Folder::open(&dir).map_err(|e| Error::file(Some(param), &dir, e))?;
        let name = target.file_name().map(name_bytes).unwrap_or_default();
        let name =
            std::ffi::OsString::from(format!("{LOCK_PREFIX}{:016x}", fnv1a(&name, FNV_START)));
        let path = dir.join(&name);
        loop {
            let (mut file, made) = match own::open_lock(&path) {
                Ok(opened) => opened,
                // Gone between the exclusive create and the open: again.
                Err(e) if e.kind() == io::ErrorKind::NotFound => continue,
                Err(e) if own::is_not_own(&e) => return Err(not_own(param, &path, &e)),
                Err(e) => return Err(Error::file(Some(param), &path, e)),
            };
            if !own::try_lock(&file).map_err(|e| Error::file(Some(param), &path, e))? {
                let mut text = String::new();
                let _ = (&file).take(LOCK_BYTES).read_to_string(&mut text);
                return Err(held(param, target, text.trim()));
            }
            // The holder before us may have removed the file between our
            // open and our lock: hold the lock of the file at the path.
            if !own::is_at(&file, &path) {
                continue;
            }
            if !made && !holds_a_lock(&mut file) {
                let e = io::Error::other("it holds something other than a process id");
                return Err(not_own(param, &path, &e));
            }
            crate::cleanup::register(&path);
            file.set_len(0)
                .and_then(|()| file.rewind())
                .and_then(|()| writeln!(file, "{}", std::process::id()))
                .map_err(|e| Error::file(Some(param), &path, e))?;
            return Ok(OutputLock {
                folder,
                name,
                _file: file,
            });
        }
    }
}

/// The most a lock file holds, bytes: a process id (at most 10 decimal
/// digits, a `u32`) and a newline.
pub(crate) const LOCK_BYTES: u64 = 11;

/// Whether `file` holds what a lock of v2ref holds: nothing (its maker has
/// not written yet) or a process id in decimal and one newline. A file a
/// user keeps under the name is not a lock and is never emptied.
fn holds_a_lock(file: &mut File) -> bool {
    let mut bytes = Vec::new();
    if file.rewind().is_err() || file.take(LOCK_BYTES + 1).read_to_end(&mut bytes).is_err() {
        return false;
    }
    match bytes.split_last() {
        None => true,
        Some((b'\n', digits)) => {
            (1..=10).contains(&digits.len())
                && std::str::from_utf8(digits).is_ok_and(|t| t.parse::<u32>().is_ok())
        }
        Some(_) => false,
    }
}

impl Drop for OutputLock {
    fn drop(&mut self) {
        // Removed while still held: a waiting writer then finds a new file.
        let _ = self.folder.unlink(&self.name);
        crate::cleanup::unregister(&self.folder.path().join(&self.name));
    }
}

fn held(param: &'static str, target: &Path, holder: &str) -> Error {
    let who = match holder.parse::<u32>() {
        Ok(pid) if pid == std::process::id() => {
            format!("another call in this process (pid {pid})")
        }
        Ok(pid) => format!("another v2ref process (pid {pid})"),
        Err(_) => "another v2ref process".to_owned(),
    };
    Error::Invalid {
        param,
        reason: format!(
            "{}: {who} is writing it now; wait for it to finish or give another name",
            target.display()
        ),
    }
}

/// The name of the `k`-th temporary of this process for the file `name`:
/// `.v2ref-tmp-PID-K-` and as much of `name` as fits in [`NAME_MAX`] bytes
/// (a name of 255 bytes has a temporary of 255 bytes). The process id only
/// keeps the names of two processes apart; it decides nothing.
pub(crate) fn temp_name(name: &[u8], k: u32) -> std::ffi::OsString {
    let mut bytes = format!("{TEMP_PREFIX}{}-{k}-", std::process::id()).into_bytes();
    let room = NAME_MAX.saturating_sub(bytes.len());
    bytes.extend_from_slice(&name[..name.len().min(room)]);
    name_from_bytes(bytes)
}

/// Removes, in `dir`, the temporaries of writers that are gone (killed
/// before they could clean up: SIGKILL, a power cut): only names
/// `.v2ref-tmp-*`, only a regular file of this user (or a folder of this
/// user holding such a file as its marker) whose `flock` this call takes,
/// so never a live writer's. Returns how many; failures are ignored (the
/// run goes on with its own fresh names).
pub(crate) fn remove_stale_temporaries(dir: &Path) -> usize {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return 0;
    };
    let mut removed = 0;
    for entry in entries.flatten() {
        if !name_bytes(&entry.file_name()).starts_with(TEMP_PREFIX.as_bytes()) {
            continue;
        }
        let path = entry.path();
        let Ok(meta) = std::fs::symlink_metadata(&path) else {
            continue;
        };
        let gone = if meta.is_file() {
            remove_if_unlocked(&path, &path, |p| std::fs::remove_file(p))
        } else if meta.is_dir() && owned(&meta) {
            let marker = path.join(FOLDER_MARKER);
            remove_if_unlocked(&marker, &path, |p| std::fs::remove_dir_all(p))
        } else {
            false
        };
        removed += usize::from(gone);
    }
    removed
}

/// Removes `path` with `remove` when `lock_file` is a regular file of this
/// user whose lock is free (its writer is gone).
fn remove_if_unlocked(lock_file: &Path, path: &Path, remove: fn(&Path) -> io::Result<()>) -> bool {
    let Ok(file) = own::open_existing_own(lock_file) else {
        return false;
    };
    if !matches!(own::try_lock(&file), Ok(true)) || !own::is_at(&file, lock_file) {
        return false;
    }
    remove(path).is_ok()
}

#[cfg(unix)]
fn owned(meta: &std::fs::Metadata) -> bool {
    use std::os::unix::fs::MetadataExt as _;
    // SAFETY: `geteuid` takes no argument and cannot fail.
    meta.uid() == unsafe { libc::geteuid() }
}

#[cfg(not(unix))]
fn owned(_: &std::fs::Metadata) -> bool {
    true
}

/// Where the lock of `target` is (for the tests of this module).
#[cfg(test)]
fn lock_path(target: &Path) -> PathBuf {
    let name = target.file_name().map(name_bytes).unwrap_or_default();
    super::target::parent_of(target).join(format!("{LOCK_PREFIX}{:016x}", fnv1a(&name, FNV_START)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_temporary_name_never_exceeds_name_max() {
        let long = vec![b'a'; NAME_MAX];
        let t = name_bytes(&temp_name(&long, 7));
        assert_eq!(t.len(), NAME_MAX);
        let short = name_bytes(&temp_name(b"x.npy", 0));
        assert!(short.ends_with(b"-0-x.npy"), "{short:?}");
        assert!(lock_path(Path::new("a/x.npy")).starts_with("a"));
    }
}
