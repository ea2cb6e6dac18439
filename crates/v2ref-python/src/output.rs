//! Files written from Python: the same writers and rules as the CLI
//! (`crate::formats::set`): atomic, checked and locked as a set, an
//! existing file replaced only with `force=True`, never through a link.

use super::ok;
use crate::conformance::sidecar::Sidecar;
use crate::formats::{write_text_atomic, NpyRowWriter, OutputSet};
use pyo3::prelude::*;
use std::path::{Path, PathBuf};

/// `out` with `ext` appended to its name, bytes kept as given.
fn with_ext(out: &Path, ext: &str) -> PathBuf {
    let mut name = out.file_name().unwrap_or_default().to_os_string();
    name.push(ext);
    out.with_file_name(name)
}

/// Writes a set from `synthesize(out=...)`: OUT.npy (the rows, `values`,
/// each of shape `row_shape`: (N) for a wide-band set, (C, N) for a
/// dispersed one) and OUT.json (the sidecar, pretty), as `v2ref synth
/// --out OUT` does.
pub fn write_set(
    py: Python<'_>,
    out: &Path,
    (values, row_shape): (&[f64], &[usize]),
    sidecar: &Sidecar,
    force: bool,
) -> PyResult<()> {
    ok(crate::atomic::target::check_file_name(out, "out"))?;
    let (npy, json) = (with_ext(out, ".npy"), with_ext(out, ".json"));
    let set = ok(OutputSet::begin(&[(&npy, "out"), (&json, "out")], force))?;
    let rows = values.len() / row_shape.iter().product::<usize>().max(1);
    ok(py.allow_threads(|| {
        set.write(|| {
            let mut w = NpyRowWriter::create_shaped(&npy, rows as u64, row_shape, "out")?;
            w.write_rows(values)?;
            w.finish()?;
            // The sidecar last, listing the .npy (as `v2ref synth` does).
            let mut sidecar = sidecar.clone();
            sidecar.members = crate::atomic::set::staged_members()?;
            let text =
                serde_json::to_string_pretty(&sidecar).map_err(|e| crate::Error::Output {
                    path: json.display().to_string(),
                    reason: format!("cannot serialize the sidecar: {e}"),
                })?;
            write_text_atomic(&json, &(text + "\n"))
        })
    }))
}
