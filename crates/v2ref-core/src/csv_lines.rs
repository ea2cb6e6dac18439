//! The one reader of comma-separated text, under every CSV the crate reads
//! (a spectrum table, a figure's table, interferograms and estimates):
//! lines one at a time, a UTF-8 byte-order mark skipped on the first,
//! lines blank or starting with `#` skipped, each content line split at its
//! commas into fields trimmed of white space. What the fields mean, and the
//! messages about them, are the caller's.
//!
//! Nothing of the text is held but the line being read, and a line longer
//! than the caller's limit is refused once the limit is passed (an endless
//! line, such as `/dev/zero`'s, stops at once).

use std::io::{self, BufRead, Read};

/// Why a line could not be read.
#[derive(Debug)]
// Told apart by the file readers of the crate `v2ref-files` only.
pub enum LineFault {
    /// Not UTF-8 text.
    NotUtf8,
    /// Longer than the limit, bytes.
    TooLong(u64),
    /// The reader failed.
    Io(io::Error),
}

/// A line that could not be read: its number (1-based) and why.
#[derive(Debug)]
pub struct LineError {
    /// The line, 1-based.
    pub line: usize,
    /// Why.
    pub fault: LineFault,
}

/// The content lines of a comma-separated text, one at a time.
pub struct CsvLines<R> {
    reader: R,
    text: String,
    /// Lines read so far (the number of the last one, 1-based).
    lines_read: usize,
    max_line_bytes: u64,
}

impl<R: BufRead> CsvLines<R> {
    /// Reads `reader`, refusing a line longer than `max_line_bytes` bytes
    /// (its newline counted).
    pub fn new(reader: R, max_line_bytes: u64) -> Self {
        CsvLines {
            reader,
            text: String::new(),
            lines_read: 0,
            max_line_bytes,
        }
    }

    /// The next content line: its number (1-based) and its fields; None
    /// at the end of the text.
    pub fn next_record(&mut self) -> Result<Option<(usize, Vec<&str>)>, LineError> {
        loop {
            self.text.clear();
            let line = self.lines_read + 1;
            let fail = |fault| LineError { line, fault };
            // One byte more than the limit tells a long line from one at it.
            let read = (&mut self.reader)
                .take(self.max_line_bytes.saturating_add(1))
                .read_line(&mut self.text)
                .map_err(|e| match e.kind() {
                    io::ErrorKind::InvalidData => fail(LineFault::NotUtf8),
                    _ => fail(LineFault::Io(e)),
                })?;
            if read == 0 {
                return Ok(None);
            }
            self.lines_read = line;
            if read as u64 > self.max_line_bytes {
                return Err(fail(LineFault::TooLong(self.max_line_bytes)));
            }
            let t = self.content();
            if !(t.is_empty() || t.starts_with('#')) {
                break;
            }
        }
        let fields = self.content().split(',').map(str::trim).collect();
        Ok(Some((self.lines_read, fields)))
    }

    /// The line read last, trimmed, without the byte-order mark that
    /// spreadsheets start their CSV with.
    fn content(&self) -> &str {
        let text = match self.lines_read {
            1 => self.text.strip_prefix('\u{feff}').unwrap_or(&self.text),
            _ => &self.text,
        };
        text.trim()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn records(text: &str, max: u64) -> Result<Vec<(usize, Vec<String>)>, LineError> {
        let mut lines = CsvLines::new(text.as_bytes(), max);
        let mut out = Vec::new();
        while let Some((n, fields)) = lines.next_record()? {
            out.push((n, fields.iter().map(|f| (*f).to_owned()).collect()));
        }
        Ok(out)
    }

    #[test]
    fn comments_blank_lines_and_a_byte_order_mark_are_skipped() {
        let got = records("\u{feff}# c\n\n a , b\r\n#x\n1,2", 100).unwrap();
        let want = vec![
            (3, vec!["a".to_owned(), "b".to_owned()]),
            (5, vec!["1".to_owned(), "2".to_owned()]),
        ];
        assert_eq!(got, want);
        assert_eq!(records("\u{feff}x,y\n", 100).unwrap()[0].1, ["x", "y"]);
    }

    #[test]
    fn a_line_past_the_limit_is_refused_with_its_number() {
        assert!(records("12345\n", 6).is_ok());
        let e = records("1\n123456\n", 6).unwrap_err();
        assert_eq!(e.line, 2);
        assert!(matches!(e.fault, LineFault::TooLong(6)));
        let bad: &[u8] = b"1\n\xff\n";
        let e = CsvLines::new(bad, 100).next_record().map(drop);
        assert!(e.is_ok());
        let mut lines = CsvLines::new(bad, 100);
        lines.next_record().unwrap();
        let e = lines.next_record().unwrap_err();
        assert!(
            matches!(e.fault, LineFault::NotUtf8) && e.line == 2,
            "{e:?}"
        );
    }
}
