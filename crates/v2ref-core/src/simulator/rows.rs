//! The rows of a set: one noisy interferogram per scan, with every effect
//! at once.
//!
//! Row s holds the modulated samples `M_i = I_i − c_i` of scan s in DFT
//! order ([`crate::formalism::interferogram::Sampling::opd_um`]):
//!
//! 1. the noise-free modulated signal: the model's `m_i` (photons · V ·
//!    fringe of the source through the spectrum, dispersion and detector),
//!    or, with piston, the same fringe read at the OPD of each sample of
//!    scan s through the differential-piston sequence
//!    ([`crate::piston::scan`]);
//! 2. the counts `I_i`: Poisson of mean `c_i + m_i` with photon noise
//!    (else `c_i + m_i`), plus Gaussian read noise `σ_det`.
//!
//! Randomness: the noise of the rows of work unit u (rows
//! `u·ROWS_PER_UNIT …`) comes from the generator of (seed, u); the piston
//! sequence of the whole set from [`piston::sweep_seed`]`(seed, f)`, laid
//! out in time as [`RowLayout`] says (independent sequences by default, one
//! contiguous observation with [`Model::rows_in`]). Without
//! piston the draws are exactly those of `v2ref simulate`
//! ([`crate::noise::simulation::simulate_noisy`]); with piston and no noise
//! the rows are those of `v2ref piston` at the same seed.

use crate::bounds::check_index;
use crate::error::{Error, Result};
use crate::montecarlo::{fold_units, run_unit_range, try_run_unit_range, Rng};
use crate::noise::simulation::{NoisySpec, SampleNoise, TRIALS_PER_UNIT};
use crate::piston::fringe_table::FringeTable;
use crate::piston::scan::{fill_scan, ScanSetup};
use crate::piston::sequences::PistonSequence;
use crate::piston::simulation::{table_range_um, validate_size};
use crate::piston::{self, RunSize};
use crate::simulator::{Model, RowLayout, RowTiming, SetLayout};

/// Rows per work unit (that of `simulate`, so that a noise-only set draws
/// what `simulate` draws).
pub const ROWS_PER_UNIT: u64 = TRIALS_PER_UNIT;

/// The scans through the piston of one set.
struct PistonScans {
    timing: RowTiming,
    sequence: PistonSequence,
    table: std::sync::Arc<FringeTable>,
    setup: ScanSetup,
    sub: (Vec<f64>, Vec<f64>),
    /// photons · V: the modulated signal per unit fringe.
    scale: f64,
    residual_rms_um: f64,
    /// The piston's correlation time B/v, s.
    spectrum_time_s: f64,
}

/// What a set's piston was.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct PistonFacts {
    /// f, Hz.
    pub fringe_hz: f64,
    /// The seed of the piston sequence.
    pub sequence_seed: u64,
    /// Duration of one scan, s.
    pub scan_time_s: f64,
    /// RMS of the piston sequence, µm.
    pub piston_rms_um: f64,
    /// RMS of the piston left in the scans after the reference is removed, µm.
    pub residual_rms_um: f64,
}

/// How a set's rows are cut from the piston sequences: a layout `synth`
/// names, or the planner's explicit `(sequences, stride)`.
#[derive(Clone, Copy)]
enum Layout {
    Named(RowTiming),
    Explicit(usize, usize),
}

/// A set of `rows` rows of one model from one seed.
pub struct Rows<'a> {
    model: &'a Model,
    rows: u64,
    seed: u64,
    /// The draws without piston (the modulated signal is the same in every row).
    fixed: Option<SampleNoise>,
    piston: Option<PistonScans>,
}

impl Model {
    /// The set of `rows` rows (≥ 1) from `seed`; `threads` synthesizes the
    /// piston sequence (the rows do not depend on it).
    ///
    /// # Example
    ///
    /// ```
    /// use v2ref_core::simulator::{Inputs, Model};
    /// let model = Model::new(&Inputs { samples: 16, ..Inputs::default() })?;
    /// let set = model.rows(3, 7, 1)?;
    /// let mut rows = Vec::new();
    /// set.fill_unit(0, &mut v2ref_core::montecarlo::unit_rng(7, 0), &mut rows)?;
    /// assert_eq!(rows.len(), 3 * 16);
    /// # Ok::<(), v2ref_core::Error>(())
    /// ```
    pub fn rows(&self, rows: u64, seed: u64, threads: usize) -> Result<Rows<'_>> {
        self.rows_in(RowLayout::Sequences, rows, seed, threads)
    }

    /// [`Model::rows`] laid out in time as `layout` says (a [`RowLayout`],
    /// or a [`RowTiming`] with the observations and the dead time); the
    /// same rows in the default [`RowLayout::Sequences`]; the layout changes
    /// nothing without piston.
    pub fn rows_in(
        &self,
        layout: impl Into<RowTiming>,
        rows: u64,
        seed: u64,
        threads: usize,
    ) -> Result<Rows<'_>> {
        self.rows_laid_out(Layout::Named(layout.into()), rows, seed, threads)
    }

    /// [`Model::rows`] with the piston layout given, `(sequences,
    /// stride)`: the rows are cut from that many independent sequences
    /// (shared out as the independent-sequence layout shares them) whose
    /// scans start `stride` samples apart (the scan period: an
    /// observation's consecutive scans). The caller keeps all the sequences
    /// within [`crate::piston::series::MAX_SERIES`] samples.
    pub fn rows_with_layout(
        &self,
        rows: u64,
        seed: u64,
        threads: usize,
        layout: Option<(usize, usize)>,
    ) -> Result<Rows<'_>> {
        let layout = match layout {
            None => Layout::Named(RowLayout::Sequences.into()),
            Some((sequences, stride)) => Layout::Explicit(sequences, stride),
        };
        self.rows_laid_out(layout, rows, seed, threads)
    }

    fn rows_laid_out(
        &self,
        layout: Layout,
        rows: u64,
        seed: u64,
        threads: usize,
    ) -> Result<Rows<'_>> {
        if rows == 0 {
            return Err(Error::OutOfRange {
                param: "rows",
                value: 0.0,
                accepted: ">= 1".into(),
            });
        }
        let piston = match (&self.piston_spectrum, self.inputs.scan_setup()) {
            (Some(spectrum), Some(setup)) => {
                let size = RunSize {
                    scans: usize::try_from(rows).unwrap_or(usize::MAX),
                    seed: piston::sweep_seed(seed, setup.fringe_hz),
                    threads,
                };
                Some(self.piston_scans(spectrum, setup, &size, layout)?)
            }
            _ => None,
        };
        let fixed = match piston {
            Some(_) => None,
            None => Some(SampleNoise::new(&NoisySpec {
                modulated: self.signal.modulated.clone(),
                continuum: self.signal.continuum.clone(),
                noise: self.noise,
                bins: Vec::new(),
            })?),
        };
        Ok(Rows {
            model: self,
            rows,
            seed,
            fixed,
            piston,
        })
    }

    fn piston_scans(
        &self,
        spectrum: &crate::piston::spectrum::PistonSpectrum,
        setup: ScanSetup,
        size: &RunSize,
        layout: Layout,
    ) -> Result<PistonScans> {
        match layout {
            Layout::Explicit(..) => setup.validate()?,
            Layout::Named(t) if t.layout == RowLayout::Observation => setup.validate()?,
            Layout::Named(_) => {
                validate_size(&setup, size).map_err(|e| e.renamed("scans", "rows"))?
            }
        }
        // The spectrum's tables on the whole pool, not by the first
        // coefficient block while the others wait.
        crate::montecarlo::in_pool(size.threads, || {
            spectrum.tabulate();
            Ok(())
        })?;
        let sequence = match layout {
            Layout::Named(t) if t.layout == RowLayout::Observation => {
                let shape = observation_shape(&setup, t, size.scans)?;
                let seeds = (size.seed, size.threads);
                PistonSequence::synthesize_observations(spectrum, &setup, shape, seeds)?
            }
            Layout::Named(_) => {
                PistonSequence::synthesize(spectrum, &setup, size, self.shared_sequences())?
            }
            Layout::Explicit(sequences, stride) => PistonSequence::synthesize_layout(
                spectrum,
                &setup,
                size,
                (sequences, stride),
                self.shared_sequences(),
            )?,
        };
        let (excursion, residual_rms_um) = sequence.excursion_and_residual();
        let table = self.fringe_table(table_range_um(&setup, excursion)?)?;
        Ok(PistonScans {
            timing: match layout {
                Layout::Named(named) => named,
                // An observation's sequences read scan after scan: recorded
                // as the independent-sequence layout they generalize.
                Layout::Explicit(..) => RowLayout::Sequences.into(),
            },
            sequence,
            table,
            setup,
            sub: self.inputs.detector().sub_samples()?,
            scale: self.inputs.photons * self.inputs.visibility,
            residual_rms_um,
            spectrum_time_s: crate::piston::sequences::correlation_time_s(spectrum),
        })
    }
}

/// `(observations, scans of each, stride)` of the observation layout
/// `timing` for `rows` rows of `setup`: the rows shared evenly, the scans
/// one scan and its dead time apart, every kept stretch within
/// [`MAX_SERIES`](crate::piston::MAX_SERIES) samples together.
fn observation_shape(
    setup: &ScanSetup,
    timing: RowTiming,
    rows: usize,
) -> Result<(usize, usize, usize)> {
    let k = timing.observations as usize;
    if rows % k != 0 || rows / k < 2 {
        return Err(Error::Invalid {
            param: "observations",
            reason: format!(
                "{k}: must divide the rows ({rows}) into observations of at least 2 scans each"
            ),
        });
    }
    let scans = rows / k;
    let n = setup.samples;
    let dead = (timing.dead_time_s / setup.sample_time_s()).round();
    let most = crate::piston::MAX_SERIES as f64;
    let stride = n as f64 + dead;
    let kept = k as f64 * ((scans - 1) as f64 * stride + n as f64 + 6.0);
    if kept > most {
        return Err(Error::OutOfRange {
            param: "rows",
            value: rows as f64,
            accepted: format!(
                "observations whose piston fits in memory together: {k} x {scans} scans \
                 {stride} samples apart span {kept:.3e} samples, at most {most:.3e} \
                 (2^24) in one set; split them over sets of different seeds"
            ),
        });
    }
    Ok((k, scans, stride as usize))
}

impl Rows<'_> {
    /// The model.
    pub fn model(&self) -> &Model {
        self.model
    }

    /// Number of rows.
    pub fn rows(&self) -> u64 {
        self.rows
    }

    /// The seed.
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// N.
    pub fn samples(&self) -> usize {
        self.model.samples()
    }

    /// Number of work units.
    pub fn units(&self) -> u64 {
        self.rows.div_ceil(ROWS_PER_UNIT)
    }

    /// Rows in unit `u`; refuses ([`Error::OutOfRange`], parameter
    /// `unit`) a unit not among the set's [`Rows::units`].
    pub fn unit_rows(&self, u: u64) -> Result<u64> {
        check_index("unit", u, self.units(), "units")?;
        Ok(self.rows_of_own_unit(u))
    }

    /// Refuses (parameter `unit`) a range of units that ends beyond the
    /// set's (an empty range is accepted wherever it starts).
    fn check_unit_range(&self, range: &std::ops::Range<u64>) -> Result<()> {
        match range.is_empty() {
            true => Ok(()),
            false => check_index("unit", range.end - 1, self.units(), "units"),
        }
    }

    /// [`Rows::unit_rows`] of a unit known to be the set's.
    fn rows_of_own_unit(&self, u: u64) -> u64 {
        (self.rows - u * ROWS_PER_UNIT).min(ROWS_PER_UNIT)
    }

    /// Independent piston sequences the rows are cut from (1 without
    /// piston: the rows are then independent of each other).
    pub fn sequences(&self) -> usize {
        self.piston.as_ref().map_or(1, |p| p.sequence.sequences())
    }

    /// The piston sequence row `s` reads (0 without piston); refuses
    /// ([`Error::OutOfRange`], parameter `row`) a row not among the set's.
    pub fn sequence_of(&self, s: u64) -> Result<usize> {
        check_index("row", s, self.rows, "rows")?;
        Ok(self.sequence_of_own_row(s))
    }

    /// [`Rows::sequence_of`] of a row known to be the set's.
    pub(crate) fn sequence_of_own_row(&self, s: u64) -> usize {
        self.piston
            .as_ref()
            .map_or(0, |p| p.sequence.sequence_of(s as usize))
    }

    /// Whether the rows scan through a piston sequence ([`Rows::piston_facts`]
    /// without its cost: the facts measure every sequence).
    pub(crate) fn has_piston(&self) -> bool {
        self.piston.is_some()
    }

    /// The piston of the set, if any.
    pub fn piston_facts(&self) -> Option<PistonFacts> {
        self.piston.as_ref().map(|p| PistonFacts {
            fringe_hz: p.setup.fringe_hz,
            sequence_seed: piston::sweep_seed(self.seed, p.setup.fringe_hz),
            scan_time_s: p.setup.scan_time_s(),
            piston_rms_um: p.sequence.rms_um(),
            residual_rms_um: p.residual_rms_um,
        })
    }

    /// Where the rows lie in time through the piston (None without
    /// piston: the rows are then independent of each other).
    pub fn layout(&self) -> Option<SetLayout> {
        let p = self.piston.as_ref()?;
        let sequence = &p.sequence;
        let stride_samples = sequence.stride();
        let rows_per_sequence: Vec<u64> = (0..sequence.sequences())
            .map(|j| sequence.scans_of(j).len() as u64)
            .collect();
        let period = sequence.period_samples();
        let note = (p.timing.layout == RowLayout::Observation).then(|| {
            let scans = rows_per_sequence.first().copied().unwrap_or(0) as usize;
            super::layout::observation_note(
                p.spectrum_time_s,
                &p.setup,
                (scans, stride_samples),
                period,
            )
        });
        Some(SetLayout {
            layout: p.timing.layout,
            sequences: sequence.sequences(),
            rows_per_sequence,
            stride_samples,
            stride_s: stride_samples as f64 * p.setup.sample_time_s(),
            scan_time_s: p.setup.scan_time_s(),
            // Only in the observation layout (the default layout's sidecars,
            // golden vectors among them, stay as they were).
            sequence_samples: note.as_ref().map(|_| period as u64),
            note,
        })
    }

    /// The noise-free modulated samples of row `s` (with its piston),
    /// written to `out`.
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] naming `row` when `s` is not one of the set's
    /// [`Rows::rows`], and `out` when it does not hold N samples; nothing
    /// is written then.
    pub fn noise_free_row(&self, s: u64, out: &mut [f64]) -> Result<()> {
        check_index("row", s, self.rows, "rows")?;
        let n = self.samples();
        if out.len() != n {
            return Err(Error::OutOfRange {
                param: "out",
                value: out.len() as f64,
                accepted: format!("{n} values (the model's samples)"),
            });
        }
        self.fill_own_row(s, out);
        Ok(())
    }

    /// [`Rows::noise_free_row`] of a row known to be the set's into N values.
    fn fill_own_row(&self, s: u64, out: &mut [f64]) {
        match &self.piston {
            None => out.copy_from_slice(&self.model.signal.modulated),
            Some(p) => p.scan(s as usize, out),
        }
    }

    /// The noise-free modulated samples of a scan without piston, read the
    /// way the piston scans read the fringe (for differences that cancel
    /// the fringe table's own error); the model's `m_i` without piston.
    pub fn piston_free_row(&self) -> Vec<f64> {
        let mut out = vec![0.0; self.samples()];
        match &self.piston {
            None => out.copy_from_slice(&self.model.signal.modulated),
            Some(p) => {
                fill_scan(
                    &p.table,
                    &p.setup,
                    &p.sub.0,
                    &p.sub.1,
                    &|_| 0.0,
                    0.0,
                    &mut out,
                );
                out.iter_mut().for_each(|m| *m *= p.scale);
            }
        }
        out
    }

    /// Appends the rows of unit `u` (row-major) to `out`, drawing from
    /// `rng`, which must be the unit's generator (`unit_rng(seed, u)`);
    /// refuses ([`Error::OutOfRange`], parameter `unit`) a unit not among
    /// the set's [`Rows::units`], appending nothing.
    pub fn fill_unit(&self, u: u64, rng: &mut Rng, out: &mut Vec<f64>) -> Result<()> {
        check_index("unit", u, self.units(), "units")?;
        self.fill_own_unit(u, rng, out);
        Ok(())
    }

    /// [`Rows::fill_unit`] of a unit known to be the set's.
    fn fill_own_unit(&self, u: u64, rng: &mut Rng, out: &mut Vec<f64>) {
        let n = self.samples();
        let first = u * ROWS_PER_UNIT;
        for s in first..first + self.rows_of_own_unit(u) {
            let start = out.len();
            out.resize(start + n, 0.0);
            let row = &mut out[start..];
            match &self.fixed {
                Some(noise) => noise.draw(rng, row),
                None => {
                    self.fill_own_row(s, row);
                    self.add_noise(rng, row);
                }
            }
        }
    }

    /// `work(u, rows of unit u)` for each unit of `range`, in parallel on
    /// `threads` threads, results in unit order; the first error of `work`
    /// (a cancelled run) stops the others and is returned. Refuses
    /// (parameter `unit`) a range that reaches beyond the set's units.
    pub fn map_units<T: Send>(
        &self,
        range: std::ops::Range<u64>,
        threads: usize,
        work: impl Fn(u64, &[f64]) -> Result<T> + Sync + Send,
    ) -> Result<Vec<T>> {
        self.check_unit_range(&range)?;
        try_run_unit_range(self.seed, range, threads, |u, rng| {
            let mut rows = Vec::with_capacity(self.rows_of_own_unit(u) as usize * self.samples());
            self.fill_own_unit(u, rng, &mut rows);
            work(u, &rows)
        })
    }

    /// `work(rows of unit u)` for every unit, in parallel on `threads`
    /// threads, each result handed to `merge` in unit order; memory stays
    /// at one batch of units ([`fold_units`]) however many rows there are.
    /// The first error of `work` (a cancelled run) stops the run.
    pub fn fold_units<T: Send>(
        &self,
        threads: usize,
        work: impl Fn(u64, &[f64]) -> Result<T> + Sync + Send,
        merge: impl FnMut(T) + Send,
    ) -> Result<()> {
        self.fold_unit_range(0..self.units(), threads, work, merge)
    }

    /// [`Rows::fold_units`] over the units of `range` only (a run split
    /// over processes: unit u has the same rows whatever range it is in).
    pub(crate) fn fold_unit_range<T: Send>(
        &self,
        range: std::ops::Range<u64>,
        threads: usize,
        work: impl Fn(u64, &[f64]) -> Result<T> + Sync + Send,
        merge: impl FnMut(T) + Send,
    ) -> Result<()> {
        self.check_unit_range(&range)?;
        let unit = |u, rng: &mut Rng| {
            let mut rows = Vec::with_capacity(self.rows_of_own_unit(u) as usize * self.samples());
            self.fill_own_unit(u, rng, &mut rows);
            work(u * ROWS_PER_UNIT, &rows)
        };
        fold_units(self.seed, range, threads, unit, merge)
    }

    /// Hands every row to `sink` in row order, `batch` units at a time
    /// (generated in parallel on `threads` threads, so memory stays at
    /// about `batch · ROWS_PER_UNIT · N` values); stops at the first error
    /// of `sink`, or of the runner (a cancelled run: [`run_unit_range`]).
    pub fn stream(
        &self,
        threads: usize,
        batch: u64,
        mut sink: impl FnMut(&[f64]) -> Result<()>,
    ) -> Result<()> {
        let batch = batch.max(1);
        let mut first = 0;
        while first < self.units() {
            let last = (first + batch).min(self.units());
            // Each unit's rows handed over as generated (not copied).
            let blocks = run_unit_range(self.seed, first..last, threads, |u, rng| {
                let mut rows =
                    Vec::with_capacity(self.rows_of_own_unit(u) as usize * self.samples());
                self.fill_own_unit(u, rng, &mut rows);
                rows
            })?;
            for block in blocks {
                sink(&block)?;
            }
            first = last;
        }
        Ok(())
    }

    /// Photon and read noise on a row of varying modulated signal (the
    /// Poisson counts first, then the Gaussian read noise, as
    /// [`SampleNoise`] draws them).
    fn add_noise(&self, rng: &mut Rng, row: &mut [f64]) {
        use rand_distr::{Distribution, Poisson};
        let noise = &self.model.noise;
        if noise.photon {
            for (m, &c) in row.iter_mut().zip(&self.model.signal.continuum) {
                let mean = (c + *m).max(0.0);
                let count = match Poisson::new(mean) {
                    Ok(p) => p.sample(rng.rand_core()),
                    Err(_) => 0.0, // mean 0: no photon
                };
                *m = count - c;
            }
        }
        if noise.read_noise > 0.0 {
            for m in row.iter_mut() {
                let z: f64 = rng.standard_normal();
                *m += noise.read_noise * z;
            }
        }
    }
}

impl PistonScans {
    /// The noise-free modulated samples of scan `s`.
    fn scan(&self, s: usize, out: &mut [f64]) {
        let r = self.sequence.reference_um(s);
        let p = self.sequence.of_scan(s);
        fill_scan(
            &self.table,
            &self.setup,
            &self.sub.0,
            &self.sub.1,
            &p,
            r,
            out,
        );
        out.iter_mut().for_each(|m| *m *= self.scale);
    }
}
