//! The four-step inverse DFT of long piston sequences (`math::fft`) against
//! its slow oracle (the DFT by definition), against rustfft's single
//! transform, Parseval, and the same bits on any number of threads.

use num_complex::Complex64;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use rustfft::FftPlanner;
use v2ref_core::math::fft::{inverse_dft, naive_inverse_dft, split_length};
use v2ref_core::montecarlo::in_pool;
use v2ref_core::tolerance::{FFT_SUM_REL, FOUR_STEP_REL, ROUNDING_REL};

fn random_spectrum(m: usize, seed: u64) -> Vec<Complex64> {
    let mut rng = Pcg64::seed_from_u64(seed);
    (0..m)
        .map(|_| Complex64::new(rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0)))
        .collect()
}

/// max |a − b| / max |b|.
fn relative_difference(a: &[Complex64], b: &[Complex64]) -> f64 {
    let scale = b.iter().map(|z| z.norm()).fold(0.0, f64::max);
    let worst = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y).norm())
        .fold(0.0, f64::max);
    worst / scale
}

#[test]
fn split_is_the_largest_divisor_not_above_the_square_root() {
    for m in 1..3000usize {
        let (m1, m2) = split_length(m);
        assert_eq!(m1 * m2, m, "m = {m}");
        assert!(m1 <= m2, "m = {m}");
        // No divisor of m lies strictly between m1 and √m.
        let bigger = (m1 + 1..=m).take_while(|d| d * d <= m).find(|d| m % d == 0);
        assert_eq!(bigger, None, "m = {m}: {m1} is not the largest");
    }
    // The Fig. 5 sequence length: two near-equal factors.
    assert_eq!(split_length(1_296_000), (1125, 1152));
    // Past 2^52 the floating-point square root can round up to an integer
    // above √m: k² − 1 reads as k, which is not a divisor, k − 1 is.
    let k = (1usize << 27) + 1;
    assert_eq!(
        ((k * k - 1) as f64).sqrt() as usize,
        k,
        "the case is reached"
    );
    assert_eq!(split_length(k * k - 1), (k - 1, k + 1));
    assert_eq!(split_length(k * k), (k, k));
    // An empty spectrum is an empty series, not a division by zero.
    assert_eq!(split_length(0), (1, 0));
    assert!(inverse_dft(&[]).is_empty());
}

#[test]
fn the_oracle_takes_each_phase_from_the_exact_residue() {
    // A single line X[k] = 1 gives x[n] = e^{2πi kn/M}. At M = 3001 the
    // products kn reach 9e6, so a phase 2π kn/M taken without reducing kn
    // mod M would be rounded to ~2e-12 rad; reduced, every value is exact
    // to a few ulps. The truth: the phase of ((kn) mod M)/M computed in
    // integers here, on exactly representable angles.
    let m = 3001usize;
    let k = 2999usize;
    let mut x = vec![Complex64::new(0.0, 0.0); m];
    x[k] = Complex64::new(1.0, 0.0);
    let y = naive_inverse_dft(&x);
    for (n, yn) in y.iter().enumerate() {
        let turns = ((k * n) % m) as f64 / m as f64;
        let exact = Complex64::from_polar(1.0, std::f64::consts::TAU * turns);
        assert!(
            (yn - exact).norm() < ROUNDING_REL,
            "n = {n}: {yn} vs {exact}"
        );
    }
}

#[test]
fn four_step_equals_the_dft_by_definition() {
    // Even and odd, prime (no split), squares, 2·3·5-smooth lengths and
    // lengths with a large prime factor (2 · 97).
    for (i, m) in [2usize, 4, 6, 9, 12, 30, 97, 120, 194, 360, 1000]
        .into_iter()
        .enumerate()
    {
        let x = random_spectrum(m, 10 + i as u64);
        let fast = inverse_dft(&x);
        let slow = naive_inverse_dft(&x);
        let d = relative_difference(&fast, &slow);
        assert!(d <= FOUR_STEP_REL, "M = {m}: {d:e}");
    }
}

#[test]
fn four_step_equals_one_rustfft_transform_at_the_fig5_length() {
    let m = 1_296_000;
    let x = random_spectrum(m, 3);
    let fast = inverse_dft(&x);
    let mut single = x.clone();
    FftPlanner::new().plan_fft_inverse(m).process(&mut single);
    let d = relative_difference(&fast, &single);
    assert!(d <= FOUR_STEP_REL, "{d:e}");
    // Power: reading the input one index off (a wrong gather k2 + M2 k1)
    // is an O(1) error, far above the tolerance.
    let mut wrong = x.clone();
    wrong.rotate_left(1);
    assert!(relative_difference(&inverse_dft(&wrong), &single) > 1e3 * FOUR_STEP_REL);
}

#[test]
fn parseval_holds() {
    // Σ|x_n|² = M Σ|X_k|² for the unnormalized inverse transform.
    for m in [1152usize, 38_880] {
        let x = random_spectrum(m, m as u64);
        let y = inverse_dft(&x);
        let lhs: f64 = y.iter().map(|z| z.norm_sqr()).sum();
        let rhs = m as f64 * x.iter().map(|z| z.norm_sqr()).sum::<f64>();
        let rel = (lhs - rhs).abs() / rhs;
        // FFT_SUM_REL is stated for N ≤ 10³ bins; the error of the sum
        // grows like √M: scaled here by √(M/10³).
        let tol = FFT_SUM_REL * (m as f64 / 1e3).sqrt();
        assert!(rel <= tol, "M = {m}: {rel:e} > {tol:e}");
    }
}

#[test]
fn same_bits_on_any_number_of_threads() {
    let x = random_spectrum(1_296_000, 5);
    let one = in_pool(1, || Ok(inverse_dft(&x))).unwrap();
    for threads in [2, 3, 7] {
        let many = in_pool(threads, || Ok(inverse_dft(&x))).unwrap();
        assert!(
            one.iter()
                .zip(&many)
                .all(|(a, b)| a.re.to_bits() == b.re.to_bits() && a.im.to_bits() == b.im.to_bits()),
            "{threads} threads"
        );
    }
}

/// The four-step transform written row by row, as plainly as it reads:
/// each row gathered value by value from its strided source, then
/// transformed; the twiddle e^{2πi r/M} the product of a coarse and a fine
/// table entry, r = qB + p with B = ⌊√M⌋ (the library's recipe, so the
/// bits can be compared). The library fills blocks of rows a few columns
/// at a time (cache lines read and written whole): the same values in
/// another order of writes.
fn row_by_row_four_step(x: &[Complex64]) -> Vec<Complex64> {
    let m = x.len();
    let (m1, m2) = split_length(m);
    let mut planner = FftPlanner::new();
    let (short, long) = (planner.plan_fft_inverse(m1), planner.plan_fft_inverse(m2));
    let phasor = |r: usize| {
        let (s, c) = (std::f64::consts::TAU * r as f64 / m as f64).sin_cos();
        Complex64::new(c, s)
    };
    let block = ((m as f64).sqrt() as usize).max(1);
    let twiddle = |r: usize| phasor(r / block * block) * phasor(r % block);
    let mut by_k2 = vec![Complex64::new(0.0, 0.0); m];
    for (k2, row) in by_k2.chunks_exact_mut(m1).enumerate() {
        for (k1, v) in row.iter_mut().enumerate() {
            *v = x[k2 + m2 * k1];
        }
        short.process(row);
    }
    let mut by_n1 = vec![Complex64::new(0.0, 0.0); m];
    for (n1, row) in by_n1.chunks_exact_mut(m2).enumerate() {
        for (k2, v) in row.iter_mut().enumerate() {
            *v = by_k2[k2 * m1 + n1] * twiddle(k2 * n1);
        }
        long.process(row);
    }
    (0..m).map(|n| by_n1[(n % m1) * m2 + n / m1]).collect()
}

#[test]
fn blocked_rows_give_the_bits_of_the_row_by_row_four_step() {
    // Square and oblong splits, row counts that are and are not multiples
    // of the 16-row blocks, row lengths not multiples of 4.
    for (seed, m) in [
        (11, 1000),
        (12, 6000),
        (13, 81_000),
        (14, 655_360),
        (15, 1 << 20),
    ] {
        let x = random_spectrum(m, seed);
        let plain = row_by_row_four_step(&x);
        let blocked = in_pool(2, || Ok(inverse_dft(&x))).unwrap();
        let differing = plain
            .iter()
            .zip(&blocked)
            .filter(|(a, b)| a.re.to_bits() != b.re.to_bits() || a.im.to_bits() != b.im.to_bits())
            .count();
        assert_eq!(
            differing,
            0,
            "M = {m} ({:?}): values differing in their bits",
            split_length(m)
        );
    }
}
