//! Where the CLI's output goes, checked: standard output and error, and
//! the folders of `--out`.
//!
//! - A write to standard output that fails is an error (one line on
//!   stderr, status [`EXIT_WRITE_FAILED`]); a reader that closed the pipe
//!   early (`v2ref claims | head`) ends the process with the same status
//!   but no message.
//! - [`exit_status`] maps every error to its status: 2 for bad input, 74
//!   for an output that cannot be written.
//! - Standard error is written without panicking when it cannot be.
//! - An `--out` folder is only replaced when v2ref wrote it (it holds the
//!   [`OUT_MARKER`] file) or it is empty; anything else needs `--force`.

use std::io::{self, Write};
use std::path::Path;
use v2ref_core::{Error, Result};

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

/// Ends the process after a failed write to standard output with
/// [`EXIT_WRITE_FAILED`]: quietly when the reader went away, else with one
/// line.
fn stdout_failed(e: &io::Error) -> ! {
    if e.kind() == io::ErrorKind::BrokenPipe {
        // The reader went away (`| head`): nothing was lost that it wanted,
        // so no message, but the output was not all written.
        std::process::exit(i32::from(EXIT_WRITE_FAILED));
    }
    write_stderr_line(format_args!("error: cannot write to standard output: {e}"));
    std::process::exit(i32::from(EXIT_WRITE_FAILED));
}

/// Writes `text` and a newline to standard error, ignoring failure (there
/// is nowhere left to report it). A message may quote a file's name or
/// contents: its control characters are written escaped
/// (`v2ref_commands::text::printable`), never sent to the terminal.
pub fn write_stderr_line(text: std::fmt::Arguments<'_>) {
    let line = text.to_string();
    let line = v2ref_commands::text::printable(&line);
    let _ = writeln!(io::stderr().lock(), "{line}");
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
    v2ref_reproduction::golden::check_parent_writable(out).map_err(|e| match e {
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

/// Runs whose time left at the measured rate exceeds this are noted
/// ([`watch_rate`]), s.
pub const NOTICE_S: f64 = 60.0;

/// How long a run's rate is measured, from its first step.
const RATE_PROBE: std::time::Duration = std::time::Duration::from_secs(2);

/// Longest a run's set-up (no step done yet) is waited for before the
/// watcher gives up on predicting it.
const SETUP_WAIT: std::time::Duration = std::time::Duration::from_secs(600);

/// Redraws `bar` every `interval` from a thread of its own, as indicatif's
/// `enable_steady_tick` does; but where the system refuses the thread (a
/// process limit, `RLIMIT_NPROC`) the bar is redrawn only as it advances,
/// where `enable_steady_tick` panics. The thread ends with the bar.
pub fn steady_tick(bar: &indicatif::ProgressBar, interval: std::time::Duration) {
    let bar = bar.downgrade();
    let _ = std::thread::Builder::new().spawn(move || {
        while let Some(bar) = bar.upgrade() {
            if bar.is_finished() {
                return;
            }
            bar.tick();
            drop(bar);
            std::thread::sleep(interval);
        }
    });
}

/// Where no bar is drawn (stderr not a terminal; on a terminal the bar's
/// ETA says the same): predicts the time left of the run from its measured
/// rate (linear in its steps: trials, rows, scans, grid points) and, when
/// it exceeds [`NOTICE_S`], says so once on stderr, with how to stop it.
/// No law predicts a run before it starts: one timed on one machine was off
/// by more than 2× on another. The rate is measured over [`RATE_PROBE`] from the
/// first step done, not from the start: a set-up that reports no step (the
/// piston sequences `plan --verify` synthesizes before its first scan)
/// says nothing of the rate, and counting it as one step predicted days.
/// Nothing is said of a run that ends sooner, nor when no step is done
/// within the probe (no rate).
pub fn watch_rate(bar: &indicatif::ProgressBar, what: &str) {
    let (bar, what) = (bar.clone(), what.to_owned());
    let start = std::time::Instant::now();
    // Under a process limit there may be no thread for it: then no note.
    let _ = std::thread::Builder::new().spawn(move || {
        let read = || Reading {
            seconds: start.elapsed().as_secs_f64(),
            done: bar.position(),
            finished: bar.is_finished(),
        };
        let len = bar.length().unwrap_or(0);
        if let Some((left, done)) = time_left(len, read, std::thread::sleep) {
            if left > NOTICE_S {
                write_stderr_line(format_args!(
                    "note: {what}: about {} left at the present rate ({done} of {len} steps done); Ctrl-C stops it and leaves no partial output",
                    duration_words(left),
                ));
            }
        }
    });
}

/// A look at a running run: seconds since its start, steps done, whether
/// it has finished.
#[derive(Clone, Copy, Debug)]
struct Reading {
    seconds: f64,
    done: u64,
    finished: bool,
}

/// The seconds left of a run of `len` steps and the steps done when that
/// was measured: the rate is taken from the first reading with a step done
/// (after [`RATE_PROBE`]) to the first reading at least [`RATE_PROBE`]
/// later with more steps done, so that a run whose steps come in blocks
/// longer than the probe (a synth of many rows) is still measured. None
/// when the run finishes first, or nothing moves for [`SETUP_WAIT`].
fn time_left(
    len: u64,
    mut read: impl FnMut() -> Reading,
    mut sleep: impl FnMut(std::time::Duration),
) -> Option<(f64, u64)> {
    let wait = SETUP_WAIT.as_secs_f64();
    sleep(RATE_PROBE);
    let first = loop {
        let r = read();
        if r.finished || r.seconds > wait {
            return None;
        }
        if r.done > 0 {
            break r;
        }
        sleep(RATE_PROBE / 4);
    };
    sleep(RATE_PROBE);
    loop {
        let r = read();
        if r.finished || r.seconds - first.seconds > wait {
            return None;
        }
        let left = seconds_left((first.seconds, first.done), (r.seconds, r.done), len);
        if let Some(left) = left {
            return Some((left, r.done));
        }
        sleep(RATE_PROBE / 4);
    }
}

/// Seconds left of a run of `len` steps at the rate between two readings
/// of (seconds since the start, steps done); None without a rate: no step
/// done at the first reading (the run's set-up is no step) or none between
/// the readings.
fn seconds_left(first: (f64, u64), second: (f64, u64), len: u64) -> Option<f64> {
    let steps = second.1.checked_sub(first.1).filter(|&d| d > 0)?;
    let seconds = second.0 - first.0;
    (first.1 > 0 && seconds > 0.0)
        .then(|| len.saturating_sub(second.1) as f64 * seconds / steps as f64)
}

/// A duration in words: seconds, minutes, hours, days or years.
pub fn duration_words(s: f64) -> String {
    match s {
        s if s < 120.0 => format!("{s:.0} s"),
        s if s < 7200.0 => format!("{:.0} min", s / 60.0),
        s if s < 172_800.0 => format!("{:.1} h", s / 3600.0),
        s if s < 3.2e7 * 2.0 => format!("{:.0} days", s / 86400.0),
        s => format!("{:.0} years", s / 3.156e7),
    }
}

/// The library parameters that name a file the CLI reads: a failure to
/// read one is bad input (status 2) whatever the system said.
const INPUT_FILES: &[&str] = &[
    "input",
    "calibrator",
    "estimates",
    "sidecar",
    "spectrum",
    "truth",
];

/// The exit status of an error: [`EXIT_WRITE_FAILED`] for an output that
/// cannot be written (read-only or full file system, no permission, a
/// closed or failing stream, an answer that cannot be produced), 2 for
/// everything else (bad input, including an output path whose parent
/// folder does not exist or is not a folder).
pub fn exit_status(e: &Error) -> u8 {
    match e {
        Error::Output { .. } => EXIT_WRITE_FAILED,
        Error::Io { param, source, .. } => {
            let input = param.is_some_and(|p| INPUT_FILES.contains(&p));
            // ENOENT, ENOTDIR: the path itself is wrong (a missing parent,
            // a file used as a folder).
            let bad_path =
                source.kind() == io::ErrorKind::NotFound || source.raw_os_error() == Some(20);
            if input || bad_path {
                super::EXIT_BAD_INPUT
            } else {
                EXIT_WRITE_FAILED
            }
        }
        _ => super::EXIT_BAD_INPUT,
    }
}

/// Whether `e` is a write to a pipe whose reader went away.
pub fn is_broken_pipe(e: &Error) -> bool {
    matches!(e, Error::Io { source, .. } if source.kind() == io::ErrorKind::BrokenPipe)
}

#[cfg(test)]
mod tests {
    use super::{duration_words, exit_status, seconds_left, EXIT_WRITE_FAILED};

    #[test]
    fn durations_read_as_words() {
        assert_eq!(duration_words(90.0), "90 s");
        assert_eq!(duration_words(600.0), "10 min");
        assert_eq!(duration_words(10_800.0), "3.0 h");
        assert_eq!(duration_words(7.0 * 86400.0), "7 days");
        assert_eq!(duration_words(1e9), "32 years");
    }

    /// The stall watcher's estimate: from the rate between two readings
    /// once steps are done; silent over a set-up that counts no step (a
    /// rate taken from the start counted 2 s of piston synthesis as one
    /// scan of 100 000: 2.3 days for a run of seconds).
    #[test]
    fn the_time_left_is_taken_from_the_rate_after_the_first_step() {
        // 200 steps in 2 s, 99 700 left: 997 s.
        assert_eq!(seconds_left((10.0, 100), (12.0, 300), 100_000), Some(997.0));
        // Nothing done at the first reading, or between the readings.
        assert_eq!(seconds_left((2.0, 0), (4.0, 5), 100_000), None);
        assert_eq!(seconds_left((2.0, 7), (4.0, 7), 100_000), None);
    }

    /// A run whose steps come in blocks longer than the rate probe (a big
    /// synth: 32 768 rows every 3 s of 1 000 000): two readings one probe
    /// apart see no step between them (as 25b05bd read them: no note,
    /// however long the run), and the watcher reads on until a block comes.
    /// A fake clock: `sleep` moves it, no time passes.
    #[test]
    fn a_run_in_blocks_longer_than_the_probe_is_still_measured() {
        use std::cell::Cell;
        let clock = Cell::new(0.0_f64);
        let done = |t: f64| (t / 3.0).floor() as u64 * 32_768;
        let read = || super::Reading {
            seconds: clock.get(),
            done: done(clock.get()),
            finished: false,
        };
        let sleep = |d: std::time::Duration| clock.set(clock.get() + d.as_secs_f64());
        let (left, at) = super::time_left(1_000_000, read, sleep).expect("a rate");
        assert!(seconds_left((3.0, done(3.0)), (5.0, done(5.0)), 1_000_000).is_none());
        assert_eq!(at, 65_536);
        // 32 768 steps in 3 s (3 s to 6 s), 934 464 left.
        assert!((left - 934_464.0 * 3.0 / 32_768.0).abs() < 1e-6, "{left}");
        assert!(left > super::NOTICE_S);
        // A run that finishes first is not predicted.
        let finished = || super::Reading {
            seconds: 1.0,
            done: 5,
            finished: true,
        };
        assert!(super::time_left(10, finished, |_| {}).is_none());
    }

    use v2ref_core::Error;

    fn io(param: Option<&'static str>, errno: i32) -> Error {
        Error::file(param, "x", std::io::Error::from_raw_os_error(errno))
    }

    #[test]
    fn each_system_error_has_its_status() {
        // EROFS, ENOSPC, EACCES, EPIPE, EIO, EDQUOT on an output: 74.
        for errno in [30, 28, 13, 32, 5, 122] {
            assert_eq!(
                exit_status(&io(Some("out"), errno)),
                EXIT_WRITE_FAILED,
                "{errno}"
            );
            assert_eq!(exit_status(&io(None, errno)), EXIT_WRITE_FAILED, "{errno}");
        }
        // ENOENT, ENOTDIR: the path is wrong, bad input.
        for errno in [2, 20] {
            assert_eq!(exit_status(&io(Some("out"), errno)), 2, "{errno}");
        }
        // Any failure to read an input file is bad input.
        for errno in [13, 5, 21] {
            assert_eq!(exit_status(&io(Some("input"), errno)), 2, "{errno}");
        }
        let refused = Error::Invalid {
            param: "out",
            reason: "exists".into(),
        };
        assert_eq!(exit_status(&refused), 2);
    }
}
