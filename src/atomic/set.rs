//! The outputs of one run written as one unit: all of them appear together,
//! or none does and what was there before stays.
//!
//! [`OutputSet::begin`] checks every target before any work (distinct
//! paths, each writable and replaceable, an existing file only with
//! `force`), takes each target's lock (`src/atomic/lock.rs`: a second run on
//! the same outputs is refused, naming the process that writes them) and
//! removes the temporaries of dead processes beside them.
//! [`OutputSet::write`] runs the writers: each finished file waits, complete
//! and synced, as its temporary; once every writer has succeeded, the
//! temporaries take their targets' places one after the other, while the
//! signal handler waits ([`crate::cleanup::hold_commit`]), under a commit
//! record ([`super::journal`]: a run killed there is completed by the next
//! run that writes or reads a file of the set). If one of these renames
//! fails, the files already placed are put back as they were.
//!
//! Without `force`, a file is placed with `link` then `unlink`: a file that
//! appeared at the target during the run (a user's, another program's) is
//! never replaced, the run is refused instead. With `force`, the old file
//! is kept as a hard link until the whole set is placed.

use super::journal::{self, real_location, Commit};
use super::lock::OutputLock;
use super::TempTarget;
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
    _locks: Vec<OutputLock>,
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
            locks.push(OutputLock::acquire(path, param)?);
        }
        // A set a killed run left half placed is completed (or rolled
        // back) before this run replaces any of it.
        let held: Vec<PathBuf> = targets.iter().map(|(p, _)| real_location(p)).collect();
        for (target, (_, param)) in held.iter().zip(targets) {
            journal::settle(&journal::entry_of(target), param, &held)?;
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

/// A file placed at its target, and the old file kept aside meanwhile.
struct Placed {
    target: PathBuf,
    old: Option<PathBuf>,
}

/// Places every staged file, while signals wait; on a failure, puts back
/// what was placed. A set of two files or more is placed under a commit
/// record ([`journal`]): a run killed during the renames is completed by
/// the next run that writes or reads one of its files.
fn place_all(staged: Vec<TempTarget>, force: bool) -> Result<()> {
    let _signals_wait = crate::cleanup::hold_commit();
    let olds = keep_olds(&staged, force)?;
    let commit = if staged.len() > 1 {
        let members = staged.iter().zip(&olds).map(|(t, old)| t.member(old));
        match Commit::write(members.collect(), force) {
            Ok(c) => Some(c),
            Err(e) => {
                olds.into_iter()
                    .flatten()
                    .for_each(|o| drop(std::fs::remove_file(o)));
                return Err(e);
            }
        }
    } else {
        None
    };
    let mut placed: Vec<Placed> = Vec::with_capacity(staged.len());
    for (k, (temp, old)) in staged.into_iter().zip(olds).enumerate() {
        match temp.place(force) {
            Ok(target) => placed.push(Placed { target, old }),
            Err(e) => {
                if let Some(old) = old {
                    let _ = std::fs::remove_file(old);
                }
                // The record first: a run killed while the files are put
                // back then removes the temporaries, never rolls forward.
                commit.into_iter().for_each(Commit::abandon);
                undo(placed);
                return Err(e);
            }
        }
        journal::fault::point(&format!("after-rename-{}", k + 1));
    }
    match commit {
        Some(c) => c.finish(),
        None => placed
            .into_iter()
            .filter_map(|p| p.old)
            .for_each(|o| drop(std::fs::remove_file(o))),
    }
    Ok(())
}

/// With `force`, the file at each target kept as a hard link beside it
/// until the set is placed (removed again if one cannot be kept).
fn keep_olds(staged: &[TempTarget], force: bool) -> Result<Vec<Option<PathBuf>>> {
    let mut olds = Vec::with_capacity(staged.len());
    for temp in staged {
        match if force { temp.keep_old() } else { Ok(None) } {
            Ok(old) => olds.push(old),
            Err(e) => {
                olds.into_iter()
                    .flatten()
                    .for_each(|o| drop(std::fs::remove_file(o)));
                return Err(e);
            }
        }
    }
    Ok(olds)
}

/// Puts back the files that were at the targets before (or removes the new
/// ones where there were none).
fn undo(placed: Vec<Placed>) {
    for p in placed.into_iter().rev() {
        let _ = match p.old {
            Some(old) => std::fs::rename(old, &p.target),
            None => std::fs::remove_file(&p.target),
        };
    }
}
