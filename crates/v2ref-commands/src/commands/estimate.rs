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
//!
//! **A dispersed set** (C spectral channels, `docs/conventions.md` §16):
//! each row holds C × N values, channel after channel. The configuration
//! knows its channels ([`Configuration::read_sidecar`], or
//! [`Configuration::with_channels`] for physical inputs); each channel has
//! its own estimator, from its own model ([`channel_estimators`]: the
//! channel's spectrum and share of the photons), normalized by the model's
//! point source or by the calibrator's rows of the same C × N layout; and
//! [`estimate_channel_rows`] gives the estimates of each channel, row by
//! row.

use crate::conformance::estimate::{BiasConvention, RowEstimate, RowEstimator, RowFault};
use crate::conformance::sidecar::Sidecar;
use crate::error::{Error, Result};
use crate::formalism::channels::Channels;
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
    /// The spectral channels each row is recorded in (C × N values a row,
    /// channel after channel), cut from the inputs' spectrum; `None`: the
    /// wide band, one channel.
    pub channels: Option<Channels>,
}

impl Configuration {
    /// A wide-band synth set's configuration: its inputs, convention and
    /// rows. A dispersed set's channels are not read here (its rows of
    /// C × N values are then refused as rows of another N): read any set
    /// with [`Configuration::read_sidecar`].
    pub fn from_sidecar(sidecar: Sidecar) -> Configuration {
        Configuration {
            set_rows: Some(sidecar.data.rows),
            inputs: sidecar.inputs,
            continuum_subtracted: sidecar.continuum_subtracted,
            samples_from_rows: false,
            channels: None,
        }
    }

    /// A synth set's configuration with its channels, if it has any
    /// (rebuilt and checked by [`Sidecar::channels`]: a refusal names the
    /// parameter `channels`).
    pub fn read_sidecar(sidecar: Sidecar) -> Result<Configuration> {
        let channels = sidecar.channels()?;
        Ok(Configuration {
            channels,
            ..Configuration::from_sidecar(sidecar)
        })
    }

    /// The configuration with its rows recorded in `channels`, which must
    /// be cut from the inputs' spectrum (refused, parameter `channels`,
    /// otherwise).
    pub fn with_channels(self, channels: Channels) -> Result<Configuration> {
        channels.check_parent(&self.inputs.spectrum.spectrum()?)?;
        Ok(Configuration {
            channels: Some(channels),
            ..self
        })
    }

    /// C, the channels of each row (1 for the wide band).
    pub fn channel_count(&self) -> usize {
        self.channels.as_ref().map_or(1, Channels::count)
    }

    /// The physical inputs `p` (checked once N is known, by
    /// [`Configuration::inputs_for`]).
    pub fn from_physical(p: &Physical, continuum_subtracted: bool) -> Result<Configuration> {
        Ok(Configuration {
            inputs: p.inputs_unchecked()?,
            continuum_subtracted,
            set_rows: None,
            samples_from_rows: true,
            channels: None,
        })
    }

    /// The inputs for `rows` rows of `cols` samples named `name`: a
    /// sidecar's N must be `cols` (and its set's rows `rows`, where
    /// [`Configuration::set_rows`] says so); otherwise N is taken from the
    /// rows, unless a piston is modelled (its sequence is drawn at the
    /// configuration's N). With C channels a row holds C × N values: `cols`
    /// must be a multiple of C, and N is `cols / C`. Every input is then
    /// checked.
    pub fn inputs_for(&self, name: RowsName<'_>, rows: usize, cols: usize) -> Result<Inputs> {
        if let Some(expected) = self.set_rows {
            if rows as u64 != expected {
                return Err(name.error("", format!("{rows} rows; its sidecar says {expected}")));
            }
        }
        let c = self.channel_count();
        if c > 1 && cols % c != 0 {
            return Err(name.error(
                "",
                format!(
                    "{cols} values per row is not C x N for the C = {c} channels; give each row as C = {c} channels of N samples, channel after channel"
                ),
            ));
        }
        let cols = cols / c;
        let mut inputs = self.inputs.clone();
        if inputs.samples != cols {
            if !self.samples_from_rows || inputs.piston.is_some() {
                return Err(name.error(
                    "",
                    match c {
                        1 => format!(
                            "{cols} columns; the configuration has {} samples per row",
                            inputs.samples
                        ),
                        _ => format!(
                            "{} columns, {cols} per channel; the configuration has C = {c} channels of N = {} samples, {} values a row",
                            cols * c,
                            inputs.samples,
                            c * inputs.samples
                        ),
                    },
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

/// The estimator of each channel of `inputs` split by `channels`
/// ([`channel_models`](crate::simulator::channels::channel_models): the
/// channel's spectrum and share of the photons), summing `window` with
/// the `bias` convention, normalized by the channel's noise-free point
/// source, or, when `calibrator` is given, by the mean bias-subtracted
/// estimates of the calibrator's rows in that channel (its rows C × N
/// values each, as the interferograms'). One channel over the whole band
/// is [`estimator`] of `inputs`.
pub fn channel_estimators(
    inputs: &Inputs,
    channels: &Channels,
    (window, bias): (BinWindow, BiasConvention),
    continuum_subtracted: bool,
    calibrator: Option<CalibratorRows<'_>>,
    threads: usize,
) -> Result<Vec<RowEstimator>> {
    let models = crate::simulator::channels::channel_models(inputs, channels)?;
    let n = inputs.samples;
    let width = models.len() * n;
    if let Some(cal) = &calibrator {
        if cal.cols != width {
            return Err(cal.name.error(
                "",
                format!(
                    "{} columns; the interferograms have C = {} channels of N = {n} samples, {width} values a row",
                    cal.cols,
                    models.len()
                ),
            ));
        }
        check_rows(cal.name, cal.rows, cal.cols, 0)?;
    }
    let mut out = Vec::with_capacity(models.len());
    for (j, model) in models.iter().enumerate() {
        let est = RowEstimator::new(model, window, bias, continuum_subtracted)?;
        let Some(cal) = &calibrator else {
            out.push(est);
            continue;
        };
        let cal_model = model.calibrator_model()?;
        let cal_est = RowEstimator::new(&cal_model, window, bias, continuum_subtracted)?;
        let rows = channel_of(cal.rows, width, j, n);
        let calibration = cal_est
            .calibration_from_rows(&rows, threads)
            .map_err(|e| in_channel(j, e))?;
        out.push(est.with_calibration(calibration)?);
    }
    Ok(out)
}

/// Channel `j`'s N samples of each row of `rows` (`width` = C × N values
/// a row), as rows of their own.
fn channel_of(rows: &[f64], width: usize, j: usize, n: usize) -> Vec<f64> {
    rows.chunks_exact(width)
        .flat_map(|row| &row[j * n..(j + 1) * n])
        .copied()
        .collect()
}

/// `e` naming channel `j` (from 0) in its reason.
fn in_channel(j: usize, e: Error) -> Error {
    match e {
        Error::Invalid { param, reason } => Error::Invalid {
            param,
            reason: format!("channel {}: {reason}", j + 1),
        },
        e => e,
    }
}

/// The estimates of each channel of `rows` (each row C × N values, channel
/// after channel; C the length of `estimators`, from
/// [`channel_estimators`]), the first `first` rows of the file before
/// them: one list per channel, in channel order, one estimate per row.
/// Refuses rows whose length is not a whole number of rows of C × N
/// values (naming C and N), and a non-finite value or a dark channel of a
/// row, naming the 1-based row and the channel.
pub fn estimate_channel_rows(
    estimators: &[RowEstimator],
    name: RowsName<'_>,
    (rows, first): (&[f64], usize),
    threads: usize,
) -> Result<Vec<Vec<RowEstimate>>> {
    let Some(n) = estimators.first().map(RowEstimator::samples) else {
        return Err(Error::Invalid {
            param: "channels",
            reason: "no channel: give the estimators of channel_estimators".into(),
        });
    };
    let c = estimators.len();
    let width = c * n;
    if rows.len() % width != 0 {
        return Err(name.error(
            "",
            format!(
                "{} values is not a whole number of rows of C x N = {c} x {n} values (C channels of N samples)",
                rows.len()
            ),
        ));
    }
    let mut out = Vec::with_capacity(c);
    for (j, est) in estimators.iter().enumerate() {
        let channel = channel_of(rows, width, j, n);
        let estimates = est.try_estimate_rows(&channel, threads).map_err(|f| {
            name.error(
                f.location(first),
                format!("channel {}: {}", j + 1, f.reason()),
            )
        })?;
        out.push(estimates);
    }
    Ok(out)
}
