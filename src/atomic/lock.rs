//! Who is writing an output, and what a process that died left behind.
//!
//! - An output file is written under a lock (an `flock` on a file
//!   `.v2ref-lock-HASH` beside it, HASH naming the target): a second writer
//!   of the same target, in another process or another thread, is refused
//!   with the process that holds it. The kernel releases the lock of a
//!   process that ends however it ends, so a lock is never stale.
//! - Temporaries carry the process id in their name
//!   (`.v2ref-tmp-PID-K-NAME`); [`remove_stale_temporaries`] removes those
//!   of processes that no longer run.

use crate::{Error, Result};
use std::fs::File;
use std::io::{Read, Seek, Write};
use std::path::{Path, PathBuf};

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
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// A held lock on an output; released (and its file removed) on drop.
pub(crate) struct OutputLock {
    path: PathBuf,
    // Holds the flock; closed after the file is removed.
    _file: File,
}

/// The 16 hexadecimal digits that name `target`'s lock file and its
/// commit record (`src/atomic/journal.rs`) in its folder.
pub(crate) fn name_hash(target: &Path) -> String {
    let name = target.file_name().map(name_bytes).unwrap_or_default();
    format!("{:016x}", fnv1a(&name))
}

/// The lock file of `target` (in the folder `target` is written in).
fn lock_path(target: &Path) -> PathBuf {
    super::target::parent_of(target).join(format!("{LOCK_PREFIX}{}", name_hash(target)))
}

impl OutputLock {
    /// Takes the lock of `target` (named `param` in errors), or refuses
    /// with the process that holds it.
    pub(crate) fn acquire(target: &Path, param: &'static str) -> Result<OutputLock> {
        OutputLock::acquire_at(lock_path(target), target, param)
    }

    /// Takes the lock file `path` of the output `target` (`target` only
    /// names it in errors).
    pub(crate) fn acquire_at(
        path: PathBuf,
        target: &Path,
        param: &'static str,
    ) -> Result<OutputLock> {
        let io = |e| Error::file(Some(param), target, e);
        loop {
            let mut file = std::fs::OpenOptions::new()
                .read(true)
                .write(true)
                .create(true)
                .truncate(false)
                .open(&path)
                .map_err(io)?;
            if !try_lock(&file).map_err(io)? {
                let mut text = String::new();
                let _ = file.read_to_string(&mut text);
                return Err(held(param, target, text.trim()));
            }
            // The holder before us may have removed the file between our
            // open and our lock: hold the lock of the file at the path.
            if !same_file(&file, &path) {
                continue;
            }
            crate::cleanup::register(&path);
            file.set_len(0)
                .and_then(|()| file.rewind())
                .and_then(|()| writeln!(file, "{}", std::process::id()))
                .map_err(io)?;
            return Ok(OutputLock { path, _file: file });
        }
    }
}

impl Drop for OutputLock {
    fn drop(&mut self) {
        // Removed while still held: a waiting writer then finds a new file.
        let _ = std::fs::remove_file(&self.path);
        crate::cleanup::unregister(&self.path);
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

/// Takes an exclusive `flock` on `file` without waiting; false when
/// another open file holds it.
#[cfg(unix)]
fn try_lock(file: &File) -> std::io::Result<bool> {
    use std::os::unix::io::AsRawFd as _;
    // SAFETY: `flock` only reads its arguments; the descriptor is open for
    // the whole call (borrowed from `file`).
    let r = unsafe { libc::flock(file.as_raw_fd(), libc::LOCK_EX | libc::LOCK_NB) };
    if r == 0 {
        return Ok(true);
    }
    let e = std::io::Error::last_os_error();
    if e.raw_os_error() == Some(libc::EWOULDBLOCK) {
        Ok(false)
    } else {
        Err(e)
    }
}

#[cfg(not(unix))]
fn try_lock(_: &File) -> std::io::Result<bool> {
    Ok(true)
}

/// Whether `file` is the file now at `path`.
#[cfg(unix)]
fn same_file(file: &File, path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt as _;
    match (file.metadata(), std::fs::metadata(path)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

#[cfg(not(unix))]
fn same_file(_: &File, _: &Path) -> bool {
    true
}

/// The name of the `k`-th temporary of this process for the file `name`:
/// `.v2ref-tmp-PID-K-` and as much of `name` as fits in [`NAME_MAX`] bytes
/// (a name of 255 bytes has a temporary of 255 bytes).
pub(crate) fn temp_name(name: &[u8], k: u32) -> std::ffi::OsString {
    let mut bytes = format!("{TEMP_PREFIX}{}-{k}-", std::process::id()).into_bytes();
    let room = NAME_MAX.saturating_sub(bytes.len());
    bytes.extend_from_slice(&name[..name.len().min(room)]);
    name_from_bytes(bytes)
}

/// The process id in a temporary's name, if it is one of v2ref's.
fn temp_pid(name: &[u8]) -> Option<u32> {
    let rest = name.strip_prefix(TEMP_PREFIX.as_bytes())?;
    let end = rest.iter().position(|&b| b == b'-')?;
    std::str::from_utf8(&rest[..end]).ok()?.parse().ok()
}

/// Whether the process `pid` runs (or may: a process of another user).
#[cfg(unix)]
pub(crate) fn is_alive(pid: u32) -> bool {
    let Ok(pid) = libc::pid_t::try_from(pid) else {
        return false;
    };
    // SAFETY: signal 0 sends nothing; `kill` only checks that the process
    // exists and may be signalled.
    let r = unsafe { libc::kill(pid, 0) };
    r == 0 || std::io::Error::last_os_error().raw_os_error() != Some(libc::ESRCH)
}

#[cfg(not(unix))]
pub(crate) fn is_alive(_: u32) -> bool {
    true
}

/// Removes, in `dir`, the temporary files (and folders holding v2ref's
/// marker) of v2ref processes that no longer run (killed before they could
/// clean up: SIGKILL, a power cut), under today's names and the names of
/// earlier versions ([`old_temp_pid`]); returns how many. A set such a
/// process left half placed is settled first (`src/atomic/journal.rs`),
/// and the files a commit record still names are kept. Failures are
/// ignored: the run goes on with its own fresh names.
pub(crate) fn remove_stale_temporaries(dir: &Path) -> usize {
    let kept = super::journal::settle_folder(dir);
    let Ok(entries) = std::fs::read_dir(dir) else {
        return 0;
    };
    let mut removed = 0;
    for entry in entries.flatten() {
        let name = entry.file_name();
        let bytes = name_bytes(&name);
        let Ok(kind) = entry.file_type() else {
            continue;
        };
        let pid = match temp_pid(&bytes) {
            Some(pid) => pid,
            None => match old_temp_pid(&bytes, kind.is_dir()) {
                Some(pid) => pid,
                None => continue,
            },
        };
        if pid == std::process::id() || is_alive(pid) || kept.contains(&name) {
            continue;
        }
        let path = entry.path();
        let gone = if kind.is_file() {
            std::fs::remove_file(&path).is_ok()
        } else if kind.is_dir() && super::folder::is_own_folder(&path) {
            // A folder only when it is v2ref's own (its marker inside).
            std::fs::remove_dir_all(&path).is_ok()
        } else {
            false
        };
        removed += usize::from(gone);
    }
    removed
}

/// The process id in the name of a temporary of v2ref before 2026-11-26:
/// a file `.NAME.PID.K.tmp`, or a folder `.NAME.tmp-PID` or `.NAME.old-PID`
/// (removed only with v2ref's marker inside, as today's folders). Both
/// numbers all digits and NAME not empty: a name that merely looks similar
/// is not one.
fn old_temp_pid(name: &[u8], folder: bool) -> Option<u32> {
    let digits = |b: &[u8]| -> Option<u32> {
        if b.is_empty() || !b.iter().all(u8::is_ascii_digit) {
            return None;
        }
        std::str::from_utf8(b).ok()?.parse().ok()
    };
    let rest = name.strip_prefix(b".")?;
    if folder {
        let at = rest
            .windows(5)
            .rposition(|w| w == b".tmp-" || w == b".old-")?;
        return if at == 0 {
            None
        } else {
            digits(&rest[at + 5..])
        };
    }
    let stem = rest.strip_suffix(b".tmp")?;
    let k_at = stem.iter().rposition(|&b| b == b'.')?;
    digits(&stem[k_at + 1..])?;
    let pid_at = stem[..k_at].iter().rposition(|&b| b == b'.')?;
    if pid_at == 0 {
        return None;
    }
    digits(&stem[pid_at + 1..k_at])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_temporary_name_never_exceeds_name_max_and_names_its_process() {
        let long = vec![b'a'; NAME_MAX];
        let t = name_bytes(&temp_name(&long, 7));
        assert_eq!(t.len(), NAME_MAX);
        assert_eq!(temp_pid(&t), Some(std::process::id()));
        let short = name_bytes(&temp_name(b"x.npy", 0));
        assert!(short.ends_with(b"-0-x.npy"), "{short:?}");
        assert_eq!(temp_pid(b".v2ref-tmp-12x-0-a"), None);
        assert_eq!(temp_pid(b"other"), None);
    }

    #[test]
    fn the_temporaries_of_earlier_versions_are_told_by_their_exact_names() {
        assert_eq!(old_temp_pid(b".set.npy.4242.0.tmp", false), Some(4242));
        assert_eq!(old_temp_pid(b".a.b.17.3.tmp", false), Some(17));
        assert_eq!(old_temp_pid(b".out.tmp-99", true), Some(99));
        assert_eq!(old_temp_pid(b".golden.old-7", true), Some(7));
        let look_alike: [(&[u8], bool); 9] = [
            (b"set.npy.4242.0.tmp", false),
            (b"..4242.0.tmp", false),
            (b".set.npy.42x.0.tmp", false),
            (b".set.npy.4242..tmp", false),
            (b".set.npy.4242.0.tmp", true),
            (b".out.tmp-99", false),
            (b".out.tmp-", true),
            (b"..tmp-99", true),
            (b".out.tmp-99a", true),
        ];
        for (name, folder) in look_alike {
            assert_eq!(old_temp_pid(name, folder), None, "{name:?}");
        }
    }

    #[test]
    fn a_dead_process_is_told_from_a_live_one() {
        assert!(is_alive(std::process::id()));
        // pid_max is at most 2^22: no process has that id.
        assert!(!is_alive(1 << 22));
    }
}
