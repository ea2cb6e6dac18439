//! The CLI's file edge: matrices and estimates read from `.npy` or `.csv`,
//! and atomic, streaming writers.
//!
//! Every refusal is an [`Error::Data`] naming the file, where in it (`row i,
//! column j` counted from 1, or `header`) and what is accepted; a file that
//! cannot be opened is an [`Error::Io`].
//!
//! `.npy` files are read and written with the `npyz` crate: float64
//! little-endian (`<f8`), C order (Fortran order is read and transposed).
//! CSV: comma-separated, lines starting with `#` and blank lines skipped.

// The writers and `read_matrix` serve `synth` and `estimate`; the tests
// include this file by path.

use npyz::{Endianness, NpyHeader, Order, TypeChar, WriterBuilder};
use std::fs::File;
use std::io::{self, BufRead, BufReader, BufWriter, Read, Seek, Write};
use std::path::{Path, PathBuf};
use v2ref::{Error, Result};

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
    #[allow(dead_code)] // read by tests/conformance_files.rs, which compiles this file
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

const ACCEPTED_EXT: &str = "accepted: .npy (float64) or .csv";
const NPY_MAGIC: &[u8] = b"\x93NUMPY";

enum Kind {
    Npy,
    Csv,
}

fn kind_of(path: &Path, param: &'static str) -> Result<Kind> {
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
            format!("unknown extension .{other}; {ACCEPTED_EXT}"),
        )),
        None => Err(Error::data(
            param,
            path,
            "",
            format!("no extension; {ACCEPTED_EXT}"),
        )),
    }
}

fn open(path: &Path, param: &'static str) -> Result<File> {
    File::open(path).map_err(|e| Error::file(Some(param), path, e))
}

fn at(row: usize, col: usize) -> String {
    format!("row {row}, column {col} (1-based)")
}

fn not_finite(param: &'static str, path: &Path, location: String, v: f64) -> Error {
    Error::data(
        param,
        path,
        location,
        format!("{v} is not a finite number; every value must be finite"),
    )
}

/// Reads a matrix of float64 from a `.npy` (2-D, `<f8`) or `.csv` file.
pub fn read_matrix(path: &Path, param: &'static str) -> Result<Matrix> {
    let m = match kind_of(path, param)? {
        Kind::Npy => {
            let (shape, data) = read_npy(path, param)?;
            if shape.len() != 2 {
                return Err(Error::data(
                    param,
                    path,
                    "header",
                    format!(
                        "{}-D array of shape {shape:?}; a 2-D array (rows, samples) is needed",
                        shape.len()
                    ),
                ));
            }
            Matrix {
                rows: shape[0],
                cols: shape[1],
                data,
            }
        }
        Kind::Csv => read_csv_matrix(path, param)?,
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

/// The numpy name of a plain dtype (`int64`, `float32`, …).
fn dtype_name(dtype: &npyz::DType) -> String {
    match dtype {
        npyz::DType::Plain(t) => {
            let bits = t.size_field() * 8;
            let base = match t.type_char() {
                TypeChar::Bool => return format!("bool ('{t}')"),
                TypeChar::Int => format!("int{bits}"),
                TypeChar::Uint => format!("uint{bits}"),
                TypeChar::Float => format!("float{bits}"),
                TypeChar::Complex => format!("complex{bits}"),
                _ => return format!("'{t}'"),
            };
            let order = match t.endianness() {
                Endianness::Big => " big-endian",
                _ => "",
            };
            format!("{base}{order} ('{t}')")
        }
        other => format!("a structured dtype {}", other.descr()),
    }
}

/// Reads a `.npy` file of `<f8` values: its shape (any number of
/// dimensions) and its values in C order (a Fortran-order file is
/// transposed). Values are not checked for finiteness.
fn open_npy(path: &Path, param: &'static str) -> Result<NpyData> {
    let file = open(path, param)?;
    let file_len = file
        .metadata()
        .map_err(|e| Error::file(Some(param), path, e))?
        .len();
    let mut reader = BufReader::with_capacity(1 << 20, file);
    let head = reader
        .fill_buf()
        .map_err(|e| Error::file(Some(param), path, e))?;
    if file_len == 0 {
        return Err(Error::data(
            param,
            path,
            "",
            "empty file; a NumPy .npy file (float64) is needed",
        ));
    }
    if !head.starts_with(NPY_MAGIC) {
        return Err(Error::data(
            param,
            path,
            "header",
            "not a NumPy .npy file (no \\x93NUMPY magic); a .npy file (float64) is needed",
        ));
    }
    let header = NpyHeader::from_reader(&mut reader).map_err(|e| {
        Error::data(
            param,
            path,
            "header",
            format!("unreadable .npy header ({e}); a .npy file written by numpy.save is needed"),
        )
    })?;
    let is_f8 = matches!(header.dtype(), npyz::DType::Plain(ref t)
        if t.type_char() == TypeChar::Float
            && t.size_field() == 8
            && t.endianness() == Endianness::Little);
    if !is_f8 {
        return Err(Error::data(
            param,
            path,
            "header",
            format!(
                "dtype {}; float64 little-endian ('<f8') is needed (numpy: a.astype('<f8'))",
                dtype_name(&header.dtype())
            ),
        ));
    }
    let shape: Vec<usize> = header.shape().iter().map(|&d| d as usize).collect();
    let count = header.len();
    let data_start = reader
        .stream_position()
        .map_err(|e| Error::file(Some(param), path, e))?;
    let need = count.saturating_mul(8);
    let have = file_len.saturating_sub(data_start);
    if have != need {
        let what = if have < need { "truncated" } else { "too long" };
        return Err(Error::data(
            param,
            path,
            "",
            format!(
                "{what}: the header's shape {shape:?} needs {need} bytes of data, the file has {have}"
            ),
        ));
    }
    Ok(NpyData {
        reader,
        shape,
        order: header.order(),
        bytes: need,
    })
}

/// The data section of a checked `<f8` `.npy` file, its reader positioned
/// at the first value.
struct NpyData {
    reader: BufReader<File>,
    shape: Vec<usize>,
    order: Order,
    bytes: u64,
}

/// Appends the little-endian float64 values of `bytes` (a multiple of 8) to
/// `out`.
fn push_le_f64(bytes: &[u8], out: &mut Vec<f64>) {
    out.extend(
        bytes
            .chunks_exact(8)
            .map(|b| f64::from_le_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]])),
    );
}

fn read_npy(path: &Path, param: &'static str) -> Result<(Vec<usize>, Vec<f64>)> {
    let NpyData {
        mut reader,
        shape,
        order,
        bytes: need,
    } = open_npy(path, param)?;
    let count = need / 8;
    use std::io::Read as _;
    // npyz has parsed and checked the header; the data section of a '<f8'
    // array is `count` little-endian 8-byte values, read here in bulk
    // (npyz's element iterator costs ~4 ns a value, 4 s on a 1 GB file).
    let mut data = Vec::with_capacity(count as usize);
    let mut chunk = vec![0u8; 1 << 23];
    let mut left = need as usize;
    while left > 0 {
        let take = left.min(chunk.len());
        reader
            .read_exact(&mut chunk[..take])
            .map_err(|e| Error::file(Some(param), path, e))?;
        push_le_f64(&chunk[..take], &mut data);
        left -= take;
    }
    if order == Order::Fortran && shape.len() == 2 {
        let (r, c) = (shape[0], shape[1]);
        let mut t = vec![0.0; data.len()];
        for j in 0..c {
            for i in 0..r {
                t[i * c + j] = data[j * r + i];
            }
        }
        data = t;
    } else if order == Order::Fortran && shape.len() > 2 {
        return Err(Error::data(
            param,
            path,
            "header",
            "Fortran-order array of more than 2 dimensions; C order is needed",
        ));
    }
    Ok((shape, data))
}

/// A 2-D C-order `<f8` `.npy` file read a block of rows at a time, each
/// value checked finite (memory stays at one block however large the file).
pub struct NpyRows {
    data: NpyData,
    path: PathBuf,
    param: &'static str,
    /// Rows in the file.
    pub rows: usize,
    /// Values per row.
    pub cols: usize,
    done: usize,
    buf: Vec<u8>,
}

impl NpyRows {
    /// Opens `path` when it is a `.npy` file whose rows can be streamed (2-D,
    /// C order); None for any other file, which [`read_matrix`] reads whole
    /// (and refuses with its own message when it must).
    pub fn open(path: &Path, param: &'static str) -> Result<Option<NpyRows>> {
        if !matches!(kind_of(path, param)?, Kind::Npy) {
            return Ok(None);
        }
        let data = open_npy(path, param)?;
        if data.shape.len() != 2 || data.order != Order::C || data.shape.contains(&0) {
            return Ok(None);
        }
        let (rows, cols) = (data.shape[0], data.shape[1]);
        Ok(Some(NpyRows {
            data,
            path: path.to_path_buf(),
            param,
            rows,
            cols,
            done: 0,
            buf: Vec::new(),
        }))
    }

    /// Replaces `out` with the next block of at most `max_rows` rows
    /// (row-major); returns the number of rows, 0 at the end.
    pub fn next_block(&mut self, max_rows: usize, out: &mut Vec<f64>) -> Result<usize> {
        use std::io::Read as _;
        let take = max_rows.max(1).min(self.rows - self.done);
        out.clear();
        self.buf.resize(take * self.cols * 8, 0);
        self.data
            .reader
            .read_exact(&mut self.buf)
            .map_err(|e| Error::file(Some(self.param), &self.path, e))?;
        push_le_f64(&self.buf, out);
        if let Some(i) = out.iter().position(|v| !v.is_finite()) {
            let location = at(self.done + i / self.cols + 1, i % self.cols + 1);
            return Err(not_finite(self.param, &self.path, location, out[i]));
        }
        self.done += take;
        Ok(take)
    }
}

/// Longest line of a CSV file read, bytes: room for a row of 100000
/// numbers at full precision.
pub const MAX_CSV_LINE_BYTES: u64 = 4 << 20;

/// The content lines of a CSV file: (1-based line number, fields), comments
/// and blank lines skipped.
fn csv_records(path: &Path, param: &'static str) -> Result<Vec<(usize, Vec<String>)>> {
    let mut reader = BufReader::new(open(path, param)?);
    let mut out = Vec::new();
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
        out.push((i + 1, t.split(',').map(|f| f.trim().to_owned()).collect()));
    }
    if out.is_empty() {
        return Err(Error::data(
            param,
            path,
            "",
            "empty file (no rows); comma-separated rows of numbers are needed",
        ));
    }
    Ok(out)
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

fn read_csv_matrix(path: &Path, param: &'static str) -> Result<Matrix> {
    let mut records = csv_records(path, param)?;
    let header = records[0].1.iter().all(|f| f.parse::<f64>().is_err());
    if header {
        records.remove(0);
    }
    let cols = records.first().map_or(0, |r| r.1.len());
    let mut data = Vec::with_capacity(records.len() * cols);
    for (r, (line, fields)) in records.iter().enumerate() {
        check_width(param, path, *line, r + 1, fields.len(), cols)?;
        for (c, f) in fields.iter().enumerate() {
            data.push(parse_value(param, path, *line, r + 1, c + 1, f)?);
        }
    }
    Ok(Matrix {
        rows: records.len(),
        cols,
        data,
    })
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
    let est = match kind_of(path, P)? {
        Kind::Csv => read_estimates_csv(path)?,
        Kind::Npy => read_estimates_npy(path, columns)?,
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

fn read_estimates_csv(path: &Path) -> Result<Estimates> {
    const P: &str = "estimates";
    let records = csv_records(path, P)?;
    let (hline, names) = &records[0];
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
    let mut v1 = i1.map(|_| Vec::with_capacity(records.len()));
    let mut v2 = i2.map(|_| Vec::with_capacity(records.len()));
    for (r, (line, fields)) in records[1..].iter().enumerate() {
        check_width(P, path, *line, r + 1, fields.len(), names.len())?;
        for (idx, out) in [(i1, &mut v1), (i2, &mut v2)] {
            if let (Some(c), Some(out)) = (idx, out.as_mut()) {
                out.push(parse_value(P, path, *line, r + 1, c + 1, &fields[c])?);
            }
        }
    }
    Ok(Estimates {
        v1_sq: v1,
        v2_sq: v2,
    })
}

fn read_estimates_npy(path: &Path, columns: Option<&[String]>) -> Result<Estimates> {
    const P: &str = "estimates";
    let names: Vec<String> = match columns {
        Some(c) => c.to_vec(),
        None => DEFAULT_COLUMNS.iter().map(|s| (*s).to_owned()).collect(),
    };
    let find = |n: &str| names.iter().position(|f| f == n);
    let (i1, i2) = (find("v1_sq"), find("v2_sq"));
    if i1.is_none() && i2.is_none() {
        return Err(Error::Invalid {
            param: "columns",
            reason: format!(
                "{} names neither v1_sq nor v2_sq; name the file's columns, e.g. v1_sq,v2_sq",
                names.join(",")
            ),
        });
    }
    for (k, n) in names.iter().enumerate() {
        if names[..k].contains(n) {
            return Err(Error::Invalid {
                param: "columns",
                reason: format!("{n} is named twice"),
            });
        }
    }
    let (shape, data) = read_npy(path, P)?;
    let cols = match shape.len() {
        1 => 1,
        2 => shape[1],
        d => {
            return Err(Error::data(
                P,
                path,
                "header",
                format!(
                    "{d}-D array of shape {shape:?}; a 2-D array (rows, columns) or a 1-D array is needed"
                ),
            ))
        }
    };
    if cols != names.len() {
        return Err(Error::data(
            P,
            path,
            "header",
            format!(
                "shape {shape:?} has {cols} column(s) but {} are named ({}); name every column with --columns",
                names.len(),
                names.join(",")
            ),
        ));
    }
    let rows = data.len().checked_div(cols).unwrap_or(0);
    let column = |c: usize| (0..rows).map(|r| data[r * cols + c]).collect::<Vec<f64>>();
    Ok(Estimates {
        v1_sq: i1.map(column),
        v2_sq: i2.map(column),
    })
}

/// A temporary file next to a target, removed on drop unless persisted.
struct TempTarget {
    target: PathBuf,
    temp: PathBuf,
    param: Option<&'static str>,
    done: bool,
}

impl TempTarget {
    fn create(target: &Path, param: Option<&'static str>) -> Result<(TempTarget, File)> {
        let dir = match target.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let name = target
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "out".into());
        let mut k = 0u32;
        loop {
            let temp = dir.join(format!(".{name}.{}.{k}.tmp", std::process::id()));
            match std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(&temp)
            {
                Ok(f) => {
                    v2ref::cleanup::register(&temp);
                    return Ok((
                        TempTarget {
                            target: target.to_path_buf(),
                            temp,
                            param,
                            done: false,
                        },
                        f,
                    ));
                }
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists && k < 1000 => k += 1,
                Err(e) => return Err(Error::file(param, target, e)),
            }
        }
    }

    fn io(&self, e: io::Error) -> Error {
        Error::file(self.param, &self.target, e)
    }

    /// Renames the temporary file onto the target.
    fn persist(mut self) -> Result<()> {
        std::fs::rename(&self.temp, &self.target).map_err(|e| self.io(e))?;
        v2ref::cleanup::unregister(&self.temp);
        self.done = true;
        Ok(())
    }
}

impl Drop for TempTarget {
    fn drop(&mut self) {
        if !self.done {
            let _ = std::fs::remove_file(&self.temp);
            v2ref::cleanup::unregister(&self.temp);
        }
    }
}

const WRITE_BUFFER: usize = 1 << 20;

/// A `.npy` writer of `rows × cols` float64 (`<f8`, C order), streamed row
/// after row into a temporary file that replaces the target only at
/// [`finish`](Self::finish); dropped unfinished, it leaves the target as
/// it was.
///
/// npyz writes the header; the values follow it as the little-endian
/// bytes of each f64 in row order (the `<f8` C-order data section), in
/// blocks, at disk speed.
pub struct NpyRowWriter {
    // Declared before `temp` so that it is closed before the temp file is
    // removed on drop.
    out: BufWriter<File>,
    temp: TempTarget,
    cols: usize,
    rows: u64,
    written: u64,
    bytes: Vec<u8>,
}

impl NpyRowWriter {
    /// Starts `path` as a (`rows`, `cols`) float64 array; `param` names the
    /// file in errors.
    pub fn create(path: &Path, rows: u64, cols: usize, param: &'static str) -> Result<Self> {
        let (temp, file) = TempTarget::create(path, Some(param))?;
        let out = npyz::WriteOptions::new_header_only()
            .dtype(npyz::DType::Plain("<f8".parse().expect("a valid dtype")))
            .shape(&[rows, cols as u64])
            .writer(BufWriter::with_capacity(WRITE_BUFFER, file))
            .write_header_only()
            .map_err(|e| temp.io(e))?;
        Ok(NpyRowWriter {
            out,
            temp,
            cols,
            rows,
            written: 0,
            bytes: Vec::new(),
        })
    }

    /// Appends whole rows (`values.len()` a multiple of the columns).
    pub fn write_rows(&mut self, values: &[f64]) -> Result<()> {
        let n = whole_rows(values.len(), self.cols, &self.temp)?;
        if self.written + n > self.rows {
            return Err(too_many(&self.temp, self.rows));
        }
        for block in values.chunks(WRITE_BUFFER / 8) {
            self.bytes.clear();
            self.bytes
                .extend(block.iter().flat_map(|v| v.to_le_bytes()));
            self.out
                .write_all(&self.bytes)
                .map_err(|e| self.temp.io(e))?;
        }
        self.written += n;
        Ok(())
    }

    /// Checks the row count, flushes, syncs and renames onto the target.
    pub fn finish(self) -> Result<()> {
        let NpyRowWriter {
            out,
            temp,
            rows,
            written,
            ..
        } = self;
        finish_file(out, temp, rows, written)
    }
}

/// Checks the row count, flushes, syncs, closes and renames.
fn finish_file(out: BufWriter<File>, temp: TempTarget, rows: u64, written: u64) -> Result<()> {
    if written != rows {
        return Err(row_count(&temp, rows, written));
    }
    let file = out.into_inner().map_err(|e| temp.io(e.into_error()))?;
    file.sync_all().map_err(|e| temp.io(e))?;
    drop(file);
    temp.persist()
}

fn whole_rows(len: usize, cols: usize, temp: &TempTarget) -> Result<u64> {
    if cols == 0 || len % cols != 0 {
        return Err(Error::Output {
            path: temp.target.display().to_string(),
            reason: format!("{len} values are not whole rows of {cols}"),
        });
    }
    Ok((len / cols) as u64)
}

fn too_many(temp: &TempTarget, rows: u64) -> Error {
    Error::Output {
        path: temp.target.display().to_string(),
        reason: format!("more than the {rows} rows announced"),
    }
}

fn row_count(temp: &TempTarget, rows: u64, written: u64) -> Error {
    Error::Output {
        path: temp.target.display().to_string(),
        reason: format!("{written} rows written, {rows} announced; the file was not written"),
    }
}

/// A CSV writer of rows of float64 (shortest round-trip formatting: the
/// file reads back to the same bits), with an optional header line,
/// atomic like [`NpyRowWriter`].
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

/// Writes `text` to `path` atomically (temporary file, then rename).
pub fn write_text_atomic(path: &Path, text: &str) -> Result<()> {
    let (temp, mut file) = TempTarget::create(path, None)?;
    file.write_all(text.as_bytes())
        .and_then(|_| file.sync_all())
        .map_err(|e| temp.io(e))?;
    drop(file);
    temp.persist()
}
