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
//! The independent sequences ([`crate::piston::sequences`]), their
//! synthesis ([`crate::piston::series`]), the scans
//! ([`crate::piston::scan`]) and the tabulated fringe
//! (`piston::fringe_table`) are in their own modules.

use crate::error::{Error, Result};
use crate::formalism::estimator::{BinWindow, Pair, BIN_WINDOWS};
use crate::formalism::interferogram::Sampling;
use crate::formalism::observation::Observation;
use crate::montecarlo::{
    derive_seed, effective_count, replicated_summary, try_run_unit_range, RunningStats, Steps,
    Summary,
};
use crate::piston::calibration::{Calibration, ScanContext, Workspace};
use crate::piston::fringe_table::MAX_OPD_UM;
use crate::piston::scan::{fill_scan, Detector, ScanSetup};
use crate::piston::sequences::{correlation_time_s, max_scans, PistonSequence};
use crate::piston::spectrum::PistonSpectrum;
use serde::Serialize;

/// Piston statistics for one window of bins.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WindowResult {
    /// The window.
    pub window: BinWindow,
    /// V1 of the piston-free scan (normalized by the unresolved calibrator).
    pub v1_no_piston: f64,
    /// V2 of the piston-free scan.
    pub v2_no_piston: f64,
    /// V1(piston) − V1(no piston) over scans: the mean is the bias, the
    /// standard deviation the scatter.
    pub v1: Summary,
    /// V2(piston) − V2(no piston) over scans.
    pub v2: Summary,
    /// The number of independent scans worth the bias of V1 (its variance
    /// over its squared standard error): fewer than `scans` when
    /// consecutive scans share their errors, more when their errors
    /// alternate in sign (negatively correlated scans average out faster
    /// than independent ones), and itself uncertain (its error has the
    /// sequences' K − 1 degrees of freedom).
    pub v1_effective_scans: f64,
    /// The same for V2.
    pub v2_effective_scans: f64,
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
    /// Number of independent piston sequences they are cut from
    /// ([`crate::piston::sequences::sequence_split`]); the standard errors have one degree of freedom
    /// fewer.
    pub sequences: usize,
    /// Seed.
    pub seed: u64,
    /// Duration of one scan, s.
    pub scan_time_s: f64,
    /// RMS of the synthesised piston sequence, µm.
    pub piston_rms_um: f64,
    /// RMS over scans and samples of the piston left after the reference is
    /// removed, µm.
    pub residual_rms_um: f64,
    /// The time spanned by each sequence, in piston correlation times B/v
    /// ([`crate::piston::sequences::correlation_time_s`]; at least [`crate::piston::sequences::SPAN_CORRELATION_TIMES`] unless
    /// the memory limit binds).
    pub span_correlation_times: f64,
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

/// Checks the scan setup and that `size.scans` scans fit in one sequence.
pub(crate) fn validate_size(setup: &ScanSetup, size: &RunSize) -> Result<()> {
    setup.validate()?;
    let most = max_scans(setup.samples);
    if size.scans < 2 || size.scans > most {
        return Err(Error::OutOfRange {
            param: "scans",
            value: size.scans as f64,
            accepted: format!("2 to {most} with {} samples per scan", setup.samples),
        });
    }
    Ok(())
}

/// The OPD range (µm) the fringe table must cover for scans of `setup`
/// whose piston moves the packet by up to `excursion_um`.
pub(crate) fn table_range_um(setup: &ScanSetup, excursion_um: f64) -> Result<f64> {
    let max_opd = (setup.samples / 2 + 1) as f64 * setup.dx_um + 1.5 * excursion_um + 1.0;
    if max_opd > MAX_OPD_UM {
        return Err(Error::Invalid {
            param: "reference",
            reason: format!(
                "the piston moves the fringe packet by up to {excursion_um:.0} um within the scans (at most {MAX_OPD_UM} um of OPD is simulated): lower the seeing, raise the fringe frequency or re-centre the scans on their mean (reference `mean`)"
            ),
        });
    }
    Ok(max_opd)
}

/// Running statistics of the differences, one accumulator per detector ×
/// window × estimator.
#[derive(Clone)]
struct DifferenceStats {
    /// `[detector][window]` → (V1, V2).
    per_detector: Vec<Vec<(RunningStats, RunningStats)>>,
}

impl DifferenceStats {
    fn new(detectors: usize) -> Self {
        let window = (RunningStats::default(), RunningStats::default());
        DifferenceStats {
            per_detector: vec![vec![window; BIN_WINDOWS.len()]; detectors],
        }
    }

    /// One scan's V1 and V2 differences through detector `detector`, per
    /// window (in the `v1_sq`, `v2_sq` fields of [`Pair`], here not
    /// squared).
    fn push(&mut self, detector: usize, diffs: &[Pair]) {
        for ((v1, v2), d) in self.per_detector[detector].iter_mut().zip(diffs) {
            v1.push(d.v1_sq);
            v2.push(d.v2_sq);
        }
    }
}

/// Scan `s` of the sequence seen by every calibrated detector, its
/// differences added to `stats` (nothing allocated per scan).
fn scan(
    (ctx, sequence, calibrations): (&ScanContext, &PistonSequence, &[Calibration]),
    s: usize,
    ws: &mut Workspace,
    stats: &mut DifferenceStats,
) {
    let r = sequence.reference_um(s);
    let p = sequence.of_scan(s);
    for (d, cal) in calibrations.iter().enumerate() {
        let (u, w) = (&cal.sub.0, &cal.sub.1);
        fill_scan(&ctx.table, ctx.setup, u, w, &p, r, &mut ws.samples);
        stats.push(d, &cal.differences(&ws.raw_per_window(ctx)));
    }
}

/// All scans, one work unit per independent sequence (its consecutive
/// scans in order), run in parallel; returns each sequence's statistics in
/// sequence order (deterministic whatever the thread count).
fn scan_all(
    ctx: &ScanContext,
    sequence: &PistonSequence,
    calibrations: &[Calibration],
    size: &RunSize,
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> Result<Vec<DifferenceStats>> {
    // The scans draw no random numbers (all the randomness is in the
    // sequences): the units' generators are unused, their seed is a label.
    let unit_seed = derive_seed(size.seed, "piston-scans", &[]);
    let units = sequence.sequences() as u64;
    // A scan: its samples (and sub-samples) through each detector, a few
    // operations each.
    let scan_work = 16 * ctx.setup.samples * calibrations.len();
    try_run_unit_range(unit_seed, 0..units, size.threads, |unit, _rng| {
        let mut ws = Workspace::new(ctx.setup.samples);
        let mut stats = DifferenceStats::new(calibrations.len());
        let mut steps = Steps::new(progress.unwrap_or(&|_| {}), scan_work);
        for s in sequence.scans_of(unit as usize) {
            scan((ctx, sequence, calibrations), s, &mut ws, &mut stats);
            steps.step()?;
        }
        steps.finish()?;
        Ok(stats)
    })
}

/// What a run reports of the sequence besides the differences.
struct SequenceFacts {
    sequences: usize,
    span_correlation_times: f64,
    piston_rms_um: f64,
    residual_rms_um: f64,
}

/// One [`PistonRun`] per detector from the merged statistics.
fn reduce(
    setup: &ScanSetup,
    size: &RunSize,
    facts: &SequenceFacts,
    calibrations: &[Calibration],
    stats: &[DifferenceStats],
) -> Vec<PistonRun> {
    calibrations
        .iter()
        .enumerate()
        .map(|(d, cal)| PistonRun {
            fringe_hz: setup.fringe_hz,
            detector: cal.detector,
            scans: size.scans,
            sequences: facts.sequences,
            seed: size.seed,
            scan_time_s: setup.scan_time_s(),
            piston_rms_um: facts.piston_rms_um,
            residual_rms_um: facts.residual_rms_um,
            span_correlation_times: facts.span_correlation_times,
            windows: BIN_WINDOWS
                .iter()
                .zip(&cal.no_piston)
                .enumerate()
                .map(|(w, (&window, v0))| {
                    let per_sequence = |pick: fn(&(RunningStats, RunningStats)) -> RunningStats| {
                        stats
                            .iter()
                            .map(|s| pick(&s.per_detector[d][w]))
                            .collect::<Vec<_>>()
                    };
                    let v1 = replicated_summary(&per_sequence(|p| p.0));
                    let v2 = replicated_summary(&per_sequence(|p| p.1));
                    WindowResult {
                        window,
                        v1_no_piston: v0.v1_sq,
                        v2_no_piston: v0.v2_sq,
                        v1,
                        v2,
                        v1_effective_scans: effective_count(&v1),
                        v2_effective_scans: effective_count(&v2),
                    }
                })
                .collect(),
        })
        .collect()
}

/// Runs the piston Monte Carlo: synthesises one piston sequence for `scans`
/// consecutive scans of `setup` at the spectrum's turbulence and baseline,
/// observes `obs` through it with each of `detectors` (the same sequence
/// for all), and returns one [`PistonRun`] per detector.
///
/// `progress`, if given, is called with the number of scans just finished.
/// Deterministic in the seed whatever the thread count; memory does not
/// grow with the number of scans beyond the sequence itself.
///
/// # Example
///
/// ```
/// use v2ref_core::prelude::*;
/// use v2ref_core::piston::{Detector, RunSize};
/// // 200 scans of an unresolved source at 1000 Hz through the paper's
/// // turbulence on 18 m: same seed, same bits, whatever the thread count.
/// let obs = Observation::new(Spectrum::flat(Band::k()), Source::Point, Frequency::BaselineM(18.0), SpectralPhase::zero())?;
/// let piston = PistonSpectrum::new(Turbulence::from_seeing(1.0, 2.2, 10.0, None)?, 0.45, 18.0)?;
/// let run = |threads| {
///     let size = RunSize { scans: 200, seed: 7, threads };
///     simulate_piston(&obs, &piston, &ScanSetup::paper(1000.0), &[Detector::Sampled], &size, None)
/// };
/// let (one, two) = (run(1)?, run(2)?);
/// assert_eq!(one, two);
/// let v2 = one[0].window(BinWindow::Positive).v2;
/// assert!(v2.mean < 0.0 && v2.std > 0.0); // piston lowers the fringe contrast on average
/// # Ok::<(), v2ref_core::Error>(())
/// ```
pub fn simulate_piston(
    obs: &Observation,
    spectrum: &PistonSpectrum,
    setup: &ScanSetup,
    detectors: &[Detector],
    size: &RunSize,
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> Result<Vec<PistonRun>> {
    let sequence = |size: &RunSize| PistonSequence::synthesize(spectrum, setup, size, None);
    simulate_through(obs, spectrum, setup, detectors, size, progress, &sequence)
}

/// The former method, kept as the named alternative the tests reject:
/// `size.scans` consecutive scans of one piston sequence. Its statistics
/// are those of the scans as if they were independent (the standard errors
/// are NaN: one sequence has no spread to measure); where the scans are
/// short against the piston's correlation time, those naive errors are
/// wrong (`tests/piston_errors.rs`).
#[doc(hidden)]
pub fn simulate_consecutive(
    obs: &Observation,
    spectrum: &PistonSpectrum,
    setup: &ScanSetup,
    detectors: &[Detector],
    size: &RunSize,
) -> Result<Vec<PistonRun>> {
    let sequence = |size: &RunSize| {
        PistonSequence::synthesize_layout(spectrum, setup, size, (1, setup.samples), None)
    };
    simulate_through(obs, spectrum, setup, detectors, size, None, &sequence)
}

/// [`simulate_piston`] through the sequences `make_sequence` synthesizes.
fn simulate_through(
    obs: &Observation,
    spectrum: &PistonSpectrum,
    setup: &ScanSetup,
    detectors: &[Detector],
    size: &RunSize,
    progress: Option<&(dyn Fn(u64) + Sync)>,
    make_sequence: &dyn Fn(&RunSize) -> Result<PistonSequence>,
) -> Result<Vec<PistonRun>> {
    validate_size(setup, size)?;
    for d in detectors {
        d.sub_samples()?;
    }
    Sampling::new(setup.samples, setup.dx_um, false)?.check_aliasing(obs)?;
    crate::montecarlo::in_pool(size.threads, || {
        spectrum.tabulate();
        Ok(())
    })?;
    let sequence = make_sequence(size)?;
    let (excursion, residual_rms_um) = sequence.excursion_and_residual();
    let ctx = ScanContext::new(obs, setup, table_range_um(setup, excursion)?)?;
    let mut ws = Workspace::new(setup.samples);
    let calibrations = detectors
        .iter()
        .map(|&d| Calibration::new(&ctx, d, &mut ws))
        .collect::<Result<Vec<_>>>()?;
    let stats = scan_all(&ctx, &sequence, &calibrations, size, progress)?;
    let facts = SequenceFacts {
        sequences: sequence.sequences(),
        span_correlation_times: sequence.span_samples() as f64 * setup.sample_time_s()
            / correlation_time_s(spectrum),
        piston_rms_um: sequence.rms_um(),
        residual_rms_um,
    };
    Ok(reduce(setup, size, &facts, &calibrations, &stats))
}

/// The seed of the run at fringe frequency `fringe_hz` of a sweep from
/// `seed`: keyed by the frequency, so a frequency's result does not depend
/// on the other frequencies asked.
pub fn sweep_seed(seed: u64, fringe_hz: f64) -> u64 {
    derive_seed(seed, "piston", &[fringe_hz])
}

/// [`simulate_piston`] at each fringe frequency of `frequencies` (the template
/// `setup` with its `fringe_hz` replaced), each from its own sequence of
/// seed [`sweep_seed`]`(size.seed, f)`. Returns, per frequency, one
/// [`PistonRun`] per detector; `progress` counts scans over all of them.
pub fn sweep(
    obs: &Observation,
    spectrum: &PistonSpectrum,
    frequencies: &[f64],
    setup: &ScanSetup,
    detectors: &[Detector],
    size: &RunSize,
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> Result<Vec<Vec<PistonRun>>> {
    // Each frequency's run is independent and keyed by its value: the
    // frequencies run in parallel (each also spreads its own scans and
    // series over the pool), and the answer does not depend on the order in
    // which they finish.
    let run = |f: f64| {
        let setup = ScanSetup {
            fringe_hz: f,
            ..*setup
        };
        // threads 0 inside: the pool installed below is the current one.
        let size = RunSize {
            seed: sweep_seed(size.seed, f),
            threads: 0,
            ..*size
        };
        simulate_piston(obs, spectrum, &setup, detectors, &size, progress)
    };
    crate::montecarlo::in_pool(size.threads, || {
        use rayon::prelude::*;
        // Tables first, on every thread, not by the first frequency while
        // the others wait.
        spectrum.tabulate();
        frequencies.par_iter().map(|&f| run(f)).collect()
    })
}
