//! Comma-separated text: matrices and estimates read (comments and blank
//! lines skipped, a header row recognised), rows written atomically.

use super::atomic::{finish_file, too_many, whole_rows, TempTarget, WRITE_BUFFER};
use super::{not_finite, open, Estimates, Matrix};
use crate::{Error, Result};
use std::fs::File;
use std::io::{self, BufRead, BufReader, BufWriter, Read, Write};
use std::path::Path;

/// Longest line of a CSV file read, bytes: room for a row of 100000
/// numbers at full precision.
pub const MAX_CSV_LINE_BYTES: u64 = 4 << 20;

/// Hands each content line of a CSV file to `each` (its 1-based line
/// number and its fields, trimmed), comments and blank lines skipped, one
/// line at a time: nothing of the file is held but the line being read.
/// Refused when there is no content line.
fn each_record(
    path: &Path,
    param: &'static str,
    mut each: impl FnMut(usize, &[&str]) -> Result<()>,
) -> Result<()> {
    let mut reader = BufReader::new(open(path, param)?);
    let mut records = 0usize;
    let mut line = String::new();
    for i in 0.. {
        line.clear();
        // One byte more than the limit tells a long line from one at it
        // (and stops an endless one, such as /dev/zero, at once).
        let read = (&mut reader)
            .take(MAX_CSV_LINE_BYTES + 1)
            .read_line(&mut line)
            .map_err(|e| match e.kind() {
                io::ErrorKind::InvalidData => Error::data(
                    param,
                    path,
                    format!("line {}", i + 1),
                    "not UTF-8 text; a comma-separated text file is needed",
                ),
                _ => Error::file(Some(param), path, e),
            })?;
        if read == 0 {
            break;
        }
        if read as u64 > MAX_CSV_LINE_BYTES {
            return Err(Error::data(
                param,
                path,
                format!("line {}", i + 1),
                format!("longer than {MAX_CSV_LINE_BYTES} bytes; rows of comma-separated numbers are needed"),
            ));
        }
        // Spreadsheets start their CSV with a UTF-8 byte-order mark.
        let text = if i == 0 {
            line.strip_prefix('\u{feff}').unwrap_or(&line)
        } else {
            &line
        };
        let t = text.trim();
        if t.is_empty() || t.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = t.split(',').map(str::trim).collect();
        each(i + 1, &fields)?;
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
    let (mut rows, mut cols) = (0usize, None);
    let mut data = Vec::new();
    each_record(path, param, |line, fields| {
        let Some(cols) = cols else {
            cols = Some(fields.len());
            // A first row that holds no number is a header.
            if fields.iter().all(|f| f.parse::<f64>().is_err()) {
                cols = None;
                return Ok(());
            }
            return push_row(param, path, (line, rows), fields, &mut data).map(|()| rows += 1);
        };
        check_width(param, path, line, rows + 1, fields.len(), cols)?;
        push_row(param, path, (line, rows), fields, &mut data)?;
        rows += 1;
        Ok(())
    })?;
    Ok(Matrix {
        rows,
        cols: cols.unwrap_or(0),
        data,
    })
}

/// Parses the fields of row `row` (0-based, at `line`) onto `data`.
fn push_row(
    param: &'static str,
    path: &Path,
    (line, row): (usize, usize),
    fields: &[&str],
    data: &mut Vec<f64>,
) -> Result<()> {
    for (c, f) in fields.iter().enumerate() {
        data.push(parse_value(param, path, line, row + 1, c + 1, f)?);
    }
    Ok(())
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
