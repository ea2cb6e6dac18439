//! The curves of a panel: the rows drawn and, per plotted column, its
//! points and error bars.

use super::labels::legend_label;
use super::presentation::PlotHint;
use crate::error::Result;
use crate::table::Table;

/// The rows drawn for `table`: Fig. 1's panels gain rows near the nulls of
/// the disk, where the grid is too coarse for the sharp turns; other
/// panels are drawn from their rows.
pub(super) fn drawn_rows(table: &Table) -> Result<Table> {
    match table.name.as_str() {
        "fig1_v1" | "fig1_v2" => crate::figures::bias::fig1_refined_near_nulls(table),
        _ => Ok(table.clone()),
    }
}

/// One curve of a panel.
pub(super) struct Series {
    /// The column drawn.
    pub(super) name: String,
    pub(super) label: String,
    pub(super) dashed: bool,
    pub(super) points: Vec<(f64, f64)>,
    pub(super) errors: Option<Vec<f64>>,
}

/// The curves of `table` under `hint`: every column but the abscissa, the
/// error bars and the hidden ones, with its finite points.
pub(super) fn series_of(table: &Table, hint: &PlotHint) -> Vec<Series> {
    let x = match table.columns.first() {
        Some(c) => table.column(&c.name).unwrap_or_default(),
        None => return Vec::new(),
    };
    table
        .columns
        .iter()
        .skip(1)
        .filter(|c| {
            !c.name.ends_with("_stderr")
                && !hint.hidden.contains(&c.name.as_str())
                && !hint.hidden_suffixes.iter().any(|sfx| c.name.ends_with(sfx))
        })
        .map(|c| {
            let y = table.column(&c.name).unwrap_or_default();
            let errors = match hint
                .error_columns
                .iter()
                .find(|(curve, _)| *curve == c.name)
            {
                Some((_, col)) => table.column(col),
                None => table.column(&format!("{}_stderr", c.name)),
            };
            let y: Vec<f64> = if hint.abs_log_y {
                y.iter().map(|v| v.abs()).collect()
            } else {
                y
            };
            let errors = if hint.abs_log_y { None } else { errors };
            // Keep points and their error bars together through the filter.
            let keep: Vec<usize> = (0..x.len().min(y.len()))
                .filter(|&i| {
                    x[i].is_finite() && y[i].is_finite() && (!hint.abs_log_y || y[i] > 0.0)
                })
                .filter(|&i| !hint.log_x || x[i] > 0.0)
                .collect();
            Series {
                name: c.name.clone(),
                label: legend_label(&c.name),
                dashed: hint.dashed.contains(&c.name.as_str()),
                points: keep.iter().map(|&i| (x[i], y[i])).collect(),
                errors: errors.map(|e| keep.iter().map(|&i| e[i]).collect()),
            }
        })
        .collect()
}
