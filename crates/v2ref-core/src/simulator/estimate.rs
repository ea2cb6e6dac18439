//! Per-row estimates: what a pipeline computes from each interferogram.
//!
//! For a row of N modulated samples `M_i` (the counts minus the continuum
//! c_i), with `B_k = Σ_i M_i e^{−2πi ik/N}` and a window K of bins:
//!
//! - raw: `V1²_raw = Σ_{k∈K} |B_k|²`, `V2²_raw = |Σ_{k∈K} B_k|²`;
//! - bias: with `v_i` the noise variance of sample i,
//!   `b1 = |K| Σ_i v_i` and `b2 = Σ_i |u_i|² v_i`, `u_i = Σ_{k∈K} e^{−2πi ik/N}`
//!   (the exact additive-noise bias of each, [`noise_bias`](crate::formalism::estimator::noise_bias));
//! - normalized: `(raw − bias) / C`, C the calibrator's noise-free raw
//!   estimate over the same window, so that an unbiased estimator of a
//!   source of visibility V has mean V².
//!
//! `v_i` is `σ_det² + n_i` with photon noise and `σ_det²` without, where
//! n_i is the sample's mean count. The [`BiasConvention`] says where n_i
//! comes from: the model's noise-free counts (`c_i + m_i`), or the row's own
//! counts (`c_i + M_i`, an unbiased estimate of n_i that needs no model of
//! the source).
//!
//! [`RowEstimator`] is the fast path; [`estimate_row_oracle`] is the slow,
//! obviously correct one (naive DFT, bias by its definition) that the tests
//! hold it to.

use crate::error::{Error, Result};
use crate::formalism::estimator::{dft_phase, noise_bias_sums, raw_sums, BinWindow, Pair};
use crate::formalism::oracle::naive_dft;
use crate::noise::simulation::WindowedEstimators;
use crate::simulator::Model;
use num_complex::Complex64;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// Where the photon-noise bias takes the mean counts n_i from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
pub enum BiasConvention {
    /// The model's noise-free counts `n_i = c_i + m_i` (exact for a known
    /// source without piston). With piston (`--fringe-hz`) it is biased:
    /// the piston moves the fringe packet within each scan, so the counts
    /// a row holds are `c_i + m_i(piston)`, not the piston-free `m_i` this
    /// convention uses, and the photon-noise bias it subtracts is off by
    /// the difference (1.5e-4 on V1² in a 0.7 µm, 50 nm case on 50 m, 5
    /// standard errors). Use [`BiasConvention::Counts`] with piston.
    Model,
    /// Each row's own counts `c_i + M_i` (needs no source model).
    Counts,
}

impl crate::words::Words for BiasConvention {
    const WORDS: &'static [crate::words::Word<Self>] = &[
        crate::words::Word {
            word: "model",
            value: BiasConvention::Model,
            help: "The model's noise-free counts `n_i = c_i + m_i` (exact for a known source without piston). With piston (`--fringe-hz`) it is biased: the piston moves the fringe packet within each scan, so the counts a row holds are `c_i + m_i(piston)`, not the piston-free `m_i` this convention uses, and the photon-noise bias it subtracts is off by the difference (1.5e-4 on V1² in a 0.7 µm, 50 nm case on 50 m, 5 standard errors). Use [`BiasConvention::Counts`] with piston",
        },
        crate::words::Word {
            word: "counts",
            value: BiasConvention::Counts,
            help: "Each row's own counts `c_i + M_i` (needs no source model)",
        },
    ];
}

/// Both conventions, in the order the sidecar lists them.
pub const BIAS_CONVENTIONS: [BiasConvention; 2] = [BiasConvention::Model, BiasConvention::Counts];

impl BiasConvention {
    /// Lowercase name.
    pub fn name(&self) -> &'static str {
        crate::words::Words::word(*self)
    }
}

/// One row's estimates.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct RowEstimate {
    /// `Σ_K |B_k|²`, photons².
    pub v1_sq_raw: f64,
    /// `|Σ_K B_k|²`, photons².
    pub v2_sq_raw: f64,
    /// The noise bias subtracted from V1², photons².
    pub v1_sq_bias: f64,
    /// The noise bias subtracted from V2², photons².
    pub v2_sq_bias: f64,
    /// `(V1²_raw − b1) / C1`.
    pub v1_sq: f64,
    /// `(V2²_raw − b2) / C2`.
    pub v2_sq: f64,
}

/// The columns of a row's estimates, in the order of
/// [`RowEstimate::values`] (the CLI's CSV header, Python's
/// `ESTIMATE_COLUMNS`).
pub const ESTIMATE_COLUMNS: [&str; 6] = [
    "v1_sq_raw",
    "v2_sq_raw",
    "v1_sq_bias",
    "v2_sq_bias",
    "v1_sq",
    "v2_sq",
];

impl RowEstimate {
    /// The six values in [`ESTIMATE_COLUMNS`] order.
    pub fn values(&self) -> [f64; 6] {
        [
            self.v1_sq_raw,
            self.v2_sq_raw,
            self.v1_sq_bias,
            self.v2_sq_bias,
            self.v1_sq,
            self.v2_sq,
        ]
    }

    fn new(raw: Pair, bias: Pair, calibration: Pair) -> RowEstimate {
        RowEstimate {
            v1_sq_raw: raw.v1_sq,
            v2_sq_raw: raw.v2_sq,
            v1_sq_bias: bias.v1_sq,
            v2_sq_bias: bias.v2_sq,
            v1_sq: (raw.v1_sq - bias.v1_sq) / calibration.v1_sq,
            v2_sq: (raw.v2_sq - bias.v2_sq) / calibration.v2_sq,
        }
    }
}

/// `|u_i|²` with `u_i = Σ_{k∈K} e^{−2πi ik/N}`: the weight of sample i's
/// variance in the bias of V2².
pub fn v2_bias_kernel(n: usize, bins: &[usize]) -> Vec<f64> {
    (0..n)
        .map(|i| {
            bins.iter()
                .map(|&k| Complex64::from_polar(1.0, dft_phase(i, k, n)))
                .sum::<Complex64>()
                .norm_sqr()
        })
        .collect()
}

/// Per-row estimates of one configuration, window, convention and
/// calibration.
#[derive(Debug, Clone)]
pub struct RowEstimator {
    windowed: WindowedEstimators,
    bins: usize,
    kernel: Vec<f64>,
    read_var: f64,
    photon: bool,
    continuum: Vec<f64>,
    continuum_subtracted: bool,
    bias: BiasConvention,
    model_bias: Pair,
    calibration: Pair,
}

impl RowEstimator {
    /// The estimator of `model`'s rows over `window` with the `bias`
    /// convention, normalized by the model's calibrator; rows hold
    /// `M_i = I_i − c_i` when `continuum_subtracted`, the counts `I_i`
    /// otherwise.
    ///
    /// # Example
    ///
    /// ```
    /// use v2ref_core::conformance::estimate::{BiasConvention, RowEstimator};
    /// use v2ref_core::formalism::estimator::BinWindow;
    /// use v2ref_core::simulator::{Inputs, Model};
    /// let model = Model::new(&Inputs::default())?;
    /// let est = RowEstimator::new(&model, BinWindow::Positive, BiasConvention::Model, true)?;
    /// // The noise-free row of the source reads its noise-free V² once the bias is added back.
    /// let e = est.estimate(&model.signal.modulated)?;
    /// assert!(e.v1_sq_raw > 0.0 && e.v1_sq < 1.0);
    /// # Ok::<(), v2ref_core::Error>(())
    /// ```
    pub fn new(
        model: &Model,
        window: BinWindow,
        bias: BiasConvention,
        continuum_subtracted: bool,
    ) -> Result<RowEstimator> {
        let calibration = model.calibrated_setup(window).calibration()?;
        let bins = model.bins(window);
        let n = model.samples();
        Ok(RowEstimator {
            windowed: WindowedEstimators::new(n, &bins),
            bins: bins.len(),
            kernel: v2_bias_kernel(n, &bins),
            read_var: model.noise.read_noise * model.noise.read_noise,
            photon: model.noise.photon,
            continuum: model.signal.continuum.clone(),
            continuum_subtracted,
            bias,
            model_bias: noise_bias_sums(&model.sample_variance(), &bins),
            calibration,
        })
    }

    /// The same estimator normalized by `calibration` (raw units) instead.
    pub fn with_calibration(self, calibration: Pair) -> Result<RowEstimator> {
        let usable = |c: f64| c > 0.0 && c.is_finite();
        if !(usable(calibration.v1_sq) && usable(calibration.v2_sq)) {
            return Err(Error::Invalid {
                param: "calibrator",
                reason: format!(
                    "the calibrator's bias-subtracted estimates ({}, {}) are not finite and > 0: nothing to normalize by",
                    calibration.v1_sq, calibration.v2_sq
                ),
            });
        }
        Ok(RowEstimator {
            calibration,
            ..self
        })
    }

    /// The divisors C1, C2.
    pub fn calibration(&self) -> Pair {
        self.calibration
    }

    /// N.
    pub fn samples(&self) -> usize {
        self.continuum.len()
    }

    /// The bias of a row whose modulated samples are `m`.
    fn bias(&self, m: &[f64]) -> Pair {
        match (self.bias, self.photon) {
            (BiasConvention::Model, _) => self.model_bias,
            (BiasConvention::Counts, false) => Pair {
                v1_sq: self.bins as f64 * self.read_var * m.len() as f64,
                v2_sq: self.read_var * self.kernel.iter().sum::<f64>(),
            },
            (BiasConvention::Counts, true) => {
                let (mut total, mut weighted) = (0.0, 0.0);
                for ((&mi, &c), &k) in m.iter().zip(&self.continuum).zip(&self.kernel) {
                    let v = self.read_var + c + mi;
                    total += v;
                    weighted += k * v;
                }
                Pair {
                    v1_sq: self.bins as f64 * total,
                    v2_sq: weighted,
                }
            }
        }
    }

    /// The estimates of one row (length N), its values taken as they are
    /// ([`RowEstimator::try_estimate`] also refuses non-finite values, a
    /// dark row and estimates that overflow).
    ///
    /// # Errors
    ///
    /// [`Error::Invalid`] (parameter `row`) when `row` does not hold N
    /// samples.
    pub fn estimate(&self, row: &[f64]) -> Result<RowEstimate> {
        self.check_row_length(row)?;
        Ok(self.estimate_checked_row(row))
    }

    /// Refuses (parameter `row`) a row that does not hold N samples.
    fn check_row_length(&self, row: &[f64]) -> Result<()> {
        let n = self.samples();
        if row.len() == n {
            return Ok(());
        }
        Err(Error::Invalid {
            param: "row",
            reason: format!(
                "{} values; accepted: a row of the model's {n} samples",
                row.len()
            ),
        })
    }

    /// [`RowEstimator::estimate`] of a row the library made (N samples: a
    /// row of its own set), without the check, in the hot loops.
    pub(crate) fn estimate_checked_row(&self, row: &[f64]) -> RowEstimate {
        self.estimate_row(row, &mut Vec::new(), &mut Vec::new())
    }

    /// The estimates of one row; refuses (parameter `row`) a row that does
    /// not hold N samples, a value that is not a finite number, a dark row
    /// ([`RowFault`]) and values so large that the estimates overflow.
    pub fn try_estimate(&self, row: &[f64]) -> Result<RowEstimate> {
        self.check_row_length(row)?;
        if let Some(fault) = RowFault::of_row(0, row) {
            return Err(Error::Invalid {
                param: "row",
                reason: fault.reason(),
            });
        }
        let e = self.estimate_row(row, &mut Vec::new(), &mut Vec::new());
        if let Some(fault) = RowFault::of_estimate(0, &e) {
            return Err(Error::Invalid {
                param: "row",
                reason: fault.reason(),
            });
        }
        Ok(e)
    }

    /// The estimates of `row`; `buf` (the modulated samples of a row of
    /// counts) and `scratch` are reused between calls. A row that already
    /// holds the modulated samples is read in place, not copied.
    fn estimate_row(
        &self,
        row: &[f64],
        buf: &mut Vec<f64>,
        scratch: &mut Vec<Complex64>,
    ) -> RowEstimate {
        let m: &[f64] = if self.continuum_subtracted {
            row
        } else {
            buf.clear();
            buf.extend(row.iter().zip(&self.continuum).map(|(x, c)| x - c));
            buf
        };
        let raw = self.windowed.raw(m, scratch);
        RowEstimate::new(raw, self.bias(m), self.calibration)
    }

    /// The estimates of every row of `rows` (row-major, N per row), on
    /// `threads` threads (0: all); each row's answer depends on that row
    /// alone. Refuses the set's first fault ([`RowFault`]).
    pub fn estimate_rows(&self, rows: &[f64], threads: usize) -> Result<Vec<RowEstimate>> {
        crate::montecarlo::check_threads(threads)?;
        let n = self.samples();
        if rows.len() % n != 0 {
            return Err(Error::Invalid {
                param: "interferograms",
                reason: format!("{} values is not a whole number of rows of {n}", rows.len()),
            });
        }
        let mut out = Vec::new();
        let what = || format!("estimates of {} rows", rows.len() / n);
        crate::bounds::reserve(&mut out, rows.len() / n, "interferograms", &what)?;
        out.resize(rows.len() / n, RowEstimate::default());
        self.estimate_rows_into(rows, threads, out)
            .map_err(|fault| Error::Invalid {
                param: "interferograms",
                reason: format!("{}: {}", fault.location(0), fault.reason()),
            })
    }

    /// The estimates of every row of `rows` (row-major, N per row) on
    /// `threads` threads (0: all; more than
    /// [`crate::montecarlo::max_threads`] run on that many), or the set's
    /// first fault ([`RowFault::first`]); a last row of fewer than N values
    /// is a fault, found before any row is estimated. One pass over the
    /// rows: each is checked while it is estimated, blocks of rows written
    /// in place by the threads.
    pub fn try_estimate_rows(
        &self,
        rows: &[f64],
        threads: usize,
    ) -> std::result::Result<Vec<RowEstimate>, RowFault> {
        let n = self.samples();
        if rows.len() % n != 0 {
            return Err(RowFault::Partial {
                row: rows.len() / n,
                values: rows.len() % n,
            });
        }
        self.estimate_rows_into(rows, threads, vec![RowEstimate::default(); rows.len() / n])
    }

    /// [`RowEstimator::try_estimate_rows`] of whole rows into `out`, one
    /// estimate per row, allocated by the caller.
    fn estimate_rows_into(
        &self,
        rows: &[f64],
        threads: usize,
        mut out: Vec<RowEstimate>,
    ) -> std::result::Result<Vec<RowEstimate>, RowFault> {
        const BLOCK_ROWS: usize = 256;
        let n = self.samples();
        let job = || {
            out.par_chunks_mut(BLOCK_ROWS)
                .zip(rows.par_chunks(n * BLOCK_ROWS))
                .enumerate()
                .map(|(b, (out, block))| {
                    let (mut buf, mut scratch, mut fault) = (Vec::new(), Vec::new(), None);
                    for (i, (o, row)) in out.iter_mut().zip(block.chunks_exact(n)).enumerate() {
                        if let Some(f) = RowFault::of_row(b * BLOCK_ROWS + i, row) {
                            fault = RowFault::first(fault, Some(f));
                        }
                        *o = self.estimate_row(row, &mut buf, &mut scratch);
                        if let Some(f) = RowFault::of_estimate(b * BLOCK_ROWS + i, o) {
                            fault = RowFault::first(fault, Some(f));
                        }
                    }
                    fault
                })
                .reduce(|| None, RowFault::first)
        };
        match crate::montecarlo::in_pool_capped(threads, job) {
            None => Ok(out),
            Some(fault) => Err(fault),
        }
    }

    /// The calibration measured on a calibrator's rows: the mean over them
    /// of `raw − bias` (this estimator's window and convention, with the
    /// calibrator's model for the `model` convention).
    pub fn calibration_from_rows(&self, rows: &[f64], threads: usize) -> Result<Pair> {
        let est = self.estimate_rows(rows, threads)?;
        if est.is_empty() {
            return Err(Error::Invalid {
                param: "calibrator",
                reason: "the calibrator file has no rows".into(),
            });
        }
        let k = est.len() as f64;
        Ok(Pair {
            v1_sq: est.iter().map(|e| e.v1_sq_raw - e.v1_sq_bias).sum::<f64>() / k,
            v2_sq: est.iter().map(|e| e.v2_sq_raw - e.v2_sq_bias).sum::<f64>() / k,
        })
    }
}

/// The slow, obviously correct estimates of one modulated row `m`: the
/// naive DFT, the window's sums, the bias of `variance` (the per-sample
/// noise variance the convention gives) by its definition
/// ([`noise_bias`](crate::formalism::estimator::noise_bias)), divided by `calibration`.
///
/// Refuses (naming the parameter) inputs that do not describe one row: an
/// empty or non-finite `m`, a `variance` not of `m`'s length or not finite
/// and >= 0, a bin not below `m`'s length, and a calibration not finite
/// and > 0.
pub fn estimate_row_oracle(
    m: &[f64],
    bins: &[usize],
    variance: &[f64],
    calibration: Pair,
) -> Result<RowEstimate> {
    let n = m.len();
    let invalid = |param: &'static str, reason: String| Err(Error::Invalid { param, reason });
    if n == 0 || m.iter().any(|x| !x.is_finite()) {
        return invalid(
            "m",
            format!("{n} samples; a row of finite samples is needed"),
        );
    }
    if variance.len() != n || variance.iter().any(|v| !(v.is_finite() && *v >= 0.0)) {
        let reason = format!(
            "{} values; one finite variance >= 0 per sample ({n})",
            variance.len()
        );
        return invalid("variance", reason);
    }
    if let Some(k) = bins.iter().find(|&&k| k >= n) {
        return invalid(
            "bins",
            format!("bin {k}; the bins of {n} samples are 0 to {}", n - 1),
        );
    }
    let good = |c: f64| c.is_finite() && c > 0.0;
    if !(good(calibration.v1_sq) && good(calibration.v2_sq)) {
        let reason = format!("{calibration:?}; both divisors must be finite and > 0");
        return invalid("calibration", reason);
    }
    let raw = raw_sums(&naive_dft(m), bins);
    Ok(RowEstimate::new(
        raw,
        noise_bias_sums(variance, bins),
        calibration,
    ))
}

/// Why a row of zeros is refused.
pub const DARK_ROW: &str =
    "every sample is 0 (no light at all, or no data); an interferogram with light is needed";

/// √(f64::MAX): a row's estimates square sums of its N values, so values
/// of magnitude `a` overflow them once `N a` nears this scale.
pub const OVERFLOW_SCALE: f64 = 1.3e154;

/// What makes a set of rows unusable: a value that is not a finite number,
/// values so large that the estimates overflow, or a dark row (every
/// sample 0: no light reached the detector, or the
/// file holds no data, and the estimators would return a bias-subtracted
/// number of no meaning).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum RowFault {
    /// `value`, at `row` and `col` (0-based), is not finite.
    NonFinite {
        /// Row, 0-based.
        row: usize,
        /// Column, 0-based.
        col: usize,
        /// The value.
        value: f64,
    },
    /// Every sample of `row` (0-based) is 0.
    Dark {
        /// Row, 0-based.
        row: usize,
    },
    /// The values of `row` (0-based), finite, are so large that its
    /// estimates (sums of squares) overflow a float64.
    Overflow {
        /// Row, 0-based.
        row: usize,
    },
    /// The last row, `row` (0-based), holds `values` values, fewer than N.
    Partial {
        /// Row, 0-based.
        row: usize,
        /// Its values.
        values: usize,
    },
}

impl RowFault {
    /// The fault of `row`, row `index` of its set, if any.
    pub fn of_row(index: usize, row: &[f64]) -> Option<RowFault> {
        // No early exit, so that the loop vectorizes: the row is checked
        // while it is in cache, at a fraction of the estimate's cost.
        let (finite, lit) = row.iter().fold((true, false), |(finite, lit), &v| {
            (finite & v.is_finite(), lit | (v != 0.0))
        });
        if !finite {
            let col = row.iter().position(|v| !v.is_finite())?;
            return Some(RowFault::NonFinite {
                row: index,
                col,
                value: row[col],
            });
        }
        (!lit).then_some(RowFault::Dark { row: index })
    }

    /// The fault of `estimate`, row `index` of its set, if any: an estimate
    /// that overflowed (the row's values were finite but too large).
    pub fn of_estimate(index: usize, estimate: &RowEstimate) -> Option<RowFault> {
        let finite = estimate.values().iter().all(|x| x.is_finite());
        (!finite).then_some(RowFault::Overflow { row: index })
    }

    /// The fault a set reports of `a` and `b`: a non-finite value before
    /// any dark row, then the earlier row (the same whatever order the
    /// rows were checked in).
    pub fn first(a: Option<RowFault>, b: Option<RowFault>) -> Option<RowFault> {
        let rank = |f: &RowFault| match *f {
            RowFault::NonFinite { row, col, .. } => (0, row, col),
            RowFault::Dark { row } => (1, row, 0),
            RowFault::Overflow { row } => (2, row, 0),
            RowFault::Partial { row, .. } => (3, row, 0),
        };
        match (a, b) {
            (Some(x), Some(y)) => Some(if rank(&y) < rank(&x) { y } else { x }),
            (x, None) | (None, x) => x,
        }
    }

    /// Where the fault is, 1-based, the set's first `first` rows (of its
    /// file) before it.
    pub fn location(&self, first: usize) -> String {
        match *self {
            RowFault::NonFinite { row, col, .. } => {
                format!("row {}, column {} (1-based)", first + row + 1, col + 1)
            }
            RowFault::Dark { row } | RowFault::Overflow { row } | RowFault::Partial { row, .. } => {
                format!("row {} (1-based)", first + row + 1)
            }
        }
    }

    /// Why the rows are refused.
    pub fn reason(&self) -> String {
        match *self {
            RowFault::NonFinite { value, .. } => {
                format!("{value} is not a finite number; every value must be finite")
            }
            RowFault::Dark { .. } => DARK_ROW.to_owned(),
            RowFault::Overflow { .. } => format!(
                "its values are so large that the estimates overflow a float64; \
                 every |value| must stay well below {OVERFLOW_SCALE:e} / samples"
            ),
            RowFault::Partial { values, .. } => {
                format!("{values} values: fewer than a row's samples, the rows are cut short")
            }
        }
    }
}
