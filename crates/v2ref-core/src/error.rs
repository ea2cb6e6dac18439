//! The library's typed error.
//!
//! Every check on user input returns one of these variants, naming the
//! parameter and the range it accepts. Nothing in the library panics on user
//! input.
//!
//! **Parameter names are the library's own**: the Rust name of the argument
//! or field that was refused, in snake_case (`wavelength_um`, `dx_um`,
//! `read_noise`, `fringe_hz`), never a command-line flag. A front end maps
//! them to its own spelling with [`Error::param`] and renders the rest with
//! [`Error::detail`]; `Display` is `param: detail` (or `detail` alone where
//! there is no parameter).

use std::path::PathBuf;
use std::sync::Arc;

/// Result alias used across the crate.
pub type Result<T> = std::result::Result<T, Error>;

/// What went wrong with an input, and what would have been accepted.
///
/// Each variant's message is its `#[error]` attribute: the parameter, `: `,
/// then the detail ([`Error::detail`]), or the detail alone where there is
/// no parameter ([`Error::param`]).
#[derive(Debug, Clone, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A number was NaN or infinite.
    #[error("{param}: {value} is not a finite number")]
    NotFinite {
        /// Library parameter name (Rust name, snake_case).
        param: &'static str,
        /// The offending value.
        value: f64,
    },
    /// A number was outside the accepted range.
    #[error("{param}: {} is out of range; accepted: {accepted}", number(*value))]
    OutOfRange {
        /// Library parameter name (Rust name, snake_case).
        param: &'static str,
        /// The offending value.
        value: f64,
        /// The accepted range, in words (for example `> 0`).
        accepted: String,
    },
    /// The sample spacing `dx_um` is too coarse for the band: the shortest
    /// wavelength is sampled with fewer than two samples per fringe.
    #[error(
        "dx_um: {} um aliases the band; accepted: 0 < spacing < {} um (half the shortest wavelength)",
        number(*dx_um),
        significant(*max_dx_um)
    )]
    Aliasing {
        /// The requested sample spacing, µm.
        dx_um: f64,
        /// The largest spacing without aliasing, µm.
        max_dx_um: f64,
    },
    /// A tabulated spectrum (parameter `spectrum`) could not be used.
    #[error("spectrum: {reason}")]
    SpectrumTable {
        /// Why the table was refused (with its line number where there is one).
        reason: String,
    },
    /// Two parameters that cannot be given together, or a missing one.
    #[error("{param}: {reason}")]
    Invalid {
        /// Library parameter name (Rust name, snake_case).
        param: &'static str,
        /// What is wrong.
        reason: String,
    },
    /// An output could not be produced or a file's content read back, with
    /// no system error behind it (a table that does not parse, a plot that
    /// cannot be drawn, an answer that cannot be serialized). Failures of
    /// the system are [`Error::Io`].
    #[error("{path}: {reason}")]
    Output {
        /// The file (or what was being produced).
        path: String,
        /// What went wrong.
        reason: String,
    },
    /// A data file (interferograms, estimates, a sidecar) was read but its
    /// content is unusable: wrong type or shape, a non-finite value, a size
    /// that does not match its sidecar.
    #[error("{param}: {path}: {}{reason}", located(location))]
    Data {
        /// The library parameter that named the file.
        param: &'static str,
        /// The file.
        path: PathBuf,
        /// Where in it (`row 3, column 7`, `field truth.windows`), or empty.
        location: String,
        /// What is wrong, and what is accepted.
        reason: String,
    },
    /// Reading or writing a file failed; keeps the system's error as
    /// [`std::error::Error::source`] (the shared `Arc<std::io::Error>`).
    #[error("{}{path}: {source}", prefix(*param))]
    Io {
        /// The library parameter that named the file, where there is one.
        param: Option<&'static str>,
        /// The file.
        path: PathBuf,
        /// The system's error (shared so that `Error` stays `Clone`).
        source: Arc<std::io::Error>,
    },
    /// The computation was cancelled from outside it ([`crate::montecarlo::cancel`]):
    /// nothing of it is returned.
    #[error("cancelled")]
    Cancelled,
}

/// `location: `, or nothing for an empty location (a [`Error::Data`]
/// message).
fn located(location: &str) -> String {
    if location.is_empty() {
        String::new()
    } else {
        format!("{location}: ")
    }
}

/// `param: `, or nothing without a parameter (an [`Error::Io`] message).
fn prefix(param: Option<&'static str>) -> String {
    param.map_or_else(String::new, |p| format!("{p}: "))
}

impl Error {
    /// A failed file operation on `path`, named by `param` where known.
    pub fn file(
        param: Option<&'static str>,
        path: impl Into<PathBuf>,
        source: std::io::Error,
    ) -> Error {
        Error::Io {
            param,
            path: path.into(),
            source: Arc::new(source),
        }
    }

    /// Unusable content in the data file `path` (named by `param`), at
    /// `location` (may be empty).
    pub fn data(
        param: &'static str,
        path: impl Into<PathBuf>,
        location: impl Into<String>,
        reason: impl Into<String>,
    ) -> Error {
        Error::Data {
            param,
            path: path.into(),
            location: location.into(),
            reason: reason.into(),
        }
    }

    /// The library parameter this error is about (Rust name, snake_case),
    /// if any.
    pub fn param(&self) -> Option<&'static str> {
        match self {
            Error::NotFinite { param, .. }
            | Error::OutOfRange { param, .. }
            | Error::Invalid { param, .. } => Some(param),
            Error::Aliasing { .. } => Some("dx_um"),
            Error::SpectrumTable { .. } => Some("spectrum"),
            Error::Io { param, .. } => *param,
            Error::Data { param, .. } => Some(param),
            Error::Output { .. } | Error::Cancelled => None,
        }
    }

    /// The message without the parameter prefix (what follows `param: `
    /// in `Display`).
    pub fn detail(&self) -> String {
        let message = self.to_string();
        match self.param() {
            Some(p) => message
                .strip_prefix(p)
                .and_then(|rest| rest.strip_prefix(": "))
                .map_or_else(|| message.clone(), str::to_owned),
            None => message,
        }
    }
}

/// Equal when the same variant carries the same values; two file errors
/// compare their system errors by kind and message.
impl PartialEq for Error {
    fn eq(&self, other: &Error) -> bool {
        use Error::*;
        match (self, other) {
            (NotFinite { param: a, value: x }, NotFinite { param: b, value: y }) => {
                a == b && x == y
            }
            (
                OutOfRange {
                    param: a,
                    value: x,
                    accepted: s,
                },
                OutOfRange {
                    param: b,
                    value: y,
                    accepted: t,
                },
            ) => a == b && x == y && s == t,
            (
                Aliasing {
                    dx_um: a,
                    max_dx_um: x,
                },
                Aliasing {
                    dx_um: b,
                    max_dx_um: y,
                },
            ) => a == b && x == y,
            (SpectrumTable { reason: a }, SpectrumTable { reason: b }) => a == b,
            (
                Invalid {
                    param: a,
                    reason: x,
                },
                Invalid {
                    param: b,
                    reason: y,
                },
            ) => a == b && x == y,
            (Output { path: a, reason: x }, Output { path: b, reason: y }) => a == b && x == y,
            (
                Io {
                    param: a,
                    path: p,
                    source: x,
                },
                Io {
                    param: b,
                    path: q,
                    source: y,
                },
            ) => a == b && p == q && x.kind() == y.kind() && x.to_string() == y.to_string(),
            (
                Data {
                    param: a,
                    path: p,
                    location: l,
                    reason: x,
                },
                Data {
                    param: b,
                    path: q,
                    location: m,
                    reason: y,
                },
            ) => a == b && p == q && l == m && x == y,
            (Cancelled, Cancelled) => true,
            _ => false,
        }
    }
}

/// `value` as a user reads it in a one-line message: plain digits for
/// ordinary magnitudes, scientific notation (`1e308`) for very large or
/// very small ones, so that a refusal never spells out hundreds of digits.
pub fn number(value: f64) -> String {
    let magnitude = value.abs();
    if value != 0.0 && value.is_finite() && !(1e-4..1e7).contains(&magnitude) {
        format!("{value:e}")
    } else {
        format!("{value}")
    }
}

impl Error {
    /// The same error naming `to` where it named `from` (a library check
    /// reached through a caller whose parameter has another name: the
    /// piston runs' `scans` are a set's `rows` and `simulate`'s `trials`).
    pub fn renamed(self, from: &str, to: &'static str) -> Error {
        match self {
            Error::OutOfRange {
                param,
                value,
                accepted,
            } if param == from => Error::OutOfRange {
                param: to,
                value,
                accepted,
            },
            e => e,
        }
    }
}

/// A computed bound at the precision a reader needs: six significant
/// figures, trailing zeros dropped (`0.3375`, not `0.33749999999999997`).
pub fn significant(value: f64) -> String {
    if value == 0.0 || !value.is_finite() {
        return number(value);
    }
    let digits = (5 - value.abs().log10().floor() as i32).max(0) as usize;
    let s = format!("{value:.digits$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        s
    }
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
            accepted: format!("{} to {}", number(lo), number(hi)),
        })
    }
}
