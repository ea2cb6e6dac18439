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
    use std::io::Read;
    let io = |e| Error::file(Some("spectrum"), path, e);
    let file = std::fs::File::open(path).map_err(io)?;
    let mut text = String::new();
    // One byte more than the limit tells a file at the limit from a
    // longer one (or an endless one such as /dev/zero).
    file.take(MAX_SPECTRUM_CSV_BYTES + 1)
        .read_to_string(&mut text)
        .map_err(io)?;
    let in_file = |reason: String| Error::SpectrumTable {
        reason: format!("{}: {reason}", path.display()),
    };
    if text.len() as u64 > MAX_SPECTRUM_CSV_BYTES {
        return Err(in_file(format!(
                "larger than {MAX_SPECTRUM_CSV_BYTES} bytes; accepted: a CSV of at most {MAX_SPECTRUM_ROWS} rows"
            )));
    }
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
