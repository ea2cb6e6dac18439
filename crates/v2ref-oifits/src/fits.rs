//! A FITS file's HDUs parsed in safe Rust from its bytes (FITS 4.0,
//! Pence et al. 2010, A&A 524, A42): headers of 80-byte cards in
//! 2880-byte blocks, each HDU's data size computed with checked
//! arithmetic and checked against the bytes that follow before anything
//! is read. Every later read is a bounds-checked slice of [`Hdu::data`],
//! so no header, however wrong, can make the reader look outside the file.
//!
//! `CHECKSUM` and `DATASUM` (FITS 4.0, appendix J) are verified where an
//! HDU has them.

use std::collections::HashMap;

/// One FITS block, bytes (every header and data unit fills whole blocks).
pub const BLOCK: usize = 2880;
/// One header card, bytes.
const CARD: usize = 80;
/// Most HDUs read (an OIFITS file has a handful per instrument).
const MAX_HDUS: usize = 10_000;
/// Most cards of one header (8 MB of cards: a table of 999 columns with
/// ten keywords each, and a long history, take a tenth of it).
pub const MAX_CARDS: usize = 100_000;

/// Where in the file, and what is wrong with it.
#[derive(Debug, Clone, PartialEq)]
pub struct Refusal {
    /// `HDU 3`, `HDU 3, keyword NAXIS2`, or empty.
    pub location: String,
    /// What is wrong and what is accepted.
    pub reason: String,
}

pub(crate) fn refuse(location: impl Into<String>, reason: impl Into<String>) -> Refusal {
    Refusal {
        location: location.into(),
        reason: reason.into(),
    }
}

/// A keyword's value as written on its card.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Value {
    /// A quoted string, trailing blanks removed.
    Str(String),
    /// `T` or `F`.
    Logical(bool),
    /// An integer.
    Int(i64),
    /// A real number (not an integer).
    Real(f64),
    /// No value (`KEY     =` with nothing after) or one not understood.
    Other(String),
}

/// One header: its keywords in order (commentary cards left out), and
/// where each keyword's first card is, found once: a table reads a few
/// keywords per column, so a scan of the cards per lookup was quadratic
/// (a header of 400 000 cards took 19 s).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Header {
    /// (keyword, value), in the order of the cards.
    cards: Vec<(String, Value)>,
    /// Keyword -> index in `cards` of its first card.
    first: HashMap<String, usize>,
}

impl Header {
    /// A header of these (keyword, value) cards, in order.
    pub fn from_cards(cards: Vec<(String, Value)>) -> Header {
        let mut first = HashMap::with_capacity(cards.len());
        for (i, (k, _)) in cards.iter().enumerate() {
            first.entry(k.clone()).or_insert(i);
        }
        Header { cards, first }
    }

    /// (keyword, value), in the order of the cards.
    pub fn cards(&self) -> &[(String, Value)] {
        &self.cards
    }

    /// The value of keyword `key` (its first card).
    pub fn get(&self, key: &str) -> Option<&Value> {
        self.first.get(key).map(|&i| &self.cards[i].1)
    }

    /// A string keyword (None when absent or not a string).
    pub fn str(&self, key: &str) -> Option<&str> {
        match self.get(key)? {
            Value::Str(s) => Some(s),
            _ => None,
        }
    }

    /// An integer keyword (None when absent or not an integer).
    pub fn int(&self, key: &str) -> Option<i64> {
        match self.get(key)? {
            Value::Int(i) => Some(*i),
            _ => None,
        }
    }

    /// A real keyword (an integer one read as real).
    pub fn real(&self, key: &str) -> Option<f64> {
        match self.get(key)? {
            Value::Int(i) => Some(*i as f64),
            Value::Real(x) => Some(*x),
            _ => None,
        }
    }
}

/// One header and data unit.
#[derive(Debug, Clone, PartialEq)]
pub struct Hdu<'a> {
    /// Its number, 1-based (the primary is 1).
    pub number: usize,
    /// Its keywords.
    pub header: Header,
    /// The header's blocks (with padding).
    pub header_bytes: &'a [u8],
    /// The data's blocks (with padding); the data proper is the first
    /// [`Hdu::data_len`] bytes.
    pub data: &'a [u8],
    /// Bytes of data proper (table and heap), without padding.
    pub data_len: usize,
}

impl Hdu<'_> {
    /// `HDU n (EXTNAME X, INSNAME Y)`, the start of every location in
    /// it: a user finds a table by its names, not by counting HDUs.
    pub fn at(&self) -> String {
        place(
            self.number,
            self.header.str("EXTNAME"),
            self.header.str("INSNAME"),
        )
    }

    /// A required integer keyword, refused (named) when absent or not one.
    pub fn required_int(&self, key: &str) -> Result<i64, Refusal> {
        self.header.int(key).ok_or_else(|| {
            refuse(
                format!("{}, keyword {key}", self.at()),
                "missing or not an integer; the FITS standard requires it",
            )
        })
    }
}

/// `HDU n`, followed by `(EXTNAME X, INSNAME Y)` as far as the HDU has
/// them (the primary: `(primary)`).
pub fn place(number: usize, extname: Option<&str>, insname: Option<&str>) -> String {
    let mut names = Vec::new();
    if number == 1 {
        names.push("primary".to_owned());
    }
    if let Some(e) = extname.filter(|e| !e.is_empty()) {
        names.push(format!("EXTNAME {e}"));
    }
    if let Some(i) = insname.filter(|i| !i.is_empty()) {
        names.push(format!("INSNAME {i}"));
    }
    if names.is_empty() {
        format!("HDU {number}")
    } else {
        format!("HDU {number} ({})", names.join(", "))
    }
}

/// Every HDU of `bytes` (a whole FITS file), in order. Refused: a size
/// that is not whole blocks, a header without `END` inside the file, a
/// card that is not printable ASCII, data that the header announces
/// beyond the file's end, bytes after the last HDU that are not an HDU.
pub fn parse(bytes: &[u8]) -> Result<Vec<Hdu<'_>>, Refusal> {
    if bytes.is_empty() || bytes.len() % BLOCK != 0 {
        return Err(refuse(
            "",
            format!(
                "{} bytes, not a whole number of 2880-byte FITS blocks: truncated or not FITS",
                bytes.len()
            ),
        ));
    }
    let mut hdus = Vec::new();
    let mut start = 0;
    while start < bytes.len() {
        if hdus.len() == MAX_HDUS {
            return Err(refuse("", format!("more than {MAX_HDUS} HDUs")));
        }
        let hdu = parse_hdu(bytes, start, hdus.len() + 1)?;
        start += hdu.header_bytes.len() + hdu.data.len();
        hdus.push(hdu);
    }
    Ok(hdus)
}

/// The HDU whose header starts at byte `start`.
fn parse_hdu(bytes: &[u8], start: usize, number: usize) -> Result<Hdu<'_>, Refusal> {
    let (header, header_len) =
        parse_header(&bytes[start..], &format!("HDU {number}"), number == 1)?;
    let at = place(number, header.str("EXTNAME"), header.str("INSNAME"));
    let data_start = start + header_len;
    let data_len = data_size(&header, &at)?;
    let padded = data_len
        .checked_next_multiple_of(BLOCK)
        .ok_or_else(|| refuse(&at, "a data size beyond any file"))?;
    let rest = bytes.len() - data_start;
    if padded > rest {
        return Err(refuse(
            &at,
            format!(
                "the header announces {data_len} bytes of data ({padded} with padding), \
                 the file holds {rest} after the header: the file is truncated or its header is wrong"
            ),
        ));
    }
    Ok(Hdu {
        number,
        header,
        header_bytes: &bytes[start..data_start],
        data: &bytes[data_start..data_start + padded],
        data_len,
    })
}

/// The header at the start of `bytes`: its keywords and its length in
/// bytes (whole blocks, up to and with the block of `END`).
fn parse_header(bytes: &[u8], at: &str, primary: bool) -> Result<(Header, usize), Refusal> {
    let mut cards = Vec::new();
    for (i, card) in bytes.chunks_exact(CARD).enumerate() {
        if i == MAX_CARDS {
            return Err(refuse(
                at,
                format!("a header of more than {MAX_CARDS} cards; an OIFITS header holds far fewer: not OIFITS or damaged"),
            ));
        }
        if let Some(c) = card.iter().position(|b| !(0x20..=0x7e).contains(b)) {
            return Err(refuse(
                format!("{at}, card {}", i + 1),
                format!(
                    "byte {:#04x} at column {}; a header holds printable ASCII only: not FITS or damaged",
                    card[c],
                    c + 1
                ),
            ));
        }
        // Checked above: every byte is ASCII.
        let text = std::str::from_utf8(card).unwrap_or_default();
        let key = text[..8].trim_end();
        if i == 0 {
            let first = if primary { "SIMPLE" } else { "XTENSION" };
            if key != first {
                return Err(refuse(
                    at,
                    format!("the header starts with {key:?}, not {first}: not FITS or damaged"),
                ));
            }
        }
        if key == "END" {
            let len = ((i + 1) * CARD).next_multiple_of(BLOCK);
            return Ok((Header::from_cards(cards), len));
        }
        if &text[8..10] == "= " {
            cards.push((key.to_owned(), parse_value(&text[10..])));
        }
    }
    Err(refuse(
        at,
        "the header has no END card before the end of the file: truncated or not FITS",
    ))
}

/// The value of a card's value field (bytes 11–80), comment removed.
fn parse_value(field: &str) -> Value {
    let field = field.trim_start();
    if let Some(rest) = field.strip_prefix('\'') {
        // A string: '' inside is one quote; it ends at the lone quote.
        let mut s = String::new();
        let mut chars = rest.chars().peekable();
        while let Some(c) = chars.next() {
            if c == '\'' {
                if chars.peek() == Some(&'\'') {
                    chars.next();
                } else {
                    return Value::Str(s.trim_end().to_owned());
                }
            }
            s.push(c);
        }
        return Value::Other(field.to_owned());
    }
    let token = field.split('/').next().unwrap_or("").trim();
    match token {
        "T" => Value::Logical(true),
        "F" => Value::Logical(false),
        _ => {
            if let Ok(i) = token.parse::<i64>() {
                Value::Int(i)
            } else if let Ok(x) = token.replace(['D', 'd'], "E").parse::<f64>() {
                Value::Real(x)
            } else {
                Value::Other(token.to_owned())
            }
        }
    }
}

/// Bytes of data proper the header announces (FITS 4.0 eq. 2):
/// `|BITPIX|/8 × GCOUNT × (PCOUNT + NAXIS1 × … × NAXISm)`, every factor
/// checked and the product computed without overflow.
fn data_size(h: &Header, at: &str) -> Result<usize, Refusal> {
    let key = |k: &str| {
        h.int(k).ok_or_else(|| {
            refuse(
                format!("{at}, keyword {k}"),
                "missing or not an integer; the FITS standard requires it",
            )
        })
    };
    let bitpix = key("BITPIX")?;
    if ![8, 16, 32, 64, -32, -64].contains(&bitpix) {
        return Err(refuse(
            format!("{at}, keyword BITPIX"),
            format!("{bitpix}; 8, 16, 32, 64, -32 or -64 is accepted"),
        ));
    }
    let naxis = key("NAXIS")?;
    if !(0..=999).contains(&naxis) {
        return Err(refuse(
            format!("{at}, keyword NAXIS"),
            format!("{naxis}; 0 to 999 is accepted"),
        ));
    }
    let nonneg = |k: &str, v: i64| {
        u64::try_from(v).map_err(|_| {
            refuse(
                format!("{at}, keyword {k}"),
                format!("{v}; a count >= 0 is needed"),
            )
        })
    };
    let too_big = || refuse(at, "the header announces more data than any file holds");
    let mut count: u64 = if naxis == 0 { 0 } else { 1 };
    for n in 1..=naxis {
        let k = format!("NAXIS{n}");
        let v = nonneg(&k, key(&k)?)?;
        count = count.checked_mul(v).ok_or_else(too_big)?;
    }
    let pcount = nonneg("PCOUNT", h.int("PCOUNT").unwrap_or(0))?;
    let gcount = nonneg("GCOUNT", h.int("GCOUNT").unwrap_or(1))?;
    let bytes = count
        .checked_add(pcount)
        .and_then(|c| c.checked_mul(gcount))
        .and_then(|c| c.checked_mul(bitpix.unsigned_abs() / 8))
        .ok_or_else(too_big)?;
    usize::try_from(bytes).map_err(|_| too_big())
}

/// The ones'-complement sum of `bytes` as big-endian 32-bit words,
/// added to `sum` (FITS 4.0, appendix J: the sum behind CHECKSUM and
/// DATASUM; `bytes` is whole blocks, so whole words).
pub fn ones_complement_sum(bytes: &[u8], sum: u32) -> u32 {
    let mut wide = u64::from(sum);
    for word in bytes.chunks_exact(4) {
        wide += u64::from(u32::from_be_bytes([word[0], word[1], word[2], word[3]]));
    }
    while wide >> 32 != 0 {
        wide = (wide & 0xffff_ffff) + (wide >> 32);
    }
    wide as u32
}

/// Which of `DATASUM` and `CHECKSUM` of `hdu` do not match its bytes (an
/// absent keyword is not checked; a present one is checked as written).
pub fn checksum_mismatches(hdu: &Hdu) -> Vec<&'static str> {
    let mut bad = Vec::new();
    let data_sum = ones_complement_sum(hdu.data, 0);
    if let Some(v) = hdu.header.get("DATASUM") {
        let written = match v {
            Value::Str(s) => s.trim().parse::<u32>().ok(),
            Value::Int(i) => u32::try_from(*i).ok(),
            _ => None,
        };
        if written != Some(data_sum) {
            bad.push("DATASUM");
        }
    }
    if hdu.header.get("CHECKSUM").is_some()
        && ones_complement_sum(hdu.header_bytes, data_sum) != u32::MAX
    {
        bad.push("CHECKSUM");
    }
    bad
}

#[cfg(test)]
mod tests {
    use super::*;

    fn header(cards: &[&str]) -> Vec<u8> {
        let mut out: Vec<u8> = cards
            .iter()
            .chain(std::iter::once(&"END"))
            .flat_map(|c| format!("{c:<80}").into_bytes())
            .collect();
        out.resize(out.len().next_multiple_of(BLOCK), b' ');
        out
    }

    #[test]
    fn values_are_read_as_written() {
        assert_eq!(parse_value("'O''Hara  ' / c"), Value::Str("O'Hara".into()));
        assert_eq!(parse_value("                  12 / c"), Value::Int(12));
        assert_eq!(parse_value("             1.5D2"), Value::Real(150.0));
        assert_eq!(parse_value("                   T"), Value::Logical(true));
    }

    #[test]
    fn data_announced_beyond_the_file_is_refused() {
        let mut file = header(&[
            "SIMPLE  =                    T",
            "BITPIX  =                    8",
            "NAXIS   =                    1",
            "NAXIS1  =                 2881",
        ]);
        file.resize(2 * BLOCK, 0);
        let r = parse(&file).unwrap_err();
        assert!(r.reason.contains("truncated"), "{r:?}");
        file.resize(3 * BLOCK, 0);
        assert_eq!(parse(&file).unwrap()[0].data_len, 2881);
    }

    #[test]
    fn the_ones_complement_sum_folds_its_carries() {
        // 0xffffffff + 2 = 0x1_00000001 -> 0x00000002 in ones' complement.
        let bytes = [0xff, 0xff, 0xff, 0xff, 0, 0, 0, 2];
        assert_eq!(ones_complement_sum(&bytes, 0), 2);
    }
}
