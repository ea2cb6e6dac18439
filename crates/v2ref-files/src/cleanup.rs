//! Temporaries in flight: the files and folders an atomic writer has made
//! and not yet renamed onto their target. An interrupt handler (the CLI's
//! Ctrl-C) removes them before the process exits, so that an interrupted
//! run leaves no partial output behind, only what was there before.

use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard, PoisonError};

static IN_FLIGHT: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Held while the files of a set take their targets' places: the cleanup
/// of a terminating signal waits for it, so that a set is never left half
/// placed.
static COMMIT: Mutex<()> = Mutex::new(());

/// Holds off [`remove_all`] (the signal handler's cleanup) until the guard
/// is dropped.
pub fn hold_commit() -> MutexGuard<'static, ()> {
    COMMIT.lock().unwrap_or_else(PoisonError::into_inner)
}

/// Records `path` as a temporary in flight.
pub fn register(path: &Path) {
    if let Ok(mut v) = IN_FLIGHT.lock() {
        v.push(path.to_path_buf());
    }
}

/// Forgets `path` (renamed onto its target, or removed).
pub fn unregister(path: &Path) {
    if let Ok(mut v) = IN_FLIGHT.lock() {
        v.retain(|p| p != path);
    }
}

/// Removes every temporary in flight (files and folders); returns how many.
pub fn remove_all() -> usize {
    let _placed = hold_commit();
    let mut v = IN_FLIGHT.lock().unwrap_or_else(PoisonError::into_inner);
    let n = v.len();
    for p in v.drain(..) {
        // Looked at, not followed: a temporary someone replaced with a
        // link is unlinked, and what it points to is left alone.
        let folder = std::fs::symlink_metadata(&p).is_ok_and(|m| m.is_dir());
        if folder {
            let _ = std::fs::remove_dir_all(&p);
        } else {
            let _ = std::fs::remove_file(&p);
        }
    }
    n
}

#[cfg(test)]
mod tests {
    #[test]
    fn removes_what_is_registered_and_only_that() {
        let dir = std::env::temp_dir().join(format!("v2ref-cleanup-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let (a, b, kept) = (dir.join("a.tmp"), dir.join("b.tmp"), dir.join("kept"));
        for p in [&a, &b, &kept] {
            std::fs::write(p, "x").unwrap();
        }
        super::register(&a);
        super::register(&b);
        super::unregister(&b);
        assert_eq!(super::remove_all(), 1);
        assert!(!a.exists() && b.exists() && kept.exists());
        // A temporary folder swapped for a link to someone else's folder:
        // the link goes, their files stay (one test: the list is global).
        #[cfg(unix)]
        {
            let (theirs, link) = (dir.join("theirs"), dir.join("set.tmp"));
            std::fs::create_dir_all(&theirs).unwrap();
            std::fs::write(theirs.join("keep.npy"), "x").unwrap();
            std::os::unix::fs::symlink(&theirs, &link).unwrap();
            super::register(&link);
            assert_eq!(super::remove_all(), 1);
            assert!(std::fs::symlink_metadata(&link).is_err());
            assert!(theirs.join("keep.npy").exists());
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
