//! Python bindings: the extension module `v2ref._v2ref`
//! that the Python package `v2ref` (`python/v2ref/`) wraps. A thin layer:
//! convert, call the library, convert back. Answers that the CLI prints as
//! JSON come back as Python objects made from the same fields (dicts and
//! lists, [`values`]; no JSON text in between), per-row estimates and
//! interferograms as NumPy arrays.
//!
//! Long calls release the GIL and run on worker threads; the calling
//! thread checks for signals every 100 ms and, on Ctrl-C, raises
//! `KeyboardInterrupt` after stopping the work at its next unit boundary
//! ([`crate::montecarlo::cancel`]).

// The modules of the crates below under their own names, so that a path
// reads the same in every crate of the workspace (`crate::formalism::…`).
#[allow(unused_imports)]
use v2ref_commands::{commands, parameters, plan, record, report};
#[allow(unused_imports)]
use v2ref_core::{
    bias, bounds, conformance, error, formalism, montecarlo, noise, piston, simulator, words,
    Error, Result,
};
#[allow(unused_imports)]
use v2ref_files::{atomic, formats};
use v2ref_reproduction as reproduction;

mod answers;
mod inputs;
mod oifits;
pub mod output;
mod units;
pub mod values;

use crate::montecarlo::cancel::{run_cancellable, Token};
use pyo3::exceptions::{PyKeyboardInterrupt, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Condvar, Mutex};
use std::time::Duration;

/// The keyword that sets the library parameter `param`
/// ([`crate::parameters::keyword_of`]; the interferograms are `input` to
/// the library and the CLI).
pub fn keyword_of(param: &str) -> String {
    match param {
        "input" => "interferograms".into(),
        p => crate::parameters::keyword_of(p),
    }
}

/// The message of a library error: `keyword: detail`.
pub fn message(e: &Error) -> String {
    let line = match e.param() {
        Some(p) => format!("{}: {}", keyword_of(p), e.detail()),
        None => e.detail(),
    };
    line.replace('\n', " ")
}

/// Library errors as Python exceptions (ValueError, or OSError for a file
/// that cannot be read).
pub trait Fail {
    /// The Python exception.
    fn into_py_err(self) -> PyErr;
}

impl Fail for Error {
    fn into_py_err(self) -> PyErr {
        match &self {
            Error::Io { .. } => pyo3::exceptions::PyOSError::new_err(message(&self)),
            Error::Cancelled => PyKeyboardInterrupt::new_err("interrupted"),
            _ => PyValueError::new_err(message(&self)),
        }
    }
}

/// `Result<T, Error>` to `PyResult<T>`.
pub fn ok<T>(r: crate::Result<T>) -> PyResult<T> {
    r.map_err(Fail::into_py_err)
}

/// Runs `work` on threads of its own with the GIL released, handing it a
/// progress callback; checks for signals (Ctrl-C) every 100 ms meanwhile.
/// On a signal the work is cancelled ([`crate::montecarlo::cancel`]: it stops at its
/// next unit or batch of steps, a few milliseconds of work away) and the signal's
/// exception is raised once its threads have stopped. A panic in the work
/// becomes a `RuntimeError` (nothing unwinds into Python).
pub fn interruptible<T: Send>(
    py: Python<'_>,
    work: impl FnOnce(&(dyn Fn(u64) + Sync)) -> crate::Result<T> + Send,
) -> PyResult<T> {
    let token = Token::new();
    // The loops check the token themselves after each progress report
    // (crate::montecarlo::Steps).
    let tick = |_: u64| {};
    let finished = (Mutex::new(false), Condvar::new());
    std::thread::scope(|s| {
        let handle = s.spawn(|| {
            let out = catch_unwind(AssertUnwindSafe(|| run_cancellable(&token, || work(&tick))));
            let (lock, cvar) = &finished;
            *lock.lock().unwrap_or_else(|e| e.into_inner()) = true;
            cvar.notify_all();
            out
        });
        let mut interrupted: Option<PyErr> = None;
        loop {
            let done = py.allow_threads(|| {
                let (lock, cvar) = &finished;
                let guard = lock.lock().unwrap_or_else(|e| e.into_inner());
                let (guard, _) = cvar
                    .wait_timeout_while(guard, Duration::from_millis(100), |done| !*done)
                    .unwrap_or_else(|e| e.into_inner());
                let done = *guard;
                drop(guard);
                (done, enter_python_or_park(&token))
            });
            let (done, entered) = done;
            if done {
                drop(entered);
                break;
            }
            if interrupted.is_none() {
                if let Err(e) = py.check_signals() {
                    token.cancel();
                    interrupted = Some(e);
                }
            }
            drop(entered);
        }
        let (out, _entered) = py.allow_threads(|| {
            let out = handle.join();
            (out, enter_python_or_park(&token))
        });
        let out = match out {
            Ok(r) => r,
            Err(p) => Err(p),
        };
        match (interrupted, out) {
            (Some(e), _) => Err(e),
            // A cancelled run (the interpreter ending) is a KeyboardInterrupt.
            (None, Ok(r)) => ok(r),
            (None, Err(p)) => {
                let what = p
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| p.downcast_ref::<&str>().map(|s| (*s).to_owned()))
                    .unwrap_or_else(|| "unknown".into());
                Err(PyRuntimeError::new_err(format!(
                    "internal error (please report): {what}"
                )))
            }
        }
    })
}

/// Set by the interpreter's `atexit`: the interpreter is ending.
static EXITING: AtomicBool = AtomicBool::new(false);

/// Threads of [`interruptible`] that found [`EXITING`] unset and are taking
/// the GIL back (or hold it) with Rust frames on their stack.
static ENTERING: AtomicUsize = AtomicUsize::new(0);

/// Longest [`mark_exiting`] waits for the threads counted in [`ENTERING`].
const EXIT_WAIT: Duration = Duration::from_secs(5);

/// Called at exit (registered with `atexit`): the calls still running on
/// daemon threads stop, and never take the GIL back. A thread that checked
/// [`EXITING`] just before it was set may already wait for the GIL: the
/// GIL is released until every such thread has left (it holds the GIL only
/// for a signal check), so that none is still waiting when the
/// interpreter starts ending threads that take it (by an unwind that Rust
/// cannot pass: an abort).
#[pyfunction]
fn mark_exiting(py: Python<'_>) {
    EXITING.store(true, Ordering::SeqCst);
    py.allow_threads(|| {
        let start = std::time::Instant::now();
        while ENTERING.load(Ordering::SeqCst) > 0 && start.elapsed() < EXIT_WAIT {
            std::thread::sleep(Duration::from_millis(1));
        }
    });
}

/// A thread counted in [`ENTERING`] until dropped (after it has left the
/// GIL's section of [`interruptible`]).
struct Entered;

impl Drop for Entered {
    fn drop(&mut self) {
        ENTERING.fetch_sub(1, Ordering::SeqCst);
    }
}

/// Before taking the GIL back: counts the thread in [`ENTERING`] or, when
/// the interpreter is ending, cancels the work and parks the thread (a
/// daemon thread: the process ends around it). Counting before checking
/// (both sequentially consistent) leaves no gap: either this thread sees
/// [`EXITING`], or [`mark_exiting`] sees it counted and waits for it.
fn enter_python_or_park(token: &Token) -> Entered {
    ENTERING.fetch_add(1, Ordering::SeqCst);
    if EXITING.load(Ordering::SeqCst) {
        ENTERING.fetch_sub(1, Ordering::SeqCst);
        token.cancel();
        loop {
            std::thread::park();
        }
    }
    Entered
}

/// The extension module `v2ref._v2ref`.
#[pymodule]
fn _v2ref(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    inputs::register(m)?;
    m.add(
        "ESTIMATE_COLUMNS",
        crate::commands::ESTIMATE_COLUMNS.to_vec(),
    )?;
    oifits::register(m)?;
    // A daemon thread still in a call at exit must not take the GIL back
    // (Python would end it by unwinding through Rust: an abort).
    let atexit = m.py().import("atexit")?;
    atexit.call_method1("register", (wrap_pyfunction!(mark_exiting, m)?,))?;
    units::register(m)?;
    answers::register(m)
}
