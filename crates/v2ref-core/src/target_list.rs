//! The target list of `plan --targets` / `plan_targets`, as text: a CSV
//! with a header naming its columns ([`INPUT_COLUMNS`], `name` required),
//! then one target a line ([`parse_targets`]). A row that cannot be read
//! (a number that does not parse or is out of range, a band that is not
//! one, a missing or repeated name) keeps its line number and its reason
//! ([`RowFault`]), and the other rows are read all the same; what each
//! target's plan is, is the planner's (`v2ref_commands::commands::targets`).
//!
//! Here, below the file readers (`v2ref-files` reads the file, bounded,
//! and hands the text over) and the planner, so that neither depends on
//! the other for it.

use crate::error::{Error, Result};
use crate::photometric_band::{Band2Mass, MAGNITUDE_RANGE};
use crate::text::printable;
use crate::words::Words;
use serde::Serialize;

/// The columns a target list may have; only `name` is required.
pub const INPUT_COLUMNS: [&str; 6] = [
    "name",
    "magnitude",
    "band",
    "diameter_mas",
    "ra_deg",
    "dec_deg",
];

/// Most targets in one list (a season is a few thousand).
pub const MAX_TARGETS: usize = 100_000;

/// One target of the list, as read (`None`: the cell was empty or the
/// column absent, so the shared value is used).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Target {
    /// Line of the file (1-based) the row is on.
    pub line: u64,
    /// The target's name.
    pub name: String,
    /// Its magnitude in `band` (with `band`; replaces the shared brightness).
    pub magnitude: Option<f64>,
    /// The band of `magnitude`.
    pub band: Option<Band2Mass>,
    /// Its uniform-disk diameter, mas.
    pub diameter_mas: Option<f64>,
    /// Right ascension, degrees (echoed to the table; the plan does not use it).
    pub ra_deg: Option<f64>,
    /// Declination, degrees (echoed likewise).
    pub dec_deg: Option<f64>,
}

/// A row that could not be read: its line, its name if it had one, and why.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RowFault {
    /// Line of the file (1-based).
    pub line: u64,
    /// The name in the row (empty when it had none).
    pub name: String,
    /// Why, in one line.
    pub reason: String,
}

/// Splits one CSV line into trimmed cells; a cell may be double-quoted
/// (`""` inside stands for one `"`) to hold a comma.
fn cells(line: &str) -> std::result::Result<Vec<String>, String> {
    let mut out = Vec::new();
    let mut chars = line.chars().peekable();
    loop {
        let mut cell = String::new();
        while chars.peek().is_some_and(|c| *c == ' ' || *c == '\t') {
            chars.next();
        }
        if chars.peek() == Some(&'"') {
            chars.next();
            loop {
                match chars.next() {
                    Some('"') if chars.peek() == Some(&'"') => {
                        chars.next();
                        cell.push('"');
                    }
                    Some('"') => break,
                    Some(c) => cell.push(c),
                    None => return Err("a quoted cell is not closed".into()),
                }
            }
            while chars.peek().is_some_and(|c| *c != ',') {
                if !chars.next().is_some_and(char::is_whitespace) {
                    return Err("text after a quoted cell".into());
                }
            }
        } else {
            while let Some(c) = chars.next_if(|c| *c != ',') {
                cell.push(c);
            }
        }
        out.push(cell.trim().to_owned());
        if chars.next().is_none() {
            return Ok(out);
        }
    }
}

/// The header's columns, each an [`INPUT_COLUMNS`] name at most once,
/// `name` among them.
fn header(line: &str) -> Result<Vec<usize>> {
    let bad = |reason: String| Error::Invalid {
        param: "targets",
        reason,
    };
    let names = cells(line).map_err(|r| bad(format!("the header: {r}")))?;
    let mut columns = Vec::with_capacity(names.len());
    for n in &names {
        let Some(k) = INPUT_COLUMNS.iter().position(|c| c.eq_ignore_ascii_case(n)) else {
            return Err(bad(format!(
                "the header names the column '{}'; the columns are {} (name required)",
                printable(n),
                INPUT_COLUMNS.join(", ")
            )));
        };
        if columns.contains(&k) {
            return Err(bad(format!(
                "the header names the column '{}' twice",
                printable(n)
            )));
        }
        columns.push(k);
    }
    if !columns.contains(&0) {
        return Err(bad(format!(
            "the header has no 'name' column; the columns are {} (name required)",
            INPUT_COLUMNS.join(", ")
        )));
    }
    Ok(columns)
}

/// A number cell: empty is None; else finite and within `lo..=hi` (`hi`
/// infinite: no upper bound).
fn number(column: &str, cell: &str, lo: f64, hi: f64) -> std::result::Result<Option<f64>, String> {
    if cell.is_empty() {
        return Ok(None);
    }
    // The bounds written as read (no 309-digit f64::MAX).
    let accepted = if hi.is_finite() {
        format!("{lo} to {hi}")
    } else {
        format!("{lo} or more")
    };
    match cell.parse::<f64>() {
        Ok(v) if v.is_finite() && (lo..=hi).contains(&v) => Ok(Some(v)),
        Ok(v) if !v.is_finite() => Err(format!(
            "{column}: {v} is not a finite number; accepted: {accepted}"
        )),
        Ok(v) => Err(format!("{column}: {v} is outside {accepted}")),
        Err(_) => Err(format!(
            "{column}: '{cell}' is not a number; accepted: {accepted}"
        )),
    }
}

/// A band cell (J, H, Ks, V, R, I in any case): empty is None.
fn band(cell: &str) -> std::result::Result<Option<Band2Mass>, String> {
    if cell.is_empty() {
        return Ok(None);
    }
    let words = Band2Mass::WORDS;
    match words.iter().find(|w| w.word.eq_ignore_ascii_case(cell)) {
        Some(w) => Ok(Some(w.value)),
        None => Err(format!(
            "band: '{cell}' is not one of: {}",
            words.iter().map(|w| w.word).collect::<Vec<_>>().join(", ")
        )),
    }
}

/// One data row under `columns`.
fn target(line: u64, columns: &[usize], text: &str) -> std::result::Result<Target, RowFault> {
    let values = cells(text);
    let name_at = columns.iter().position(|&c| c == 0).unwrap_or(0);
    let name = values
        .as_ref()
        .ok()
        .and_then(|v| v.get(name_at).cloned())
        .unwrap_or_default();
    // A fault's name is echoed in the table and the messages: a control
    // character (a terminal's escape sequence) is shown escaped there.
    let fault = |reason: String| RowFault {
        line,
        name: printable(&name).into_owned(),
        reason,
    };
    let values = values.map_err(fault)?;
    for (i, v) in values.iter().enumerate() {
        if let Some(c) = v.chars().find(|c| c.is_control()) {
            let column = columns.get(i).map_or("a cell", |&k| INPUT_COLUMNS[k]);
            return Err(fault(format!(
                "{column}: holds the control character {}; a cell is printable text",
                c.escape_unicode()
            )));
        }
    }
    if values.len() != columns.len() {
        return Err(fault(format!(
            "{} cells where the header has {} columns",
            values.len(),
            columns.len()
        )));
    }
    let cell = |k: usize| {
        columns
            .iter()
            .position(|&c| c == k)
            .map_or("", |i| values[i].as_str())
    };
    let (lo, hi) = MAGNITUDE_RANGE;
    let t = Target {
        line,
        name: name.clone(),
        magnitude: number("magnitude", cell(1), lo, hi).map_err(fault)?,
        band: band(cell(2)).map_err(fault)?,
        diameter_mas: number("diameter_mas", cell(3), 0.0, f64::INFINITY).map_err(fault)?,
        ra_deg: number("ra_deg", cell(4), 0.0, 360.0).map_err(fault)?,
        dec_deg: number("dec_deg", cell(5), -90.0, 90.0).map_err(fault)?,
    };
    if name.is_empty() {
        return Err(fault("name: missing; every row needs a name".into()));
    }
    if t.magnitude.is_some() != t.band.is_some() {
        return Err(fault(
            "magnitude and band: give both (or neither, for the shared brightness)".into(),
        ));
    }
    Ok(t)
}

/// The lines of `text`, each ended by a line feed, a carriage return and
/// line feed, or a carriage return alone (as classic Mac OS and some
/// spreadsheets save CSV), in order.
fn lines(text: &str) -> impl Iterator<Item = &str> {
    text.split('\n')
        .flat_map(|l| l.strip_suffix('\r').unwrap_or(l).split('\r'))
}

/// The rows of a target list (see the module doc): a header, then one
/// target a line (ended by LF, CRLF or CR); blank lines and lines starting
/// with `#` are skipped.
/// A row that cannot be read is a [`RowFault`] in its place; the list as a
/// whole is refused only when its header is (or it has no row, or more
/// than [`MAX_TARGETS`]).
pub fn parse_targets(text: &str) -> Result<Vec<std::result::Result<Target, RowFault>>> {
    let mut lines = lines(text)
        .enumerate()
        .map(|(i, l)| (i as u64 + 1, l.trim_start_matches('\u{feff}')))
        .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
    let invalid = |reason: String| Error::Invalid {
        param: "targets",
        reason,
    };
    let (_, first) = lines
        .next()
        .ok_or_else(|| invalid("no header: the first line names the columns".into()))?;
    let columns = header(first)?;
    let mut rows: Vec<std::result::Result<Target, RowFault>> = Vec::new();
    let mut seen = std::collections::HashMap::<String, u64>::new();
    for (line, text) in lines {
        if rows.len() == MAX_TARGETS {
            return Err(invalid(format!("more than {MAX_TARGETS} targets")));
        }
        let mut row = target(line, &columns, text);
        let name = row.as_ref().map_or_else(|f| &f.name, |t| &t.name).clone();
        // A name is taken by its first row, read or not.
        if let Some(first) = seen.get(&name).filter(|_| !name.is_empty()) {
            row = Err(RowFault {
                line,
                reason: format!("name: '{name}' already on line {first}"),
                name,
            });
        } else {
            seen.insert(name, line);
        }
        rows.push(row);
    }
    if rows.is_empty() {
        return Err(invalid(
            "no target: the header is followed by no row".into(),
        ));
    }
    Ok(rows)
}
