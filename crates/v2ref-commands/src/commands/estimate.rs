//! `estimate`: per row of a user's interferograms, V1² and V2² raw,
//! bias-subtracted and normalized ([`RowEstimator`]), built once for the
//! CLI (rows read from a file) and Python (rows handed in as an array).
//!
//! The steps, each checked here rather than at the edges:
//! 1. the configuration ([`Configuration`]): a synth sidecar's, or the
//!    physical inputs with N taken from the rows;
//! 2. its inputs checked against the rows' shape
//!    ([`Configuration::inputs_for`]);
//! 3. the estimator, normalized by the model's point source or by a
//!    calibrator's rows ([`estimator`]);
//! 4. the rows checked (finite, not dark: [`check_rows`]) and estimated,
//!    in one pass ([`estimate_rows`]).
//!
//! Errors name the rows as the edge does ([`RowsName`]): the CLI's flag
//! and its file, or Python's argument.

use crate::conformance::estimate::{BiasConvention, RowEstimate, RowEstimator, RowFault};
use crate::conformance::sidecar::Sidecar;
use crate::error::{Error, Result};
use crate::formalism::estimator::{BinWindow, Pair};
use crate::parameters::Physical;
use crate::simulator::{Inputs, Model};
use std::path::Path;

/// What a refusal of some rows names: the library parameter (the CLI's
/// flag, Python's argument) and, for a file, its path.
#[derive(Debug, Clone, Copy)]
pub struct RowsName<'a> {
    /// The parameter (`input`, `calibrator`, `interferograms`).
    pub param: &'static str,
    /// The file the rows came from; `None` for an array.
    pub path: Option<&'a Path>,
}

impl RowsName<'_> {
    /// The error for these rows, at `location` (may be empty).
    pub fn error(&self, location: impl Into<String>, reason: impl Into<String>) -> Error {
        let (location, reason) = (location.into(), reason.into());
        match self.path {
            Some(path) => Error::data(self.param, path, location, reason),
            None if location.is_empty() => Error::Invalid {
                param: self.param,
                reason,
            },
            None => Error::Invalid {
                param: self.param,
                reason: format!("{location}: {reason}"),
            },
        }
    }
}

/// Where an estimate's configuration comes from.
#[derive(Debug, Clone)]
pub struct Configuration {
    /// The physical inputs (N may still be taken from the rows).
    pub inputs: Inputs,
    /// Whether the rows hold `M_i = I_i − c_i` (or the counts `I_i`).
    pub continuum_subtracted: bool,
    /// The rows the data must have (a sidecar's set read as such);
    /// `None`: any number.
    pub set_rows: Option<u64>,
    /// Whether N may be taken from the rows (physical inputs without
    /// piston); a sidecar's N is its set's.
    pub samples_from_rows: bool,
}

impl Configuration {
    /// A synth set's configuration: its inputs, convention and rows.
    pub fn from_sidecar(sidecar: Sidecar) -> Configuration {
        Configuration {
            set_rows: Some(sidecar.data.rows),
            inputs: sidecar.inputs,
            continuum_subtracted: sidecar.continuum_subtracted,
            samples_from_rows: false,
        }
    }

    /// The physical inputs `p` (checked once N is known, by
    /// [`Configuration::inputs_for`]).
    pub fn from_physical(p: &Physical, continuum_subtracted: bool) -> Result<Configuration> {
        Ok(Configuration {
            inputs: p.inputs_unchecked()?,
            continuum_subtracted,
            set_rows: None,
            samples_from_rows: true,
        })
    }

    /// The inputs for `rows` rows of `cols` samples named `name`: a
    /// sidecar's N must be `cols` (and its set's rows `rows`, where
    /// [`Configuration::set_rows`] says so); otherwise N is taken from the
    /// rows, unless a piston is modelled (its sequence is drawn at the
    /// configuration's N). Every input is then checked.
    pub fn inputs_for(&self, name: RowsName<'_>, rows: usize, cols: usize) -> Result<Inputs> {
        if let Some(expected) = self.set_rows {
            if rows as u64 != expected {
                return Err(name.error("", format!("{rows} rows; its sidecar says {expected}")));
            }
        }
        let mut inputs = self.inputs.clone();
        if inputs.samples != cols {
            if !self.samples_from_rows || inputs.piston.is_some() {
                return Err(name.error(
                    "",
                    format!(
                        "{cols} columns; the configuration has {} samples per row",
                        inputs.samples
                    ),
                ));
            }
            inputs.samples = cols;
        }
        inputs.validate()?;
        Ok(inputs)
    }
}

/// A calibrator's interferograms: `rows` row-major, `cols` samples each.
#[derive(Debug, Clone, Copy)]
pub struct CalibratorRows<'a> {
    /// What a refusal names.
    pub name: RowsName<'a>,
    /// The rows, row-major.
    pub rows: &'a [f64],
    /// Samples per row.
    pub cols: usize,
}

/// The estimator of `inputs` summing `window` with the `bias` convention,
/// normalized by the model's noise-free point source, or by the mean
/// bias-subtracted estimates of `calibrator`'s rows (same N, same
/// continuum convention) when given.
pub fn estimator(
    inputs: &Inputs,
    (window, bias): (BinWindow, BiasConvention),
    continuum_subtracted: bool,
    calibrator: Option<CalibratorRows<'_>>,
    threads: usize,
) -> Result<RowEstimator> {
    let model = Model::new(inputs)?;
    let est = RowEstimator::new(&model, window, bias, continuum_subtracted)?;
    let Some(cal) = calibrator else {
        return Ok(est);
    };
    if cal.cols != model.samples() {
        return Err(cal.name.error(
            "",
            format!(
                "{} columns; the interferograms have {}",
                cal.cols,
                model.samples()
            ),
        ));
    }
    check_rows(cal.name, cal.rows, cal.cols, 0)?;
    let cal_model = model.calibrator_model()?;
    let cal_est = RowEstimator::new(&cal_model, window, bias, continuum_subtracted)?;
    let calibration: Pair = cal_est.calibration_from_rows(cal.rows, threads)?;
    est.with_calibration(calibration)
}

/// Refuses the first non-finite value and the first dark row (every
/// sample 0: no light, or no data) of `rows` (`cols` samples each, the
/// first `first` rows of the file before them), named by `name`; a
/// non-finite value anywhere comes first ([`RowFault::first`]). One pass
/// over the rows.
pub fn check_rows(name: RowsName<'_>, rows: &[f64], cols: usize, first: usize) -> Result<()> {
    let mut fault = None;
    for (r, row) in rows.chunks(cols.max(1)).enumerate() {
        fault = RowFault::first(fault, RowFault::of_row(r, row));
        if let Some(RowFault::NonFinite { .. }) = fault {
            break;
        }
    }
    match fault {
        Some(f) => Err(name.error(f.location(first), f.reason())),
        None => Ok(()),
    }
}

/// Rows estimated at a time from a large input (8 MB at N = 128): a bad
/// row is refused once its block is read, not after the whole input.
pub const STREAM_ROWS: usize = 8192;

/// The estimates of `rows` (the first `first` rows of the file before
/// them), each row checked ([`check_rows`]'s refusals, same messages) as
/// it is estimated, in one pass over the rows.
pub fn estimate_rows(
    est: &RowEstimator,
    name: RowsName<'_>,
    (rows, first): (&[f64], usize),
    threads: usize,
) -> Result<Vec<RowEstimate>> {
    let n = est.samples();
    if rows.len() % n != 0 {
        return Err(name.error(
            "",
            format!("{} values is not a whole number of rows of {n}", rows.len()),
        ));
    }
    est.try_estimate_rows(rows, threads)
        .map_err(|f| name.error(f.location(first), f.reason()))
}
