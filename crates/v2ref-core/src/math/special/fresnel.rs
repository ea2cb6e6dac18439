//! Fresnel integrals `C(x) = ∫₀ˣ cos(πt²/2) dt`, `S(x) = ∫₀ˣ sin(πt²/2) dt`.
//!
//! They give the closed form of V2 for an unresolved source seen through a
//! flat band with the paper's quadratic dispersion phase (Section "Effect of
//! chromatic dispersion", Fig. 2): with `φ = ½ D (σ − σ0)²` of peak-to-peak
//! value P over the band, substituting `t = u √(D/π)` turns the band average
//! of `e^{iφ}` into `(C(T) + i S(T)) / T` with `T = √(2P/π)`, so
//! `V2² = (C(T)² + S(T)²) / T²` ([`point_source_v2_sq`]).
//!
//! Method: for |x| ≤ 1.5 the alternating power series (its largest term is
//! below e^{π·1.5²/2} ≈ 34, so at most two digits are lost to cancellation);
//! beyond, the complementary error function of the complex argument
//! `(1 − i) √π x / 2` by its continued fraction, evaluated with the modified
//! Lentz algorithm (the scheme of Press et al., *Numerical Recipes*, §6.9),
//! which converges fast for large arguments. Both are odd functions.
//! Checked against mpmath at 50 digits (`tests/data/fresnel_reference.csv`).

use num_complex::Complex64;
use std::f64::consts::{FRAC_PI_2, PI};

/// Where the power series hands over to the continued fraction.
const SERIES_LIMIT: f64 = 1.5;
/// Iteration cap of both expansions (each converges in well under 100).
const MAX_TERMS: usize = 200;
/// Series cut-off: stop when the next term is below this fraction of the
/// larger partial sum (a tenth of an ulp, so the truncation is invisible).
const SERIES_STOP_REL: f64 = 1e-17;
/// Floor of the scale the series cut-off is relative to, as a fraction of
/// x: C(x) ≈ x near 0, so the sums never fall far below 1e-3 x; the floor
/// only keeps the very first iterations from stopping on a zero partial sum.
const SERIES_SCALE_FLOOR: f64 = 1e-3;
/// Lentz's method: the stand-in for a zero denominator (the smallest
/// magnitude safely above underflow, so 1/TINY is still finite).
const LENTZ_TINY: f64 = 1e-300;
/// Continued-fraction cut-off: stop when the last factor differs from 1
/// by less than this (half an ulp: the remaining factors change nothing).
const CF_STOP: f64 = 1e-16;
/// Below this T, [`point_source_v2_sq`] uses its series to T⁴: the next
/// term is O(T⁸) < 1e-32, and (C² + S²)/T² would cancel to 1 − O(T⁴).
const SMALL_T_SERIES_BELOW: f64 = 1e-8;

/// `(C(x), S(x))`, the Fresnel integrals with the π/2 normalization.
/// Accurate to a few 1e-16 absolute for every finite x; NaN for NaN.
pub fn fresnel_cs(x: f64) -> (f64, f64) {
    if x.is_nan() {
        return (f64::NAN, f64::NAN);
    }
    let ax = x.abs();
    let (c, s) = if ax.is_infinite() {
        (0.5, 0.5)
    } else if ax <= SERIES_LIMIT {
        series(ax)
    } else {
        continued_fraction(ax)
    };
    if x < 0.0 {
        (-c, -s)
    } else {
        (c, s)
    }
}

/// `C(x)`.
pub fn fresnel_c(x: f64) -> f64 {
    fresnel_cs(x).0
}

/// `S(x)`.
pub fn fresnel_s(x: f64) -> f64 {
    fresnel_cs(x).1
}

/// The power series `∫₀ˣ e^{iπt²/2} dt = Σ_k (iπ/2)^k x^{2k+1} / (k! (2k+1))`:
/// even k feed C, odd k feed S, with alternating signs in each.
fn series(x: f64) -> (f64, f64) {
    let a = FRAC_PI_2 * x * x;
    let (mut c, mut s) = (0.0, 0.0);
    let mut term = x; // a^k x / k!
    for k in 0..MAX_TERMS {
        let contribution = term / (2 * k + 1) as f64;
        match k % 4 {
            0 => c += contribution,
            1 => s += contribution,
            2 => c -= contribution,
            _ => s -= contribution,
        }
        term *= a / (k + 1) as f64;
        if term < SERIES_STOP_REL * c.abs().max(s.abs()).max(x * SERIES_SCALE_FLOOR) {
            break;
        }
    }
    (c, s)
}

/// `C + iS = (1+i)/2 · (1 − w)`, with `w = e^{iπx²/2} · (1 − i) x · h` and
/// `h` the continued fraction of `erfc` at `(1 − i)√π x/2`, written in the
/// variable `b = 1 − iπx²` (even part of the classical fraction).
fn continued_fraction(x: f64) -> (f64, f64) {
    let pix2 = PI * x * x;
    let tiny = LENTZ_TINY;
    let one = Complex64::new(1.0, 0.0);
    let mut b = Complex64::new(1.0, -pix2);
    let mut c = Complex64::new(1.0 / tiny, 0.0);
    let mut d = one / b;
    let mut h = d;
    let mut n = -1.0_f64;
    for _ in 1..MAX_TERMS {
        n += 2.0;
        let a = -n * (n + 1.0);
        b += Complex64::new(4.0, 0.0);
        d = one / (d * a + b);
        c = b + Complex64::new(a, 0.0) / c;
        let delta = c * d;
        h *= delta;
        if (delta.re - 1.0).abs() + delta.im.abs() < CF_STOP {
            break;
        }
    }
    h *= Complex64::new(x, -x);
    // e^{iπx²/2} has period 4 in x²: reduce x² (split exactly into
    // hi + lo by a fused multiply-add) before the trigonometry, so large x
    // do not lose the phase to rounding.
    let hi = x * x;
    let lo = x.mul_add(x, -hi);
    let phase = Complex64::from_polar(1.0, FRAC_PI_2 * ((hi % 4.0) + lo));
    let cs = Complex64::new(0.5, 0.5) * (one - phase * h);
    (cs.re, cs.im)
}

/// V2² of an unresolved source through a flat band (flat in wavenumber)
/// with the quadratic dispersion phase of peak-to-peak value
/// `peak_to_peak_rad` (P) over the band: `(C(T)² + S(T)²)/T²`, `T = √(2|P|/π)`
/// (paper, Section "Effect of chromatic dispersion"; the sign of P only
/// conjugates the sum). 1 at P = 0.
pub fn point_source_v2_sq(peak_to_peak_rad: f64) -> f64 {
    let t = (2.0 * peak_to_peak_rad.abs() / PI).sqrt();
    if t < SMALL_T_SERIES_BELOW {
        // C ≈ T − (π/2)² T⁵/10, S ≈ (π/2) T³/3: V2² = 1 − (π/2)² T⁴ (1/5 − 1/9) + …
        return 1.0 - (FRAC_PI_2 * FRAC_PI_2) * t.powi(4) * 4.0 / 45.0;
    }
    let (c, s) = fresnel_cs(t);
    (c * c + s * s) / (t * t)
}
