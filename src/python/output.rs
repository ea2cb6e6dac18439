//! Files written from Python: the same writers and rules as the CLI
//! (`crate::formats::set`): atomic, checked and locked as a set, an
//! existing file replaced only with `force=True`, never through a link.

use super::ok;
use crate::formats::{write_text_atomic, NpyRowWriter, OutputSet};
use numpy::{PyReadonlyArray2, PyUntypedArrayMethods as _};
use pyo3::prelude::*;
use std::path::{Path, PathBuf};

/// `out` with `ext` appended to its name, bytes kept as given.
fn with_ext(out: &Path, ext: &str) -> PathBuf {
    let mut name = out.file_name().unwrap_or_default().to_os_string();
    name.push(ext);
    out.with_file_name(name)
}

/// Writes a set from `synthesize(out=...)`: OUT.npy (the rows) and
/// OUT.json (the sidecar's text), as `v2ref synth --out OUT` does.
#[pyfunction]
#[pyo3(signature = (out, data, sidecar, force))]
pub(super) fn write_set(
    py: Python<'_>,
    out: PathBuf,
    data: PyReadonlyArray2<'_, f64>,
    sidecar: String,
    force: bool,
) -> PyResult<()> {
    if out.file_name().filter(|n| !n.is_empty()).is_none() {
        return Err(pyo3::exceptions::PyValueError::new_err(format!(
            "out: {}: needs a file name (the set's stem)",
            out.display()
        )));
    }
    let (npy, json) = (with_ext(&out, ".npy"), with_ext(&out, ".json"));
    let set = ok(OutputSet::begin(&[(&npy, "out"), (&json, "out")], force))?;
    let (rows, cols) = (data.shape()[0], data.shape()[1]);
    let values = data.as_slice()?;
    ok(py.allow_threads(|| {
        set.write(|| {
            let mut w = NpyRowWriter::create(&npy, rows as u64, cols, "out")?;
            w.write_rows(values)?;
            w.finish()?;
            write_text_atomic(&json, &(sidecar + "\n"))
        })
    }))
}

/// Registers the writers.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(write_set, m)?)
}
