//! The spectrum CSV file of `--spectrum-csv` / `spectrum_csv`, read at the
//! edges: the numerics take the parsed table (`SpectrumFile` of the crate
//! `v2ref-commands`, carried by its `Physical`, made by the edges from the
//! file's name and [`spectrum_from_csv_path`]) and read no file themselves.

use crate::error::{Error, Result};
use crate::formalism::spectrum::{Spectrum, MAX_SPECTRUM_CSV_BYTES, MAX_SPECTRUM_ROWS};
use std::path::Path;

/// Reads a tabulated spectrum from a CSV file, in the form of
/// [`Spectrum::from_csv_str`]. At most [`MAX_SPECTRUM_CSV_BYTES`] bytes
/// and [`MAX_SPECTRUM_ROWS`] rows; a refusal names the file.
pub fn spectrum_from_csv_path(path: &Path) -> Result<Spectrum> {
    let in_file = |reason: String| Error::SpectrumTable {
        reason: format!("{}: {reason}", path.display()),
    };
    let accepted = format!("a CSV of at most {MAX_SPECTRUM_ROWS} rows");
    let text = super::read_text(path, "spectrum", MAX_SPECTRUM_CSV_BYTES, &accepted).map_err(
        |e| match e {
            Error::Data { reason, .. } => in_file(reason),
            other => other,
        },
    )?;
    Spectrum::from_csv_str(&text).map_err(|e| match e {
        Error::SpectrumTable { reason } => in_file(reason),
        other => other,
    })
}
