//! Deterministic parallel Monte Carlo: fixed work units, one generator per
//! unit derived from (seed, unit index), results reduced in unit order (the
//! pattern of rand's `examples/rayon-monte-carlo.rs`). The answer is
//! bit-identical whatever the number of threads.
//!
//! Generators are [`Rng`], a v2ref type around `rand_pcg::Pcg64Mcg`
//! (the releases required in `crates/v2ref-core/Cargo.toml`), seeded from a
//! SplitMix64 hash of (seed, unit) so that neighbouring units get unrelated
//! streams.

pub mod cancel;
pub mod pool;
pub(crate) mod statistics;

pub use statistics::{
    effective_count, replicated_summary, replicated_t_quantile, variance_stderr, RunningStats,
    Summary,
};

use rand::{RngCore, SeedableRng};
use rand_pcg::Pcg64Mcg;
use rayon::prelude::*;

/// The generator every Monte Carlo in the crate uses: PCG-64 MCG (O'Neill
/// 2014; 128-bit multiplicative congruential state, XSL RR 64-bit output),
/// the bits of `rand_pcg::Pcg64Mcg` 0.3. A v2ref type with its own methods,
/// so that a pipeline on any rand release draws from it (its own rand
/// traits are not needed, nor ours): wrap [`Rng::next_u64`] in the
/// pipeline's `RngCore` to use its own distributions.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Rng(Pcg64Mcg);

impl Rng {
    /// The generator of the 128-bit state `seed` (little-endian), as
    /// `rand_pcg::Pcg64Mcg::from_seed` (the state's lowest bit is forced to 1).
    pub fn from_seed(seed: [u8; 16]) -> Rng {
        Rng(Pcg64Mcg::from_seed(seed))
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0.next_u64()
    }

    /// A uniform f64 in [0, 1): the top 53 bits of [`Rng::next_u64`] times
    /// 2⁻⁵³ (one draw; every multiple of 2⁻⁵³ below 1 equally likely), the
    /// value of rand 0.8's `Standard` for f64.
    pub fn uniform_f64(&mut self) -> f64 {
        const TWO_POW_MINUS_53: f64 = 1.0 / (1u64 << 53) as f64;
        (self.next_u64() >> 11) as f64 * TWO_POW_MINUS_53
    }

    /// A standard normal draw (mean 0, variance 1): `rand_distr`'s
    /// `StandardNormal` (ziggurat, Marsaglia & Tsang 2000), the Gaussian
    /// draw of every Monte Carlo in the crate.
    pub fn standard_normal(&mut self) -> f64 {
        use rand_distr::Distribution;
        rand_distr::StandardNormal.sample(&mut self.0)
    }

    /// The inner generator, for the crate's `rand_distr` samplers.
    pub(crate) fn rand_core(&mut self) -> &mut Pcg64Mcg {
        &mut self.0
    }
}

/// SplitMix64 finalizer (Steele, Lea & Flood 2014): a bijective 64-bit mix.
fn splitmix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The generator of work unit `unit` for user seed `seed`: its 128-bit
/// state is two SplitMix64 words of (seed, unit).
pub fn unit_rng(seed: u64, unit: u64) -> Rng {
    let a = splitmix64(seed ^ splitmix64(unit));
    let b = splitmix64(a ^ 0xD1B5_4A32_D192_ED03);
    let mut state = [0u8; 16];
    state[..8].copy_from_slice(&a.to_le_bytes());
    state[8..].copy_from_slice(&b.to_le_bytes());
    Rng::from_seed(state)
}

/// Most work units one run accepts: 2^27. A unit is a batch of thousands
/// of trials or rows, 1 ms of one core or more, so 2^27 units are more than
/// 37 hours of one core: past what a run does in a day, and far below a
/// count whose bookkeeping (one result per unit) would exhaust memory.
pub const MAX_UNITS: u64 = 1 << 27;

/// Checks the units of a run: at most [`MAX_UNITS`].
pub fn check_units(range: &std::ops::Range<u64>) -> crate::Result<()> {
    let units = range.end.saturating_sub(range.start);
    if units > MAX_UNITS {
        return Err(crate::Error::OutOfRange {
            param: "units",
            value: units as f64,
            accepted: format!("0 to {MAX_UNITS} work units (2^27) per run"),
        });
    }
    Ok(())
}

/// Runs `work(unit_index, rng)` for `units` work units, on `threads` threads
/// (0 = rayon's default), and returns the results in unit order. Each unit
/// has its own generator from [`unit_rng`], so the results do not depend on
/// the thread count or on scheduling. Refuses more than [`MAX_UNITS`] units
/// and more than [`max_threads`] threads; a cancelled run ([`cancel`])
/// returns [`crate::Error::Cancelled`], checked before each unit.
pub fn run_units<T, F>(seed: u64, units: u64, threads: usize, work: F) -> crate::Result<Vec<T>>
where
    T: Send,
    F: Fn(u64, &mut Rng) -> T + Sync + Send,
{
    run_unit_range(seed, 0..units, threads, work)
}

/// [`run_units`] for the units of `range` only (a run processed in
/// batches: unit u has the same generator whatever batch it is in).
pub fn run_unit_range<T, F>(
    seed: u64,
    range: std::ops::Range<u64>,
    threads: usize,
    work: F,
) -> crate::Result<Vec<T>>
where
    T: Send,
    F: Fn(u64, &mut Rng) -> T + Sync + Send,
{
    try_run_unit_range(seed, range, threads, |u, rng| Ok(work(u, rng)))
}

/// [`run_unit_range`] for work that may fail: the results in unit order,
/// or the error of a unit (the other units stop at once). A cancelled run
/// ([`cancel`]) is checked before each unit and returns
/// [`crate::Error::Cancelled`].
pub fn try_run_unit_range<T, F>(
    seed: u64,
    range: std::ops::Range<u64>,
    threads: usize,
    work: F,
) -> crate::Result<Vec<T>>
where
    T: Send,
    F: Fn(u64, &mut Rng) -> crate::Result<T> + Sync + Send,
{
    check_units(&range)?;
    in_pool(threads, || {
        range
            .into_par_iter()
            .map(|u| {
                cancel::check()?;
                work(u, &mut unit_rng(seed, u))
            })
            .collect::<crate::Result<Vec<T>>>()
    })
}

/// `item(i)` for `i` in `0..n`, in order on the calling thread, for a long
/// deterministic loop that is not a Monte Carlo (an interferogram of a
/// long scan, a finite-scan bias): its items are the units of the run, a
/// cancelled run ([`cancel`]) stopping between them with
/// [`crate::Error::Cancelled`] (checked every [`cancel::stride`] items of
/// `work_per_item` operations, a few milliseconds).
pub fn map_items<T>(
    n: usize,
    work_per_item: usize,
    mut item: impl FnMut(usize) -> T,
) -> crate::Result<Vec<T>> {
    let every = cancel::stride(work_per_item);
    (0..n)
        .map(|i| {
            if i % every == 0 {
                cancel::check()?;
            }
            Ok(item(i))
        })
        .collect()
}

/// Reports the steps of a loop (trials, rows, scans) to a progress
/// callback in batches, each batch about [`cancel::WORK_PER_CHECK`]
/// operations (a call per step would cost more than a short step), with a
/// cancellation check after each; [`Steps::finish`] reports the rest and
/// checks again.
pub struct Steps<'a> {
    progress: &'a (dyn Fn(u64) + Sync),
    every: u64,
    pending: u64,
}

impl<'a> Steps<'a> {
    /// Steps of `work_per_step` elementary operations each, reported to
    /// `progress`.
    pub fn new(progress: &'a (dyn Fn(u64) + Sync), work_per_step: usize) -> Steps<'a> {
        Steps {
            progress,
            every: cancel::stride(work_per_step) as u64,
            pending: 0,
        }
    }

    /// One more step done; [`crate::Error::Cancelled`] when the run was
    /// cancelled ([`cancel::check`]), for the loop to return.
    pub fn step(&mut self) -> crate::Result<()> {
        self.pending += 1;
        if self.pending >= self.every {
            (self.progress)(self.pending);
            self.pending = 0;
            cancel::check()?;
        }
        Ok(())
    }

    /// Reports the steps not yet reported; [`crate::Error::Cancelled`]
    /// when the run was cancelled (a loop shorter than a batch of steps
    /// is checked here only).
    pub fn finish(self) -> crate::Result<()> {
        if self.pending > 0 {
            (self.progress)(self.pending);
        }
        cancel::check()
    }
}

/// Units computed together by [`fold_units`] before their results are
/// merged: enough to keep every core busy, few enough that the results of
/// one batch are small (memory does not grow with the number of units).
pub const FOLD_BATCH_UNITS: u64 = 1024;

/// Runs `work(unit_index, rng)` for the units of `range` as
/// [`run_unit_range`] does, and hands each result to `merge` in unit order,
/// [`FOLD_BATCH_UNITS`] units at a time. Memory is that of one batch of
/// results however many units there are; the answer is the fold of
/// [`run_unit_range`]'s results in unit order, bit for bit, whatever the
/// thread count. The first error of a unit stops the run and is returned;
/// a cancelled run ([`cancel`]) is checked before each unit.
pub fn fold_units<T, F, M>(
    seed: u64,
    range: std::ops::Range<u64>,
    threads: usize,
    work: F,
    merge: M,
) -> crate::Result<()>
where
    T: Send,
    F: Fn(u64, &mut Rng) -> crate::Result<T> + Sync + Send,
    M: FnMut(T) + Send,
{
    check_units(&range)?;
    let mut merge = merge;
    in_pool(threads, || {
        let mut first = range.start;
        while first < range.end {
            let last = first.saturating_add(FOLD_BATCH_UNITS).min(range.end);
            let batch: Vec<T> = (first..last)
                .into_par_iter()
                .map(|u| {
                    cancel::check()?;
                    work(u, &mut unit_rng(seed, u))
                })
                .collect::<crate::Result<Vec<T>>>()?;
            batch.into_iter().for_each(&mut merge);
            first = last;
        }
        Ok(())
    })
}

/// Most worker threads per core a run accepts.
pub const MAX_THREADS_PER_CORE: usize = 4;

/// Fewest worker threads the cap allows, however few the cores (so that
/// the same command runs on a small machine).
pub const MAX_THREADS_FLOOR: usize = 16;

/// The most worker threads a run accepts here: [`MAX_THREADS_PER_CORE`] ×
/// the cores, at least [`MAX_THREADS_FLOOR`]. More only add overhead (the
/// answer never depends on the thread count), and an unbounded request
/// would spawn until the system refuses.
pub fn max_threads() -> usize {
    let cores = std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get);
    (MAX_THREADS_PER_CORE * cores).max(MAX_THREADS_FLOOR)
}

/// Checks a thread count: 0 (all cores) to [`max_threads`].
pub fn check_threads(threads: usize) -> crate::Result<usize> {
    let max = max_threads();
    if threads > max {
        return Err(crate::Error::OutOfRange {
            param: "threads",
            value: threads as f64,
            accepted: format!("0 (all cores) to {max} ({MAX_THREADS_PER_CORE} per core, at least {MAX_THREADS_FLOOR})"),
        });
    }
    Ok(threads)
}

/// Runs `job` on a pool of `threads` threads; 0: the pool the caller runs
/// in (the CLI's, of [`pool::default_threads`]), or a new one of
/// [`pool::default_threads`] outside any pool. Refuses more than
/// [`max_threads`] threads ([`check_threads`]) before spawning any; a
/// system that refuses threads gives fewer ([`pool::build_pool`]).
pub fn in_pool<T: Send>(
    threads: usize,
    job: impl FnOnce() -> crate::Result<T> + Send,
) -> crate::Result<T> {
    in_pool_capped(check_threads(threads)?, job)
}

/// [`in_pool`] with `threads` capped at [`max_threads`] rather than
/// refused (for a caller whose error type is not [`crate::Error`]).
pub fn in_pool_capped<T: Send>(threads: usize, job: impl FnOnce() -> T + Send) -> T {
    let threads = threads.min(max_threads());
    if threads == 0 && rayon::current_thread_index().is_some() {
        return job();
    }
    // The pool's threads work for the caller's computation: they hold its
    // cancellation token ([`cancel`]), if any.
    let token = cancel::current();
    let start: pool::StartHandler = std::sync::Arc::new(move |_| cancel::hold(token.clone()));
    pool::install(threads, Some(start), job)
}

/// The seed of one independent computation of a run: a SplitMix64 hash of
/// the run's seed, a `label` naming what is computed (for example
/// `"fig4"`) and the parameters that identify it (`key`, for example the
/// diameter, fringe frequency and spatial frequency of a point, by their
/// bits).
///
/// This is the crate's one seed-derivation rule. Keying by what is computed,
/// never by a position in a list, makes a point's result independent of the
/// other points asked for in the same run; the hash makes seeds of
/// neighbouring keys unrelated.
///
/// ```
/// use v2ref_core::montecarlo::derive_seed;
/// let a = derive_seed(7, "fig5", &[300.0]);
/// assert_eq!(a, derive_seed(7, "fig5", &[300.0]));
/// assert_ne!(a, derive_seed(7, "fig5", &[1000.0]));
/// assert_ne!(a, derive_seed(7, "fig4", &[300.0]));
/// ```
pub fn derive_seed(seed: u64, label: &str, key: &[f64]) -> u64 {
    let words = label
        .bytes()
        .map(u64::from)
        .chain(key.iter().map(|x| x.to_bits()));
    words.fold(splitmix64(seed), |h, w| splitmix64(h ^ w))
}
