//! The conformance kit of a dispersed set (C spectral channels a scan,
//! `docs/conventions.md` §16): its rows as arrays (rows, C, N), its
//! estimates as arrays (rows, C), its score channel by channel. One
//! channel keeps the wide-band shapes (rows, N) and (rows,) unless the
//! rows were given as (rows, 1, N).

use super::data::{data_error, parse_sidecar};
use crate::commands::estimate::{self as rows_estimate, CalibratorRows, Configuration};
use crate::conformance::channel_score::score_channels;
use crate::conformance::channels::synthesize_channels;
use crate::conformance::estimate::{BiasConvention, RowEstimate};
use crate::conformance::score::Estimates;
use crate::conformance::sidecar::{ConventionTruth, Sidecar};
use crate::conformance::synth::SetSize;
use crate::error::Result;
use crate::formalism::channels::Channels;
use crate::formalism::estimator::BinWindow;
use crate::parameters::Physical;
use crate::values::to_py;
use crate::{interruptible, ok};
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde::Serialize;

use crate::commands::ESTIMATE_COLUMNS;

/// The dispersed set of `p` cut in `channels` (given by the keyword
/// `input`): its rows (rows, C, N), or (rows, N) for one channel, and its
/// sidecar; with `out`, written as `v2ref synth --out` writes it.
pub(super) fn synthesize<'py>(
    py: Python<'py>,
    (p, channels, input): (&Physical, Channels, &'static str),
    size: SetSize,
    npy: String,
    (out, force): (Option<std::path::PathBuf>, bool),
) -> PyResult<(Bound<'py, PyAny>, PyObject)> {
    let inputs = ok(p.inputs())?;
    let (rows, c, n) = (size.rows, channels.count(), inputs.samples);
    super::data::check_array_fits(rows, c * n)?;
    let (data, sidecar) = interruptible(py, |tick| {
        let mut data: Vec<f64> = Vec::with_capacity(rows as usize * c * n);
        let mut sink = |block: &[f64]| -> Result<()> {
            data.extend_from_slice(block);
            Ok(())
        };
        let files = (npy, None);
        let sidecar = synthesize_channels(&inputs, &channels, &size, files, &mut sink, tick)
            .map_err(|e| crate::commands::channels::renamed(e, input))?;
        Ok((data, sidecar))
    })?;
    let row_shape: &[usize] = if c == 1 { &[n] } else { &[c, n] };
    if let Some(out) = out {
        crate::output::write_set(py, &out, (&data, row_shape), &sidecar, force)?;
    }
    let flat = PyArray1::from_vec(py, data);
    let array = match c {
        1 => flat.reshape([rows as usize, n])?.into_any(),
        _ => flat.reshape([rows as usize, c, n])?.into_any(),
    };
    Ok((array, to_py(py, &sidecar)?))
}

/// Refuses rows whose channel axis (`given`: axis 1 of a 3-D array, None
/// for a 2-D one) is not the configuration's C.
pub(super) fn check_channel_axis(param: &str, given: Option<usize>, c: usize) -> PyResult<()> {
    match given {
        Some(g) if g == c => Ok(()),
        None if c == 1 => Ok(()),
        Some(g) => Err(data_error(
            param,
            "",
            &format!(
                "{g} channels (axis 1 of a 3-D array); the configuration has C = {c}: an array of shape (rows, {c}, N) is needed"
            ),
        )),
        None => Err(data_error(
            param,
            "",
            &format!(
                "a 2-D array; the configuration has C = {c} channels: an array of shape (rows, {c}, N) is needed, channel after channel"
            ),
        )),
    }
}

/// The per-channel estimates of `data` (`rows` rows of C × N values) under
/// `config` (which has channels).
pub(super) fn estimate_channels(
    py: Python<'_>,
    config: &Configuration,
    (rows, cols, data): (usize, usize, &[f64]),
    options: (BinWindow, BiasConvention),
    calibrator: Option<CalibratorRows<'_>>,
    threads: usize,
) -> PyResult<Vec<Vec<RowEstimate>>> {
    let channels = config.channels.as_ref().expect("a dispersed configuration");
    let inputs = ok(config.inputs_for(super::data::INTERFEROGRAMS, rows, cols))?;
    interruptible(py, |_| {
        let cs = config.continuum_subtracted;
        let ests =
            rows_estimate::channel_estimators(&inputs, channels, options, cs, calibrator, threads)?;
        let mut out: Vec<Vec<RowEstimate>> = vec![Vec::with_capacity(rows); ests.len()];
        // A block of rows at a time, as the CLI streams a file.
        let block_len = (rows_estimate::STREAM_ROWS * cols).max(1);
        for (k, block) in data.chunks(block_len).enumerate() {
            let at = (block, k * rows_estimate::STREAM_ROWS);
            let name = super::data::INTERFEROGRAMS;
            let part = rows_estimate::estimate_channel_rows(&ests, name, at, threads)?;
            for (o, p) in out.iter_mut().zip(part) {
                o.extend(p);
            }
        }
        Ok(out)
    })
}

/// The per-channel estimates as a dict of arrays (rows, C) per column of
/// [`ESTIMATE_COLUMNS`] (row-major: row r, channel j at `r·C + j`).
pub(super) fn channel_columns<'py>(
    py: Python<'py>,
    channels: &[Vec<RowEstimate>],
) -> PyResult<Bound<'py, PyDict>> {
    let c = channels.len();
    let rows = channels.first().map_or(0, Vec::len);
    let mut columns: [Vec<f64>; 6] = std::array::from_fn(|_| vec![0.0; rows * c]);
    for (j, list) in channels.iter().enumerate() {
        for (r, e) in list.iter().enumerate() {
            for (col, v) in columns.iter_mut().zip(e.values()) {
                col[r * c + j] = v;
            }
        }
    }
    let out = PyDict::new(py);
    for (name, col) in ESTIMATE_COLUMNS.iter().zip(columns) {
        out.set_item(name, PyArray1::from_vec(py, col).reshape([rows, c])?)?;
    }
    Ok(out)
}

#[derive(Serialize)]
struct ChannelScoreAnswer<'a> {
    sidecar: &'a str,
    estimates: &'a str,
    bins: BinWindow,
    bias: BiasConvention,
    rows: u64,
    #[serde(flatten)]
    report: &'a crate::conformance::channel_score::ChannelScoreReport,
}

/// Each channel's column of a (rows, C) estimate array, checked finite.
fn channel_slices(name: &str, a: &PyReadonlyArray2<'_, f64>, c: usize) -> PyResult<Vec<Vec<f64>>> {
    let shape = a.shape();
    if shape[1] != c {
        return Err(data_error(
            "estimates",
            "",
            &format!(
                "{name} has {} columns; the set has C = {c} channels: an array of shape (rows, {c}) is needed",
                shape[1]
            ),
        ));
    }
    let view = a.as_array();
    let mut out = Vec::with_capacity(c);
    for j in 0..c {
        let col: Vec<f64> = view.column(j).to_vec();
        if let Some(r) = col.iter().position(|v| !v.is_finite()) {
            return Err(data_error(
                "estimates",
                &format!("row {} (1-based), column {name}, channel {}", r + 1, j + 1),
                &format!(
                    "{} is not a finite number; every value must be finite",
                    col[r]
                ),
            ));
        }
        out.push(col);
    }
    Ok(out)
}

/// The truth of each channel of `sc` under `window` and `bias`.
fn channel_truths<'s>(
    sc: &'s Sidecar,
    sidecar_name: &str,
    (window, bias): (BinWindow, BiasConvention),
) -> PyResult<Vec<&'s ConventionTruth>> {
    let Some(list) = &sc.channels else {
        return Err(PyValueError::new_err(
            "estimates: (rows, C) arrays, but the set is wide-band (its sidecar lists no channels); give 1-D arrays (rows,)",
        ));
    };
    ok(sc.channels())?;
    list.iter()
        .enumerate()
        .map(|(j, ch)| {
            let w = ch.truth.windows.iter().find(|w| w.bins == window);
            w.and_then(|w| w.conventions.iter().find(|t| t.bias == bias))
                .ok_or_else(|| {
                    data_error(
                        "sidecar",
                        &format!("{sidecar_name}: channel {}: field truth.windows", j + 1),
                        &format!(
                            "no truth for bins={} bias={}; pick a window and convention the set has",
                            window.name(),
                            bias.name()
                        ),
                    )
                })
        })
        .collect()
}

/// `score_channels`: a dispersed set's estimates, (rows, C) arrays (either
/// may be None, not both), scored channel by channel under one threshold
/// (the library's `ChannelScoreReport`, with the names of the inputs,
/// the window, bias and rows).
#[pyfunction]
#[pyo3(signature = (v1_sq, v2_sq, sidecar, sidecar_name, estimates_name, bins, bias, alpha))]
#[allow(clippy::too_many_arguments)]
pub(super) fn score_channels_answer(
    py: Python<'_>,
    v1_sq: Option<PyReadonlyArray2<'_, f64>>,
    v2_sq: Option<PyReadonlyArray2<'_, f64>>,
    sidecar: &Bound<'_, PyAny>,
    sidecar_name: &str,
    estimates_name: &str,
    bins: &str,
    bias: &str,
    alpha: f64,
) -> PyResult<PyObject> {
    let window = ok(super::window(bins))?;
    let bias = ok(super::convention(bias))?;
    let sc = parse_sidecar(sidecar, sidecar_name)?;
    let truths = channel_truths(&sc, sidecar_name, (window, bias))?;
    let c = truths.len();
    if v1_sq.is_none() && v2_sq.is_none() {
        return Err(PyValueError::new_err(
            "estimates: no column named v1_sq or v2_sq; one of them is needed",
        ));
    }
    let v1 = v1_sq
        .as_ref()
        .map(|a| channel_slices("v1_sq", a, c))
        .transpose()?;
    let v2 = v2_sq
        .as_ref()
        .map(|a| channel_slices("v2_sq", a, c))
        .transpose()?;
    let estimates: Vec<Estimates<'_>> = (0..c)
        .map(|j| {
            let mut e = Estimates::default();
            if let Some(v) = &v1 {
                e = e.v1_sq(&v[j]);
            }
            if let Some(v) = &v2 {
                e = e.v2_sq(&v[j]);
            }
            e
        })
        .collect();
    let rows = sc.data.rows;
    let report = ok(score_channels(&estimates, &truths, rows, alpha))?;
    to_py(
        py,
        &ChannelScoreAnswer {
            sidecar: sidecar_name,
            estimates: estimates_name,
            bins: window,
            bias,
            rows,
            report: &report,
        },
    )
}
