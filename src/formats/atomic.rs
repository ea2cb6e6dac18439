//! Atomic writes: each output goes to a temporary file beside its target
//! (registered with [`crate::cleanup`], so that Ctrl-C removes it), which
//! is renamed onto the target only once it is complete and synced.

use crate::{Error, Result};
use std::fs::File;
use std::io::{self, BufWriter, Write};
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
        super::target::check_parent(target, param)?;
        super::target::check_replaceable(target, param)?;
        let dir = super::target::parent_of(target);
        let name = target
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "out".into());
        let mut k = 0u32;
        loop {
            let temp = dir.join(format!(".{name}.{}.{k}.tmp", std::process::id()));
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

    /// Renames the temporary file onto the target.
    pub(crate) fn persist(mut self) -> Result<()> {
        // Checked again: a link or a device put there meanwhile stays.
        super::target::check_replaceable(&self.target, self.param)?;
        std::fs::rename(&self.temp, &self.target).map_err(|e| self.io(e))?;
        crate::cleanup::unregister(&self.temp);
        self.done = true;
        Ok(())
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
