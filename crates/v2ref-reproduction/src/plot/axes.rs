//! The axes of a panel: ranges and scales from the data, labels with
//! units, the mesh with its tick labels, and the reference lines.

use super::plot_error;
use super::presentation::PlotHint;
use super::series::Series;
use crate::error::Result;
use crate::table::Table;
use plotters::coord::ranged1d::ValueFormatter;
use plotters::prelude::*;

/// A chart of the SVG backend on coordinates `X × Y` (linear or log).
pub(super) type Chart<'a, 'b, X, Y> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<X, Y>>;

/// The axes of one panel: ranges, scales, labels and the reference lines
/// that fall within them.
#[derive(Clone)]
pub(super) struct Frame {
    pub(super) x: (f64, f64),
    pub(super) y: (f64, f64),
    pub(super) log_x: bool,
    pub(super) log_y: bool,
    pub(super) x_desc: String,
    pub(super) y_desc: String,
    pub(super) lines: Vec<(f64, &'static str)>,
}

impl Frame {
    pub(super) fn new(table: &Table, hint: &PlotHint, series: &[Series]) -> Result<Frame> {
        let (x, y) = data_ranges(series)
            .ok_or_else(|| plot_error(format!("table {} has nothing to plot", table.name)))?;
        let x = widen_if_flat(x);
        let log_y = hint.abs_log_y || (y.0 > 0.0 && y.1 / y.0 > 1e3);
        let y = pad_ordinate(y, log_y);
        let y = if log_y {
            (y.0 / 10f64.powf(hint.log_y_room_below), y.1)
        } else {
            y
        };
        let lines = reference_lines(hint, y);
        // The ordinate also covers the reference lines drawn.
        let y = lines
            .iter()
            .fold(y, |(y0, y1), (l, _)| (y0.min(*l), y1.max(*l)));
        let (x_desc, y_desc) = axis_labels(table, hint);
        Ok(Frame {
            x,
            y,
            log_x: hint.log_x,
            log_y,
            x_desc,
            y_desc,
            lines,
        })
    }
}

/// The abscissa and ordinate ranges of the points and their error bars
/// (None when there is no point).
fn data_ranges(series: &[Series]) -> Option<((f64, f64), (f64, f64))> {
    let span = (f64::INFINITY, f64::NEG_INFINITY);
    let points = series.iter().flat_map(|s| s.points.iter());
    let (x, y) = points.fold((span, span), |(x, y), p| {
        ((x.0.min(p.0), x.1.max(p.0)), (y.0.min(p.1), y.1.max(p.1)))
    });
    if x.0 > x.1 {
        return None;
    }
    let bars = series
        .iter()
        .filter_map(|s| s.errors.as_ref().map(|e| s.points.iter().zip(e)))
        .flatten();
    let y = bars.fold(y, |(y0, y1), ((_, v), e)| (y0.min(v - e), y1.max(v + e)));
    Some((x, y))
}

/// A range of one value widened to a unit span around it.
fn widen_if_flat((x0, x1): (f64, f64)) -> (f64, f64) {
    if x1 <= x0 {
        (x0 - 0.5, x1 + 0.5)
    } else {
        (x0, x1)
    }
}

/// The ordinate range with a 5% margin (linear scale), or widened when flat.
fn pad_ordinate((y0, y1): (f64, f64), log_y: bool) -> (f64, f64) {
    if y1 <= y0 {
        let pad = if y0 == 0.0 { 1.0 } else { 0.05 * y0.abs() };
        (y0 - pad, y1 + pad)
    } else if !log_y {
        let pad = 0.05 * (y1 - y0);
        (y0 - pad, y1 + pad)
    } else {
        (y0, y1)
    }
}

/// Reference lines are drawn when they are within a span of the data.
fn reference_lines(hint: &PlotHint, (y0, y1): (f64, f64)) -> Vec<(f64, &'static str)> {
    hint.lines
        .iter()
        .copied()
        .filter(|(y, _)| *y > y0 - (y1 - y0) && *y < y1 + (y1 - y0))
        .collect()
}

/// The abscissa label (the first column in words, with its unit) and the
/// ordinate label.
fn axis_labels(table: &Table, hint: &PlotHint) -> (String, String) {
    let x = &table.columns[0];
    let x_words = match x.name.as_str() {
        "s" | "spatial_freq_cpas" => "spatial frequency S".to_owned(),
        "fringe_hz" => "fringe frequency".to_owned(),
        "stroke" => "scan stroke".to_owned(),
        "dispersion_pp" => "dispersion, peak to peak".to_owned(),
        other => other.replace('_', " "),
    };
    let x_desc = match x.unit.as_str() {
        "" => x_words,
        "um" => format!("{x_words} [µm]"),
        unit => format!("{x_words} [{unit}]"),
    };
    let y_unit = table
        .columns
        .get(1)
        .map(|c| c.unit.clone())
        .unwrap_or_default();
    let y_desc = match (hint.y_label, y_unit.is_empty()) {
        (Some(l), _) => l.to_owned(),
        (None, true) => "value".to_owned(),
        (None, false) => format!("value [{y_unit}]"),
    };
    (x_desc, y_desc)
}

/// Axes, grid and tick labels.
pub(super) fn draw_mesh<X, Y>(chart: &mut Chart<'_, '_, X, Y>, frame: &Frame) -> Result<()>
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    chart
        .configure_mesh()
        .x_desc(frame.x_desc.as_str())
        .y_desc(frame.y_desc.as_str())
        .y_label_formatter(&|y: &f64| tick(*y))
        .x_label_formatter(&|x: &f64| tick(*x))
        .x_labels(if frame.log_x { 5 } else { 10 })
        .light_line_style(RGBColor(242, 242, 242))
        .bold_line_style(RGBColor(215, 215, 215))
        .draw()
        .map_err(plot_error)
}

/// The horizontal reference lines within the ordinate, across the whole
/// abscissa (a line keeps its style when others are out of range).
pub(super) fn draw_reference_lines<X, Y>(
    chart: &mut Chart<'_, '_, X, Y>,
    frame: &Frame,
) -> Result<()>
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let (x0, x1) = frame.x;
    // Distinct colours (and dash lengths) per level, so two lines on one
    // panel are told apart; a +/- pair of one level shares its style.
    const STYLES: [(RGBColor, i32); 2] = [(RGBColor(200, 30, 30), 8), (RGBColor(110, 60, 160), 3)];
    let mut levels: Vec<f64> = Vec::new();
    for (y, label) in &frame.lines {
        let level = match levels.iter().position(|l| *l == y.abs()) {
            Some(i) => i,
            None => {
                levels.push(y.abs());
                levels.len() - 1
            }
        };
        if *y < frame.y.0 || *y > frame.y.1 {
            continue;
        }
        let (colour, dash) = STYLES[level % STYLES.len()];
        let style = colour.stroke_width(2);
        let text = format!("reference: {label}");
        chart
            .draw_series(DashedLineSeries::new([(x0, *y), (x1, *y)], dash, 4, style))
            .map_err(plot_error)?
            .label(text)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + dash, y)], colour.stroke_width(2))
            });
    }
    Ok(())
}

/// A compact tick label: plain for ordinary magnitudes, `1e-5` style beyond.
pub(super) fn tick(y: f64) -> String {
    let a = y.abs();
    if a < 1e-12 {
        // Zero, or rounding noise of a tick placed at zero.
        "0".to_owned()
    } else if (1e-3..1e4).contains(&a) {
        let s = format!("{y:.4}");
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        // One digit of mantissa when it is not whole (2.5e-4, not 2e-4).
        let s = format!("{y:.1e}");
        s.replace(".0e", "e")
    }
}
