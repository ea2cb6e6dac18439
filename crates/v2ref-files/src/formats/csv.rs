//! Comma-separated text: matrices and estimates read (comments and blank
//! lines skipped, a header row recognised), rows written atomically.

use super::atomic::{finish_file, too_many, whole_rows, TempTarget, WRITE_BUFFER};
use super::{kind_of, not_finite, open, Estimates, Kind, Matrix};
use crate::csv_lines::{CsvLines, LineError, LineFault};
use crate::{Error, Result};
use std::fs::File;
use std::io::{BufReader, BufWriter, Write};
use std::path::{Path, PathBuf};

/// Longest line of a CSV file read, bytes: room for a row of 100000
/// numbers at full precision.
pub const MAX_CSV_LINE_BYTES: u64 = 4 << 20;

/// The content lines of the CSV file `path` ([`crate::csv_lines`]).
fn lines_of(path: &Path, param: &'static str) -> Result<CsvLines<BufReader<File>>> {
    check_regular(path, param)?;
    let file = BufReader::new(open(path, param)?);
    Ok(CsvLines::new(file, MAX_CSV_LINE_BYTES))
}

/// Refuses an input that is not a regular file (a FIFO, a device, a
/// socket, a folder), looked at without waiting ([`super::open`]): a file
/// is read more than once (a CSV's shape, then its values), which a pipe
/// cannot give twice.
pub fn check_regular(path: &Path, param: &'static str) -> Result<()> {
    open(path, param).map(drop)
}

/// The refusal of a line of `path` that could not be read.
fn line_error(param: &'static str, path: &Path, e: LineError) -> Error {
    let at = format!("line {}", e.line);
    match e.fault {
        LineFault::NotUtf8 => Error::data(
            param,
            path,
            at,
            "not UTF-8 text; a comma-separated text file is needed",
        ),
        LineFault::TooLong(max) => Error::data(
            param,
            path,
            at,
            format!("longer than {max} bytes; rows of comma-separated numbers are needed"),
        ),
        LineFault::Io(e) => Error::file(Some(param), path, e),
    }
}

/// Hands each content line of a CSV file to `each` (its 1-based line
/// number and its fields, trimmed), one line at a time: nothing of the
/// file is held but the line being read. Refused when there is no content
/// line.
fn each_record(
    path: &Path,
    param: &'static str,
    mut each: impl FnMut(usize, &[&str]) -> Result<()>,
) -> Result<()> {
    let mut lines = lines_of(path, param)?;
    let mut records = 0usize;
    while let Some((line, fields)) = lines
        .next_record()
        .map_err(|e| line_error(param, path, e))?
    {
        each(line, &fields)?;
        records += 1;
    }
    if records == 0 {
        return Err(Error::data(
            param,
            path,
            "",
            "empty file (no rows); comma-separated rows of numbers are needed",
        ));
    }
    Ok(())
}

fn check_width(
    param: &'static str,
    path: &Path,
    line: usize,
    row: usize,
    got: usize,
    want: usize,
) -> Result<()> {
    if got == want {
        Ok(())
    } else {
        Err(Error::data(
            param,
            path,
            format!("row {row} (1-based, line {line})"),
            format!(
                "{got} columns, the rows above have {want}; every row must have the same number"
            ),
        ))
    }
}

fn parse_value(
    param: &'static str,
    path: &Path,
    line: usize,
    row: usize,
    col: usize,
    field: &str,
) -> Result<f64> {
    let location = format!("row {row}, column {col} (1-based, line {line})");
    match field.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(v) => Err(not_finite(param, path, location, v)),
        Err(_) => Err(Error::data(
            param,
            path,
            location,
            format!("{field:?} is not a number; a decimal number is needed"),
        )),
    }
}

pub(crate) fn read_csv_matrix(path: &Path, param: &'static str) -> Result<Matrix> {
    let mut data = Vec::new();
    let (rows, cols) = scan_matrix(path, param, Some(&mut data))?;
    Ok(Matrix { rows, cols, data })
}

/// Reads the rows of numbers of a CSV file, onto `data` when given (only
/// checked otherwise); returns the rows and columns. The first lines that
/// hold no number are a header.
fn scan_matrix(
    path: &Path,
    param: &'static str,
    mut data: Option<&mut Vec<f64>>,
) -> Result<(usize, usize)> {
    let (mut rows, mut cols) = (0usize, None);
    each_record(path, param, |line, fields| {
        let want = match cols {
            None if is_header(fields) => return Ok(()),
            None => *cols.insert(fields.len()),
            Some(c) => c,
        };
        check_width(param, path, line, rows + 1, fields.len(), want)?;
        for (c, f) in fields.iter().enumerate() {
            let v = parse_value(param, path, line, rows + 1, c + 1, f)?;
            if let Some(d) = data.as_mut() {
                d.push(v);
            }
        }
        rows += 1;
        Ok(())
    })?;
    Ok((rows, cols.unwrap_or(0)))
}

/// Whether the fields of a line before the first row hold no number (a
/// header).
fn is_header(fields: &[&str]) -> bool {
    fields.iter().all(|f| f.parse::<f64>().is_err())
}

/// The rows, columns and header lines of a CSV file of numbers, from its
/// structure alone (each row as wide as the first; the values are parsed
/// by [`CsvRows::next_block`]).
fn shape_of(path: &Path, param: &'static str) -> Result<(usize, usize, usize)> {
    let (mut rows, mut cols, mut headers) = (0usize, None, 0usize);
    each_record(path, param, |line, fields| {
        let want = match cols {
            None if is_header(fields) => {
                headers += 1;
                return Ok(());
            }
            None => *cols.insert(fields.len()),
            Some(c) => c,
        };
        check_width(param, path, line, rows + 1, fields.len(), want)?;
        rows += 1;
        Ok(())
    })?;
    Ok((rows, cols.unwrap_or(0), headers))
}

/// A CSV file of numbers read a block of rows at a time, each value
/// checked finite, as [`super::NpyRows`] reads a `.npy` file: memory stays
/// at one block however large the file. The file is read twice: once for
/// its shape (the rows and columns, each row as wide as the first), then
/// block by block for its values.
pub struct CsvRows {
    lines: CsvLines<BufReader<File>>,
    path: PathBuf,
    param: &'static str,
    /// Rows in the file.
    pub rows: usize,
    /// Values per row.
    pub cols: usize,
    headers: usize,
    done: usize,
}

impl CsvRows {
    /// Opens `path` when it is a `.csv` file of at least one row and one
    /// column; None for any other file, which [`super::read_matrix`] reads
    /// (and refuses with its own message when it must). A file whose
    /// shape is wrong is refused as [`super::read_matrix`] refuses it, at
    /// its first fault.
    pub fn open(path: &Path, param: &'static str) -> Result<Option<CsvRows>> {
        if !matches!(kind_of(path, param)?, Kind::Csv) {
            return Ok(None);
        }
        let (rows, cols, headers) = match shape_of(path, param) {
            Ok(shape) => shape,
            // A value before the fault is refused first, as in a whole read.
            Err(fault) => return Err(scan_matrix(path, param, None).err().unwrap_or(fault)),
        };
        if rows == 0 || cols == 0 {
            return Ok(None);
        }
        Ok(Some(CsvRows {
            lines: lines_of(path, param)?,
            path: path.to_path_buf(),
            param,
            rows,
            cols,
            headers,
            done: 0,
        }))
    }

    /// Replaces `out` with the next block of at most `max_rows` rows
    /// (row-major); returns the number of rows, 0 at the end.
    pub fn next_block(&mut self, max_rows: usize, out: &mut Vec<f64>) -> Result<usize> {
        let (param, path) = (self.param, self.path.as_path());
        let take = max_rows.max(1).min(self.rows - self.done);
        out.clear();
        let mut taken = 0;
        while taken < take {
            let Some((line, fields)) = self
                .lines
                .next_record()
                .map_err(|e| line_error(param, path, e))?
            else {
                return Err(Error::data(
                    param,
                    path,
                    "",
                    format!(
                        "{} rows, then {}: the file changed while it was read; give a file that stays",
                        self.rows, self.done + taken
                    ),
                ));
            };
            if self.headers > 0 {
                self.headers -= 1;
                continue;
            }
            let row = self.done + taken + 1;
            check_width(param, path, line, row, fields.len(), self.cols)?;
            for (c, f) in fields.iter().enumerate() {
                out.push(parse_value(param, path, line, row, c + 1, f)?);
            }
            taken += 1;
        }
        self.done += take;
        Ok(take)
    }
}

pub(crate) fn read_estimates_csv(path: &Path) -> Result<Estimates> {
    const P: &str = "estimates";
    let mut header: Option<EstimatesHeader> = None;
    let (mut v1, mut v2) = (Vec::new(), Vec::new());
    let mut rows = 0usize;
    each_record(path, P, |line, fields| {
        let Some(EstimatesHeader { names, i1, i2 }) = &header else {
            header = Some(estimates_header(path, line, fields)?);
            return Ok(());
        };
        rows += 1;
        check_width(P, path, line, rows, fields.len(), names.len())?;
        for (idx, out) in [(*i1, &mut v1), (*i2, &mut v2)] {
            if let Some(c) = idx {
                out.push(parse_value(P, path, line, rows, c + 1, fields[c])?);
            }
        }
        Ok(())
    })?;
    let (i1, i2) = header.map_or((None, None), |h| (h.i1, h.i2));
    Ok(Estimates {
        v1_sq: i1.map(|_| v1),
        v2_sq: i2.map(|_| v2),
    })
}

/// The header of an estimates CSV: the column names and where v1_sq and
/// v2_sq are (at least one; neither named twice).
struct EstimatesHeader {
    names: Vec<String>,
    i1: Option<usize>,
    i2: Option<usize>,
}

fn estimates_header(path: &Path, hline: usize, fields: &[&str]) -> Result<EstimatesHeader> {
    const P: &str = "estimates";
    let names: Vec<String> = fields.iter().map(|f| (*f).to_owned()).collect();
    let find = |n: &str| names.iter().position(|f| f == n);
    let (i1, i2) = (find("v1_sq"), find("v2_sq"));
    if i1.is_none() && i2.is_none() {
        return Err(Error::data(
            P,
            path,
            format!("header (line {hline})"),
            format!(
                "no column named v1_sq or v2_sq (found: {}); a header row naming the columns is needed",
                names.join(",")
            ),
        ));
    }
    // A column read twice would be read from the first, maybe junk, one.
    for (name, first) in [("v1_sq", i1), ("v2_sq", i2)] {
        let Some(c) = first else { continue };
        if let Some(k) = names[c + 1..].iter().position(|f| f == name) {
            return Err(Error::data(
                P,
                path,
                format!("header (line {hline})"),
                format!(
                    "column {name} is named twice (columns {} and {}); name each column once",
                    c + 1,
                    c + k + 2
                ),
            ));
        }
    }
    Ok(EstimatesHeader { names, i1, i2 })
}

/// A CSV writer of rows of float64 (shortest round-trip formatting: the
/// file reads back to the same bits), with an optional header line,
/// atomic like [`super::NpyRowWriter`].
pub struct CsvRowWriter {
    out: BufWriter<File>,
    temp: TempTarget,
    cols: usize,
    rows: u64,
    written: u64,
    line: String,
}

impl CsvRowWriter {
    /// Starts `path` with `rows` rows of `cols` values, after `header`
    /// (one line, without its newline) if given.
    pub fn create(
        path: &Path,
        rows: u64,
        cols: usize,
        header: Option<&str>,
        param: &'static str,
    ) -> Result<Self> {
        let (temp, file) = TempTarget::create(path, Some(param))?;
        let mut out = BufWriter::with_capacity(WRITE_BUFFER, file);
        if let Some(h) = header {
            writeln!(out, "{h}").map_err(|e| temp.io(e))?;
        }
        Ok(CsvRowWriter {
            out,
            temp,
            cols,
            rows,
            written: 0,
            line: String::new(),
        })
    }

    /// Appends whole rows.
    pub fn write_rows(&mut self, values: &[f64]) -> Result<()> {
        use std::fmt::Write as _;
        let n = whole_rows(values.len(), self.cols, &self.temp)?;
        if self.written + n > self.rows {
            return Err(too_many(&self.temp, self.rows));
        }
        for row in values.chunks_exact(self.cols) {
            self.line.clear();
            for (j, v) in row.iter().enumerate() {
                if j > 0 {
                    self.line.push(',');
                }
                let _ = write!(self.line, "{v:?}");
            }
            self.line.push('\n');
            self.out
                .write_all(self.line.as_bytes())
                .map_err(|e| self.temp.io(e))?;
        }
        self.written += n;
        Ok(())
    }

    /// Checks the row count, flushes, syncs and renames onto the target.
    pub fn finish(self) -> Result<()> {
        let CsvRowWriter {
            out,
            temp,
            rows,
            written,
            ..
        } = self;
        finish_file(out, temp, rows, written)
    }
}
