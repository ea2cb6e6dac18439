//! The physical keyword arguments of the Python functions, read into the
//! library's [`Physical`] (its defaults, its builders: the same as the
//! CLI's flags).

use super::values::to_py;
use super::Fail;
use crate::parameters::{Kind, Parameter, Value, PARAMETERS};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

pub use crate::parameters::Physical;

/// The value of the keyword argument `key` (`v`, not None) as its
/// declaration's kind takes it, or a TypeError naming it.
fn extract<'py, T: FromPyObject<'py>>(v: &Bound<'py, PyAny>, key: &str) -> PyResult<T> {
    v.extract().map_err(|e| {
        pyo3::exceptions::PyTypeError::new_err(format!(
            "{key}: {}",
            e.value(v.py())
                .str()
                .map(|s| s.to_string())
                .unwrap_or_default()
        ))
    })
}

/// The keyword argument `v` of the input `p`, as its kind is given; a
/// spectrum's file is only named here ([`Given::File`]), read after the
/// checks.
fn given(p: &Parameter, v: &Bound<'_, PyAny>) -> PyResult<Given> {
    Ok(Given::Value(match p.kind {
        Kind::Number => Value::Number(extract(v, p.name)?),
        Kind::Count => Value::Count(extract(v, p.name)?),
        Kind::Flag => Value::Flag(extract(v, p.name)?),
        Kind::Word => Value::Word(extract(v, p.name)?),
        Kind::File => return Ok(Given::File(extract(v, p.name)?)),
    }))
}

/// A keyword argument as given: a value, or the name of a file to read.
enum Given {
    Value(Value),
    File(PathBuf),
}

/// The physical inputs in `d` (missing or None: [`Physical::default`]),
/// checked ([`Physical::check`]), each set by its key in the one
/// declaration ([`PARAMETERS`]); a spectrum's file is read here, at the
/// edge, after the checks.
pub fn physical_from_dict(d: &Bound<'_, PyDict>) -> PyResult<Physical> {
    for (k, _) in d.iter() {
        let k: String = k.extract()?;
        if !PARAMETERS.iter().any(|p| p.name == k) {
            let names: Vec<&str> = PARAMETERS.iter().map(|p| p.name).collect();
            return Err(pyo3::exceptions::PyTypeError::new_err(format!(
                "{k}: not a keyword argument (accepted: {})",
                names.join(", ")
            )));
        }
    }
    let mut p = Physical::default();
    let mut files = Vec::new();
    for key in &PARAMETERS {
        let Some(v) = d.get_item(key.name)?.filter(|v| !v.is_none()) else {
            continue;
        };
        match given(key, &v)? {
            Given::Value(value) => p.set(key, value).map_err(|e| e.into_py_err())?,
            Given::File(path) => files.push((key, path)),
        }
    }
    p.check().map_err(|e| e.into_py_err())?;
    for (key, path) in files {
        let table = v2ref_files::formats::spectrum_csv::read_spectrum_file(&path)
            .map_err(|e| e.into_py_err())?;
        p.set(key, Value::Spectrum(table))
            .map_err(|e| e.into_py_err())?;
    }
    Ok(p)
}

/// Adds the one declaration of the physical inputs to the module:
/// `PHYSICAL_KEYWORDS` (their names, in order), `PHYSICAL_DEFAULTS` (a dict)
/// and `PHYSICAL_PARAMETERS` (a list of dicts: [`PARAMETERS`], each with its
/// help text `doc` and what leaving it unset means, `unset_doc`, other
/// inputs named ``` ``name`` ```). The package reads the same declaration
/// from `_declaration.py`, generated from it.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
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
