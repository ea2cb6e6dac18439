//! The one home for the crate's numerical tolerances.
//!
//! Every tolerance the library iterates to, and every tolerance a test, a
//! doc test or the golden check compares against, is a named constant
//! here, with the reason for its size (in the manner of statrs's
//! `src/prec.rs`). A change of policy is one edit.
//!
//! Deterministic code is held to machine epsilon [`EPS`] times a stated
//! condition number or operation count; quadratures to their convergence
//! target; truncated series and discretizations to their known rate of
//! convergence; Monte Carlo code to `k` standard errors with `k` at least
//! [`MC_SIGMAS`].
//!
//! The constants fall in four groups:
//!
//! * deterministic identities (rounding only): [`EPS`], [`ULPS`],
//!   [`ROUNDING_REL`], [`VISIBILITY_SQ_FLOOR`], [`DEFAULT_REL`],
//!   [`DEFAULT_ABS`], [`DFT_REL_PER_LOG2N`], [`DIRECT_SUM_REL`],
//!   [`NAIVE_DFT_ABS`], [`FOUR_STEP_REL`], [`FFT_SUM_REL`], [`BIN_SUM_REL`],
//!   [`PATHS_AGREE_ABS`], [`BIN_ORACLE_ABS`], [`GAMMA_REL`],
//!   [`IDENTITY_REL`], [`IDENTITY_ABS`], [`CANCELLATION_ABS`],
//!   [`STREAMING_M3_REL`], [`STREAMING_M3_FLOOR`], [`STREAMING_LARGE_MEAN_REL`],
//!   [`NONNEGATIVE_REL`], [`BAND_EDGE_REL`],
//!   [`GOLDEN_REL`], [`GOLDEN_ABS`], [`EXAMPLE_GOLDEN_ABS`],
//!   [`VISIBILITY_SCALING_REL`], [`VISIBILITY_SCALING_ABS`];
//! * quadrature and special functions (convergence targets, finite
//!   differences, iteration stops): [`QUADRATURE_REL`], [`QUADRATURE_ABS`],
//!   [`QUADRATURE_CHECK_REL`], [`NODES_REL`], [`TURBULENCE_QUADRATURE_REL`],
//!   [`TURBULENCE_CHECK_REL`], [`TURBULENCE_SPECTRAL_REL`],
//!   [`TURBULENCE_TAIL_REL`], [`CROSSWIND_REL`], [`TABLE_LN_ABS`], [`CORNER_REL`], [`FRINGE_TABLE_REL`],
//!   [`FRINGE_TABLE_CHECK_ABS`], [`FRINGE_ORACLE_ABS`], [`BESSEL_ABS`],
//!   [`BESSEL_ZERO_REL`], [`FRESNEL_ABS`], [`CLOSED_FORM_VS_NUMERICAL`],
//!   [`FINITE_DIFFERENCE_REL`], [`SECOND_DIFFERENCE_ABS`],
//!   [`RESIDUAL_PHASE_REL`], [`KERNEL_ZERO_REL`], [`MINIMIZE_BRACKET_REL`],
//!   [`REFERENCE_QUADRATURE_REL`], [`RESIDUAL_CUBIC_REL`], [`GLASS_DISPERSION_REL`],
//!   [`ARGMAX_ABS`];
//! * convergence studies (truncated series, discretizations, asymptotic
//!   regimes, printed precision): [`SAMPLED_VS_SPECTRAL_ABS`],
//!   [`SCALING_LAW_REL`], [`SQUARE_LAW_REL`], [`PSD_TABLE_REL`],
//!   [`PSD_TABLE_CORNER_REL`], [`PSD_TABLE_WIGGLE_REL`],
//!   [`ASYMPTOTIC_LIMIT_REL`], [`ASYMPTOTIC_CORRECTION_REL`],
//!   [`LOW_FREQ_VALUE_COEFF`], [`LOW_FREQ_SLOPE_COEFF`],
//!   [`MID_FREQ_VALUE_COEFF`], [`MID_FREQ_SLOPE_COEFF`],
//!   [`DECADE_SLOPE_ABS`], [`ROUGH_SCALING_REL`], [`LINEAR_RESPONSE_REL`],
//!   [`LEADING_TERM_REL`], [`SMALL_P_EXPANSION_ABS`],
//!   [`GRID_INTERPOLATION_REL`], [`DIRICHLET_VS_SINC_ABS`],
//!   [`SAMPLING_LIMIT_ABS`], [`NARROW_BAND_LIMIT_ABS`],
//!   [`CONVERGENCE_GROWTH_REL`], [`RIEMANN_SUM_ABS`], [`SINC_TAIL_ABS`],
//!   [`INTEGRATION_LOSS_ABS`], [`PRINTED_5_DECIMALS_ABS`],
//!   [`PRINTED_3_DECIMALS_ABS`], [`PRINTED_2_DECIMALS_ABS`];
//! * Monte Carlo: [`MC_SIGMAS`], [`SIGNIFICANCE_SIGMAS`], [`POWER_FACTOR`],
//!   [`MC_POWER_SIGMAS`], [`PLAN_MEAN_SIGMAS`].
//!
//! The assertion macros [`assert_rel_eq!`](crate::assert_rel_eq),
//! [`assert_abs_eq!`](crate::assert_abs_eq) and
//! [`assert_within_sigmas!`](crate::assert_within_sigmas) compare through
//! these constants (with [`DEFAULT_REL`], [`DEFAULT_ABS`] and [`MC_SIGMAS`]
//! when none is named) and print both values, their difference and the
//! tolerance on failure.
//!
//! The module and the macros are public for the workspace's test suites
//! (and for a pipeline's own tests, at its choice): test machinery, one
//! file for every tolerance, those the library iterates to beside those
//! only the tests use.

mod convergence;
mod identities;
mod monte_carlo;
mod quadrature;

pub use convergence::*;
pub use identities::*;
pub use monte_carlo::*;
pub use quadrature::*;

/// Checks `|actual − expected| ≤ tol · |expected|` (exact equality always
/// passes, so infinities and zeros compare); on failure, the message the
/// macros print. Used by [`assert_rel_eq!`](crate::assert_rel_eq).
pub fn check_rel(actual: f64, expected: f64, tol: f64) -> Result<(), String> {
    let diff = (actual - expected).abs();
    let allowed = tol * expected.abs();
    if actual == expected || diff <= allowed {
        Ok(())
    } else {
        Err(format!(
            "actual {actual:e}, expected {expected:e}: |difference| {diff:e} (relative {:e}) exceeds the relative tolerance {tol:e} (allowed {allowed:e})",
            diff / expected.abs()
        ))
    }
}

/// Checks `|actual − expected| ≤ tol`; on failure, the message the macros
/// print. Used by [`assert_abs_eq!`](crate::assert_abs_eq).
pub fn check_abs(actual: f64, expected: f64, tol: f64) -> Result<(), String> {
    let diff = (actual - expected).abs();
    if actual == expected || diff <= tol {
        Ok(())
    } else {
        Err(format!(
            "actual {actual:e}, expected {expected:e}: |difference| {diff:e} exceeds the absolute tolerance {tol:e}"
        ))
    }
}

/// Checks `|value − expected| ≤ k · stderr`; on failure, the message the
/// macros print. Used by [`assert_within_sigmas!`](crate::assert_within_sigmas).
pub fn check_sigmas(value: f64, expected: f64, stderr: f64, k: f64) -> Result<(), String> {
    let diff = (value - expected).abs();
    let allowed = k * stderr;
    if diff <= allowed {
        Ok(())
    } else {
        Err(format!(
            "value {value:e}, expected {expected:e}: |difference| {diff:e} = {:.2} standard errors of {stderr:e} exceeds {k} (allowed {allowed:e})",
            diff / stderr
        ))
    }
}

/// Asserts that `actual` equals `expected` to a relative tolerance:
/// `|actual − expected| ≤ tol · |expected|`, with `tol` =
/// [`DEFAULT_REL`](crate::tolerance::DEFAULT_REL) unless given. An optional
/// format string and arguments follow the tolerance. On failure the message
/// prints both values, the difference and the tolerance.
///
/// ```
/// use v2ref_core::{assert_rel_eq, tolerance::ULPS};
/// assert_rel_eq!(0.1 + 0.2, 0.3);
/// assert_rel_eq!(2f64.sqrt().powi(2), 2.0, ULPS);
/// ```
#[macro_export]
macro_rules! assert_rel_eq {
    ($actual:expr, $expected:expr $(,)?) => {
        $crate::assert_rel_eq!($actual, $expected, $crate::tolerance::DEFAULT_REL)
    };
    ($actual:expr, $expected:expr, $tol:expr $(,)?) => {
        if let Err(msg) = $crate::tolerance::check_rel($actual, $expected, $tol) {
            panic!(
                "assert_rel_eq!({}, {}) failed: {}",
                stringify!($actual),
                stringify!($expected),
                msg
            );
        }
    };
    ($actual:expr, $expected:expr, $tol:expr, $($arg:tt)+) => {
        if let Err(msg) = $crate::tolerance::check_rel($actual, $expected, $tol) {
            panic!(
                "assert_rel_eq!({}, {}) failed: {}: {}",
                stringify!($actual),
                stringify!($expected),
                msg,
                format_args!($($arg)+)
            );
        }
    };
}

/// Asserts that `actual` equals `expected` to an absolute tolerance:
/// `|actual − expected| ≤ tol`, with `tol` =
/// [`DEFAULT_ABS`](crate::tolerance::DEFAULT_ABS) unless given. An optional
/// format string and arguments follow the tolerance. On failure the message
/// prints both values, the difference and the tolerance.
///
/// ```
/// use v2ref_core::{assert_abs_eq, tolerance::ULPS};
/// assert_abs_eq!(0.1 + 0.2, 0.3);
/// assert_abs_eq!((0.5f64).sin().asin(), 0.5, ULPS);
/// ```
#[macro_export]
macro_rules! assert_abs_eq {
    ($actual:expr, $expected:expr $(,)?) => {
        $crate::assert_abs_eq!($actual, $expected, $crate::tolerance::DEFAULT_ABS)
    };
    ($actual:expr, $expected:expr, $tol:expr $(,)?) => {
        if let Err(msg) = $crate::tolerance::check_abs($actual, $expected, $tol) {
            panic!(
                "assert_abs_eq!({}, {}) failed: {}",
                stringify!($actual),
                stringify!($expected),
                msg
            );
        }
    };
    ($actual:expr, $expected:expr, $tol:expr, $($arg:tt)+) => {
        if let Err(msg) = $crate::tolerance::check_abs($actual, $expected, $tol) {
            panic!(
                "assert_abs_eq!({}, {}) failed: {}: {}",
                stringify!($actual),
                stringify!($expected),
                msg,
                format_args!($($arg)+)
            );
        }
    };
}

/// Asserts that a Monte Carlo estimate `value` with standard error `stderr`
/// is within `k` standard errors of `expected`: `|value − expected| ≤ k ·
/// stderr`, with `k` = [`MC_SIGMAS`](crate::tolerance::MC_SIGMAS) unless
/// given. An optional format string and arguments follow `k`. On failure
/// the message prints both values, the difference, the number of standard
/// errors and the bound.
///
/// ```
/// use v2ref_core::assert_within_sigmas;
/// assert_within_sigmas!(1.02, 1.0, 0.01); // 2σ of 5
/// ```
#[macro_export]
macro_rules! assert_within_sigmas {
    ($value:expr, $expected:expr, $stderr:expr $(,)?) => {
        $crate::assert_within_sigmas!($value, $expected, $stderr, $crate::tolerance::MC_SIGMAS)
    };
    ($value:expr, $expected:expr, $stderr:expr, $k:expr $(,)?) => {
        if let Err(msg) = $crate::tolerance::check_sigmas($value, $expected, $stderr, $k) {
            panic!(
                "assert_within_sigmas!({}, {}) failed: {}",
                stringify!($value),
                stringify!($expected),
                msg
            );
        }
    };
    ($value:expr, $expected:expr, $stderr:expr, $k:expr, $($arg:tt)+) => {
        if let Err(msg) = $crate::tolerance::check_sigmas($value, $expected, $stderr, $k) {
            panic!(
                "assert_within_sigmas!({}, {}) failed: {}: {}",
                stringify!($value),
                stringify!($expected),
                msg,
                format_args!($($arg)+)
            );
        }
    };
}
