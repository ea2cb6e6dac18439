//! The independent piston sequences a run's scans are cut from: how many,
//! how long, their seeds, and where each scan sits in its sequence.
//!
//! Consecutive scans through one sequence are correlated (the piston moves
//! little from one scan to the next when the scans are short against its
//! correlation time B/v), so a run draws several independent sequences and
//! its standard errors come from the spread between them
//! ([`crate::montecarlo::replicated_summary`]).

use crate::montecarlo::derive_seed;
use crate::piston::scan::{interp, PistonReference, ScanSetup};
use crate::piston::series::{sequence_length, ModeScales, MAX_SERIES};
use crate::piston::spectrum::PistonSpectrum;
use crate::piston::RunSize;
use crate::{Error, Result};
use std::sync::{Arc, Mutex};

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
/// use v2ref_core::piston::sequence_split;
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
    segments: Vec<Arc<Vec<f64>>>,
    /// First scan of each sequence, and one past the last scan.
    first_scan: Vec<usize>,
    /// Samples from the start of one scan to the start of the next in a
    /// sequence (≥ N: the scans are spread over the sequence's span).
    stride: usize,
    /// N.
    samples: usize,
    /// The piston removed from each scan, µm (measured once: every reader
    /// of a scan subtracts it).
    references: Vec<f64>,
    /// How each scan's reference is taken.
    reference: PistonReference,
    /// Where the first scan of a sequence starts in its segment (0, or
    /// [`OBSERVATION_LEAD`] when only the stretch read of a longer
    /// sequence is kept).
    first_sample: usize,
    /// Samples of the longest periodic sequence synthesized.
    period_samples: usize,
}

/// How many times what an observation spans its piston sequence spans at
/// least (the observation layout): the sequence then also holds the
/// piston's wander slower than the observation, as the plan's observation
/// model does (`plan::observation::BLOCKS_PER_SEQUENCE`, whose sequences
/// hold at least 4 observations).
pub const OBSERVATION_SPAN: usize = 4;

/// Samples kept before an observation's first scan (what the cubic
/// interpolation reads before a sample).
const OBSERVATION_LEAD: usize = 2;

/// Samples of the piston sequence an observation reading `read` samples is
/// cut from: [`OBSERVATION_SPAN`] times `read` and at least
/// [`SPAN_CORRELATION_TIMES`] correlation times, within [`MAX_SERIES`].
pub(crate) fn observation_sequence_samples(
    spectrum: &PistonSpectrum,
    setup: &ScanSetup,
    read: usize,
) -> usize {
    let span = SPAN_CORRELATION_TIMES * correlation_time_s(spectrum) / setup.sample_time_s();
    let wanted = (OBSERVATION_SPAN as f64 * read as f64).max(span.ceil());
    (wanted.min(MAX_SERIES as f64) as usize).max(read.min(MAX_SERIES))
}

impl PistonSequence {
    /// Synthesises the sequences of `size.scans` scans of `setup` from the
    /// differential-piston spectrum, from `size.seed` (all its randomness).
    /// With `shared`, a sequence another run under the same spectrum has
    /// drawn from the same seed, length and step is read, not drawn again.
    pub(crate) fn synthesize(
        spectrum: &PistonSpectrum,
        setup: &ScanSetup,
        size: &RunSize,
        shared: Option<&SharedSequences>,
    ) -> Result<Self> {
        let k = sequence_split(size.scans).0;
        let layout = (k, scan_stride(spectrum, setup, size.scans));
        Self::synthesize_layout(spectrum, setup, size, layout, shared)
    }

    /// [`synthesize`](Self::synthesize) with `k` sequences whose scans start
    /// `stride` samples apart.
    pub(crate) fn synthesize_layout(
        spectrum: &PistonSpectrum,
        setup: &ScanSetup,
        size: &RunSize,
        (k, stride): (usize, usize),
        shared: Option<&SharedSequences>,
    ) -> Result<Self> {
        let psd = |nu: f64| spectrum.psd_um2_per_hz(nu);
        let n = setup.samples;
        let dt_s = setup.sample_time_s();
        let mut first_scan = vec![0];
        for j in 0..k {
            let scans = size.scans / k + usize::from(j < size.scans % k);
            first_scan.push(first_scan[j] + scans);
        }
        let len_of = |j: usize| (first_scan[j + 1] - first_scan[j] - 1) * stride + n + 4;
        // The sequences' lengths differ by at most a stride: most share
        // one FFT length, hence one set of scales, made here before the
        // sequences are drawn side by side (none when all are shared
        // already). No lock is held across parallel work: a worker waiting
        // for its share may take up another sequence's draw meanwhile.
        let mut scales: Vec<ModeScales> = Vec::new();
        for j in 0..k {
            let key = (
                sequence_seed(size.seed, j),
                sequence_length(len_of(j)),
                dt_s,
            );
            let drawn = shared.is_some_and(|s| s.has(spectrum, key));
            if !drawn && !scales.iter().any(|s| s.fits(len_of(j), dt_s)) {
                scales.push(ModeScales::new(&psd, dt_s, len_of(j), size.threads)?);
            }
        }
        let scales_for = |len: usize| -> Result<&ModeScales> {
            scales
                .iter()
                .find(|s| s.fits(len, dt_s))
                .ok_or_else(|| Error::Invalid {
                    param: "shared",
                    reason: "a shared piston sequence was dropped while in use".into(),
                })
        };
        // The sequences side by side (each its own seed: the same bits in
        // any order), on the run's threads.
        let segments = crate::montecarlo::in_pool(size.threads, || {
            use rayon::prelude::*;
            (0..k)
                .into_par_iter()
                .map(|j| {
                    let len = len_of(j);
                    let seed = sequence_seed(size.seed, j);
                    let draw = || scales_for(len)?.synthesize(seed, 0);
                    match shared {
                        Some(shared) => {
                            shared.get(spectrum, (seed, sequence_length(len), dt_s), draw)
                        }
                        None => Ok(Arc::new(draw()?)),
                    }
                })
                .collect::<Result<Vec<_>>>()
        })?;
        let period_samples = segments.iter().map(|s| s.len()).max().unwrap_or(0);
        Ok(PistonSequence {
            segments,
            first_scan,
            stride,
            samples: n,
            reference: setup.reference,
            first_sample: 0,
            period_samples,
            references: Vec::new(),
        }
        .with_references())
    }

    /// `observations` independent observations of `scans` consecutive
    /// scans each, `stride` samples apart (the scan and its dead time), in
    /// that order: observation j reads the start of its own sequence (seed
    /// [`sequence_seed`]`(size.seed, j)`), synthesized
    /// [`observation_sequence_samples`] long — [`OBSERVATION_SPAN`] times
    /// what the observation spans and at least [`SPAN_CORRELATION_TIMES`]
    /// correlation times, within [`MAX_SERIES`] — of which only the
    /// stretch the scans read is kept. A sequence only as long as the scans
    /// is periodic over them, so the piston's drift over the observation
    /// is forced to zero: measured on 64 scans of 0.145 s (1 m/s over 1.8 m
    /// apertures 18 m apart, B/v = 18 s), the variance of their mean V1²
    /// came out 300 times below that of 64 consecutive scans of a long
    /// sequence; at a bright K setting with n = 8 000 scans, the piston σ
    /// of the observation 3.4 times below.
    pub(crate) fn synthesize_observations(
        spectrum: &PistonSpectrum,
        setup: &ScanSetup,
        (observations, scans, stride): (usize, usize, usize),
        (seed, threads): (u64, usize),
    ) -> Result<Self> {
        let psd = |nu: f64| spectrum.psd_um2_per_hz(nu);
        let n = setup.samples;
        let read = (scans - 1) * stride + n + 4;
        let long = observation_sequence_samples(spectrum, setup, read);
        let mut segments = Vec::with_capacity(observations);
        let mut period = 0;
        let scales = ModeScales::new(&psd, setup.sample_time_s(), long, threads)?;
        for j in 0..observations {
            let series = scales.synthesize(sequence_seed(seed, j), threads)?;
            let m = series.len();
            period = period.max(m);
            // The stretch read, with the two samples before its start (the
            // cubic of the first sample reads one before it).
            let mut kept = Vec::with_capacity(read + OBSERVATION_LEAD);
            kept.extend_from_slice(&series[m - OBSERVATION_LEAD..]);
            kept.extend_from_slice(&series[..read.min(m)]);
            segments.push(Arc::new(kept));
        }
        Ok(PistonSequence {
            segments,
            first_scan: (0..=observations).map(|j| j * scans).collect(),
            stride,
            samples: n,
            reference: setup.reference,
            first_sample: OBSERVATION_LEAD,
            period_samples: period,
            references: Vec::new(),
        }
        .with_references())
    }

    /// Number of independent sequences.
    pub(crate) fn sequences(&self) -> usize {
        self.segments.len()
    }

    /// The scans of sequence `j`.
    pub(crate) fn scans_of(&self, j: usize) -> std::ops::Range<usize> {
        self.first_scan[j]..self.first_scan[j + 1]
    }

    /// Samples from the start of one scan to the start of the next in a
    /// sequence.
    pub(crate) fn stride(&self) -> usize {
        self.stride
    }

    /// Samples of the longest periodic sequence synthesized (the piston's
    /// slowest wander is at one over this).
    pub(crate) fn period_samples(&self) -> usize {
        self.period_samples
    }

    /// Where scan `local` of a sequence starts in its segment.
    fn start_of(&self, local: usize) -> usize {
        self.first_sample + local * self.stride
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
        let m: usize = self.segments.iter().map(|s| s.len()).sum();
        let sum2: f64 = self
            .segments
            .iter()
            .flat_map(|s| s.iter())
            .map(|p| p * p)
            .sum();
        (sum2 / m as f64).sqrt()
    }

    /// The piston removed from scan `s`, µm.
    pub(crate) fn reference_um(&self, s: usize) -> f64 {
        self.references[s]
    }

    /// This sequence with the piston removed from each scan measured.
    fn with_references(mut self) -> Self {
        let scans = self.first_scan[self.sequences()];
        self.references = (0..scans).map(|s| self.measure_reference(s)).collect();
        self
    }

    /// The piston removed from scan `s`, µm, measured on its samples.
    fn measure_reference(&self, s: usize) -> f64 {
        let (series, local) = self.locate(s);
        let (n, base) = (self.samples, self.start_of(local));
        match self.reference {
            PistonReference::Centre => series[base + n / 2],
            PistonReference::Mean => series[base..base + n].iter().sum::<f64>() / n as f64,
            PistonReference::Absolute => 0.0,
        }
    }

    /// The piston of scan `s` (µm) as a function of τ, sample intervals
    /// from the scan's start; its sequence is located once, not at each
    /// sample.
    pub(crate) fn of_scan(&self, s: usize) -> impl Fn(f64) -> f64 + '_ {
        let (series, local) = self.locate(s);
        let start = self.start_of(local) as f64;
        move |tau| interp(series, start + tau)
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
            let start = self.start_of(local);
            // The scan's samples and the one after it, wrapping round the
            // period only when they reach its end (a division a sample
            // otherwise).
            let at = |i: usize| if i < m { series[i] } else { series[i % m] };
            for j in 0..=n + 1 {
                let d = at(start + j) - r;
                excursion = excursion.max(d.abs());
                if j < n {
                    resid2 += d * d;
                }
            }
            let prev = series[(start + m - 1) % m] - r;
            excursion = excursion.max(prev.abs());
        }
        (excursion, (resid2 / (scans * n) as f64).sqrt())
    }
}

/// The piston sequences of several runs under one sky, shared: a sequence
/// is drawn once per spectrum, seed, FFT length and step, and read by every
/// run that asks for the same (a planner's strokes at one fringe frequency,
/// keyed by that frequency, read one atmosphere).
///
/// The sequence a run reads depends only on what it asks for, not on which
/// runs asked before or on how many threads, so the answer has the same
/// bits whatever the order, and the bits a run has alone. No lock is held
/// while a sequence is drawn (the draw runs on the thread pool, whose
/// waiting workers take up other work, a run asking for the same sequence
/// among it): two runs asking for one sequence at once may both draw it,
/// and the first kept is read by both. Clones share the sequences; they
/// are freed when the last clone is dropped (a planner keeps one
/// frequency's at a time: they hold up to [`MAX_SERIES`] samples per run).
#[derive(Debug, Clone, Default)]
pub struct SharedSequences {
    drawn: Arc<Mutex<Vec<SharedSequence>>>,
}

/// What a shared sequence is drawn from: the spectrum, the seed, the FFT
/// length and the step (s).
type SequenceKey = (PistonSpectrum, u64, usize, f64);

/// One shared sequence and what it was drawn from.
type SharedSequence = (SequenceKey, Arc<Vec<f64>>);

impl SharedSequences {
    /// No sequence yet.
    pub fn new() -> SharedSequences {
        SharedSequences::default()
    }

    /// The sequence of `spectrum` from `(seed, FFT length, step)` among
    /// `drawn`, if there.
    fn find_in(
        drawn: &[SharedSequence],
        spectrum: &PistonSpectrum,
        key: (u64, usize, f64),
    ) -> Option<Arc<Vec<f64>>> {
        drawn
            .iter()
            .find(|((sp, s, m, dt), _)| (*s, *m, *dt) == key && sp == spectrum)
            .map(|(_, sequence)| sequence.clone())
    }

    /// The sequence of `spectrum` from `(seed, FFT length, step)`, if drawn.
    fn find(&self, spectrum: &PistonSpectrum, key: (u64, usize, f64)) -> Option<Arc<Vec<f64>>> {
        let drawn = self.drawn.lock().unwrap_or_else(|e| e.into_inner());
        Self::find_in(&drawn, spectrum, key)
    }

    /// Whether the sequence of `spectrum` from `(seed, FFT length, step)`
    /// is drawn already.
    fn has(&self, spectrum: &PistonSpectrum, key: (u64, usize, f64)) -> bool {
        self.find(spectrum, key).is_some()
    }

    /// The sequence of `spectrum` from `(seed, FFT length, step)`: the one
    /// drawn before, or `draw()`'s (which must draw exactly that).
    fn get(
        &self,
        spectrum: &PistonSpectrum,
        key: (u64, usize, f64),
        draw: impl FnOnce() -> Result<Vec<f64>>,
    ) -> Result<Arc<Vec<f64>>> {
        if let Some(sequence) = self.find(spectrum, key) {
            return Ok(sequence);
        }
        let made = Arc::new(draw()?);
        let mut drawn = self.drawn.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(first) = Self::find_in(&drawn, spectrum, key) {
            return Ok(first);
        }
        let (seed, m, dt_s) = key;
        drawn.push(((spectrum.clone(), seed, m, dt_s), made.clone()));
        Ok(made)
    }
}
