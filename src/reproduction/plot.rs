//! SVG plots of figure tables (plotters, SVG backend), one per panel.
//!
//! A table is drawn by convention: the first column is the abscissa; every
//! other column is a curve, except columns named `<curve>_stderr`, which
//! become error bars on `<curve>`, and the context columns of [`hint`]
//! (the monochromatic visibility beside its deviations, sample counts).
//! Axis labels carry the columns' units. The ordinate is logarithmic when
//! every plotted value is positive and they span more than three decades.
//! Per-panel presentation (ordinate label, reference lines such as the
//! paper's 0.2% accuracy) lives in [`hint`], apart from the data.

use crate::error::{Error, Result};
use crate::reproduction::table::{Figure, Table};
use plotters::coord::ranged1d::ValueFormatter;
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
    Error::Output {
        path: "plot".into(),
        reason: e.to_string(),
    }
}

/// How one panel is presented.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PlotHint {
    /// Columns not drawn (context kept in the CSV).
    pub hidden: Vec<&'static str>,
    /// Ordinate label (default: "value [unit]").
    pub y_label: Option<&'static str>,
    /// Horizontal reference lines: (ordinate, label).
    pub lines: Vec<(f64, &'static str)>,
    /// Column-name suffixes whose columns are not drawn (variants kept in
    /// the CSV, such as other bin windows).
    pub hidden_suffixes: Vec<&'static str>,
    /// (curve, column) pairs: draw `column` as the error bars of `curve`
    /// instead of `<curve>_stderr` (the paper's Fig. 4 shows the scatter).
    pub error_columns: Vec<(&'static str, &'static str)>,
    /// Draw |y| on a logarithmic ordinate (bias magnitudes spanning decades).
    pub abs_log_y: bool,
    /// Logarithmic abscissa.
    pub log_x: bool,
    /// What the panel shows, in words (default: the figure and panel ids).
    pub title: Option<&'static str>,
    /// Curves drawn dashed with markers (so that a curve lying on another
    /// stays visible).
    pub dashed: Vec<&'static str>,
    /// A caveat printed under the parameters.
    pub note: Option<&'static str>,
    /// Where the legend goes (where it hides no curve).
    pub legend_at: LegendAt,
    /// A zoom drawn inside the chart, on linear axes.
    pub inset: Option<Inset>,
    /// Decades of room below the data on a logarithmic ordinate (for the
    /// inset and the legend).
    pub log_y_room_below: f64,
    /// Panel height, pixels (default: 560, the figures' standard height).
    pub height_px: Option<u32>,
}

/// A corner of the chart for the legend.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum LegendAt {
    /// Upper right (plotters' usual place).
    #[default]
    UpperRight,
    /// Lower right.
    LowerRight,
    /// Lower left.
    LowerLeft,
}

/// A zoom on part of the abscissa, drawn in the lower left corner of the
/// chart on linear axes, with the panel's curves and reference lines and
/// no legend (the panel's applies).
#[derive(Debug, Clone, PartialEq)]
pub struct Inset {
    /// The abscissa shown, in the panel's unit.
    pub x_range: (f64, f64),
    /// The columns whose values over `x_range` set the ordinate's top
    /// (the others may leave it).
    pub fit: Vec<&'static str>,
    /// What the inset shows, printed above it.
    pub caption: &'static str,
}

/// The inset's share of the chart's width and height.
const INSET_SHARE: f64 = 0.45;

/// Columns that give context to a panel rather than being its subject.
const CONTEXT_COLUMNS: [&str; 6] = [
    "v_mono",
    "samples",
    "v1_infinite",
    "v2_infinite",
    "difference",
    "scans",
];

/// The paper's "current best accuracy" of single-mode interferometers (0.2%).
const ACCURACY_0P2: f64 = 2e-3;

/// Why Fig. 1's curves turn sharply at the nulls of the disk, and how they
/// are drawn there.
const FIG1_NOTE: &str = "At the nulls |V mono| and the wide-band V vanish at slightly different S: the sharp turns are real, drawn from extra points there (the CSV keeps the grid).";

/// The presentation of the panel called `table`.
pub fn hint(table: &str) -> PlotHint {
    let mut h = PlotHint {
        hidden: CONTEXT_COLUMNS.to_vec(),
        ..PlotHint::default()
    };
    match table {
        "fig0_normalization" => {
            h.y_label = Some("|V2 normalized - V2 unnormalized|, V = 1");
            h.title =
                Some("Fig. 0: effect of normalizing V2 by the mean flux, against scan stroke");
            h.lines = vec![(ACCURACY_0P2, "0.2%")];
            // The Riemann-sum curve runs along the top: the legend goes below.
            h.legend_at = LegendAt::LowerLeft;
            h.log_y_room_below = 1.5;
        }
        "fig1_v1" => {
            h.note = Some(FIG1_NOTE);
            h.y_label = Some("V1 - V mono");
            h.title = Some("Fig. 1: wide-band V1 minus monochromatic V, uniform disk");
        }
        "fig1_v2" => {
            h.note = Some(FIG1_NOTE);
            h.legend_at = LegendAt::LowerLeft;
            h.y_label = Some("V2 - V mono");
            h.title = Some("Fig. 1: wide-band V2 minus monochromatic V, uniform disk");
        }
        "fig2_disk" => {
            h.y_label = Some("V2 - V mono");
            h.title = Some("Fig. 2: V2 minus monochromatic V under dispersion, uniform disk");
            h.legend_at = LegendAt::LowerRight;
        }
        "fig2_point" => {
            h.y_label = Some("V2 of a point source");
            h.title =
                Some("Fig. 2: V2 of a point source against dispersion (numerical and Fresnel)");
            h.dashed = vec!["v2_fresnel"];
        }
        "fig3_v1" | "fig3_v2" | "fig3_abcd" | "fig3_convolution" => {
            h.y_label = Some("bias against the infinite scan");
            h.title = Some(match table {
                "fig3_v1" => "Fig. 3: bias of V1 from a finite scan, against spatial frequency",
                "fig3_v2" => "Fig. 3: bias of V2 from a finite scan, against spatial frequency",
                "fig3_abcd" => "Fig. 3: finite-scan bias, DFT against convolution estimators",
                _ => "Fig. 3: finite-scan bias of V1 and V2 (convolution estimator)",
            });
            h.lines = vec![(ACCURACY_0P2, "+0.2%"), (-ACCURACY_0P2, "-0.2%")];
            // The biases dip at the nulls, the last one under the upper
            // right corner; the lower left is empty.
            if table != "fig3_v2" {
                h.legend_at = LegendAt::LowerLeft;
            }
        }
        t if t.starts_with("fig4_") => {
            h.y_label = Some("V(piston) - V(no piston); bars: scatter over scans");
            h.title = Some("Fig. 4: bias of V1 and V2 (on V) from atmospheric piston");
            h.hidden.extend([
                "baseline_m",
                "piston_rms_um",
                "v1_no_piston",
                "v2_no_piston",
                "scatter_v1",
                "scatter_v2",
            ]);
            h.error_columns = vec![("bias_v1", "scatter_v1"), ("bias_v2", "scatter_v2")];
            h.lines = vec![(1e-3, "+0.1%"), (-1e-3, "-0.1%")];
        }
        t if t.starts_with("fig5_") => {
            h.y_label = Some("|bias| and scatter of V");
            h.title = Some(if table == "fig5_sampled" {
                "Fig. 5: piston bias and scatter of V against fringe frequency (sampled)"
            } else {
                "Fig. 5: piston bias and scatter of V against fringe frequency (integrating)"
            });
            h.hidden.extend(["scan_time_s", "residual_rms_um"]);
            h.hidden_suffixes = vec!["_band", "_all"];
            h.abs_log_y = true;
            h.log_x = true;
            h.lines = vec![(1e-2, "1%"), (1e-5, "1e-5")];
            // The biases near 1e-5 at high fringe frequency, on linear axes.
            h.inset = Some(Inset {
                x_range: (500.0, 2000.0),
                fit: vec!["bias_v1", "bias_v2"],
                caption: "zoom: |bias| at 500-2000 Hz, linear axes",
            });
            h.log_y_room_below = 2.0;
            h.legend_at = LegendAt::LowerRight;
            h.height_px = Some(700);
        }
        _ => {}
    }
    h
}

/// The rows drawn for `table`: Fig. 1's panels gain rows near the nulls of
/// the disk, where the grid is too coarse for the sharp turns; other
/// panels are drawn from their rows.
fn drawn_rows(table: &Table) -> Result<Table> {
    match table.name.as_str() {
        "fig1_v1" | "fig1_v2" => crate::reproduction::figures::bias::fig1_refined_near_nulls(table),
        _ => Ok(table.clone()),
    }
}

struct Series {
    /// The column drawn.
    name: String,
    label: String,
    dashed: bool,
    points: Vec<(f64, f64)>,
    errors: Option<Vec<f64>>,
}

fn series_of(table: &Table, hint: &PlotHint) -> Vec<Series> {
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

/// The SVG text of one panel of `figure`.
pub fn table_svg(figure: &Figure, table: &Table) -> Result<String> {
    let hint = hint(&table.name);
    let table = &drawn_rows(table)?;
    let series = series_of(table, &hint);
    let frame = Frame::new(table, &hint, &series)?;
    let mut title = match hint.title {
        Some(t) => t.to_owned(),
        None => format!("{} — {}", figure.id, table.name),
    };
    // Fig. 4's panels differ by diameter and fringe frequency: say which.
    if let Some(rest) = table.name.strip_prefix("fig4_") {
        if let Some((mas, hz)) = rest.split_once("mas_") {
            let hz = hz.trim_end_matches("hz");
            title.push_str(&format!(", {mas} mas disk, {hz} Hz fringes"));
        }
    }
    let subtitle = parameter_line(&figure.parameters);
    let mut svg = String::new();
    {
        let size = (SIZE.0, hint.height_px.unwrap_or(SIZE.1));
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(plot_error)?;
        let (head, root) = root.split_vertically(if hint.note.is_some() { 72 } else { 52 });
        if let Some(note) = hint.note {
            head.draw(&Text::new(
                note,
                (15, 52),
                ("sans-serif", 13).into_font().color(&RGBColor(150, 40, 40)),
            ))
            .map_err(plot_error)?;
        }
        head.draw(&Text::new(
            title.clone(),
            (15, 8),
            ("sans-serif", 19).into_font().color(&BLACK),
        ))
        .map_err(plot_error)?;
        head.draw(&Text::new(
            subtitle,
            (15, 32),
            ("sans-serif", 13).into_font().color(&RGBColor(70, 70, 70)),
        ))
        .map_err(plot_error)?;
        let root = root;
        let mut builder = ChartBuilder::on(&root);
        builder
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(80);
        let (x, y) = (frame.x.0..frame.x.1, frame.y.0..frame.y.1);
        let legend_at = hint.legend_at;
        let chart_px = match (frame.log_x, frame.log_y) {
            (false, true) => draw(
                builder.build_cartesian_2d(x, y.log_scale()),
                &frame,
                &series,
                legend_at,
            )?,
            (false, false) => draw(builder.build_cartesian_2d(x, y), &frame, &series, legend_at)?,
            (true, true) => draw(
                builder.build_cartesian_2d(x.log_scale(), y.log_scale()),
                &frame,
                &series,
                legend_at,
            )?,
            (true, false) => draw(
                builder.build_cartesian_2d(x.log_scale(), y),
                &frame,
                &series,
                legend_at,
            )?,
        };
        if let Some(inset) = &hint.inset {
            draw_inset(&root, chart_px, inset, &frame, &series)?;
        }
        root.present().map_err(plot_error)?;
    }
    Ok(svg)
}

/// The axes of one panel: ranges, scales, labels and the reference lines
/// that fall within them.
#[derive(Clone)]
struct Frame {
    x: (f64, f64),
    y: (f64, f64),
    log_x: bool,
    log_y: bool,
    x_desc: String,
    y_desc: String,
    lines: Vec<(f64, &'static str)>,
}

impl Frame {
    fn new(table: &Table, hint: &PlotHint, series: &[Series]) -> Result<Frame> {
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

/// A chart of the SVG backend on coordinates `X × Y` (linear or log).
type Chart<'a, 'b, X, Y> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<X, Y>>;

/// The pixels a chart's plotting area covers (abscissa, ordinate).
type PixelBox = (std::ops::Range<i32>, std::ops::Range<i32>);

/// Draws mesh and ticks, reference lines, series with their error bars and
/// the legend, in that order, on a built chart; returns where the plotting
/// area lies.
fn draw<'a, 'b: 'a, X, Y, E>(
    chart: std::result::Result<Chart<'a, 'b, X, Y>, E>,
    frame: &Frame,
    series: &[Series],
    legend_at: LegendAt,
) -> Result<PixelBox>
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
    E: std::fmt::Display,
{
    let mut chart = chart.map_err(plot_error)?;
    draw_mesh(&mut chart, frame)?;
    draw_reference_lines(&mut chart, frame)?;
    for (i, s) in series.iter().enumerate() {
        draw_series(&mut chart, s, style_of(i))?;
    }
    let position = match legend_at {
        LegendAt::UpperRight => SeriesLabelPosition::UpperRight,
        LegendAt::LowerRight => SeriesLabelPosition::LowerRight,
        LegendAt::LowerLeft => SeriesLabelPosition::LowerLeft,
    };
    chart
        .configure_series_labels()
        .position(position)
        .border_style(BLACK)
        .background_style(WHITE.mix(0.85))
        .draw()
        .map_err(plot_error)?;
    Ok(chart.plotting_area().get_pixel_range())
}

/// Draws `inset` in the lower left corner of the plotting area `chart_px`
/// of `root`: a white box with its own linear axes, the curves of `series`
/// clipped to it in their colours and styles, the reference lines of
/// `frame` that fall within it, no legend.
fn draw_inset(
    root: &DrawingArea<SVGBackend<'_>, plotters::coord::Shift>,
    (px, py): PixelBox,
    inset: &Inset,
    frame: &Frame,
    series: &[Series],
) -> Result<()> {
    let y_top = inset_top(inset, series);
    let (root_x, root_y) = root.get_pixel_range();
    let share = |r: &std::ops::Range<i32>| (f64::from(r.end - r.start) * INSET_SHARE) as i32;
    let (w, h) = (share(&px), share(&py));
    let (left, top) = (px.start - root_x.start + 12, py.end - root_y.start - h - 12);
    let area = root.clone().shrink((left, top), (w, h));
    area.fill(&WHITE).map_err(plot_error)?;
    area.draw(&Rectangle::new(
        [(0, 0), (w - 1, h - 1)],
        BLACK.stroke_width(1),
    ))
    .map_err(plot_error)?;
    let mut chart = ChartBuilder::on(&area)
        .margin(8)
        .caption(inset.caption, ("sans-serif", 12))
        .x_label_area_size(22)
        .y_label_area_size(50)
        .build_cartesian_2d(inset.x_range.0..inset.x_range.1, 0.0..y_top)
        .map_err(plot_error)?;
    chart
        .configure_mesh()
        .label_style(("sans-serif", 11))
        .x_labels(4)
        .y_labels(5)
        .y_label_formatter(&|y: &f64| tick(*y))
        .x_label_formatter(&|x: &f64| tick(*x))
        .light_line_style(RGBColor(242, 242, 242))
        .bold_line_style(RGBColor(215, 215, 215))
        .draw()
        .map_err(plot_error)?;
    let zoom = Frame {
        x: inset.x_range,
        y: (0.0, y_top),
        ..frame.clone()
    };
    draw_reference_lines(&mut chart, &zoom)?;
    for (i, s) in series.iter().enumerate() {
        for piece in clip_polyline(&s.points, zoom.x, zoom.y) {
            let piece = Series {
                points: piece,
                errors: None,
                name: s.name.clone(),
                label: s.label.clone(),
                dashed: s.dashed,
            };
            draw_series(&mut chart, &piece, style_of(i))?;
        }
    }
    Ok(())
}

/// The top of the inset's ordinate: 10% above the largest value of its
/// `fit` columns over its abscissa.
fn inset_top(inset: &Inset, series: &[Series]) -> f64 {
    let (x0, x1) = inset.x_range;
    let top = series
        .iter()
        .filter(|s| inset.fit.contains(&s.name.as_str()))
        .flat_map(|s| s.points.iter())
        .filter(|(x, _)| (x0..=x1).contains(x))
        .fold(0.0_f64, |m, (_, y)| m.max(*y));
    if top > 0.0 {
        1.1 * top
    } else {
        1.0
    }
}

/// The parts of the polyline `points` inside the box `x` × `y` (linear
/// axes), each a polyline.
fn clip_polyline(points: &[(f64, f64)], x: (f64, f64), y: (f64, f64)) -> Vec<Vec<(f64, f64)>> {
    let mut pieces: Vec<Vec<(f64, f64)>> = Vec::new();
    for segment in points.windows(2) {
        let Some((p, q)) = clip_segment(segment[0], segment[1], x, y) else {
            continue;
        };
        match pieces.last_mut() {
            Some(last) if last.last() == Some(&p) => last.push(q),
            _ => pieces.push(vec![p, q]),
        }
    }
    pieces
}

/// The part of the segment `a`–`b` inside the box `x` × `y` (Liang and
/// Barsky's parametric clipping), its ends exactly `a` or `b` when inside.
fn clip_segment(
    a: (f64, f64),
    b: (f64, f64),
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
) -> Option<((f64, f64), (f64, f64))> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for (p, q) in [
        (-dx, a.0 - x0),
        (dx, x1 - a.0),
        (-dy, a.1 - y0),
        (dy, y1 - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else if p < 0.0 {
            t0 = t0.max(q / p);
        } else {
            t1 = t1.min(q / p);
        }
    }
    let at = |t: f64| match t {
        0.0 => a,
        1.0 => b,
        _ => (a.0 + t * dx, a.1 + t * dy),
    };
    (t0 <= t1).then(|| (at(t0), at(t1)))
}

/// Axes, grid and tick labels.
fn draw_mesh<X, Y>(chart: &mut Chart<'_, '_, X, Y>, frame: &Frame) -> Result<()>
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
fn draw_reference_lines<X, Y>(chart: &mut Chart<'_, '_, X, Y>, frame: &Frame) -> Result<()>
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

/// The colour of the `i`-th curve, and whether it is drawn dashed: past the
/// palette's eight colours the curves repeat them dashed, so that no two
/// curves of a panel look alike.
fn style_of(i: usize) -> (RGBColor, bool) {
    (PALETTE[i % PALETTE.len()], i >= PALETTE.len())
}

/// One curve in `colour` (dashed on the palette's second round), with its
/// error bars if any.
fn draw_series<X, Y>(
    chart: &mut Chart<'_, '_, X, Y>,
    s: &Series,
    (colour, second_round): (RGBColor, bool),
) -> Result<()>
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    if second_round && !s.dashed {
        chart
            .draw_series(DashedLineSeries::new(
                s.points.iter().copied(),
                7,
                4,
                colour.stroke_width(2),
            ))
            .map_err(plot_error)?
            .label(s.label.as_str())
            .legend(move |(x, y)| {
                // One dash of the line's pattern, against a solid line's 20 px.
                PathElement::new(vec![(x, y), (x + 7, y)], colour.stroke_width(2))
            });
    } else if s.dashed {
        chart
            .draw_series(DashedLineSeries::new(
                s.points.iter().copied(),
                10,
                6,
                colour.stroke_width(3),
            ))
            .map_err(plot_error)?;
        chart
            .draw_series(
                s.points
                    .iter()
                    .step_by((s.points.len() / 12).max(1))
                    .map(|&p| Circle::new(p, 4, colour.stroke_width(2))),
            )
            .map_err(plot_error)?
            .label(format!("{} (dashed, circles)", s.label))
            .legend(move |(x, y)| Circle::new((x + 10, y), 4, colour.stroke_width(2)));
    } else {
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
    }
    if let Some(e) = &s.errors {
        chart
            .draw_series(s.points.iter().zip(e).map(|(&(x, y), &e)| {
                ErrorBar::new_vertical(x, y - e, y, y + e, colour.filled(), 6)
            }))
            .map_err(plot_error)?;
    }
    Ok(())
}

/// A compact tick label: plain for ordinary magnitudes, `1e-5` style beyond.
fn tick(y: f64) -> String {
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

/// A column name in words, with units: `v2_minus_vmono_12p5nm` becomes
/// "V2 - V mono, band 12.5 nm".
pub fn legend_label(name: &str) -> String {
    let (head, qualifier) = split_qualifier(name);
    let head = head.replace('_', " ");
    let words = match head.as_str() {
        "v1 minus vmono" => "V1 - V mono".to_owned(),
        "v2 minus vmono" => "V2 - V mono".to_owned(),
        "v2 calibrated minus vmono" => "V2 calibrated - V mono".to_owned(),
        "bias v1" => "bias of V1 (on V)".to_owned(),
        "bias v2" => "bias of V2 (on V)".to_owned(),
        "scatter v1" => "scatter of V1 (on V)".to_owned(),
        "scatter v2" => "scatter of V2 (on V)".to_owned(),
        "bias v1 dft" => "bias of V1, DFT".to_owned(),
        "bias v2 dft" => "bias of V2, DFT".to_owned(),
        "bias v1 convolution" => "bias of V1, convolution".to_owned(),
        "bias v2 convolution" => "bias of V2, convolution".to_owned(),
        "v2 numerical" => "V2, numerical integration".to_owned(),
        "v2 fresnel" => "V2, Fresnel integrals".to_owned(),
        "dev v2 flat" => "V2, flat band".to_owned(),
        "dev v2sq flat" => "V2 squared, flat band".to_owned(),
        "dev v2 smooth edges" => "V2, band with smooth edges".to_owned(),
        "dev riemann flat" => "V2, flat band, Riemann sum".to_owned(),
        "dev v2 index" => "V2, power-law band, index".to_owned(),
        other => other.to_owned(),
    };
    match qualifier {
        Some(q) if words.ends_with("index") => format!("{words} {q}"),
        Some(q) => format!("{words}, {}", describe_qualifier(&q)),
        None => words,
    }
}

/// Splits a trailing value such as `12p5nm`, `256um`, `1p5rad` or `-2`.
fn split_qualifier(name: &str) -> (String, Option<String>) {
    match name.rsplit_once('_') {
        Some((head, tail))
            if tail
                .chars()
                .next()
                .is_some_and(|c| c.is_ascii_digit() || c == '-') =>
        {
            (head.to_owned(), Some(tail.replace('p', ".")))
        }
        _ => (name.to_owned(), None),
    }
}

fn describe_qualifier(q: &str) -> String {
    let split = q.find(|c: char| c.is_ascii_alphabetic()).unwrap_or(q.len());
    let (value, unit) = q.split_at(split);
    match unit {
        "nm" => format!("bandwidth {value} nm"),
        "um" => format!("scan {value} µm"),
        "rad" => format!("dispersion {value} rad"),
        "" => value.to_owned(),
        u => format!("{value} {u}"),
    }
}

/// The figure's scalar parameters on one line, `name = value`, for the
/// subtitle.
fn parameter_line(parameters: &serde_json::Value) -> String {
    let Some(map) = parameters.as_object() else {
        return String::new();
    };
    let items: Vec<String> = map
        .iter()
        .filter_map(|(k, v)| {
            let v = match v {
                serde_json::Value::Number(n) => n.to_string(),
                serde_json::Value::String(s) if s.len() <= 24 => s.clone(),
                serde_json::Value::Bool(b) => b.to_string(),
                serde_json::Value::Array(a) if a.len() <= 6 && a.iter().all(|x| x.is_number()) => a
                    .iter()
                    .map(|x| x.to_string())
                    .collect::<Vec<_>>()
                    .join("/"),
                _ => return None,
            };
            let units = [
                ("_um", "µm"),
                ("_nm", "nm"),
                ("_mas", "mas"),
                ("_cpas", "cycles/arcsec"),
                ("_hz", "Hz"),
                ("_rad", "rad"),
                ("_m", "m"),
                ("_s", "s"),
            ];
            let (key, unit) = units
                .iter()
                .find_map(|(sfx, u)| k.strip_suffix(sfx).map(|h| (h, *u)))
                .unwrap_or((k.as_str(), ""));
            let key = key.replace('_', " ");
            Some(if unit.is_empty() {
                format!("{key} = {v}")
            } else {
                format!("{key} = {v} {unit}")
            })
        })
        .collect();
    let mut line = String::new();
    for item in items {
        if line.len() + item.len() > 125 {
            line.push_str(", …");
            break;
        }
        if !line.is_empty() {
            line.push_str(", ");
        }
        line.push_str(&item);
    }
    line
}
