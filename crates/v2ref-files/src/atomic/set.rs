//! The outputs of one run written as one unit.
//!
//! [`OutputSet::begin`] checks every target before any work (distinct
//! paths, each writable and replaceable, an existing file only with
//! `force`), takes each target's lock (`crates/v2ref-files/src/atomic/lock.rs`: a second run on
//! the same outputs is refused, naming the process that writes them) and
//! removes the temporaries of writers that are gone beside them.
//! [`OutputSet::write`] runs the writers: each finished file waits,
//! complete and synced, as its temporary; once every writer has succeeded,
//! the temporaries take their targets' places one rename each, in the
//! order they were written, while the signal handler waits
//! ([`crate::cleanup::hold_commit`]). Without `force`, a file is placed
//! with `link` then `unlink`: a file that appeared at the target during the
//! run is never replaced, the run is refused and the files it placed are
//! removed again.
//!
//! A run killed between two renames (SIGKILL, a power cut: no handler
//! runs) can leave a set half placed. A set that is read back as a set
//! therefore writes its sidecar last, listing every other member
//! ([`staged_members`]: name, size, checksum); a reader checks the members
//! it uses ([`verify_member`]) and refuses a mismatch in one line. Nothing
//! is repaired by a reader: the next writer of the set replaces it whole.

use super::TempTarget;
pub use crate::manifest::Member;
use crate::{Error, Result};
use std::cell::RefCell;
use std::path::{Path, PathBuf};

thread_local! {
    /// The finished files of the set this thread is writing, if any.
    static STAGED: RefCell<Option<Vec<TempTarget>>> = const { RefCell::new(None) };
}

/// The outputs of one run, checked and locked.
pub struct OutputSet {
    force: bool,
    // Released after the set is placed (or abandoned).
    _locks: Vec<super::lock::OutputLock>,
}

impl OutputSet {
    /// Checks and locks `targets` (each with the parameter that names it):
    /// refused when two are the same file, when one cannot be written or
    /// exists (without `force`), or when another writer holds one.
    pub fn begin(targets: &[(&Path, &'static str)], force: bool) -> Result<OutputSet> {
        check_distinct(targets)?;
        for (path, param) in targets {
            super::target::check_output_file(path, param, force)?;
        }
        let mut locks = Vec::with_capacity(targets.len());
        for (path, param) in targets {
            locks.push(super::lock::OutputLock::acquire(path, param)?);
        }
        for (path, _) in targets {
            super::lock::remove_stale_temporaries(&super::target::parent_of(path));
        }
        Ok(OutputSet {
            force,
            _locks: locks,
        })
    }

    /// Runs `write`, whose finished files (every atomic writer of
    /// [`super`] on this thread) wait as temporaries; places them all when
    /// `write` succeeds, none when it fails.
    pub fn write<T>(self, write: impl FnOnce() -> Result<T>) -> Result<T> {
        let scope = Scope::open()?;
        let value = write()?;
        let staged = scope.close();
        place_all(staged, self.force)?;
        Ok(value)
    }
}

/// This thread's staging, undone on drop (also on an error or an unwind:
/// the temporaries are then removed by their own drop).
struct Scope;

impl Scope {
    fn open() -> Result<Scope> {
        STAGED.with(|s| {
            let mut s = s.borrow_mut();
            if s.is_some() {
                return Err(Error::Output {
                    path: String::new(),
                    reason: "a set of outputs inside another set".into(),
                });
            }
            *s = Some(Vec::new());
            Ok(Scope)
        })
    }

    fn close(self) -> Vec<TempTarget> {
        STAGED.with(|s| s.borrow_mut().take()).unwrap_or_default()
    }
}

impl Drop for Scope {
    fn drop(&mut self) {
        let staged = STAGED.with(|s| s.borrow_mut().take());
        drop(staged);
    }
}

/// Keeps `temp` until its set is placed when this thread writes a set;
/// gives it back otherwise.
pub(crate) fn stage(temp: TempTarget) -> Option<TempTarget> {
    STAGED.with(|s| match s.borrow_mut().as_mut() {
        Some(staged) => {
            staged.push(temp);
            None
        }
        None => Some(temp),
    })
}

/// Refuses two targets that are the same file (`a.csv` and `./a.csv`,
/// or the same name through a linked folder).
fn check_distinct(targets: &[(&Path, &'static str)]) -> Result<()> {
    let mut seen: Vec<(PathBuf, &'static str, &Path)> = Vec::new();
    for &(path, param) in targets {
        let key = identity(path);
        if let Some((_, first, first_path)) = seen.iter().find(|(k, _, _)| *k == key) {
            return Err(Error::Invalid {
                param,
                reason: format!(
                    "{} is the same file as the {first} output ({}); give each output its own path",
                    path.display(),
                    first_path.display()
                ),
            });
        }
        seen.push((key, param, path));
    }
    Ok(())
}

/// The folder (resolved) and name of `path`.
fn identity(path: &Path) -> PathBuf {
    let parent = super::target::parent_of(path);
    let parent = std::fs::canonicalize(&parent).unwrap_or(parent);
    parent.join(path.file_name().unwrap_or_default())
}

/// Places every staged file in order, while signals wait. Without
/// `force`, a failure removes the files already placed (they are new);
/// with `force`, the files replaced are gone, and the error says the set
/// is half placed (its sidecar, last, still lists the old members).
fn place_all(mut staged: Vec<TempTarget>, force: bool) -> Result<()> {
    let _signals_wait = crate::cleanup::hold_commit();
    for k in 0..staged.len() {
        if let Err(e) = staged[k].place(force) {
            if !force {
                staged[..k].iter().for_each(TempTarget::unplace);
                return Err(e);
            }
            return Err(half_placed(&staged[k], k, e));
        }
        fault::point(&format!("after-rename-{}", k + 1));
    }
    for t in &staged {
        t.folder.sync();
    }
    Ok(())
}

fn half_placed(failed: &TempTarget, k: usize, e: Error) -> Error {
    if k == 0 {
        return e;
    }
    Error::Output {
        path: failed.target.display().to_string(),
        reason: format!(
            "{e}; {k} file(s) of the set before it were replaced already, and readers of the set refuse it: run the writer again"
        ),
    }
}

/// The most members a sidecar may list (a v2ref set has at most 4).
pub const MAX_MEMBERS: usize = 16;

/// The members staged so far by this thread's set (the files written
/// before the sidecar that lists them); None when no set is being written.
pub fn staged_members() -> Result<Option<Vec<Member>>> {
    STAGED.with(|s| match s.borrow().as_ref() {
        Some(staged) => staged
            .iter()
            .map(TempTarget::member)
            .collect::<Result<_>>()
            .map(Some),
        None => Ok(None),
    })
}

/// The size and FNV-1a of the whole of `file`, read from its start.
pub(crate) fn checksum(file: &std::fs::File) -> std::io::Result<(u64, u64)> {
    use std::io::{Read, Seek};
    let mut file = file;
    file.rewind()?;
    let mut buf = vec![0u8; 1 << 20];
    let (mut bytes, mut sum) = (0u64, super::lock::FNV_START);
    loop {
        match file.read(&mut buf)? {
            0 => return Ok((bytes, sum)),
            n => {
                sum = super::lock::fnv1a(&buf[..n], sum);
                bytes += n as u64;
            }
        }
    }
}

/// Checks `file` (named `param`), about to be read as a member of the set
/// whose sidecar `sidecar` lists `members`: when the sidecar lists a file
/// of that name and `file` is in the sidecar's folder, its size and
/// checksum must match (a set a run left half placed is refused, saying
/// what to do). Writes nothing.
pub fn verify_member(
    sidecar: &Path,
    members: &[Member],
    file: &Path,
    param: &'static str,
) -> Result<()> {
    if members.len() > MAX_MEMBERS {
        return Err(Error::data(
            "sidecar",
            sidecar,
            "field members",
            format!(
                "{} members; a v2ref set has at most {MAX_MEMBERS}",
                members.len()
            ),
        ));
    }
    let name = file.file_name().unwrap_or_default().to_string_lossy();
    let Some(m) = members.iter().find(|m| m.name == name) else {
        return Ok(());
    };
    let folder = |p: &Path| {
        let dir = super::target::parent_of(p);
        std::fs::canonicalize(&dir).unwrap_or(dir)
    };
    if folder(file) != folder(sidecar) {
        return Ok(());
    }
    let f = crate::formats::open(file, param)?;
    let same = f.metadata().map(|md| md.len() == m.bytes).unwrap_or(false)
        && checksum(&f)
            .map(|(n, s)| n == m.bytes && format!("{s:016x}") == m.fnv1a64)
            .unwrap_or(false);
    if same {
        return Ok(());
    }
    Err(Error::Invalid {
        param,
        reason: format!(
            "{}: not the file its sidecar {} lists ({} bytes, checksum {}): the set was half written by a run that stopped, or this file was changed since; run the writer again",
            file.display(),
            sidecar.display(),
            m.bytes,
            m.fnv1a64
        ),
    })
}

/// A test-only way to stop a run between two renames of a set, as a
/// SIGKILL there would: the process kills itself with SIGKILL when the
/// environment variable [`fault::VARIABLE`] is exactly `after-rename-K`
/// (K from 1). Its long name is not one to set by accident.
pub(crate) mod fault {
    /// The variable's name.
    pub(crate) const VARIABLE: &str = "V2REF_TEST_ONLY_SIGKILL_SELF_AT_SET_COMMIT_STEP";

    /// Dies here, as by a SIGKILL, when asked to at `step`.
    pub(crate) fn point(step: &str) {
        if std::env::var_os(VARIABLE).is_some_and(|v| v == step) {
            kill_self();
        }
    }

    #[cfg(unix)]
    fn kill_self() {
        // SAFETY: `kill` only reads its arguments; the signal is sent to
        // this process, which it ends at once.
        unsafe {
            libc::kill(libc::getpid(), libc::SIGKILL);
        }
    }

    #[cfg(not(unix))]
    fn kill_self() {
        std::process::abort();
    }
}
