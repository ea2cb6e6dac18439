//! Stopping a long computation from outside it (Python's Ctrl-C) within a
//! fraction of a second, however large the request.
//!
//! A caller that may need to stop a computation runs it under a token
//! ([`run_cancellable`]) and gets [`Error::Cancelled`] back when it was
//! cancelled: nothing is returned half done.
//!
//! The library's loops look at the token every [`WORK_PER_CHECKPOINT`]
//! elementary operations or so (a few milliseconds of one core), in two
//! ways:
//! - the Monte Carlo loops (trials, rows, scans: [`crate::montecarlo::Steps`])
//!   and the loops of a function that returns a [`Result`] call [`check`],
//!   which returns [`Error::Cancelled`] through their `Result`: no unwinding,
//!   so cancellation works the same in a build with `panic = "abort"`;
//! - the deterministic numerics that return no `Result` (a spectral grid,
//!   an interferogram, an FFT, the exact window statistics) call
//!   [`checkpoint`], which unwinds with the payload [`Cancelled`] where
//!   panics unwind (the Python package, the CLI), caught by
//!   [`run_cancellable`]. Built with `panic = "abort"`, a checkpoint does
//!   nothing: such a computation runs to its end, and the cancellation is
//!   returned at the next [`check`] or by [`run_cancellable`].
//!
//! The token is held per thread, so that two computations started from two
//! threads stop independently: [`run_cancellable`] runs the work on a
//! thread pool whose every thread holds the token, and
//! [`crate::montecarlo::in_pool`] hands the token of its caller to the
//! threads of any pool it builds. Without a token (the CLI, whose Ctrl-C
//! ends the process; a call from Rust) a check is a thread-local read.

use crate::{Error, Result};
use std::cell::RefCell;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// The unwind payload of a [`checkpoint`] of a cancelled computation
/// (never seen by a caller of [`run_cancellable`], which returns
/// [`Error::Cancelled`] instead).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cancelled;

impl From<Cancelled> for Error {
    fn from(_: Cancelled) -> Error {
        Error::Cancelled
    }
}

/// Elementary operations (a multiply-add, a sine, a random draw) between
/// two checkpoints of a loop: 2^20 of them take 1 to 20 ms on one core, so
/// a cancelled computation stops well within a second, and the checkpoints
/// (a thread-local read each) cost nothing measurable.
pub const WORK_PER_CHECKPOINT: usize = 1 << 20;

/// Iterations of a loop between two checkpoints when one iteration costs
/// `work_per_item` elementary operations (at least 1).
pub fn stride(work_per_item: usize) -> usize {
    (WORK_PER_CHECKPOINT / work_per_item.max(1)).max(1)
}

/// A cancellation flag shared by the threads of one computation.
#[derive(Debug, Clone, Default)]
pub struct Token(Arc<AtomicBool>);

impl Token {
    /// A token not cancelled.
    pub fn new() -> Token {
        Token::default()
    }

    /// Cancels the computations holding this token at their next
    /// [`checkpoint`].
    pub fn cancel(&self) {
        self.0.store(true, Ordering::Relaxed);
    }

    /// Whether [`Token::cancel`] was called.
    pub fn is_cancelled(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }
}

thread_local! {
    /// The token of the computation this thread works for, if any.
    static CURRENT: RefCell<Option<Token>> = const { RefCell::new(None) };
}

/// The token of the calling thread, if it works for a cancellable
/// computation.
pub fn current() -> Option<Token> {
    CURRENT.with(|c| c.borrow().clone())
}

/// Makes `token` the calling thread's (for a pool's start handler: the
/// thread works only for that computation).
pub fn hold(token: Option<Token>) {
    CURRENT.with(|c| *c.borrow_mut() = token);
}

/// Whether the calling thread's computation was cancelled.
fn cancelled() -> bool {
    CURRENT.with(|c| c.borrow().as_ref().is_some_and(Token::is_cancelled))
}

/// [`Error::Cancelled`] when the calling thread's computation was
/// cancelled; otherwise `Ok` at once. For loops that return a [`Result`].
pub fn check() -> Result<()> {
    if cancelled() {
        Err(Error::Cancelled)
    } else {
        Ok(())
    }
}

/// For loops that return no [`Result`]: unwinds with [`Cancelled`] (caught
/// by [`run_cancellable`]) when the calling thread's computation was
/// cancelled, where panics unwind; does nothing in a build with
/// `panic = "abort"` (the computation then runs to its end).
pub fn checkpoint() {
    #[cfg(panic = "unwind")]
    if cancelled() {
        std::panic::resume_unwind(Box::new(Cancelled));
    }
}

/// Runs `job` on a thread pool ([`crate::montecarlo::pool::default_threads`]
/// threads, fewer when the system refuses them) whose every thread holds
/// `token`, and returns its result, or [`Error::Cancelled`] when `token`
/// was cancelled (whatever the job returned: nothing half done). When no
/// pool can be built at all, `job` runs on the calling thread holding the
/// token. A panic of the job other than a [`checkpoint`]'s goes on.
pub fn run_cancellable<T: Send>(
    token: &Token,
    job: impl FnOnce() -> Result<T> + Send,
) -> Result<T> {
    let for_pool = token.clone();
    let start: crate::montecarlo::pool::StartHandler =
        Arc::new(move |_| hold(Some(for_pool.clone())));
    let out = match crate::montecarlo::pool::build_pool(0, Some(start)) {
        Some(pool) => pool.install(|| catch_checkpoint(job)),
        None => {
            let before = current();
            hold(Some(token.clone()));
            let restore = Restore(before);
            let out = catch_checkpoint(job);
            drop(restore);
            out
        }
    };
    if token.is_cancelled() {
        return Err(Error::Cancelled);
    }
    out
}

/// `job`'s result, or [`Error::Cancelled`] when a [`checkpoint`] unwound it.
fn catch_checkpoint<T>(job: impl FnOnce() -> Result<T>) -> Result<T> {
    #[cfg(panic = "unwind")]
    {
        use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
        // The job's state is dropped with the unwind: nothing of it is used.
        match catch_unwind(AssertUnwindSafe(job)) {
            Ok(out) => out,
            Err(payload) if payload.is::<Cancelled>() => Err(Error::Cancelled),
            Err(payload) => resume_unwind(payload),
        }
    }
    #[cfg(not(panic = "unwind"))]
    job()
}

/// Gives the calling thread back its former token when dropped (also on
/// an unwind).
struct Restore(Option<Token>);

impl Drop for Restore {
    fn drop(&mut self) {
        hold(self.0.take());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cancelled_computation_returns_the_error() {
        checkpoint(); // no token: nothing happens
        assert_eq!(check(), Ok(()));
        let token = Token::new();
        let finished = run_cancellable(&token, || {
            checkpoint();
            check()?;
            Ok(current().is_some())
        });
        assert_eq!(finished, Ok(true));
        token.cancel();
        // Through a check (a Result), and through a checkpoint (caught).
        assert_eq!(run_cancellable(&token, check), Err(Error::Cancelled));
        let unwound = run_cancellable(&token, || {
            checkpoint();
            Ok(())
        });
        assert_eq!(unwound, Err(Error::Cancelled));
        // Cancelled, a job that ended well returns the error all the same.
        assert_eq!(run_cancellable(&token, || Ok(1)), Err(Error::Cancelled));
        // The calling thread was never given the token.
        assert!(current().is_none());
    }

    #[test]
    fn other_panics_of_a_cancellable_computation_go_on() {
        let token = Token::new();
        let out = std::panic::catch_unwind(|| {
            run_cancellable(&token, || -> Result<()> { panic!("a bug") })
        });
        let payload = out.expect_err("the panic goes on");
        assert_eq!(payload.downcast_ref::<&str>(), Some(&"a bug"));
    }

    #[test]
    fn the_workers_of_a_cancellable_computation_hold_its_token() {
        use rayon::prelude::*;
        let token = Token::new();
        let held = run_cancellable(&token, || {
            Ok((0..64)
                .into_par_iter()
                .map(|_| current().is_some())
                .collect::<Vec<_>>())
        });
        assert!(held.unwrap().iter().all(|&h| h));
    }

    #[test]
    fn stride_keeps_the_work_between_checkpoints_bounded() {
        assert_eq!(stride(0), WORK_PER_CHECKPOINT);
        assert_eq!(stride(1 << 10), 1 << 10);
        assert_eq!(stride(usize::MAX), 1);
    }
}
