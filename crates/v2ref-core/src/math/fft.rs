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
    block: usize,
    coarse: Vec<Complex64>,
    fine: Vec<Complex64>,
}

impl Twiddles {
    fn new(m: usize) -> Twiddles {
        let block = ((m as f64).sqrt() as usize).max(1);
        Twiddles {
            block,
            coarse: (0..m.div_ceil(block))
                .map(|q| twiddle(q * block, m))
                .collect(),
            fine: (0..block).map(|p| twiddle(p, m)).collect(),
        }
    }

    /// e^{2πi r/M}, 0 ≤ r < M.
    fn at(&self, r: usize) -> Complex64 {
        self.coarse[r / self.block] * self.fine[r % self.block]
    }
}

/// Runs `fft` in place on each `len`-long row of `data`, in parallel, after
/// `fill(row_index, row)` has written the row's input.
fn rows_in_parallel(
    data: &mut [Complex64],
    len: usize,
    fft: &Arc<dyn Fft<f64>>,
    fill: impl Fn(usize, &mut [Complex64]) + Sync,
) {
    let zero = Complex64::new(0.0, 0.0);
    data.par_chunks_mut(len).enumerate().for_each_init(
        || vec![zero; fft.get_inplace_scratch_len()],
        |scratch, (i, row)| {
            fill(i, row);
            fft.process_with_scratch(row, scratch);
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
    let m = spectrum.len();
    let (m1, m2) = split_length(m);
    let mut planner = FftPlanner::new();
    if m1 == 1 {
        let mut out = spectrum.to_vec();
        planner.plan_fft_inverse(m).process(&mut out);
        return out;
    }
    let zero = Complex64::new(0.0, 0.0);
    // Step 1: row k2 holds Σ_{k1} X[k2 + M2 k1] e^{2πi k1 n1/M1} over n1.
    let mut by_k2 = vec![zero; m];
    let short = planner.plan_fft_inverse(m1);
    rows_in_parallel(&mut by_k2, m1, &short, |k2, row| {
        for (k1, v) in row.iter_mut().enumerate() {
            *v = spectrum[k2 + m2 * k1];
        }
    });
    // Steps 2 and 3: row n1 gathers those, times the twiddles
    // e^{2πi k2 n1/M}, and holds x[n1 + M1 n2] over n2.
    let twiddles = Twiddles::new(m);
    let mut by_n1 = vec![zero; m];
    let long = planner.plan_fft_inverse(m2);
    rows_in_parallel(&mut by_n1, m2, &long, |n1, row| {
        for (k2, v) in row.iter_mut().enumerate() {
            // k2 n1 < M2 M1 = M: the residue is the product itself.
            *v = by_k2[k2 * m1 + n1] * twiddles.at(k2 * n1);
        }
    });
    // Back to natural order, n = n1 + M1 n2.
    let mut out = by_k2;
    out.par_chunks_mut(m1).enumerate().for_each(|(n2, row)| {
        for (n1, v) in row.iter_mut().enumerate() {
            *v = by_n1[n1 * m2 + n2];
        }
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
