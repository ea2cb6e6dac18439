//! Stopping a long computation from outside it (Python's Ctrl-C) within a
//! fraction of a second, however large the request.
//!
//! A caller that may need to stop a computation runs it under a token
//! ([`run_cancellable`]); the library's long loops call [`checkpoint`] every
//! [`WORK_PER_CHECKPOINT`] elementary operations or so (a few milliseconds
//! of one core), and the first checkpoint after [`Token::cancel`] unwinds
//! the computation with the payload [`Cancelled`], which the caller catches.
//! Nothing is returned half done: the unwind drops every partial result.
//!
//! The token is held per thread, so that two computations started from two
//! threads stop independently: [`run_cancellable`] runs the work on a
//! thread pool whose every thread holds the token, and
//! [`crate::montecarlo::in_pool`] hands the token of its caller to the
//! threads of any pool it builds. Without a token (the CLI, whose Ctrl-C
//! ends the process; a call from Rust) a checkpoint is a thread-local read.

use std::cell::RefCell;
use std::panic::resume_unwind;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// The unwind payload of a cancelled computation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cancelled;

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

/// Unwinds with [`Cancelled`] when the calling thread's computation was
/// cancelled; otherwise returns at once.
pub fn checkpoint() {
    let cancelled = CURRENT.with(|c| c.borrow().as_ref().is_some_and(Token::is_cancelled));
    if cancelled {
        resume_unwind(Box::new(Cancelled));
    }
}

/// Runs `job` on a thread pool ([`crate::montecarlo::pool::default_threads`]
/// threads, fewer when the system refuses them) whose every thread holds
/// `token`, and returns its result; a cancelled job unwinds with
/// [`Cancelled`] out of this call. When no pool can be built at all, `job`
/// runs on the calling thread holding the token.
pub fn run_cancellable<T: Send>(token: &Token, job: impl FnOnce() -> T + Send) -> T {
    let for_pool = token.clone();
    let start: crate::montecarlo::pool::StartHandler =
        Arc::new(move |_| hold(Some(for_pool.clone())));
    match crate::montecarlo::pool::build_pool(0, Some(start)) {
        Some(pool) => pool.install(job),
        None => {
            let before = current();
            hold(Some(token.clone()));
            let restore = Restore(before);
            let out = job();
            drop(restore);
            out
        }
    }
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
    use std::panic::catch_unwind;

    #[test]
    fn a_checkpoint_unwinds_only_a_cancelled_computation() {
        checkpoint(); // no token: nothing happens
        let token = Token::new();
        let finished = run_cancellable(&token, || {
            checkpoint();
            current().is_some()
        });
        assert!(finished);
        token.cancel();
        let stopped = catch_unwind(|| run_cancellable(&token, checkpoint));
        let payload = stopped.expect_err("the cancelled job unwinds");
        assert!(payload.is::<Cancelled>());
        // The calling thread was never given the token.
        assert!(current().is_none());
    }

    #[test]
    fn the_workers_of_a_cancellable_computation_hold_its_token() {
        use rayon::prelude::*;
        let token = Token::new();
        let held = run_cancellable(&token, || {
            (0..64)
                .into_par_iter()
                .map(|_| current().is_some())
                .collect::<Vec<_>>()
        });
        assert!(held.iter().all(|&h| h));
    }

    #[test]
    fn stride_keeps_the_work_between_checkpoints_bounded() {
        assert_eq!(stride(0), WORK_PER_CHECKPOINT);
        assert_eq!(stride(1 << 10), 1 << 10);
        assert_eq!(stride(usize::MAX), 1);
    }
}
