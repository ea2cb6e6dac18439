//! `plan --targets`: a list of targets planned with one instrument's
//! settings, one row of recommendations per target.
//!
//! The list is a CSV text ([`parse_targets`]): a header naming its columns,
//! then one target a line. Each row overrides the shared request's
//! magnitude (and band), the source's diameter and the seed; everything
//! else is shared. A row that cannot be planned (a number that does not
//! parse, a band that is not one, a magnitude out of range, a missing or
//! repeated name, a plan refused) keeps its line number and its reason, and
//! the other rows are planned all the same ([`TargetRow`] with status
//! `error`).
//!
//! A row's seed is keyed by its content (name and values) and the shared
//! seed, never by its position: reordering the list or adding rows leaves
//! every other row's plan bit for bit the same.

use crate::commands::plan::{self, PlanAnswer, PlanRequest};
use crate::error::{Error, Result};
use crate::montecarlo::derive_seed;
use crate::parameters::Physical;
use crate::plan::photometry::{Band2Mass, Magnitude};
use crate::text::printable;
use crate::words::Words;

pub use super::targets_table::{table_csv, RowFault, Status, Target, TargetRow, COLUMNS};

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

/// What is shared by every target: the physical inputs, the plan's
/// options, the throughput a row's magnitude is collected with (when the
/// shared request has no magnitude of its own), and whether to verify.
#[derive(Debug, Clone)]
pub struct SharedPlan {
    /// The physical inputs (a row replaces `diameter_mas`).
    pub physical: Physical,
    /// The plan's options (a row replaces `magnitude` and `seed`).
    pub request: PlanRequest,
    /// Throughput for rows with a magnitude, when `request.magnitude` is
    /// None (else its throughput is used).
    pub throughput: Option<f64>,
    /// Observations simulated to verify each recommendation (None: no
    /// verification).
    pub verify_observations: Option<u64>,
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
    let (lo, hi) = crate::plan::photometry::MAGNITUDE_RANGE;
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

/// The seed of `t`'s plan: the shared seed hashed with the row's name and
/// values ([`derive_seed`]), so that it does not depend on where the row is.
pub fn target_seed(shared_seed: u64, t: &Target) -> u64 {
    let band = t.band.map_or(f64::NAN, |b| {
        Band2Mass::WORDS
            .iter()
            .position(|w| w.value == b)
            .unwrap_or(0) as f64
    });
    let or_nan = |v: Option<f64>| v.unwrap_or(f64::NAN);
    derive_seed(
        shared_seed,
        &format!("target\u{0}{}", t.name),
        &[
            or_nan(t.magnitude),
            band,
            or_nan(t.diameter_mas),
            or_nan(t.ra_deg),
            or_nan(t.dec_deg),
        ],
    )
}

/// The shared inputs with `t`'s values in place.
fn inputs_of(shared: &SharedPlan, t: &Target) -> Result<(Physical, PlanRequest)> {
    let mut p = shared.physical.clone();
    let mut req = shared.request.clone();
    if let Some(d) = t.diameter_mas {
        p.diameter_mas = d;
    }
    req.seed = target_seed(shared.request.seed, t);
    if let (Some(magnitude), Some(band)) = (t.magnitude, t.band) {
        if p.spectrum_csv.is_some() {
            return Err(Error::Invalid {
                param: "magnitude",
                reason: "a magnitude is converted over the flat band, not with a spectrum CSV"
                    .into(),
            });
        }
        let throughput = shared
            .request
            .magnitude
            .map(|m| m.throughput)
            .or(shared.throughput)
            .ok_or_else(|| Error::Invalid {
                param: "throughput",
                reason: "needed with a row's magnitude: give a throughput (or an instrument \
                         whose preset has one)"
                    .into(),
            })?;
        req.magnitude = Some(Magnitude {
            magnitude,
            band,
            aperture_m: p.aperture_m,
            throughput,
        });
    }
    Ok((p, req))
}

/// The plan of one target, alone (`threads` as `plan`'s): its answer, or
/// the error that refused it. Cancellation is the only error that stops
/// the caller rather than marking the row ([`plan_targets`]).
pub fn plan_target(shared: &SharedPlan, t: &Target, threads: usize) -> Result<PlanAnswer> {
    let (p, req) = inputs_of(shared, t)?;
    let prepared = plan::prepare(&p, &req)?;
    let mut answer = plan::run(prepared, threads, &|_| {})?;
    // Nothing to verify when nothing reaches the target: the row says why.
    let recommended = answer.plan.recommended.is_some();
    if let Some(observations) = shared.verify_observations.filter(|_| recommended) {
        let size = plan::verification(&answer, observations)?;
        plan::verify(&mut answer, &size, threads, &|_| {})?;
    }
    Ok(answer)
}

/// The table row of one read row: planned, or marked `error` with the
/// reason (a cancellation is returned as the error).
pub fn target_row(
    shared: &SharedPlan,
    row: &std::result::Result<Target, RowFault>,
    threads: usize,
) -> Result<TargetRow> {
    match row {
        Err(fault) => Ok(TargetRow::fault(fault)),
        Ok(t) => match plan_target(shared, t, threads) {
            Err(Error::Cancelled) => Err(Error::Cancelled),
            Err(e) => Ok(TargetRow::fault(&RowFault {
                line: t.line,
                name: t.name.clone(),
                reason: e.to_string().replace('\n', " "),
            })),
            Ok(answer) => {
                let seed = target_seed(shared.request.seed, t);
                let diameter_mas = t.diameter_mas.unwrap_or(shared.physical.diameter_mas);
                Ok(TargetRow::planned(t, seed, diameter_mas, &answer))
            }
        },
    }
}

/// Every row planned in order, one after the other (each plan uses
/// `threads`); `progress` counts targets.
pub fn plan_targets(
    shared: &SharedPlan,
    rows: &[std::result::Result<Target, RowFault>],
    threads: usize,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Vec<TargetRow>> {
    let mut table = Vec::with_capacity(rows.len());
    for row in rows {
        table.push(target_row(shared, row, threads)?);
        progress(1);
    }
    Ok(table)
}
