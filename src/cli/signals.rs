//! The terminating signals of the command line: SIGINT (Ctrl-C), SIGTERM
//! and SIGHUP each stop a run at once. The temporaries of the run are
//! removed (a set being put in place is finished first, which takes
//! microseconds), one line says which signal stopped it, and the status is
//! 128 + the signal's number: 130 (SIGINT), 143 (SIGTERM), 129 (SIGHUP).
//!
//! The signals are blocked in every thread (set before any thread starts,
//! inherited by the worker pools) and taken by one thread that waits for
//! them (`sigwait`), so the cleanup runs as ordinary code, not in a signal
//! handler. SIGINT is taken even where the shell started v2ref with it
//! ignored (a background job); SIGHUP ignored at the start (`nohup`) stays
//! ignored.

/// Installs the handling of the terminating signals; call first in `main`,
/// before any thread starts.
pub fn install() {
    #[cfg(unix)]
    unix::install();
}

/// Ends the process after `signal` (its name, its number).
fn stop(name: &str, number: i32) -> ! {
    v2ref_files::cleanup::remove_all();
    super::output::write_stderr_line(format_args!("interrupted ({name})"));
    std::process::exit(128 + number);
}

#[cfg(unix)]
mod unix {
    use libc::{c_int, sigset_t, SIGHUP, SIGINT, SIGTERM};

    fn name(signal: c_int) -> &'static str {
        match signal {
            SIGINT => "SIGINT",
            SIGTERM => "SIGTERM",
            SIGHUP => "SIGHUP",
            _ => "a signal",
        }
    }

    /// Whether `signal` was ignored when the process started.
    fn ignored(signal: c_int) -> bool {
        // SAFETY: a zeroed sigaction is a valid value to be overwritten;
        // a null new action only reads the current one.
        unsafe {
            let mut old: libc::sigaction = std::mem::zeroed();
            libc::sigaction(signal, std::ptr::null(), &mut old) == 0
                && old.sa_sigaction == libc::SIG_IGN
        }
    }

    pub(super) fn install() {
        // No thread runs yet, so every later thread inherits the mask set here.
        // SAFETY: the set is initialised by sigemptyset before use; the calls
        // only change this process's signal dispositions and this thread's mask.
        let set = unsafe {
            let mut set: sigset_t = std::mem::zeroed();
            libc::sigemptyset(&mut set);
            for signal in [SIGINT, SIGTERM, SIGHUP] {
                if signal == SIGHUP && ignored(SIGHUP) {
                    continue;
                }
                // A blocked but ignored signal would be discarded.
                libc::signal(signal, libc::SIG_DFL);
                libc::sigaddset(&mut set, signal);
            }
            libc::pthread_sigmask(libc::SIG_BLOCK, &set, std::ptr::null_mut());
            set
        };
        let spawned = std::thread::Builder::new()
            .name("signals".into())
            .spawn(move || loop {
                let mut signal: c_int = 0;
                // SAFETY: `set` is an initialised signal set owned by this
                // thread; `signal` is a valid place for the answer.
                if unsafe { libc::sigwait(&set, &mut signal) } == 0 {
                    super::stop(name(signal), signal);
                }
            });
        if spawned.is_err() {
            // No thread for them: the signals' default action (the process
            // ends; its temporaries are removed by a later run).
            // SAFETY: unblocks the signals blocked above in this thread.
            unsafe {
                libc::pthread_sigmask(libc::SIG_UNBLOCK, &set, std::ptr::null_mut());
            }
        }
    }
}
