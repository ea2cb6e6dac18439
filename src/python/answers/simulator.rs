//! The end-to-end simulator and the conformance kit: `simulate`,
//! `synthesize`, `estimate`, `score`.

use super::data::{check_finite, data_error, estimate_column, matrix, parse_sidecar};
use super::{convention, formula, json, window};
use crate::commands::cost::{self, SetOutput};
use crate::commands::synth::{self as synth_set, SetSize};
use crate::conformance::estimate::{BiasConvention, RowEstimate, RowEstimator};
use crate::conformance::score::score_report;
use crate::error::Result;
use crate::formalism::estimator::{BinWindow, Pair};
use crate::noise::calibrated::Trials;
use crate::python::inputs::Physical;
use crate::python::{interruptible, ok, warn_cost};
use crate::simulator::report::{check_trials, Estimation, SimulateReport};
use crate::simulator::{simulate as run_simulation, Inputs, Model};
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde::Serialize;

use crate::commands::ESTIMATE_COLUMNS;

/// The first non-finite value of the interferograms, found without a
/// pass over all of them: a NaN or infinity in a row makes its raw
/// estimates non-finite (sums and products with unit-modulus twiddles
/// keep it), so only the rows whose raw estimates are not finite are
/// searched, in order.
fn check_rows_finite(data: &[f64], cols: usize, rows: &[RowEstimate]) -> PyResult<()> {
    for (r, e) in rows.iter().enumerate() {
        if e.v1_sq_raw.is_finite() && e.v2_sq_raw.is_finite() {
            continue;
        }
        let row = &data[r * cols..(r + 1) * cols];
        if let Some(c) = row.iter().position(|v| !v.is_finite()) {
            return Err(data_error(
                "interferograms",
                &format!("row {}, column {} (1-based)", r + 1, c + 1),
                &format!(
                    "{} is not a finite number; every value must be finite",
                    row[c]
                ),
            ));
        }
    }
    Ok(())
}

/// `estimate`: per-row V1², V2² (raw, bias, normalized), as `v2ref
/// estimate`. `physical` holds only the keyword arguments given;
/// `sidecar` is a sidecar's JSON text, `sidecar_name` where it came from.
#[pyfunction]
#[pyo3(signature = (interferograms, physical, sidecar, sidecar_name, continuum_subtracted, bins, bias, calibrator, threads))]
#[allow(clippy::too_many_arguments)]
pub(super) fn estimate<'py>(
    py: Python<'py>,
    interferograms: PyReadonlyArray2<'py, f64>,
    physical: &Bound<'py, PyDict>,
    sidecar: Option<&str>,
    sidecar_name: &str,
    continuum_subtracted: Option<bool>,
    bins: &str,
    bias: &str,
    calibrator: Option<PyReadonlyArray2<'py, f64>>,
    threads: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let window = ok(window(bins))?;
    let bias = ok(convention(bias))?;
    let (rows, cols, data) = matrix("interferograms", &interferograms)?;
    let given = Configuration {
        physical,
        sidecar: sidecar.map(|text| (text, sidecar_name)),
        continuum_subtracted,
    };
    let (inputs, continuum_subtracted) = configuration(given, rows, cols)?;
    warn_cost(
        py,
        "estimate",
        &ok(cost::estimate(&inputs, rows as u64, threads))?,
    )?;
    let cal = match &calibrator {
        None => None,
        Some(c) => Some(calibrator_rows(c, cols)?),
    };
    let rows = interruptible(py, |_| -> Result<Vec<RowEstimate>> {
        let model = Model::new(&inputs)?;
        let est = RowEstimator::new(&model, window, bias, continuum_subtracted)?;
        let est = match cal {
            None => est,
            Some(cdata) => {
                let cal_model = model.calibrator_model()?;
                let cal_est = RowEstimator::new(&cal_model, window, bias, continuum_subtracted)?;
                let c: Pair = cal_est.calibration_from_rows(cdata, threads)?;
                est.with_calibration(c)?
            }
        };
        est.estimate_rows(data, threads)
    })?;
    check_rows_finite(data, cols, &rows)?;
    estimate_columns(py, &rows)
}

/// Where `estimate` takes its configuration from: the keyword arguments
/// given, or a sidecar's JSON text and where it came from (then no
/// keyword may be given).
struct Configuration<'a, 'py> {
    physical: &'a Bound<'py, PyDict>,
    sidecar: Option<(&'a str, &'a str)>,
    continuum_subtracted: Option<bool>,
}

/// The inputs of `estimate` and whether the rows are continuum-subtracted,
/// checked against the `rows` × `cols` interferograms: a sidecar's must
/// match them; keyword arguments take their samples per row from them
/// unless a piston is modelled.
fn configuration(
    given: Configuration<'_, '_>,
    rows: usize,
    cols: usize,
) -> PyResult<(Inputs, bool)> {
    let (mut inputs, continuum_subtracted, strict) = match given.sidecar {
        Some((text, sidecar_name)) => {
            if let Some((k, _)) = given.physical.iter().next() {
                return Err(PyValueError::new_err(format!(
                    "{k}: cannot be used with sidecar (the configuration comes from it)"
                )));
            }
            if given.continuum_subtracted.is_some() {
                return Err(PyValueError::new_err(
                    "continuum_subtracted: cannot be used with sidecar (the configuration comes from it)",
                ));
            }
            let sc = parse_sidecar(text, sidecar_name)?;
            if rows as u64 != sc.data.rows {
                return Err(data_error(
                    "interferograms",
                    "",
                    &format!("{rows} rows; its sidecar says {}", sc.data.rows),
                ));
            }
            (sc.inputs, sc.continuum_subtracted, true)
        }
        None => {
            let p = Physical::from_dict(given.physical)?;
            (
                ok(p.inputs_unchecked())?,
                given.continuum_subtracted.unwrap_or(true),
                false,
            )
        }
    };
    if inputs.samples != cols {
        if strict || inputs.piston.is_some() {
            return Err(data_error(
                "interferograms",
                "",
                &format!(
                    "{cols} columns; the configuration has {} samples per row",
                    inputs.samples
                ),
            ));
        }
        inputs.samples = cols;
    }
    ok(inputs.validate())?;
    Ok((inputs, continuum_subtracted))
}

/// The calibrator's rows, checked: finite, with as many columns (`cols`)
/// as the interferograms.
fn calibrator_rows<'a>(c: &'a PyReadonlyArray2<'_, f64>, cols: usize) -> PyResult<&'a [f64]> {
    let (_, ccols, cdata) = matrix("calibrator", c)?;
    check_finite("calibrator", cdata, ccols)?;
    if ccols != cols {
        return Err(data_error(
            "calibrator",
            "",
            &format!("{ccols} columns; the interferograms have {cols}"),
        ));
    }
    Ok(cdata)
}

/// The per-row estimates as a dict of 1-D arrays, [`ESTIMATE_COLUMNS`].
fn estimate_columns<'py>(py: Python<'py>, rows: &[RowEstimate]) -> PyResult<Bound<'py, PyDict>> {
    let mut columns: [Vec<f64>; 6] = std::array::from_fn(|_| Vec::with_capacity(rows.len()));
    for e in rows {
        for (c, v) in columns.iter_mut().zip(e.values()) {
            c.push(v);
        }
    }
    let out = PyDict::new(py);
    for (name, c) in ESTIMATE_COLUMNS.iter().zip(columns) {
        out.set_item(name, PyArray1::from_vec(py, c))?;
    }
    Ok(out)
}

/// `synthesize`: a set's rows (2-D array) and its sidecar (JSON text), as
/// `v2ref synth` writes them; `npy` is the data file name recorded.
#[pyfunction]
#[pyo3(signature = (physical, rows, seed, threads, reference_blocks, keep_continuum, npy))]
#[allow(clippy::too_many_arguments)]
pub(super) fn synthesize<'py>(
    py: Python<'py>,
    physical: &Bound<'py, PyDict>,
    rows: u64,
    seed: u64,
    threads: usize,
    reference_blocks: Option<u64>,
    keep_continuum: bool,
    npy: String,
) -> PyResult<(Bound<'py, PyAny>, String)> {
    let inputs = ok(Physical::from_dict(physical)?.inputs())?;
    // None: sized by what the truth needs (`default_reference_blocks`).
    let reference_blocks = reference_blocks.unwrap_or_else(|| {
        crate::conformance::truth::default_reference_blocks(inputs.piston.is_some())
    });
    ok(crate::bounds::check_set_size(
        rows,
        inputs.samples,
        reference_blocks,
    ))?;
    let n = inputs.samples;
    let reference_rows = reference_blocks
        * crate::conformance::truth::reference_rows_per_block(
            rows,
            reference_blocks,
            inputs.piston.is_some(),
        );
    let predicted = cost::synth(&inputs, (rows, reference_rows), threads, SetOutput::Memory);
    warn_cost(py, "synthesize", &ok(predicted)?)?;
    let size = SetSize {
        rows,
        seed,
        reference_blocks,
        threads,
        keep_continuum,
    };
    let (data, sidecar) = interruptible(py, |tick| {
        let model = Model::new(&inputs)?;
        let mut data: Vec<f64> = Vec::with_capacity(rows as usize * n);
        let mut sink = |block: &[f64]| -> Result<()> {
            data.extend_from_slice(block);
            Ok(())
        };
        let sidecar = synth_set::synthesize(&model, &size, (npy, None), &mut sink, tick)?;
        Ok((data, sidecar))
    })?;
    let array = PyArray1::from_vec(py, data).reshape([rows as usize, n])?;
    Ok((array.into_any(), json(&sidecar)?))
}

/// `simulate`: the running statistics of `v2ref simulate --json`.
#[pyfunction]
#[pyo3(signature = (physical, bins, bias, formula, trials, seed, threads))]
#[allow(clippy::too_many_arguments)]
pub(super) fn simulate(
    py: Python<'_>,
    physical: &Bound<'_, PyDict>,
    bins: &str,
    bias: &str,
    formula: &str,
    trials: u64,
    seed: u64,
    threads: usize,
) -> PyResult<String> {
    let (window, bias, formula) = (
        ok(window(bins))?,
        ok(convention(bias))?,
        ok(self::formula(formula))?,
    );
    ok(check_trials(trials))?;
    let inputs = ok(Physical::from_dict(physical)?.inputs())?;
    let size = Trials {
        trials,
        seed,
        threads,
    };
    warn_cost(
        py,
        "simulate",
        &ok(cost::simulate(&inputs, trials, threads))?,
    )?;
    let run = interruptible(py, |tick| {
        let model = Model::new(&inputs)?;
        run_simulation(&model, window, bias, formula, size, tick)
    })?;
    let estimation = Estimation {
        window,
        bias,
        formula,
    };
    json(&SimulateReport::new(inputs, estimation, size, &run))
}

#[derive(Serialize)]
struct ScoreAnswer<'a> {
    sidecar: &'a str,
    estimates: &'a str,
    bins: BinWindow,
    bias: BiasConvention,
    rows: u64,
    #[serde(flatten)]
    report: &'a crate::conformance::score::ScoreReport,
}

/// `score`: `v2ref score --json`, the estimates as 1-D arrays (either may
/// be None, not both).
#[pyfunction]
#[pyo3(signature = (v1_sq, v2_sq, sidecar, sidecar_name, estimates_name, bins, bias, alpha))]
#[allow(clippy::too_many_arguments)]
pub(super) fn score(
    v1_sq: Option<PyReadonlyArray1<'_, f64>>,
    v2_sq: Option<PyReadonlyArray1<'_, f64>>,
    sidecar: &str,
    sidecar_name: &str,
    estimates_name: &str,
    bins: &str,
    bias: &str,
    alpha: f64,
) -> PyResult<String> {
    let window = ok(window(bins))?;
    let bias = ok(convention(bias))?;
    let sc = parse_sidecar(sidecar, sidecar_name)?;
    let truth = sc.truth(window, bias).ok_or_else(|| {
        data_error(
            "sidecar",
            &format!("{sidecar_name}: field truth.windows"),
            &format!(
                "no truth for bins={} bias={}; pick a window and convention the set has",
                window.name(),
                bias.name()
            ),
        )
    })?;
    if v1_sq.is_none() && v2_sq.is_none() {
        return Err(PyValueError::new_err(
            "estimates: no column named v1_sq or v2_sq; one of them is needed",
        ));
    }
    let mut slices: Vec<Option<&[f64]>> = Vec::new();
    for (name, col) in [("v1_sq", &v1_sq), ("v2_sq", &v2_sq)] {
        slices.push(match col {
            None => None,
            Some(a) => Some(estimate_column(name, a)?),
        });
    }
    let rows = sc.data.rows;
    let report = ok(score_report(slices[0], slices[1], truth, rows, alpha))?;
    json(&ScoreAnswer {
        sidecar: sidecar_name,
        estimates: estimates_name,
        bins: window,
        bias,
        rows,
        report: &report,
    })
}
