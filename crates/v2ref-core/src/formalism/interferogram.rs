//! Sampled interferograms (paper, Section "Sampled signals" and Appendix
//! "Sampled interferogram formalism").
//!
//! Noise-free samples in photon units: `I_i = c_i + m_i` with a flat
//! continuum `c_i = c` and the modulated part
//!
//! `m_i = c · Re ∫ W(σ) V(σ) e^{iφ(σ)} e^{2πiσ x_i} s(σ) dσ`,
//!
//! so that an unresolved source without phase has `m_0 = c` (the Appendix's
//! `m_0 = n V`). `s(σ) = sinc(σ δx) = sin(πσδx)/(πσδx)` for an integrating
//! detector (each sample is the fringe averaged over its own δx, paper eq.
//! for γ_s with the door function), 1 for a sampling one.
//!
//! Sample positions: N samples at spacing δx with sample 0 on the
//! white-light fringe (`docs/conventions.md`). The scan is centred on it, in DFT
//! order: `x_i = i δx` for `i < ⌈N/2⌉` and `(i − N) δx` beyond, i.e. the
//! stroke `[−Δx/2, Δx/2)` of the paper's window `Π(x/Δx)`, replicated with
//! period Δx as the DFT assumes. A per-sample OPD perturbation `p_i` (piston)
//! is added to `x_i`.
//!
//! The fast path evaluates the integral on a fixed composite Gauss–Legendre
//! grid ([`SpectralNodes`]) sized to the largest |x| so that every panel spans
//! less than a quarter fringe; `crate::formalism::oracle` keeps the slow adaptive
//! version each test compares against.

use crate::error::{self, Error, Result};
use crate::formalism::observation::Observation;
use crate::math::quadrature::gauss_legendre;
use num_complex::Complex64;

/// Largest number of samples accepted (2^24).
pub const MAX_SAMPLES: usize = 1 << 24;

/// How the interferogram is sampled.
///
/// # Example
///
/// ```
/// use v2ref_core::prelude::*;
/// use v2ref_core::formalism::estimator::{all_bins, positive_bins};
/// // 128 samples of 0.5 µm: a 64 µm stroke centred on the white-light fringe,
/// // stored in DFT order (sample 0 at zero OPD, the negative half last).
/// let s = Sampling::new(128, 0.5, false)?;
/// assert_eq!(s.stroke_um(), 64.0);
/// assert_eq!((s.opd_um(0), s.opd_um(63), s.opd_um(64)), (0.0, 31.5, -32.0));
/// // Odd N: indices 0 … (N−1)/2 are the non-negative OPDs.
/// let odd = Sampling::new(7, 0.5, false)?;
/// assert_eq!((odd.opd_um(3), odd.opd_um(4)), (1.5, -1.5));
/// # Ok::<(), v2ref_core::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sampling {
    samples: usize,
    dx_um: f64,
    integrating: bool,
}

impl Sampling {
    /// N samples (2 … 2^24) at spacing δx (µm, > 0); `integrating` selects
    /// the integrating detector.
    pub fn new(samples: usize, dx_um: f64, integrating: bool) -> Result<Sampling> {
        if !(2..=MAX_SAMPLES).contains(&samples) {
            return Err(Error::OutOfRange {
                param: "samples",
                value: samples as f64,
                accepted: format!("2 to {MAX_SAMPLES}"),
            });
        }
        error::positive("dx_um", dx_um)?;
        if !(samples as f64 * dx_um).is_finite() {
            return Err(Error::OutOfRange {
                param: "dx_um",
                value: dx_um,
                accepted: format!("a spacing whose stroke over {samples} samples is finite"),
            });
        }
        Ok(Sampling {
            samples,
            dx_um,
            integrating,
        })
    }

    /// A scan of `stroke_um` (Δx) at spacing `dx_um`: N = round(Δx/δx).
    pub fn from_stroke(stroke_um: f64, dx_um: f64, integrating: bool) -> Result<Sampling> {
        error::positive("stroke_um", stroke_um)?;
        error::positive("dx_um", dx_um)?;
        let n = (stroke_um / dx_um).round();
        if !(2.0..=MAX_SAMPLES as f64).contains(&n) {
            return Err(Error::OutOfRange {
                param: "stroke_um",
                value: stroke_um,
                accepted: format!(
                    "{} to {} um at dx_um = {dx_um} (2 to {MAX_SAMPLES} samples)",
                    2.0 * dx_um,
                    MAX_SAMPLES as f64 * dx_um
                ),
            });
        }
        Self::new(n as usize, dx_um, integrating)
    }

    /// N.
    pub fn samples(&self) -> usize {
        self.samples
    }
    /// δx, µm.
    pub fn dx_um(&self) -> f64 {
        self.dx_um
    }
    /// Whether the detector integrates over each sample.
    pub fn integrating(&self) -> bool {
        self.integrating
    }
    /// Δx = N δx, µm.
    pub fn stroke_um(&self) -> f64 {
        self.samples as f64 * self.dx_um
    }
    /// δσ = 1/Δx, the bin spacing, µm⁻¹.
    pub fn delta_sigma_per_um(&self) -> f64 {
        1.0 / self.stroke_um()
    }
    /// OPD of sample i (DFT order, centred scan), µm.
    ///
    /// # Panics
    ///
    /// When `i` is not a sample of the scan (`i ≥ N`), as indexing past a
    /// slice does.
    pub fn opd_um(&self, i: usize) -> f64 {
        let n = self.samples;
        assert!(i < n, "sample {i} of a scan of {n} samples");
        let j = if i < n.div_ceil(2) {
            i as f64
        } else {
            i as f64 - n as f64
        };
        j * self.dx_um
    }

    /// Refuses a spacing that aliases the band: requires `δx < 1/(2 σ_max)`.
    pub fn check_aliasing(&self, obs: &Observation) -> Result<()> {
        let sigma_max = obs.spectrum.support().1;
        let max_dx_um = 0.5 / sigma_max;
        if self.dx_um >= max_dx_um {
            return Err(Error::Aliasing {
                dx_um: self.dx_um,
                max_dx_um,
            });
        }
        Ok(())
    }
}

/// Below this |u|, [`sinc`] uses its Taylor series to (πu)⁴: the next term,
/// (πu)⁶/5040 < 2e-22, is far below an ulp; the series avoids the 0/0 at
/// u = 0.
const SINC_SERIES_BELOW: f64 = 1e-4;

/// Half-step (µm⁻¹) of the central difference that estimates the slope of
/// the spectral phase when sizing the quadrature panels: only the order of
/// magnitude of the rate matters there.
const PHASE_STEP_PER_UM: f64 = 1e-6;

/// From 2^52 on, every f64 is an integer.
const SINC_INTEGERS_FROM: f64 = 4_503_599_627_370_496.0;

/// `sinc(u) = sin(πu)/(πu)`, 1 at 0.
pub fn sinc(u: f64) -> f64 {
    if u.abs() >= SINC_INTEGERS_FROM {
        // Every f64 this large is an integer, a zero of sin(πu) (and π u
        // itself may overflow to ∞, whose sine is NaN).
        0.0
    } else if u.abs() < SINC_SERIES_BELOW {
        let p = std::f64::consts::PI * u;
        1.0 - p * p / 6.0 + p.powi(4) / 120.0
    } else {
        let p = std::f64::consts::PI * u;
        p.sin() / p
    }
}

/// Gauss–Legendre points per panel of [`SpectralNodes`].
const NODES_PER_PANEL: usize = 16;
/// Largest phase change of the integrand across one panel, in cycles.
const CYCLES_PER_PANEL: f64 = 0.25;

/// Most nodes [`SpectralNodes::new`] makes (2^28, 6 GiB of nodes): a
/// scan of the most samples ([`MAX_SAMPLES`]) at its Nyquist spacing needs
/// fewer than 2^27.
pub const MAX_SPECTRAL_NODES: usize = 1 << 28;

/// The panels of [`SpectralNodes`]: for each piece `(a, b)` of the
/// spectrum (σ, µm⁻¹), as many panels as keep the phase change of the
/// integrand across one within [`CYCLES_PER_PANEL`] for |x| ≤ `max_opd_um`.
fn panel_plan(obs: &Observation, max_opd_um: f64) -> Vec<(f64, f64, usize)> {
    let spectrum = &obs.spectrum;
    // Cycles per unit σ of everything that oscillates in the integrand:
    // the fringe term, the disk's Bessel lobes (z = πθBσ, ~1/2 cycle per
    // π of z), the dispersion phase.
    let disk_rate = match &obs.source {
        crate::formalism::source::Source::UniformDisk { diameter_mas } => {
            0.5 * diameter_mas
                * crate::formalism::source::ARCSEC_PER_MAS
                * obs.baseline_m
                * crate::formalism::spectrum::CPAS_PER_M_PER_INV_UM
        }
        _ => 0.0,
    };
    let (lo, hi) = spectrum.support();
    let phase_rate = {
        let d = |s: f64| {
            (obs.phase.at(s + PHASE_STEP_PER_UM) - obs.phase.at(s - PHASE_STEP_PER_UM))
                / (2.0 * PHASE_STEP_PER_UM)
        };
        d(lo).abs().max(d(hi).abs()) / (2.0 * std::f64::consts::PI)
    };
    let rate = max_opd_um.abs() + disk_rate + phase_rate + 1.0 / (hi - lo);
    let pieces = spectrum.pieces(&obs.source.features_per_um());
    pieces
        .windows(2)
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            let panels = ((b - a) * rate / CYCLES_PER_PANEL).ceil().max(1.0) as usize;
            (a, b, panels)
        })
        .collect()
}

/// The fringe spectrum `W V e^{iφ} s` on a quadrature grid: σ_j and
/// `a_j = w_j W(σ_j) V(σ_j) e^{iφ(σ_j)} s(σ_j)`, so that the modulated
/// signal per unit continuum at OPD x is `Re Σ_j a_j e^{2πiσ_j x}`.
#[derive(Debug, Clone, PartialEq)]
pub struct SpectralNodes {
    /// σ_j, µm⁻¹.
    pub sigma_per_um: Vec<f64>,
    /// a_j (dimensionless: W dσ V e^{iφ} s).
    pub amplitude: Vec<Complex64>,
}

impl SpectralNodes {
    /// Nodes that resolve the fringe spectrum of `obs` for |x| ≤ `max_opd_um`;
    /// `integrating_dx_um` applies the integrating detector's sinc(σδx).
    /// More than [`MAX_SPECTRAL_NODES`] nodes (an OPD far beyond any scan's)
    /// are refused before any is made.
    pub fn new(
        obs: &Observation,
        max_opd_um: f64,
        integrating_dx_um: Option<f64>,
    ) -> Result<SpectralNodes> {
        error::finite("max_opd_um", max_opd_um)?;
        if let Some(dx) = integrating_dx_um {
            error::positive("integrating_dx_um", dx)?;
        }
        let count = SpectralNodes::count(obs, max_opd_um);
        if count > MAX_SPECTRAL_NODES {
            return Err(Error::OutOfRange {
                param: "max_opd_um",
                value: max_opd_um,
                accepted: format!(
                    "an OPD resolved by at most {MAX_SPECTRAL_NODES} spectral nodes ({count} needed)"
                ),
            });
        }
        let spectrum = &obs.spectrum;
        let filter = |s: f64| integrating_dx_um.map_or(1.0, |dx| sinc(s * dx));
        if spectrum.is_monochromatic() {
            let s = spectrum.sigma_eff_per_um();
            return Ok(SpectralNodes {
                sigma_per_um: vec![s],
                amplitude: vec![obs.fringe_amplitude(s) * filter(s)],
            });
        }
        // NODES_PER_PANEL (16) is within the rule's range: this cannot fail.
        let (gx, gw) = gauss_legendre(NODES_PER_PANEL).expect("16 Gauss-Legendre nodes");
        let mut sigma = Vec::new();
        let mut amplitude = Vec::new();
        for (a, b, panels) in panel_plan(obs, max_opd_um) {
            let h = (b - a) / panels as f64;
            for p in 0..panels {
                let c = a + (p as f64 + 0.5) * h;
                for (x, wt) in gx.iter().zip(&gw) {
                    let s = c + 0.5 * h * x;
                    let weight = spectrum.weight(s);
                    if weight == 0.0 {
                        continue;
                    }
                    sigma.push(s);
                    amplitude.push(obs.fringe_amplitude(s) * (0.5 * h * wt * weight * filter(s)));
                }
            }
        }
        Ok(SpectralNodes {
            sigma_per_um: sigma,
            amplitude,
        })
    }

    /// How many nodes [`SpectralNodes::new`] makes for `obs` and
    /// `max_opd_um` at most (the nodes of zero weight are dropped), without
    /// making them: what a sample of the interferogram costs.
    pub fn count(obs: &Observation, max_opd_um: f64) -> usize {
        if obs.spectrum.is_monochromatic() {
            return 1;
        }
        panel_plan(obs, max_opd_um)
            .iter()
            .map(|&(_, _, panels)| panels.saturating_mul(NODES_PER_PANEL))
            .fold(0, usize::saturating_add)
    }

    /// `Re Σ_j a_j e^{2πiσ_j x}`: the modulated signal per unit continuum at
    /// OPD `x_um`.
    pub fn fringe(&self, x_um: f64) -> f64 {
        let tau = 2.0 * std::f64::consts::PI * x_um;
        self.sigma_per_um
            .iter()
            .zip(&self.amplitude)
            .map(|(&s, a)| {
                let (sin, cos) = (tau * s).sin_cos();
                a.re * cos - a.im * sin
            })
            .sum()
    }
}

/// A noise-free sampled interferogram in photon units.
///
/// # Example
///
/// ```
/// use v2ref_core::prelude::*;
/// use v2ref_core::formalism::estimator::{all_bins, positive_bins};
/// // An unresolved source without spectral phase: m_0 = c (full contrast at
/// // zero OPD).
/// let obs = Observation::new(Spectrum::flat(Band::k()), Source::Point, Frequency::BaselineM(18.0), SpectralPhase::zero())?;
/// let ifg = Interferogram::synthesize(&obs, &Sampling::new(128, 0.5, false)?, 100.0, None)?;
/// assert!((ifg.modulated[0] - 100.0).abs() < 1e-9);
/// assert!(ifg.continuum.iter().all(|&c| c == 100.0));
/// # Ok::<(), v2ref_core::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Interferogram {
    /// c_i, photons per sample.
    pub continuum: Vec<f64>,
    /// m_i, photons per sample.
    pub modulated: Vec<f64>,
}

impl Interferogram {
    /// Synthesizes the interferogram of `obs` with `photons_per_sample`
    /// continuum photons (c) per sample, optionally with an OPD perturbation
    /// `opd_perturbation_um[i]` added to sample i (DFT order).
    pub fn synthesize(
        obs: &Observation,
        sampling: &Sampling,
        photons_per_sample: f64,
        opd_perturbation_um: Option<&[f64]>,
    ) -> Result<Interferogram> {
        crate::bounds::non_negative_at_most(
            "photons_per_sample",
            photons_per_sample,
            crate::bounds::PHOTONS_MAX,
        )?;
        sampling.check_aliasing(obs)?;
        let n = sampling.samples();
        if let Some(p) = opd_perturbation_um {
            if p.len() != n {
                return Err(Error::Invalid {
                    param: "opd_perturbation_um",
                    reason: format!("{} values for {n} samples", p.len()),
                });
            }
            if let Some(&bad) = p.iter().find(|v| !v.is_finite()) {
                return Err(Error::NotFinite {
                    param: "opd_perturbation_um",
                    value: bad,
                });
            }
        }
        let x = |i: usize| sampling.opd_um(i) + opd_perturbation_um.map_or(0.0, |p| p[i]);
        let max_opd = (0..n).map(|i| x(i).abs()).fold(0.0, f64::max);
        let nodes = SpectralNodes::new(
            obs,
            max_opd,
            sampling.integrating().then_some(sampling.dx_um()),
        )?;
        // N samples × N-proportional nodes: the one long loop of a large N
        // (5 s at N = 16384), stopped between samples when cancelled.
        let modulated = crate::montecarlo::map_items(n, nodes.sigma_per_um.len(), |i| {
            photons_per_sample * nodes.fringe(x(i))
        })?;
        Ok(Interferogram {
            continuum: vec![photons_per_sample; n],
            modulated,
        })
    }

    /// Mean total count per sample, `n_i = c_i + m_i`.
    pub fn mean_counts(&self) -> Vec<f64> {
        self.continuum
            .iter()
            .zip(&self.modulated)
            .map(|(c, m)| c + m)
            .collect()
    }
}
