//! The target list: `plan_targets` (`v2ref plan --targets`).

use super::plan::{request, Magnitude3};
use crate::commands::targets::{self, SharedPlan};
use crate::values::to_py;
use crate::{interruptible, ok};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// `plan_targets`: `v2ref plan --targets` with `plan`'s keywords shared
/// (less its files), the list given as a CSV `path` or as CSV `text` (the
/// wrapper writes a Table or a list of dicts so); `throughput` is the rows'
/// when the shared keywords have no magnitude. Returns the table's rows as
/// dicts (the CSV's columns); rows in error are marked, not raised.
#[pyfunction]
#[pyo3(signature = (path, text, throughput, physical, samples_per_fringe, photon_rate_per_s, dead_time_s, fringe_hz, stroke_um, target_sigma_v2, time_budget_s, scans, seed, threads, diameter_err_mas=0.0, bias="counts", verify_observations=None, magnitude=None, frame_rate_hz=None, instrument=None))]
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
) -> PyResult<PyObject> {
    let rows = match (path, text) {
        (Some(path), None) => ok(crate::formats::targets_csv::read_targets(&path))?,
        (None, Some(text)) => ok(targets::parse_targets(&text))?,
        _ => {
            return Err(pyo3::exceptions::PyTypeError::new_err(
                "targets: a path or rows",
            ))
        }
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
        preset.apply(&mut physical, &mut request, &|key| given.iter().any(|g| g == key));
        preset_throughput = Some(preset.throughput);
    }
    let shared = SharedPlan {
        physical,
        request,
        throughput: throughput.or(preset_throughput),
        verify_observations,
    };
    let table = interruptible(py, |tick| {
        targets::plan_targets(&shared, &rows, threads, tick)
    })?;
    to_py(py, &table)
}
