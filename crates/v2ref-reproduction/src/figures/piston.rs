//! Figures 4 and 5 of the paper: bias and scatter of V1 and V2 caused by
//! differential piston (Section "Effect of differential piston").
//!
//! - Fig. 4: uniform disks of 43 and 10 mas, fringe frequencies 300 and
//!   1000 Hz, against spatial frequency S, the baseline following S
//!   (B = S/σ_eff, so the piston grows with S); 1000 scans per point.
//! - Fig. 5: unresolved source on 18 m (40 cycles/arcsec), fringe frequency
//!   50 to 2000 Hz (log-spaced), 10000 scans per point, sampled (left) and
//!   integrating (right) detectors on the same piston sequences.
//!
//! Common parameters: seeing 1 arcsec at 2.2 µm (r0 = 45.4 cm), wind
//! 10 m/s along the baseline, infinite outer scale, 45 cm apertures, K band
//! 2.0–2.4 µm flat, 128 samples of 0.5 µm (64 µm), packet centred on the
//! scan-mean piston. Every bias and scatter comes with its standard error;
//! the seed of each point is fixed, so the figures are reproducible bit for
//! bit whatever the thread count.

use crate::cases::{
    fig4_size, fig5_frequencies, fig5_size, paper_turbulence, Effort, APERTURE_M, FIG5_BASELINE_M,
    FIGURE_SEED, SEEING_ARCSEC, WIND_MPS,
};
use crate::error::Result;
use crate::formalism::estimator::{BinWindow, BIN_WINDOWS};
use crate::formalism::observation::{Frequency, Observation};
use crate::formalism::phase::SpectralPhase;
use crate::formalism::source::Source;
use crate::formalism::spectrum::{Band, Spectrum};
use crate::montecarlo::{derive_seed, Summary};
use crate::piston::spectrum::PistonPsdModel;
use crate::piston::spectrum::{PistonSpectrum, TransverseTable};
use crate::piston::turbulence::Turbulence;
use crate::piston::{
    simulate_piston, sweep, Detector, PistonRun, RunSize, ScanSetup, DEFAULT_SUB_SAMPLES,
};
use crate::table::{Column, Figure, Table};
use std::sync::{Arc, Mutex};

fn estimate_columns(prefix: &str, cols: &mut Vec<Column>) {
    for (name, unit) in [
        ("bias", ""),
        ("bias_stderr", ""),
        ("scatter", ""),
        ("scatter_stderr", ""),
    ] {
        let (what, rest) = name.split_once('_').unwrap_or((name, ""));
        let full = if rest.is_empty() {
            format!("{what}_{prefix}")
        } else {
            format!("{what}_{prefix}_{rest}")
        };
        cols.push(Column::new(&full, unit));
    }
}

/// bias = mean, bias_stderr = stderr_mean, scatter = std, scatter_stderr =
/// stderr_std.
fn estimate_cells(e: &Summary, row: &mut Vec<f64>) {
    row.extend([e.mean, e.stderr_mean, e.std, e.stderr_std]);
}

/// A process-wide cache: the claims and the figure registry share one run.
type Cache = Mutex<Vec<((&'static str, bool), Figure)>>;
static CACHE: Cache = Mutex::new(Vec::new());

fn cached(id: &'static str, effort: Effort, make: impl Fn() -> Result<Figure>) -> Result<Figure> {
    let key = (id, effort == Effort::Full);
    if let Ok(c) = CACHE.lock() {
        if let Some((_, f)) = c.iter().find(|(k, _)| *k == key) {
            return Ok(f.clone());
        }
    }
    let fig = make()?;
    if let Ok(mut c) = CACHE.lock() {
        c.push((key, fig.clone()));
    }
    Ok(fig)
}

fn k_band_obs(source: Source, frequency: Frequency) -> Result<Observation> {
    Observation::new(
        Spectrum::flat(Band::k()),
        source,
        frequency,
        SpectralPhase::zero(),
    )
}

/// Fig. 4 at `effort`.
pub fn fig4(effort: Effort) -> Result<Figure> {
    cached("fig4", effort, || make_fig4(effort))
}

/// Fig. 4's lower fringe frequency, Hz.
pub const FIG4_LOW_HZ: f64 = 300.0;
/// Fig. 4's higher fringe frequency, Hz.
pub const FIG4_HIGH_HZ: f64 = 1000.0;

/// The Fig. 4 cases: (disk diameter, mas; fringe frequency, Hz).
const FIG4_CASES: [(f64, f64); 4] = [
    (43.0, FIG4_LOW_HZ),
    (43.0, FIG4_HIGH_HZ),
    (10.0, FIG4_LOW_HZ),
    (10.0, FIG4_HIGH_HZ),
];

fn fig4_columns() -> Vec<Column> {
    let mut columns = vec![
        Column::new("spatial_freq_cpas", "cycles/arcsec"),
        Column::new("baseline_m", "m"),
        Column::new("piston_rms_um", "um"),
        Column::new("v1_no_piston", ""),
        Column::new("v2_no_piston", ""),
    ];
    estimate_columns("v1", &mut columns);
    estimate_columns("v2", &mut columns);
    columns
}

/// The seed of the Fig. 4 point (disk, fringe frequency, spatial frequency):
/// keyed by what it computes, not by its position in the figure.
pub fn fig4_seed(seed: u64, diameter_mas: f64, fringe_hz: f64, s_cpas: f64) -> u64 {
    derive_seed(seed, "fig4", &[diameter_mas, fringe_hz, s_cpas])
}

/// One Fig. 4 row: the disk of `diameter_mas` at spatial frequency `s`
/// (the baseline follows it), sampled detector, positive bins.
fn fig4_row(
    table: &Arc<TransverseTable>,
    (diameter_mas, fringe_hz): (f64, f64),
    s: f64,
    scans: usize,
) -> Result<Vec<f64>> {
    let obs = k_band_obs(
        Source::uniform_disk(diameter_mas)?,
        Frequency::SpatialFreqCpas(s),
    )?;
    let spectrum = PistonSpectrum::from_table(table.clone(), obs.baseline_m)?;
    let size = RunSize {
        scans,
        seed: fig4_seed(FIGURE_SEED, diameter_mas, fringe_hz, s),
        threads: 0,
    };
    let setup = ScanSetup::paper(fringe_hz);
    let run = &simulate_piston(&obs, &spectrum, &setup, &[Detector::Sampled], &size, None)?[0];
    let w = run.window(BinWindow::Positive);
    let mut row = vec![
        s,
        obs.baseline_m,
        spectrum.rms_um(),
        w.v1_no_piston,
        w.v2_no_piston,
    ];
    estimate_cells(&w.v1, &mut row);
    estimate_cells(&w.v2, &mut row);
    Ok(row)
}

/// One Fig. 4 panel: S from 0 to 80 cycles/arcsec by `step`.
fn fig4_table(
    table: &Arc<TransverseTable>,
    case: (f64, f64),
    step: f64,
    scans: usize,
) -> Result<Table> {
    let points = (80.0 / step).round() as usize + 1;
    let rows = (0..points)
        .map(|p| fig4_row(table, case, p as f64 * step, scans))
        .collect::<Result<Vec<_>>>()?;
    Ok(Table {
        name: format!("fig4_{}mas_{}hz", case.0 as u32, case.1 as u32),
        columns: fig4_columns(),
        rows,
    })
}

fn make_fig4(effort: Effort) -> Result<Figure> {
    let (step, scans) = fig4_size(effort);
    let table = Arc::new(TransverseTable::new(paper_turbulence(), APERTURE_M)?);
    let tables = FIG4_CASES
        .iter()
        .map(|&case| fig4_table(&table, case, step, scans))
        .collect::<Result<Vec<_>>>()?;
    fig4_figure(step, scans, tables)
}

fn fig4_figure(step: f64, scans: usize, tables: Vec<Table>) -> Result<Figure> {
    Ok(Figure {
        id: "fig4".into(),
        caption: "Fig. 4: bias (mean of V with piston minus V without) and scatter (standard deviation over scans) of V1 and V2 for 43 and 10 mas uniform disks at 300 and 1000 Hz fringe frequency, against spatial frequency; the baseline follows the spatial frequency so the piston grows with it. Positive-frequency bins.".into(),
        monte_carlo: true,
        parameters: with_paper_setup(serde_json::json!({
            "detector": "sampled",
            "window": "positive",
            "scans_per_point": scans,
            "spatial_freq_step_cpas": step,
        })),
        tables,
    })
}

/// The parameters both piston figures share (the paper's turbulence, band,
/// apertures, scans and seed), added to a figure's own.
fn with_paper_setup(mut own: serde_json::Value) -> serde_json::Value {
    let common = serde_json::json!({
            "seeing_arcsec": SEEING_ARCSEC,
            "wavelength_um": 2.2,
            "bandwidth_um": 0.4,
            "wind_mps": WIND_MPS,
            "wind_direction": "along the baseline",
            "wind_angle_deg": 0.0,
            "piston_psd": PistonPsdModel::TwoAperture.name(),
            "outer_scale_m": null,
            "aperture_m": APERTURE_M,
            "samples": 128,
            "dx_um": 0.5,
            "stroke_um": 64.0,
            "piston_reference": "mean",
            "seed": FIGURE_SEED,
    });
    if let (Some(own), serde_json::Value::Object(common)) = (own.as_object_mut(), common) {
        own.extend(common);
    }
    own
}

/// Fig. 5 at `effort`.
pub fn fig5(effort: Effort) -> Result<Figure> {
    cached("fig5", effort, || make_fig5(effort))
}

/// The Fig. 5 runs (sampled, integrating) at each frequency of `freqs`, on
/// 18 m for an unresolved source with turbulence `turb`, through
/// [`crate::piston::sweep`]: the run at f has seed
/// [`crate::piston::sweep_seed`]`(seed, f)`, whatever the other frequencies.
/// The piston runs behind Fig. 5 (uncached): per frequency of `freqs`, the
/// sampled and the integrating detector on the same sequence of `scans`
/// scans, on the current rayon pool (`examples/piston_scaling.rs` times it).
pub fn fig5_runs(
    turb: Turbulence,
    freqs: &[f64],
    scans: usize,
    seed: u64,
) -> Result<Vec<(PistonRun, PistonRun)>> {
    let obs = k_band_obs(Source::Point, Frequency::BaselineM(FIG5_BASELINE_M))?;
    let spectrum = PistonSpectrum::new(turb, APERTURE_M, FIG5_BASELINE_M)?;
    let detectors = [
        Detector::Sampled,
        Detector::Integrating {
            sub_samples: DEFAULT_SUB_SAMPLES,
        },
    ];
    let size = RunSize {
        scans,
        seed,
        threads: 0,
    };
    let template = ScanSetup::paper(freqs.first().copied().unwrap_or(1.0));
    let runs = sweep(&obs, &spectrum, freqs, &template, &detectors, &size, None)?;
    Ok(runs
        .into_iter()
        .map(|mut r| {
            let integ = r.pop().expect("two detectors");
            let samp = r.pop().expect("two detectors");
            (samp, integ)
        })
        .collect())
}

fn fig5_columns() -> Vec<Column> {
    let mut columns = vec![
        Column::new("fringe_hz", "Hz"),
        Column::new("scan_time_s", "s"),
        Column::new("residual_rms_um", "um"),
    ];
    for w in BIN_WINDOWS {
        let suffix = match w {
            BinWindow::Positive => String::new(),
            other => format!("_{}", other.name()),
        };
        estimate_columns(&format!("v1{suffix}"), &mut columns);
        estimate_columns(&format!("v2{suffix}"), &mut columns);
    }
    columns
}

/// One Fig. 5 panel: a row per frequency of one detector's runs.
pub(crate) fn fig5_table<'a>(name: &str, runs: impl Iterator<Item = &'a PistonRun>) -> Table {
    let rows = runs
        .map(|r| {
            let mut row = vec![r.fringe_hz, r.scan_time_s, r.residual_rms_um];
            for w in BIN_WINDOWS {
                let wr = r.window(w);
                estimate_cells(&wr.v1, &mut row);
                estimate_cells(&wr.v2, &mut row);
            }
            row
        })
        .collect();
    Table {
        name: name.into(),
        columns: fig5_columns(),
        rows,
    }
}

fn make_fig5(effort: Effort) -> Result<Figure> {
    let (count, scans) = fig5_size(effort);
    let freqs = fig5_frequencies(count);
    let runs = fig5_runs(paper_turbulence(), &freqs, scans, FIGURE_SEED)?;
    let tables = vec![
        fig5_table("fig5_sampled", runs.iter().map(|p| &p.0)),
        fig5_table("fig5_integrating", runs.iter().map(|p| &p.1)),
    ];
    fig5_figure(count, scans, tables)
}

fn fig5_figure(count: usize, scans: usize, tables: Vec<Table>) -> Result<Figure> {
    Ok(Figure {
        id: "fig5".into(),
        caption: "Fig. 5: bias and scatter of V1 and V2 from differential piston against fringe frequency, unresolved source, 18 m baseline; sampled detector (left, fig5_sampled) and integrating detector (right, fig5_integrating) on the same piston sequences. Unsuffixed columns sum the positive-frequency bins; _band the bins inside the band; _all every bin.".into(),
        monte_carlo: true,
        parameters: with_paper_setup(serde_json::json!({
            "baseline_m": FIG5_BASELINE_M,
            "source": "point",
            "integrating_sub_samples": DEFAULT_SUB_SAMPLES,
            "scans_per_point": scans,
            "frequencies": count,
        })),
        tables,
    })
}

/// The figures this area computes.
pub(super) fn figures(effort: Effort) -> Result<Vec<Figure>> {
    let (f4, f5) = rayon::join(|| fig4(effort), || fig5(effort));
    Ok(vec![f4?, f5?])
}
