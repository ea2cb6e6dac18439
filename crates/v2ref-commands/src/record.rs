//! The `inputs` object that the JSON answers of `bias`, `snr` and `piston`
//! (CLI and Python) carry, so that an answer is a self-describing record.
//! The record states the values actually used: the baseline and the
//! spatial frequency whichever was given, σ_eff of the spectrum, the seeing
//! converted to the observing wavelength, and an infinite outer scale in
//! words.

// The plain values of the inputs (the oracle's), beside their records.
pub use v2ref_core::record::*;

use crate::formalism::{estimator::BinWindow, interferogram::Sampling, observation::Observation};
use serde::Serialize;

/// The observation: spectrum, source, where in the (u, v) plane, dispersion.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ObservationRecord {
    /// S(σ)F(σ): the flat band (λ0 µm, Δλ nm) or the table (σ µm⁻¹, weight).
    pub spectrum: SpectrumInput,
    /// The source.
    pub source: SourceInput,
    /// Projected baseline B, m.
    pub baseline_m: f64,
    /// S = B σ_eff, cycles/arcsec.
    pub spatial_freq_cpas: f64,
    /// σ_eff of the spectrum, µm⁻¹.
    pub sigma_eff_per_um: f64,
    /// Quadratic dispersion phase, peak-to-peak over the band, rad.
    pub dispersion_pp_rad: f64,
}

impl ObservationRecord {
    /// The record of `obs`, a view of `source`; `flat` is the (λ0 µm,
    /// Δλ nm) of a flat band (unused for a tabulated spectrum),
    /// `dispersion_pp_rad` as given.
    pub fn new(
        obs: &Observation,
        source: SourceInput,
        flat: (f64, f64),
        dispersion_pp_rad: f64,
    ) -> ObservationRecord {
        ObservationRecord {
            spectrum: SpectrumInput::from_spectrum(&obs.spectrum, flat),
            source,
            baseline_m: obs.baseline_m,
            spatial_freq_cpas: obs.spatial_freq_cpas(),
            sigma_eff_per_um: obs.spectrum.sigma_eff_per_um(),
            dispersion_pp_rad,
        }
    }
}

/// The scan: samples, spacing, stroke, detector and the bins summed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SamplingRecord {
    /// N.
    pub samples: usize,
    /// δx, µm.
    pub dx_um: f64,
    /// Δx = N δx, µm.
    pub stroke_um: f64,
    /// Integrating (true) or sampling detector.
    pub integrating: bool,
    /// The Fourier bins the estimators sum.
    pub bins: &'static str,
}

impl SamplingRecord {
    /// The record of `sampling` summed over `window`.
    pub fn new(sampling: &Sampling, window: BinWindow) -> SamplingRecord {
        SamplingRecord {
            samples: sampling.samples(),
            dx_um: sampling.dx_um(),
            stroke_um: sampling.stroke_um(),
            integrating: sampling.integrating(),
            bins: window.name(),
        }
    }
}

/// An outer scale: a length, or infinite (Kolmogorov).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(untagged)]
#[non_exhaustive]
pub enum OuterScale {
    /// von Kármán outer scale, m.
    Metres(f64),
    /// "infinite".
    Infinite(&'static str),
}

impl From<Option<f64>> for OuterScale {
    fn from(l0: Option<f64>) -> OuterScale {
        l0.map_or(OuterScale::Infinite("infinite"), OuterScale::Metres)
    }
}

/// The atmosphere and telescopes behind the piston.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AtmosphereRecord {
    /// Seeing as given, arcsec.
    pub seeing_arcsec: f64,
    /// Wavelength at which the seeing was given, µm.
    pub seeing_wavelength_um: f64,
    /// The seeing at the observing wavelength λ0 (r0 ∝ λ^(6/5)), arcsec.
    pub seeing_at_observing_arcsec: f64,
    /// λ0, µm.
    pub wavelength_um: f64,
    /// Wind speed, m/s (frozen flow along the baseline).
    pub wind_mps: f64,
    /// Telescope aperture diameter, m.
    pub aperture_m: f64,
    /// Outer scale, m, or "infinite".
    pub outer_scale_m: OuterScale,
    /// Where the fringe packet sits in each scan.
    pub reference: PistonReference,
    /// Sub-samples per sample of the integrating detector.
    pub sub_samples: usize,
}

/// The `inputs` object of an answer.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InputsRecord {
    /// The observation.
    pub observation: ObservationRecord,
    /// The scan, where the answer depends on it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sampling: Option<SamplingRecord>,
    /// The atmosphere, where the answer depends on it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub atmosphere: Option<AtmosphereRecord>,
}
