//! The effect of a finite scan (paper, Section "Effect of finite scan
//! length", eq. `eq:sampled_V`, Fig. 3): the bias of V1 and V2 measured
//! from a scan of stroke Δx = N δx, against the infinite-scan estimators.
//!
//! # Estimators
//!
//! Both estimators sum the positive-frequency bins `K = {1, …, ⌈N/2⌉ − 1}`
//! of the DFT `B_k` (no DC, no Nyquist; [`BinWindow::Positive`]):
//! `V1² ∝ Σ_K |B_k|²`, `V2² ∝ |Σ_K B_k|²`. Each is normalized by the same
//! estimator on an unresolved, phase-free calibrator observed through the
//! same spectrum and the same scan, so that a point source reads exactly 1
//! whatever the stroke: the finite-scan bias left is the one the source's
//! own structure causes (the paper's reading: a bias where the visibility
//! varies fast or changes sign within a resolution element 1/Δx). The bias
//! is `√V²(finite) − √V²(infinite)`, the infinite-scan values being the
//! spectral forms of [`crate::formalism::estimator::wide_band`].
//!
//! With all N bins instead, V2² would be `N² m_0²`, which does not depend on
//! the stroke at all (sample 0 sits on the white-light fringe): the choice
//! of bins, not the estimator's name, decides V2's finite-scan bias.
//!
//! # Two computations
//!
//! 1. [`dft_estimates`]: synthesize the sampled, truncated interferogram
//!    ([`Interferogram::synthesize`]) and take its FFT.
//! 2. [`convolution_bins`]: eq. `eq:sampled_V` — each bin is the extended
//!    visibility convolved with the scan's response. With the centred scan
//!    `x_j = j δx`, `j ∈ J` (N consecutive integers), and
//!    `A(σ) = W V e^{iφ}`,
//!    `B_k = ½ ∫ A(σ) K(σδx − k/N) dσ + ½ ∫ A*(σ) K(−σδx − k/N) dσ`,
//!    `K(u) = Σ_{j∈J} e^{2πiju} = e^{iπu(2j_0+N−1)} sin(πNu)/sin(πu)`:
//!    the sinc of width 1/Δx replicated with period 1/δx (Poisson), with
//!    the phase of the scan's centring. [`Kernel::Sinc`] keeps the single
//!    sinc `N sinc(Nu)` of the printed equation (no replication), to show
//!    what the replication adds.

use crate::error::{self, Result};
use crate::formalism::estimator::{dft, raw_sums, wide_band, BinWindow, Pair};
use crate::formalism::interferogram::{sinc, Interferogram, Sampling, SpectralNodes};
use crate::formalism::observation::Frequency;
use crate::formalism::observation::Observation;
use crate::formalism::phase::SpectralPhase;
use crate::formalism::source::Source;
use crate::formalism::spectrum::Spectrum;
use num_complex::Complex64;
use rayon::prelude::*;
use std::f64::consts::PI;

/// The bins both estimators sum (see the module docs).
pub const WINDOW: BinWindow = BinWindow::Positive;

/// Below this |u − round(u)|, the Dirichlet ratio sin(πNu)/sin(πu) is taken
/// from its series N(1 − π²r²(N² − 1)/6), which avoids the 0/0 at r = 0:
/// the next term, O((πNr)⁴/120), is below 3e-14 relative for the scans of
/// up to 4096 samples the crate uses.
const DIRICHLET_SERIES_BELOW: f64 = 1e-7;

/// The scan's response to a unit spectral line, as a function of
/// `u = σ δx − k/N` (cycles per sample).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Kernel {
    /// `Σ_j e^{2πiju}`: exact for N samples (periodic in u with period 1).
    Dirichlet,
    /// `e^{iπu(2j_0+N−1)} N sinc(N u)`: eq. `eq:sampled_V` as printed,
    /// without the replication by the sampling comb.
    Sinc,
}

/// First index j_0 of the centred scan (DFT order, `Sampling::opd_um`):
/// `−⌊N/2⌋`.
fn first_index(n: usize) -> f64 {
    -((n / 2) as f64)
}

impl Kernel {
    /// The kernel at `u` for `n` samples.
    pub fn at(&self, u: f64, n: usize) -> Complex64 {
        let nf = n as f64;
        let centring = Complex64::from_polar(1.0, PI * u * (2.0 * first_index(n) + nf - 1.0));
        match self {
            Kernel::Dirichlet => {
                // The phase uses u itself (the centring factor is not
                // 1-periodic for even N); the ratio uses u reduced to
                // [−½, ½], where sin(πu) vanishes only at 0.
                let r = u - u.round();
                let ratio = if r.abs() < DIRICHLET_SERIES_BELOW {
                    nf * (1.0 - PI * PI * r * r * (nf * nf - 1.0) / 6.0)
                } else {
                    (PI * nf * r).sin() / (PI * r).sin()
                };
                // sin(πN u)/sin(πu) = (−1)^{(N−1) round(u)} · ratio(r).
                let parity = if (n % 2 == 0) && (u.round() as i64).rem_euclid(2) == 1 {
                    -1.0
                } else {
                    1.0
                };
                centring * (parity * ratio)
            }
            Kernel::Sinc => centring * (nf * sinc(nf * u)),
        }
    }
}

/// Raw estimates `(Σ_K |B_k|², |Σ_K B_k|²)` per unit continuum from the
/// synthesized interferogram of `obs` (path 1).
pub fn dft_estimates(obs: &Observation, sampling: &Sampling) -> Result<Pair> {
    let ifg = Interferogram::synthesize(obs, sampling, 1.0, None)?;
    let bins = WINDOW.bins(sampling.samples(), sampling.dx_um(), &obs.spectrum)?;
    Ok(raw_sums(&dft(&ifg.modulated), &bins))
}

/// `B_k` for every `k` of `bins`, per unit continuum, by the convolution of
/// eq. `eq:sampled_V` (path 2), on Gauss–Legendre nodes that resolve the
/// kernel (it oscillates at up to Δx/2 cycles per unit σ).
pub fn convolution_bins(
    obs: &Observation,
    sampling: &Sampling,
    bins: &[usize],
    kernel: Kernel,
) -> Result<Vec<Complex64>> {
    sampling.check_aliasing(obs)?;
    let n = sampling.samples();
    let dx = sampling.dx_um();
    let integrating = sampling.integrating().then_some(dx);
    let nodes = SpectralNodes::new(obs, 0.5 * sampling.stroke_um() + dx, integrating)?;
    // |K| bins × N-proportional nodes, stopped between bins when cancelled.
    crate::montecarlo::map_items(bins.len(), nodes.sigma_per_um.len(), |j| {
        let k = bins[j];
        let kn = k as f64 / n as f64;
        nodes
            .sigma_per_um
            .iter()
            .zip(&nodes.amplitude)
            .map(|(&s, a)| {
                0.5 * (a * kernel.at(s * dx - kn, n) + a.conj() * kernel.at(-s * dx - kn, n))
            })
            .sum()
    })
}

/// Raw estimates from [`convolution_bins`] over the window [`WINDOW`].
pub fn convolution_estimates(
    obs: &Observation,
    sampling: &Sampling,
    kernel: Kernel,
) -> Result<Pair> {
    let bins = WINDOW.bins(sampling.samples(), sampling.dx_um(), &obs.spectrum)?;
    let b = convolution_bins(obs, sampling, &bins, kernel)?;
    let all: Vec<usize> = (0..b.len()).collect();
    Ok(raw_sums(&b, &all))
}

/// How the raw estimates are computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Method {
    /// FFT of the synthesized interferogram.
    Dft,
    /// Convolution of the extended visibility with the scan's kernel.
    Convolution(Kernel),
}

/// Calibrated finite-scan V1² and V2² of `obs`: source over calibrator,
/// both through the same `sampling` (see the module docs). `calibrator`
/// may pass the calibrator's raw estimates when they are already known
/// (they depend on the spectrum and the scan only).
pub fn calibrated(
    obs: &Observation,
    sampling: &Sampling,
    method: Method,
    calibrator: Option<Pair>,
) -> Result<Pair> {
    let raw = |o: &Observation| match method {
        Method::Dft => dft_estimates(o, sampling),
        Method::Convolution(k) => convolution_estimates(o, sampling, k),
    };
    let src = raw(obs)?;
    let cal = match calibrator {
        Some(c) => {
            // A calibrator's raw estimates are positive powers.
            error::positive("calibrator", c.v1_sq)?;
            error::positive("calibrator", c.v2_sq)?;
            c
        }
        None => raw(&obs.calibrator())?,
    };
    let pair = Pair {
        v1_sq: src.v1_sq / cal.v1_sq,
        v2_sq: src.v2_sq / cal.v2_sq,
    };
    error::finite("calibrator", pair.v1_sq)?;
    error::finite("calibrator", pair.v2_sq)?;
    Ok(pair)
}

/// A bias of both estimators, in visibility (not squared).
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct Bias {
    /// Bias of V1 = √V1².
    pub v1: f64,
    /// Bias of V2 = √V2².
    pub v2: f64,
}

/// The finite-scan bias `(√V1²_fin − V1_inf, √V2²_fin − V2_inf)` of `obs`.
///
/// # Example
///
/// ```
/// use v2ref_core::prelude::*;
/// use v2ref_core::formalism::estimator::{all_bins, positive_bins};
/// use v2ref_core::bias::finite_scan::{finite_scan_bias, Method};
/// // The finite-scan bias of V1 for a 43 mas disk in K at 20 cycles/arcsec
/// // shrinks as the stroke grows.
/// let obs = Observation::new(Spectrum::flat(Band::k()), Source::uniform_disk(43.0)?, Frequency::SpatialFreqCpas(20.0), SpectralPhase::zero())?;
/// let short = finite_scan_bias(&obs, &Sampling::from_stroke(16.0, 0.55, false)?, Method::Dft, None)?;
/// let long = finite_scan_bias(&obs, &Sampling::from_stroke(256.0, 0.55, false)?, Method::Dft, None)?;
/// assert!(long.v1.abs() < short.v1.abs());
/// # Ok::<(), v2ref_core::Error>(())
/// ```
pub fn finite_scan_bias(
    obs: &Observation,
    sampling: &Sampling,
    method: Method,
    calibrator: Option<Pair>,
) -> Result<Bias> {
    let fin = calibrated(obs, sampling, method, calibrator)?;
    let inf = wide_band(obs);
    Ok(Bias {
        v1: fin.v1_sq.sqrt() - inf.v1,
        v2: fin.v2_sq.sqrt() - inf.v2,
    })
}

/// The raw estimates of the calibrator of `obs` through `sampling`.
pub fn calibrator_raw(obs: &Observation, sampling: &Sampling, method: Method) -> Result<Pair> {
    let cal = obs.calibrator();
    match method {
        Method::Dft => dft_estimates(&cal, sampling),
        Method::Convolution(k) => convolution_estimates(&cal, sampling, k),
    }
}

/// Finite-scan biases of `source` through `band` at each S of `grid`
/// for each of `samplings`, by `method`: `[sampling][point]`.
pub fn disk_biases(
    band: &Spectrum,
    source: &Source,
    grid: &[f64],
    samplings: &[Sampling],
    method: Method,
) -> Result<Vec<Vec<Bias>>> {
    let cal_obs = Observation::new(
        band.clone(),
        Source::Point,
        Frequency::BaselineM(0.0),
        SpectralPhase::zero(),
    )?;
    samplings
        .iter()
        .map(|sampling| {
            let cal = calibrator_raw(&cal_obs, sampling, method)?;
            grid.par_iter()
                .map(|&s| {
                    let obs = Observation::new(
                        band.clone(),
                        source.clone(),
                        Frequency::SpatialFreqCpas(s),
                        SpectralPhase::zero(),
                    )?;
                    finite_scan_bias(&obs, sampling, method, Some(cal))
                })
                .collect()
        })
        .collect()
}
