//! The target list: `plan_targets` (`v2ref plan --targets`).

use super::plan::{request, Magnitude3};
use crate::commands::targets::{self, SharedPlan};
use crate::plan::photometry::Band2Mass;
use crate::values::to_py;
use crate::words::Words;
use crate::{interruptible, ok};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// The rows of a list given as a CSV `path` or as CSV `text`.
fn read_list(path: Option<PathBuf>, text: Option<String>) -> PyResult<Vec<ListRow>> {
    match (path, text) {
        (Some(path), None) => ok(crate::formats::targets_csv::read_targets(&path)),
        (None, Some(text)) => ok(targets::parse_targets(&text)),
        _ => Err(PyTypeError::new_err("targets: a path or rows")),
    }
}

/// A row of a list as read: a target, or why it could not be read.
type ListRow = Result<targets::Target, targets::RowFault>;

/// A row read, as Python holds it between the parse and its plan (a
/// task's whole input from the list): `(line, name, magnitude, band,
/// diameter_mas, ra_deg, dec_deg, reason)`, `reason` None for a target.
type RowTuple = (
    u64,
    String,
    Option<f64>,
    Option<String>,
    Option<f64>,
    Option<f64>,
    Option<f64>,
    Option<String>,
);

/// `row` as a [`RowTuple`].
fn row_tuple(row: &ListRow) -> RowTuple {
    match row {
        Ok(t) => {
            let band = t.band.and_then(|b| {
                Band2Mass::WORDS
                    .iter()
                    .find(|w| w.value == b)
                    .map(|w| w.word.to_owned())
            });
            let (line, name) = (t.line, t.name.clone());
            (
                line,
                name,
                t.magnitude,
                band,
                t.diameter_mas,
                t.ra_deg,
                t.dec_deg,
                None,
            )
        }
        Err(f) => (
            f.line,
            f.name.clone(),
            None,
            None,
            None,
            None,
            None,
            Some(f.reason.clone()),
        ),
    }
}

/// The row a [`RowTuple`] holds; ValueError for a band that is none.
fn tuple_row(t: RowTuple) -> PyResult<ListRow> {
    let (line, name, magnitude, band, diameter_mas, ra_deg, dec_deg, reason) = t;
    if let Some(reason) = reason {
        return Ok(Err(targets::RowFault { line, name, reason }));
    }
    let band = match band {
        None => None,
        Some(word) => match Band2Mass::WORDS.iter().find(|w| w.word == word) {
            Some(w) => Some(w.value),
            None => {
                return Err(PyValueError::new_err(format!(
                    "rows: band {word:?} is not one"
                )))
            }
        },
    };
    Ok(Ok(targets::Target {
        line,
        name,
        magnitude,
        band,
        diameter_mas,
        ra_deg,
        dec_deg,
    }))
}

/// The rows of a list given as `plan_targets` takes it, read once: each
/// a tuple that `plan_targets(rows=[…])` plans alone.
#[pyfunction]
#[pyo3(signature = (path, text))]
pub(super) fn _targets_rows(
    path: Option<PathBuf>,
    text: Option<String>,
) -> PyResult<Vec<RowTuple>> {
    Ok(read_list(path, text)?.iter().map(row_tuple).collect())
}

/// `plan_targets`: `v2ref plan --targets` with `plan`'s keywords shared
/// (less its files), the list given as a CSV `path` or as CSV `text` (the
/// wrapper writes a Table or a list of dicts so); `throughput` is the rows'
/// when the shared keywords have no magnitude. Returns the table's rows as
/// dicts (the CSV's columns); rows in error are marked, not raised.
/// `rows=[…]` plans instead rows read by `_targets_rows` (a task of
/// `v2ref.dask` carries its own row, not the list: each row is planned
/// alone, so the rows planned apart and joined in order are the whole
/// table, bit for bit).
#[pyfunction]
#[pyo3(signature = (path, text, throughput, physical, samples_per_fringe, photon_rate_per_s, dead_time_s, fringe_hz, stroke_um, target_sigma_v2, time_budget_s, scans, seed, threads, diameter_err_mas=0.0, bias="counts", verify_observations=None, magnitude=None, frame_rate_hz=None, instrument=None, rows=None))]
#[allow(clippy::too_many_arguments)]
pub(super) fn plan_targets(
    py: Python<'_>,
    path: Option<PathBuf>,
    text: Option<String>,
    throughput: Option<f64>,
    physical: &Bound<'_, PyDict>,
    samples_per_fringe: f64,
    photon_rate_per_s: f64,
    dead_time_s: f64,
    fringe_hz: Vec<f64>,
    stroke_um: Vec<f64>,
    target_sigma_v2: Option<f64>,
    time_budget_s: Option<f64>,
    scans: u64,
    seed: u64,
    threads: usize,
    diameter_err_mas: f64,
    bias: &str,
    verify_observations: Option<u64>,
    magnitude: Magnitude3,
    frame_rate_hz: Option<f64>,
    instrument: Option<(String, Vec<String>)>,
    rows: Option<Vec<RowTuple>>,
) -> PyResult<PyObject> {
    let list = match rows {
        Some(rows) if path.is_none() && text.is_none() => {
            rows.into_iter().map(tuple_row).collect::<PyResult<_>>()?
        }
        Some(_) => return Err(PyTypeError::new_err("targets: a path, rows or parsed rows")),
        None => read_list(path, text)?,
    };
    let (mut physical, mut request) = request(
        physical,
        (samples_per_fringe, photon_rate_per_s, dead_time_s),
        (fringe_hz, stroke_um),
        (target_sigma_v2, time_budget_s, scans, seed),
        (diameter_err_mas, bias, magnitude, frame_rate_hz),
    )?;
    // As `plan --targets --instrument`: the preset fills what was not
    // given, and a row's magnitude takes its throughput when none was.
    let mut preset_throughput = None;
    if let Some((name, given)) = instrument {
        let preset = ok(crate::plan::instrument::instrument(&name))?;
        preset.apply(&mut physical, &mut request, &|key| {
            given.iter().any(|g| g == key)
        });
        preset_throughput = Some(preset.throughput);
    }
    let shared = SharedPlan {
        physical,
        request,
        throughput: throughput.or(preset_throughput),
        verify_observations,
    };
    let table = interruptible(py, |tick| {
        targets::plan_targets(&shared, &list, threads, tick)
    })?;
    to_py(py, &table)
}
