//! The physical keyword arguments of the Python functions, read into the
//! library's [`Physical`] the way the CLI reads its flags: made a JSON
//! object and deserialized over the defaults ([`Physical::overlay`]).

use super::values::{to_json, to_py};
use super::Fail;
use crate::parameters::{unknown_input, Parameter, PARAMETERS};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

pub use crate::parameters::Physical;

/// The physical inputs in `d` (missing or None: [`Physical::default`]),
/// checked ([`Physical::check`]): an unknown name a TypeError offering the
/// nearest one, a value of the wrong type a TypeError and one out of range
/// a ValueError, each naming its keyword. A spectrum's or channel table's
/// file is read here, at the edge, after the checks.
pub fn physical_from_dict(d: &Bound<'_, PyDict>) -> PyResult<Physical> {
    let mut given = serde_json::Map::new();
    let mut file = None;
    let mut channels = None;
    for (k, v) in d.iter() {
        let k: String = k.extract()?;
        match Parameter::named(&k) {
            None => return Err(PyTypeError::new_err(unknown_input(&k))),
            Some(_) if v.is_none() => {}
            Some(p) if p.name == "spectrum_csv" => file = Some(v.extract::<PathBuf>()?),
            Some(p) if p.name == "channels_csv" => channels = Some(v.extract::<PathBuf>()?),
            Some(_) => match v.extract::<f64>() {
                Ok(x) if !x.is_finite() => {
                    let e = format!("{k}: {x} is not a finite number");
                    return Err(pyo3::exceptions::PyValueError::new_err(e));
                }
                _ => {
                    given.insert(k.clone(), to_json(&k, &v)?);
                }
            },
        }
    }
    let mut p = Physical::default();
    p.overlay(given.into()).map_err(|e| match e.to_string() {
        m if m.contains("invalid type") => PyTypeError::new_err(m),
        _ => e.into_py_err(),
    })?;
    p.check().map_err(|e| e.into_py_err())?;
    if let Some(path) = file {
        let table = v2ref_files::formats::spectrum_csv::spectrum_from_csv_path(&path)
            .map_err(|e| e.into_py_err())?;
        p.spectrum_csv = Some(v2ref_commands::parameters::SpectrumFile::new(&path, table));
    }
    if let Some(path) = channels {
        let text = v2ref_files::formats::channels_csv::read_channels_text(&path)
            .map_err(|e| e.into_py_err())?;
        p.channels_csv = Some(v2ref_commands::parameters::ChannelsFile::new(&path, text));
    }
    Ok(p)
}

/// The text of the sidecar file `path`, read as the command line reads it
/// ([`v2ref_files::formats::read_sidecar_text`]: without waiting on a FIFO,
/// a regular file only, at most 16 MiB), for the package's `sidecar=`.
#[pyfunction]
pub fn _read_sidecar(path: PathBuf) -> PyResult<String> {
    v2ref_files::formats::read_sidecar_text(&path).map_err(|e| e.into_py_err())
}

/// Adds the one declaration of the physical inputs to the module:
/// `PHYSICAL_KEYWORDS` (their names, in order), `PHYSICAL_DEFAULTS` (a dict)
/// and `PHYSICAL_PARAMETERS` (a list of dicts: [`PARAMETERS`], each with its
/// help text `doc` and what leaving it unset means, `unset_doc`, other
/// inputs named ``` ``name`` ```). The package reads the same declaration
/// at import (`_docstrings.declaration`) for its docstrings.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add_function(wrap_pyfunction!(_read_sidecar, m)?)?;
    let names: Vec<&str> = PARAMETERS.iter().map(|p| p.name).collect();
    m.add("PHYSICAL_KEYWORDS", names)?;
    m.add("PHYSICAL_DEFAULTS", to_py(py, &Physical::default())?)?;
    let keyword = |n: &str| format!("``{n}``");
    let table: Vec<serde_json::Value> = PARAMETERS
        .iter()
        .map(|p| {
            let mut v = serde_json::json!(p);
            v["doc"] = p.describe(&keyword).into();
            v["unset_doc"] = p.unset(&keyword).into();
            v
        })
        .collect();
    m.add("PHYSICAL_PARAMETERS", to_py(py, &table)?)
}
