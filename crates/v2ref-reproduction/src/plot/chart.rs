//! A built chart drawn: mesh, reference lines, curves in the palette's
//! colours with their error bars, and the legend.

use super::axes::{draw_mesh, draw_reference_lines, Chart, Frame};
use super::plot_error;
use super::presentation::LegendAt;
use super::series::Series;
use crate::error::Result;
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

/// The pixels a chart's plotting area covers (abscissa, ordinate).
pub(super) type PixelBox = (std::ops::Range<i32>, std::ops::Range<i32>);

/// Draws mesh and ticks, reference lines, series with their error bars and
/// the legend, in that order, on a built chart; returns where the plotting
/// area lies.
pub(super) fn draw<'a, 'b: 'a, X, Y, E>(
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

/// The colour of the `i`-th curve, and whether it is drawn dashed: past the
/// palette's eight colours the curves repeat them dashed, so that no two
/// curves of a panel look alike.
pub(super) fn style_of(i: usize) -> (RGBColor, bool) {
    (PALETTE[i % PALETTE.len()], i >= PALETTE.len())
}

/// One curve in `colour` (dashed on the palette's second round), with its
/// error bars if any.
pub(super) fn draw_series<X, Y>(
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
