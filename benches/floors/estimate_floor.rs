//! The floor of `estimate` on rows in memory, shared by `benches/floors.rs`
//! and `examples/estimate_timing.rs`: per row a real-input FFT (one plan,
//! buffers reused per block) and the two sums over the positive bins
//! 1 … ⌈N/2⌉ − 1, written to a preallocated output; blocks of 256 rows
//! over the threads of the current pool.

use rayon::prelude::*;
use realfft::num_complex::Complex;
use realfft::RealFftPlanner;

/// `(Σ_{k∈K} |B_k|², |Σ_{k∈K} B_k|²)` over the positive bins of a real
/// row's half spectrum `half` (N = `n`).
pub fn positive_sums(half: &[Complex<f64>], n: usize) -> (f64, f64) {
    let (mut power, mut re, mut im) = (0.0, 0.0, 0.0);
    for b in &half[1..n.div_ceil(2)] {
        power += b.norm_sqr();
        re += b.re;
        im += b.im;
    }
    (power, re * re + im * im)
}

/// The raw V1², V2² of each row of `rows` (row-major, `n` per row).
pub fn estimate_floor(rows: &[f64], n: usize) -> Vec<(f64, f64)> {
    let plan = RealFftPlanner::<f64>::new().plan_fft_forward(n);
    let mut out = vec![(0.0, 0.0); rows.len() / n];
    out.par_chunks_mut(256)
        .zip(rows.par_chunks(n * 256))
        .for_each(|(out, block)| {
            let mut input = plan.make_input_vec();
            let mut half = plan.make_output_vec();
            let mut scratch = plan.make_scratch_vec();
            for (o, row) in out.iter_mut().zip(block.chunks_exact(n)) {
                input.copy_from_slice(row);
                plan.process_with_scratch(&mut input, &mut half, &mut scratch)
                    .expect("lengths from the plan");
                *o = positive_sums(&half, n);
            }
        });
    out
}
