//! Figures 0 to 3 of the paper: the noise-free bias curves.
//!
//! - `fig0`: the V2 normalization factor against OPD stroke
//!   ([`crate::bias::normalization`]);
//! - `fig1`: V1 − V_mono and V2 − V_mono of a 43 mas uniform disk at
//!   2.2 µm for flat bands 12.5 to 400 nm wide ([`crate::bias::bandwidth`]);
//! - `fig2`: V2 − V_mono of the same disk in the 400 nm band under 1, 1.5
//!   and 2 rad of quadratic dispersion, and V2 of a point source against
//!   dispersion, numerical and closed form ([`crate::math::special::fresnel`]);
//! - `fig3`: the finite-scan bias of V1 and V2 for strokes 256 to 2 µm
//!   ([`crate::bias::finite_scan`]), by the DFT path, checked by the convolution
//!   path, and the ABCD case.
//!
//! Each curve is computed point by point in parallel (rayon); the points
//! are independent and collected in order, so the numbers do not depend on
//! the number of threads.

use crate::bias::bandwidth;
use crate::bias::finite_scan::{self, Kernel, Method};
use crate::bias::normalization;
use crate::cases::Effort;
use crate::cases::{fig1_step, fig3_check_step, fig3_step};
use crate::error::Result;
use crate::formalism::estimator::{v2_sq, wide_band};
use crate::formalism::interferogram::Sampling;
use crate::formalism::observation::{Frequency, Observation};
use crate::formalism::phase::SpectralPhase;
use crate::formalism::source::{uniform_disk_visibility, Source};
use crate::formalism::spectrum::{Band, Spectrum};
use crate::math::special::fresnel::point_source_v2_sq;
use crate::table::{Column, Figure, Table};
use rayon::prelude::*;
use serde_json::json;

use crate::cases::{ABCD_DX_UM, DX_UM, STROKES_UM};
use crate::cases::{BANDWIDTHS_NM, DIAMETER_MAS, S_MAX_CPAS, WAVELENGTH_UM};

use crate::cases::{disk, k_band, observe_at, s_grid};
use crate::cases::{DISPERSIONS_RAD, FIG0_EDGE_PER_UM, FIG0_INDICES, FIG0_MAX_SAMPLES};

/// Column-name label of a number: 12.5 → "12p5".
pub(crate) fn label(x: f64) -> String {
    let s = format!("{x}");
    s.replace('.', "p")
}

/// The figures of this area, computed side by side (each is deterministic
/// on its own; the first error in figure order is returned).
pub(super) fn figures(effort: Effort) -> Result<Vec<Figure>> {
    let ((f0, f1), (f2, f3)) = rayon::join(
        || rayon::join(fig0, || fig1(effort)),
        || rayon::join(|| fig2(effort), || fig3(effort)),
    );
    Ok(vec![f0?, f1?, f2?, f3?])
}

/// Fig. 0.
pub fn fig0() -> Result<Figure> {
    let samples: Vec<usize> = (2..=FIG0_MAX_SAMPLES).collect();
    let strokes: Vec<f64> = samples.iter().map(|&n| n as f64 * DX_UM).collect();
    let flat = k_band();
    let mut columns = vec![
        Column::new("stroke", "um"),
        Column::new("samples", ""),
        Column::new("dev_v2_flat", ""),
        Column::new("dev_v2sq_flat", ""),
    ];
    let mut data: Vec<Vec<f64>> =
        vec![strokes.clone(), samples.iter().map(|&n| n as f64).collect()];
    let dev_flat = normalization::deviation_curve(&flat, DX_UM, &samples)?;
    data.push(dev_flat.clone());
    data.push(
        dev_flat
            .iter()
            .map(|d| (1.0 - (1.0 - d) * (1.0 - d)).abs())
            .collect(),
    );
    for idx in FIG0_INDICES {
        let sp = Spectrum::power_law(Band::k(), idx)?;
        columns.push(Column::new(&format!("dev_v2_index_{}", label(idx)), ""));
        data.push(normalization::deviation_curve(&sp, DX_UM, &samples)?);
    }
    let smooth = Spectrum::smooth_top_hat(Band::k(), FIG0_EDGE_PER_UM)?;
    columns.push(Column::new("dev_v2_smooth_edges", ""));
    data.push(normalization::deviation_curve(&smooth, DX_UM, &samples)?);
    columns.push(Column::new("dev_riemann_flat", ""));
    data.push(normalization::riemann_deviation(&flat, DX_UM, &samples)?);
    Ok(Figure {
        id: "fig0".into(),
        caption: "Fig. 0 (fig:figure_0): |V2 normalized - V2 unnormalized| for a 100% visibility against OPD stroke, K band (2.0-2.4 um). dev_v2_* = |1 - u|, u the V2 of a point source from the positive-frequency bins without the normalization factor; dev_v2sq_flat = |1 - u^2| (the squared estimator); dev_riemann_flat = |1 - sum_k W(k dsigma) dsigma| (the factor read as a Riemann sum of the unconvolved W). The paper's G5 III spectrum is not available.".into(),
        monte_carlo: false,
        parameters: json!({
            "band_um": [2.0, 2.4],
            "dx_um": DX_UM,
            "samples": [2, FIG0_MAX_SAMPLES],
            "bins": "positive frequencies k = 1 .. ceil(N/2)-1",
            "spectra": {
                "flat": "S F constant in wavenumber",
                "index": FIG0_INDICES,
                "smooth_edges_per_um": FIG0_EDGE_PER_UM,
            },
            "threshold": 0.002,
        }),
        tables: vec![table("fig0_normalization", columns, data)],
    })
}

/// Builds a table from columns of equal length.
fn table(name: &str, columns: Vec<Column>, data: Vec<Vec<f64>>) -> Table {
    let rows = (0..data.first().map_or(0, Vec::len))
        .map(|i| data.iter().map(|c| c[i]).collect())
        .collect();
    Table {
        name: name.into(),
        columns,
        rows,
    }
}

/// The Fig. 1 bands: flat, centred on [`WAVELENGTH_UM`], each of
/// [`BANDWIDTHS_NM`].
fn fig1_bands() -> Result<Vec<Spectrum>> {
    BANDWIDTHS_NM
        .iter()
        .map(|bw| {
            let width_um = bw * crate::formalism::spectrum::UM_PER_NM;
            Ok(Spectrum::flat(Band::new(WAVELENGTH_UM, width_um)?))
        })
        .collect()
}

/// The two Fig. 1 rows at spatial frequency `s` (cycles/arcsec):
/// (S, |V mono|, V1 − V mono per band) and (S, |V mono|, V2 − V mono per
/// band).
fn fig1_rows_at(bands: &[Spectrum], s: f64) -> Result<[Vec<f64>; 2]> {
    let v_mono = uniform_disk_visibility(DIAMETER_MAS, s).abs();
    let mut rows = [vec![s, v_mono], vec![s, v_mono]];
    for sp in bands {
        let w = bandwidth::curve(sp, &disk(), &SpectralPhase::zero(), &[s])?[0];
        rows[0].push(w.v1 - w.v_mono);
        rows[1].push(w.v2 - w.v_mono);
    }
    Ok(rows)
}

/// Fig. 1.
pub fn fig1(effort: Effort) -> Result<Figure> {
    let grid = s_grid(fig1_step(effort));
    let bands = fig1_bands()?;
    let mut cols1 = vec![Column::new("s", "cycles/arcsec"), Column::new("v_mono", "")];
    let mut cols2 = cols1.clone();
    for bw in BANDWIDTHS_NM {
        cols1.push(Column::new(&format!("v1_minus_vmono_{}nm", label(bw)), ""));
        cols2.push(Column::new(&format!("v2_minus_vmono_{}nm", label(bw)), ""));
    }
    let rows: Vec<[Vec<f64>; 2]> = grid
        .par_iter()
        .map(|&s| fig1_rows_at(&bands, s))
        .collect::<Result<_>>()?;
    let (rows1, rows2): (Vec<_>, Vec<_>) = rows.into_iter().map(|[a, b]| (a, b)).unzip();
    let panel = |name: &str, columns, rows| Table {
        name: name.into(),
        columns,
        rows,
    };
    Ok(Figure {
        id: "fig1".into(),
        caption: "Fig. 1 (fig:figure_1): wide-band V1 and V2 minus the monochromatic visibility |2J1(pi theta S)/(pi theta S)| of a 43 mas uniform disk, flat bands centred on 2.2 um, 12.5 to 400 nm wide, infinite scan, S = B sigma_eff.".into(),
        monte_carlo: false,
        parameters: json!({
            "diameter_mas": DIAMETER_MAS,
            "wavelength_um": WAVELENGTH_UM,
            "bandwidths_nm": BANDWIDTHS_NM,
            "spectrum": "flat in wavenumber",
            "s_step_cpas": fig1_step(effort),
            "s_max_cpas": S_MAX_CPAS,
            "scan": "infinite",
        }),
        tables: vec![panel("fig1_v1", cols1, rows1), panel("fig1_v2", cols2, rows2)],
    })
}

/// A Fig. 1 curve is refined where it departs from the straight line
/// between two points by more than this fraction of the panel's ordinate
/// span (a fraction of a pixel on the drawn panel).
const FIG1_REFINE_TOLERANCE: f64 = 1e-3;
/// Half-width of the window refined around each null, cycles/arcsec: wider
/// than the gap between the nulls of |V mono| and of the widest band's V.
const FIG1_REFINE_HALF_WIDTH_CPAS: f64 = 0.5;
/// Most halvings of one grid step (0.1 / 2^16 ≈ 2e-6 cycles/arcsec).
const FIG1_REFINE_DEPTH: u32 = 16;
/// Below this step (about a pixel of the drawn panel), cycles/arcsec, only
/// the turning points are kept: more points on a steep stretch, rounded to
/// whole pixels by the SVG, would draw it as a staircase.
const FIG1_PIXEL_CPAS: f64 = S_MAX_CPAS / 800.0;

/// The nulls of the disk's monochromatic visibility up to [`S_MAX_CPAS`]:
/// S_k = j_{1,k} / (π θ), θ the diameter in arcsec, cycles/arcsec.
pub fn disk_nulls_cpas() -> Vec<f64> {
    let theta_arcsec = DIAMETER_MAS * crate::formalism::source::ARCSEC_PER_MAS;
    (1..)
        .map(|k| crate::math::special::bessel_j1_zero(k) / (std::f64::consts::PI * theta_arcsec))
        .take_while(|&s| s <= S_MAX_CPAS)
        .collect()
}

/// `panel` (`fig1_v1` or `fig1_v2`, as [`fig1`] makes it) with rows added
/// near each null of the disk, for drawing: there |V mono| and the
/// wide-band V vanish at slightly different S, so the differences turn or
/// change sign within a fraction of the grid step. Each grid step within
/// [`FIG1_REFINE_HALF_WIDTH_CPAS`] of a null is halved until the curves
/// are straight to [`FIG1_REFINE_TOLERANCE`] of the ordinate span. The
/// rows are exact values at the added S; the CSV keeps the regular grid.
pub fn fig1_refined_near_nulls(panel: &Table) -> Result<Table> {
    let estimator = usize::from(panel.name.ends_with("_v2"));
    let bands = fig1_bands()?;
    let curves = |r: &Vec<f64>| r[2..].to_vec();
    let (lo, hi) = panel
        .rows
        .iter()
        .flat_map(curves)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    let refine = Refinement {
        bands: &bands,
        estimator,
        tolerance: FIG1_REFINE_TOLERANCE * (hi - lo),
    };
    let nulls = disk_nulls_cpas();
    let near_null = |a: f64, b: f64| {
        nulls
            .iter()
            .any(|n| b > n - FIG1_REFINE_HALF_WIDTH_CPAS && a < n + FIG1_REFINE_HALF_WIDTH_CPAS)
    };
    let mut rows = panel.rows.clone();
    for step in panel.rows.windows(2) {
        if near_null(step[0][0], step[1][0]) {
            refine.bisect(&step[0], &step[1], FIG1_REFINE_DEPTH, &mut rows)?;
        }
    }
    rows.sort_by(|a, b| a[0].total_cmp(&b[0]));
    Ok(Table {
        rows,
        ..panel.clone()
    })
}

/// Adaptive refinement of one Fig. 1 panel (see [`fig1_refined_near_nulls`]).
struct Refinement<'a> {
    bands: &'a [Spectrum],
    /// 0 for V1, 1 for V2.
    estimator: usize,
    /// Largest departure from a straight segment left unrefined.
    tolerance: f64,
}

impl Refinement<'_> {
    /// Adds to `out` the row at the middle of rows `a` and `b` when some
    /// curve bends between them (on a sub-pixel step, only when it is a
    /// turning point of some curve), and recurses into both halves.
    fn bisect(&self, a: &[f64], b: &[f64], depth: u32, out: &mut Vec<Vec<f64>>) -> Result<()> {
        if depth == 0 {
            return Ok(());
        }
        let [v1, v2] = fig1_rows_at(self.bands, 0.5 * (a[0] + b[0]))?;
        let mid = if self.estimator == 0 { v1 } else { v2 };
        let bent = (2..mid.len()).any(|j| (mid[j] - 0.5 * (a[j] + b[j])).abs() > self.tolerance);
        if !bent {
            // On the straight segment: adds nothing to the drawing.
            return Ok(());
        }
        self.bisect(a, &mid, depth - 1, out)?;
        self.bisect(&mid, b, depth - 1, out)?;
        let turning = (2..mid.len()).any(|j| (mid[j] - a[j]) * (mid[j] - b[j]) > 0.0);
        if turning || b[0] - a[0] > 2.0 * FIG1_PIXEL_CPAS {
            out.push(mid);
        }
        Ok(())
    }
}

/// Fig. 2.
pub fn fig2(effort: Effort) -> Result<Figure> {
    let band = k_band();
    Ok(Figure {
        id: "fig2".into(),
        caption: "Fig. 2 (fig:figure_2): V2 minus the monochromatic visibility of a 43 mas uniform disk in the flat 400 nm band at 2.2 um under quadratic dispersion phi = D (sigma - sigma0)^2 / 2 of 1, 1.5 and 2 rad peak-to-peak (0 rad for reference); calibrated columns divide by V2 of a point source with the same dispersion. Panel fig2_point: V2 of a point source against dispersion, by quadrature and by the Fresnel closed form.".into(),
        monte_carlo: false,
        parameters: json!({
            "diameter_mas": DIAMETER_MAS,
            "band_um": [2.0, 2.4],
            "spectrum": "flat in wavenumber",
            "dispersions_pp_rad": DISPERSIONS_RAD,
            "peak_to_peak": "P = D (delta_sigma / 2)^2 / 2, sigma0 the band centre in wavenumber",
            "s_step_cpas": fig1_step(effort),
            "s_max_cpas": S_MAX_CPAS,
            "scan": "infinite",
        }),
        tables: vec![fig2_disk(&band, effort)?, fig2_point(&band)?],
    })
}

/// Fig. 2, the disk: V2 − V_mono under each dispersion (and 0 rad), then
/// the same calibrated on a point source with the same dispersion.
fn fig2_disk(band: &Spectrum, effort: Effort) -> Result<Table> {
    let grid = s_grid(fig1_step(effort));
    let v_mono: Vec<f64> = grid
        .iter()
        .map(|&s| uniform_disk_visibility(DIAMETER_MAS, s).abs())
        .collect();
    let mut cols = vec![Column::new("s", "cycles/arcsec"), Column::new("v_mono", "")];
    let mut data = vec![grid.clone(), v_mono.clone()];
    let mut cal_cols = Vec::new();
    let mut cal_data = Vec::new();
    for pp in std::iter::once(0.0).chain(DISPERSIONS_RAD) {
        let phase = SpectralPhase::dispersion_peak_to_peak(band, pp)?;
        let point = observe_at(band, Source::Point, 0.0, &phase)?;
        let v2_point = v2_sq(&point).sqrt();
        let v2: Vec<f64> = grid
            .par_iter()
            .map(|&s| observe_at(band, disk(), s, &phase).map(|o| v2_sq(&o).sqrt()))
            .collect::<Result<_>>()?;
        cols.push(Column::new(&format!("v2_minus_vmono_{}rad", label(pp)), ""));
        data.push(v2.iter().zip(&v_mono).map(|(v, m)| v - m).collect());
        if pp > 0.0 {
            cal_cols.push(Column::new(
                &format!("v2_calibrated_minus_vmono_{}rad", label(pp)),
                "",
            ));
            cal_data.push(
                v2.iter()
                    .zip(&v_mono)
                    .map(|(v, m)| v / v2_point - m)
                    .collect(),
            );
        }
    }
    cols.extend(cal_cols);
    data.extend(cal_data);
    Ok(table("fig2_disk", cols, data))
}

/// Fig. 2, the point source: V2 against dispersion, numerical and closed
/// form.
fn fig2_point(band: &Spectrum) -> Result<Table> {
    let pps: Vec<f64> = (0..=60).map(|i| i as f64 * 0.05).collect();
    let numerical: Vec<f64> = pps
        .iter()
        .map(|&pp| {
            let phase = SpectralPhase::dispersion_peak_to_peak(band, pp)?;
            Observation::new(
                band.clone(),
                Source::Point,
                Frequency::BaselineM(0.0),
                phase,
            )
            .map(|o| v2_sq(&o).sqrt())
        })
        .collect::<Result<_>>()?;
    let closed: Vec<f64> = pps
        .iter()
        .map(|&pp| point_source_v2_sq(pp).sqrt())
        .collect();
    let diff: Vec<f64> = numerical.iter().zip(&closed).map(|(a, b)| a - b).collect();
    Ok(table(
        "fig2_point",
        vec![
            Column::new("dispersion_pp", "rad"),
            Column::new("v2_numerical", ""),
            Column::new("v2_fresnel", ""),
            Column::new("difference", ""),
        ],
        vec![pps, numerical, closed, diff],
    ))
}

/// The Fig. 3 scans: (nominal stroke, sampling) at [`DX_UM`].
pub fn fig3_samplings() -> Result<Vec<(f64, Sampling)>> {
    STROKES_UM
        .iter()
        .map(|&st| Sampling::from_stroke(st, DX_UM, false).map(|s| (st, s)))
        .collect()
}

/// Fig. 3.
pub fn fig3(effort: Effort) -> Result<Figure> {
    let scans = fig3_samplings()?;
    let samplings: Vec<Sampling> = scans.iter().map(|s| s.1).collect();
    let grid = s_grid(fig3_step(effort));
    let (v1, v2) = fig3_dft(&scans, &grid)?;
    Ok(Figure {
        id: "fig3".into(),
        caption: "Fig. 3 (fig:figure_3): finite-scan bias sqrt(V^2 finite) - sqrt(V^2 infinite) of V1 (fig3_v1) and V2 (fig3_v2) for a 43 mas uniform disk, flat 400 nm band at 2.2 um, 4 samples per fringe at 2.2 um, strokes 256 to 2 um (nominal; N = round(stroke/dx)). Both estimators sum the positive-frequency bins k = 1..ceil(N/2)-1 and are divided by the same estimator on a point source through the same scan. fig3_v1/fig3_v2: DFT of the synthesized interferogram; fig3_convolution: the same biases from eq:sampled_V (extended visibility convolved with the scan kernel) on a coarser grid; fig3_abcd: 4 samples at 0.5 um (ABCD at 2 um), both paths.".into(),
        monte_carlo: false,
        parameters: json!({
            "diameter_mas": DIAMETER_MAS,
            "band_um": [2.0, 2.4],
            "spectrum": "flat in wavenumber",
            "dx_um": DX_UM,
            "strokes_nominal_um": STROKES_UM,
            "samples": samplings.iter().map(Sampling::samples).collect::<Vec<_>>(),
            "strokes_um": samplings.iter().map(Sampling::stroke_um).collect::<Vec<_>>(),
            "bins": "positive frequencies k = 1 .. ceil(N/2)-1",
            "normalization": "divided by the same estimator on a point source through the same scan",
            "abcd": {"samples": 4, "dx_um": ABCD_DX_UM},
            "s_step_cpas": fig3_step(effort),
            "convolution_s_step_cpas": fig3_check_step(effort),
            "s_max_cpas": S_MAX_CPAS,
        }),
        tables: vec![
            v1,
            v2,
            fig3_convolution(&scans, effort)?,
            fig3_abcd(&grid)?,
        ],
    })
}

/// Fig. 3 by the DFT path: the infinite-scan V1, V2 and the bias of each
/// scan (tables `fig3_v1`, `fig3_v2`).
fn fig3_dft(scans: &[(f64, Sampling)], grid: &[f64]) -> Result<(Table, Table)> {
    let band = k_band();
    let samplings: Vec<Sampling> = scans.iter().map(|s| s.1).collect();
    let inf: Vec<_> = grid
        .par_iter()
        .map(|&s| observe_at(&band, disk(), s, &SpectralPhase::zero()).map(|o| wide_band(&o)))
        .collect::<Result<_>>()?;
    let dft = finite_scan::disk_biases(&k_band(), &disk(), grid, &samplings, Method::Dft)?;
    let mut cols1 = vec![
        Column::new("s", "cycles/arcsec"),
        Column::new("v1_infinite", ""),
    ];
    let mut cols2 = vec![
        Column::new("s", "cycles/arcsec"),
        Column::new("v2_infinite", ""),
    ];
    let mut d1 = vec![grid.to_vec(), inf.iter().map(|w| w.v1).collect()];
    let mut d2 = vec![grid.to_vec(), inf.iter().map(|w| w.v2).collect()];
    for ((st, _), b) in scans.iter().zip(&dft) {
        cols1.push(Column::new(&format!("bias_v1_{}um", label(*st)), ""));
        cols2.push(Column::new(&format!("bias_v2_{}um", label(*st)), ""));
        d1.push(b.iter().map(|x| x.v1).collect());
        d2.push(b.iter().map(|x| x.v2).collect());
    }
    Ok((table("fig3_v1", cols1, d1), table("fig3_v2", cols2, d2)))
}

/// Fig. 3 by the convolution path (eq:sampled_V) on a coarser grid (table
/// `fig3_convolution`).
fn fig3_convolution(scans: &[(f64, Sampling)], effort: Effort) -> Result<Table> {
    let samplings: Vec<Sampling> = scans.iter().map(|s| s.1).collect();
    let check_grid = s_grid(fig3_check_step(effort));
    let conv = finite_scan::disk_biases(
        &k_band(),
        &disk(),
        &check_grid,
        &samplings,
        Method::Convolution(Kernel::Dirichlet),
    )?;
    let mut cols_c = vec![Column::new("s", "cycles/arcsec")];
    let mut d_c = vec![check_grid.clone()];
    for ((st, _), b) in scans.iter().zip(&conv) {
        cols_c.push(Column::new(&format!("bias_v1_{}um", label(*st)), ""));
        cols_c.push(Column::new(&format!("bias_v2_{}um", label(*st)), ""));
        d_c.push(b.iter().map(|x| x.v1).collect());
        d_c.push(b.iter().map(|x| x.v2).collect());
    }
    Ok(table("fig3_convolution", cols_c, d_c))
}

/// Fig. 3, ABCD: 4 samples per fringe at 2 µm, N = 4, both paths (table
/// `fig3_abcd`).
fn fig3_abcd(grid: &[f64]) -> Result<Table> {
    let abcd = Sampling::new(4, ABCD_DX_UM, false)?;
    let a_dft = finite_scan::disk_biases(&k_band(), &disk(), grid, &[abcd], Method::Dft)?.remove(0);
    let a_conv = finite_scan::disk_biases(
        &k_band(),
        &disk(),
        grid,
        &[abcd],
        Method::Convolution(Kernel::Dirichlet),
    )?
    .remove(0);
    Ok(table(
        "fig3_abcd",
        vec![
            Column::new("s", "cycles/arcsec"),
            Column::new("bias_v1_dft", ""),
            Column::new("bias_v2_dft", ""),
            Column::new("bias_v1_convolution", ""),
            Column::new("bias_v2_convolution", ""),
        ],
        vec![
            grid.to_vec(),
            a_dft.iter().map(|b| b.v1).collect(),
            a_dft.iter().map(|b| b.v2).collect(),
            a_conv.iter().map(|b| b.v1).collect(),
            a_conv.iter().map(|b| b.v2).collect(),
        ],
    ))
}
