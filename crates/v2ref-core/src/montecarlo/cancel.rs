//! Stopping a long computation from outside it (Python's Ctrl-C) within a
//! fraction of a second, however large the request.
//!
//! A caller that may need to stop a computation runs it under a token
//! ([`run_cancellable`]) and gets [`Error::Cancelled`] back when it was
//! cancelled: nothing is returned half done.
//!
//! Only the Monte Carlo's runners look at the token: between two work
//! units ([`super::try_run_unit_range`], [`super::fold_units`]) and after
//! each batch of steps of a long unit ([`super::Steps`]). The error goes
//! back through `Result`, never by unwinding, so cancellation works the
//! same in a build with `panic = "abort"`; the numerical kernels (FFT,
//! interferogram, estimator, tables) know nothing of it.
//!
//! The token is held per thread, so that two computations started from two
//! threads stop independently: [`run_cancellable`] runs the work on a
//! thread pool whose every thread holds the token, and [`super::in_pool`]
//! hands the token of its caller to the threads of any pool it builds.
//! Without a token (the CLI, whose Ctrl-C ends the process; a call from
//! Rust) a check is a thread-local read.

use crate::{Error, Result};
use std::cell::RefCell;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// Elementary operations (a multiply-add, a sine, a random draw) between
/// two checks of a long unit ([`super::Steps`]): 2^20 of them take 1 to
/// 20 ms on one core, so a cancelled computation stops well within a
/// second, and the checks
/// (a thread-local read each) cost nothing measurable.
pub const WORK_PER_CHECK: usize = 1 << 20;

/// Iterations of a loop between two checks when one iteration costs
/// `work_per_item` elementary operations (at least 1).
pub fn stride(work_per_item: usize) -> usize {
    (WORK_PER_CHECK / work_per_item.max(1)).max(1)
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
    /// next check.
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

/// Runs `job` on a thread pool ([`super::pool::default_threads`]
/// threads, fewer when the system refuses them) whose every thread holds
/// `token`, and returns its result, or [`Error::Cancelled`] when `token`
/// was cancelled (whatever the job returned: nothing half done). When no
/// pool can be built at all, `job` runs on the calling thread holding the
/// token.
pub fn run_cancellable<T: Send>(
    token: &Token,
    job: impl FnOnce() -> Result<T> + Send,
) -> Result<T> {
    let for_pool = token.clone();
    let start: super::pool::StartHandler = Arc::new(move |_| hold(Some(for_pool.clone())));
    let out = match super::pool::build_pool(0, Some(start)) {
        Some(pool) => pool.install(job),
        None => {
            let before = current();
            hold(Some(token.clone()));
            let restore = Restore(before);
            let out = job();
            drop(restore);
            out
        }
    };
    if token.is_cancelled() {
        return Err(Error::Cancelled);
    }
    out
}

/// Gives the calling thread back its former token when dropped (also on
/// a panic of the job).
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
        assert_eq!(check(), Ok(())); // no token: nothing happens
        let token = Token::new();
        let finished = run_cancellable(&token, || {
            check()?;
            Ok(current().is_some())
        });
        assert_eq!(finished, Ok(true));
        token.cancel();
        assert_eq!(run_cancellable(&token, check), Err(Error::Cancelled));
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
    fn stride_keeps_the_work_between_checks_bounded() {
        assert_eq!(stride(0), WORK_PER_CHECK);
        assert_eq!(stride(1 << 10), 1 << 10);
        assert_eq!(stride(usize::MAX), 1);
    }
}
