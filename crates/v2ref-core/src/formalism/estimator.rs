//! The two squared-visibility estimators (paper eq. `eq:estimateurs`), in
//! their spectral (infinite-scan, noise-free) form and in their sampled form
//! built from the DFT of the interferogram (paper, Appendix "Sampled
//! interferogram formalism").
//!
//! # Spectral form
//!
//! With sums over the Fourier grid replaced by integrals over wavenumber
//! (infinite scan), the factor 4 of eq. `eq:estimateurs` cancels the ½ of
//! the extended visibility on the positive-frequency side and
//!
//! - `V1² = ∫ W² |V|² dσ / ∫ W² dσ` — the W²-weighted mean of |V|²,
//!   blind to any spectral phase;
//! - `V2² = |∫ W V e^{iφ} dσ|² / (∫ W dσ)²` — the complex components are
//!   summed coherently before squaring (∫ W = 1).
//!
//! The monochromatic reference is `V_mono = |V(σ_eff)|`.
//!
//! # Sampled form
//!
//! From `B_k = Σ_i M_i e^{−2πi ik/N}` and a window K of bins:
//!
//! - `V1²_raw = Σ_{k∈K} |B_k|²`,
//! - `V2²_raw = |Σ_{k∈K} B_k|² = (Σ Re B_k)² + (Σ Im B_k)²`,
//!
//! from which the additive-noise biases ([`noise_bias`]) are subtracted.
//! With all N bins, Parseval gives `V1²_raw = N Σ M_i²` and
//! `V2²_raw = N² M_0²` (the forms the Appendix uses); the positive-frequency
//! half reproduces the spectral form in the long-scan limit.
//! [`sampled_wide_band`] normalizes by the same estimator on an unresolved,
//! phase-free calibrator, so that a source of visibility V reads V².

use crate::error::{Error, Result};
use crate::formalism::interferogram::{Interferogram, Sampling};
use crate::formalism::observation::Observation;
use crate::formalism::spectrum::Spectrum;
use num_complex::Complex64;
use rustfft::FftPlanner;
use serde::Serialize;

/// The band window's tie rule is a convention a pipeline matches, so its
/// slack is public here, the one tolerance of the stable surface (its home,
/// with the others, is the test machinery's `tolerance`).
pub use crate::tolerance::BAND_EDGE_REL;

/// Noise-free wide-band estimates for one observation (the `bias` command's
/// answer).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WideBand {
    /// |V(σ_eff)|, the monochromatic visibility at the effective wavenumber.
    pub v_mono: f64,
    /// √V1².
    pub v1: f64,
    /// √V2².
    pub v2: f64,
    /// V1² (spectral form).
    pub v1_sq: f64,
    /// V2² (spectral form).
    pub v2_sq: f64,
    /// S = B σ_eff, cycles/arcsec.
    pub spatial_freq_cpas: f64,
    /// σ_eff, µm⁻¹.
    pub sigma_eff_per_um: f64,
    /// B, m.
    pub baseline_m: f64,
}

/// `V1² = ∫ W² |V|² dσ / ∫ W² dσ` (infinite scan, no noise).
pub fn v1_sq(obs: &Observation) -> f64 {
    obs.spectrum.mean_w2_split(
        |s| obs.source.visibility(s, obs.baseline_m).norm_sqr(),
        &obs.source.features_per_um(),
    )
}

/// `V2² = |∫ W V e^{iφ} dσ|²` (infinite scan, no noise; ∫ W = 1).
pub fn v2_sq(obs: &Observation) -> f64 {
    obs.spectrum
        .mean_w_split(|s| obs.fringe_amplitude(s), &obs.source.features_per_um())
        .norm_sqr()
}

/// `V_mono = |V(σ_eff)|`.
pub fn v_mono(obs: &Observation) -> f64 {
    obs.source
        .visibility(obs.spectrum.sigma_eff_per_um(), obs.baseline_m)
        .norm()
}

/// All noise-free infinite-scan numbers for `obs`.
///
/// # Example
///
/// ```
/// use v2ref_core::prelude::*;
/// use v2ref_core::formalism::estimator::{all_bins, positive_bins};
/// // A point source reads V1 = V2 = 1 whatever the band.
/// let obs = Observation::new(Spectrum::flat(Band::k()), Source::Point, Frequency::BaselineM(100.0), SpectralPhase::zero())?;
/// let wb = wide_band(&obs);
/// assert!((wb.v1 - 1.0).abs() < 1e-12 && (wb.v2 - 1.0).abs() < 1e-12);
/// # Ok::<(), v2ref_core::Error>(())
/// ```
pub fn wide_band(obs: &Observation) -> WideBand {
    let (v1_sq, v2_sq) = (v1_sq(obs), v2_sq(obs));
    WideBand {
        v_mono: v_mono(obs),
        v1: v1_sq.sqrt(),
        v2: v2_sq.sqrt(),
        v1_sq,
        v2_sq,
        spatial_freq_cpas: obs.spatial_freq_cpas(),
        sigma_eff_per_um: obs.spectrum.sigma_eff_per_um(),
        baseline_m: obs.baseline_m,
    }
}

/// Which Fourier bins K an estimator sums, in `V1² = Σ_{k∈K} |B_k|²` and
/// `V2² = |Σ_{k∈K} B_k|²` (the paper does not fix the window; the
/// conventions document compares them).
///
/// For N samples at spacing δx, bin k holds wavenumber k δσ with
/// δσ = 1/(N δx):
///
/// | window | bins | N = 8 | N = 7 |
/// |---|---|---|---|
/// | [`Positive`](BinWindow::Positive) | 1 … ⌈N/2⌉ − 1 ([`positive_bins`]) | 1, 2, 3 | 1, 2, 3 |
/// | [`Band`](BinWindow::Band) | the positive bins with k δσ in the spectrum's support ([`band_bins`]) | | |
/// | [`All`](BinWindow::All) | 0 … N − 1 ([`all_bins`]) | 0 … 7 | 0 … 6 |
///
/// ```
/// use v2ref_core::formalism::estimator::BinWindow;
/// use v2ref_core::formalism::spectrum::{Band, Spectrum};
/// let k = Spectrum::flat(Band::k());
/// assert_eq!(BinWindow::Positive.bins(8, 0.5, &k)?, vec![1, 2, 3]);
/// assert_eq!(BinWindow::Positive.bins(7, 0.5, &k)?, vec![1, 2, 3]);
/// // 2.0–2.4 µm is 0.417–0.5 µm⁻¹; with δσ = 1/(64 · 0.5 µm) = 1/32 µm⁻¹ the bins are 14, 15, 16.
/// assert_eq!(BinWindow::Band.bins(64, 0.5, &k)?, vec![14, 15, 16]);
/// assert_eq!(BinWindow::All.bins(4, 0.5, &k)?, vec![0, 1, 2, 3]);
/// # Ok::<(), v2ref_core::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
pub enum BinWindow {
    /// The positive frequencies k = 1 … ⌈N/2⌉ − 1: DC excluded, and the
    /// Nyquist bin N/2 excluded when N is even.
    Positive,
    /// The positive-frequency bins whose wavenumber lies inside the
    /// spectrum's support.
    Band,
    /// All N bins (the Appendix's form; V2 then reads N² M_0²).
    All,
}

impl crate::words::Words for BinWindow {
    const WORDS: &'static [crate::words::Word<Self>] = &[
        crate::words::Word {
            word: "positive",
            value: BinWindow::Positive,
            help: "The positive frequencies k = 1 … ⌈N/2⌉ − 1: DC excluded, and the Nyquist bin N/2 excluded when N is even",
        },
        crate::words::Word {
            word: "band",
            value: BinWindow::Band,
            help: "The positive-frequency bins whose wavenumber lies inside the spectrum's support",
        },
        crate::words::Word {
            word: "all",
            value: BinWindow::All,
            help: "All N bins (the Appendix's form; V2 then reads N² M_0²)",
        },
    ];
}

/// The three windows, in the order results are reported.
pub const BIN_WINDOWS: [BinWindow; 3] = [BinWindow::Positive, BinWindow::Band, BinWindow::All];

impl BinWindow {
    /// The bins of this window for `n` samples at spacing `dx_um` (µm), the
    /// band being the support of `spectrum`.
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] (parameter `samples`) when `n` exceeds
    /// [`MAX_BINS`].
    pub fn bins(&self, n: usize, dx_um: f64, spectrum: &Spectrum) -> Result<Vec<usize>> {
        check_bins(n)?;
        Ok(self.bins_within_bound(n, dx_um, spectrum))
    }

    /// [`BinWindow::bins`] for `n` already within [`MAX_BINS`] (a
    /// [`Sampling`]'s samples, or a checked scan's).
    pub(crate) fn bins_within_bound(
        &self,
        n: usize,
        dx_um: f64,
        spectrum: &Spectrum,
    ) -> Vec<usize> {
        match self {
            BinWindow::Positive => (1..n.div_ceil(2)).collect(),
            BinWindow::All => (0..n).collect(),
            BinWindow::Band => {
                let (lo, hi) = spectrum.support();
                band_bins_within_bound(n, dx_um, lo, hi)
            }
        }
    }

    /// Lowercase name, as in JSON and on the command line.
    pub fn name(&self) -> &'static str {
        crate::words::Words::word(*self)
    }
}

/// Most samples whose bins are listed: a scan's most samples
/// ([`crate::formalism::interferogram::MAX_SAMPLES`], 2^24).
pub const MAX_BINS: usize = crate::formalism::interferogram::MAX_SAMPLES;

/// k = 1 … ⌈N/2⌉ − 1: for even N, 1 … N/2 − 1; for odd N, 1 … (N − 1)/2.
///
/// # Errors
///
/// [`Error::OutOfRange`] (parameter `samples`) when `n` exceeds
/// [`MAX_BINS`]: no scan has that many samples, and the list would take
/// memory without bound.
pub fn positive_bins(n: usize) -> Result<Vec<usize>> {
    check_bins(n)?;
    Ok((1..n.div_ceil(2)).collect())
}

/// k = 0 … N − 1.
///
/// # Errors
///
/// [`Error::OutOfRange`] (parameter `samples`) when `n` exceeds
/// [`MAX_BINS`], as [`positive_bins`].
pub fn all_bins(n: usize) -> Result<Vec<usize>> {
    check_bins(n)?;
    Ok((0..n).collect())
}

/// Refuses more samples than [`MAX_BINS`] before any list is made.
fn check_bins(n: usize) -> Result<()> {
    if n <= MAX_BINS {
        return Ok(());
    }
    Err(Error::OutOfRange {
        param: "samples",
        value: n as f64,
        accepted: format!("0 to {MAX_BINS} (a scan's most samples)"),
    })
}

/// The positive bins ([`positive_bins`]) whose wavenumber k/(N δx) lies in
/// [`lo_per_um`, `hi_per_um`] (µm⁻¹, bounds included).
///
/// **Ties.** A bin on an edge is kept, and "on" does not depend on how the
/// edge and the bin's wavenumber were rounded: the edges are taken in
/// units of bins, `N δx σ`, and each is widened outward by
/// [`BAND_EDGE_REL`] of itself, so bin k is kept when
/// `N δx σ_min (1 − ε) ≤ k ≤ N δx σ_max (1 + ε)`. Computed as
/// `k/(N δx)` or as `k · (1/(N δx))`, a bin that sits on an edge in exact
/// arithmetic (the K band's 1/2.4 µm⁻¹ reached by N δx = 2.4 k µm) lands
/// within a few ulps of it on either side; the slack keeps it either way.
///
/// ```
/// use v2ref_core::formalism::estimator::band_bins;
/// use v2ref_core::formalism::spectrum::Band;
/// // N δx = 8 × 0.3 µm = 2.4 µm: bin 1 sits exactly on the K band's long edge (2.4 µm).
/// let k = Band::k();
/// assert_eq!(band_bins(8, 0.3, k.sigma_min_per_um(), k.sigma_max_per_um())?, vec![1]);
/// # Ok::<(), v2ref_core::Error>(())
/// ```
///
/// # Errors
///
/// [`Error::OutOfRange`] (parameter `samples`) when `n` exceeds
/// [`MAX_BINS`], as [`positive_bins`].
pub fn band_bins(n: usize, dx_um: f64, lo_per_um: f64, hi_per_um: f64) -> Result<Vec<usize>> {
    check_bins(n)?;
    Ok(band_bins_within_bound(n, dx_um, lo_per_um, hi_per_um))
}

/// [`band_bins`] for `n` already within [`MAX_BINS`].
pub(crate) fn band_bins_within_bound(
    n: usize,
    dx_um: f64,
    lo_per_um: f64,
    hi_per_um: f64,
) -> Vec<usize> {
    let scan_um = n as f64 * dx_um;
    let (lo_bin, hi_bin) = (lo_per_um * scan_um, hi_per_um * scan_um);
    let (lo_kept, hi_kept) = (
        lo_bin - BAND_EDGE_REL * lo_bin.abs(),
        hi_bin + BAND_EDGE_REL * hi_bin.abs(),
    );
    (1..n.div_ceil(2))
        .filter(|&k| (lo_kept..=hi_kept).contains(&(k as f64)))
        .collect()
}

/// The DFT phase `−2π (i k mod N)/N` of sample `i` in bin `k` (rad): the
/// one place the transform's sign and the exact reduction of `i k` are
/// written (reducing before the division keeps the phase exact for large
/// `i k`).
#[inline]
pub fn dft_phase(i: usize, k: usize, n: usize) -> f64 {
    -2.0 * std::f64::consts::PI * ((i * k) % n) as f64 / n as f64
}

/// A pair of values, one per estimator.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Default, serde::Deserialize)]
pub struct Pair {
    /// For V1².
    pub v1_sq: f64,
    /// For V2².
    pub v2_sq: f64,
}

/// `B_k = Σ_i M_i e^{−2πi ik/N}` by FFT (rustfft).
///
/// # Example
///
/// ```
/// use v2ref_core::prelude::*;
/// use v2ref_core::formalism::estimator::{all_bins, positive_bins};
/// // A cosine of 2 cycles over 8 samples puts N/2 in bins 2 and N − 2.
/// let m: Vec<f64> = (0..8).map(|i| (std::f64::consts::PI * i as f64 / 2.0).cos()).collect();
/// let b = dft(&m);
/// assert!((b[2].re - 4.0).abs() < 1e-12 && (b[6].re - 4.0).abs() < 1e-12);
/// assert!(b[1].norm() < 1e-12);
/// # Ok::<(), v2ref_core::Error>(())
/// ```
pub fn dft(samples: &[f64]) -> Vec<Complex64> {
    let mut buf: Vec<Complex64> = samples.iter().map(|&m| Complex64::new(m, 0.0)).collect();
    if !buf.is_empty() {
        FftPlanner::new()
            .plan_fft_forward(buf.len())
            .process(&mut buf);
    }
    buf
}

/// `(Σ_{k∈K} |B_k|², |Σ_{k∈K} B_k|²)`: the raw estimators over `bins`.
///
/// # Example
///
/// ```
/// use v2ref_core::prelude::*;
/// use v2ref_core::formalism::estimator::{all_bins, positive_bins};
/// // With all N bins, Parseval gives V1² = N Σ M² and V2² = N² M_0².
/// let m = [3.0, -1.0, 0.5, 2.0, -0.25];
/// let raw = raw_estimates(&dft(&m), &all_bins(m.len())?)?;
/// let n = m.len() as f64;
/// assert!((raw.v1_sq - n * m.iter().map(|x| x * x).sum::<f64>()).abs() < 1e-12);
/// assert!((raw.v2_sq - n * n * m[0] * m[0]).abs() < 1e-12);
/// # Ok::<(), v2ref_core::Error>(())
/// ```
///
/// # Errors
///
/// [`Error::Invalid`] (parameter `bins`) when a bin is not below the
/// spectrum's length (checked once, before any sum).
pub fn raw_estimates(spectrum: &[Complex64], bins: &[usize]) -> Result<Pair> {
    check_bins_below(bins, spectrum.len(), "values in the spectrum")?;
    Ok(raw_sums(spectrum, bins))
}

/// [`raw_estimates`] of bins already known to lie below the spectrum's
/// length (the library's own windows of its own scans).
pub(crate) fn raw_sums(spectrum: &[Complex64], bins: &[usize]) -> Pair {
    let (mut power, mut sum) = (0.0, Complex64::new(0.0, 0.0));
    for &k in bins {
        power += spectrum[k].norm_sqr();
        sum += spectrum[k];
    }
    Pair {
        v1_sq: power,
        v2_sq: sum.norm_sqr(),
    }
}

/// Refuses (parameter `bins`) a bin not below `n`, the count of `what`.
fn check_bins_below(bins: &[usize], n: usize, what: &str) -> Result<()> {
    match bins.iter().find(|&&k| k >= n) {
        None => Ok(()),
        Some(k) => Err(Error::Invalid {
            param: "bins",
            reason: match n {
                0 => format!("bin {k}; there are no {what}, so no bin is accepted"),
                _ => format!("bin {k}; accepted: 0 to {} ({n} {what})", n - 1),
            },
        }),
    }
}

/// The expected contribution of independent zero-mean additive noise of
/// per-sample variance `variance[i]` to the raw estimators over `bins`:
///
/// - V1²: `|K| Σ_i v_i` (every bin carries the whole noise power);
/// - V2²: `Σ_i v_i |Σ_{k∈K} e^{−2πi ik/N}|²`, which is `N² v_0` for all bins.
///
/// Detector noise has `v_i = σ_det²`; photon noise `v_i = n_i`, the mean
/// total count of sample i.
///
/// # Example
///
/// ```
/// use v2ref_core::prelude::*;
/// use v2ref_core::formalism::estimator::{all_bins, positive_bins};
/// // White noise of variance 4 on 16 samples, positive half (7 bins):
/// // V1² gains 7 · 16 · 4; V2² gains Σ_i 4 |Σ_k e^{−2πi ik/N}|².
/// let var = vec![4.0; 16];
/// let b = noise_bias(&var, &positive_bins(16)?)?;
/// assert!((b.v1_sq - 7.0 * 16.0 * 4.0).abs() < 1e-9);
/// assert!((b.v2_sq - 4.0 * 7.0 * 16.0).abs() < 1e-9); // Parseval on the kernel
/// # Ok::<(), v2ref_core::Error>(())
/// ```
///
/// # Errors
///
/// [`Error::Invalid`] naming `bins` when a bin is not below the number of
/// samples (`variance.len()`), and `variance` when a variance is not finite
/// and >= 0 or the bias overflows a float64 (checked once, before the
/// sums over samples and bins).
pub fn noise_bias(variance: &[f64], bins: &[usize]) -> Result<Pair> {
    check_bins_below(bins, variance.len(), "samples")?;
    if let Some(v) = variance.iter().find(|v| !(v.is_finite() && **v >= 0.0)) {
        return Err(Error::Invalid {
            param: "variance",
            reason: format!("{v}; accepted: every variance finite and >= 0"),
        });
    }
    let bias = noise_bias_sums(variance, bins);
    if !(bias.v1_sq.is_finite() && bias.v2_sq.is_finite()) {
        return Err(Error::Invalid {
            param: "variance",
            reason: format!(
                "the bias ({}, {}) overflows a float64; accepted: variances whose sum times the bins stays below {:e}",
                bias.v1_sq,
                bias.v2_sq,
                f64::MAX
            ),
        });
    }
    Ok(bias)
}

/// [`noise_bias`] of bins already known to lie below `variance.len()`.
pub(crate) fn noise_bias_sums(variance: &[f64], bins: &[usize]) -> Pair {
    let n = variance.len();
    let total: f64 = variance.iter().sum();
    let v2 = variance
        .iter()
        .enumerate()
        .map(|(i, &v)| {
            let kernel: Complex64 = bins
                .iter()
                .map(|&k| Complex64::from_polar(1.0, dft_phase(i, k, n)))
                .sum();
            v * kernel.norm_sqr()
        })
        .sum();
    Pair {
        v1_sq: bins.len() as f64 * total,
        v2_sq: v2,
    }
}

/// Noise-free sampled estimates of `obs`, normalized by the same estimator
/// on [`Observation::calibrator`]: a source of visibility V reads V² when the
/// sampling resolves the band.
///
/// # Example
///
/// ```
/// use v2ref_core::prelude::*;
/// use v2ref_core::formalism::estimator::{all_bins, positive_bins};
/// // A long, fine scan gives the spectral (infinite-scan) estimators back.
/// let obs = Observation::new(Spectrum::flat(Band::k()), Source::uniform_disk(10.0)?, Frequency::SpatialFreqCpas(40.0), SpectralPhase::zero())?;
/// let scan = sampled_wide_band(&obs, &Sampling::new(2048, 0.5, false)?, BinWindow::Positive)?;
/// let wb = wide_band(&obs);
/// assert!((scan.v1_sq - wb.v1_sq).abs() < 2e-3 && (scan.v2_sq - wb.v2_sq).abs() < 2e-3);
/// # Ok::<(), v2ref_core::Error>(())
/// ```
pub fn sampled_wide_band(
    obs: &Observation,
    sampling: &Sampling,
    window: BinWindow,
) -> Result<Pair> {
    let bins = window.bins_within_bound(sampling.samples(), sampling.dx_um(), &obs.spectrum);
    let raw = |o: &Observation| -> Result<Pair> {
        let ifg = Interferogram::synthesize(o, sampling, 1.0, None)?;
        Ok(raw_sums(&dft(&ifg.modulated), &bins))
    };
    let (src, cal) = (raw(obs)?, raw(&obs.calibrator())?);
    if !(cal.v1_sq > 0.0 && cal.v2_sq > 0.0) {
        // No bin of the window holds the calibrator's fringe (N = 2 has no
        // positive-frequency bin): the normalized estimate is 0/0.
        return Err(Error::Invalid {
            param: "samples",
            reason: format!(
                "{} samples leave the {} bins no fringe to normalize by; accepted: at least 3 samples, a window that holds the band",
                sampling.samples(),
                window.name()
            ),
        });
    }
    Ok(Pair {
        v1_sq: src.v1_sq / cal.v1_sq,
        v2_sq: src.v2_sq / cal.v2_sq,
    })
}
