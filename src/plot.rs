//! SVG plots of figure tables (plotters, SVG backend), one per panel.
//!
//! A table is drawn by convention: the first column is the abscissa; every
//! other column is a curve, except columns named `<curve>_stderr`, which
//! become error bars on `<curve>`. Axis labels carry the columns' units. The
//! ordinate is logarithmic when every plotted value is positive and they
//! span more than three decades.

use crate::error::{Error, Result};
use crate::figure::{Figure, Table};
use plotters::prelude::*;

/// Curve colours (Okabe–Ito, distinguishable by colour-blind readers).
const PALETTE: [RGBColor; 8] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 0, 0),
    RGBColor(240, 228, 66),
];

/// Size of one panel, pixels.
const SIZE: (u32, u32) = (900, 560);

fn plot_error(e: impl std::fmt::Display) -> Error {
    Error::Io {
        path: "plot".into(),
        reason: e.to_string(),
    }
}

struct Series {
    label: String,
    points: Vec<(f64, f64)>,
    errors: Option<Vec<f64>>,
}

fn series_of(table: &Table) -> Vec<Series> {
    let x = match table.columns.first() {
        Some(c) => table.column(&c.name).unwrap_or_default(),
        None => return Vec::new(),
    };
    table
        .columns
        .iter()
        .skip(1)
        .filter(|c| !c.name.ends_with("_stderr"))
        .map(|c| {
            let y = table.column(&c.name).unwrap_or_default();
            let errors = table.column(&format!("{}_stderr", c.name));
            Series {
                label: c.name.clone(),
                points: x
                    .iter()
                    .copied()
                    .zip(y)
                    .filter(|p| p.0.is_finite() && p.1.is_finite())
                    .collect(),
                errors,
            }
        })
        .collect()
}

/// The SVG text of one panel of `figure`.
pub fn table_svg(figure: &Figure, table: &Table) -> Result<String> {
    let series = series_of(table);
    let all: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|s| s.points.iter().copied())
        .collect();
    if all.is_empty() {
        return Err(plot_error(format!(
            "table {} has nothing to plot",
            table.name
        )));
    }
    let (mut x0, mut x1) = all
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.0), b.max(p.0))
        });
    let (mut y0, mut y1) = all
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.1), b.max(p.1))
        });
    for s in &series {
        if let Some(e) = &s.errors {
            for ((_, y), e) in s.points.iter().zip(e) {
                y0 = y0.min(y - e);
                y1 = y1.max(y + e);
            }
        }
    }
    if x1 <= x0 {
        x0 -= 0.5;
        x1 += 0.5;
    }
    let log_y = y0 > 0.0 && y1 / y0 > 1e3;
    if y1 <= y0 {
        let pad = if y0 == 0.0 { 1.0 } else { 0.05 * y0.abs() };
        y0 -= pad;
        y1 += pad;
    } else if !log_y {
        let pad = 0.05 * (y1 - y0);
        y0 -= pad;
        y1 += pad;
    }
    let x_desc = table.columns[0].header();
    let y_unit = table
        .columns
        .get(1)
        .map(|c| c.unit.clone())
        .unwrap_or_default();
    let y_desc = if y_unit.is_empty() {
        "value".to_owned()
    } else {
        format!("value [{y_unit}]")
    };
    let title = format!("{} — {}", figure.id, table.name);

    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(plot_error)?;
        let mut builder = ChartBuilder::on(&root);
        builder
            .caption(&title, ("sans-serif", 20))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(80);
        macro_rules! draw {
            ($chart:expr) => {{
                let mut chart = $chart;
                chart
                    .configure_mesh()
                    .x_desc(x_desc.as_str())
                    .y_desc(y_desc.as_str())
                    .draw()
                    .map_err(plot_error)?;
                for (i, s) in series.iter().enumerate() {
                    let colour = PALETTE[i % PALETTE.len()];
                    chart
                        .draw_series(LineSeries::new(
                            s.points.iter().copied(),
                            colour.stroke_width(2),
                        ))
                        .map_err(plot_error)?
                        .label(s.label.as_str())
                        .legend(move |(x, y)| {
                            PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
                        });
                    if let Some(e) = &s.errors {
                        chart
                            .draw_series(s.points.iter().zip(e).map(|(&(x, y), &e)| {
                                ErrorBar::new_vertical(x, y - e, y, y + e, colour.filled(), 6)
                            }))
                            .map_err(plot_error)?;
                    }
                }
                chart
                    .configure_series_labels()
                    .position(SeriesLabelPosition::UpperRight)
                    .border_style(BLACK)
                    .background_style(WHITE.mix(0.85))
                    .draw()
                    .map_err(plot_error)?;
            }};
        }
        if log_y {
            draw!(builder
                .build_cartesian_2d(x0..x1, (y0..y1).log_scale())
                .map_err(plot_error)?);
        } else {
            draw!(builder
                .build_cartesian_2d(x0..x1, y0..y1)
                .map_err(plot_error)?);
        }
        root.present().map_err(plot_error)?;
    }
    Ok(svg)
}
