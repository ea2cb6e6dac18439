//! The end-to-end simulator and the conformance kit: `simulate`,
//! `synthesize`, `estimate`, `score`.

use super::data::{
    check_array_fits, data_error, estimate_column, matrix, parse_sidecar, INTERFEROGRAMS,
};
use super::{convention, dispersed, formula, window};
use crate::commands::estimate::{self as rows_estimate, CalibratorRows, Configuration, RowsName};
use crate::commands::synth::{self as synth_set, SetSize};
use crate::conformance::estimate::{BiasConvention, RowEstimate};
use crate::conformance::score::score_report;
use crate::error::Result;
use crate::formalism::estimator::BinWindow;
use crate::noise::calibrated::Trials;
use crate::report::simulator::{check_trials, Estimation, SimulateReport};
use crate::simulator::{simulate as run_simulation, Model, SimulationRun};
use crate::values::to_py;
use crate::{interruptible, ok};
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde::Serialize;
use v2ref_commands::units::simulate::SimulateJob;
use v2ref_commands::units::truth::TruthJob;
use v2ref_commands::units::{Partial, UnitJob};

use crate::commands::ESTIMATE_COLUMNS;

/// `estimate`: per-row V1², V2² (raw, bias, normalized), as `v2ref
/// estimate`. `physical` holds only the keyword arguments given;
/// `sidecar` is a sidecar (a file's text or a dict), `sidecar_name` where
/// it came from.
#[pyfunction]
#[pyo3(signature = (interferograms, physical, sidecar, sidecar_name, continuum_subtracted, bins, bias, calibrator, threads, channel_axis=None))]
#[allow(clippy::too_many_arguments)]
pub(super) fn estimate<'py>(
    py: Python<'py>,
    interferograms: PyReadonlyArray2<'py, f64>,
    physical: &Bound<'py, PyDict>,
    sidecar: Option<Bound<'py, PyAny>>,
    sidecar_name: &str,
    continuum_subtracted: Option<bool>,
    bins: &str,
    bias: &str,
    calibrator: Option<PyReadonlyArray2<'py, f64>>,
    threads: usize,
    channel_axis: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let window = ok(window(bins))?;
    let bias = ok(convention(bias))?;
    let (rows, cols, data) = matrix("interferograms", &interferograms)?;
    let given = Given {
        physical,
        sidecar: sidecar.as_ref().map(|s| (s, sidecar_name)),
        continuum_subtracted,
    };
    let config = configuration(given)?;
    dispersed::check_channel_axis("interferograms", channel_axis, config.channel_count())?;
    let cal = match &calibrator {
        None => None,
        Some(c) => {
            let (_, cols, rows) = matrix("calibrator", c)?;
            Some(CalibratorRows {
                name: RowsName {
                    param: "calibrator",
                    path: None,
                },
                rows,
                cols,
            })
        }
    };
    if config.channels.is_some() {
        let options = (window, bias);
        let at = (rows, cols, data);
        let per_channel = dispersed::estimate_channels(py, &config, at, options, cal, threads)?;
        return match channel_axis {
            None => estimate_columns(py, &per_channel[0]),
            Some(_) => dispersed::channel_columns(py, &per_channel),
        };
    }
    let inputs = ok(config.inputs_for(INTERFEROGRAMS, rows, cols))?;
    let rows = interruptible(py, |_| -> Result<Vec<RowEstimate>> {
        let options = (window, bias);
        let cs = config.continuum_subtracted;
        let est = rows_estimate::estimator(&inputs, options, cs, cal, threads)?;
        // A block of rows at a time, as the CLI streams a file: a bad row of
        // a memory-mapped array is refused once its block is read.
        let mut out = Vec::with_capacity(rows);
        let block_len = (rows_estimate::STREAM_ROWS * cols).max(1);
        for (k, block) in data.chunks(block_len).enumerate() {
            let at = (block, k * rows_estimate::STREAM_ROWS);
            out.extend(rows_estimate::estimate_rows(
                &est,
                INTERFEROGRAMS,
                at,
                threads,
            )?);
        }
        Ok(out)
    })?;
    estimate_columns(py, &rows)
}

/// Where `estimate` takes its configuration from: the keyword arguments
/// given, or a sidecar's JSON text and where it came from (then no
/// keyword may be given).
struct Given<'a, 'py> {
    physical: &'a Bound<'py, PyDict>,
    sidecar: Option<(&'a Bound<'py, PyAny>, &'a str)>,
    continuum_subtracted: Option<bool>,
}

/// The configuration of `estimate`: a sidecar's (its set's rows, its
/// channels), or the keyword arguments' (N from the rows; C from the
/// channel keywords).
fn configuration(given: Given<'_, '_>) -> PyResult<Configuration> {
    let Some((sidecar, sidecar_name)) = given.sidecar else {
        let p = crate::inputs::physical_from_dict(given.physical)?;
        let cs = given.continuum_subtracted.unwrap_or(true);
        let config = ok(Configuration::from_physical(&p, cs))?;
        return match ok(crate::commands::channels::given(&p))? {
            None => Ok(config),
            Some((channels, input)) => ok(config
                .with_channels(channels)
                .map_err(|e| crate::commands::channels::renamed(e, input))),
        };
    };
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
    // Any number of rows of the set's N, as the CLI's `estimate --sidecar
    // SET.json --input ROWS` takes them (a subset of the set's rows, one
    // observation of an observation-layout set).
    Ok(Configuration {
        set_rows: None,
        ..ok(Configuration::read_sidecar(parse_sidecar(
            sidecar,
            sidecar_name,
        )?))?
    })
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

/// `synthesize`: a set's rows (2-D array) and its sidecar (a dict), as
/// `v2ref synth` writes them; `npy` is the data file name recorded. With
/// `out`, also writes the set as `v2ref synth --out OUT` does
/// ([`super::super::output::write_set`]).
/// `truth_partials`: the partial results of the truth's reference run
/// ([`TruthJob`], computed in ranges elsewhere, in unit order).
#[pyfunction]
#[pyo3(signature = (physical, rows, seed, threads, reference_blocks, keep_continuum, npy, layout, out, force, observations=1, dead_time_s=0.0, truth_partials=None))]
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
    layout: &str,
    out: Option<std::path::PathBuf>,
    force: bool,
    observations: u64,
    dead_time_s: f64,
    truth_partials: Option<Vec<Vec<u8>>>,
) -> PyResult<(Bound<'py, PyAny>, PyObject)> {
    let p = crate::inputs::physical_from_dict(physical)?;
    if truth_partials.is_none() {
        if let Some((channels, input)) = ok(crate::commands::channels::given(&p))? {
            let timing = crate::simulator::RowTiming::new(
                ok(crate::simulator::RowLayout::from_name(layout))?,
                observations,
                dead_time_s,
            );
            let piston = ok(p.inputs())?.piston.is_some();
            let reference_blocks = reference_blocks
                .unwrap_or_else(|| crate::conformance::truth::default_reference_blocks(piston));
            let size = SetSize {
                rows,
                seed,
                reference_blocks,
                threads,
                keep_continuum,
                layout: ok(timing)?,
            };
            let set = (&p, channels, input);
            return dispersed::synthesize(py, set, size, npy, (out, force));
        }
    }
    let job = truth_job(
        physical,
        (rows, seed, threads, reference_blocks),
        (layout, observations, dead_time_s),
    )?;
    let (inputs, layout, reference_blocks) = (&job.inputs, job.layout, job.size.reference_blocks);
    ok(crate::bounds::check_set_size(
        rows,
        inputs.samples,
        reference_blocks,
    ))?;
    let n = inputs.samples;
    check_array_fits(rows, n)?;
    let size = SetSize {
        rows,
        seed,
        reference_blocks,
        threads,
        keep_continuum,
        layout,
    };
    let (data, sidecar) = interruptible(py, |tick| {
        let model = Model::new(inputs)?;
        let mut data: Vec<f64> = Vec::with_capacity(rows as usize * n);
        let mut sink = |block: &[f64]| -> Result<()> {
            data.extend_from_slice(block);
            Ok(())
        };
        let files = (npy, None);
        let sidecar = match &truth_partials {
            None => synth_set::synthesize(&model, &size, files, &mut sink, tick)?,
            Some(bytes) => {
                let partials = bytes
                    .iter()
                    .map(|b| Partial::from_bytes(b, job.key()))
                    .collect::<Result<Vec<_>>>()?;
                let truth = job.reduce(&partials)?;
                synth_set::synthesize_with_truth(&model, &size, truth, files, &mut sink, tick)?
            }
        };
        Ok((data, sidecar))
    })?;
    if let Some(out) = out {
        crate::output::write_set(py, &out, (&data, &[n]), &sidecar, force)?;
    }
    let array = PyArray1::from_vec(py, data).reshape([rows as usize, n])?;
    Ok((array.into_any(), to_py(py, &sidecar)?))
}

/// The truth of `synthesize`'s set as ranges of units (`reference_blocks`
/// None: sized by what the truth needs, `default_reference_blocks`).
pub(crate) fn truth_job(
    physical: &Bound<'_, PyDict>,
    (rows, seed, threads, reference_blocks): (u64, u64, usize, Option<u64>),
    (layout, observations, dead_time_s): (&str, u64, f64),
) -> PyResult<TruthJob> {
    let layout = ok(crate::simulator::RowLayout::from_name(layout))?;
    let layout = ok(crate::simulator::RowTiming::new(
        layout,
        observations,
        dead_time_s,
    ))?;
    let p = crate::inputs::physical_from_dict(physical)?;
    ok(p.refuse_channels("synthesize with client or checkpoint"))?;
    let inputs = ok(p.inputs())?;
    let reference_blocks = reference_blocks.unwrap_or_else(|| {
        crate::conformance::truth::default_reference_blocks(inputs.piston.is_some())
    });
    let size = crate::conformance::truth::TruthSize {
        rows,
        seed,
        reference_blocks,
        threads,
    };
    Ok(TruthJob {
        inputs,
        size,
        layout,
    })
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
) -> PyResult<PyObject> {
    let p = crate::inputs::physical_from_dict(physical)?;
    if let Some(channels) = ok(crate::commands::channels::given(&p))? {
        let estimation = Estimation {
            window: ok(window(bins))?,
            bias: ok(convention(bias))?,
            formula: ok(self::formula(formula))?,
        };
        let size = Trials {
            trials,
            seed,
            threads,
        };
        let answer = interruptible(py, |_| {
            crate::commands::channels_simulate::simulate(
                &p,
                (&channels.0, channels.1),
                estimation,
                size,
            )
        })?;
        return to_py(py, &answer);
    }
    let job = simulate_job(physical, bins, bias, formula, trials, seed, threads)?;
    let (inputs, size) = (&job.inputs, job.size);
    let run = interruptible(py, |tick| {
        let model = Model::new(inputs)?;
        let e = job.estimation;
        run_simulation(&model, e.window, e.bias, e.formula, size, tick)
    })?;
    simulate_answer(py, &job, &run)
}

/// The request of [`simulate`] from its arguments (also parsed so by the
/// functions of a run split in ranges of units, `crate::units`).
#[allow(clippy::too_many_arguments)]
pub(crate) fn simulate_job(
    physical: &Bound<'_, PyDict>,
    bins: &str,
    bias: &str,
    formula: &str,
    trials: u64,
    seed: u64,
    threads: usize,
) -> PyResult<SimulateJob> {
    let estimation = Estimation {
        window: ok(window(bins))?,
        bias: ok(convention(bias))?,
        formula: ok(self::formula(formula))?,
    };
    ok(check_trials(trials))?;
    let p = crate::inputs::physical_from_dict(physical)?;
    ok(p.refuse_channels("simulate with client or checkpoint"))?;
    let inputs = ok(p.inputs())?;
    let size = Trials {
        trials,
        seed,
        threads,
    };
    Ok(SimulateJob {
        inputs,
        estimation,
        size,
    })
}

/// [`simulate`]'s answer from the run of `job`.
pub(crate) fn simulate_answer(
    py: Python<'_>,
    job: &SimulateJob,
    run: &SimulationRun,
) -> PyResult<PyObject> {
    let report = SimulateReport::new(job.inputs.clone(), job.estimation, job.size, run);
    to_py(py, &report)
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
    py: Python<'_>,
    v1_sq: Option<PyReadonlyArray1<'_, f64>>,
    v2_sq: Option<PyReadonlyArray1<'_, f64>>,
    sidecar: &Bound<'_, PyAny>,
    sidecar_name: &str,
    estimates_name: &str,
    bins: &str,
    bias: &str,
    alpha: f64,
) -> PyResult<PyObject> {
    let window = ok(window(bins))?;
    let bias = ok(convention(bias))?;
    let sc = parse_sidecar(sidecar, sidecar_name)?;
    let c = sc.channel_count();
    if c > 1 {
        // Its top-level truth is the whole band's closed forms, not what
        // any channel's rows give: a dispersed set is scored per channel.
        return Err(PyValueError::new_err(format!(
            "estimates: 1-D arrays; the set has C = {c} channels: give v1_sq and/or v2_sq as arrays of shape (rows, {c}), one column per channel"
        )));
    }
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
    to_py(
        py,
        &ScoreAnswer {
            sidecar: sidecar_name,
            estimates: estimates_name,
            bins: window,
            bias,
            rows,
            report: &report,
        },
    )
}
