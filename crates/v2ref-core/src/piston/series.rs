//! §6, *Effect of differential piston*: the differential-piston sequence
//! p(t) (µm) sampled at the scan's sample interval Δt (s), synthesised by FFT
//! from the two-sided spectrum P(ν) (µm²/Hz).
//!
//! # Piston sequences
//!
//! A Gaussian piston sequence with the two-sided spectrum P(ν) of
//! [`crate::piston::spectrum::PistonSpectrum`] is synthesised by FFT: with M
//! samples at step Δt, ν_k = k/(MΔt), the coefficients
//! `W_k = √(P(ν_k)Δν) (g + i g')` (g, g' standard normal) for
//! 0 < k < M/2 and `p_n = √2 Re Σ_k W_k e^{2πikn/M}` give
//! `⟨p²⟩ = Σ_{k≠0} P(ν_k) Δν` and the periodogram `E|W_k|² = 2P(ν_k)Δν`
//! (the mean over the period is removed: it sits below the lowest frequency
//! the sequence resolves). Consecutive scans read consecutive stretches of
//! one sequence, as in an observation.

use crate::error::{self, Error, Result};
use crate::math::fft::inverse_dft_with;
use crate::montecarlo::{in_pool, try_run_unit_range};
use num_complex::Complex64;

/// Largest piston sequence accepted (scans × samples), 2^24 samples.
pub const MAX_SERIES: usize = 1 << 24;

/// Coefficients generated per work unit in [`synthesize_series`].
const COEFF_BLOCK: usize = 1 << 15;

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
/// Deterministic in `seed` whatever the thread count: the coefficients are
/// drawn in fixed blocks, one generator each, and the transform is split
/// into rows ([`crate::math::fft::inverse_dft`]), all spread over
/// `threads` threads (0 = the current pool). Refuses (parameter `psd`) a
/// spectrum that is not a finite number >= 0 at some frequency drawn.
pub fn synthesize_series(
    psd: &(dyn Fn(f64) -> f64 + Sync),
    dt_s: f64,
    len: usize,
    seed: u64,
    threads: usize,
) -> Result<Vec<f64>> {
    ModeScales::new(psd, dt_s, len, threads)?.synthesize(seed, threads)
}

/// The scale `√(P(ν_k)Δν)` of each coefficient `W_k`, 0 < k < M/2, of
/// the M-sample sequences ([`sequence_length`]) at one step: what every
/// sequence of that length and step shares, computed once (evaluating the
/// spectrum is a third of a synthesis; the draws and the transform are
/// each sequence's own). [`ModeScales::synthesize`] then gives the bits
/// [`synthesize_series`] gives.
pub(crate) struct ModeScales {
    /// M, the FFT length.
    m: usize,
    /// Δt, s.
    dt_s: f64,
    /// `√(P(ν_k)Δν)` for k = 1 .. M/2 − 1, µm.
    scale: Vec<f64>,
}

impl ModeScales {
    /// The scales for sequences of `len` samples at step `dt_s`; refuses
    /// a step that is not positive, a length out of 1..=[`MAX_SERIES`]
    /// and a spectrum that is not a finite number >= 0 at some frequency.
    pub(crate) fn new(
        psd: &(dyn Fn(f64) -> f64 + Sync),
        dt_s: f64,
        len: usize,
        threads: usize,
    ) -> Result<ModeScales> {
        use rayon::prelude::*;
        error::positive("dt", dt_s)?;
        crate::montecarlo::check_threads(threads)?;
        if len == 0 || len > MAX_SERIES {
            return Err(Error::OutOfRange {
                param: "scans",
                value: len as f64,
                accepted: format!("1 to {MAX_SERIES} piston samples (scans x samples)"),
            });
        }
        let m = sequence_length(len);
        let dnu = 1.0 / (m as f64 * dt_s);
        let scale: Vec<f64> = in_pool(threads, || {
            Ok((1..m / 2)
                .into_par_iter()
                .with_min_len(COEFF_BLOCK)
                .map(|k| (psd(k as f64 * dnu) * dnu).sqrt())
                .collect())
        })?;
        crate::montecarlo::cancel::check()?;
        // A spectrum that is not a finite number >= 0 somewhere leaves a
        // scale that is not finite: refused, naming the frequency.
        if let Some(k) = scale.iter().position(|s| !s.is_finite()) {
            let nu_hz = (k + 1) as f64 * dnu;
            return Err(Error::Invalid {
                param: "psd",
                reason: format!(
                    "the spectrum at {nu_hz:e} Hz is {}; a power spectral density is a finite number >= 0",
                    psd(nu_hz)
                ),
            });
        }
        Ok(ModeScales { m, dt_s, scale })
    }

    /// Whether these are the scales of sequences of `len` samples at step
    /// `dt_s` (the same FFT length and step).
    pub(crate) fn fits(&self, len: usize, dt_s: f64) -> bool {
        len > 0 && sequence_length(len) == self.m && dt_s == self.dt_s
    }

    /// One sequence from `seed`: the coefficients drawn in fixed blocks,
    /// one generator each, then the M-point inverse transform.
    pub(crate) fn synthesize(&self, seed: u64, threads: usize) -> Result<Vec<f64>> {
        let (m, half) = (self.m, self.m / 2);
        let units = (half - 1).div_ceil(COEFF_BLOCK) as u64;
        // The runner checks for a cancellation between blocks.
        let blocks = try_run_unit_range(seed, 0..units, threads, |u, rng| {
            let first = 1 + u as usize * COEFF_BLOCK;
            let last = (first + COEFF_BLOCK).min(half);
            let block = self.scale[first - 1..last - 1]
                .iter()
                .map(|&s| {
                    let g: f64 = rng.standard_normal();
                    let h: f64 = rng.standard_normal();
                    Complex64::new(s * g, s * h)
                })
                .collect::<Vec<_>>();
            Ok(block)
        })?;
        let modes: Vec<Complex64> = blocks.concat();
        let zero = Complex64::new(0.0, 0.0);
        let coefficient = |k: usize| match k {
            1.. if k < half => modes[k - 1],
            _ => zero,
        };
        // The M-point transform split into rows over the threads
        // (crate::math::fft): same bits for any thread count.
        let root2 = std::f64::consts::SQRT_2;
        in_pool(threads, || {
            Ok(inverse_dft_with(m, coefficient, |z| root2 * z.re))
        })
    }
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
