//! The checks of array and sidecar arguments: a message naming the
//! argument and where in it the value is unusable.

use crate::conformance::sidecar::{Sidecar, FORMAT};
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

/// The first non-finite value of a row-major matrix of `cols` columns.
pub(super) fn check_finite(param: &str, data: &[f64], cols: usize) -> PyResult<()> {
    match data.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(i) => Err(data_error(
            param,
            &format!("row {}, column {} (1-based)", i / cols + 1, i % cols + 1),
            &format!(
                "{} is not a finite number; every value must be finite",
                data[i]
            ),
        )),
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

/// A sidecar from its JSON text (`name`: where it came from, for messages).
pub(super) fn parse_sidecar(text: &str, name: &str) -> PyResult<Sidecar> {
    let value: serde_json::Value = serde_json::from_str(text).map_err(|e| {
        data_error(
            "sidecar",
            name,
            &format!("not JSON ({e}); the sidecar written by v2ref synth is needed"),
        )
    })?;
    match value.get("format") {
        Some(serde_json::Value::String(f)) if f == FORMAT => {}
        Some(f) => {
            return Err(data_error(
                "sidecar",
                &format!("{name}: field format"),
                &format!("{f}; \"{FORMAT}\" is needed"),
            ))
        }
        None => {
            return Err(data_error(
                "sidecar",
                &format!("{name}: field format"),
                &format!("missing; \"{FORMAT}\" is needed"),
            ))
        }
    }
    serde_json::from_value::<Sidecar>(value)
        .map_err(|e| data_error("sidecar", name, &format!("not a v2ref sidecar: {e}")))
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
