//! Why the Fig. 5 thresholds differ from the paper's: the four thresholds
//! recomputed for every combination of the choices the paper leaves open —
//! the piston spectrum model ([`PistonPsdModel`]), where the packet sits in
//! each scan ([`PistonReference`]: centre, mean), the window of Fourier bins
//! ([`BinWindow`]: positive, band, all) and the reading of "64 µm at 4
//! samples per fringe" (128 samples of 0.5 µm, four per 2.0 µm fringe, or
//! 116 of 0.55 µm, four per 2.2 µm fringe).
//!
//! Each combination is a Fig. 5 sweep (unresolved source, 18 m, sampled
//! detector, log-spaced 50–2000 Hz) with the figure's seed, so that every
//! combination sees the same random numbers where the sequences have the
//! same length; the bin windows share one run.
//!
//! Each threshold carries its Monte Carlo interval: for the three level
//! crossings that of the claims (the frequencies where |bias| is within
//! `tolerance::SIGNIFICANCE_SIGMAS` (3) standard
//! errors of the level, plus half a grid step each side); for "V1
//! unbiased from", from the last frequency where |bias V1| is significant
//! to the threshold itself (the grid step that brackets it).

use super::{column, locate, unbiased_from};
use crate::cases::{
    fig5_frequencies, paper_turbulence, Effort, APERTURE_M, FIG5_BASELINE_M, FIGURE_SEED,
};
use crate::error::Result;
use crate::figures::piston::fig5_table;
use crate::formalism::estimator::{BinWindow, BIN_WINDOWS};
use crate::formalism::observation::{Frequency, Observation};
use crate::formalism::phase::SpectralPhase;
use crate::formalism::source::Source;
use crate::formalism::spectrum::{Band, Spectrum};
use crate::piston::spectrum::{PistonPsdModel, PistonSpectrum};
use crate::piston::{sweep, Detector, PistonReference, RunSize, ScanSetup};
use crate::table::Table;
use crate::tolerance::SIGNIFICANCE_SIGMAS;
use serde::Serialize;
use std::sync::Mutex;

/// The paper's thresholds, Hz: V1 biased by > 1 % below, V2 biased by
/// > 1 % below, V1 unbiased from, V2 below 1e-5 from.
pub const PAPER_THRESHOLDS_HZ: [f64; 4] = [100.0, 300.0, 300.0, 800.0];

/// The level of |bias| under which a visibility counts as biased (V1 and
/// V2 "biased by more than 1 %").
pub const BIASED_LEVEL: f64 = 0.01;
/// The level under which the paper calls V2 unbiased ("below 1e-5").
pub const V2_UNBIASED_LEVEL: f64 = 1e-5;

/// The names of the four thresholds, in [`PAPER_THRESHOLDS_HZ`] order.
pub const THRESHOLD_NAMES: [&str; 4] = [
    "v1_biased_1pct_below_hz",
    "v2_biased_1pct_below_hz",
    "v1_unbiased_from_hz",
    "v2_below_1e-5_from_hz",
];

/// The two readings of a 64 µm stroke at 4 samples per fringe: (N, δx µm).
pub const SAMPLINGS: [(usize, f64); 2] = [(128, 0.5), (116, 0.55)];

/// One combination of choices and its four thresholds.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SensitivityRow {
    /// The spectrum model.
    pub psd: PistonPsdModel,
    /// Where the packet sits.
    pub reference: PistonReference,
    /// The bins summed.
    pub window: BinWindow,
    /// N.
    pub samples: usize,
    /// δx, µm.
    pub dx_um: f64,
    /// The thresholds, Hz, in [`THRESHOLD_NAMES`] order (the lowest or
    /// highest frequency simulated when the crossing is outside the range;
    /// NaN for "V1 unbiased from" when V1 is still biased at the highest).
    pub thresholds_hz: [f64; 4],
    /// Their intervals (lo, hi), Hz (module documentation; NaN where the
    /// threshold is).
    pub intervals_hz: [(f64, f64); 4],
}

impl SensitivityRow {
    /// Whether the paper's threshold `i` lies inside the interval.
    pub fn paper_inside(&self, i: usize) -> bool {
        let (lo, hi) = self.intervals_hz[i];
        (lo..=hi).contains(&PAPER_THRESHOLDS_HZ[i])
    }

    /// How far each threshold is from the paper's, as |ln(computed/paper)|.
    pub fn log_distance(&self) -> [f64; 4] {
        let mut d = [0.0; 4];
        for (i, x) in d.iter_mut().enumerate() {
            *x = (self.thresholds_hz[i] / PAPER_THRESHOLDS_HZ[i]).ln().abs();
        }
        d
    }

    /// The combination in words.
    pub fn label(&self) -> String {
        format!(
            "{} spectrum, {} reference, {} bins, {} x {} um",
            self.psd.name(),
            self.reference.name(),
            self.window.name(),
            self.samples,
            self.dx_um
        )
    }
}

/// The sensitivity table: every combination, and the grid it used.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Sensitivity {
    /// Frequencies of each sweep, Hz.
    pub frequencies: Vec<f64>,
    /// Scans per frequency.
    pub scans: usize,
    /// One row per combination.
    pub rows: Vec<SensitivityRow>,
}

/// Sizes: (frequencies, scans per frequency).
pub fn sensitivity_size(effort: Effort) -> (usize, usize) {
    match effort {
        Effort::Full => (17, 10_000),
        Effort::Quick => (9, 300),
    }
}

static CACHE: Mutex<Vec<(bool, Sensitivity)>> = Mutex::new(Vec::new());

/// The sensitivity table at `effort` (computed once per process).
pub fn fig5_sensitivity(effort: Effort) -> Result<Sensitivity> {
    let key = effort == Effort::Full;
    if let Some((_, s)) = CACHE.lock().ok().and_then(|c| {
        c.iter()
            .find(|(k, _)| *k == key)
            .map(|(k, s)| (*k, s.clone()))
    }) {
        return Ok(s);
    }
    let s = compute(effort)?;
    if let Ok(mut c) = CACHE.lock() {
        c.push((key, s.clone()));
    }
    Ok(s)
}

fn compute(effort: Effort) -> Result<Sensitivity> {
    let (count, scans) = sensitivity_size(effort);
    let frequencies = fig5_frequencies(count);
    let base = PistonSpectrum::new(paper_turbulence(), APERTURE_M, FIG5_BASELINE_M)?;
    let mut rows = Vec::new();
    for psd in [PistonPsdModel::TwoAperture, PistonPsdModel::ThreeSlope] {
        let spectrum = base.with_model(psd)?;
        for reference in [PistonReference::Centre, PistonReference::Mean] {
            for (samples, dx_um) in SAMPLINGS {
                let setup = ScanSetup {
                    samples,
                    dx_um,
                    wavelength_um: 2.2,
                    fringe_hz: frequencies[0],
                    reference,
                };
                let table = sampled_sweep(&spectrum, &frequencies, &setup, scans)?;
                for window in BIN_WINDOWS {
                    let (thresholds_hz, intervals_hz) = thresholds(&table, window)?;
                    rows.push(SensitivityRow {
                        psd,
                        reference,
                        window,
                        samples,
                        dx_um,
                        thresholds_hz,
                        intervals_hz,
                    });
                }
            }
        }
    }
    Ok(Sensitivity {
        frequencies,
        scans,
        rows,
    })
}

/// The Fig. 5 sweep of the sampled detector for one combination, as a
/// Fig. 5 table.
fn sampled_sweep(
    spectrum: &PistonSpectrum,
    frequencies: &[f64],
    setup: &ScanSetup,
    scans: usize,
) -> Result<Table> {
    let obs = Observation::new(
        Spectrum::flat(Band::k()),
        Source::Point,
        Frequency::BaselineM(FIG5_BASELINE_M),
        SpectralPhase::zero(),
    )?;
    let size = RunSize {
        scans,
        seed: FIGURE_SEED,
        threads: 0,
    };
    let runs = sweep(
        &obs,
        spectrum,
        frequencies,
        setup,
        &[Detector::Sampled],
        &size,
        None,
    )?;
    Ok(fig5_table("sensitivity", runs.iter().map(|r| &r[0])))
}

/// Four thresholds, Hz, and their intervals (lo, hi).
type Thresholds = ([f64; 4], [(f64, f64); 4]);

/// The four thresholds of one window, read as the claims read them, and
/// their intervals.
fn thresholds(table: &Table, window: BinWindow) -> Result<Thresholds> {
    let suffix = match window {
        BinWindow::Positive => String::new(),
        other => format!("_{}", other.name()),
    };
    let v1 = format!("bias_v1{suffix}");
    let v2 = format!("bias_v2{suffix}");
    let freqs = column(table, "fringe_hz")?;
    let (unbiased, last_biased) = unbiased_from(
        &freqs,
        &column(table, &v1)?,
        &column(table, &format!("{v1}_stderr"))?,
    );
    let unbiased_interval = if unbiased.is_nan() {
        (f64::NAN, f64::NAN)
    } else {
        (last_biased.min(unbiased), unbiased)
    };
    let located = [
        locate(table, &v1, BIASED_LEVEL)?,
        locate(table, &v2, BIASED_LEVEL)?,
        locate(table, &v2, V2_UNBIASED_LEVEL)?,
    ];
    let [a, b, c] = located.map(|l| (l.value, (l.lo, l.hi)));
    Ok((
        [a.0, b.0, unbiased, c.0],
        [a.1, b.1, unbiased_interval, c.1],
    ))
}

impl Sensitivity {
    /// The table as CSV: the choices, then per threshold its value, its
    /// interval (`_lo`, `_hi`) and the paper's.
    pub fn to_csv(&self) -> String {
        let mut out = String::from("psd,reference,window,samples,dx_um");
        for name in THRESHOLD_NAMES {
            out.push_str(&format!(",{name},{name}_lo,{name}_hi,paper_{name}"));
        }
        out.push('\n');
        for r in &self.rows {
            out.push_str(&format!(
                "{},{},{},{},{}",
                r.psd.name(),
                r.reference.name(),
                r.window.name(),
                r.samples,
                r.dx_um
            ));
            for ((t, (lo, hi)), p) in r
                .thresholds_hz
                .iter()
                .zip(r.intervals_hz)
                .zip(PAPER_THRESHOLDS_HZ)
            {
                out.push_str(&format!(",{t:.1},{lo:.1},{hi:.1},{p}"));
            }
            out.push('\n');
        }
        out
    }

    /// The table as Markdown: each threshold as `value (lo–hi)`, ✓ when
    /// the paper's lies inside the interval.
    pub fn to_markdown(&self) -> String {
        let mut out = format!(
            "Fig. 5 thresholds (Hz) for each combination: {} log-spaced frequencies {:.0}–{:.0} Hz, {} scans each, sampled detector, seed {FIGURE_SEED}. Paper: {}. In brackets the Monte Carlo interval of each threshold: for the level crossings, the frequencies where |bias| is within {SIGNIFICANCE_SIGMAS} standard errors of the level, widened by half a grid step; for \"V1 unbiased from\", the last frequency where |bias V1| exceeds {SIGNIFICANCE_SIGMAS} standard errors to the threshold. ✓: the paper's threshold lies inside the interval.\n\n| spectrum | reference | bins | N x δx | V1 > {biased_pct}% below | V2 > {biased_pct}% below | V1 unbiased from | V2 < {V2_UNBIASED_LEVEL:e} from |\n|---|---|---|---|---:|---:|---:|---:|\n",
            self.frequencies.len(),
            self.frequencies[0],
            self.frequencies[self.frequencies.len() - 1],
            self.scans,
            PAPER_THRESHOLDS_HZ.map(|t| t.to_string()).join(" / "),
            biased_pct = 100.0 * BIASED_LEVEL,
        );
        for r in &self.rows {
            let t: Vec<String> = (0..4).map(|i| self.cell(r, i)).collect();
            out.push_str(&format!(
                "| {} | {} | {} | {} x {} | {} |\n",
                r.psd.name(),
                r.reference.name(),
                r.window.name(),
                r.samples,
                r.dx_um,
                t.join(" | ")
            ));
        }
        out
    }

    /// Threshold `i` of `r` as a Markdown cell: `622 (571–680)`, with `≤`
    /// or `≥` at the ends of the range, and ✓ when the paper's is inside.
    fn cell(&self, r: &SensitivityRow, i: usize) -> String {
        let (lo, hi) = (
            self.frequencies[0],
            self.frequencies[self.frequencies.len() - 1],
        );
        let t = r.thresholds_hz[i];
        let value = if t.is_nan() {
            return format!("none ≤ {hi:.0}");
        } else if t <= lo {
            format!("≤ {lo:.0}")
        } else if t >= hi {
            format!("≥ {hi:.0}")
        } else {
            format!("{t:.0}")
        };
        let (a, b) = r.intervals_hz[i];
        let mark = if r.paper_inside(i) { " ✓" } else { "" };
        format!("{value} ({a:.0}–{b:.0}){mark}")
    }

    /// For threshold `i`: the rows within one grid step of the paper's
    /// value, and the closest row.
    pub fn closest(&self, i: usize) -> (Vec<&SensitivityRow>, Option<&SensitivityRow>) {
        let step = self.grid_step_ln();
        let within = self
            .rows
            .iter()
            .filter(|r| r.log_distance()[i] <= step)
            .collect();
        let best = self
            .rows
            .iter()
            .min_by(|a, b| a.log_distance()[i].total_cmp(&b.log_distance()[i]));
        (within, best)
    }

    /// The combinations within one grid step of all four paper values.
    pub fn reproducing_all(&self) -> Vec<&SensitivityRow> {
        let step = self.grid_step_ln();
        self.rows
            .iter()
            .filter(|r| r.log_distance().iter().all(|d| *d <= step))
            .collect()
    }

    /// One step of the log-spaced grid, ln units.
    fn grid_step_ln(&self) -> f64 {
        let n = self.frequencies.len();
        (self.frequencies[n - 1] / self.frequencies[0]).ln() / (n - 1) as f64
    }
}
