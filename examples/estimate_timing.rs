//! Times `RowEstimator::estimate_rows` alone on a file of raw float64
//! rows (little-endian, C order: what NumPy's `x.tofile(path)` writes), for
//! `benches/python_estimate.py` to compare with the Python binding on the
//! same array.
//!
//! ```sh
//! cargo run --release --example estimate_timing -- ROWS.f64 128 [threads] [repeats]
//! ```
//!
//! Prints one line: `rows samples best_seconds checksum`.

use std::time::Instant;
use v2ref::conformance::estimate::{BiasConvention, RowEstimator};
use v2ref::formalism::estimator::BinWindow;
use v2ref::simulator::{Inputs, Model};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 3 {
        return Err("usage: estimate_timing ROWS.f64 SAMPLES [threads] [repeats]".into());
    }
    let samples: usize = args[2].parse()?;
    let threads: usize = args.get(3).map_or(Ok(0), |s| s.parse())?;
    let repeats: usize = args.get(4).map_or(Ok(3), |s| s.parse())?;
    let bytes = std::fs::read(&args[1])?;
    let data: Vec<f64> = bytes
        .chunks_exact(8)
        .map(|b| f64::from_le_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]]))
        .collect();
    let model = Model::new(&Inputs {
        samples,
        ..Inputs::default()
    })?;
    let est = RowEstimator::new(&model, BinWindow::Positive, BiasConvention::Model, true)?;
    let mut best = f64::INFINITY;
    let mut checksum = 0.0;
    for _ in 0..repeats {
        let t = Instant::now();
        let rows = est.estimate_rows(&data, threads)?;
        best = best.min(t.elapsed().as_secs_f64());
        checksum = rows.iter().map(|r| r.v1_sq + r.v2_sq).sum::<f64>();
    }
    println!(
        "{} {samples} {best:.6} {checksum:.17e}",
        data.len() / samples
    );
    Ok(())
}
