//! Worker pools the system may refuse: a process limit (`RLIMIT_NPROC`),
//! a container's task limit or a full thread table give fewer threads than
//! asked, down to the calling thread alone, never a panic (rayon's own
//! global pool panics when it cannot start). The answer does not depend on
//! the thread count, only the time does.
//!
//! How many threads "all cores" means: `RAYON_NUM_THREADS` when it is a
//! positive integer, else the cores, and never more than
//! [`super::max_threads`] (the cap of `--threads`).

use rayon::{ThreadPool, ThreadPoolBuilder};
use std::sync::{Arc, OnceLock};

/// The stack of a worker: the main thread's usual 8 MiB, so that a
/// computation moved off the main thread has the same room.
const WORKER_STACK_BYTES: usize = 8 << 20;

/// What is done at the start of each worker (hold a cancellation token).
pub type StartHandler = Arc<dyn Fn(usize) + Send + Sync>;

/// Who is told when fewer threads run than asked (the CLI: one line on
/// stderr), with the threads asked and those granted.
static NOTICE: OnceLock<fn(usize, usize)> = OnceLock::new();

/// Sets who is told when the system grants fewer threads than asked (once
/// per process; later calls are ignored).
pub fn set_fewer_threads_notice(notice: fn(asked: usize, granted: usize)) {
    let _ = NOTICE.set(notice);
}

/// The threads of "all cores" (`threads = 0`): `RAYON_NUM_THREADS` when it
/// is a positive integer, else the cores; at most [`super::max_threads`].
pub fn default_threads() -> usize {
    let cores = std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get);
    let asked = std::env::var("RAYON_NUM_THREADS")
        .ok()
        .and_then(|v| v.trim().parse::<usize>().ok())
        .filter(|&n| n > 0)
        .unwrap_or(cores);
    asked.min(super::max_threads())
}

/// A pool of `threads` workers (0: [`default_threads`]), or, when the
/// system refuses that many, of half as many, and so on, down to a pool
/// made of the calling thread alone; the shortfall is told to the notice
/// ([`set_fewer_threads_notice`]). None only when not even that can be
/// made (the calling thread already works for another pool).
pub fn build_pool(threads: usize, start: Option<StartHandler>) -> Option<ThreadPool> {
    let asked = if threads == 0 {
        default_threads()
    } else {
        threads
    };
    let builder = |n: usize| {
        let b = ThreadPoolBuilder::new()
            .num_threads(n)
            .stack_size(WORKER_STACK_BYTES);
        match start.clone() {
            Some(s) => b.start_handler(move |i| s(i)),
            None => b,
        }
    };
    let mut n = asked.max(1);
    loop {
        if let Ok(pool) = builder(n).build() {
            tell(asked, n);
            return Some(pool);
        }
        if n == 1 {
            break;
        }
        n /= 2;
    }
    let pool = builder(1).use_current_thread().build().ok()?;
    tell(asked, 1);
    Some(pool)
}

fn tell(asked: usize, granted: usize) {
    if granted < asked {
        if let Some(notice) = NOTICE.get() {
            notice(asked, granted);
        }
    }
}

/// Runs `job` on a pool of `threads` workers ([`build_pool`]), or on the
/// calling thread when no pool can be made.
pub fn install<T: Send>(
    threads: usize,
    start: Option<StartHandler>,
    job: impl FnOnce() -> T + Send,
) -> T {
    match build_pool(threads, start) {
        Some(pool) => pool.install(job),
        None => job(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_is_capped_and_a_pool_has_what_it_asked() {
        assert!(default_threads() >= 1 && default_threads() <= super::super::max_threads());
        let pool = build_pool(3, None).unwrap();
        assert_eq!(pool.current_num_threads(), 3);
    }
}
