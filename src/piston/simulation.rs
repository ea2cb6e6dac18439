//! Scanned interferograms corrupted by differential piston, and the bias and
//! scatter it gives the two estimators (paper, Section "Effect of
//! differential piston", Figs. 4 and 5).
//!
//! # Piston sequences
//!
//! A Gaussian piston sequence with the two-sided spectrum P(ν) of
//! [`crate::piston::turbulence::PistonSpectrum`] is synthesised by FFT: with M
//! samples at step Δt, ν_k = k/(MΔt), the coefficients
//! `W_k = √(P(ν_k)Δν) (g + i g')` (g, g' standard normal) for
//! 0 < k < M/2 and `p_n = √2 Re Σ_k W_k e^{2πikn/M}` give
//! `⟨p²⟩ = Σ_{k≠0} P(ν_k) Δν` and the periodogram `E|W_k|² = 2P(ν_k)Δν`
//! (the mean over the period is removed: it sits below the lowest frequency
//! the sequence resolves). Consecutive scans read consecutive stretches of
//! one sequence, as in an observation.
//!
//! # Scans
//!
//! The OPD at time t of a scan is `v t + p(t) − p_ref`, v = f λ0 (f the
//! fringe frequency), sampled every δx/v; N samples (scan Δx = N δx). The
//! sampled detector reads the fringe at the sample time; the integrating
//! detector averages it over the sample's own interval, computed with K
//! Gauss–Legendre sub-samples in time (the piston interpolated between its
//! samples by a cubic), which converges to the exact average — with no
//! piston, to the sinc(σδx)-filtered fringe (`tests/piston.rs` shows it).
//!
//! `p_ref` is the paper's unstated choice of where the fringe packet sits in
//! the scan ([`PistonReference`]). By default it is the piston averaged over
//! the scan (a group-delay tracker, or the packet located on the scan
//! itself, centres the scan on the mean OPD error), so that a piston frozen
//! during the scan has no effect on either estimator — the paper's premise
//! that fast scanning freezes the piston. The alternatives are the piston at
//! the middle (zero-OPD) sample, which makes the all-bins V2 = N²M_0²
//! immune by construction, and no correction at all.
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
//! # Speed
//!
//! The fringe `m(x) = Re Σ_j a_j e^{2πiσ_j x}` ([`SpectralNodes`]) is written
//! `Re[e^{2πiσ_c x} a(x)]` with the slowly varying complex envelope
//! `a(x) = Σ_j a_j e^{2πi(σ_j − σ_c)x}`, tabulated with its derivative and
//! interpolated by cubic Hermite polynomials ([`FringeTable`]); the grid step
//! bounds the interpolation error below 1e-12 of the fringe amplitude.

use crate::error::{self, Error, Result};
use crate::formalism::estimator::{raw_estimates, BinWindow, Pair, BIN_WINDOWS};
use crate::formalism::interferogram::{Sampling, SpectralNodes};
use crate::formalism::observation::Observation;
use crate::formalism::source::Source;
use crate::math::quadrature::gauss_legendre;
use crate::montecarlo::run_units;
use crate::piston::turbulence::PistonSpectrum;
use num_complex::Complex64;
use rand_distr::{Distribution, StandardNormal};
use rustfft::{Fft, FftPlanner};
use serde::Serialize;
use std::f64::consts::PI;

/// Largest piston sequence accepted (scans × samples), 2^24 samples.
pub const MAX_SERIES: usize = 1 << 24;
/// Most Gauss–Legendre sub-samples per integrating sample.
pub const MAX_SUB_SAMPLES: usize = 64;
/// Default sub-samples of the integrating detector: at 4 samples per 2 µm
/// fringe the Gauss–Legendre average is converged to ~2e-13 of the fringe
/// amplitude (errors 8e-2, 1e-3, 1e-8, 2e-13 for K = 1, 2, 4, 6; see
/// `tests/piston.rs`).
pub const DEFAULT_SUB_SAMPLES: usize = 6;

/// Largest OPD (µm) a scan may reach with its piston: beyond, the fringe
/// table would cost more memory and time than any realistic case needs.
pub const MAX_OPD_UM: f64 = 5000.0;

/// Coefficients generated per work unit in [`synthesize_series`].
const COEFF_BLOCK: usize = 1 << 15;
/// Scans per work unit in [`simulate`].
const SCAN_BLOCK: usize = 100;

/// The FFT length used for a sequence of `len` samples: the smallest even
/// M ≥ max(len, 4) whose only prime factors are 2, 3 and 5 (fast for
/// rustfft, at most ~8 % longer than asked).
pub fn sequence_length(len: usize) -> usize {
    let target = len.max(4);
    let mut best = target.next_power_of_two();
    let mut p5 = 1usize;
    while p5 < best {
        let mut p35 = p5;
        while p35 < best {
            let mut n = p35 * 2;
            while n < target {
                n *= 2;
            }
            best = best.min(n);
            p35 *= 3;
        }
        p5 *= 5;
    }
    best
}

/// Synthesises `len` samples at step `dt_s` of a zero-mean Gaussian sequence
/// with two-sided spectrum `psd(ν)` (µm²/Hz), by FFT over
/// M = [`sequence_length`]`(len)` (the sequence is M long and periodic).
/// Deterministic in `seed` whatever the thread count.
pub fn synthesize_series(
    psd: &(dyn Fn(f64) -> f64 + Sync),
    dt_s: f64,
    len: usize,
    seed: u64,
    threads: usize,
) -> Result<Vec<f64>> {
    error::positive("dt", dt_s)?;
    if len == 0 || len > MAX_SERIES {
        return Err(Error::OutOfRange {
            param: "scans",
            value: len as f64,
            accepted: format!("1 to {MAX_SERIES} piston samples (scans x samples)"),
        });
    }
    let m = sequence_length(len);
    let half = m / 2;
    let dnu = 1.0 / (m as f64 * dt_s);
    let units = (half - 1).div_ceil(COEFF_BLOCK) as u64;
    let blocks = run_units(seed, units, threads, |u, rng| {
        let first = 1 + u as usize * COEFF_BLOCK;
        let last = (first + COEFF_BLOCK).min(half);
        (first..last)
            .map(|k| {
                let s = (psd(k as f64 * dnu) * dnu).sqrt();
                let g: f64 = StandardNormal.sample(rng);
                let h: f64 = StandardNormal.sample(rng);
                Complex64::new(s * g, s * h)
            })
            .collect::<Vec<_>>()
    });
    let mut buf = vec![Complex64::new(0.0, 0.0); m];
    for (dst, src) in buf[1..half].iter_mut().zip(blocks.into_iter().flatten()) {
        *dst = src;
    }
    FftPlanner::new().plan_fft_inverse(m).process(&mut buf);
    let root2 = std::f64::consts::SQRT_2;
    Ok(buf.iter().map(|z| root2 * z.re).collect())
}

/// The expected sample variance of [`synthesize_series`] output,
/// `Σ_{0<k<M/2} 2 P(ν_k) Δν`, and its standard deviation over realisations,
/// `√Σ (2 P(ν_k) Δν)²` (each pair of modes contributes an exponential
/// variable).
pub fn series_variance(psd: &dyn Fn(f64) -> f64, dt_s: f64, len: usize) -> (f64, f64) {
    let m = sequence_length(len);
    let dnu = 1.0 / (m as f64 * dt_s);
    let (mut mean, mut var) = (0.0, 0.0);
    for k in 1..m / 2 {
        let s = 2.0 * psd(k as f64 * dnu) * dnu;
        mean += s;
        var += s * s;
    }
    (mean, var.sqrt())
}

/// The fringe per unit continuum, `m(x) = Re Σ_j a_j e^{2πiσ_j x}`, tabulated
/// for fast evaluation on |x| ≤ `max_opd_um` (see the module docs).
#[derive(Debug, Clone)]
pub struct FringeTable {
    nodes: SpectralNodes,
    sigma_c: f64,
    x0: f64,
    h: f64,
    value: Vec<Complex64>,
    slope: Vec<Complex64>,
    carrier: Vec<Complex64>,
}

/// Largest carrier phase 2πσ_c h across one grid step, rad: the step's
/// carrier rotation is evaluated by its Taylor series to θ⁷, whose error
/// θ⁸/8! stays below 1e-15 there.
const MAX_STEP_PHASE: f64 = 0.06;

/// Interpolation error target of [`FringeTable`], relative to Σ|a_j|.
const TABLE_REL: f64 = crate::tolerance::FRINGE_TABLE_REL;

impl FringeTable {
    /// The table of the (unfiltered) fringe of `obs` over |x| ≤ `max_opd_um`.
    pub fn new(obs: &Observation, max_opd_um: f64) -> Result<FringeTable> {
        error::positive("max-opd", max_opd_um)?;
        // SpectralNodes sizes its Gauss–Legendre panels (16 points) to a
        // quarter fringe at the largest OPD it is given; a whole fringe per
        // panel already integrates e^{2πiσx} to ~1e-20 (the error of the
        // 16-point rule on one cycle is ~π³²/32!), so ask for a quarter of
        // the range: four times fewer nodes (checked against the full set
        // and the adaptive oracle in tests/piston.rs).
        let nodes = SpectralNodes::new(obs, 0.25 * max_opd_um, None);
        let (lo, hi) = nodes
            .sigma_per_um
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &s| {
                (a.min(s), b.max(s))
            });
        let sigma_c = if lo.is_finite() { 0.5 * (lo + hi) } else { 0.0 };
        let dmax = if lo.is_finite() { 0.5 * (hi - lo) } else { 0.0 };
        // Cubic Hermite error ≤ h⁴/384 · max|a''''| ≤ h⁴/384 · (2π dmax)⁴ Σ|a_j|.
        let h = if dmax > 0.0 {
            ((384.0 * TABLE_REL).powf(0.25) / (2.0 * PI * dmax)).min(0.5)
        } else {
            0.5
        };
        let h = if sigma_c > 0.0 {
            h.min(MAX_STEP_PHASE / (2.0 * PI * sigma_c))
        } else {
            h
        };
        let n = (2.0 * max_opd_um / h).ceil() as usize + 1;
        let h = 2.0 * max_opd_um / (n - 1) as f64;
        let x0 = -max_opd_um;
        let mut value = vec![Complex64::new(0.0, 0.0); n];
        let mut slope = vec![Complex64::new(0.0, 0.0); n];
        // Per node, march e^{2πiδ_j x} along the grid by complex
        // multiplication, re-anchored exactly every RESYNC steps.
        const RESYNC: usize = 128;
        for (&s, &a) in nodes.sigma_per_um.iter().zip(&nodes.amplitude) {
            let d = s - sigma_c;
            let w = 2.0 * PI * d;
            let step = Complex64::from_polar(1.0, w * h);
            let da = a * Complex64::new(0.0, w);
            let mut phase = Complex64::new(0.0, 0.0);
            for i in 0..n {
                if i % RESYNC == 0 {
                    phase = Complex64::from_polar(1.0, w * (x0 + i as f64 * h));
                } else {
                    phase *= step;
                }
                value[i] += a * phase;
                slope[i] += da * phase;
            }
        }
        let carrier = (0..n)
            .map(|i| Complex64::from_polar(1.0, 2.0 * PI * sigma_c * (x0 + i as f64 * h)))
            .collect();
        Ok(FringeTable {
            nodes,
            sigma_c,
            x0,
            h,
            value,
            slope,
            carrier,
        })
    }

    /// The nodes the table was built from.
    pub fn nodes(&self) -> &SpectralNodes {
        &self.nodes
    }

    /// Half-width of the tabulated OPD range, µm.
    pub fn max_opd_um(&self) -> f64 {
        -self.x0
    }

    /// m(x) per unit continuum at OPD `x_um` (beyond the table, the direct
    /// node sum).
    #[inline]
    pub fn fringe(&self, x_um: f64) -> f64 {
        let t = (x_um - self.x0) / self.h;
        let n = self.value.len();
        if !(t >= 0.0 && t < (n - 1) as f64) {
            return self.nodes.fringe(x_um);
        }
        let i = t as usize;
        let u = t - i as f64;
        let u2 = u * u;
        let u3 = u2 * u;
        let h00 = 2.0 * u3 - 3.0 * u2 + 1.0;
        let h10 = (u3 - 2.0 * u2 + u) * self.h;
        let h01 = 3.0 * u2 - 2.0 * u3;
        let h11 = (u3 - u2) * self.h;
        let a = self.value[i] * h00
            + self.slope[i] * h10
            + self.value[i + 1] * h01
            + self.slope[i + 1] * h11;
        // e^{2πiσ_c x} = carrier_i · e^{iθ}, θ = 2πσ_c u h ≤ MAX_STEP_PHASE.
        let th = 2.0 * PI * self.sigma_c * u * self.h;
        let t2 = th * th;
        let cos = 1.0 - t2 / 2.0 * (1.0 - t2 / 12.0 * (1.0 - t2 / 30.0 * (1.0 - t2 / 56.0)));
        let sin = th * (1.0 - t2 / 6.0 * (1.0 - t2 / 20.0 * (1.0 - t2 / 42.0)));
        let c = self.carrier[i];
        let (zr, zi) = (c.re * cos - c.im * sin, c.re * sin + c.im * cos);
        a.re * zr - a.im * zi
    }
}

/// How each sample sees the fringe.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Detector {
    /// The fringe at the sample time.
    Sampled,
    /// The fringe averaged over the sample's interval, with this many
    /// Gauss–Legendre sub-samples (1 … [`MAX_SUB_SAMPLES`]).
    Integrating {
        /// K.
        sub_samples: usize,
    },
}

impl Detector {
    /// Sub-sample offsets within a sample (units of the sample interval,
    /// centred on 0) and their weights (summing to 1).
    fn sub_samples(&self) -> Result<(Vec<f64>, Vec<f64>)> {
        match *self {
            Detector::Sampled => Ok((vec![0.0], vec![1.0])),
            Detector::Integrating { sub_samples } => {
                if !(1..=MAX_SUB_SAMPLES).contains(&sub_samples) {
                    return Err(Error::OutOfRange {
                        param: "sub-samples",
                        value: sub_samples as f64,
                        accepted: format!("1 to {MAX_SUB_SAMPLES}"),
                    });
                }
                let (x, w) = gauss_legendre(sub_samples);
                Ok((
                    x.iter().map(|u| 0.5 * u).collect(),
                    w.iter().map(|w| 0.5 * w).collect(),
                ))
            }
        }
    }

    /// `"sampled"` or `"integrating"`.
    pub fn name(&self) -> &'static str {
        match self {
            Detector::Sampled => "sampled",
            Detector::Integrating { .. } => "integrating",
        }
    }
}

/// Where the fringe packet sits in each scan.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum PistonReference {
    /// The piston at the time of the middle (zero-OPD) sample is removed:
    /// the scan is centred on the white-light fringe at that instant.
    Centre,
    /// The piston averaged over the scan is removed.
    Mean,
    /// Nothing is removed: the packet wanders with the absolute piston.
    Absolute,
}

impl PistonReference {
    /// Lowercase name.
    pub fn name(&self) -> &'static str {
        match self {
            PistonReference::Centre => "centre",
            PistonReference::Mean => "mean",
            PistonReference::Absolute => "absolute",
        }
    }
}

/// One scan's acquisition parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScanSetup {
    /// N.
    pub samples: usize,
    /// δx, µm.
    pub dx_um: f64,
    /// λ0 that defines the fringe frequency f = v/λ0, µm.
    pub wavelength_um: f64,
    /// f, Hz.
    pub fringe_hz: f64,
    /// Where the packet sits.
    pub reference: PistonReference,
}

impl ScanSetup {
    /// The paper's scans at fringe frequency `fringe_hz`: 128 samples of
    /// 0.5 µm (a 64 µm stroke, four samples per 2.0 µm fringe), λ0 = 2.2 µm,
    /// the packet centred on the scan-mean piston ([`PistonReference::Mean`]).
    pub fn paper(fringe_hz: f64) -> ScanSetup {
        ScanSetup {
            samples: 128,
            dx_um: 0.5,
            wavelength_um: 2.2,
            fringe_hz,
            reference: PistonReference::Mean,
        }
    }

    /// Checks the values.
    pub fn validate(&self) -> Result<()> {
        Sampling::new(self.samples, self.dx_um, false)?;
        error::positive("wavelength-um", self.wavelength_um)?;
        error::in_range("fringe-hz", self.fringe_hz, 1e-3, 1e7)?;
        Ok(())
    }

    /// OPD speed v = f λ0, µm/s.
    pub fn opd_speed_um_per_s(&self) -> f64 {
        self.fringe_hz * self.wavelength_um
    }
    /// Time per sample δx/v, s.
    pub fn sample_time_s(&self) -> f64 {
        self.dx_um / self.opd_speed_um_per_s()
    }
    /// Duration of one scan N δx / v, s.
    pub fn scan_time_s(&self) -> f64 {
        self.samples as f64 * self.sample_time_s()
    }
}

/// The modulated samples (per unit continuum, DFT order as
/// [`Sampling::opd_um`]) of one scan whose OPD error at time τ (in sample
/// intervals from the scan start, sample j centred on τ = j) is
/// `piston(τ)` µm; `reference_um` is subtracted from it.
pub fn scan_samples(
    table: &FringeTable,
    setup: &ScanSetup,
    detector: Detector,
    piston: impl Fn(f64) -> f64,
    reference_um: f64,
) -> Result<Vec<f64>> {
    let (u, w) = detector.sub_samples()?;
    let mut out = vec![0.0; setup.samples];
    fill_scan(table, setup, &u, &w, &piston, reference_um, &mut out);
    Ok(out)
}

#[inline]
fn fill_scan(
    table: &FringeTable,
    setup: &ScanSetup,
    u: &[f64],
    w: &[f64],
    piston: &impl Fn(f64) -> f64,
    reference_um: f64,
    out: &mut [f64],
) {
    let n = setup.samples;
    let half = n / 2;
    for j in 0..n {
        let nominal = (j as f64 - half as f64) * setup.dx_um;
        let mut acc = 0.0;
        for (&uk, &wk) in u.iter().zip(w) {
            let x = nominal + uk * setup.dx_um + piston(j as f64 + uk) - reference_um;
            acc += wk * table.fringe(x);
        }
        let i = (j + n - half) % n;
        out[i] = acc;
    }
}

/// Cubic (Catmull–Rom) interpolation of a periodic sequence at position t.
#[inline]
fn interp(series: &[f64], t: f64) -> f64 {
    let m = series.len();
    let fl = t.floor();
    let u = t - fl;
    if u == 0.0 {
        return series[(fl as i64).rem_euclid(m as i64) as usize];
    }
    let i = fl as i64;
    let (p0, p1, p2, p3) = if i >= 1 && (i as usize) + 2 < m {
        let i = i as usize;
        (series[i - 1], series[i], series[i + 1], series[i + 2])
    } else {
        let at = |k: i64| series[(i + k).rem_euclid(m as i64) as usize];
        (at(-1), at(0), at(1), at(2))
    };
    let u2 = u * u;
    let u3 = u2 * u;
    0.5 * ((2.0 * p1)
        + (-p0 + p2) * u
        + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * u2
        + (-p0 + 3.0 * p1 - 3.0 * p2 + p3) * u3)
}

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
            param: "seeing-arcsec",
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
