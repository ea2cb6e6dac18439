//! The checks of array and sidecar arguments: a message naming the
//! argument and where in it the value is unusable.

use crate::conformance::sidecar::Sidecar;
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

/// A sidecar from its JSON text (`name`: where it came from, for messages).
pub(super) fn parse_sidecar(text: &str, name: &str) -> PyResult<Sidecar> {
    crate::python::ok(Sidecar::from_json(text, std::path::Path::new(name)))
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
