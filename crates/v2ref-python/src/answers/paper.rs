//! The paper's effects one at a time: `bias`, `snr`, `piston`, `claims`.

use super::{formula, window};
use crate::commands::{self, piston::PistonRequest};
use crate::piston::spectrum::PistonPsdModel;
use crate::reproduction::cases::Effort;
use crate::values::to_py;
use crate::words::Words;
use crate::{interruptible, ok};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use v2ref_commands::units::piston::PistonJob;

/// `bias`: `v2ref bias --json`.
#[pyfunction]
#[pyo3(signature = (physical, bins, finite_scan))]
pub(super) fn bias(
    py: Python<'_>,
    physical: &Bound<'_, PyDict>,
    bins: &str,
    finite_scan: bool,
) -> PyResult<PyObject> {
    let p = crate::inputs::physical_from_dict(physical)?;
    let window = ok(window(bins))?;
    let answer = interruptible(py, |_| commands::bias::answer(&p, window, finite_scan))?;
    to_py(py, &answer)
}

/// `snr`: `v2ref snr --json`.
#[pyfunction]
#[pyo3(signature = (physical, bins, formula))]
pub(super) fn snr(
    py: Python<'_>,
    physical: &Bound<'_, PyDict>,
    bins: &str,
    formula: &str,
) -> PyResult<PyObject> {
    let p = crate::inputs::physical_from_dict(physical)?;
    let window = ok(window(bins))?;
    let formula = ok(self::formula(formula))?;
    let answer = interruptible(py, |_| commands::snr::answer(&p, window, formula))?;
    to_py(py, &answer)
}

/// `piston`: `v2ref piston --json` (`physical` without `fringe_hz`; `psd`
/// and `wind_angle_deg` as `--psd`, `--wind-angle-deg`).
#[pyfunction]
#[pyo3(signature = (physical, fringe_hz, bins, scans, seed, threads, psd, wind_angle_deg))]
#[allow(clippy::too_many_arguments)]
pub(super) fn piston(
    py: Python<'_>,
    physical: &Bound<'_, PyDict>,
    fringe_hz: Vec<f64>,
    bins: &str,
    scans: usize,
    seed: u64,
    threads: usize,
    psd: &str,
    wind_angle_deg: f64,
) -> PyResult<PyObject> {
    let job = piston_job(
        physical,
        fringe_hz,
        bins,
        scans,
        seed,
        threads,
        psd,
        wind_angle_deg,
    )?;
    let (p, req) = (&job.physical, &job.request);
    let prepared = ok(commands::piston::prepare(p, req))?;
    let answer = interruptible(py, |tick| {
        commands::piston::run(&prepared, p, req, Some(tick))
    })?;
    to_py(py, &answer)
}

/// The request of [`piston`] from its arguments (also parsed so by the
/// functions of a run split in ranges of units, `crate::units`).
#[allow(clippy::too_many_arguments)]
pub(crate) fn piston_job(
    physical: &Bound<'_, PyDict>,
    fringe_hz: Vec<f64>,
    bins: &str,
    scans: usize,
    seed: u64,
    threads: usize,
    psd: &str,
    wind_angle_deg: f64,
) -> PyResult<PistonJob> {
    let psd = ok(PistonPsdModel::from_word("psd", psd))?;
    let physical = crate::inputs::physical_from_dict(physical)?;
    let request = PistonRequest {
        fringe_hz,
        bins: ok(window(bins))?,
        scans,
        seed,
        threads,
        psd,
        wind_angle_deg,
        observation: None,
    };
    Ok(PistonJob { physical, request })
}

/// `claims`: `v2ref claims --json` (`quick`: `--quick`).
#[pyfunction]
#[pyo3(signature = (quick))]
pub(super) fn claims(py: Python<'_>, quick: bool) -> PyResult<PyObject> {
    let effort = if quick { Effort::Quick } else { Effort::Full };
    let results = interruptible(py, |_| Ok(crate::reproduction::claims::evaluate(effort)))?;
    to_py(py, &results)
}
