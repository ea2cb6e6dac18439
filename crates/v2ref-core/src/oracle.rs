//! The oracle route: what a pipeline's own `cargo test` needs to hold its
//! V1²/V2² estimator to v2ref, all in memory — no file, no path into this
//! repository, no C compiler.
//!
//! 1. **A set in memory**: [`Set::synthesize`] makes noisy interferograms
//!    of any [`Inputs`] (rows as one row-major `Vec<f64>`, [`Set::rows`]
//!    one `&[f64]` each) and their [`Truth`] — the expected mean and
//!    variance of each estimator under every window of bins and bias
//!    convention, with the scatter a set of that size has.
//! 2. **The closed forms** of the same configuration: the bins of each
//!    window, the calibrator and the exact noise bias ([`WindowTruth`]),
//!    the exact mean and variance without piston ([`Set::closed_form`]),
//!    and v2ref's own per-row estimates ([`Set::reference_estimates`]), to
//!    compare a pipeline with row by row.
//! 3. **The score on slices**: [`Set::score`] takes the pipeline's
//!    per-row V1² and V2² and gives z-scores, the verdict at a family-wise
//!    false-alarm rate of [`DEFAULT_ALPHA`], and the power of the test
//!    (the smallest relative error it catches with probability 0.9).
//! 4. **The golden vectors**, regenerated bit for bit from their
//!    catalogue ([`Set::golden`]: the rows equal `golden/vectors/NAME.npy`,
//!    [`Set::sidecar_json`] equals `NAME.json`, byte for byte — the test
//!    suite checks both), and **sets with power** ([`Set::powered`]): the
//!    piston-free vectors made large enough to catch a 2 % error of either
//!    estimator's mean or variance.
//! 5. **A dispersed set** ([`Set::synthesize_channels`]): the scan in C
//!    spectral channels ([`Channels`]), rows of C × N values, a truth per
//!    channel ([`Set::expected_channel`]), v2ref's estimates per channel
//!    ([`Set::reference_channel_estimates`]) and one verdict over every
//!    channel at a family-wise rate ([`Set::score_channels`],
//!    [`ChannelScoreReport`]).
//!
//! ```
//! use v2ref_core::oracle::{BiasConvention, BinWindow, Estimates, Inputs, Set, SourceInput};
//!
//! // 2000 scans of 32 samples of a V = 0.6 point source in K, photon noise only.
//! let source = SourceInput::Point;
//! let inputs = Inputs { samples: 32, source, visibility: 0.6, photons: 50.0, ..Inputs::default() };
//! let set = Set::synthesize(&inputs, 2000, 7)?;
//!
//! // The pipeline under test: here v2ref's own estimator stands in for it.
//! let (window, bias) = (BinWindow::Positive, BiasConvention::Model);
//! let rows = set.reference_estimates(window, bias)?;
//! let v1_sq: Vec<f64> = rows.iter().map(|r| r.v1_sq).collect();
//! let v2_sq: Vec<f64> = rows.iter().map(|r| r.v2_sq).collect();
//!
//! let report = set.score(window, bias, Estimates::default().v1_sq(&v1_sq).v2_sq(&v2_sq))?;
//! assert!(report.pass, "{report}");
//! // The power of this set: the smallest relative error of the mean of V1² it catches.
//! let power = report.estimators[0].score.min_detectable_rel_bias_mean;
//! assert!(power < 0.05, "{power}");
//!
//! // A pipeline that forgets the photon-noise bias is rejected.
//! let divisor = set.closed_form(window)?.calibration.v1_sq;
//! let forgot: Vec<f64> = rows.iter().map(|r| r.v1_sq_raw / divisor).collect();
//! assert!(!set.score(window, bias, Estimates::default().v1_sq(&forgot))?.pass);
//! # Ok::<(), v2ref_core::Error>(())
//! ```

use crate::conformance::score::{critical_z, min_detectable_rel_bias, TESTS_PER_ESTIMATOR};
use crate::conformance::synth::{synthesize, SetSize};
use crate::conformance::truth::{default_reference_blocks, POOLED_MIN_ROWS};
use crate::conformance::vectors::{VECTOR_REFERENCE_BLOCKS, VECTOR_ROWS};
use crate::error::{Error, Result};
use crate::noise::calibrated::expectation;
use crate::simulator::RowLayout;

mod channels;

pub use crate::conformance::channel_score::{ChannelScore, ChannelScoreReport};
pub use crate::conformance::estimate::{
    BiasConvention, RowEstimate, RowEstimator, BIAS_CONVENTIONS,
};
pub use crate::conformance::score::{
    score_report, Estimates, EstimatorScore, NamedScore, ScoreReport, DEFAULT_ALPHA, POWER,
};
pub use crate::conformance::sidecar::ChannelSidecar;
pub use crate::conformance::sidecar::{
    ConventionTruth, EstimatorTruth, Sidecar, Truth, WindowTruth,
};
pub use crate::conformance::vectors::{catalogue, Vector};
pub use crate::formalism::channels::Channels;
pub use crate::formalism::estimator::{
    all_bins, band_bins, noise_bias, positive_bins, BinWindow, Pair, BIN_WINDOWS,
};
pub use crate::noise::calibrated::CalibratedExpectation;
pub use crate::noise::Formula;
pub use crate::simulator::{Inputs, Model, PistonInputs, SourceInput, SpectrumInput};

/// The relative error a powered set catches ([`Set::powered`]): 2 % of
/// either estimator's mean or variance, with probability [`POWER`], at
/// [`DEFAULT_ALPHA`].
pub const POWERED_REL_ERROR: f64 = 0.02;

/// The error a powered set's row count aims at: 5 % under
/// [`POWERED_REL_ERROR`], a margin for the pilot's and the set's own
/// estimates of the fourth moment (the error of a set's variance), which
/// differ by a few percent (`noise_both`, aimed at 2 %: 2.03 %).
const POWERED_AIM_REL: f64 = 0.95 * POWERED_REL_ERROR;

/// Reference blocks of a powered set: the default of a piston-free set
/// (its pool of `8 × rows` rows gives the truth's own error `1/√8` of a
/// set's, where there is no closed form).
const POWERED_REFERENCE_BLOCKS: u64 = 8;

/// Rows of the pilot truth [`powered_rows`] scales from: a set this large
/// has its reference pool grow with it, so every standard error of its
/// truth falls as `1/√rows` from here on.
const PILOT_ROWS: u64 = POOLED_MIN_ROWS / POWERED_REFERENCE_BLOCKS;

/// Rows of a powered set are a multiple of this (a round number to read
/// in the vectors' README).
const POWERED_ROWS_STEP: u64 = 1024;

/// A synth set in memory: the model, the rows and the sidecar (inputs,
/// sample positions, continuum, truth) that `v2ref synth` would write.
#[derive(Debug, Clone)]
pub struct Set {
    model: Model,
    values: Vec<f64>,
    sidecar: Sidecar,
    /// A dispersed set's channels and their models (None: wide band).
    dispersed: Option<channels::Dispersed>,
}

impl Set {
    /// `rows` scans of `inputs` drawn with `seed`, continuum subtracted
    /// (each row holds `M_i = I_i − c_i`), with the truth of a set of that
    /// size (the default reference run: 8 blocks, 16 with piston). The
    /// same bits as `v2ref synth` of the same inputs, rows and seed,
    /// whatever the thread count; refuses what `synth` refuses (invalid
    /// inputs, a set too small or too large) and a set whose values would
    /// take more than half the physical memory.
    pub fn synthesize(inputs: &Inputs, rows: u64, seed: u64) -> Result<Set> {
        let blocks = default_reference_blocks(inputs.piston.is_some());
        Set::synthesize_with_blocks(inputs, rows, seed, blocks, "set")
    }

    fn synthesize_with_blocks(
        inputs: &Inputs,
        rows: u64,
        seed: u64,
        reference_blocks: u64,
        name: &str,
    ) -> Result<Set> {
        let model = Model::new(inputs)?;
        crate::bounds::check_set_size(rows, inputs.samples, reference_blocks)?;
        check_set_memory(rows, inputs.samples)?;
        let size = SetSize {
            rows,
            seed,
            reference_blocks,
            threads: 0,
            keep_continuum: false,
            layout: RowLayout::default().into(),
        };
        let mut values = Vec::new();
        let count = (rows * inputs.samples as u64) as usize; // at most SET_MAX_VALUES
        let what = || format!("values of {rows} rows of {} samples", inputs.samples);
        crate::bounds::reserve(&mut values, count, "rows", &what)?;
        let mut sink = |block: &[f64]| {
            values.extend_from_slice(block);
            Ok(())
        };
        let names = (format!("{name}.npy"), None);
        let sidecar = synthesize(&model, &size, names, &mut sink, &|_| {})?;
        Ok(Set {
            model,
            values,
            sidecar,
            dispersed: None,
        })
    }

    /// The golden vector `name` (one of [`catalogue`]), regenerated in
    /// memory: its rows are bit for bit those of `golden/vectors/NAME.npy`
    /// and [`Set::sidecar_json`] is byte for byte `NAME.json`. Refuses a
    /// name not in the catalogue, listing those that are.
    ///
    /// ```
    /// let set = v2ref_core::oracle::Set::golden("short_scan_odd")?;
    /// assert_eq!((set.len(), set.samples()), (1000, 25));
    /// # Ok::<(), v2ref_core::Error>(())
    /// ```
    pub fn golden(name: &str) -> Result<Set> {
        let v = vector(name)?;
        Set::synthesize_with_blocks(
            &v.inputs,
            VECTOR_ROWS,
            v.seed,
            VECTOR_REFERENCE_BLOCKS,
            name,
        )
    }

    /// The piston-free golden vector `name` made large enough to catch a
    /// [`POWERED_REL_ERROR`] (2 %) error of the mean or the variance of
    /// either estimator, over every window and bias convention of its
    /// truth: [`powered_rows`] rows, the vector's seed, 8 reference blocks.
    /// Refuses a vector with piston (its truth needs replicates of the
    /// whole set: 16 times the rows again) and a name not in the catalogue.
    pub fn powered(name: &str) -> Result<Set> {
        let v = vector(name)?;
        let rows = powered_rows(&v)?;
        Set::synthesize_with_blocks(&v.inputs, rows, v.seed, POWERED_REFERENCE_BLOCKS, name)
    }

    /// The model the rows were drawn from.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The sidecar: every input, the sample positions, the continuum, the
    /// mean counts and the truth.
    pub fn sidecar(&self) -> &Sidecar {
        &self.sidecar
    }

    /// The sidecar as `v2ref synth` writes it (pretty JSON, a final
    /// newline).
    pub fn sidecar_json(&self) -> String {
        // A Sidecar is numbers, strings and enums: serializing cannot fail.
        serde_json::to_string_pretty(&self.sidecar).expect("a sidecar serializes") + "\n"
    }

    /// The truth of the set.
    pub fn truth(&self) -> &Truth {
        &self.sidecar.truth
    }

    /// N, samples per row (per channel in a dispersed set).
    pub fn samples(&self) -> usize {
        self.model.samples()
    }

    /// Values per row: C × N ([`Set::channels`] × [`Set::samples`]).
    fn row_len(&self) -> usize {
        self.channels() * self.samples()
    }

    /// Rows (scans).
    pub fn len(&self) -> usize {
        self.values.len() / self.row_len()
    }

    /// Whether the set has no row.
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// Every value, row-major (`channels() × samples()` per row, channel
    /// after channel).
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The rows, one slice of `channels() × samples()` values each
    /// (channel j's samples at `j·N … (j+1)·N`).
    pub fn rows(&self) -> std::slice::ChunksExact<'_, f64> {
        self.values.chunks_exact(self.row_len())
    }

    /// The calibrator's noise-free row `m_i`, photons: what a point source
    /// of visibility 1 gives through the set's instrument (same photons,
    /// band, sampling and detector; no dispersion, no piston). A pipeline
    /// normalizes by its own raw V1² and V2² over its own bins; v2ref's
    /// divisors over each window are [`WindowTruth::calibration`].
    pub fn calibrator_row(&self) -> &[f64] {
        &self.model.calibrator.modulated
    }

    /// `n_i = c_i + m_i`, the noise-free mean count of each sample without
    /// piston, photons (what the `model` bias convention uses).
    pub fn mean_counts(&self) -> &[f64] {
        &self.sidecar.mean_counts_photons
    }

    /// The truth of `window` under `bias`; refuses one the truth lacks (a
    /// window whose calibrator has no fringe), and a dispersed set of more
    /// than one channel ([`Set::expected_channel`]).
    pub fn expected(&self, window: BinWindow, bias: BiasConvention) -> Result<&ConventionTruth> {
        self.check_wide_band()?;
        self.sidecar.truth(window, bias).ok_or_else(|| Error::Invalid {
            param: "window",
            reason: format!(
                "the set has no truth for the {} window under the {} convention (its calibrator has no fringe in those bins)",
                window.name(),
                bias.name()
            ),
        })
    }

    /// The window's closed forms without piston: bins, calibrator, exact
    /// noise bias, and the exact mean and variance of both normalized
    /// estimators under the `model` convention.
    pub fn closed_form(&self, window: BinWindow) -> Result<CalibratedExpectation> {
        let setup = self.model.calibrated_setup(window);
        expectation(&setup, &self.model.noise, Formula::Exact)
    }

    /// v2ref's own per-row estimates of the set under `window` and `bias`;
    /// refuses a dispersed set of more than one channel
    /// ([`Set::reference_channel_estimates`]).
    pub fn reference_estimates(
        &self,
        window: BinWindow,
        bias: BiasConvention,
    ) -> Result<Vec<RowEstimate>> {
        self.check_wide_band()?;
        RowEstimator::new(&self.model, window, bias, true)?.estimate_rows(&self.values, 0)
    }

    /// Scores a pipeline's per-row V1² and V2² (each named in
    /// `estimates`, either or both; one value per row, in row order)
    /// against the truth of `window` under `bias`, at [`DEFAULT_ALPHA`]
    /// shared by the tests made. Refuses estimates with neither, and a
    /// dispersed set of more than one channel ([`Set::score_channels`]).
    pub fn score(
        &self,
        window: BinWindow,
        bias: BiasConvention,
        estimates: Estimates<'_>,
    ) -> Result<ScoreReport> {
        let truth = self.expected(window, bias)?;
        let rows = self.len() as u64;
        score_report(estimates.v1_sq, estimates.v2_sq, truth, rows, DEFAULT_ALPHA)
    }
}

/// Refuses a set whose values (`rows × samples` float64, held in memory)
/// would take more than half the physical memory: the allocation would
/// otherwise abort the process, or swap for hours.
fn check_set_memory(rows: u64, samples: usize) -> Result<()> {
    let need = rows.saturating_mul(samples as u64).saturating_mul(8);
    let Some(budget) = physical_memory().map(|m| m / 2) else {
        return Ok(());
    };
    if need <= budget {
        return Ok(());
    }
    let gib = |b: u64| b as f64 / (1u64 << 30) as f64;
    Err(Error::Invalid {
        param: "rows",
        reason: format!(
            "{rows} rows of {samples} samples take {:.2} GiB, more than half the physical memory ({:.2} GiB); make the set smaller",
            gib(need),
            gib(budget)
        ),
    })
}

/// The machine's physical memory, bytes (None where unknown).
#[cfg(unix)]
fn physical_memory() -> Option<u64> {
    // SAFETY: sysconf only reads a system constant.
    let (pages, size) = unsafe {
        (
            libc::sysconf(libc::_SC_PHYS_PAGES),
            libc::sysconf(libc::_SC_PAGESIZE),
        )
    };
    u64::try_from(pages)
        .ok()?
        .checked_mul(u64::try_from(size).ok()?)
}

#[cfg(not(unix))]
fn physical_memory() -> Option<u64> {
    None
}

/// The catalogue's vector `name`.
fn vector(name: &str) -> Result<Vector> {
    let all = catalogue();
    let names: Vec<&str> = all.iter().map(|v| v.name).collect();
    let listed = names.join(", ");
    all.into_iter()
        .find(|v| v.name == name)
        .ok_or_else(|| Error::Invalid {
            param: "name",
            reason: format!("no vector {name:?}; the vectors are {listed}"),
        })
}

/// The power of a truth: the largest smallest-detectable relative error
/// over every window, convention, estimator, mean and variance, when both
/// estimators are scored together at [`DEFAULT_ALPHA`]; None if any lacks
/// the error of a set's variance.
pub fn worst_min_detectable(truth: &Truth) -> Result<Option<f64>> {
    let z_crit = critical_z(DEFAULT_ALPHA, 2 * TESTS_PER_ESTIMATOR)?;
    let mut worst: f64 = 0.0;
    for c in truth.windows.iter().flat_map(|w| &w.conventions) {
        for t in [&c.v1_sq, &c.v2_sq] {
            let Some((mean, var)) = min_detectable_rel_bias(t, z_crit) else {
                return Ok(None);
            };
            worst = worst.max(mean).max(var);
        }
    }
    Ok(Some(worst))
}

/// Rows a powered set of `vector` needs ([`Set::powered`]): its truth at
/// a pilot size (8192 rows, a pool of 65 536) gives the worst smallest
/// detectable error `e`; every standard error of a piston-free truth falls
/// as `1/√rows` beyond it, so `8192 (e/1.9 %)²` rows, rounded up to a
/// multiple of 1024, bring it to 1.9 %, under 2 % with a margin for the
/// fourth moments estimated by the pilot and by the set. Refuses a vector
/// with piston.
pub fn powered_rows(vector: &Vector) -> Result<u64> {
    if vector.inputs.piston.is_some() {
        return Err(Error::Invalid {
            param: "name",
            reason: format!(
                "{} has piston: its truth needs replicates of the whole set, so a powered set is not made; the piston-free vectors are",
                vector.name
            ) + &piston_free_names(),
        });
    }
    let model = Model::new(&vector.inputs)?;
    let size = crate::conformance::truth::TruthSize {
        rows: PILOT_ROWS,
        seed: vector.seed,
        reference_blocks: POWERED_REFERENCE_BLOCKS,
        threads: 0,
    };
    let truth = crate::conformance::truth::truth(&model, size, &|_| {})?;
    let worst = worst_min_detectable(&truth)?.ok_or_else(|| Error::Invalid {
        param: "name",
        reason: format!(
            "{}: the pilot truth has no error of a set's variance",
            vector.name
        ),
    })?;
    let rows = (PILOT_ROWS as f64 * (worst / POWERED_AIM_REL).powi(2)).ceil() as u64;
    Ok(rows.max(PILOT_ROWS).div_ceil(POWERED_ROWS_STEP) * POWERED_ROWS_STEP)
}

fn piston_free_names() -> String {
    let names: Vec<&str> = catalogue()
        .into_iter()
        .filter(|v| v.inputs.piston.is_none())
        .map(|v| v.name)
        .collect();
    format!(" {}", names.join(", "))
}
