//! Figure data: the curves behind each figure panel, as self-describing
//! tables that any language can read (CSV with a header of names and units,
//! plus JSON metadata per figure).

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// One column of a table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Column {
    /// Column name (snake_case).
    pub name: String,
    /// Unit ("" for dimensionless).
    pub unit: String,
}

impl Column {
    /// A column.
    pub fn new(name: &str, unit: &str) -> Column {
        Column {
            name: name.into(),
            unit: unit.into(),
        }
    }

    /// The CSV header cell: `name` or `name [unit]`.
    pub fn header(&self) -> String {
        if self.unit.is_empty() {
            self.name.clone()
        } else {
            format!("{} [{}]", self.name, self.unit)
        }
    }
}

/// One panel's data: named columns of numbers.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Table {
    /// File stem, e.g. `fig1_v1`.
    pub name: String,
    /// Columns.
    pub columns: Vec<Column>,
    /// Rows, each as long as `columns`.
    pub rows: Vec<Vec<f64>>,
}

impl Table {
    /// CSV text: one header line, then rows with 17 significant digits
    /// (round-trips every f64 exactly).
    pub fn to_csv(&self) -> String {
        let mut out = self
            .columns
            .iter()
            .map(Column::header)
            .collect::<Vec<_>>()
            .join(",");
        out.push('\n');
        for row in &self.rows {
            let cells: Vec<String> = row.iter().map(|v| format!("{v:.16e}")).collect();
            out.push_str(&cells.join(","));
            out.push('\n');
        }
        out
    }

    /// Parses CSV text written by [`Table::to_csv`] (read as every CSV of
    /// the crate is: `#` comments and blank lines skipped, cells trimmed).
    pub fn from_csv(name: &str, text: &str) -> Result<Table> {
        let bad = |reason: String| Error::Output {
            path: format!("{name}.csv"),
            reason,
        };
        // Text in memory: every line can be read (no limit, no I/O).
        let mut lines = crate::csv_lines::CsvLines::new(text.as_bytes(), u64::MAX);
        let unreadable = |e: crate::csv_lines::LineError| {
            bad(format!("line {}: cannot be read ({:?})", e.line, e.fault))
        };
        let Some((_, header)) = lines.next_record().map_err(unreadable)? else {
            return Err(bad("empty file".into()));
        };
        let columns: Vec<Column> = header
            .iter()
            .map(|h| match h.split_once(" [") {
                Some((n, u)) => Column::new(n, u.trim_end_matches(']')),
                None => Column::new(h, ""),
            })
            .collect();
        let mut rows = Vec::new();
        while let Some((line, cells)) = lines.next_record().map_err(unreadable)? {
            let row: std::result::Result<Vec<f64>, _> = cells.iter().map(|c| c.parse()).collect();
            let row = row.map_err(|e| bad(format!("line {line}: {e}")))?;
            if row.len() != columns.len() {
                return Err(bad(format!(
                    "line {line}: {} cells for {} columns",
                    row.len(),
                    columns.len()
                )));
            }
            rows.push(row);
        }
        Ok(Table {
            name: name.into(),
            columns,
            rows,
        })
    }

    /// The values of the column called `name`.
    pub fn column(&self, name: &str) -> Option<Vec<f64>> {
        let j = self.columns.iter().position(|c| c.name == name)?;
        Some(self.rows.iter().map(|r| r[j]).collect())
    }
}

/// A figure of the paper: its panels' tables and the metadata that
/// regenerates them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Figure {
    /// `fig0` … `fig5`.
    pub id: String,
    /// What it shows, in our words, with the paper's figure label.
    pub caption: String,
    /// Whether the numbers are Monte Carlo estimates (with standard errors).
    pub monte_carlo: bool,
    /// Every parameter the curves depend on.
    pub parameters: serde_json::Value,
    /// The panels.
    pub tables: Vec<Table>,
}

/// A difference between two tables.
#[derive(Debug, Clone, PartialEq)]
pub struct Mismatch {
    /// Table name.
    pub table: String,
    /// What differs.
    pub detail: String,
}

/// Compares `fresh` against `golden` cell by cell: equal headers and shapes,
/// and `|a − b| ≤ max(abs, rel · max(|a|, |b|))` for every cell.
pub fn compare_tables(golden: &Table, fresh: &Table, rel: f64, abs: f64) -> Vec<Mismatch> {
    let mut out = Vec::new();
    let mm = |detail: String| Mismatch {
        table: golden.name.clone(),
        detail,
    };
    if golden.columns != fresh.columns {
        out.push(mm("the columns differ".into()));
        return out;
    }
    if golden.rows.len() != fresh.rows.len() {
        out.push(mm(format!(
            "{} rows in golden, {} computed",
            golden.rows.len(),
            fresh.rows.len()
        )));
        return out;
    }
    for (i, (g, f)) in golden.rows.iter().zip(&fresh.rows).enumerate() {
        for (j, (a, b)) in g.iter().zip(f).enumerate() {
            let ok = a == b || (a - b).abs() <= abs.max(rel * a.abs().max(b.abs()));
            if !ok {
                out.push(mm(format!(
                    "row {} column {}: golden {a:e}, computed {b:e}",
                    i + 1,
                    golden.columns[j].name
                )));
            }
        }
    }
    out
}
