//! `--max-memory-gib`, the memory budget of the commands that read data
//! files (`estimate`, `score`): the library's budget
//! (`v2ref_files::formats::budget`) set for the run.

use v2ref_core::Result;
use v2ref_files::formats::{budget_bytes_of_gib, set_memory_budget_gib};

/// The memory budget flag.
#[derive(Debug, Clone, clap::Args)]
pub struct MemoryArgs {
    /// The most memory, GiB, a reader may hold whole (a .npy read whole,
    /// the columns of an estimates file, estimate's per-row answer): a file
    /// that needs more is refused from its header. Above 0, at most
    /// 1048576; default: V2REF_MAX_MEMORY_GIB when set, else half the
    /// physical memory.
    #[arg(long, value_name = "GIB", value_parser = memory_gib, allow_negative_numbers = true)]
    max_memory_gib: Option<f64>,
}

impl MemoryArgs {
    /// Sets the budget of this run when the flag is given.
    pub fn apply(&self) -> Result<()> {
        match self.max_memory_gib {
            Some(gib) => set_memory_budget_gib(gib),
            None => Ok(()),
        }
    }
}

/// Parses `--max-memory-gib` (clap value parser), checked by the library.
fn memory_gib(s: &str) -> std::result::Result<f64, String> {
    let gib = super::finite_f64(s)?;
    budget_bytes_of_gib(gib).map_err(|e| e.detail())?;
    Ok(gib)
}
