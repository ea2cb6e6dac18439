//! The library's typed error.
//!
//! Every check on user input returns one of these variants, naming the
//! parameter (as the CLI flag spells it, without the dashes) and the range it
//! accepts. Nothing in the library panics on user input.

use thiserror::Error;

/// Result alias used across the crate.
pub type Result<T> = std::result::Result<T, Error>;

/// What went wrong with an input, and what would have been accepted.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum Error {
    /// A number was NaN or infinite.
    #[error("{param}: {value} is not a finite number")]
    NotFinite {
        /// Parameter name (CLI flag without dashes).
        param: &'static str,
        /// The offending value.
        value: f64,
    },
    /// A number was outside the accepted range.
    #[error("{param}: {value} is out of range; accepted: {accepted}")]
    OutOfRange {
        /// Parameter name (CLI flag without dashes).
        param: &'static str,
        /// The offending value.
        value: f64,
        /// The accepted range, in words (for example `> 0`).
        accepted: String,
    },
    /// The sample spacing is too coarse for the band: the shortest
    /// wavelength is sampled with fewer than two samples per fringe.
    #[error("dx-um: {dx_um} um aliases the band; accepted: 0 < dx-um < {max_dx_um} um (half the shortest wavelength)")]
    Aliasing {
        /// The requested sample spacing, µm.
        dx_um: f64,
        /// The largest spacing without aliasing, µm.
        max_dx_um: f64,
    },
    /// A spectrum table could not be used.
    #[error("spectrum-csv: {reason}")]
    SpectrumTable {
        /// Why the table was refused (with its line number where there is one).
        reason: String,
    },
    /// Two parameters that cannot be given together, or a missing one.
    #[error("{param}: {reason}")]
    Invalid {
        /// Parameter name (CLI flag without dashes).
        param: &'static str,
        /// What is wrong.
        reason: String,
    },
    /// Reading or writing a file failed.
    #[error("{path}: {reason}")]
    Io {
        /// The file.
        path: String,
        /// The system's message.
        reason: String,
    },
}

/// Checks that `value` is finite.
pub fn finite(param: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::NotFinite { param, value })
    }
}

/// Checks that `value` is finite and strictly positive.
pub fn positive(param: &'static str, value: f64) -> Result<f64> {
    finite(param, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(Error::OutOfRange {
            param,
            value,
            accepted: "> 0".into(),
        })
    }
}

/// Checks that `value` is finite and not negative.
pub fn non_negative(param: &'static str, value: f64) -> Result<f64> {
    finite(param, value)?;
    if value >= 0.0 {
        Ok(value)
    } else {
        Err(Error::OutOfRange {
            param,
            value,
            accepted: ">= 0".into(),
        })
    }
}

/// Checks that `lo <= value <= hi` (and that it is finite).
pub fn in_range(param: &'static str, value: f64, lo: f64, hi: f64) -> Result<f64> {
    finite(param, value)?;
    if (lo..=hi).contains(&value) {
        Ok(value)
    } else {
        Err(Error::OutOfRange {
            param,
            value,
            accepted: format!("{lo} to {hi}"),
        })
    }
}
