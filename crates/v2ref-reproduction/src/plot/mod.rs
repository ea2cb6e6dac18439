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
//!
//! The files, one concern each: `layout.rs` assembles a panel (size, title,
//! parameters, note, chart area) from the presentation of `presentation.rs`,
//! the curves of `series.rs` and the axes of `axes.rs` (ranges, labels,
//! ticks, reference lines); `chart.rs` draws the curves and the legend,
//! `inset.rs` the zoom, `labels.rs` turns column names and parameters into
//! words.

mod axes;
mod chart;
mod inset;
mod labels;
mod layout;
mod presentation;
mod series;

pub use labels::legend_label;
pub use layout::table_svg;
pub use presentation::{hint, Inset, LegendAt, PlotHint};

use crate::error::Error;

/// A plotters failure as the library's output error.
fn plot_error(e: impl std::fmt::Display) -> Error {
    Error::Output {
        path: "plot".into(),
        reason: e.to_string(),
    }
}
