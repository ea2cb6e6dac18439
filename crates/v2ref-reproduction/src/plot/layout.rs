//! The panel's layout: its size, the head (title, parameters, note) above
//! the chart, and the inset placed on the chart.

use super::axes::Frame;
use super::chart::{draw, PixelBox};
use super::inset::draw_inset;
use super::labels::parameter_line;
use super::plot_error;
use super::presentation::{hint, LegendAt, PlotHint};
use super::series::{drawn_rows, series_of, Series};
use crate::error::Result;
use crate::table::{Figure, Table};
use plotters::prelude::*;

/// Size of one panel, pixels.
const SIZE: (u32, u32) = (900, 560);

/// A drawing area of the SVG backend, in pixels.
type Area<'a> = DrawingArea<SVGBackend<'a>, plotters::coord::Shift>;

/// The SVG text of one panel of `figure`.
pub fn table_svg(figure: &Figure, table: &Table) -> Result<String> {
    let hint = hint(&table.name);
    let table = &drawn_rows(table)?;
    let series = series_of(table, &hint);
    let frame = Frame::new(table, &hint, &series)?;
    let title = panel_title(figure, table, &hint);
    let subtitle = parameter_line(&figure.parameters);
    let mut svg = String::new();
    {
        let size = (SIZE.0, hint.height_px.unwrap_or(SIZE.1));
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(plot_error)?;
        let (head, root) = root.split_vertically(if hint.note.is_some() { 72 } else { 52 });
        draw_head(&head, &title, &subtitle, hint.note)?;
        let chart_px = draw_chart(&root, &frame, &series, hint.legend_at)?;
        if let Some(inset) = &hint.inset {
            draw_inset(&root, chart_px, inset, &frame, &series)?;
        }
        root.present().map_err(plot_error)?;
    }
    Ok(svg)
}

/// The panel's title: the presentation's, or the figure and panel ids;
/// Fig. 4's panels, which differ by diameter and fringe frequency, say which.
fn panel_title(figure: &Figure, table: &Table, hint: &PlotHint) -> String {
    let mut title = match hint.title {
        Some(t) => t.to_owned(),
        None => format!("{} — {}", figure.id, table.name),
    };
    if let Some(rest) = table.name.strip_prefix("fig4_") {
        if let Some((mas, hz)) = rest.split_once("mas_") {
            let hz = hz.trim_end_matches("hz");
            title.push_str(&format!(", {mas} mas disk, {hz} Hz fringes"));
        }
    }
    title
}

/// The head above the chart: the title, the parameters under it and the
/// note, if any, in red below them.
fn draw_head(head: &Area, title: &str, subtitle: &str, note: Option<&str>) -> Result<()> {
    if let Some(note) = note {
        head.draw(&Text::new(
            note,
            (15, 52),
            ("sans-serif", 13).into_font().color(&RGBColor(150, 40, 40)),
        ))
        .map_err(plot_error)?;
    }
    head.draw(&Text::new(
        title,
        (15, 8),
        ("sans-serif", 19).into_font().color(&BLACK),
    ))
    .map_err(plot_error)?;
    head.draw(&Text::new(
        subtitle,
        (15, 32),
        ("sans-serif", 13).into_font().color(&RGBColor(70, 70, 70)),
    ))
    .map_err(plot_error)
}

/// The chart on `root`, on the scales of `frame` (linear or logarithmic on
/// each axis); returns where its plotting area lies.
fn draw_chart(
    root: &Area,
    frame: &Frame,
    series: &[Series],
    legend_at: LegendAt,
) -> Result<PixelBox> {
    let mut builder = ChartBuilder::on(root);
    builder
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(80);
    let (x, y) = (frame.x.0..frame.x.1, frame.y.0..frame.y.1);
    match (frame.log_x, frame.log_y) {
        (false, true) => draw(
            builder.build_cartesian_2d(x, y.log_scale()),
            frame,
            series,
            legend_at,
        ),
        (false, false) => draw(builder.build_cartesian_2d(x, y), frame, series, legend_at),
        (true, true) => draw(
            builder.build_cartesian_2d(x.log_scale(), y.log_scale()),
            frame,
            series,
            legend_at,
        ),
        (true, false) => draw(
            builder.build_cartesian_2d(x.log_scale(), y),
            frame,
            series,
            legend_at,
        ),
    }
}
