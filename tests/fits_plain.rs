//! A plain FITS writer and reader for the OIFITS tests, written here from
//! the FITS standard (4.0: 2880-byte blocks of 80-character cards, binary
//! tables of big-endian fields) and sharing no code with v2ref's own, so
//! that a file the tests write is another pipeline's, and a file v2ref
//! wrote is read back by an independent reader. The Python suite reads the
//! same files with astropy, and `tests/oifits_rules.rs` runs HEASARC's
//! fitsverify on them. Only what the tests need: header keywords, and
//! columns of one value per row of the types I, J, E, D, L and nA, and of
//! n values per row of D and L (an OIFITS table of n channels).

use std::collections::HashMap;
use std::path::Path;

/// A header value as a test writes it.
pub enum Card<'a> {
    Int(i64),
    Str(&'a str),
}

/// One column of a binary table to write: its name and its values.
pub enum Column<'a> {
    I16(&'a str, Vec<i16>),
    F32(&'a str, Vec<f32>),
    F64(&'a str, Vec<f64>),
    Logical(&'a str, Vec<bool>),
    Text(&'a str, usize, Vec<String>),
    /// `n` values a row, row after row.
    F64s(&'a str, usize, Vec<f64>),
    /// `n` logicals a row, row after row.
    Logicals(&'a str, usize, Vec<bool>),
}

impl Column<'_> {
    fn name(&self) -> &str {
        match self {
            Column::I16(n, _) | Column::F32(n, _) | Column::F64(n, _) => n,
            Column::Logical(n, _) | Column::Text(n, _, _) => n,
            Column::F64s(n, _, _) | Column::Logicals(n, _, _) => n,
        }
    }
    fn tform(&self) -> String {
        match self {
            Column::I16(..) => "1I".into(),
            Column::F32(..) => "1E".into(),
            Column::F64(..) => "1D".into(),
            Column::Logical(..) => "1L".into(),
            Column::Text(_, width, _) => format!("{width}A"),
            Column::F64s(_, n, _) => format!("{n}D"),
            Column::Logicals(_, n, _) => format!("{n}L"),
        }
    }
    fn rows(&self) -> usize {
        match self {
            Column::I16(_, v) => v.len(),
            Column::F32(_, v) => v.len(),
            Column::F64(_, v) => v.len(),
            Column::Logical(_, v) => v.len(),
            Column::Text(_, _, v) => v.len(),
            Column::F64s(_, n, v) => v.len() / n,
            Column::Logicals(_, n, v) => v.len() / n,
        }
    }
    fn field(&self, row: usize) -> Vec<u8> {
        match self {
            Column::I16(_, v) => v[row].to_be_bytes().to_vec(),
            Column::F32(_, v) => v[row].to_be_bytes().to_vec(),
            Column::F64(_, v) => v[row].to_be_bytes().to_vec(),
            Column::Logical(_, v) => vec![if v[row] { b'T' } else { b'F' }],
            Column::Text(_, width, v) => {
                let mut b = v[row].as_bytes().to_vec();
                b.resize(*width, b' ');
                b
            }
            Column::F64s(_, n, v) => v[row * n..(row + 1) * n]
                .iter()
                .flat_map(|x| x.to_be_bytes())
                .collect(),
            Column::Logicals(_, n, v) => v[row * n..(row + 1) * n]
                .iter()
                .map(|&b| if b { b'T' } else { b'F' })
                .collect(),
        }
    }
}

/// A card image: `KEY     = value`, 80 bytes.
fn card(key: &str, value: &str) -> String {
    format!("{key:<8}= {value:>20}")
}

fn value_text(v: &Card) -> String {
    match v {
        Card::Int(i) => i.to_string(),
        Card::Str(s) => format!("'{:<8}'", s.replace('\'', "''")),
    }
}

/// Appends the cards, END and the padding of one header.
fn push_header(out: &mut Vec<u8>, cards: &[String]) {
    for c in cards.iter().map(String::as_str).chain(["END"]) {
        out.extend_from_slice(format!("{c:<80}").as_bytes());
    }
    pad(out, b' ');
}

fn pad(out: &mut Vec<u8>, with: u8) {
    while !out.len().is_multiple_of(2880) {
        out.push(with);
    }
}

/// One binary table to write: its EXTNAME, its keywords and its columns.
pub type Table<'a> = (&'a str, Vec<(&'a str, Card<'a>)>, Vec<Column<'a>>);

/// A FITS file: an empty primary HDU, then the binary tables given.
pub fn write(path: &Path, tables: &[Table]) {
    let mut out = Vec::new();
    let primary = [
        card("SIMPLE", "T"),
        card("BITPIX", "8"),
        card("NAXIS", "0"),
        card("EXTEND", "T"),
    ];
    push_header(&mut out, &primary);
    for (extname, keys, columns) in tables {
        let rows = columns.first().map_or(0, Column::rows);
        let width: usize = columns.iter().map(|c| c.field(0).len()).sum();
        let mut cards = vec![
            card("XTENSION", "'BINTABLE'"),
            card("BITPIX", "8"),
            card("NAXIS", "2"),
            card("NAXIS1", &width.to_string()),
            card("NAXIS2", &rows.to_string()),
            card("PCOUNT", "0"),
            card("GCOUNT", "1"),
            card("TFIELDS", &columns.len().to_string()),
        ];
        for (i, c) in columns.iter().enumerate() {
            cards.push(card(&format!("TTYPE{}", i + 1), &format!("'{}'", c.name())));
            cards.push(card(
                &format!("TFORM{}", i + 1),
                &format!("'{}'", c.tform()),
            ));
        }
        cards.push(card("EXTNAME", &format!("'{extname}'")));
        cards.extend(keys.iter().map(|(k, v)| card(k, &value_text(v))));
        push_header(&mut out, &cards);
        for row in 0..rows {
            for c in columns {
                out.extend(c.field(row));
            }
        }
        pad(&mut out, 0);
    }
    std::fs::write(path, out).unwrap();
}

/// One HDU as read: its header (keyword → value text, strings unquoted)
/// and, for a binary table, its data.
pub struct Hdu {
    pub header: HashMap<String, String>,
    data: Vec<u8>,
}

impl Hdu {
    pub fn key(&self, key: &str) -> &str {
        self.header
            .get(key)
            .unwrap_or_else(|| panic!("no keyword {key}"))
    }
    pub fn f64_key(&self, key: &str) -> f64 {
        self.key(key).replace('D', "E").parse().unwrap()
    }
    fn int(&self, key: &str) -> usize {
        self.key(key).parse().unwrap()
    }

    /// The column `name`, each row's field as big-endian bytes.
    fn fields(&self, name: &str) -> Vec<&[u8]> {
        let (mut offset, mut width) = (None, 0);
        let mut at = 0;
        for i in 1..=self.int("TFIELDS") {
            let form = self.key(&format!("TFORM{i}"));
            let (count, code) = form.split_at(form.len() - 1);
            let count: usize = if count.is_empty() {
                1
            } else {
                count.parse().unwrap()
            };
            let size = match code {
                "L" | "A" | "B" => 1,
                "I" => 2,
                "J" | "E" => 4,
                "K" | "D" => 8,
                other => panic!("TFORM {other} not read here"),
            } * count;
            if self.key(&format!("TTYPE{i}")) == name {
                (offset, width) = (Some(at), size);
            }
            at += size;
        }
        let offset = offset.unwrap_or_else(|| panic!("no column {name}"));
        let row_bytes = self.int("NAXIS1");
        (0..self.int("NAXIS2"))
            .map(|r| &self.data[r * row_bytes + offset..][..width])
            .collect()
    }
    pub fn f64_col(&self, name: &str) -> Vec<f64> {
        self.fields(name)
            .iter()
            .map(|b| f64::from_be_bytes((*b).try_into().unwrap()))
            .collect()
    }
    pub fn f32_col(&self, name: &str) -> Vec<f32> {
        self.fields(name)
            .iter()
            .map(|b| f32::from_be_bytes((*b).try_into().unwrap()))
            .collect()
    }
    /// Every value of a column of `D` values, row after row.
    pub fn f64_values(&self, name: &str) -> Vec<f64> {
        self.fields(name)
            .iter()
            .flat_map(|b| b.chunks(8))
            .map(|c| f64::from_be_bytes(c.try_into().unwrap()))
            .collect()
    }
    /// Every value of a column of `L` values, row after row.
    pub fn logical_values(&self, name: &str) -> Vec<bool> {
        self.fields(name)
            .iter()
            .flat_map(|b| b.iter().map(|&c| c == b'T'))
            .collect()
    }
    pub fn text_col(&self, name: &str) -> Vec<String> {
        self.fields(name)
            .iter()
            .map(|b| {
                String::from_utf8_lossy(b)
                    .trim_end_matches([' ', '\0'])
                    .to_owned()
            })
            .collect()
    }
}

/// The value text of a card's value field: a quoted string unquoted, else
/// the text before any comment.
fn card_value(field: &str) -> String {
    let field = field.trim_start();
    let Some(quoted) = field.strip_prefix('\'') else {
        return field.split('/').next().unwrap_or("").trim().to_owned();
    };
    // The string ends at the first quote that is not doubled.
    let bytes = quoted.as_bytes();
    let mut end = 0;
    while end < bytes.len() && !(bytes[end] == b'\'' && bytes.get(end + 1) != Some(&b'\'')) {
        end += if bytes[end] == b'\'' { 2 } else { 1 };
    }
    quoted[..end].replace("''", "'").trim_end().to_owned()
}

/// Every HDU of the FITS file at `path` (plain, not gzip).
pub fn read(path: &Path) -> Vec<Hdu> {
    let bytes = std::fs::read(path).unwrap();
    let mut hdus = Vec::new();
    let mut at = 0;
    while at < bytes.len() {
        let mut header = HashMap::new();
        loop {
            let c = std::str::from_utf8(&bytes[at..at + 80]).unwrap();
            at += 80;
            if c.starts_with("END ") || c == format!("{:<80}", "END") {
                break;
            }
            if &c[8..10] == "= " {
                header.insert(c[..8].trim().to_owned(), card_value(&c[10..]));
            }
        }
        at = at.div_ceil(2880) * 2880;
        let dims: usize = (1..=header["NAXIS"].parse::<usize>().unwrap())
            .map(|i| header[&format!("NAXIS{i}")].parse::<usize>().unwrap())
            .product();
        let len = if header["NAXIS"] == "0" { 0 } else { dims };
        let data = bytes[at..at + len].to_vec();
        at = (at + len).div_ceil(2880) * 2880;
        hdus.push(Hdu { header, data });
    }
    hdus
}

/// The HDU named `extname` (the first of that name).
pub fn hdu<'a>(hdus: &'a [Hdu], extname: &str) -> &'a Hdu {
    hdus.iter()
        .find(|h| h.header.get("EXTNAME").is_some_and(|n| n == extname))
        .unwrap_or_else(|| panic!("no HDU {extname}"))
}

#[test]
fn what_is_written_is_read_back() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.fits");
    let table = (
        "T",
        vec![("OI_REVN", Card::Int(2)), ("INSNAME", Card::Str("O'K"))],
        vec![
            Column::F64("X", vec![1.5, -2.25e-300]),
            Column::Text("NAME", 16, vec!["a".into(), "bb".into()]),
            Column::F32("Y", vec![2.2e-6, 0.0]),
        ],
    );
    write(&path, &[table]);
    let hdus = read(&path);
    assert_eq!(hdus.len(), 2);
    let t = hdu(&hdus, "T");
    assert_eq!((t.key("OI_REVN"), t.key("INSNAME")), ("2", "O'K"));
    assert_eq!(t.f64_col("X"), [1.5, -2.25e-300]);
    assert_eq!(t.text_col("NAME"), ["a", "bb"]);
    assert_eq!(t.f32_col("Y"), [2.2e-6, 0.0]);
    assert_eq!(std::fs::metadata(&path).unwrap().len() % 2880, 0);
}
