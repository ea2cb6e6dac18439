//! NumPy `.npy` files of float64: read whole, streamed a block of rows at
//! a time, or written row after row (atomically).

use super::atomic::{finish_file, too_many, whole_rows, TempTarget, WRITE_BUFFER};
use super::budget::check_budget;
use super::{at, kind_of, not_finite, open, Estimates, Kind, DEFAULT_COLUMNS};
use crate::{Error, Result};
use npyz::{Endianness, NpyHeader, Order, TypeChar, WriterBuilder};
use std::fs::File;
use std::io::{BufReader, BufWriter, Read, Write};
use std::path::{Path, PathBuf};

const NPY_MAGIC: &[u8] = b"\x93NUMPY";

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
    if file_len == 0 {
        return Err(Error::data(
            param,
            path,
            "",
            "empty file; a NumPy .npy file (float64) is needed",
        ));
    }
    let header_bytes = read_header_bytes(&mut reader, file_len, param, path)?;
    // v2ref checks the shape itself before npyz sees it: npyz multiplies
    // the dimensions unchecked while parsing (a panic where overflow checks
    // are on, as in `cargo test`; a wrapped product elsewhere).
    checked_shape(&header_shape(&header_bytes, param, path)?, param, path)?;
    let header = NpyHeader::from_reader(header_bytes.as_slice()).map_err(|e| {
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
    let (shape, count) = checked_shape(header.shape(), param, path)?;
    let data_start = header_bytes.len() as u64;
    let need = count * 8;
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

/// The longest `.npy` header read: numpy itself refuses headers longer
/// than 10 000 bytes unless told otherwise (`max_header_size`); a header
/// of this size describes any array numpy writes.
const MAX_HEADER_BYTES: u64 = 1 << 20;

/// Reads the preamble (magic, version, header length) and the header text,
/// refused when the magic is missing, the version unknown or the claimed
/// length runs past the end of the file or past [`MAX_HEADER_BYTES`] (a
/// version 2 header may claim 4 GiB), before anything is allocated for it.
fn read_header_bytes(
    reader: &mut impl Read,
    file_len: u64,
    param: &'static str,
    path: &Path,
) -> Result<Vec<u8>> {
    let bad = |what: String| Error::data(param, path, "header", what);
    let mut bytes = vec![0u8; 10.min(file_len) as usize];
    reader
        .read_exact(&mut bytes)
        .map_err(|e| Error::file(Some(param), path, e))?;
    if !bytes.starts_with(NPY_MAGIC) {
        return Err(bad(
            "not a NumPy .npy file (no \\x93NUMPY magic); a .npy file (float64) is needed".into(),
        ));
    }
    let preamble = match bytes.get(6) {
        Some(1) => 10,
        Some(2 | 3) => 12,
        Some(v) => {
            return Err(bad(format!(
                "unknown .npy format version {v}; versions 1 to 3 (numpy.save) are read"
            )))
        }
        None => return Err(bad("truncated before the header's length".into())),
    };
    if file_len < preamble {
        return Err(bad("truncated before the header's length".into()));
    }
    bytes.resize(preamble as usize, 0);
    reader
        .read_exact(&mut bytes[10..])
        .map_err(|e| Error::file(Some(param), path, e))?;
    let len = match preamble {
        10 => u64::from(u16::from_le_bytes([bytes[8], bytes[9]])),
        _ => u64::from(u32::from_le_bytes([
            bytes[8], bytes[9], bytes[10], bytes[11],
        ])),
    };
    if preamble + len > file_len {
        return Err(bad(format!(
            "the header claims {len} bytes but the file has {} after the preamble; the file is truncated or not a .npy file",
            file_len - preamble
        )));
    }
    if len > MAX_HEADER_BYTES {
        return Err(bad(format!(
            "the header claims {len} bytes; at most {MAX_HEADER_BYTES} are read (numpy.save writes a few hundred)"
        )));
    }
    bytes.resize((preamble + len) as usize, 0);
    reader
        .read_exact(&mut bytes[preamble as usize..])
        .map_err(|e| Error::file(Some(param), path, e))?;
    Ok(bytes)
}

/// The dimensions of the `'shape'` tuple of a header (`(3, 4)`, `(5,)`,
/// `()`), each a decimal integer that fits a `u64`, read by v2ref before
/// any dependency computes with them.
fn header_shape(header: &[u8], param: &'static str, path: &Path) -> Result<Vec<u64>> {
    let bad = |what: &str| {
        Error::data(
            param,
            path,
            "header",
            format!("{what}; a .npy file written by numpy.save is needed"),
        )
    };
    let text = String::from_utf8_lossy(header);
    // The key followed by a colon (a structured dtype may name a field
    // 'shape' in a list, followed by a comma).
    let value = ["'shape'", "\"shape\""]
        .iter()
        .flat_map(|k| text.match_indices(k).map(|(i, _)| i + k.len()))
        .filter_map(|i| text[i..].trim_start().strip_prefix(':'))
        .min_by_key(|rest| std::cmp::Reverse(rest.len()))
        .ok_or_else(|| bad("no 'shape' key in the header"))?;
    let rest = value
        .trim_start()
        .strip_prefix('(')
        .ok_or_else(|| bad("the header's 'shape' is not a tuple"))?;
    let inside = &rest[..rest
        .find(')')
        .ok_or_else(|| bad("the header's 'shape' tuple is not closed"))?];
    let mut dims = Vec::new();
    for item in inside.split(',').map(str::trim) {
        if item.is_empty() {
            continue;
        }
        let digits = item.strip_suffix('L').unwrap_or(item);
        match digits.parse::<u64>() {
            Ok(d) => dims.push(d),
            Err(_) if !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()) => {
                return Err(bad(&format!(
                    "shape dimension {digits} claims more values than any file can hold"
                )))
            }
            Err(_) => {
                return Err(bad(&format!(
                    "shape dimension {item:?} is not a non-negative integer"
                )))
            }
        }
    }
    Ok(dims)
}

/// The header's shape as `usize`s and its number of values, refused when
/// a dimension or the product of the dimensions (times 8 bytes) does not
/// fit in a `u64`/`usize` (npyz's own product wraps on overflow).
fn checked_shape(dims: &[u64], param: &'static str, path: &Path) -> Result<(Vec<usize>, u64)> {
    let too_big = || {
        Error::data(
            param,
            path,
            "header",
            format!(
                "shape {dims:?} claims more values than any file can hold; a .npy file written by numpy.save is needed"
            ),
        )
    };
    let mut count: u64 = 1;
    // The product of the non-zero dimensions bounds every partial product
    // (npyz multiplies them for its strides, even for an empty array).
    let mut strides: u64 = 1;
    let mut shape = Vec::with_capacity(dims.len());
    for &d in dims {
        shape.push(usize::try_from(d).map_err(|_| too_big())?);
        count = count.checked_mul(d).ok_or_else(too_big)?;
        strides = strides.checked_mul(d.max(1)).ok_or_else(too_big)?;
    }
    count
        .checked_mul(8)
        .and_then(|b| usize::try_from(b).ok())
        .ok_or_else(too_big)?;
    Ok((shape, count))
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

/// Reads a whole `.npy` file of `<f8` once `shape_ok` has accepted its
/// shape and its data fit in the [`memory_budget`]: both refusals come from
/// the header, before the data are read.
pub(crate) fn read_npy(
    path: &Path,
    param: &'static str,
    shape_ok: impl FnOnce(&[usize]) -> Result<()>,
) -> Result<(Vec<usize>, Vec<f64>)> {
    let NpyData {
        mut reader,
        shape,
        order,
        bytes: need,
    } = open_npy(path, param)?;
    shape_ok(&shape)?;
    check_budget(need, param, path)?;
    let count = need / 8;
    // npyz has parsed and checked the header; the data section of a '<f8'
    // array is `count` little-endian 8-byte values, read here in bulk
    // (npyz's element iterator costs ~4 ns a value, 4 s on a 1 GB file).
    let mut data = Vec::with_capacity(count as usize);
    let mut chunk = vec![0u8; (1usize << 23).min(need as usize)];
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
    /// C order); None for any other file, which [`super::read_matrix`] reads whole
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
        // A fold without early exit vectorizes (a quarter of the cost of
        // `position` on the `estimate` CLI's rows); the value is looked for
        // only in a block that holds one.
        if !out.iter().fold(true, |finite, v| finite & v.is_finite()) {
            if let Some(i) = out.iter().position(|v| !v.is_finite()) {
                let location = at(self.done + i / self.cols + 1, i % self.cols + 1);
                return Err(not_finite(self.param, &self.path, location, out[i]));
            }
        }
        self.done += take;
        Ok(take)
    }
}

pub(crate) fn read_estimates_npy(path: &Path, columns: Option<&[String]>) -> Result<Estimates> {
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
    let mut data = open_npy(path, P)?;
    check_estimates_shape(&data.shape, &names, path)?;
    let cols = data.shape.get(1).copied().unwrap_or(1);
    let rows = data.shape[0];
    if data.order == Order::Fortran && cols > 1 {
        // Column after column on disk: read whole and taken apart.
        let (_, all) = read_npy(path, P, |_| Ok(()))?;
        let column = |c: usize| (0..rows).map(|r| all[r * cols + c]).collect::<Vec<f64>>();
        return Ok(Estimates {
            v1_sq: i1.map(column),
            v2_sq: i2.map(column),
        });
    }
    // Only the columns read are kept, filled a block of rows at a time.
    let kept = u64::from(i1.is_some()) + u64::from(i2.is_some());
    check_budget(rows as u64 * kept * 8, P, path)?;
    let (mut v1, mut v2) = (
        i1.map(|_| Vec::with_capacity(rows)),
        i2.map(|_| Vec::with_capacity(rows)),
    );
    let mut bytes = Vec::new();
    let mut values = Vec::new();
    let mut done = 0;
    while done < rows {
        let take = ESTIMATE_BLOCK_ROWS.min(rows - done);
        bytes.resize(take * cols * 8, 0);
        data.reader
            .read_exact(&mut bytes)
            .map_err(|e| Error::file(Some(P), path, e))?;
        values.clear();
        push_le_f64(&bytes, &mut values);
        for (idx, out) in [(i1, &mut v1), (i2, &mut v2)] {
            if let (Some(c), Some(out)) = (idx, out.as_mut()) {
                out.extend(values.chunks_exact(cols).map(|row| row[c]));
            }
        }
        done += take;
    }
    Ok(Estimates {
        v1_sq: v1,
        v2_sq: v2,
    })
}

/// Rows of an estimates file read at a time (a few MB).
const ESTIMATE_BLOCK_ROWS: usize = 1 << 16;

/// An estimates array is 1-D (one name) or 2-D with one column per name.
fn check_estimates_shape(shape: &[usize], names: &[String], path: &Path) -> Result<()> {
    const P: &str = "estimates";
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
    Ok(())
}

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
        Self::create_shaped(path, rows, &[cols], param)
    }

    /// Starts `path` as a (`rows`, `row_shape`…) float64 array, each row
    /// the product of `row_shape` values (a dispersed set: (rows, C, N));
    /// `param` names the file in errors.
    pub fn create_shaped(
        path: &Path,
        rows: u64,
        row_shape: &[usize],
        param: &'static str,
    ) -> Result<Self> {
        let cols = row_shape.iter().product();
        let shape: Vec<u64> = std::iter::once(rows)
            .chain(row_shape.iter().map(|&d| d as u64))
            .collect();
        let (temp, file) = TempTarget::create(path, Some(param))?;
        let out = npyz::WriteOptions::new_header_only()
            .dtype(npyz::DType::Plain("<f8".parse().expect("a valid dtype")))
            .shape(&shape)
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
