//! Bessel functions of the first kind of orders 0 and 1, and the zeros of J1.
//!
//! The uniform-disk visibility (paper, Section "Effect of spectral
//! bandwidth", the formula for V(S)) is `2 J1(z)/z` with `z = π θ S`.
//!
//! Method (Abramowitz & Stegun 9.12; Numerical Recipes §6.5):
//! - |x| < [`SERIES_BELOW`]: the first two terms of the power series
//!   (A&S 9.1.10), whose next term is below 2e-22 relative.
//! - |x| < [`ASYMPTOTIC_FROM`]: Miller's backward recurrence
//!   `J_{n-1} = (2n/x) J_n − J_{n+1}` from an order well above x, normalized
//!   with the identity `J0 + 2 Σ_k J_{2k} = 1` (A&S 9.1.46). Stable, and its
//!   absolute error is a few ulps times the number of steps.
//! - larger |x|: Hankel's asymptotic expansion (A&S 9.2.5–9.2.10), summed
//!   until its terms fall below `HANKEL_STOP` (at x ≥ 30 the smallest term is far
//!   below that).
//!
//! Accuracy: |error| ≤ `tolerance::BESSEL_ABS` (1e-14) for |x| ≤ 100, checked
//! against mpmath in `tests/special.rs`.

/// Where the Hankel expansion takes over from the recurrence.
pub const ASYMPTOTIC_FROM: f64 = 30.0;

/// Below this |x| the power series is used. Miller's recurrence multiplies
/// by `2n/x` at each step, so for tiny x a single step overflows (it gave
/// NaN at x = 1e-300); from 1e-5 on, its largest unnormalized value is the
/// seed times J_0/J_start ≤ 1e-300 · 1e260, far from overflow.
pub const SERIES_BELOW: f64 = 1e-5;

/// Cut-off of the power series of `2 J1(z)/z` (|z| < 4, terms alternate and
/// the sum is ≥ 0.13 there): a term below 1e-18 changes the sum by less
/// than a hundredth of an ulp.
const JINC_SERIES_STOP: f64 = 1e-18;
/// Newton's method for a zero of J1 stops when its step is below this
/// fraction of the zero (half an ulp): the iterate no longer moves.
const NEWTON_STOP_REL: f64 = 1e-16;
/// Seed of Miller's backward recurrence (any tiny nonzero value: the
/// normalization removes it), far above underflow.
const MILLER_SEED: f64 = 1e-300;
/// Cut-off of Hankel's P and Q: terms below 1e-17 are under a tenth of an
/// ulp of P ≈ 1 (the series is asymptotic and also stops at its smallest
/// term).
const HANKEL_STOP: f64 = 1e-17;

/// J0(x) and J1(x) together (one recurrence gives both).
pub fn bessel_j0_j1(x: f64) -> (f64, f64) {
    let ax = x.abs();
    let (j0, j1) = if ax < SERIES_BELOW {
        small_argument_j0_j1(ax)
    } else if ax < ASYMPTOTIC_FROM {
        miller_j0_j1(ax)
    } else {
        hankel_j0_j1(ax)
    };
    // J0 is even, J1 is odd.
    (j0, if x < 0.0 { -j1 } else { j1 })
}

/// Bessel function of the first kind of order 0, J0(x).
pub fn bessel_j0(x: f64) -> f64 {
    bessel_j0_j1(x).0
}

/// Bessel function of the first kind of order 1, J1(x).
pub fn bessel_j1(x: f64) -> f64 {
    bessel_j0_j1(x).1
}

/// `2 J1(z) / z`, equal to 1 at z = 0: the visibility of a uniform disk at
/// `z = π θ S` (θ the diameter, S the spatial frequency, same angular unit).
///
/// For |z| < 4 the power series `Σ_k (−z²/4)^k / (k! (k+1)!)` is used
/// (its largest term is below 2 there, so no cancellation); beyond, `2 J1(z)/z`.
pub fn jinc(z: f64) -> f64 {
    if z.abs() < 4.0 {
        let q = -0.25 * z * z;
        let mut term = 1.0;
        let mut sum = 1.0;
        let mut k = 0.0;
        loop {
            k += 1.0;
            term *= q / (k * (k + 1.0));
            sum += term;
            if term.abs() < JINC_SERIES_STOP {
                break;
            }
        }
        sum
    } else {
        2.0 * bessel_j1(z) / z
    }
}

/// The `s`-th positive zero of J1 (s = 1, 2, …): 3.8317…, 7.0156…
///
/// McMahon's expansion (A&S 9.5.12) gives the start, Newton's method with
/// `J1' = J0 − J1/x` converges it to a few ulps. Returns NaN for s = 0.
pub fn bessel_j1_zero(s: u32) -> f64 {
    if s == 0 {
        return f64::NAN;
    }
    let beta = (f64::from(s) + 0.25) * std::f64::consts::PI;
    let mu = 4.0; // 4 ν², ν = 1
    let b8 = 8.0 * beta;
    let mut x = beta - (mu - 1.0) / b8 - 4.0 * (mu - 1.0) * (7.0 * mu - 31.0) / (3.0 * b8.powi(3));
    for _ in 0..50 {
        let (j0, j1) = bessel_j0_j1(x);
        let step = j1 / (j0 - j1 / x);
        x -= step;
        if step.abs() <= NEWTON_STOP_REL * x {
            break;
        }
    }
    x
}

/// J0 and J1 for 0 ≤ x < [`SERIES_BELOW`]: with q = x²/4 < 2.5e-11,
/// `J0 = 1 − q` and `J1 = (x/2)(1 − q/2)`; the next terms, q²/4 and
/// q²/12 relative, are below 2e-22, a millionth of an ulp.
fn small_argument_j0_j1(x: f64) -> (f64, f64) {
    let q = 0.25 * x * x;
    (1.0 - q, 0.5 * x * (1.0 - 0.5 * q))
}

fn miller_j0_j1(x: f64) -> (f64, f64) {
    // Start order: far enough above x that J_start(x) is negligible
    // (J_n(x) decays like (ex/2n)^n once n > x); even, for the normalization.
    let start = {
        let m = (x + 40.0 + 8.0 * x.cbrt()) as usize;
        m + (m & 1)
    };
    let two_over_x = 2.0 / x;
    let (mut j_next, mut j_cur) = (0.0_f64, MILLER_SEED); // J_{n+1}, J_n (unnormalized)
    let mut even_sum = 0.0; // Σ J_{2k}, k ≥ 1
    let mut j1 = 0.0;
    let mut n = start;
    while n > 0 {
        let j_prev = (n as f64) * two_over_x * j_cur - j_next;
        j_next = j_cur;
        j_cur = j_prev;
        n -= 1;
        // j_cur now holds J_n.
        if n % 2 == 0 && n > 0 {
            even_sum += j_cur;
        }
        if n == 1 {
            j1 = j_cur;
        }
    }
    let norm = j_cur + 2.0 * even_sum;
    (j_cur / norm, j1 / norm)
}

fn hankel_j0_j1(x: f64) -> (f64, f64) {
    let (p0, q0) = hankel_pq(0.0, x);
    let (p1, q1) = hankel_pq(4.0, x);
    let (s, c) = x.sin_cos();
    let r = std::f64::consts::FRAC_1_SQRT_2;
    // χ0 = x − π/4, χ1 = x − 3π/4, expanded to avoid subtracting an inexact π.
    let (cos0, sin0) = (r * (c + s), r * (s - c));
    let (cos1, sin1) = (r * (s - c), -r * (s + c));
    let amp = (2.0 / (std::f64::consts::PI * x)).sqrt();
    (amp * (p0 * cos0 - q0 * sin0), amp * (p1 * cos1 - q1 * sin1))
}

/// Hankel's P and Q for μ = 4ν² (A&S 9.2.9, 9.2.10).
fn hankel_pq(mu: f64, x: f64) -> (f64, f64) {
    let z8 = 8.0 * x;
    let mut p = 1.0;
    let mut q = 0.0;
    let mut term = 1.0;
    let mut k = 1u32;
    let mut last = f64::INFINITY;
    loop {
        let odd = f64::from(2 * k - 1);
        term *= (mu - odd * odd) / (f64::from(k) * z8);
        if term.abs() > last || k > 60 {
            break; // the series is asymptotic: stop at its smallest term
        }
        last = term.abs();
        match k % 4 {
            1 => q += term,
            2 => p -= term,
            3 => q -= term,
            _ => p += term,
        }
        if term.abs() < HANKEL_STOP {
            break;
        }
        k += 1;
    }
    (p, q)
}
