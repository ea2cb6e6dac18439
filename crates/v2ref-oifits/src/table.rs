//! Binary tables (`XTENSION = 'BINTABLE'`, FITS 4.0 §7.3) read in safe
//! Rust: the columns' `TFORMn` parsed, their widths summed and checked to
//! equal the row width `NAXIS1`, and `NAXIS1 × NAXIS2` checked to lie
//! inside the HDU's data (itself checked against the file by
//! [`super::fits::parse`]). Values are read big-endian from bounds-checked
//! slices.

use super::fits::{refuse, Hdu, Refusal, Value};

/// Most columns of a table (FITS 4.0 allows 999).
const MAX_COLUMNS: i64 = 999;

/// The data type of a column (`TFORMn`'s letter).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Kind {
    /// `L`: logical, one byte (`T`, `F`, or 0 for undefined).
    Logical,
    /// `X`: bits.
    Bit,
    /// `B`: unsigned byte.
    U8,
    /// `I`: 16-bit integer.
    I16,
    /// `J`: 32-bit integer.
    I32,
    /// `K`: 64-bit integer.
    I64,
    /// `A`: character.
    Char,
    /// `E`: 32-bit float.
    F32,
    /// `D`: 64-bit float.
    F64,
    /// `C`: complex of two 32-bit floats.
    C32,
    /// `M`: complex of two 64-bit floats.
    C64,
    /// `P`: 32-bit array descriptor (values on the heap, not read).
    P,
    /// `Q`: 64-bit array descriptor (values on the heap, not read).
    Q,
}

impl Kind {
    fn of(letter: char) -> Option<Kind> {
        Some(match letter {
            'L' => Kind::Logical,
            'X' => Kind::Bit,
            'B' => Kind::U8,
            'I' => Kind::I16,
            'J' => Kind::I32,
            'K' => Kind::I64,
            'A' => Kind::Char,
            'E' => Kind::F32,
            'D' => Kind::F64,
            'C' => Kind::C32,
            'M' => Kind::C64,
            'P' => Kind::P,
            'Q' => Kind::Q,
            _ => return None,
        })
    }

    /// Bytes of one element (a bit column counts whole bytes itself).
    fn bytes(self) -> u64 {
        match self {
            Kind::Logical | Kind::Bit | Kind::U8 | Kind::Char => 1,
            Kind::I16 => 2,
            Kind::I32 | Kind::F32 => 4,
            Kind::I64 | Kind::F64 | Kind::C32 | Kind::P => 8,
            Kind::C64 | Kind::Q => 16,
        }
    }
}

/// One column: name, type, repeat count and place in the row.
#[derive(Debug, Clone, PartialEq)]
pub struct Column {
    /// `TTYPEn` (trailing blanks removed; empty when absent).
    pub name: String,
    /// The type.
    pub kind: Kind,
    /// Elements per row (`TFORMn`'s repeat count).
    pub repeat: usize,
    /// Byte offset of its first element in a row.
    pub offset: usize,
    /// `TSCALn` and `TZEROn` (1 and 0 when absent).
    pub scale: (f64, f64),
}

/// A binary table: its columns and rows, over its HDU's data.
#[derive(Debug, Clone)]
pub struct Table<'a> {
    /// The HDU.
    pub hdu: &'a Hdu<'a>,
    /// Columns, in order.
    pub columns: Vec<Column>,
    /// Rows (`NAXIS2`).
    pub rows: usize,
    /// Bytes per row (`NAXIS1`).
    pub row_bytes: usize,
}

/// `TFORMn`: repeat count and type (`rT`, `rTa`; `P`/`Q` as `rPt(max)`).
fn parse_tform(tform: &str) -> Option<(u64, Kind)> {
    let t = tform.trim();
    let digits = t.find(|c: char| !c.is_ascii_digit())?;
    let repeat = if digits == 0 {
        1
    } else {
        t[..digits].parse().ok()?
    };
    let kind = Kind::of(t[digits..].chars().next()?)?;
    Some((repeat, kind))
}

impl<'a> Table<'a> {
    /// The binary table of `hdu`, its layout checked against its data.
    pub fn new(hdu: &'a Hdu<'a>) -> Result<Table<'a>, Refusal> {
        let at = hdu.at();
        if hdu.header.str("XTENSION") != Some("BINTABLE") {
            return Err(refuse(&at, "not a binary table (XTENSION = 'BINTABLE')"));
        }
        let (naxis, bitpix) = (hdu.required_int("NAXIS")?, hdu.required_int("BITPIX")?);
        let gcount = hdu.header.int("GCOUNT").unwrap_or(1);
        if naxis != 2 || bitpix != 8 || gcount != 1 {
            return Err(refuse(
                &at,
                format!(
                    "NAXIS {naxis}, BITPIX {bitpix}, GCOUNT {gcount}; a binary table has 2, 8, 1"
                ),
            ));
        }
        // data_size has checked both >= 0 and their product within the file.
        let row_bytes = hdu.required_int("NAXIS1")? as u64;
        let rows = hdu.required_int("NAXIS2")? as u64;
        let fields = hdu.required_int("TFIELDS")?;
        if !(0..=MAX_COLUMNS).contains(&fields) {
            return Err(refuse(
                format!("{at}, keyword TFIELDS"),
                format!("{fields}; 0 to {MAX_COLUMNS} columns are accepted"),
            ));
        }
        let mut columns = Vec::new();
        let mut offset: u64 = 0;
        for n in 1..=fields {
            let col = column(hdu, n, offset)?;
            offset = col.1;
            columns.push(col.0);
        }
        if offset != row_bytes {
            return Err(refuse(
                format!("{at}, keyword NAXIS1"),
                format!(
                    "{row_bytes} bytes per row, its columns (TFORMn) take {offset}: \
                     the header is inconsistent"
                ),
            ));
        }
        // Rows of no bytes would be counted without bounds.
        if row_bytes == 0 && rows > 0 {
            return Err(refuse(
                format!("{at}, keyword NAXIS1"),
                format!("0 bytes per row in {rows} rows; a table with rows has columns"),
            ));
        }
        if row_bytes.saturating_mul(rows) > hdu.data_len as u64 {
            return Err(refuse(
                &at,
                "the rows run past the data: the header is wrong",
            ));
        }
        Ok(Table {
            hdu,
            columns,
            rows: rows as usize,
            row_bytes: row_bytes as usize,
        })
    }

    /// The column named `name` (case-insensitive, as FITS compares
    /// `TTYPEn`), refused when absent.
    pub fn column(&self, name: &str) -> Result<&Column, Refusal> {
        self.columns
            .iter()
            .find(|c| c.name.eq_ignore_ascii_case(name))
            .ok_or_else(|| {
                refuse(
                    format!("{}, column {name}", self.hdu.at()),
                    "missing; the standard requires it",
                )
            })
    }

    /// The bytes of element `k` of column `c` in row `r`: a checked
    /// slice of the data.
    fn element(&self, c: &Column, r: usize, k: usize) -> Result<&'a [u8], Refusal> {
        let width = c.kind.bytes() as usize;
        let start = r
            .checked_mul(self.row_bytes)
            .and_then(|s| s.checked_add(c.offset))
            .and_then(|s| s.checked_add(k.checked_mul(width)?));
        start
            .and_then(|s| self.hdu.data.get(s..s.checked_add(width)?))
            .ok_or_else(|| refuse(self.hdu.at(), "a value lies outside the data"))
    }

    /// Every value of numeric column `c`, row after row, as f64 with
    /// `TSCALn`/`TZEROn` applied; refused for a non-numeric column.
    pub fn reals(&self, c: &Column) -> Result<Vec<f64>, Refusal> {
        let convert: fn(&[u8]) -> f64 = match c.kind {
            Kind::F64 => |b| f64::from_be_bytes(b.try_into().unwrap_or_default()),
            Kind::F32 => |b| f32::from_be_bytes(b.try_into().unwrap_or_default()) as f64,
            Kind::I16 => |b| i16::from_be_bytes(b.try_into().unwrap_or_default()) as f64,
            Kind::I32 => |b| i32::from_be_bytes(b.try_into().unwrap_or_default()) as f64,
            Kind::I64 => |b| i64::from_be_bytes(b.try_into().unwrap_or_default()) as f64,
            Kind::U8 => |b| b[0] as f64,
            other => {
                return Err(refuse(
                    format!("{}, column {}", self.hdu.at(), c.name),
                    format!(
                        "of type {other:?}; a numeric column (TFORM D, E, I, J, K or B) is needed"
                    ),
                ))
            }
        };
        let (scale, zero) = c.scale;
        self.each(c, |b| convert(b) * scale + zero)
    }

    /// Every value of logical column `c` (true: `T`; `F` and undefined
    /// are false), refused for another type.
    pub fn logicals(&self, c: &Column) -> Result<Vec<bool>, Refusal> {
        if c.kind != Kind::Logical {
            return Err(refuse(
                format!("{}, column {}", self.hdu.at(), c.name),
                format!("of type {:?}; a logical column (TFORM L) is needed", c.kind),
            ));
        }
        self.each(c, |b| b[0] == b'T')
    }

    /// Every string of character column `c`, one per row, trailing
    /// blanks and NULs removed.
    pub fn strings(&self, c: &Column) -> Result<Vec<String>, Refusal> {
        if c.kind != Kind::Char {
            return Err(refuse(
                format!("{}, column {}", self.hdu.at(), c.name),
                format!(
                    "of type {:?}; a character column (TFORM A) is needed",
                    c.kind
                ),
            ));
        }
        (0..self.rows)
            .map(|r| {
                let cell = self.cell(c, r)?;
                let text: String = cell
                    .iter()
                    .take_while(|&&b| b != 0)
                    .map(|&b| b as char)
                    .collect();
                Ok(text.trim_end().to_owned())
            })
            .collect()
    }

    /// The bytes of column `c` in row `r`: a checked slice of the data.
    fn cell(&self, c: &Column, r: usize) -> Result<&'a [u8], Refusal> {
        let width = c.repeat.checked_mul(c.kind.bytes() as usize);
        r.checked_mul(self.row_bytes)
            .and_then(|s| s.checked_add(c.offset))
            .and_then(|s| self.hdu.data.get(s..s.checked_add(width?)?))
            .ok_or_else(|| refuse(self.hdu.at(), "a value lies outside the data"))
    }

    /// `f` of every element of column `c`, row after row.
    fn each<T>(&self, c: &Column, f: impl Fn(&[u8]) -> T) -> Result<Vec<T>, Refusal> {
        let mut out = Vec::with_capacity(self.rows.saturating_mul(c.repeat));
        for r in 0..self.rows {
            for k in 0..c.repeat {
                out.push(f(self.element(c, r, k)?));
            }
        }
        Ok(out)
    }
}

/// Column `n` (1-based) starting at byte `offset` of the row: the column
/// and the offset of the next.
fn column(hdu: &Hdu, n: i64, offset: u64) -> Result<(Column, u64), Refusal> {
    let at = format!("{}, keyword TFORM{n}", hdu.at());
    let tform = hdu.header.str(&format!("TFORM{n}")).ok_or_else(|| {
        refuse(
            &at,
            "missing or not a string; the FITS standard requires it",
        )
    })?;
    let (repeat, kind) = parse_tform(tform).ok_or_else(|| {
        refuse(
            &at,
            format!("{tform:?}; a repeat count and one of L X B I J K A E D C M P Q is accepted"),
        )
    })?;
    let width = match kind {
        Kind::Bit => repeat.div_ceil(8),
        _ => repeat.saturating_mul(kind.bytes()),
    };
    let next = offset.saturating_add(width);
    let real = |k: &str, default: f64| match hdu.header.get(&format!("{k}{n}")) {
        Some(Value::Int(i)) => *i as f64,
        Some(Value::Real(x)) => *x,
        _ => default,
    };
    let name = hdu
        .header
        .str(&format!("TTYPE{n}"))
        .unwrap_or("")
        .to_owned();
    let col = Column {
        name,
        kind,
        repeat: repeat as usize,
        offset: offset as usize,
        scale: (real("TSCAL", 1.0), real("TZERO", 0.0)),
    };
    Ok((col, next))
}
