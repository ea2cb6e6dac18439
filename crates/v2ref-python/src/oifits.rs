//! OIFITS from Python: the library's reader and writers
//! (`crate::formats::oifits`) with NumPy arrays in and out. The Python
//! wrappers (`python/v2ref/oifits.py`) check types and read sidecars.

use super::ok;
use super::values::{to_py, SidecarArg};
use crate::conformance::estimate::BiasConvention;
use crate::conformance::score::Estimator;
use crate::conformance::sidecar::{Sidecar, FORMAT};
use crate::formalism::estimator::BinWindow;
use crate::simulator::Model;
use crate::words::Words;
use crate::Error;
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::Path;
use v2ref_oifits::{self as oifits, docs, Expected, ObservingContext, ObservingSpec};

/// The library's parameter `from` renamed `to` (the Python keyword).
fn renamed(e: Error, from: &str, to: &'static str) -> Error {
    match e {
        Error::Data {
            param,
            path,
            location,
            reason,
        } if param == from => Error::Data {
            param: to,
            path,
            location,
            reason,
        },
        other => other,
    }
}

/// A sidecar from a file's text or a dict (`name`: where it came from).
fn sidecar_of(sidecar: &Bound<'_, PyAny>, name: &str) -> PyResult<Sidecar> {
    let parsed = match SidecarArg::of(sidecar)? {
        SidecarArg::Text(text) => serde_json::from_str(&text),
        SidecarArg::Value(v) => serde_json::from_value(v),
    };
    let sc: Sidecar = parsed
        .map_err(|e| PyValueError::new_err(format!("sidecar: {name}: not a v2ref sidecar: {e}")))?;
    if sc.format != FORMAT {
        return Err(PyValueError::new_err(format!(
            "sidecar: {name}: format {:?}; \"{FORMAT}\" is needed",
            sc.format
        )));
    }
    Ok(sc)
}

/// The keywords `target_name`, `ra_deg`, `dec_deg`, `date`, `site`,
/// `site_lon_deg`, `site_lat_deg`, `site_height_m` in that order, as the
/// Python wrappers pass them (types checked there).
pub(crate) type ObservingKeywords = (
    Option<String>,
    Option<f64>,
    Option<f64>,
    Option<String>,
    Option<String>,
    Option<f64>,
    Option<f64>,
    Option<f64>,
);

/// Where and when an OIFITS file says (None: every default), checked by
/// the library (ValueError naming the keyword); any given is refused when
/// no file is written (`writes` false; `what_writes` says what would).
pub(crate) fn observing_of(
    keywords: Option<ObservingKeywords>,
    writes: bool,
    what_writes: &str,
) -> PyResult<ObservingContext> {
    let Some((target_name, ra_deg, dec_deg, date, site, lon, lat, height)) = keywords else {
        return Ok(ObservingContext::default());
    };
    let spec = ObservingSpec {
        target_name,
        ra_deg,
        dec_deg,
        date,
        site,
        site_lon_deg: lon,
        site_lat_deg: lat,
        site_height_m: height,
    };
    ok(spec.resolve_for(writes, what_writes))
}

fn estimator_name(e: Estimator) -> &'static str {
    e.name()
}

/// The `OI_VIS2` tables of an OIFITS file of `insname` (every one when
/// None), with the rows of `target` (every row when None), as `score`
/// chooses them: `{"tables": [dict], "notes": [str]}`, each table a dict
/// (`insname`, `estimator`, `revn`, `hdu`, `eff_wave_m`, `eff_band_m`,
/// per row `target_id`, `mjd`, `ucoord_m`, `vcoord_m`, and `vis2data`,
/// `vis2err`, `flag` of shape (rows, nwave)).
#[pyfunction]
#[pyo3(signature = (path, insname=None, target=None, accept_checksum_mismatch=false))]
fn read_oifits<'py>(
    py: Python<'py>,
    path: &str,
    insname: Option<&str>,
    target: Option<&str>,
    accept_checksum_mismatch: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let options = oifits::ReadOptions {
        accept_checksum_mismatch,
    };
    let file = ok(oifits::read_oifits_file(Path::new(path), "path", options))?;
    let tables = ok(oifits::choose_tables(
        &file,
        insname,
        target,
        Path::new(path),
    ))?;
    let out = PyList::empty(py);
    for t in tables {
        out.append(table_dict(py, t)?)?;
    }
    let d = PyDict::new(py);
    d.set_item("tables", out)?;
    d.set_item("notes", file.notes)?;
    Ok(d)
}

/// One `OI_VIS2` table as `read_oifits` returns it.
fn table_dict(py: Python<'_>, t: oifits::Vis2Table) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    let shape = [t.rows, t.nwave];
    d.set_item("insname", &t.insname)?;
    let est = match t.estimator.as_deref() {
        Some("V1SQ") => Some("v1_sq"),
        Some("V2SQ") => Some("v2_sq"),
        _ => None,
    };
    d.set_item("estimator", est)?;
    d.set_item("revn", t.revn)?;
    d.set_item("hdu", t.hdu)?;
    d.set_item("eff_wave_m", PyArray1::from_vec(py, t.eff_wave_m))?;
    d.set_item("eff_band_m", PyArray1::from_vec(py, t.eff_band_m))?;
    d.set_item("target_id", PyArray1::from_vec(py, t.target_id))?;
    d.set_item("mjd", PyArray1::from_vec(py, t.mjd))?;
    d.set_item("ucoord_m", PyArray1::from_vec(py, t.ucoord_m))?;
    d.set_item("vcoord_m", PyArray1::from_vec(py, t.vcoord_m))?;
    d.set_item(
        "vis2data",
        PyArray1::from_vec(py, t.vis2data).reshape(shape)?,
    )?;
    d.set_item("vis2err", PyArray1::from_vec(py, t.vis2err).reshape(shape)?)?;
    d.set_item("flag", PyArray1::from_vec(py, t.flag).reshape(shape)?)?;
    Ok(d)
}

/// Per-row estimates of a synth set written as OIFITS v2 (one table per
/// array given), the configuration from the sidecar, where and when
/// `observing` says.
#[pyfunction]
#[pyo3(signature = (path, v1_sq, v2_sq, sidecar, sidecar_name, bins, bias, observing=None, force=false))]
#[allow(clippy::too_many_arguments)] // one per keyword of the Python wrapper
fn write_oifits(
    path: &str,
    v1_sq: Option<PyReadonlyArray1<'_, f64>>,
    v2_sq: Option<PyReadonlyArray1<'_, f64>>,
    sidecar: &Bound<'_, PyAny>,
    sidecar_name: &str,
    bins: &str,
    bias: &str,
    observing: Option<ObservingKeywords>,
    force: bool,
) -> PyResult<()> {
    let bins: BinWindow = ok(Words::from_word("bins", bins))?;
    let bias: BiasConvention = ok(Words::from_word("bias", bias))?;
    let observing = observing_of(observing, true, "path")?;
    let sc = sidecar_of(sidecar, sidecar_name)?;
    let mut columns = Vec::new();
    for (e, a) in [(Estimator::V1Sq, v1_sq), (Estimator::V2Sq, v2_sq)] {
        if let Some(a) = a {
            let v = a
                .as_slice()
                .map(<[f64]>::to_vec)
                .unwrap_or_else(|_| a.as_array().to_vec());
            if v.len() as u64 != sc.data.rows {
                return Err(PyValueError::new_err(format!(
                    "{}: {} values; the set has {} rows",
                    estimator_name(e),
                    v.len(),
                    sc.data.rows
                )));
            }
            columns.push((e, v));
        }
    }
    if columns.is_empty() {
        return Err(PyValueError::new_err("v1_sq: give v1_sq, v2_sq or both"));
    }
    let model = ok(Model::new(&sc.inputs))?;
    let doc = ok(docs::estimates_doc(
        &model,
        &columns,
        (bins, bias),
        &observing,
    ))?;
    write_new(path, &doc, force)
}

/// Writes `doc` at `path` as `v2ref` writes a set of one file: checked and
/// locked, never through a link, an existing file replaced only with
/// `force` (and one that appears meanwhile never).
fn write_new(path: &str, doc: &oifits::OifitsDoc, force: bool) -> PyResult<()> {
    let path = Path::new(path);
    let set = ok(crate::formats::OutputSet::begin(&[(path, "path")], force))?;
    ok(set.write(|| oifits::write_oifits(path, "path", doc)))
}

/// A synth set's truth (window positive, convention model) as OIFITS v2,
/// where and when `observing` says.
#[pyfunction]
#[pyo3(signature = (path, sidecar, sidecar_name, observing=None, force=false))]
fn write_oifits_truth(
    path: &str,
    sidecar: &Bound<'_, PyAny>,
    sidecar_name: &str,
    observing: Option<ObservingKeywords>,
    force: bool,
) -> PyResult<()> {
    let observing = observing_of(observing, true, "path")?;
    let sc = sidecar_of(sidecar, sidecar_name)?;
    let window = (BinWindow::Positive, BiasConvention::Model);
    let doc = ok(docs::truth_doc(&sc, window, &observing))?;
    write_new(path, &doc, force)
}

/// Which table of an OIFITS file holds a pipeline's estimates (the
/// keywords of `read_oifits_estimates` and `score_oifits`).
struct Pick<'a> {
    insname: Option<&'a str>,
    estimator: Option<&'a str>,
    target: Option<&'a str>,
    accept_checksum_mismatch: bool,
}

/// The estimates of the OIFITS file `path` picked by `pick`, read against
/// the set of the sidecar `sc` (its rows, its band) under `window`.
fn read_estimates(
    path: &str,
    sc: &Sidecar,
    window: (BinWindow, BiasConvention),
    pick: &Pick<'_>,
) -> PyResult<oifits::OifitsEstimates> {
    let estimator = estimator_of(pick.estimator)?;
    let c = sc.channel_count();
    if c > 1 {
        // Not yet per channel from Python: the whole band's reading would
        // score every channel against one truth.
        return Err(PyValueError::new_err(format!(
            "sidecar: a dispersed set of C = {c} channels; its OIFITS estimates are not read per channel here yet: \
             read the file with read_oifits (vis2data of shape (rows, {c})) and score the (rows, {c}) arrays"
        )));
    }
    let (lo, hi) = ok(sc.inputs.spectrum.spectrum())?.support();
    let expected = Expected {
        rows: sc.data.rows,
        band_m: (1e-6 / hi, 1e-6 / lo),
        channels_m: None,
        bins: window.0,
        bias: window.1,
    };
    let choice = oifits::Choice {
        insname: pick.insname,
        estimator,
        target: pick.target,
        read: oifits::ReadOptions {
            accept_checksum_mismatch: pick.accept_checksum_mismatch,
        },
    };
    ok(
        oifits::read_oifits_estimates(Path::new(path), &choice, &expected)
            .map_err(|e| renamed(e, "estimates", "path")),
    )
}

/// A pipeline's estimates read from OIFITS against a set's sidecar: a
/// dict (`v1_sq`, `v2_sq`: arrays of the unflagged rows or None; `rows`,
/// `flagged`).
#[pyfunction]
#[pyo3(signature = (path, sidecar, sidecar_name, insname, estimator, target, bins, bias, accept_checksum_mismatch))]
#[allow(clippy::too_many_arguments)] // one per keyword of the Python wrapper
fn read_oifits_estimates<'py>(
    py: Python<'py>,
    path: &str,
    sidecar: &Bound<'py, PyAny>,
    sidecar_name: &str,
    insname: Option<&str>,
    estimator: Option<&str>,
    target: Option<&str>,
    bins: &str,
    bias: &str,
    accept_checksum_mismatch: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let bins: BinWindow = ok(Words::from_word("bins", bins))?;
    let bias: BiasConvention = ok(Words::from_word("bias", bias))?;
    let sc = sidecar_of(sidecar, sidecar_name)?;
    let pick = Pick {
        insname,
        estimator,
        target,
        accept_checksum_mismatch,
    };
    let read = read_estimates(path, &sc, (bins, bias), &pick)?;
    let d = PyDict::new(py);
    d.set_item(
        "v1_sq",
        read.estimates.v1_sq.map(|v| PyArray1::from_vec(py, v)),
    )?;
    d.set_item(
        "v2_sq",
        read.estimates.v2_sq.map(|v| PyArray1::from_vec(py, v)),
    )?;
    d.set_item("rows", read.rows)?;
    d.set_item("flagged", read.flagged)?;
    d.set_item("notes", read.notes)?;
    Ok(d)
}

/// `score` of an OIFITS path: `v2ref score --estimates FILE.fits --json`
/// (flagged rows left out and counted; the verdict "too few rows" when
/// fewer than [`oifits::min_unflagged_rows`] are left).
#[pyfunction]
#[pyo3(signature = (path, sidecar, sidecar_name, bins, bias, alpha, insname, estimator, target, accept_checksum_mismatch))]
#[allow(clippy::too_many_arguments)] // one per keyword of the Python wrapper
fn score_oifits(
    py: Python<'_>,
    path: &str,
    sidecar: &Bound<'_, PyAny>,
    sidecar_name: &str,
    bins: &str,
    bias: &str,
    alpha: f64,
    insname: Option<&str>,
    estimator: Option<&str>,
    target: Option<&str>,
    accept_checksum_mismatch: bool,
) -> PyResult<PyObject> {
    let window: BinWindow = ok(Words::from_word("bins", bins))?;
    let convention: BiasConvention = ok(Words::from_word("bias", bias))?;
    ok(crate::conformance::score::critical_z(alpha, 1))?;
    let sc = sidecar_of(sidecar, sidecar_name)?;
    let truth = sc.truth(window, convention).ok_or_else(|| {
        PyValueError::new_err(format!(
            "sidecar: {sidecar_name}: no truth for bins={bins} bias={bias}; pick a window and convention the set has"
        ))
    })?;
    let pick = Pick {
        insname,
        estimator,
        target,
        accept_checksum_mismatch,
    };
    let read = read_estimates(path, &sc, (window, convention), &pick)?;
    let (set_rows, flagged) = (sc.data.rows, read.flagged as u64);
    let kept = set_rows - flagged;
    let head = serde_json::json!({
        "sidecar": sidecar_name,
        "estimates": path,
        "bins": window,
        "bias": convention,
        "rows": kept,
        "flagged": flagged,
        "notes": read.notes,
    });
    let floor = oifits::min_unflagged_rows(set_rows);
    let mut answer = head.as_object().cloned().unwrap_or_default();
    if kept < floor {
        answer.insert("min_rows".into(), floor.into());
        answer.insert("verdict".into(), "too few rows".into());
        answer.insert("pass".into(), false.into());
    } else {
        let truth = oifits::truth_for_kept_rows(truth, set_rows, kept);
        let e = &read.estimates;
        let report = ok(crate::conformance::score::score_report(
            e.v1_sq.as_deref(),
            e.v2_sq.as_deref(),
            &truth,
            kept,
            alpha,
        ))?;
        let report = serde_json::to_value(&report)
            .map_err(|e| PyValueError::new_err(format!("cannot serialize the answer: {e}")))?;
        answer.extend(report.as_object().cloned().unwrap_or_default());
    }
    to_py(py, &serde_json::Value::Object(answer))
}

fn estimator_of(estimator: Option<&str>) -> PyResult<Option<Estimator>> {
    match estimator {
        None => Ok(None),
        Some("v1_sq") => Ok(Some(Estimator::V1Sq)),
        Some("v2_sq") => Ok(Some(Estimator::V2Sq)),
        Some(s) => Err(PyValueError::new_err(format!(
            "estimator: '{s}' is not one of: v1_sq, v2_sq"
        ))),
    }
}

/// Adds the functions to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(read_oifits, m)?)?;
    m.add_function(wrap_pyfunction!(write_oifits, m)?)?;
    m.add_function(wrap_pyfunction!(write_oifits_truth, m)?)?;
    m.add_function(wrap_pyfunction!(read_oifits_estimates, m)?)?;
    m.add_function(wrap_pyfunction!(score_oifits, m)?)?;
    Ok(())
}
