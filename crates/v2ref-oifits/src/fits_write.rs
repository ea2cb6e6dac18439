//! FITS written in safe Rust (FITS 4.0, Pence et al. 2010): a primary HDU
//! without data and binary tables, each HDU closed with `CHECKSUM` and
//! `DATASUM` (FITS 4.0, appendix J). The reader is [`super::fits`].
//!
//! Cards are laid out as cfitsio lays them out (values right-justified to
//! column 30, strings quoted and padded to 8 characters, reals as C's
//! `%.15G`, the structural keywords' comments), so that the files this
//! writer makes are those cfitsio made before it, byte for byte, but for
//! the time they were written (`DATE`, and the time in the comments of
//! `CHECKSUM` and `DATASUM`, hence the `CHECKSUM` value).

use super::fits::{ones_complement_sum, BLOCK};

/// One header card, bytes.
const CARD: usize = 80;

/// A keyword's value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum CardValue<'a> {
    /// A character string (at most 68 bytes kept, as cfitsio keeps).
    Str(&'a str),
    /// An integer.
    Int(i64),
    /// A real number (finite).
    Real(f64),
    /// `T` or `F`.
    Logical(bool),
}

/// The data of one binary-table column, `repeat` values per row.
#[derive(Debug, Clone, Copy)]
pub(crate) enum ColumnData<'a> {
    /// `I`: 16-bit integers.
    I16(&'a [i16]),
    /// `E`: 32-bit reals.
    F32(&'a [f32]),
    /// `D`: 64-bit reals.
    F64(&'a [f64]),
    /// `A`: one string per row, padded with blanks to the column's width.
    Str(&'a [&'a str]),
    /// `L`: logicals (`T`, `F`).
    Logical(&'a [bool]),
}

/// One binary-table column.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Column<'a> {
    /// `TTYPEn`.
    pub name: &'a str,
    /// Values per row (the width in characters for a string column).
    pub repeat: usize,
    /// Every row's values, row after row.
    pub data: ColumnData<'a>,
}

impl Column<'_> {
    /// The TFORM letter, the bytes of one element and cfitsio's words for it.
    fn form(&self) -> (char, usize, &'static str) {
        match self.data {
            ColumnData::I16(_) => ('I', 2, "2-byte INTEGER"),
            ColumnData::F32(_) => ('E', 4, "4-byte REAL"),
            ColumnData::F64(_) => ('D', 8, "8-byte DOUBLE"),
            ColumnData::Str(_) => ('A', 1, "ASCII Character"),
            ColumnData::Logical(_) => ('L', 1, "1-byte LOGICAL"),
        }
    }

    /// Bytes per row.
    fn width(&self) -> usize {
        self.form().1 * self.repeat
    }

    /// Rows held (None when the values do not fill whole rows).
    fn rows(&self) -> Option<usize> {
        let (len, per_row) = match self.data {
            ColumnData::I16(v) => (v.len(), self.repeat),
            ColumnData::F32(v) => (v.len(), self.repeat),
            ColumnData::F64(v) => (v.len(), self.repeat),
            ColumnData::Str(v) => (v.len(), 1),
            ColumnData::Logical(v) => (v.len(), self.repeat),
        };
        (per_row > 0 && len % per_row == 0).then(|| len / per_row)
    }

    /// Appends row `r`'s bytes (big-endian; strings cut or blank-padded).
    fn put_row(&self, r: usize, out: &mut Vec<u8>) {
        let span = r * self.repeat..(r + 1) * self.repeat;
        match self.data {
            ColumnData::I16(v) => v[span].iter().for_each(|x| out.extend(x.to_be_bytes())),
            ColumnData::F32(v) => v[span].iter().for_each(|x| out.extend(x.to_be_bytes())),
            ColumnData::F64(v) => v[span].iter().for_each(|x| out.extend(x.to_be_bytes())),
            ColumnData::Logical(v) => v[span].iter().for_each(|&b| out.push(logical(b))),
            ColumnData::Str(v) => {
                let text = v[r].as_bytes();
                let kept = text.len().min(self.repeat);
                out.extend(&text[..kept]);
                out.resize(out.len() + self.repeat - kept, b' ');
            }
        }
    }
}

fn logical(b: bool) -> u8 {
    if b {
        b'T'
    } else {
        b'F'
    }
}

/// One HDU being written: its cards, then its data.
#[derive(Debug, Clone)]
pub(crate) struct HduWriter {
    cards: Vec<[u8; CARD]>,
    data: Vec<u8>,
}

impl HduWriter {
    /// A primary HDU without data (`NAXIS = 0`), extensions to follow.
    pub fn primary() -> HduWriter {
        let mut h = HduWriter {
            cards: Vec::new(),
            data: Vec::new(),
        };
        let structure = [
            (
                "SIMPLE",
                CardValue::Logical(true),
                "file does conform to FITS standard",
            ),
            ("BITPIX", CardValue::Int(8), "number of bits per data pixel"),
            ("NAXIS", CardValue::Int(0), "number of data axes"),
            (
                "EXTEND",
                CardValue::Logical(true),
                "FITS dataset may contain extensions",
            ),
        ];
        for (name, value, comment) in structure {
            h.push(card(name, value, comment));
        }
        h.push(text_card(
            "COMMENT   FITS (Flexible Image Transport System) format is defined in 'Astronomy",
        ));
        h.push(text_card(
            "COMMENT   and Astrophysics', volume 376, page 359; bibcode: 2001A&A...376..359H",
        ));
        h
    }

    /// A binary table `extname` of `columns` (each holding the same number
    /// of rows), its structural cards written as cfitsio writes them.
    pub fn bintable(extname: &str, columns: &[Column]) -> Result<HduWriter, String> {
        let rows = columns.first().and_then(Column::rows).unwrap_or(0);
        if let Some(c) = columns.iter().find(|c| c.rows() != Some(rows)) {
            return Err(format!(
                "{extname}: column {} does not hold {rows} whole rows",
                c.name
            ));
        }
        let width: usize = columns.iter().map(Column::width).sum();
        let mut h = HduWriter {
            cards: Vec::new(),
            data: Vec::with_capacity(width * rows),
        };
        let int = |n: usize| CardValue::Int(n as i64);
        let structure = [
            (
                "XTENSION",
                CardValue::Str("BINTABLE"),
                "binary table extension",
            ),
            ("BITPIX", CardValue::Int(8), "8-bit bytes"),
            ("NAXIS", CardValue::Int(2), "2-dimensional binary table"),
            ("NAXIS1", int(width), "width of table in bytes"),
            ("NAXIS2", int(rows), "number of rows in table"),
            ("PCOUNT", CardValue::Int(0), "size of special data area"),
            (
                "GCOUNT",
                CardValue::Int(1),
                "one data group (required keyword)",
            ),
            (
                "TFIELDS",
                int(columns.len()),
                "number of fields in each row",
            ),
        ];
        for (name, value, comment) in structure {
            h.push(card(name, value, comment));
        }
        for (i, c) in columns.iter().enumerate() {
            let (letter, _, words) = c.form();
            let n = i + 1;
            let label = format!("label for field {n:3}");
            h.push(card(&format!("TTYPE{n}"), CardValue::Str(c.name), &label));
            let form = format!("{}{letter}", c.repeat);
            let format = format!("data format of field: {words}");
            h.push(card(&format!("TFORM{n}"), CardValue::Str(&form), &format));
        }
        h.key(
            "EXTNAME",
            CardValue::Str(extname),
            "name of this binary table extension",
        )?;
        for r in 0..rows {
            columns.iter().for_each(|c| c.put_row(r, &mut h.data));
        }
        Ok(h)
    }

    /// Appends the keyword `name` (at most 8 characters of `A-Z 0-9 - _`;
    /// a real must be finite).
    pub fn key(&mut self, name: &str, value: CardValue, comment: &str) -> Result<(), String> {
        check_name(name)?;
        if let CardValue::Real(x) = value {
            if !x.is_finite() {
                return Err(format!("keyword {name}: {x} is not a FITS number"));
            }
        }
        self.push(card(name, value, comment));
        Ok(())
    }

    /// Gives the first card of keyword `name` the comment `comment` (its
    /// value kept, the comment cut at the card's end).
    pub fn set_comment(&mut self, name: &str, comment: &str) -> Result<(), String> {
        let at = self
            .cards
            .iter()
            .position(|c| card_name(c) == name)
            .ok_or_else(|| format!("no keyword {name} to comment"))?;
        let value = value_field(&self.cards[at]);
        self.cards[at] = layout(name, Some(&value), comment);
        Ok(())
    }

    /// The HDU's bytes, appended to `out`: the cards, `CHECKSUM` and
    /// `DATASUM` (their comments stamped with `stamp`,
    /// `YYYY-MM-DDThh:mm:ss` UTC), `END`, blanks to a whole block, then the
    /// data with zeros to a whole block.
    pub fn finish(mut self, stamp: &str, out: &mut Vec<u8>) {
        let mut data = std::mem::take(&mut self.data);
        data.resize(data.len().div_ceil(BLOCK) * BLOCK, 0);
        let data_sum = ones_complement_sum(&data, 0);
        // cfitsio writes a zero sum as its placeholder, blank-padded.
        let data_sum_text = match data_sum {
            0 => "         0".to_string(),
            s => s.to_string(),
        };
        let checksum_comment = format!("HDU checksum updated {stamp}");
        self.push(card(
            "CHECKSUM",
            CardValue::Str("0000000000000000"),
            &checksum_comment,
        ));
        let checksum_at = self.cards.len() - 1;
        let data_comment = format!("data unit checksum updated {stamp}");
        self.push(card(
            "DATASUM",
            CardValue::Str(&data_sum_text),
            &data_comment,
        ));
        self.push(text_card("END"));
        let mut header: Vec<u8> = self.cards.concat();
        header.resize(header.len().div_ceil(BLOCK) * BLOCK, b' ');
        // The complement of the HDU's sum, encoded in place of the zeros,
        // brings the whole HDU's sum to -0 (all ones).
        let sum = ones_complement_sum(&header, data_sum);
        let encoded = encode_checksum(!sum);
        let value_at = checksum_at * CARD + 11;
        header[value_at..value_at + 16].copy_from_slice(&encoded);
        out.extend_from_slice(&header);
        out.extend_from_slice(&data);
    }

    fn push(&mut self, c: [u8; CARD]) {
        self.cards.push(c);
    }
}

/// Refuses a keyword name that is not a standard one.
fn check_name(name: &str) -> Result<(), String> {
    let legal = |b: &u8| b.is_ascii_uppercase() || b.is_ascii_digit() || *b == b'-' || *b == b'_';
    if name.is_empty() || name.len() > 8 || !name.as_bytes().iter().all(legal) {
        return Err(format!(
            "keyword {name:?}: a FITS keyword is 1 to 8 characters of A-Z, 0-9, - and _"
        ));
    }
    Ok(())
}

/// The card `NAME = value / comment`.
fn card(name: &str, value: CardValue, comment: &str) -> [u8; CARD] {
    let text = match value {
        CardValue::Str(s) => quoted(s),
        CardValue::Int(i) => i.to_string(),
        CardValue::Real(x) => real(x),
        CardValue::Logical(b) => char::from(logical(b)).to_string(),
    };
    layout(name, Some(&text), comment)
}

/// A card of free text (`COMMENT …`, `END`).
fn text_card(text: &str) -> [u8; CARD] {
    layout_bytes(text.as_bytes())
}

/// cfitsio's layout of a card (`ffmkky`): the name padded to 8, `= `, a
/// string left-justified and a number right-justified to column 30, then
/// ` / comment` when there is one, cut at column 80.
fn layout(name: &str, value: Option<&str>, comment: &str) -> [u8; CARD] {
    let mut line = format!("{name:<8}= ");
    if let Some(v) = value {
        if v.starts_with('\'') {
            line.push_str(v);
            if !comment.is_empty() && line.len() < 30 {
                line = format!("{line:<30}");
            }
        } else {
            line = format!("{line}{v:>20}");
        }
    }
    if line.len() < 77 && !comment.is_empty() {
        line.push_str(" / ");
        line.push_str(comment);
    }
    layout_bytes(line.as_bytes())
}

/// 80 bytes: cut, blank-padded, any byte that is not printable ASCII
/// made a blank (as cfitsio's `ffprec` does).
fn layout_bytes(text: &[u8]) -> [u8; CARD] {
    let mut c = [b' '; CARD];
    for (slot, &b) in c.iter_mut().zip(text) {
        *slot = if (b' '..=b'~').contains(&b) { b } else { b' ' };
    }
    c
}

/// The keyword name of a card.
fn card_name(c: &[u8; CARD]) -> &str {
    std::str::from_utf8(&c[..8]).map_or("", str::trim_end)
}

/// The value field of a card (from column 11 to the comment's `/`, outside
/// quotes), trimmed.
fn value_field(c: &[u8; CARD]) -> String {
    let field = String::from_utf8_lossy(&c[10..]).into_owned();
    let mut in_quote = false;
    for (i, ch) in field.char_indices() {
        match ch {
            '\'' => in_quote = !in_quote,
            '/' if !in_quote => return field[..i].trim().to_string(),
            _ => {}
        }
    }
    field.trim().to_string()
}

/// A string value quoted as cfitsio quotes it (`ffs2c`): at most 68 bytes
/// kept, quotes doubled, blank-padded to 8 characters.
fn quoted(s: &str) -> String {
    let mut inner = String::new();
    for &b in &s.as_bytes()[..s.len().min(68)] {
        // A byte that is not printable ASCII becomes a blank on the card.
        let ch = if (b' '..=b'~').contains(&b) {
            char::from(b)
        } else {
            ' '
        };
        let room = if ch == '\'' { 2 } else { 1 };
        if inner.len() + room > 68 {
            break;
        }
        inner.push(ch);
        if ch == '\'' {
            inner.push('\'');
        }
    }
    format!("'{inner:<8}'")
}

/// A real as C's `%.15G`, with a decimal point always shown (cfitsio's
/// `ffd2e`: `3` is written `3.`, `1E+20` is written `1.0E+20`).
fn real(x: f64) -> String {
    const DIGITS: i32 = 15;
    let sci = format!("{:.*e}", DIGITS as usize - 1, x);
    let (mantissa, exponent) = sci.split_once('e').unwrap_or((&sci, "0"));
    let exponent: i32 = exponent.parse().unwrap_or(0);
    let text = if (-4..DIGITS).contains(&exponent) {
        let decimals = (DIGITS - 1 - exponent) as usize;
        strip_zeros(&format!("{x:.decimals$}"))
    } else {
        c_exponent(&strip_zeros(mantissa), exponent)
    };
    if text.contains('.') {
        text
    } else if text.contains('E') {
        let sci = format!("{x:.1e}");
        let (mantissa, exponent) = sci.split_once('e').unwrap_or((&sci, "0"));
        c_exponent(mantissa, exponent.parse().unwrap_or(0))
    } else {
        text + "."
    }
}

/// C's exponent: `E`, a sign, at least two digits.
fn c_exponent(mantissa: &str, exponent: i32) -> String {
    let sign = if exponent < 0 { '-' } else { '+' };
    format!("{mantissa}E{sign}{:02}", exponent.abs())
}

/// `%G`'s trailing zeros removed, and the point if nothing follows it.
fn strip_zeros(s: &str) -> String {
    if !s.contains('.') {
        return s.to_string();
    }
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// The 16 characters encoding a checksum (FITS 4.0, appendix J: Seaman's
/// ASCII encoding, as cfitsio's `ffesum`): each byte spread over four
/// characters from `0`, punctuation avoided, rotated one to the right.
fn encode_checksum(value: u32) -> [u8; 16] {
    const PUNCTUATION: [u8; 13] = [
        0x3a, 0x3b, 0x3c, 0x3d, 0x3e, 0x3f, 0x40, 0x5b, 0x5c, 0x5d, 0x5e, 0x5f, 0x60,
    ];
    let mut ascii = [0u8; 16];
    for (i, byte) in value.to_be_bytes().into_iter().enumerate() {
        let mut ch = [i32::from(byte / 4 + 0x30); 4];
        ch[0] += i32::from(byte % 4);
        let mut changed = true;
        while changed {
            changed = false;
            for p in PUNCTUATION {
                for j in [0, 2] {
                    if ch[j] as u8 == p || ch[j + 1] as u8 == p {
                        ch[j] += 1;
                        ch[j + 1] -= 1;
                        changed = true;
                    }
                }
            }
        }
        for (j, c) in ch.into_iter().enumerate() {
            ascii[4 * j + i] = c as u8;
        }
    }
    std::array::from_fn(|i| ascii[(i + 15) % 16])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reals_are_written_as_c_writes_percent_15g() {
        let cases = [
            (-1937286.1758406, "-1937286.1758406"),
            (0.0163305760927739, "0.0163305760927739"),
            (1.02546073048344e-5, "1.02546073048344E-05"),
            (0.0, "0."),
            (300.0, "300."),
            (31.9, "31.9"),
            (1e20, "1.0E+20"),
            (1.5e-300, "1.5E-300"),
            (0.0001, "0.0001"),
            (123456789012345678.0, "1.23456789012346E+17"),
        ];
        for (x, text) in cases {
            assert_eq!(real(x), text, "{x:e}");
        }
    }

    #[test]
    fn cards_are_laid_out_as_cfitsio_lays_them_out() {
        let c = |n, v, m| String::from_utf8(card(n, v, m).to_vec()).unwrap();
        let mut expected = format!(
            "{:<80}",
            "NAXIS1  =                  134 / width of table in bytes"
        );
        assert_eq!(
            c("NAXIS1", CardValue::Int(134), "width of table in bytes"),
            expected
        );
        expected = format!("{:<80}", "TUNIT3  = 'deg     '");
        assert_eq!(c("TUNIT3", CardValue::Str("deg"), ""), expected);
        expected = format!(
            "{:<80}",
            "REFERENC= 'Perrin & Ridgway 2005' / estimators V1^2 and V2^2"
        );
        let reference = CardValue::Str("Perrin & Ridgway 2005");
        assert_eq!(
            c("REFERENC", reference, "estimators V1^2 and V2^2"),
            expected
        );
        expected = format!("{:<80}", "OBJECT  = 'it''s   '           / target");
        assert_eq!(c("OBJECT", CardValue::Str("it's"), "target"), expected);
    }

    #[test]
    fn an_hdu_sums_to_minus_zero_with_its_checksum() {
        let v = [1.5f64, -2.0, f64::NAN];
        let columns = [Column {
            name: "X",
            repeat: 1,
            data: ColumnData::F64(&v),
        }];
        let stamp = "2026-01-01T00:00:00";
        let mut bytes = Vec::new();
        HduWriter::primary().finish(stamp, &mut bytes);
        assert_eq!(bytes.len(), BLOCK);
        HduWriter::bintable("T", &columns)
            .unwrap()
            .finish(stamp, &mut bytes);
        assert_eq!(bytes.len(), 3 * BLOCK);
        assert_eq!(ones_complement_sum(&bytes[..BLOCK], 0), u32::MAX);
        assert_eq!(ones_complement_sum(&bytes[BLOCK..], 0), u32::MAX);
        let hdus = super::super::fits::parse(&bytes).unwrap();
        assert_eq!(hdus.len(), 2);
        for hdu in &hdus {
            assert!(super::super::fits::checksum_mismatches(hdu).is_empty());
        }
        // A column that does not fill its rows is refused, not written.
        let short = [Column {
            name: "Y",
            repeat: 2,
            data: ColumnData::F64(&v),
        }];
        assert!(HduWriter::bintable("T", &short).is_err());
    }
}
