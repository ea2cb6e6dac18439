//! How each panel is presented: hidden context columns, ordinate label,
//! title, reference lines (the paper's 0.2% accuracy), legend corner and
//! inset — apart from the data.

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
#[non_exhaustive]
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
        "fig0_normalization" => fig0(&mut h),
        "fig1_v1" | "fig1_v2" => fig1(table, &mut h),
        "fig2_disk" | "fig2_point" => fig2(table, &mut h),
        "fig3_v1" | "fig3_v2" | "fig3_abcd" | "fig3_convolution" => fig3(table, &mut h),
        t if t.starts_with("fig4_") => fig4(&mut h),
        t if t.starts_with("fig5_") => fig5(table, &mut h),
        _ => {}
    }
    h
}

/// Fig. 0: the normalization of V2 against the stroke.
fn fig0(h: &mut PlotHint) {
    h.y_label = Some("|V2 normalized - V2 unnormalized|, V = 1");
    h.title = Some("Fig. 0: effect of normalizing V2 by the mean flux, against scan stroke");
    h.lines = vec![(ACCURACY_0P2, "0.2%")];
    // The Riemann-sum curve runs along the top: the legend goes below.
    h.legend_at = LegendAt::LowerLeft;
    h.log_y_room_below = 1.5;
}

/// Fig. 1: the bandwidth bias of V1 and V2.
fn fig1(table: &str, h: &mut PlotHint) {
    h.note = Some(FIG1_NOTE);
    if table == "fig1_v1" {
        h.y_label = Some("V1 - V mono");
        h.title = Some("Fig. 1: wide-band V1 minus monochromatic V, uniform disk");
    } else {
        h.legend_at = LegendAt::LowerLeft;
        h.y_label = Some("V2 - V mono");
        h.title = Some("Fig. 1: wide-band V2 minus monochromatic V, uniform disk");
    }
}

/// Fig. 2: V2 under dispersion, disk and point source.
fn fig2(table: &str, h: &mut PlotHint) {
    if table == "fig2_disk" {
        h.y_label = Some("V2 - V mono");
        h.title = Some("Fig. 2: V2 minus monochromatic V under dispersion, uniform disk");
        h.legend_at = LegendAt::LowerRight;
    } else {
        h.y_label = Some("V2 of a point source");
        h.title = Some("Fig. 2: V2 of a point source against dispersion (numerical and Fresnel)");
        h.dashed = vec!["v2_fresnel"];
    }
}

/// Fig. 3: the finite-scan bias.
fn fig3(table: &str, h: &mut PlotHint) {
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

/// Fig. 4: the piston bias of V1 and V2, the scatter as error bars.
fn fig4(h: &mut PlotHint) {
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

/// Fig. 5: the piston bias and scatter against fringe frequency, with a
/// zoom on the high frequencies.
fn fig5(table: &str, h: &mut PlotHint) {
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
