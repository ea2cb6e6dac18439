//! Scanned interferograms corrupted by differential piston, and the bias and
//! scatter it gives the two estimators (paper, Section "Effect of
//! differential piston", Figs. 4 and 5).
//!
//! # Estimators
//!
//! Each scan's modulated samples are Fourier transformed and V1², V2² are
//! summed over a window of bins ([`BinWindow`]: the positive half, the band, or
//! all N bins — the paper does not say which). Each is normalized by the
//! same estimator on the piston-free interferogram of an unresolved source,
//! and the visibility is its square root. The bias is the mean over scans
//! of `V(with piston) − V(without)`, the scatter their standard deviation.
//!
//! The sequence ([`crate::piston::series`]), the scans
//! ([`crate::piston::scan`]) and the tabulated fringe
//! ([`crate::piston::fringe_table`]) are in their own modules.

use crate::error::{Error, Result};
use crate::formalism::estimator::{raw_estimates, BinWindow, Pair, BIN_WINDOWS};
use crate::formalism::interferogram::Sampling;
use crate::formalism::observation::Observation;
use crate::formalism::source::Source;
use crate::montecarlo::run_units;
use crate::piston::fringe_table::{FringeTable, MAX_OPD_UM};
use crate::piston::scan::{fill_scan, interp, Detector, PistonReference, ScanSetup};
use crate::piston::series::{synthesize_series, MAX_SERIES};
use crate::piston::turbulence::PistonSpectrum;
use num_complex::Complex64;
use rustfft::{Fft, FftPlanner};
use serde::Serialize;

/// Scans per work unit in [`simulate`].
const SCAN_BLOCK: usize = 100;

/// A mean and a standard deviation over scans, with their standard errors.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Default)]
pub struct Estimate {
    /// Mean (the bias).
    pub mean: f64,
    /// Its standard error, std/√n.
    pub mean_stderr: f64,
    /// Standard deviation (the scatter), n − 1 denominator.
    pub std: f64,
    /// Its standard error, √((m4 − s⁴)/n)/(2s) (no normality assumed).
    pub std_stderr: f64,
}

impl Estimate {
    /// The estimate from a sample (two passes).
    pub fn from_values(x: &[f64]) -> Estimate {
        let n = x.len() as f64;
        if x.is_empty() {
            return Estimate::default();
        }
        let mean = x.iter().sum::<f64>() / n;
        let (mut m2, mut m4) = (0.0, 0.0);
        for v in x {
            let d = (v - mean) * (v - mean);
            m2 += d;
            m4 += d * d;
        }
        let var = if x.len() > 1 { m2 / (n - 1.0) } else { 0.0 };
        let std = var.sqrt();
        let m4 = m4 / n;
        let std_stderr = if std > 0.0 {
            ((m4 - var * var).max(0.0) / n).sqrt() / (2.0 * std)
        } else {
            0.0
        };
        Estimate {
            mean,
            mean_stderr: (var / n).sqrt(),
            std,
            std_stderr,
        }
    }
}

/// Piston statistics for one window of bins.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WindowResult {
    /// The window.
    pub window: BinWindow,
    /// V1 of the piston-free scan (normalized by the unresolved calibrator).
    pub v1_no_piston: f64,
    /// V2 of the piston-free scan.
    pub v2_no_piston: f64,
    /// V1(piston) − V1(no piston) over scans.
    pub v1: Estimate,
    /// V2(piston) − V2(no piston) over scans.
    pub v2: Estimate,
}

/// The result of one piston Monte Carlo at one fringe frequency.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PistonRun {
    /// f, Hz.
    pub fringe_hz: f64,
    /// The detector.
    pub detector: Detector,
    /// Number of scans.
    pub scans: usize,
    /// Seed.
    pub seed: u64,
    /// Duration of one scan, s.
    pub scan_time_s: f64,
    /// RMS of the synthesised piston sequence, µm.
    pub piston_rms_um: f64,
    /// RMS over scans and samples of the piston left after the reference is
    /// removed, µm.
    pub residual_rms_um: f64,
    /// One entry per window of [`BIN_WINDOWS`].
    pub windows: Vec<WindowResult>,
}

impl PistonRun {
    /// The result for `window`.
    pub fn window(&self, window: BinWindow) -> &WindowResult {
        self.windows
            .iter()
            .find(|w| w.window == window)
            .unwrap_or(&self.windows[0])
    }
}

/// How many scans, from which seed, on how many threads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RunSize {
    /// Number of consecutive scans (≥ 2).
    pub scans: usize,
    /// The user seed.
    pub seed: u64,
    /// Worker threads (0 = all cores); the result does not depend on it.
    pub threads: usize,
}

/// Raw estimates per window.
fn raw_per_window(
    fft: &dyn Fft<f64>,
    samples: &[f64],
    bins: &[Vec<usize>],
    buf: &mut Vec<Complex64>,
    scratch: &mut Vec<Complex64>,
) -> Vec<Pair> {
    buf.clear();
    buf.extend(samples.iter().map(|&m| Complex64::new(m, 0.0)));
    scratch.resize(fft.get_inplace_scratch_len(), Complex64::new(0.0, 0.0));
    fft.process_with_scratch(buf, scratch);
    bins.iter().map(|b| raw_estimates(buf, b)).collect()
}

/// Runs the piston Monte Carlo: synthesises one piston sequence for `scans`
/// consecutive scans of `setup` at the spectrum's turbulence and baseline,
/// observes `obs` through it with each of `detectors` (the same sequence
/// for all), and returns one [`PistonRun`] per detector.
///
/// `progress`, if given, is called with the number of scans just finished.
/// Deterministic in the seed whatever the thread count.
pub fn simulate(
    obs: &Observation,
    spectrum: &PistonSpectrum,
    setup: &ScanSetup,
    detectors: &[Detector],
    size: &RunSize,
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> Result<Vec<PistonRun>> {
    let RunSize {
        scans,
        seed,
        threads,
    } = *size;
    setup.validate()?;
    let n = setup.samples;
    if scans < 2 || scans.saturating_mul(n) > MAX_SERIES - 4 {
        return Err(Error::OutOfRange {
            param: "scans",
            value: scans as f64,
            accepted: format!("2 to {} with {n} samples per scan", (MAX_SERIES - 4) / n),
        });
    }
    let subs = detectors
        .iter()
        .map(Detector::sub_samples)
        .collect::<Result<Vec<_>>>()?;
    Sampling::new(n, setup.dx_um, false)?.check_aliasing(obs)?;
    let dt = setup.sample_time_s();
    let psd = |nu: f64| spectrum.psd_um2_per_hz(nu);
    // The sequence: stream 0 of the seed's unit space is the coefficient
    // blocks; scans use no further randomness.
    let series = synthesize_series(&psd, dt, scans * n + 4, seed, threads)?;
    let m = series.len();
    let piston_rms_um = (series.iter().map(|p| p * p).sum::<f64>() / m as f64).sqrt();
    let reference = |s: usize| -> f64 {
        let base = s * n;
        match setup.reference {
            PistonReference::Centre => series[base + n / 2],
            PistonReference::Mean => series[base..base + n].iter().sum::<f64>() / n as f64,
            PistonReference::Absolute => 0.0,
        }
    };
    // Largest OPD any sub-sample reaches, for the table.
    let (mut excursion, mut resid2) = (0.0_f64, 0.0);
    for s in 0..scans {
        let r = reference(s);
        for j in 0..=n + 1 {
            let d = series[(s * n + j) % m] - r;
            excursion = excursion.max(d.abs());
            if j < n {
                resid2 += d * d;
            }
        }
        let prev = series[(s * n + m - 1) % m] - r;
        excursion = excursion.max(prev.abs());
    }
    let residual_rms_um = (resid2 / (scans * n) as f64).sqrt();
    let max_opd = (n / 2 + 1) as f64 * setup.dx_um + 1.5 * excursion + 1.0;
    if max_opd > MAX_OPD_UM {
        return Err(Error::Invalid {
            param: "reference",
            reason: format!(
                "the piston moves the fringe packet by up to {excursion:.0} um within the scans (at most {MAX_OPD_UM} um of OPD is simulated): lower the seeing, raise the fringe frequency or re-centre the scans (--reference mean)"
            ),
        });
    }
    let table = FringeTable::new(obs, max_opd)?;
    let cal_obs = obs.calibrator();
    let cal_table = if obs.source == Source::Point && obs.phase.is_zero() {
        None
    } else {
        Some(FringeTable::new(&cal_obs, max_opd)?)
    };
    let bins: Vec<Vec<usize>> = BIN_WINDOWS
        .iter()
        .map(|w| w.bins(n, setup.dx_um, &obs.spectrum))
        .collect();
    let fft = FftPlanner::new().plan_fft_forward(n);
    let mut out = Vec::new();
    // All detectors' scans are computed in one pass per block.
    struct Fixed {
        cal: Vec<Pair>,
        v0: Vec<Pair>,
    }
    let mut fixed = Vec::new();
    for (u, w) in &subs {
        let mut buf = Vec::new();
        let mut scratch = Vec::new();
        let mut samples = vec![0.0; n];
        fill_scan(&table, setup, u, w, &|_| 0.0, 0.0, &mut samples);
        let src = raw_per_window(fft.as_ref(), &samples, &bins, &mut buf, &mut scratch);
        let cal = match &cal_table {
            None => src.clone(),
            Some(t) => {
                fill_scan(t, setup, u, w, &|_| 0.0, 0.0, &mut samples);
                raw_per_window(fft.as_ref(), &samples, &bins, &mut buf, &mut scratch)
            }
        };
        let v0 = src
            .iter()
            .zip(&cal)
            .map(|(s, c)| Pair {
                v1_sq: (s.v1_sq / c.v1_sq).sqrt(),
                v2_sq: (s.v2_sq / c.v2_sq).sqrt(),
            })
            .collect();
        fixed.push(Fixed { cal, v0 });
    }
    let units = scans.div_ceil(SCAN_BLOCK) as u64;
    let nw = BIN_WINDOWS.len();
    let per_unit = run_units(seed ^ 0x5CA4_5CA4, units, threads, |unit, _rng| {
        let first = unit as usize * SCAN_BLOCK;
        let last = (first + SCAN_BLOCK).min(scans);
        let mut buf = Vec::with_capacity(n);
        let mut scratch = Vec::new();
        let mut samples = vec![0.0; n];
        // Per detector, per scan: [d1, d2] per window.
        let mut diffs = vec![Vec::with_capacity((last - first) * 2 * nw); subs.len()];
        for s in first..last {
            let base = (s * n) as f64;
            let r = reference(s);
            let p = |tau: f64| interp(&series, base + tau);
            for (di, (u, w)) in subs.iter().enumerate() {
                fill_scan(&table, setup, u, w, &p, r, &mut samples);
                let raw = raw_per_window(fft.as_ref(), &samples, &bins, &mut buf, &mut scratch);
                for (k, pr) in raw.iter().enumerate() {
                    let c = &fixed[di].cal[k];
                    let v0 = &fixed[di].v0[k];
                    diffs[di].push((pr.v1_sq / c.v1_sq).sqrt() - v0.v1_sq);
                    diffs[di].push((pr.v2_sq / c.v2_sq).sqrt() - v0.v2_sq);
                }
            }
        }
        if let Some(cb) = progress {
            cb((last - first) as u64);
        }
        diffs
    });
    for (di, det) in detectors.iter().enumerate() {
        let windows = BIN_WINDOWS
            .iter()
            .enumerate()
            .map(|(k, &window)| {
                let pick = |e: usize| -> Vec<f64> {
                    per_unit
                        .iter()
                        .flat_map(|u| u[di].chunks(2 * nw).map(move |c| c[2 * k + e]))
                        .collect()
                };
                WindowResult {
                    window,
                    v1_no_piston: fixed[di].v0[k].v1_sq,
                    v2_no_piston: fixed[di].v0[k].v2_sq,
                    v1: Estimate::from_values(&pick(0)),
                    v2: Estimate::from_values(&pick(1)),
                }
            })
            .collect();
        out.push(PistonRun {
            fringe_hz: setup.fringe_hz,
            detector: *det,
            scans,
            seed,
            scan_time_s: setup.scan_time_s(),
            piston_rms_um,
            residual_rms_um,
            windows,
        });
    }
    Ok(out)
}
