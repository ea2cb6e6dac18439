//! A long inverse DFT computed as many short ones, on every thread.
//!
//! A piston sequence of M samples (`piston::series`) is one inverse
//! DFT of M up to 2^24 points; a single rustfft call runs it on one thread.
//! The four-step algorithm (Bailey 1990, "FFTs in external or hierarchical
//! memory", J. Supercomputing 4, 23) writes M = M1 M2, the output index
//! n = n1 + M1 n2 and the input index k = k2 + M2 k1, so that
//!
//! ```text
//! x[n1 + M1 n2] = Σ_{k2} e^{2πi k2 n2 / M2} · e^{2πi k2 n1 / M} · Σ_{k1} X[k2 + M2 k1] e^{2πi k1 n1 / M1}
//! ```
//!
//! 1. M2 inverse DFTs of length M1 (one per k2, over k1);
//! 2. the twiddle factors e^{2πi k2 n1 / M} (from two tables of √M
//!    values each, not M sines);
//! 3. M1 inverse DFTs of length M2 (one per n1, over k2).
//!
//! Steps 1 and 3 are independent rows: they run in parallel, each row by the
//! same rustfft plan whatever thread takes it, so the output has the same
//! bits for any thread count. The split (M1, M2) depends on M only.
//!
//! The slow oracle is [`naive_inverse_dft`] (tests: `tests/fft.rs`, which also
//! compares with rustfft's single transform and checks Parseval).

use num_complex::Complex64;
use rayon::prelude::*;
use rustfft::{Fft, FftPlanner};
use std::sync::Arc;
use strength_reduce::StrengthReducedUsize;

/// The split M = M1 M2 of [`inverse_dft`]: M1 the largest divisor of `m`
/// not above √m (so M1 ≤ M2 and both are near √m when `m` has many small
/// factors, as the 2·3·5-smooth lengths of piston sequences do).
///
/// ```
/// use v2ref_core::math::fft::split_length;
/// assert_eq!(split_length(1_296_000), (1125, 1152));
/// assert_eq!(split_length(4), (2, 2));
/// assert_eq!(split_length(7), (1, 7)); // a prime: one transform
/// ```
pub fn split_length(m: usize) -> (usize, usize) {
    let mut m1 = (m as f64).sqrt() as usize;
    while m1 * m1 > m {
        m1 -= 1;
    }
    while m1 > 1 && m % m1 != 0 {
        m1 -= 1;
    }
    let m1 = m1.max(1);
    (m1, m / m1)
}

/// e^{2πi r/m} for 0 ≤ r < m, the angle taken from the exact residue.
fn twiddle(r: usize, m: usize) -> Complex64 {
    let (s, c) = (std::f64::consts::TAU * r as f64 / m as f64).sin_cos();
    Complex64::new(c, s)
}

/// e^{2πi r/M} for any r < M from two short tables, r = q B + p with
/// B ≈ √M: e^{2πi qB/M} · e^{2πi p/M}, each factor exact to rounding (a
/// product of two, not a recurrence: no error grows with r), and O(√M)
/// sines instead of M.
struct Twiddles {
    /// B, divided by with a multiplication (the M divisions by a divisor
    /// known only at run time were a third of step 2).
    block: StrengthReducedUsize,
    coarse: Vec<Complex64>,
    fine: Vec<Complex64>,
}

impl Twiddles {
    fn new(m: usize) -> Twiddles {
        let block = ((m as f64).sqrt() as usize).max(1);
        Twiddles {
            block: StrengthReducedUsize::new(block),
            coarse: (0..m.div_ceil(block))
                .map(|q| twiddle(q * block, m))
                .collect(),
            fine: (0..block).map(|p| twiddle(p, m)).collect(),
        }
    }

    /// e^{2πi r/M}, 0 ≤ r < M.
    fn at(&self, r: usize) -> Complex64 {
        let (q, p) = StrengthReducedUsize::div_rem(r, self.block);
        self.coarse[q] * self.fine[p]
    }
}

/// Rows of `data` filled together. Each step reads its input across the
/// rows (a transpose): filled one row at a time, each value read came from
/// its own cache line and each line a row wrote was written by another
/// row's turn later (those strided reads and writes were 70 % of a
/// 2^20-point transform, the butterflies 12 %). A block of 16 rows reads 16
/// consecutive values of its source (four lines) at a time.
const BLOCK_ROWS: usize = 16;

/// Columns a block writes to one row before the next row: four values,
/// one 64-byte line, written whole (rows 2^k values apart map to the same
/// cache sets, so a line left half written is evicted before its turn
/// comes back). 2^20 points on one thread: 27 ms before the blocks, about
/// 17 ms with them (rows and columns of 4 to 32 within the noise).
const TILE_COLUMNS: usize = 4;

/// Writes `entry(first + r, j)` at column j of each `len`-long row r of
/// `block`, [`TILE_COLUMNS`] columns at a time down the rows, so an
/// `entry` that reads `src[j * stride + i]` reads consecutive values.
/// Each value is computed as it was row by row: the order of the writes
/// changes, not their bits (a test compares with the row-by-row transform
/// bit for bit).
fn fill_block<T>(block: &mut [T], first: usize, len: usize, entry: &impl Fn(usize, usize) -> T) {
    let rows = block.len() / len;
    for j0 in (0..len).step_by(TILE_COLUMNS) {
        let columns = j0..(j0 + TILE_COLUMNS).min(len);
        for r in 0..rows {
            for j in columns.clone() {
                block[r * len + j] = entry(first + r, j);
            }
        }
    }
}

/// `len`-long rows of `data`, row i holding `entry(i, j)` at column j,
/// filled in blocks of [`BLOCK_ROWS`] rows in parallel ([`fill_block`]);
/// each row then transformed in place by `fft`.
fn rows_in_parallel(
    data: &mut [Complex64],
    len: usize,
    fft: &Arc<dyn Fft<f64>>,
    entry: impl Fn(usize, usize) -> Complex64 + Sync,
) {
    let zero = Complex64::new(0.0, 0.0);
    data.par_chunks_mut(len * BLOCK_ROWS)
        .enumerate()
        .for_each_init(
            || vec![zero; fft.get_inplace_scratch_len()],
            |scratch, (b, block)| {
                fill_block(block, b * BLOCK_ROWS, len, &entry);
                for row in block.chunks_exact_mut(len) {
                    fft.process_with_scratch(row, scratch);
                }
            },
        );
}

/// The unnormalized inverse DFT `x[n] = Σ_k X[k] e^{+2πi kn/M}` of
/// `spectrum` (M = its length), by the four-step split of
/// [`split_length`], rows in parallel on the current rayon pool (wrap in
/// [`crate::montecarlo::in_pool`] to choose the threads). Same bits for
/// any thread count; agrees with a single rustfft transform to rounding.
///
/// ```
/// use num_complex::Complex64;
/// use v2ref_core::math::fft::inverse_dft;
/// // A single line at k = 3 of M = 12 gives the phasor e^{2πi 3n/12}.
/// let mut x = vec![Complex64::new(0.0, 0.0); 12];
/// x[3] = Complex64::new(1.0, 0.0);
/// let y = inverse_dft(&x);
/// assert!((y[1] - Complex64::new(0.0, 1.0)).norm() < 1e-15);
/// ```
pub fn inverse_dft(spectrum: &[Complex64]) -> Vec<Complex64> {
    inverse_dft_with(spectrum.len(), |k| spectrum[k], |z| z)
}

/// [`inverse_dft`] of the M-point spectrum `X[k] = coefficient(k)`, each
/// output value mapped by `output`: the same bits as mapping
/// [`inverse_dft`]'s output, without the M-point input and output
/// arrays (a piston sequence is the real part of the transform of a
/// spectrum that is half zeros: `piston::series`).
pub fn inverse_dft_with<T: Copy + Default + Send + Sync>(
    m: usize,
    coefficient: impl Fn(usize) -> Complex64 + Sync,
    output: impl Fn(Complex64) -> T + Sync,
) -> Vec<T> {
    let (m1, m2) = split_length(m);
    let mut planner = FftPlanner::new();
    if m1 == 1 {
        let mut out: Vec<Complex64> = (0..m).map(&coefficient).collect();
        planner.plan_fft_inverse(m).process(&mut out);
        return out.into_iter().map(output).collect();
    }
    let zero = Complex64::new(0.0, 0.0);
    // Step 1: row k2 holds Σ_{k1} X[k2 + M2 k1] e^{2πi k1 n1/M1} over n1.
    let mut by_k2 = vec![zero; m];
    let short = planner.plan_fft_inverse(m1);
    rows_in_parallel(&mut by_k2, m1, &short, |k2, k1| coefficient(k2 + m2 * k1));
    // Steps 2 and 3: row n1 gathers those, times the twiddles
    // e^{2πi k2 n1/M}, and holds x[n1 + M1 n2] over n2.
    let twiddles = Twiddles::new(m);
    let mut by_n1 = vec![zero; m];
    let long = planner.plan_fft_inverse(m2);
    rows_in_parallel(&mut by_n1, m2, &long, |n1, k2| {
        // k2 n1 < M2 M1 = M: the residue is the product itself.
        by_k2[k2 * m1 + n1] * twiddles.at(k2 * n1)
    });
    drop(by_k2);
    // Back to natural order, n = n1 + M1 n2, each value mapped.
    let mut out = vec![T::default(); m];
    out.par_chunks_mut(m1 * BLOCK_ROWS)
        .enumerate()
        .for_each(|(b, block)| {
            fill_block(block, b * BLOCK_ROWS, m1, &|n2, n1| {
                output(by_n1[n1 * m2 + n2])
            })
        });
    out
}

/// The inverse DFT by its definition, O(M²): the oracle of
/// [`inverse_dft`], the phase of each term taken from the exact residue
/// `kn mod M`.
pub fn naive_inverse_dft(spectrum: &[Complex64]) -> Vec<Complex64> {
    let m = spectrum.len();
    (0..m)
        .map(|n| {
            spectrum
                .iter()
                .enumerate()
                .map(|(k, &x)| x * twiddle((k * n) % m, m))
                .sum()
        })
        .collect()
}
