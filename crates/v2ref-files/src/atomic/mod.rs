//! The one atomic writer of the crate. An output (a file, or a folder
//! written as a whole) is made as a temporary beside its target
//! (`.v2ref-tmp-PID-K-NAME`, at most 255 bytes; created new, never through
//! a link, and held under an `flock` by its writer for as long as it
//! lives; registered with [`crate::cleanup`], so that a terminating signal
//! removes it), which takes the target's place by one rename once it is
//! complete and synced, alone or with the rest of its set ([`set`]).
//! Targets are checked ([`target`]) and locked for the run
//! (`crates/v2ref-files/src/atomic/lock.rs`); the temporaries of writers that are gone are
//! removed by the next writer beside them, only when their lock is free.
//!
//! A set that is read back as a set (`synth`'s files) lists its members,
//! each by file name with its size and checksum, in its sidecar, placed
//! last ([`set::Member`]); a reader that uses a member checks it against
//! that list, so that a set a run left half placed is refused in one line,
//! without anything written. Readers never write.
//!
//! - A file: a temporary file under every writer of [`crate::formats`]
//!   (`.npy`, CSV, OIFITS, text: [`write_text_atomic`]).
//! - A folder: [`replace_folder`] (`reproduce --out`, `golden --update`).

pub(crate) mod lock;
pub(crate) mod own;
pub mod set;
pub mod target;

mod folder;

use crate::{Error, Result};
pub use folder::{check_folder_parent, replace_folder, ScratchFolder};
use lock::{name_bytes, temp_name};
use own::Folder;
use std::ffi::OsString;
use std::fs::File;
use std::io::BufWriter;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// A temporary file next to a target, held under its writer's lock,
/// removed on drop unless placed.
pub struct TempTarget {
    target: PathBuf,
    folder: Folder,
    temp: OsString,
    // The temporary, open: holds its flock until it is placed or removed.
    held: File,
    param: Option<&'static str>,
    done: bool,
}

impl TempTarget {
    /// A new temporary beside `target` (created exclusively, not followed
    /// through a link, held under its lock), and the file to write it
    /// through; `param` names the parameter that gave `target`.
    pub fn create(target: &Path, param: Option<&'static str>) -> Result<(TempTarget, File)> {
        target::check_parent(target, param)?;
        target::check_replaceable(target, param)?;
        let dir = target::parent_of(target);
        let folder = Folder::open(&dir).map_err(|e| Error::file(param, &dir, e))?;
        let name = target.file_name().map(name_bytes).unwrap_or_default();
        for k in 0..1000 {
            let temp = temp_name(&name, k);
            let path = dir.join(&temp);
            let held = match own::open_own(&path, true) {
                Ok(f) => f,
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
                Err(e) => return Err(Error::file(param, target, e)),
            };
            // A sweep may have taken it between the create and the lock.
            if !own::try_lock(&held).unwrap_or(false) || !own::is_at(&held, &path) {
                continue;
            }
            crate::cleanup::register(&path);
            let file = held
                .try_clone()
                .map_err(|e| Error::file(param, target, e))?;
            let temp = TempTarget {
                target: target.to_path_buf(),
                folder,
                temp,
                held,
                param,
                done: false,
            };
            return Ok((temp, file));
        }
        Err(Error::file(
            param,
            target,
            io::Error::new(io::ErrorKind::AlreadyExists, "no free temporary name"),
        ))
    }

    /// The error `e` met while writing this temporary, naming its target.
    pub fn io(&self, e: io::Error) -> Error {
        Error::file(self.param, &self.target, e)
    }

    fn target_name(&self) -> OsString {
        self.target.file_name().unwrap_or_default().to_os_string()
    }

    /// Puts the finished temporary file at its target: at once, or, when
    /// this thread writes a set ([`set::OutputSet::write`]), with the
    /// rest of the set.
    pub fn persist(self) -> Result<()> {
        match set::stage(self) {
            None => Ok(()),
            Some(mut temp) => temp.place(true),
        }
    }

    /// Renames the temporary file onto the target; without `replace`, only
    /// when nothing is there at that moment (link, then unlink: a file that
    /// appeared meanwhile stays and the write is refused).
    pub(crate) fn place(&mut self, replace: bool) -> Result<()> {
        // Checked again: a link or a device put there meanwhile stays.
        target::check_replaceable(&self.target, self.param)?;
        if replace {
            let to = self.target_name();
            self.folder
                .rename(&self.temp, &to)
                .map_err(|e| self.io(e))?;
        } else {
            self.link_new()?;
        }
        crate::cleanup::unregister(&self.folder.path().join(&self.temp));
        self.done = true;
        Ok(())
    }

    /// Links the temporary at the target, refused when the target exists.
    fn link_new(&self) -> Result<()> {
        let to = self.target_name();
        match self.folder.link(&self.temp, &to) {
            Ok(()) => {
                let _ = self.folder.unlink(&self.temp);
                Ok(())
            }
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => Err(Error::Invalid {
                param: self.param.unwrap_or("out"),
                reason: format!(
                    "{}: appeared during the run and was not replaced; remove it, give a new name or --force",
                    self.target.display()
                ),
            }),
            // A file system without hard links: the rename, checked just
            // before.
            Err(_) if std::fs::symlink_metadata(&self.target).is_err() => {
                self.folder.rename(&self.temp, &to).map_err(|e| self.io(e))
            }
            Err(e) => Err(self.io(e)),
        }
    }

    /// Removes the placed file again, when the target is still this file
    /// (a set that could not be placed whole, without `--force`).
    fn unplace(&self) {
        if own::is_at(&self.held, &self.target) {
            let _ = self.folder.unlink(&self.target_name());
        }
    }

    /// The target's name, size and checksum ([`set::Member`]), read from
    /// the finished temporary.
    fn member(&self) -> Result<set::Member> {
        let (bytes, sum) = set::checksum(&self.held).map_err(|e| self.io(e))?;
        Ok(set::Member::new(
            self.target_name().to_string_lossy().into_owned(),
            bytes,
            sum,
        ))
    }
}

impl Drop for TempTarget {
    fn drop(&mut self) {
        if !self.done {
            let _ = self.folder.unlink(&self.temp);
            crate::cleanup::unregister(&self.folder.path().join(&self.temp));
        }
    }
}

pub(crate) const WRITE_BUFFER: usize = 1 << 20;

/// Checks the row count, flushes, syncs, closes and renames.
pub(crate) fn finish_file(
    out: BufWriter<File>,
    temp: TempTarget,
    rows: u64,
    written: u64,
) -> Result<()> {
    if written != rows {
        return Err(row_count(&temp, rows, written));
    }
    let file = out.into_inner().map_err(|e| temp.io(e.into_error()))?;
    file.sync_all().map_err(|e| temp.io(e))?;
    drop(file);
    temp.persist()
}

pub(crate) fn whole_rows(len: usize, cols: usize, temp: &TempTarget) -> Result<u64> {
    if cols == 0 || len % cols != 0 {
        return Err(Error::Output {
            path: temp.target.display().to_string(),
            reason: format!("{len} values are not whole rows of {cols}"),
        });
    }
    Ok((len / cols) as u64)
}

pub(crate) fn too_many(temp: &TempTarget, rows: u64) -> Error {
    Error::Output {
        path: temp.target.display().to_string(),
        reason: format!("more than the {rows} rows announced"),
    }
}

pub(crate) fn row_count(temp: &TempTarget, rows: u64, written: u64) -> Error {
    Error::Output {
        path: temp.target.display().to_string(),
        reason: format!("{written} rows written, {rows} announced; the file was not written"),
    }
}

/// Writes `text` to `path` atomically (temporary file, then rename).
pub fn write_text_atomic(path: &Path, text: &str) -> Result<()> {
    let (temp, mut file) = TempTarget::create(path, None)?;
    file.write_all(text.as_bytes())
        .and_then(|_| file.sync_all())
        .map_err(|e| temp.io(e))?;
    drop(file);
    temp.persist()
}
