//! The one home for the crate's numerical tolerances.
//!
//! Deterministic code is held to machine epsilon times a stated condition
//! number; Monte Carlo code to `k` standard errors with `k` at least
//! [`MC_SIGMAS`]. Tests and the golden check import their tolerances from
//! here, so that a change of policy is one edit.

/// Machine epsilon for `f64`.
pub const EPS: f64 = f64::EPSILON;

/// Relative accuracy the band integrals are converged to (the adaptive
/// Gauss–Kronrod target). The integrands are smooth and bounded by one, so
/// the absolute error of a normalized integral is of the same order.
pub const QUADRATURE_REL: f64 = 1e-13;

/// Absolute accuracy of `2 J1(z)/z` and of J0, J1 over |z| ≤ 100, checked
/// against mpmath at 50 digits (`tests/data/bessel_reference.csv`). Miller's
/// backward recurrence loses a few ulps over ~100 steps.
pub const BESSEL_ABS: f64 = 1e-14;

/// Accuracy of a located zero of J1, relative.
pub const BESSEL_ZERO_REL: f64 = 1e-14;

/// The DFT identities (Parseval, Σ B_k = N M_0) hold to rounding: the
/// relative error of an N-point FFT grows like ε log2 N; we allow
/// `DFT_REL_PER_LOG2N * log2 N` with a safety factor of 10.
pub const DFT_REL_PER_LOG2N: f64 = 10.0 * EPS;

/// Golden-data comparison: relative tolerance for deterministic curves
/// (the 1e-12; the computations are reproducible to a few ulps, the
/// margin covers a change of libm or of FMA contraction).
pub const GOLDEN_REL: f64 = 1e-12;

/// Absolute floor of the golden comparison, for values that cross zero
/// (a difference of two O(1) numbers is only known to ~1e-15).
pub const GOLDEN_ABS: f64 = 1e-14;

/// Number of standard errors a Monte Carlo test allows (≥ 5 by policy:
/// a 5σ two-sided excursion has probability 5.7e-7 per test).
pub const MC_SIGMAS: f64 = 5.0;

/// Agreement between the spectral (continuous) estimators and those from a
/// long, finely sampled interferogram: limited by the finite-scan
/// convolution, which falls as 1/(stroke · Δσ); see `tests/interferogram.rs`.
pub const SAMPLED_VS_SPECTRAL_ABS: f64 = 2e-3;

/// Agreement between two routes to the same closed form (cumulant recursion
/// vs the printed polynomial, quadratic form vs the Appendix sum, the O(N⁴)
/// moment oracle vs the quadratic form): sums of up to ~10⁴ terms of mixed
/// sign and magnitude up to (n N)⁴ ~ 10¹⁶, so a few hundred ulps of the
/// largest term; 1e-10 relative leaves a margin of ~10³ and still catches
/// any wrong coefficient (which moves the result by ≥ 1e-3 relative).
pub const IDENTITY_REL: f64 = 1e-10;
