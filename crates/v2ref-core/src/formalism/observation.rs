//! One wide-band observation: spectrum, source, baseline and spectral phase.
//!
//! The spatial frequency of a wide-band measurement is `S = B σ_eff`
//! (`docs/conventions.md`): a user may give either S (cycles/arcsec) or B (m);
//! the other follows from the spectrum's effective wavenumber.

use crate::error::Result;
use crate::formalism::phase::SpectralPhase;
use crate::formalism::source::Source;
use crate::formalism::spectrum::{Spectrum, CPAS_PER_M_PER_INV_UM};
use num_complex::Complex64;

/// Where on the (u, v) plane: a spatial frequency or a baseline.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Frequency {
    /// Spatial frequency at σ_eff, cycles/arcsec (≥ 0).
    SpatialFreqCpas(f64),
    /// Projected baseline, m (≥ 0).
    BaselineM(f64),
}

/// Everything that sets the noise-free fringe spectrum `W(σ) V(σ) e^{iφ(σ)}`.
///
/// # Example
///
/// ```
/// use v2ref_core::prelude::*;
/// use v2ref_core::formalism::estimator::{all_bins, positive_bins};
/// // The same baseline given as S = B σ_eff or as B.
/// let k = Spectrum::flat(Band::k());
/// let by_s = Observation::new(k.clone(), Source::Point, Frequency::SpatialFreqCpas(40.0), SpectralPhase::zero())?;
/// let by_b = Observation::new(k, Source::Point, Frequency::BaselineM(by_s.baseline_m), SpectralPhase::zero())?;
/// assert!((by_b.spatial_freq_cpas() - 40.0).abs() < 1e-12);
/// assert!((by_s.baseline_m - 18.0).abs() < 0.01); // the paper's 18 m in K
/// # Ok::<(), v2ref_core::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Observation {
    /// S(σ)F(σ).
    pub spectrum: Spectrum,
    /// The source.
    pub source: Source,
    /// Projected baseline B, m.
    pub baseline_m: f64,
    /// φ(σ) (dispersion), rad.
    pub phase: SpectralPhase,
}

impl Observation {
    /// An observation of `source` through `spectrum` at `frequency`, with
    /// spectral phase `phase`.
    pub fn new(
        spectrum: Spectrum,
        source: Source,
        frequency: Frequency,
        phase: SpectralPhase,
    ) -> Result<Observation> {
        use crate::bounds::{non_negative_at_most, BASELINE_MAX_M, SPATIAL_FREQ_MAX_CPAS};
        let baseline_m = match frequency {
            Frequency::SpatialFreqCpas(s) => {
                non_negative_at_most("spatial_freq_cpas", s, SPATIAL_FREQ_MAX_CPAS)?;
                s / (spectrum.sigma_eff_per_um() * CPAS_PER_M_PER_INV_UM)
            }
            Frequency::BaselineM(b) => non_negative_at_most("baseline_m", b, BASELINE_MAX_M)?,
        };
        Ok(Observation {
            spectrum,
            source,
            baseline_m,
            phase,
        })
    }

    /// `S = B σ_eff`, cycles/arcsec.
    pub fn spatial_freq_cpas(&self) -> f64 {
        self.baseline_m * self.spectrum.sigma_eff_per_um() * CPAS_PER_M_PER_INV_UM
    }

    /// The complex fringe amplitude per unit W at σ: `V(σ) e^{iφ(σ)}`.
    pub fn fringe_amplitude(&self, sigma_per_um: f64) -> Complex64 {
        let v = self.source.visibility(sigma_per_um, self.baseline_m);
        if self.phase.is_zero() {
            v
        } else {
            v * Complex64::from_polar(1.0, self.phase.at(sigma_per_um))
        }
    }

    /// The same observation of an unresolved source with no spectral phase:
    /// the calibrator that normalizes sampled estimators.
    pub fn calibrator(&self) -> Observation {
        Observation {
            spectrum: self.spectrum.clone(),
            source: Source::Point,
            baseline_m: self.baseline_m,
            phase: SpectralPhase::zero(),
        }
    }
}
