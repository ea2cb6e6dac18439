//! A Monte Carlo command in ranges of work units, for `v2ref.dask` (which
//! maps the ranges on a cluster): `_units_count`, `_units_run`,
//! `_units_check`, `_units_reduce`. `command` names the function and
//! `args` are the positional arguments its binding takes, parsed by the
//! same code ([`crate::answers::simulator::simulate_job`]).

use crate::answers::paper::piston_job;
use crate::answers::simulator::{simulate_answer, simulate_job, truth_job};
use crate::values::to_py;
use crate::{interruptible, ok};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyTuple};
use v2ref_commands::units::piston::PistonJob;
use v2ref_commands::units::simulate::SimulateJob;
use v2ref_commands::units::truth::TruthJob;
use v2ref_commands::units::verify::VerifyJob;
use v2ref_commands::units::{Partial, UnitJob, FRAME_BYTES};

/// The commands that run in ranges of units.
const COMMANDS: &str = "simulate, piston, truth, powered, verify";

/// A command's job.
enum Job {
    Simulate(SimulateJob),
    Piston(PistonJob),
    Truth(TruthJob),
    Verify(VerifyJob),
}

/// The job of `command` from its binding's arguments.
fn job(command: &str, args: &Bound<'_, PyTuple>) -> PyResult<Job> {
    match command {
        "simulate" => {
            let (physical, bins, bias, formula, trials, seed, threads): (
                Bound<'_, PyDict>,
                String,
                String,
                String,
                u64,
                u64,
                usize,
            ) = args.extract()?;
            let job = simulate_job(&physical, &bins, &bias, &formula, trials, seed, threads)?;
            Ok(Job::Simulate(job))
        }
        "piston" => {
            let (physical, fringe_hz, bins, scans, seed, threads, psd, wind_angle_deg): (
                Bound<'_, PyDict>,
                Vec<f64>,
                String,
                usize,
                u64,
                usize,
                String,
                f64,
            ) = args.extract()?;
            let job = piston_job(
                &physical,
                fringe_hz,
                &bins,
                scans,
                seed,
                threads,
                &psd,
                wind_angle_deg,
            )?;
            Ok(Job::Piston(job))
        }
        "truth" => {
            // synthesize's arguments that the truth depends on.
            let (
                physical,
                rows,
                seed,
                threads,
                reference_blocks,
                layout,
                observations,
                dead_time_s,
            ): (
                Bound<'_, PyDict>,
                u64,
                u64,
                usize,
                Option<u64>,
                String,
                u64,
                f64,
            ) = args.extract()?;
            let job = truth_job(
                &physical,
                (rows, seed, threads, reference_blocks),
                (&layout, observations, dead_time_s),
            )?;
            Ok(Job::Truth(job))
        }
        "powered" => {
            // powered_set's vector and rows.
            let (name, rows, threads): (String, u64, usize) = args.extract()?;
            let v = crate::answers::powered::powered_vector(&name)?;
            let job = crate::answers::powered::powered_truth_job(&v, rows, threads);
            Ok(Job::Truth(job))
        }
        "verify" => {
            // plan's keywords, and the point verified.
            let (kw, fringe_hz, stroke_um, n, observations, threads): (
                Bound<'_, PyDict>,
                f64,
                f64,
                u64,
                u64,
                usize,
            ) = args.extract()?;
            let inputs = crate::answers::plan::plan_inputs(&kw)?;
            let point = (fringe_hz, stroke_um, n);
            Ok(Job::Verify(ok(VerifyJob::new(
                inputs,
                point,
                observations,
                threads,
            ))?))
        }
        _ => Err(PyValueError::new_err(format!(
            "command: {command:?} does not run in units (accepted: {COMMANDS})"
        ))),
    }
}

impl Job {
    fn key(&self) -> u64 {
        match self {
            Job::Simulate(j) => j.key(),
            Job::Piston(j) => j.key(),
            Job::Truth(j) => j.key(),
            Job::Verify(j) => j.key(),
        }
    }

    fn shape(&self) -> crate::Result<(u64, usize)> {
        match self {
            Job::Simulate(j) => j.shape(),
            Job::Piston(j) => j.shape(),
            Job::Truth(j) => j.shape(),
            Job::Verify(j) => j.shape(),
        }
    }

    fn run_range(
        &self,
        range: std::ops::Range<u64>,
        progress: &(dyn Fn(u64) + Sync),
    ) -> crate::Result<Partial> {
        match self {
            Job::Simulate(j) => j.run_range(range, progress),
            Job::Piston(j) => j.run_range(range, progress),
            Job::Truth(j) => j.run_range(range, progress),
            Job::Verify(j) => j.run_range(range, progress),
        }
    }

    fn reduce(&self, py: Python<'_>, partials: &[Partial]) -> PyResult<PyObject> {
        match self {
            Job::Simulate(j) => {
                let run = interruptible(py, |_| j.reduce(partials))?;
                simulate_answer(py, j, &run)
            }
            Job::Piston(j) => {
                let report = interruptible(py, |_| j.reduce(partials))?;
                to_py(py, &report)
            }
            Job::Truth(j) => {
                let truth = interruptible(py, |_| j.reduce(partials))?;
                to_py(py, &truth)
            }
            // The observations' means (plan reduces them with its answer).
            Job::Verify(j) => {
                let means = interruptible(py, |_| j.reduce(partials))?;
                to_py(py, &means)
            }
        }
    }
}

/// `(units, key, bytes)`: the number of work units, the request's key
/// (16 hex digits; the same for every thread count) and the size in bytes
/// of a partial result of `n` units, `bytes[0] + n * bytes[1]`.
#[pyfunction]
fn _units_count(
    py: Python<'_>,
    command: &str,
    args: &Bound<'_, PyTuple>,
) -> PyResult<(u64, String, (usize, usize))> {
    let job = job(command, args)?;
    let (units, words) = interruptible(py, |_| job.shape())?;
    let bytes = (FRAME_BYTES, 8 * words);
    Ok((units, format!("{:016x}", job.key()), bytes))
}

/// The partial result (bytes) of units `start..end`.
#[pyfunction]
fn _units_run<'py>(
    py: Python<'py>,
    command: &str,
    args: &Bound<'py, PyTuple>,
    start: u64,
    end: u64,
) -> PyResult<Bound<'py, PyBytes>> {
    let job = job(command, args)?;
    let partial = interruptible(py, |tick| job.run_range(start..end, tick))?;
    Ok(PyBytes::new(py, &partial.to_bytes()))
}

/// `(start, end)` of a partial result of this request; ValueError
/// (`partial: …`) for bytes that are not one.
#[pyfunction]
fn _units_check(command: &str, args: &Bound<'_, PyTuple>, partial: &[u8]) -> PyResult<(u64, u64)> {
    let job = job(command, args)?;
    let p = ok(Partial::from_bytes(partial, job.key()))?;
    Ok((p.range.start, p.range.end))
}

/// The command's answer from the partial results of every range, in unit
/// order.
#[pyfunction]
fn _units_reduce(
    py: Python<'_>,
    command: &str,
    args: &Bound<'_, PyTuple>,
    partials: Vec<Vec<u8>>,
) -> PyResult<PyObject> {
    let job = job(command, args)?;
    let key = job.key();
    let partials: Vec<Partial> = partials
        .iter()
        .map(|b| ok(Partial::from_bytes(b, key)))
        .collect::<PyResult<_>>()?;
    job.reduce(py, &partials)
}

/// The key of the spectrum table that `physical` names (16 hex digits of
/// its values' checksum; empty without a spectrum CSV): what keys a
/// checkpoint by the file's content, not its name.
#[pyfunction]
fn _spectrum_key(physical: &Bound<'_, PyDict>) -> PyResult<String> {
    let physical = crate::inputs::physical_from_dict(physical)?;
    let text = v2ref_commands::units::spectrum_key_text(&physical);
    Ok(if text.is_empty() {
        text
    } else {
        format!("{:016x}", v2ref_commands::units::checksum(text.as_bytes()))
    })
}

/// Adds the functions to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(_units_count, m)?)?;
    m.add_function(wrap_pyfunction!(_units_run, m)?)?;
    m.add_function(wrap_pyfunction!(_units_check, m)?)?;
    m.add_function(wrap_pyfunction!(_units_reduce, m)?)?;
    m.add_function(wrap_pyfunction!(_spectrum_key, m)?)?;
    Ok(())
}
