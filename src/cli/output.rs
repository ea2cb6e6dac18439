//! Where the CLI's output goes, checked: standard output and error, and
//! the folders of `--out`.
//!
//! - A write to standard output that fails is an error (one line on
//!   stderr, status [`EXIT_WRITE_FAILED`]), except a reader that closed the
//!   pipe early (`v2ref claims | head`), which ends the process quietly
//!   with status 0.
//! - Standard error is written without panicking when it cannot be.
//! - An `--out` folder is only replaced when v2ref wrote it (it holds the
//!   [`OUT_MARKER`] file) or it is empty; anything else needs `--force`.

use std::io::{self, Write};
use std::path::Path;
use v2ref::{Error, Result};

/// Exit status when the output cannot be written (sysexits' `EX_IOERR`).
pub const EXIT_WRITE_FAILED: u8 = 74;

/// The file that marks a folder as written by v2ref (`reproduce --out`).
pub const OUT_MARKER: &str = ".v2ref-output";

/// Writes `text` and a newline to standard output; see the module doc for
/// what happens when that fails.
pub fn write_stdout_line(text: std::fmt::Arguments<'_>) {
    let mut out = io::stdout().lock();
    if let Err(e) = writeln!(out, "{text}").and_then(|()| out.flush()) {
        stdout_failed(&e);
    }
}

/// Flushes standard output at the end of a run (see [`write_stdout_line`]).
pub fn flush_stdout() {
    if let Err(e) = io::stdout().lock().flush() {
        stdout_failed(&e);
    }
}

/// Ends the process after a failed write to standard output: quietly with
/// status 0 when the reader went away, else with one line and
/// [`EXIT_WRITE_FAILED`].
fn stdout_failed(e: &io::Error) -> ! {
    if e.kind() == io::ErrorKind::BrokenPipe {
        std::process::exit(0);
    }
    write_stderr_line(format_args!("error: cannot write to standard output: {e}"));
    std::process::exit(i32::from(EXIT_WRITE_FAILED));
}

/// Writes `text` and a newline to standard error, ignoring failure (there
/// is nowhere left to report it).
pub fn write_stderr_line(text: std::fmt::Arguments<'_>) {
    let _ = writeln!(io::stderr().lock(), "{text}");
}

/// Checks that `out` may be replaced by a folder of results before any work
/// is done: a path that does not exist (its parent is created and must be
/// writable), an empty folder, or a folder holding [`OUT_MARKER`]; with
/// `force`, any folder. A file or another kind of entry is refused always.
pub fn check_out_dir(out: &Path, force: bool) -> Result<()> {
    let refuse = |reason: String| Error::Invalid {
        param: "out",
        reason: format!("{}: {reason}", out.display()),
    };
    match std::fs::symlink_metadata(out) {
        Err(e) if e.kind() == io::ErrorKind::NotFound => {}
        Err(e) => return Err(Error::file(Some("out"), out, e)),
        Ok(meta) if !meta.is_dir() => {
            return Err(refuse(
                "exists and is not a folder; give a new folder name".into(),
            ))
        }
        Ok(_) if force || out.join(OUT_MARKER).is_file() || is_empty_dir(out) => {}
        Ok(_) => {
            return Err(refuse(format!(
                "is a folder v2ref did not write (no {OUT_MARKER} in it) and would be replaced; give a new folder or --force"
            )))
        }
    }
    v2ref::reproduction::golden::check_parent_writable(out).map_err(|e| match e {
        Error::Io { path, source, .. } => Error::Io {
            param: Some("out"),
            path,
            source,
        },
        other => other,
    })
}

fn is_empty_dir(dir: &Path) -> bool {
    std::fs::read_dir(dir).is_ok_and(|mut entries| entries.next().is_none())
}

/// Writes the [`OUT_MARKER`] into a folder being filled.
pub fn write_out_marker(dir: &Path) -> Result<()> {
    let path = dir.join(OUT_MARKER);
    let text = concat!(
        "written by v2ref ",
        env!("CARGO_PKG_VERSION"),
        "; v2ref replaces this folder when asked to write here again\n"
    );
    std::fs::write(&path, text).map_err(|e| Error::file(Some("out"), path, e))
}
