//! The checks of array and sidecar arguments: a message naming the
//! argument and where in it the value is unusable.

use crate::commands::estimate::RowsName;
use crate::conformance::sidecar::Sidecar;
use crate::values::SidecarArg;
use numpy::{PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// Unusable content of an array argument.
pub(super) fn data_error(param: &str, location: &str, reason: &str) -> PyErr {
    if location.is_empty() {
        PyValueError::new_err(format!("{param}: {reason}"))
    } else {
        PyValueError::new_err(format!("{param}: {location}: {reason}"))
    }
}

/// A 2-D C-contiguous float64 array as (rows, cols, data).
pub(super) fn matrix<'a>(
    param: &str,
    a: &'a PyReadonlyArray2<'_, f64>,
) -> PyResult<(usize, usize, &'a [f64])> {
    let shape = a.shape();
    let (rows, cols) = (shape[0], shape[1]);
    if rows == 0 || cols == 0 {
        return Err(data_error(
            param,
            "",
            &format!(
                "empty ({rows} rows, {cols} columns); at least one row and one column are needed"
            ),
        ));
    }
    let data = a.as_slice().map_err(|_| {
        pyo3::exceptions::PyTypeError::new_err(format!(
            "{param}: not a C-contiguous array (pass numpy.ascontiguousarray(x))"
        ))
    })?;
    Ok((rows, cols, data))
}

/// A sidecar from a file's text or a dict (`name`: where it came from,
/// for messages): the format checked first, as [`Sidecar::from_json`] does.
pub(super) fn parse_sidecar(sidecar: &Bound<'_, PyAny>, name: &str) -> PyResult<Sidecar> {
    use crate::conformance::sidecar::FORMAT;
    use crate::error::Error;
    use serde_json::Value;
    let path = std::path::Path::new(name);
    let value = match SidecarArg::of(sidecar)? {
        SidecarArg::Text(text) => return crate::ok(Sidecar::from_json(&text, path)),
        SidecarArg::Value(v) => v,
    };
    let format = match value.get("format") {
        Some(Value::String(f)) if f == FORMAT => {
            let sc = serde_json::from_value::<Sidecar>(value).map_err(|e| {
                Error::data(
                    "sidecar",
                    path,
                    "fields",
                    format!("not a v2ref sidecar: {e}"),
                )
            });
            return crate::ok(sc);
        }
        Some(f) => f.to_string(),
        None => "missing".to_owned(),
    };
    let reason = format!("{format}; \"{FORMAT}\" is needed");
    crate::ok(Err(Error::data("sidecar", path, "field format", reason)))
}

/// The estimates of column `name` (`v1_sq` or `v2_sq`) given to `score`:
/// contiguous, not empty, every value finite.
pub(super) fn estimate_column<'a>(
    name: &str,
    a: &'a PyReadonlyArray1<'_, f64>,
) -> PyResult<&'a [f64]> {
    let x = a.as_slice().map_err(|_| {
        pyo3::exceptions::PyTypeError::new_err(format!(
            "estimates: column {name} is not contiguous"
        ))
    })?;
    if x.is_empty() {
        return Err(data_error(
            "estimates",
            "",
            "no rows; one estimate per row is needed",
        ));
    }
    if let Some(r) = x.iter().position(|v| !v.is_finite()) {
        return Err(data_error(
            "estimates",
            &format!("row {} (1-based), column {name}", r + 1),
            &format!(
                "{} is not a finite number; every value must be finite",
                x[r]
            ),
        ));
    }
    Ok(x)
}

/// How a refusal names the rows of `estimate`.
pub(super) const INTERFEROGRAMS: RowsName<'static> = RowsName {
    param: "interferograms",
    path: None,
};

/// Refuses, before anything is allocated, an answer of `rows` rows of `n`
/// samples (float64, held whole as the returned array) larger than the
/// memory budget (`V2REF_MAX_MEMORY_GIB`, else half the physical memory):
/// within the documented bounds, 60 million rows of 32 samples (15 GB)
/// aborted the interpreter when the allocation failed.
pub(super) fn check_array_fits(rows: u64, n: usize) -> PyResult<()> {
    let budget = crate::ok(crate::formats::memory_budget())?;
    let need = rows.saturating_mul(n as u64).saturating_mul(8);
    if need <= budget {
        return Ok(());
    }
    let gib = |b: u64| b as f64 / (1u64 << 30) as f64;
    Err(pyo3::exceptions::PyMemoryError::new_err(format!(
        "rows: {rows} rows of {n} samples take {:.2} GiB, more than the memory budget of {:.2} GiB \
         (V2REF_MAX_MEMORY_GIB, else half the physical memory); write fewer rows, or raise the budget",
        gib(need),
        gib(budget)
    )))
}
