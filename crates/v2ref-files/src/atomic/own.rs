//! v2ref's own files in a folder that others may write in: a lock or a
//! temporary is opened without following a link and without waiting
//! (`O_NOFOLLOW | O_NONBLOCK`), and used only when it is a regular file of
//! this process's effective user; anything else found under such a name
//! (a link to a file elsewhere, a FIFO, a device, a folder, another
//! user's file) is refused, never opened through, truncated or removed.
//! Files are removed and renamed through the folder as opened at the start
//! (`unlinkat`, `renameat`, `linkat`), so that a folder moved during a run
//! keeps none of the run's locks or temporaries.

use std::ffi::OsStr;
use std::fs::File;
use std::io;
use std::path::{Path, PathBuf};

/// Opens `path` for reading and writing, a new file when `create_new`,
/// else an existing one or a new one; never through a link, never
/// waiting; refused unless a regular file owned by this user.
pub(crate) fn open_own(path: &Path, create_new: bool) -> io::Result<File> {
    let mut options = std::fs::OpenOptions::new();
    options.read(true).write(true);
    if create_new {
        options.create_new(true);
    } else {
        options.create(true);
    }
    no_follow(&mut options);
    let file = options.open(path)?;
    check_own(&file)?;
    Ok(file)
}

/// Opens the lock file `path` for reading and writing: a new file
/// (`O_CREAT | O_EXCL`, so a link, FIFO or file already there is never
/// opened through) and true, or else the file already there, never through
/// a link, and false, refused (checked on the open file, before anything is
/// read or written) unless a regular file of this user with no other link:
/// a hard link (another name of someone's file) is never a lock.
pub(crate) fn open_lock(path: &Path) -> io::Result<(File, bool)> {
    match open_own(path, true) {
        Ok(file) => return Ok((file, true)),
        Err(e) if e.kind() != io::ErrorKind::AlreadyExists => return Err(e),
        Err(_) => {}
    }
    let mut options = std::fs::OpenOptions::new();
    options.read(true).write(true);
    no_follow(&mut options);
    let file = options.open(path)?;
    check_own(&file)?;
    let links = link_count(&file)?;
    if links != 1 {
        return Err(io::Error::other(format!(
            "it has {links} names, a hard link to a file elsewhere"
        )));
    }
    Ok((file, false))
}

#[cfg(unix)]
fn link_count(file: &File) -> io::Result<u64> {
    use std::os::unix::fs::MetadataExt as _;
    Ok(file.metadata()?.nlink())
}

#[cfg(not(unix))]
fn link_count(_: &File) -> io::Result<u64> {
    Ok(1)
}

/// Opens an existing `path` read-only, as [`open_own`] (for the sweep).
pub(crate) fn open_existing_own(path: &Path) -> io::Result<File> {
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    no_follow(&mut options);
    let file = options.open(path)?;
    check_own(&file)?;
    Ok(file)
}

#[cfg(unix)]
fn no_follow(options: &mut std::fs::OpenOptions) {
    use std::os::unix::fs::OpenOptionsExt as _;
    options.custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK | libc::O_CLOEXEC);
}

#[cfg(not(unix))]
fn no_follow(_: &mut std::fs::OpenOptions) {}

/// Whether `e`, from [`open_own`], says that the name holds something that
/// is not v2ref's to use (a link, a folder, a FIFO or device not a regular
/// file, another user's file), rather than that the file system refused.
pub(crate) fn is_not_own(e: &io::Error) -> bool {
    #[cfg(unix)]
    if matches!(
        e.raw_os_error(),
        Some(libc::ELOOP | libc::EISDIR | libc::ENXIO)
    ) {
        return true;
    }
    e.raw_os_error().is_none() && e.kind() == io::ErrorKind::Other
}

fn not_own() -> io::Error {
    io::Error::other("not a regular file of yours")
}

/// Refuses an open file that is not a regular file of this effective user.
#[cfg(unix)]
pub(crate) fn check_own(file: &File) -> io::Result<()> {
    use std::os::unix::fs::MetadataExt as _;
    let m = file.metadata()?;
    // SAFETY: `geteuid` takes no argument and cannot fail.
    let me = unsafe { libc::geteuid() };
    if m.is_file() && m.uid() == me {
        Ok(())
    } else {
        Err(not_own())
    }
}

#[cfg(not(unix))]
pub(crate) fn check_own(file: &File) -> io::Result<()> {
    if file.metadata()?.is_file() {
        Ok(())
    } else {
        Err(not_own())
    }
}

/// Takes an exclusive `flock` on `file` without waiting; false when
/// another open file holds it.
#[cfg(unix)]
pub(crate) fn try_lock(file: &File) -> io::Result<bool> {
    use std::os::unix::io::AsRawFd as _;
    // SAFETY: `flock` only reads its arguments; the descriptor is open for
    // the whole call (borrowed from `file`).
    let r = unsafe { libc::flock(file.as_raw_fd(), libc::LOCK_EX | libc::LOCK_NB) };
    if r == 0 {
        return Ok(true);
    }
    let e = io::Error::last_os_error();
    if e.raw_os_error() == Some(libc::EWOULDBLOCK) {
        Ok(false)
    } else {
        Err(e)
    }
}

#[cfg(not(unix))]
pub(crate) fn try_lock(_: &File) -> io::Result<bool> {
    Ok(true)
}

/// Whether `file` is the entry now at `path` (not followed).
#[cfg(unix)]
pub(crate) fn is_at(file: &File, path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt as _;
    match (file.metadata(), std::fs::symlink_metadata(path)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

#[cfg(not(unix))]
pub(crate) fn is_at(_: &File, _: &Path) -> bool {
    true
}

/// A folder as opened when a run began; names are removed and renamed in
/// it wherever it is moved meanwhile.
pub(crate) struct Folder {
    path: PathBuf,
    #[cfg(unix)]
    dir: File,
}

/// The bytes of `name` as a C string.
#[cfg(unix)]
fn c_name(name: &OsStr) -> io::Result<std::ffi::CString> {
    use std::os::unix::ffi::OsStrExt as _;
    std::ffi::CString::new(name.as_bytes()).map_err(io::Error::other)
}

#[cfg(unix)]
fn status(r: libc::c_int) -> io::Result<()> {
    if r == 0 {
        Ok(())
    } else {
        Err(io::Error::last_os_error())
    }
}

impl Folder {
    /// Opens the folder `path` (as given by the user: a link to a folder
    /// is the folder it names).
    pub(crate) fn open(path: &Path) -> io::Result<Folder> {
        Ok(Folder {
            path: path.to_path_buf(),
            #[cfg(unix)]
            dir: File::open(path)?,
        })
    }

    /// The path the folder had when opened.
    pub(crate) fn path(&self) -> &Path {
        &self.path
    }

    /// Removes the file `name` in the folder.
    #[cfg(unix)]
    pub(crate) fn unlink(&self, name: &OsStr) -> io::Result<()> {
        use std::os::unix::io::AsRawFd as _;
        let name = c_name(name)?;
        // SAFETY: a NUL-terminated name that lives through the call; the
        // descriptor is open (borrowed from `self.dir`).
        status(unsafe { libc::unlinkat(self.dir.as_raw_fd(), name.as_ptr(), 0) })
    }

    #[cfg(not(unix))]
    pub(crate) fn unlink(&self, name: &OsStr) -> io::Result<()> {
        std::fs::remove_file(self.path.join(name))
    }

    /// Renames `from` onto `to` in the folder (replacing a file at `to`).
    #[cfg(unix)]
    pub(crate) fn rename(&self, from: &OsStr, to: &OsStr) -> io::Result<()> {
        use std::os::unix::io::AsRawFd as _;
        let (from, to, fd) = (c_name(from)?, c_name(to)?, self.dir.as_raw_fd());
        // SAFETY: as in `unlink`.
        status(unsafe { libc::renameat(fd, from.as_ptr(), fd, to.as_ptr()) })
    }

    #[cfg(not(unix))]
    pub(crate) fn rename(&self, from: &OsStr, to: &OsStr) -> io::Result<()> {
        std::fs::rename(self.path.join(from), self.path.join(to))
    }

    /// Links `from` at `to` in the folder; fails when `to` exists.
    #[cfg(unix)]
    pub(crate) fn link(&self, from: &OsStr, to: &OsStr) -> io::Result<()> {
        use std::os::unix::io::AsRawFd as _;
        let (from, to, fd) = (c_name(from)?, c_name(to)?, self.dir.as_raw_fd());
        // SAFETY: as in `unlink`; flags 0: a link at `from` is not followed.
        status(unsafe { libc::linkat(fd, from.as_ptr(), fd, to.as_ptr(), 0) })
    }

    #[cfg(not(unix))]
    pub(crate) fn link(&self, from: &OsStr, to: &OsStr) -> io::Result<()> {
        std::fs::hard_link(self.path.join(from), self.path.join(to))
    }

    /// Syncs the folder, so that a rename in it survives a power cut
    /// (ignored where folders cannot be synced).
    pub(crate) fn sync(&self) {
        #[cfg(unix)]
        let _ = self.dir.sync_all();
    }
}
