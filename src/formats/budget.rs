//! The memory budget of the readers: what a reader must hold whole (a
//! `.npy` read whole, the columns of an estimates file, the per-row answer
//! of `estimate`) is refused from the file's header when it would exceed
//! it, before anything is read or allocated.

use crate::{Error, Result};
use std::path::Path;

/// The most memory a reader may hold, bytes: half the machine's
/// physical memory, or `V2REF_MAX_MEMORY_GIB` GiB when set (to raise it, or
/// lower it under a memory limit).
pub fn memory_budget() -> u64 {
    if let Some(gib) = std::env::var("V2REF_MAX_MEMORY_GIB")
        .ok()
        .and_then(|v| v.trim().parse::<f64>().ok())
        .filter(|g| g.is_finite() && *g > 0.0)
    {
        return (gib * (1u64 << 30) as f64) as u64;
    }
    physical_memory().map_or(u64::MAX, |m| m / 2)
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
    let budget = memory_budget();
    if need <= budget {
        return Ok(());
    }
    let gib = |b: u64| b as f64 / (1u64 << 30) as f64;
    Err(Error::data(
        param,
        path,
        "header",
        format!(
            "reading it takes {:.2} GiB, more than the memory budget of {:.2} GiB (half the physical memory); raise it with V2REF_MAX_MEMORY_GIB",
            gib(need),
            gib(budget)
        ),
    ))
}
