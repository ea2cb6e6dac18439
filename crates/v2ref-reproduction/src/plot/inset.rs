//! The inset: a zoom on part of the abscissa drawn inside the chart on
//! linear axes, the curves clipped to it.

use super::axes::{draw_reference_lines, tick, Frame};
use super::chart::{draw_series, style_of, PixelBox};
use super::plot_error;
use super::presentation::Inset;
use super::series::Series;
use crate::error::Result;
use plotters::prelude::*;

/// The inset's share of the chart's width and height.
const INSET_SHARE: f64 = 0.45;

/// Draws `inset` in the lower left corner of the plotting area `chart_px`
/// of `root`: a white box with its own linear axes, the curves of `series`
/// clipped to it in their colours and styles, the reference lines of
/// `frame` that fall within it, no legend.
pub(super) fn draw_inset(
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
