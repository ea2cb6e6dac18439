//! A folder written as a whole: filled as a temporary folder beside its
//! target, which then takes the target's place: swapped with the old
//! folder in one step where the system can (Linux's `RENAME_EXCHANGE`),
//! else by rename, the old folder moved aside first (put back if the
//! rename fails); the old folder removed last. Only a folder is ever
//! replaced: a file, a link or anything else at the target is refused.

use super::lock::{name_bytes, remove_stale_temporaries, temp_name, OutputLock, FOLDER_MARKER};
use super::own;
use super::target::parent_of;
use crate::{Error, Result};
use std::fs::File;
use std::path::{Path, PathBuf};

/// Replaces the folder `dir` as a whole (its parent created if needed):
/// `fill` writes into a fresh temporary folder beside it, which takes
/// `dir`'s place once `fill` succeeds. The folder is locked for the run (a
/// second writer is refused, naming the process), and the temporaries of
/// writers that are gone beside it are removed first. If `fill` fails, or
/// the rename does, `dir` is left as it was and nothing half-written
/// remains; a terminating signal waits for the renames. Errors name
/// `param`.
pub fn replace_folder<T>(
    dir: &Path,
    param: Option<&'static str>,
    fill: impl FnOnce(&Path) -> Result<T>,
) -> Result<T> {
    let parent = parent_of(dir);
    let made = MadeFolders::create(&parent).map_err(|e| Error::file(param, &parent, e))?;
    check_folder_target(dir, param)?;
    let _lock = OutputLock::acquire(dir, param.unwrap_or("out"))?;
    remove_stale_temporaries(&parent);
    let temp = TempFolder::create(dir, param)?;
    let value = fill(&temp.path)?;
    temp.place()?;
    made.keep();
    Ok(value)
}

/// The folders a run made for its output's parent, removed again (when
/// still empty) unless the run succeeds: a failed run leaves no folder of
/// its own behind.
struct MadeFolders(Vec<PathBuf>);

impl MadeFolders {
    /// Creates `dir` and whatever of its parents is missing.
    fn create(dir: &Path) -> std::io::Result<MadeFolders> {
        let mut missing = Vec::new();
        let mut at = Some(dir);
        while let Some(p) = at.filter(|p| !p.as_os_str().is_empty()) {
            if std::fs::symlink_metadata(p).is_ok() {
                break;
            }
            missing.push(p.to_path_buf());
            at = p.parent();
        }
        let mut made = MadeFolders(Vec::new());
        for p in missing.into_iter().rev() {
            match std::fs::create_dir(&p) {
                Ok(()) => made.0.push(p),
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {}
                Err(e) => return Err(e),
            }
        }
        Ok(made)
    }

    /// The run succeeded: its folders stay.
    fn keep(mut self) {
        self.0.clear();
    }
}

impl Drop for MadeFolders {
    fn drop(&mut self) {
        // Deepest first; `remove_dir` removes only an empty folder.
        for p in self.0.iter().rev() {
            let _ = std::fs::remove_dir(p);
        }
    }
}

/// Removes the temporary folder `path` and what it holds. A folder made
/// under a umask that leaves its owner no access (0777: mode 000) cannot
/// be listed, so its owner's access is given back (to folders only, never
/// through a link) before a second try.
fn remove_temporary_folder(path: &Path) {
    if std::fs::remove_dir_all(path).is_ok() {
        return;
    }
    give_owner_access(path);
    let _ = std::fs::remove_dir_all(path);
}

#[cfg(unix)]
fn give_owner_access(path: &Path) {
    use std::os::unix::fs::PermissionsExt as _;
    let Ok(meta) = std::fs::symlink_metadata(path) else {
        return;
    };
    if !meta.is_dir() {
        return;
    }
    let mode = meta.permissions().mode() | 0o700;
    let _ = std::fs::set_permissions(path, std::fs::Permissions::from_mode(mode));
    for entry in std::fs::read_dir(path).into_iter().flatten().flatten() {
        give_owner_access(&entry.path());
    }
}

#[cfg(not(unix))]
fn give_owner_access(_: &Path) {}

/// Checks, before any work, that [`replace_folder`] can write next to
/// `dir`: creates its parent and a probe file there, then removes both
/// (the parent only when this call made it).
pub fn check_folder_parent(dir: &Path, param: Option<&'static str>) -> Result<()> {
    let parent = parent_of(dir);
    let made = MadeFolders::create(&parent).map_err(|e| Error::file(param, &parent, e))?;
    check_folder_target(dir, param)?;
    let name = dir.file_name().map(name_bytes).unwrap_or_default();
    let probe = parent.join(temp_name(&name, 3000));
    own::open_own(&probe, true).map_err(|e| Error::file(param, &parent, e))?;
    let removed = std::fs::remove_file(&probe).map_err(|e| Error::file(param, &probe, e));
    // The parents it made are removed again ([`replace_folder`] makes them
    // when it writes): a run refused later leaves none behind.
    drop(made);
    removed
}

/// Refuses a target that is there and is not a folder (a file, a link).
fn check_folder_target(dir: &Path, param: Option<&'static str>) -> Result<()> {
    match std::fs::symlink_metadata(dir) {
        Ok(m) if !m.is_dir() => Err(Error::Invalid {
            param: param.unwrap_or("out"),
            reason: format!(
                "{}: is not a folder (a file or a link); v2ref replaces only a folder: give another name",
                dir.display()
            ),
        }),
        _ => Ok(()),
    }
}

/// A temporary folder beside a target, removed on drop unless placed.
struct TempFolder {
    target: PathBuf,
    path: PathBuf,
    param: Option<&'static str>,
    // The marker, open: holds its flock for the life of the folder.
    _marker: File,
    placed: bool,
}

impl TempFolder {
    fn create(target: &Path, param: Option<&'static str>) -> Result<TempFolder> {
        let name = target
            .file_name()
            .map(name_bytes)
            .ok_or_else(|| Error::Output {
                path: target.display().to_string(),
                reason: "not a folder name".into(),
            })?;
        let path = free_name(target, &name).map_err(|e| Error::file(param, target, e))?;
        let marker = own::open_own(&path.join(FOLDER_MARKER), true)
            .and_then(|f| own::try_lock(&f).map(|_| f));
        let marker = match marker {
            Ok(f) => f,
            Err(e) => {
                remove_temporary_folder(&path);
                crate::cleanup::unregister(&path);
                return Err(Error::file(param, &path, e));
            }
        };
        Ok(TempFolder {
            target: target.to_path_buf(),
            path,
            param,
            _marker: marker,
            placed: false,
        })
    }

    /// Puts the folder at its target: swapped with the old folder, or
    /// renamed in (the old folder moved aside first), the old one removed.
    fn place(mut self) -> Result<()> {
        let io = |e| Error::file(self.param, &self.target, e);
        let signals_wait = crate::cleanup::hold_commit();
        check_folder_target(&self.target, self.param)?;
        let there = std::fs::symlink_metadata(&self.target).is_ok();
        // One atomic swap where the system has it: no instant without a
        // folder at the target, even for a run killed there.
        let old = if there && exchange(&self.path, &self.target) {
            Some(self.path.clone())
        } else {
            let old = if there {
                let name = self.target.file_name().map(name_bytes).unwrap_or_default();
                let old = parent_of(&self.target).join(temp_name(&name, 2000));
                std::fs::rename(&self.target, &old).map_err(io)?;
                crate::cleanup::register(&old);
                Some(old)
            } else {
                None
            };
            if let Err(e) = std::fs::rename(&self.path, &self.target) {
                if let Some(old) = &old {
                    let _ = std::fs::rename(old, &self.target);
                    crate::cleanup::unregister(old);
                }
                return Err(io(e));
            }
            old
        };
        crate::cleanup::unregister(&self.path);
        self.placed = true;
        drop(signals_wait);
        let _ = std::fs::remove_file(self.target.join(FOLDER_MARKER));
        if let Some(old) = old {
            let _ = std::fs::remove_dir_all(&old);
            crate::cleanup::unregister(&old);
        }
        Ok(())
    }
}

impl Drop for TempFolder {
    fn drop(&mut self) {
        if !self.placed {
            remove_temporary_folder(&self.path);
            crate::cleanup::unregister(&self.path);
        }
    }
}

/// Swaps the folders `a` and `b` in one step (`renameat2` with
/// `RENAME_EXCHANGE`); false where the system or the file system cannot,
/// nothing then moved.
#[cfg(any(target_os = "linux", target_os = "android"))]
fn exchange(a: &Path, b: &Path) -> bool {
    use std::os::unix::ffi::OsStrExt as _;
    let c = |p: &Path| std::ffi::CString::new(p.as_os_str().as_bytes()).ok();
    let (Some(a), Some(b)) = (c(a), c(b)) else {
        return false;
    };
    // SAFETY: both paths are NUL-terminated strings that live through the
    // call; `renameat2` only reads them.
    let r = unsafe {
        libc::renameat2(
            libc::AT_FDCWD,
            a.as_ptr(),
            libc::AT_FDCWD,
            b.as_ptr(),
            libc::RENAME_EXCHANGE,
        )
    };
    r == 0
}

#[cfg(not(any(target_os = "linux", target_os = "android")))]
fn exchange(_: &Path, _: &Path) -> bool {
    false
}

/// Makes (and registers) the first free temporary folder for `name`
/// beside `target`.
fn free_name(target: &Path, name: &[u8]) -> std::io::Result<PathBuf> {
    let dir = parent_of(target);
    let mut k = 0;
    loop {
        let path = dir.join(temp_name(name, k));
        // Registered first: a signal that comes as it is made removes it.
        crate::cleanup::register(&path);
        match std::fs::create_dir(&path) {
            Ok(()) => return Ok(path),
            Err(e) => {
                crate::cleanup::unregister(&path);
                match e.kind() {
                    std::io::ErrorKind::AlreadyExists if k < 1000 => k += 1,
                    _ => return Err(e),
                }
            }
        }
    }
}

/// A folder of scratch files, a temporary of the one writer that is never
/// placed: named for `target` beside it, registered (a terminating signal
/// removes it), removed on drop; a dead process's is removed by a later
/// run beside it.
pub struct ScratchFolder(TempFolder);

impl ScratchFolder {
    /// Makes the scratch folder for `target` (in `target`'s folder, which
    /// must exist); errors name `param`.
    pub fn create(target: &Path, param: Option<&'static str>) -> Result<ScratchFolder> {
        remove_stale_temporaries(&parent_of(target));
        TempFolder::create(target, param).map(ScratchFolder)
    }

    /// The folder.
    pub fn path(&self) -> &Path {
        &self.0.path
    }
}
