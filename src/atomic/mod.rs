//! The one atomic writer of the crate: an output (a file, or a folder
//! written as a whole) is made as a temporary beside its target
//! (`.v2ref-tmp-PID-K-NAME`, at most 255 bytes; registered with
//! [`crate::cleanup`], so that a terminating signal removes it), which
//! takes the target's place only once it is complete and synced, alone or
//! with the rest of its set ([`set`]; the set's renames under a commit
//! record, [`journal`], so that a run killed between two of them is
//! completed or undone by the next run). Targets are checked ([`target`])
//! and locked for the run (`src/atomic/lock.rs`); temporaries of processes that no
//! longer run are removed by the next run that writes beside them.
//!
//! - A file: a temporary file under every writer of [`crate::formats`]
//!   (`.npy`, CSV, OIFITS, text: [`write_text_atomic`]).
//! - A folder: [`replace_folder`] (`reproduce --out`, `golden --update`).

pub mod journal;
pub(crate) mod lock;
pub mod set;
pub mod target;

mod folder;

use crate::{Error, Result};
pub use folder::{check_folder_parent, replace_folder, ScratchFolder};
use lock::{name_bytes, temp_name};
use std::fs::File;
#[cfg(feature = "files")]
use std::io::BufWriter;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// A temporary file next to a target, removed on drop unless persisted.
pub(crate) struct TempTarget {
    target: PathBuf,
    temp: PathBuf,
    param: Option<&'static str>,
    done: bool,
}

impl TempTarget {
    pub(crate) fn create(target: &Path, param: Option<&'static str>) -> Result<(TempTarget, File)> {
        target::check_parent(target, param)?;
        target::check_replaceable(target, param)?;
        let dir = target::parent_of(target);
        let name = target.file_name().map(name_bytes).unwrap_or_default();
        let mut k = 0u32;
        loop {
            let temp = dir.join(temp_name(&name, k));
            match std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(&temp)
            {
                Ok(f) => {
                    crate::cleanup::register(&temp);
                    return Ok((
                        TempTarget {
                            target: target.to_path_buf(),
                            temp,
                            param,
                            done: false,
                        },
                        f,
                    ));
                }
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists && k < 1000 => k += 1,
                Err(e) => return Err(Error::file(param, target, e)),
            }
        }
    }

    pub(crate) fn io(&self, e: io::Error) -> Error {
        Error::file(self.param, &self.target, e)
    }

    /// Puts the finished temporary file at its target: at once, or, when
    /// this thread writes a set ([`set::OutputSet::write`]), with the
    /// rest of the set.
    pub(crate) fn persist(self) -> Result<()> {
        match set::stage(self) {
            None => Ok(()),
            Some(temp) => temp.place(true).map(drop),
        }
    }

    /// Renames the temporary file onto the target; without `replace`, only
    /// when nothing is there at that moment (link, then unlink: a file that
    /// appeared meanwhile stays and the write is refused). Returns the
    /// target.
    pub(crate) fn place(mut self, replace: bool) -> Result<PathBuf> {
        // Checked again: a link or a device put there meanwhile stays.
        target::check_replaceable(&self.target, self.param)?;
        if replace {
            std::fs::rename(&self.temp, &self.target).map_err(|e| self.io(e))?;
        } else {
            self.link_new()?;
        }
        crate::cleanup::unregister(&self.temp);
        self.done = true;
        Ok(std::mem::take(&mut self.target))
    }

    /// Links the temporary at the target, refused when the target exists.
    fn link_new(&self) -> Result<()> {
        match std::fs::hard_link(&self.temp, &self.target) {
            Ok(()) => {
                let _ = std::fs::remove_file(&self.temp);
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
                std::fs::rename(&self.temp, &self.target).map_err(|e| self.io(e))
            }
            Err(e) => Err(self.io(e)),
        }
    }

    /// This file as a member of a set's commit record (absolute paths),
    /// with the old file kept aside.
    pub(crate) fn member(&self, old: &Option<PathBuf>) -> journal::Member {
        let dir = journal::real_location(&target::parent_of(&self.target));
        let beside = |p: &Path| dir.join(p.file_name().unwrap_or_default());
        journal::Member {
            target: beside(&self.target),
            temp: beside(&self.temp),
            old: old.as_deref().map(beside),
        }
    }

    /// Keeps the regular file now at the target as a hard link beside it
    /// (its own temporary name), so that it can be put back; None when
    /// there is none.
    pub(crate) fn keep_old(&self) -> Result<Option<PathBuf>> {
        if !std::fs::symlink_metadata(&self.target).is_ok_and(|m| m.is_file()) {
            return Ok(None);
        }
        let dir = target::parent_of(&self.target);
        let name = self.target.file_name().map(name_bytes).unwrap_or_default();
        for k in 1000..2000 {
            let old = dir.join(temp_name(&name, k));
            match std::fs::hard_link(&self.target, &old) {
                Ok(()) => return Ok(Some(old)),
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
                // No hard links here: the old file is replaced without a
                // copy kept.
                Err(_) => return Ok(None),
            }
        }
        Ok(None)
    }
}

impl Drop for TempTarget {
    fn drop(&mut self) {
        if !self.done {
            let _ = std::fs::remove_file(&self.temp);
            crate::cleanup::unregister(&self.temp);
        }
    }
}

#[cfg(feature = "files")]
pub(crate) const WRITE_BUFFER: usize = 1 << 20;

/// Checks the row count, flushes, syncs, closes and renames.
#[cfg(feature = "files")]
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

#[cfg(feature = "files")]
pub(crate) fn whole_rows(len: usize, cols: usize, temp: &TempTarget) -> Result<u64> {
    if cols == 0 || len % cols != 0 {
        return Err(Error::Output {
            path: temp.target.display().to_string(),
            reason: format!("{len} values are not whole rows of {cols}"),
        });
    }
    Ok((len / cols) as u64)
}

#[cfg(feature = "files")]
pub(crate) fn too_many(temp: &TempTarget, rows: u64) -> Error {
    Error::Output {
        path: temp.target.display().to_string(),
        reason: format!("more than the {rows} rows announced"),
    }
}

#[cfg(feature = "files")]
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
