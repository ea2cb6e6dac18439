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
use crate::formalism::estimator::{BinWindow, Pair, BIN_WINDOWS};
use crate::formalism::interferogram::Sampling;
use crate::formalism::observation::Observation;
use crate::montecarlo::{
    derive_seed, effective_count, replicated_summary, run_units, RunningStats, Summary,
};
use crate::piston::calibration::{Calibration, ScanContext, Workspace};
use crate::piston::fringe_table::MAX_OPD_UM;
use crate::piston::scan::{fill_scan, interp, Detector, PistonReference, ScanSetup};
use crate::piston::series::{synthesize_series, MAX_SERIES};
use crate::piston::turbulence::PistonSpectrum;
use serde::Serialize;

/// Scans between two calls of the progress callback (and chances to stop).
const PROGRESS_SCANS: usize = 100;

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
    /// consecutive scans are correlated.
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
    /// ([`sequence_split`]); the standard errors have one degree of freedom
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
    /// ([`correlation_time_s`]; at least [`SPAN_CORRELATION_TIMES`] unless
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

/// The most scans of `samples` samples one run can hold: all its
/// sequences together have at most [`MAX_SERIES`] samples (the memory
/// limit), each with 4 samples of margin and a scan's worth of slack.
pub fn max_scans(samples: usize) -> usize {
    let n = samples.max(1);
    MAX_SERIES.saturating_sub(MAX_SEQUENCES * (n + 4)) / n
}

/// Fewest consecutive scans cut from one piston sequence.
pub const MIN_SCANS_PER_SEQUENCE: usize = 16;

/// Most independent piston sequences of one run.
pub const MAX_SEQUENCES: usize = 16;

/// How a run of `scans` scans is cut into independent piston sequences:
/// `(sequences, scans of the longest)`. Consecutive scans through one
/// sequence are correlated (the piston moves little from one scan to the
/// next when the scans are short against its correlation time), so the
/// standard errors come from the spread between independent sequences
/// ([`crate::montecarlo::replicated_summary`]), never from the scans as if
/// they were independent. As many sequences as there are
/// [`MIN_SCANS_PER_SEQUENCE`] scans, at least 2 (the fewest that give an
/// error, with one degree of freedom) and at most [`MAX_SEQUENCES`]; the scans are
/// shared out as evenly as possible (sequence j has `scans / K` scans, one
/// more for the first `scans % K`).
///
/// ```
/// use v2ref::piston::simulation::sequence_split;
/// assert_eq!(sequence_split(1000), (16, 63));
/// assert_eq!(sequence_split(20), (2, 10));
/// assert_eq!(sequence_split(100_000), (16, 6250));
/// ```
pub fn sequence_split(scans: usize) -> (usize, usize) {
    let k = (scans / MIN_SCANS_PER_SEQUENCE).clamp(2.min(scans.max(1)), MAX_SEQUENCES);
    (k, scans.div_ceil(k))
}

/// How many piston correlation times (B/v, [`correlation_time_s`]) one
/// sequence spans at least: a sequence shorter than the piston's
/// correlation time lacks its slow wander, and its scans see less piston
/// than the night's (the scatter comes out low, the same for every seed).
/// Measured on a 330 m baseline in H at 10 m/s (B/v = 33 s, 1569.5 Hz):
/// the V1 scatter is 1.92e-3 from consecutive scans spanning 0.3 B/v,
/// 2.28e-3 at 1 B/v, 2.44e-3 at 3 B/v and the same at 10 (±0.04e-3); 2 is
/// the cost's compromise (the plan's piston runs grow with the span).
pub const SPAN_CORRELATION_TIMES: f64 = 2.0;

/// The differential piston's correlation time, B/v, s: below the
/// frequency v/B the two apertures see the same slow wander and the
/// spectrum flattens.
pub fn correlation_time_s(spectrum: &PistonSpectrum) -> f64 {
    spectrum.baseline_m() / spectrum.wind_mps()
}

/// Samples from one scan's start to the next within a sequence of
/// `scans` scans: N (consecutive scans) unless that would span less than
/// [`SPAN_CORRELATION_TIMES`] correlation times, in which case the scans are
/// spread out over that span (the piston between them is synthesized but
/// not scanned); within [`MAX_SERIES`] samples.
pub fn scan_stride(spectrum: &PistonSpectrum, setup: &ScanSetup, total_scans: usize) -> usize {
    let n = setup.samples;
    let (sequences, scans) = sequence_split(total_scans);
    let span_samples =
        SPAN_CORRELATION_TIMES * correlation_time_s(spectrum) / setup.sample_time_s();
    // L scans start L − 1 strides apart.
    let wanted = (span_samples / scans.saturating_sub(1).max(1) as f64).ceil();
    let most = ((MAX_SERIES / sequences).saturating_sub(n + 4) / scans.max(1)) as f64;
    wanted.min(most).max(n as f64) as usize
}

/// The seed of independent sequence `j` of a run from `seed` (keyed by
/// its index: sequence j is the same whatever the number of scans).
pub fn sequence_seed(seed: u64, j: usize) -> u64 {
    derive_seed(seed, "piston-sequence", &[j as f64])
}

/// The piston read by the scans of a run: independent sequences, each read
/// by consecutive scans ([`sequence_split`]), and where the fringe packet
/// sits in each scan.
pub(crate) struct PistonSequence {
    /// p at each sample time, µm, per sequence (each periodic, at least
    /// its scans × N + 4 long).
    segments: Vec<Vec<f64>>,
    /// First scan of each sequence, and one past the last scan.
    first_scan: Vec<usize>,
    /// Samples from the start of one scan to the start of the next in a
    /// sequence (≥ N: the scans are spread over the sequence's span).
    stride: usize,
    /// N.
    samples: usize,
    /// How each scan's reference is taken.
    reference: PistonReference,
}

impl PistonSequence {
    /// Synthesises the sequences of `size.scans` scans of `setup` from the
    /// differential-piston spectrum, from `size.seed` (all its randomness).
    pub(crate) fn synthesize(
        spectrum: &PistonSpectrum,
        setup: &ScanSetup,
        size: &RunSize,
    ) -> Result<Self> {
        let k = sequence_split(size.scans).0;
        Self::synthesize_layout(
            spectrum,
            setup,
            size,
            (k, scan_stride(spectrum, setup, size.scans)),
        )
    }

    /// [`synthesize`](Self::synthesize) with `k` sequences whose scans start
    /// `stride` samples apart.
    fn synthesize_layout(
        spectrum: &PistonSpectrum,
        setup: &ScanSetup,
        size: &RunSize,
        (k, stride): (usize, usize),
    ) -> Result<Self> {
        let psd = |nu: f64| spectrum.psd_um2_per_hz(nu);
        let n = setup.samples;
        let mut first_scan = vec![0];
        let mut segments = Vec::with_capacity(k);
        for j in 0..k {
            let scans = size.scans / k + usize::from(j < size.scans % k);
            first_scan.push(first_scan[j] + scans);
            segments.push(synthesize_series(
                &psd,
                setup.sample_time_s(),
                (scans - 1) * stride + n + 4,
                sequence_seed(size.seed, j),
                size.threads,
            )?);
        }
        Ok(PistonSequence {
            segments,
            first_scan,
            stride,
            samples: n,
            reference: setup.reference,
        })
    }

    /// Number of independent sequences.
    pub(crate) fn sequences(&self) -> usize {
        self.segments.len()
    }

    /// The scans of sequence `j`.
    pub(crate) fn scans_of(&self, j: usize) -> std::ops::Range<usize> {
        self.first_scan[j]..self.first_scan[j + 1]
    }

    /// The index of the sequence read by scan `s`.
    pub(crate) fn sequence_of(&self, s: usize) -> usize {
        self.first_scan.partition_point(|&f| f <= s) - 1
    }

    /// The sequence read by scan `s`, and the scan's index in it.
    fn locate(&self, s: usize) -> (&[f64], usize) {
        let j = self.sequence_of(s);
        (&self.segments[j], s - self.first_scan[j])
    }

    /// Samples spanned by the scans of the longest sequence.
    pub(crate) fn span_samples(&self) -> usize {
        let longest = self.scans_of(0).len();
        (longest - 1) * self.stride + self.samples
    }

    /// RMS of all the sequences, µm.
    pub(crate) fn rms_um(&self) -> f64 {
        let m: usize = self.segments.iter().map(Vec::len).sum();
        let sum2: f64 = self.segments.iter().flatten().map(|p| p * p).sum();
        (sum2 / m as f64).sqrt()
    }

    /// The piston removed from scan `s`, µm.
    pub(crate) fn reference_um(&self, s: usize) -> f64 {
        let (series, local) = self.locate(s);
        let (n, base) = (self.samples, local * self.stride);
        match self.reference {
            PistonReference::Centre => series[base + n / 2],
            PistonReference::Mean => series[base..base + n].iter().sum::<f64>() / n as f64,
            PistonReference::Absolute => 0.0,
        }
    }

    /// The piston of scan `s` at τ sample intervals from its start, µm.
    pub(crate) fn at(&self, s: usize, tau: f64) -> f64 {
        let (series, local) = self.locate(s);
        interp(series, (local * self.stride) as f64 + tau)
    }

    /// Over all the scans: the largest |p − reference| any sub-sample can
    /// reach (the cubic reads one sample either side of the scan), and the
    /// RMS of p − reference over the samples.
    pub(crate) fn excursion_and_residual(&self) -> (f64, f64) {
        let n = self.samples;
        let (mut excursion, mut resid2) = (0.0_f64, 0.0);
        let scans = self.first_scan[self.sequences()];
        for s in 0..scans {
            let (series, local) = self.locate(s);
            let m = series.len();
            let r = self.reference_um(s);
            for j in 0..=n + 1 {
                let d = series[(local * self.stride + j) % m] - r;
                excursion = excursion.max(d.abs());
                if j < n {
                    resid2 += d * d;
                }
            }
            let prev = series[(local * self.stride + m - 1) % m] - r;
            excursion = excursion.max(prev.abs());
        }
        (excursion, (resid2 / (scans * n) as f64).sqrt())
    }
}

/// The OPD range (µm) the fringe table must cover for scans of `setup`
/// whose piston moves the packet by up to `excursion_um`.
pub(crate) fn table_range_um(setup: &ScanSetup, excursion_um: f64) -> Result<f64> {
    let max_opd = (setup.samples / 2 + 1) as f64 * setup.dx_um + 1.5 * excursion_um + 1.0;
    if max_opd > MAX_OPD_UM {
        return Err(Error::Invalid {
            param: "reference",
            reason: format!(
                "the piston moves the fringe packet by up to {excursion_um:.0} um within the scans (at most {MAX_OPD_UM} um of OPD is simulated): lower the seeing, raise the fringe frequency or re-centre the scans (--reference mean)"
            ),
        });
    }
    Ok(max_opd)
}

/// One scan's effect of the piston: per detector, per window, the V1 and V2
/// differences (in the `v1_sq`, `v2_sq` fields of [`Pair`], here not
/// squared).
struct ScanResult {
    per_detector: Vec<Vec<Pair>>,
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

    fn push(&mut self, scan: &ScanResult) {
        for (acc, diffs) in self.per_detector.iter_mut().zip(&scan.per_detector) {
            for ((v1, v2), d) in acc.iter_mut().zip(diffs) {
                v1.push(d.v1_sq);
                v2.push(d.v2_sq);
            }
        }
    }
}

/// Scan `s` of the sequence seen by every calibrated detector.
fn scan(
    ctx: &ScanContext,
    sequence: &PistonSequence,
    calibrations: &[Calibration],
    s: usize,
    ws: &mut Workspace,
) -> ScanResult {
    let r = sequence.reference_um(s);
    let p = |tau: f64| sequence.at(s, tau);
    let per_detector = calibrations
        .iter()
        .map(|cal| {
            let (u, w) = (&cal.sub.0, &cal.sub.1);
            fill_scan(&ctx.table, ctx.setup, u, w, &p, r, &mut ws.samples);
            cal.differences(&ws.raw_per_window(ctx))
        })
        .collect();
    ScanResult { per_detector }
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
) -> Vec<DifferenceStats> {
    // The scans draw no random numbers (all the randomness is in the
    // sequences): the units' generators are unused, their seed is a label.
    let unit_seed = derive_seed(size.seed, "piston-scans", &[]);
    let units = sequence.sequences() as u64;
    run_units(unit_seed, units, size.threads, |unit, _rng| {
        let mut ws = Workspace::new(ctx.setup.samples);
        let mut stats = DifferenceStats::new(calibrations.len());
        let mut done = 0;
        for s in sequence.scans_of(unit as usize) {
            stats.push(&scan(ctx, sequence, calibrations, s, &mut ws));
            done += 1;
            if done % PROGRESS_SCANS == 0 {
                if let Some(cb) = progress {
                    cb(PROGRESS_SCANS as u64);
                }
            }
        }
        if let Some(cb) = progress {
            cb((done % PROGRESS_SCANS) as u64);
        }
        stats
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
/// use v2ref::prelude::*;
/// use v2ref::piston::{Detector, RunSize};
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
/// # Ok::<(), v2ref::Error>(())
/// ```
pub fn simulate(
    obs: &Observation,
    spectrum: &PistonSpectrum,
    setup: &ScanSetup,
    detectors: &[Detector],
    size: &RunSize,
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> Result<Vec<PistonRun>> {
    let sequence = |size: &RunSize| PistonSequence::synthesize(spectrum, setup, size);
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
        PistonSequence::synthesize_layout(spectrum, setup, size, (1, setup.samples))
    };
    simulate_through(obs, spectrum, setup, detectors, size, None, &sequence)
}

/// [`simulate`] through the sequences `make_sequence` synthesizes.
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
    crate::montecarlo::in_pool(size.threads, || spectrum.tabulate());
    let sequence = make_sequence(size)?;
    let (excursion, residual_rms_um) = sequence.excursion_and_residual();
    let ctx = ScanContext::new(obs, setup, table_range_um(setup, excursion)?)?;
    let mut ws = Workspace::new(setup.samples);
    let calibrations = detectors
        .iter()
        .map(|&d| Calibration::new(&ctx, d, &mut ws))
        .collect::<Result<Vec<_>>>()?;
    let stats = scan_all(&ctx, &sequence, &calibrations, size, progress);
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

/// [`simulate`] at each fringe frequency of `frequencies` (the template
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
        simulate(obs, spectrum, &setup, detectors, &size, progress)
    };
    crate::montecarlo::in_pool(size.threads, || {
        use rayon::prelude::*;
        // Tables first, on every thread, not by the first frequency while
        // the others wait.
        spectrum.tabulate();
        frequencies.par_iter().map(|&f| run(f)).collect()
    })
}
