//! `powered_set`: a piston-free golden vector made large enough to catch a
//! 2 % error ([`Set::powered`]), in one process, or with its truth (8
//! times the set's rows, nearly all of its cost) computed in units
//! elsewhere (`v2ref.dask`) and the rows made here.

use crate::commands::synth::{self as synth_set, SetSize};
use crate::conformance::truth::{default_reference_blocks, TruthSize};
use crate::error::Result;
use crate::interruptible;
use crate::values::to_py;
use numpy::{PyArray1, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use v2ref_commands::units::truth::TruthJob;
use v2ref_commands::units::{Partial, UnitJob};
use v2ref_core::oracle::{catalogue, powered_rows, Model, Set, Vector};

/// The piston-free vector `name`; ValueError naming `name` and the
/// accepted names for another name or a vector with piston (its truth
/// would need replicates of the whole set).
pub(crate) fn powered_vector(name: &str) -> PyResult<Vector> {
    let all = catalogue();
    let accepted: Vec<&str> = all
        .iter()
        .filter(|v| v.inputs.piston.is_none())
        .map(|v| v.name)
        .collect();
    let accepted = accepted.join(", ");
    match all.iter().find(|v| v.name == name) {
        Some(v) if v.inputs.piston.is_none() => Ok(v.clone()),
        Some(_) => Err(PyValueError::new_err(format!(
            "name: {name:?} has piston (its truth needs replicates of the whole set: no powered set); accepted: {accepted}"
        ))),
        None => Err(PyValueError::new_err(format!(
            "name: no piston-free vector {name:?}; accepted: {accepted}"
        ))),
    }
}

/// The truth of the powered set of `v` with `rows` rows, as
/// [`Set::powered`] computes it (the vector's seed, the default reference
/// blocks of a piston-free set, the default layout).
pub(crate) fn powered_truth_job(v: &Vector, rows: u64, threads: usize) -> TruthJob {
    TruthJob {
        inputs: v.inputs.clone(),
        size: TruthSize {
            rows,
            seed: v.seed,
            reference_blocks: default_reference_blocks(false),
            threads,
        },
        layout: Default::default(),
    }
}

/// `_powered_rows`: the rows of vector `name`'s powered set (from a pilot
/// truth of 8192 rows, computed here: [`powered_rows`]).
#[pyfunction]
pub(super) fn _powered_rows(py: Python<'_>, name: &str) -> PyResult<u64> {
    let v = powered_vector(name)?;
    interruptible(py, |_| powered_rows(&v))
}

/// `powered_set`: the rows (2-D array) and sidecar (dict) of
/// [`Set::powered`]`(name)`; with `truth_partials` (the partial results of
/// [`powered_truth_job`] for `rows` rows, in unit order) its truth is
/// reduced from them and only the rows are made here.
#[pyfunction]
#[pyo3(signature = (name, rows=None, truth_partials=None))]
pub(super) fn powered_set<'py>(
    py: Python<'py>,
    name: &str,
    rows: Option<u64>,
    truth_partials: Option<Vec<Vec<u8>>>,
) -> PyResult<(Bound<'py, PyAny>, PyObject)> {
    let v = powered_vector(name)?;
    let n = v.inputs.samples;
    let (data, sidecar) = match (rows, truth_partials) {
        (Some(rows), Some(bytes)) => {
            super::data::check_array_fits(rows, n)?;
            interruptible(py, |tick| from_partials(&v, rows, &bytes, tick))?
        }
        _ => {
            let set = interruptible(py, |_| Set::powered(name))?;
            (set.values().to_vec(), set.sidecar().clone())
        }
    };
    let rows = data.len() / n;
    let array = PyArray1::from_vec(py, data).reshape([rows, n])?;
    Ok((array.into_any(), to_py(py, &sidecar)?))
}

/// The powered set of `v` with its truth reduced from `bytes`, the rows
/// made as [`Set::powered`] makes them.
fn from_partials(
    v: &Vector,
    rows: u64,
    bytes: &[Vec<u8>],
    progress: &(dyn Fn(u64) + Sync),
) -> Result<(Vec<f64>, crate::conformance::sidecar::Sidecar)> {
    let job = powered_truth_job(v, rows, 0);
    let partials = bytes
        .iter()
        .map(|b| Partial::from_bytes(b, job.key()))
        .collect::<Result<Vec<_>>>()?;
    let truth = job.reduce(&partials)?;
    let model = Model::new(&v.inputs)?;
    crate::bounds::check_set_size(rows, v.inputs.samples, job.size.reference_blocks)?;
    let size = SetSize {
        rows,
        seed: v.seed,
        reference_blocks: job.size.reference_blocks,
        threads: 0,
        keep_continuum: false,
        layout: job.layout,
    };
    let mut data: Vec<f64> = Vec::with_capacity(rows as usize * v.inputs.samples);
    let mut sink = |block: &[f64]| -> Result<()> {
        data.extend_from_slice(block);
        Ok(())
    };
    let files = (format!("{}.npy", v.name), None);
    let sidecar =
        synth_set::synthesize_with_truth(&model, &size, truth, files, &mut sink, progress)?;
    Ok((data, sidecar))
}
