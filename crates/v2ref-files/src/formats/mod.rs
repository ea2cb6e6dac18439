//! File formats of the conformance kit and the command line: matrices and
//! estimates read from `.npy` or `.csv` (`npy`, `csv`), and atomic,
//! streaming writers (over the crate's one atomic writer, [`crate::atomic`]:
//! a temporary file renamed onto the target only when complete, so that a
//! failed or interrupted write leaves the target as it was).
//!
//! Every refusal is an [`Error::Data`] naming the file, where in it (`row i,
//! column j` counted from 1, or `header`) and what is accepted; a file that
//! cannot be opened is an [`Error::Io`].
//!
//! `.npy` files are read and written with the `npyz` crate: float64
//! little-endian (`<f8`), C order (Fortran order is read and transposed).
//! CSV: comma-separated, lines starting with `#` and blank lines skipped.
//!
//! This module is the edge's (the command line's and Python's): the
//! numerical core reads and writes no file.

// The atomic writers' one public path is `crate::atomic`; these names are
// this module's shorthand for them, crate-private.
pub use crate::atomic;
pub mod budget;
pub mod channels_csv;
pub mod csv;
mod input;
pub(crate) mod npy;
pub mod spectrum_csv;
pub mod targets_csv;

pub use budget::{budget_bytes_of_gib, check_budget, memory_budget, set_memory_budget_gib};
pub use csv::{CsvRowWriter, CsvRows, MAX_CSV_LINE_BYTES};
pub use input::{
    open, open_found, read_found_bytes, read_found_text, read_sidecar_text, read_text,
    MAX_SIDECAR_BYTES,
};
pub use npy::{NpyRowWriter, NpyRows};
// The Python bindings' shorthand for the atomic writers.
pub use atomic::{set::OutputSet, write_text_atomic};

use crate::{Error, Result};
use std::path::Path;

/// A matrix of float64, row-major.
#[derive(Debug, Clone, PartialEq)]
pub struct Matrix {
    /// Rows.
    pub rows: usize,
    /// Columns.
    pub cols: usize,
    /// `rows × cols` values, row after row.
    pub data: Vec<f64>,
}

impl Matrix {
    /// Row `r` (0-based).
    pub fn row(&self, r: usize) -> &[f64] {
        &self.data[r * self.cols..(r + 1) * self.cols]
    }
}

/// The per-row estimates of a pipeline: either column may be absent, not both.
#[derive(Debug, Clone, PartialEq)]
pub struct Estimates {
    /// Normalized V1², one per row.
    pub v1_sq: Option<Vec<f64>>,
    /// Normalized V2², one per row.
    pub v2_sq: Option<Vec<f64>>,
}

/// The columns of an estimates `.npy` file when `--columns` is not given.
pub const DEFAULT_COLUMNS: [&str; 2] = ["v1_sq", "v2_sq"];

/// The extensions of a matrix (interferograms, a calibrator).
const ACCEPTED_EXT: &str = "accepted: .npy (float64) or .csv";

/// The extensions of an estimates file: a matrix's, and the OIFITS ones
/// (`v2ref_oifits::FITS_EXTENSIONS`, each also gzipped), which the
/// callers read before they come here.
pub const ACCEPTED_ESTIMATES_EXT: &str =
    "accepted: .npy (float64), .csv, or OIFITS (.fits, .oifits, .fit, each also as .gz)";

pub(crate) enum Kind {
    Npy,
    Csv,
}

pub(crate) fn kind_of(path: &Path, param: &'static str) -> Result<Kind> {
    kind_accepting(path, param, ACCEPTED_EXT)
}

/// The kind of `path` by its extension, refused naming `accepted`.
fn kind_accepting(path: &Path, param: &'static str, accepted: &str) -> Result<Kind> {
    match path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .as_deref()
    {
        Some("npy") => Ok(Kind::Npy),
        Some("csv") => Ok(Kind::Csv),
        Some(other) => Err(Error::data(
            param,
            path,
            "",
            format!("unknown extension .{other}; {accepted}"),
        )),
        None => Err(Error::data(
            param,
            path,
            "",
            format!("no extension; {accepted}"),
        )),
    }
}

pub(crate) fn at(row: usize, col: usize) -> String {
    format!("row {row}, column {col} (1-based)")
}

pub(crate) fn not_finite(param: &'static str, path: &Path, location: String, v: f64) -> Error {
    Error::data(
        param,
        path,
        location,
        format!("{v} is not a finite number; every value must be finite"),
    )
}

/// A file of rows read a block of rows at a time, each value checked
/// finite: a `.npy` ([`NpyRows`]) or a `.csv` ([`CsvRows`]) file.
#[non_exhaustive]
pub enum RowStream {
    /// A `.npy` file.
    Npy(NpyRows),
    /// A `.csv` file.
    Csv(CsvRows),
}

impl RowStream {
    /// Opens `path` when its rows can be streamed; None for a file that
    /// [`read_matrix`] reads whole (or refuses with its own message).
    pub fn open(path: &Path, param: &'static str) -> Result<Option<RowStream>> {
        Ok(match kind_of(path, param)? {
            Kind::Npy => NpyRows::open(path, param)?.map(RowStream::Npy),
            Kind::Csv => CsvRows::open(path, param)?.map(RowStream::Csv),
        })
    }

    /// Rows in the file.
    pub fn rows(&self) -> usize {
        match self {
            RowStream::Npy(s) => s.rows,
            RowStream::Csv(s) => s.rows,
        }
    }

    /// Values per row.
    pub fn cols(&self) -> usize {
        match self {
            RowStream::Npy(s) => s.cols,
            RowStream::Csv(s) => s.cols,
        }
    }

    /// Replaces `out` with the next block of at most `max_rows` rows
    /// (row-major); returns the number of rows, 0 at the end.
    pub fn next_block(&mut self, max_rows: usize, out: &mut Vec<f64>) -> Result<usize> {
        match self {
            RowStream::Npy(s) => s.next_block(max_rows, out),
            RowStream::Csv(s) => s.next_block(max_rows, out),
        }
    }
}

/// Reads a matrix of float64 from a `.npy` (2-D, `<f8`) or `.csv` file.
pub fn read_matrix(path: &Path, param: &'static str) -> Result<Matrix> {
    let m = match kind_of(path, param)? {
        Kind::Npy => {
            let (shape, data) = npy::read_npy(path, param, |shape| {
                if shape.len() == 2 {
                    return Ok(());
                }
                Err(Error::data(
                    param,
                    path,
                    "header",
                    format!(
                        "{}-D array of shape {shape:?}; a 2-D array (rows, samples) is needed",
                        shape.len()
                    ),
                ))
            })?;
            Matrix {
                rows: shape[0],
                cols: shape[1],
                data,
            }
        }
        Kind::Csv => csv::read_csv_matrix(path, param)?,
    };
    if m.rows == 0 || m.cols == 0 {
        return Err(Error::data(
            param,
            path,
            "",
            format!(
                "empty ({} rows, {} columns); at least one row and one column are needed",
                m.rows, m.cols
            ),
        ));
    }
    if let Some(i) = m.data.iter().position(|v| !v.is_finite()) {
        return Err(not_finite(
            param,
            path,
            at(i / m.cols + 1, i % m.cols + 1),
            m.data[i],
        ));
    }
    Ok(m)
}

/// Reads a pipeline's per-row estimates.
///
/// - `.csv`: a header row naming the columns; `v1_sq` and/or `v2_sq` are
///   read, any other column (`row`, `v1_sq_raw`, …) is ignored.
/// - `.npy`: float64, 2-D with one column per name in `columns`
///   (default [`DEFAULT_COLUMNS`]), or 1-D with exactly one name; names
///   other than `v1_sq` and `v2_sq` are ignored.
///
/// A non-finite estimate is refused with its row.
pub fn read_estimates(path: &Path, columns: Option<&[String]>) -> Result<Estimates> {
    const P: &str = "estimates";
    let est = match kind_accepting(path, P, ACCEPTED_ESTIMATES_EXT)? {
        Kind::Csv => csv::read_estimates_csv(path)?,
        Kind::Npy => npy::read_estimates_npy(path, columns)?,
    };
    for (name, col) in [("v1_sq", &est.v1_sq), ("v2_sq", &est.v2_sq)] {
        if let Some(x) = col {
            if x.is_empty() {
                return Err(Error::data(
                    P,
                    path,
                    "",
                    "no rows; one estimate per row is needed",
                ));
            }
            if let Some(r) = x.iter().position(|v| !v.is_finite()) {
                return Err(not_finite(
                    P,
                    path,
                    format!("row {} (1-based), column {name}", r + 1),
                    x[r],
                ));
            }
        }
    }
    Ok(est)
}
