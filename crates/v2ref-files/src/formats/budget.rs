//! The memory budget of the readers: what a reader must hold whole (a
//! `.npy` read whole, the columns of an estimates file, the per-row answer
//! of `estimate`) is refused from the file's header when it would exceed
//! it, before anything is read or allocated.
//!
//! The budget is, first found: what the process set
//! ([`set_memory_budget_gib`]: the CLI's `--max-memory-gib`), the
//! environment's `V2REF_MAX_MEMORY_GIB`, or half the physical memory.

use crate::{Error, Result};
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

/// The environment variable that sets the budget, GiB.
pub const MEMORY_BUDGET_ENV: &str = "V2REF_MAX_MEMORY_GIB";

/// The largest budget that may be set, GiB (1 PiB: beyond any machine's
/// memory, far below 2^64 bytes).
pub const MAX_MEMORY_GIB: f64 = 1048576.0;

/// The budget the process set, bytes; 0 when it set none.
static SET_BUDGET_BYTES: AtomicU64 = AtomicU64::new(0);

const GIB: f64 = (1u64 << 30) as f64;

/// What a budget is, in words.
const ACCEPTED: &str = "a number of GiB above 0 and at most 1048576";

/// Checks a budget of `gib` GiB: a number above 0 and at most
/// `MAX_MEMORY_GIB`; returns it in bytes (at least 1).
pub fn budget_bytes_of_gib(gib: f64) -> Result<u64> {
    if !(gib.is_finite() && gib > 0.0 && gib <= MAX_MEMORY_GIB) {
        return Err(Error::Invalid {
            param: "max_memory_gib",
            reason: format!("{gib} GiB; the memory budget is {ACCEPTED}"),
        });
    }
    Ok(((gib * GIB) as u64).max(1))
}

/// Sets the budget of this process to `gib` GiB (in place of
/// `V2REF_MAX_MEMORY_GIB` and of the default), checked as
/// [`budget_bytes_of_gib`] does.
pub fn set_memory_budget_gib(gib: f64) -> Result<()> {
    SET_BUDGET_BYTES.store(budget_bytes_of_gib(gib)?, Ordering::Relaxed);
    Ok(())
}

/// The most memory a reader may hold, bytes (see the module doc). A
/// `V2REF_MAX_MEMORY_GIB` that is not a budget is refused, naming it.
pub fn memory_budget() -> Result<u64> {
    match SET_BUDGET_BYTES.load(Ordering::Relaxed) {
        0 => {}
        set => return Ok(set),
    }
    if let Some(text) = std::env::var_os(MEMORY_BUDGET_ENV) {
        let gib = text.to_str().and_then(|t| t.trim().parse::<f64>().ok());
        return gib
            .and_then(|g| budget_bytes_of_gib(g).ok())
            .ok_or_else(|| Error::Invalid {
                param: "max_memory_gib",
                reason: format!("{MEMORY_BUDGET_ENV}={text:?} is not a memory budget; {ACCEPTED}"),
            });
    }
    Ok(physical_memory().map_or(u64::MAX, |m| m / 2))
}

/// Where the budget in force comes from, in words (for a refusal).
fn budget_source() -> &'static str {
    if SET_BUDGET_BYTES.load(Ordering::Relaxed) != 0 {
        "as set by --max-memory-gib"
    } else if std::env::var_os(MEMORY_BUDGET_ENV).is_some() {
        "as set by V2REF_MAX_MEMORY_GIB"
    } else {
        "half the physical memory"
    }
}

#[cfg(unix)]
fn physical_memory() -> Option<u64> {
    // SAFETY: sysconf only reads a system constant.
    let (pages, size) = unsafe {
        (
            libc::sysconf(libc::_SC_PHYS_PAGES),
            libc::sysconf(libc::_SC_PAGESIZE),
        )
    };
    let (pages, size) = (u64::try_from(pages).ok()?, u64::try_from(size).ok()?);
    pages.checked_mul(size)
}

#[cfg(not(unix))]
fn physical_memory() -> Option<u64> {
    None
}

/// Refuses, from a header, `need` bytes of answer or data of the file
/// `path` that would not fit in [`memory_budget`].
pub fn check_budget(need: u64, param: &'static str, path: &Path) -> Result<()> {
    let budget = memory_budget()?;
    if need <= budget {
        return Ok(());
    }
    Err(over_budget(need, budget, param, path, "header", ""))
}

/// The refusal of `need` bytes (`more`: "more than " when reading stopped
/// there) over `budget`, at `location` of `path`.
pub fn over_budget(
    need: u64,
    budget: u64,
    param: &'static str,
    path: &Path,
    location: &str,
    more: &str,
) -> Error {
    let gib = |b: u64| b as f64 / GIB;
    Error::data(
        param,
        path,
        location,
        format!(
            "reading it takes {more}{:.2} GiB, more than the memory budget of {:.2} GiB ({}); raise it with --max-memory-gib (or V2REF_MAX_MEMORY_GIB)",
            gib(need),
            gib(budget),
            budget_source()
        ),
    )
}
