//! The planner's figure: the σ(V²) each estimator reaches against fringe
//! frequency (best stroke at each), in the plan's time, with the target;
//! its numbers are the planner's ([`v2ref_commands::plan::figure`]), only drawn here.
//! The promise is drawn as lines through filled points; settings not solved
//! for consecutive scans as open circles at the other frequencies, with
//! their own legend line.

use plotters::coord::combinators::WithKeyPoints;
use plotters::prelude::*;
use std::ops::Range;
use std::path::Path;
use v2ref_commands::plan::figure::{figure_time_s, sigma_curve, Drawn};
use v2ref_commands::plan::{Estimator, Plan, PlanInputs};
use v2ref_core::{Error, Result};

fn fail(path: &Path, e: impl std::fmt::Display) -> Error {
    Error::Output {
        path: path.display().to_string(),
        reason: e.to_string(),
    }
}

fn nothing_to_plot(path: &Path, why: &str) -> Error {
    Error::Invalid {
        param: "svg",
        reason: format!("{}: nothing to plot: {why}", path.display()),
    }
}

/// Writes the figure to `path` (SVG).
pub fn write(path: &Path, plan: &Plan, inputs: &PlanInputs) -> Result<()> {
    // The planner's own numbers (upper ends of the piston intervals).
    let time_s = figure_time_s(plan, inputs);
    let curve = |e, drawn| sigma_curve(plan, inputs, (e, drawn), time_s);
    let v1 = curve(Estimator::V1, Drawn::Promise);
    let v2 = curve(Estimator::V2, Drawn::Promise);
    // The open circles where the estimator has no promise at that
    // frequency (elsewhere they are other strokes, slower by the per-scan
    // estimate, and would only crowd the line).
    let apart = |e, promise: &[(f64, f64)]| {
        let mut points = curve(e, Drawn::IndependentScans);
        points.retain(|(f, _)| promise.iter().all(|(g, _)| g != f));
        points
    };
    let v1_independent = apart(Estimator::V1, &v1);
    let v2_independent = apart(Estimator::V2, &v2);
    let all: Vec<f64> = [&v1, &v2, &v1_independent, &v2_independent]
        .into_iter()
        .flatten()
        .map(|p| p.1)
        .collect();
    let target = inputs.target.sigma_v2();
    let lo = all
        .iter()
        .copied()
        .chain(target)
        .fold(f64::INFINITY, f64::min)
        / 2.0;
    let hi = all.iter().copied().chain(target).fold(0.0, f64::max) * 2.0;
    let (f0, f1) = (
        inputs
            .fringe_hz
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min),
        inputs.fringe_hz.iter().copied().fold(0.0, f64::max),
    );
    // Nothing to plot is a property of the plan asked for, not of the
    // file: bad input (status 2), not an output that cannot be written.
    if all.is_empty() || !(lo > 0.0 && hi > lo) {
        return Err(nothing_to_plot(path, "no grid point reaches any accuracy"));
    }
    if f1 <= f0 {
        return Err(nothing_to_plot(
            path,
            "one fringe frequency; the figure draws σ(V²) against two or more (--fringe-hz)",
        ));
    }
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (900, 560)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| fail(path, e))?;
        let title = format!(
            "σ(V²) reached in {time_s:.1} s against fringe frequency (best stroke at each)"
        );
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 20))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(
                log_axis(f0 / 1.2..f1 * 1.2, frequency_label),
                log_axis(lo..hi, tick_label),
            )
            .map_err(|e| fail(path, e))?;
        chart
            .configure_mesh()
            .x_desc("fringe frequency [Hz]")
            .x_label_formatter(&|f| frequency_label(*f))
            .y_desc("σ(V²) of the averaged measurement")
            .y_label_formatter(&|v| tick_label(*v))
            .light_line_style(WHITE)
            .draw()
            .map_err(|e| fail(path, e))?;
        let blue = RGBColor(0, 114, 178);
        let orange = RGBColor(213, 94, 0);
        for (points, colour, label) in [
            (&v1, blue, "V1² (sum of |B_k|²)"),
            (&v2, orange, "V2² (|Σ B_k|²)"),
        ] {
            chart
                .draw_series(LineSeries::new(
                    points.iter().copied(),
                    colour.stroke_width(2),
                ))
                .map_err(|e| fail(path, e))?
                .label(label)
                .legend(move |(x, y)| {
                    PathElement::new([(x, y), (x + 20, y)], colour.stroke_width(2))
                });
            chart
                .draw_series(points.iter().map(|&p| Circle::new(p, 3, colour.filled())))
                .map_err(|e| fail(path, e))?;
        }
        // Not promised: open circles, one legend line for both estimators.
        for (points, colour, labelled) in [
            (&v1_independent, blue, true),
            (&v2_independent, orange, false),
        ] {
            let series = chart
                .draw_series(
                    points
                        .iter()
                        .map(|&p| Circle::new(p, 4, colour.stroke_width(1))),
                )
                .map_err(|e| fail(path, e))?;
            if labelled && !(v1_independent.is_empty() && v2_independent.is_empty()) {
                series
                    .label("open: not solved for consecutive scans (σ_scan/√n, no promise)")
                    .legend(|(x, y)| Circle::new((x + 10, y), 4, BLACK.stroke_width(1)));
            }
        }
        if let Some(t) = target {
            chart
                .draw_series(LineSeries::new(
                    [(f0 / 1.2, t), (f1 * 1.2, t)],
                    BLACK.stroke_width(1),
                ))
                .map_err(|e| fail(path, e))?
                .label(format!("target σ(V²) = {t:e}"))
                .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], BLACK));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(|e| fail(path, e))?;
        root.present().map_err(|e| fail(path, e))?;
    }
    v2ref_files::atomic::write_text_atomic(path, &svg)
}

/// Labels drawn on an axis at most: plotters' default for a mesh.
const MESH_LABELS: usize = 11;

/// A log axis over `range` with plotters' ticks, each label once: plotters
/// 0.3.7, when it ticks 1 to 9 in a decade, gives the next decade twice
/// (as its ninth tick and as the decade), and its label was drawn over
/// itself ("1e-2" twice). No light lines (the mesh drew them white).
fn log_axis(range: Range<f64>, label: fn(f64) -> String) -> WithKeyPoints<LogCoord<f64>> {
    let axis: LogCoord<f64> = range.log_scale().into();
    let mut ticks = axis.key_points(MESH_LABELS);
    ticks.dedup_by_key(|v| label(*v));
    axis.with_key_points(ticks)
}

/// A fringe frequency's tick, Hz.
fn frequency_label(f: f64) -> String {
    format!("{f:.0}")
}

/// A log-axis tick at the precision it carries: three significant figures
/// at most, trailing zeros dropped (`9e-3`, not `0.009000000000000001`).
fn tick_label(v: f64) -> String {
    let s = format!("{v:.2e}");
    match s.split_once('e') {
        Some((mantissa, exp)) => {
            let m = mantissa.trim_end_matches('0').trim_end_matches('.');
            format!("{m}e{exp}")
        }
        None => s,
    }
}
