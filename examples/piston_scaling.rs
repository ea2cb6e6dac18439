//! Scaling of the piston Monte Carlo with the thread count: the full Fig. 5
//! (both panels: 32 fringe frequencies × 10 000 scans, sampled and
//! integrating detectors on the same sequences), timed on 1, 2, 4, … threads,
//! with a digest of the runs to show the bits do not move.
//!
//! ```sh
//! cargo run --release --example piston_scaling -- [quick|full] [--repeats R] [THREADS ...]
//! cargo run --release --example piston_scaling -- full --repeats 3 1 2 4 8 16
//! ```
//!
//! Prints one line per thread count: `threads best_seconds speedup_vs_first
//! digest`, and exits non-zero if two digests differ. The measured timings
//! are in `docs/performance.md`.

use std::time::Instant;
use v2ref_core::montecarlo::in_pool;
use v2ref_reproduction::cases::{
    fig5_frequencies, fig5_size, paper_turbulence, Effort, FIGURE_SEED,
};
use v2ref_reproduction::figures::fig5_runs;

/// FNV-1a over the JSON of the runs (every number's shortest
/// round-trip decimal, so equal digests mean equal bits).
fn digest(text: &str) -> u64 {
    text.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ b as u64).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (mut effort, mut repeats, mut threads) = (Effort::Full, 1, Vec::new());
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "quick" => effort = Effort::Quick,
            "full" => effort = Effort::Full,
            "--repeats" => repeats = args.next().ok_or("--repeats needs a count")?.parse()?,
            t => threads.push(t.parse::<usize>()?),
        }
    }
    if threads.is_empty() {
        threads = vec![1, 2];
    }
    let mut first: Option<(f64, u64)> = None;
    for &t in &threads {
        let mut best = f64::INFINITY;
        let mut hash = 0;
        for _ in 0..repeats.max(1) {
            let start = Instant::now();
            let (count, scans) = fig5_size(effort);
            let freqs = fig5_frequencies(count);
            let runs = in_pool(t, || {
                fig5_runs(paper_turbulence(), &freqs, scans, FIGURE_SEED)
            })?;
            best = best.min(start.elapsed().as_secs_f64());
            hash = digest(&serde_json::to_string(&runs)?);
        }
        let (t0, h0) = *first.get_or_insert((best, hash));
        println!("{t:>3} {best:>8.3} {:>6.2} {hash:016x}", t0 / best);
        if hash != h0 {
            return Err(format!("digest on {t} threads differs from the first").into());
        }
    }
    Ok(())
}
