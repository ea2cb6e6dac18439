//! The spectrum CSV file of `--spectrum-csv` / `spectrum_csv`, read at the
//! edges: the numerics take the parsed table ([`SpectrumFile`], carried by
//! [`crate::parameters::Physical`]) and read no file themselves.

use crate::error::{Error, Result};
use crate::formalism::spectrum::{Spectrum, MAX_SPECTRUM_CSV_BYTES, MAX_SPECTRUM_ROWS};
use crate::parameters::SpectrumFile;
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

/// The table of the CSV file at `path` ([`spectrum_from_csv_path`]), with
/// its name.
pub fn read_spectrum_file(path: &Path) -> Result<SpectrumFile> {
    Ok(SpectrumFile::new(path, spectrum_from_csv_path(path)?))
}
