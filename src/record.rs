//! What a computation was asked, as plain values in the units of the
//! command-line flags: the inputs every level of the library shares (the
//! spectrum, the source, where the fringe packet sits in a scan), and the
//! `inputs` object that the JSON answers of `bias`, `snr` and `piston` (CLI
//! and Python) carry, so that an answer is a self-describing record. The
//! record states the values actually used: the baseline and the spatial
//! frequency whichever was given, σ_eff of the spectrum, the seeing
//! converted to the observing wavelength, and an infinite outer scale in
//! words.
//!
//! It sits just above [`crate::formalism`], below the paper's effects
//! ([`crate::bias`], [`crate::noise`], [`crate::piston`]) whose answers
//! carry it. The module is internal (feature `internals`); the records a
//! public answer carries are public at [`crate::simulator`] and
//! [`crate::piston`] (for [`PistonReference`]).

use crate::error::{self, Result};
// (The answers' records, below, are built for the edges only.)
#[cfg(feature = "internals")]
use crate::formalism::{
    estimator::BinWindow, interferogram::Sampling, observation::Observation,
};
use crate::formalism::source::Source;
use crate::formalism::spectrum::{Band, Spectrum};
use serde::{Deserialize, Serialize};

/// S(σ)F(σ): a flat band or a table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
#[non_exhaustive]
pub enum SpectrumInput {
    /// Flat in wavenumber over [λ0 − Δλ/2, λ0 + Δλ/2].
    Flat {
        /// λ0, µm.
        wavelength_um: f64,
        /// Δλ, nm.
        bandwidth_nm: f64,
    },
    /// Piecewise linear through (σ_j, w_j), zero outside.
    Table {
        /// σ_j, µm⁻¹, strictly increasing.
        wavenumber_per_um: Vec<f64>,
        /// w_j ≥ 0 (any scale).
        weight: Vec<f64>,
    },
}

impl SpectrumInput {
    /// The spectrum.
    pub fn spectrum(&self) -> Result<Spectrum> {
        match self {
            SpectrumInput::Flat {
                wavelength_um,
                bandwidth_nm,
            } => {
                error::positive("bandwidth_nm", *bandwidth_nm)?;
                Ok(Spectrum::flat(Band::new(
                    *wavelength_um,
                    bandwidth_nm * 1e-3,
                )?))
            }
            SpectrumInput::Table {
                wavenumber_per_um,
                weight,
            } => Spectrum::tabulated(wavenumber_per_um.clone(), weight.clone()),
        }
    }

    /// The table of a tabulated spectrum, else the flat band.
    pub fn from_spectrum(spectrum: &Spectrum, flat: (f64, f64)) -> SpectrumInput {
        match spectrum.table() {
            Some((s, w)) => SpectrumInput::Table {
                wavenumber_per_um: s.to_vec(),
                weight: w.to_vec(),
            },
            None => SpectrumInput::Flat {
                wavelength_um: flat.0,
                bandwidth_nm: flat.1,
            },
        }
    }
}

/// The source.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
#[non_exhaustive]
pub enum SourceInput {
    /// Unresolved.
    Point,
    /// Uniform disk.
    Ud {
        /// θ, mas.
        diameter_mas: f64,
    },
}

impl SourceInput {
    /// The source.
    pub fn source(&self) -> Result<Source> {
        match *self {
            SourceInput::Point => Ok(Source::Point),
            SourceInput::Ud { diameter_mas } => Source::uniform_disk(diameter_mas),
        }
    }
}

/// Where the fringe packet sits in each scan.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
pub enum PistonReference {
    /// The piston at the time of the middle (zero-OPD) sample is removed:
    /// the scan is centred on the white-light fringe at that instant.
    Centre,
    /// The piston averaged over the scan is removed.
    Mean,
    /// Nothing is removed: the packet wanders with the absolute piston.
    Absolute,
}

impl crate::words::Words for PistonReference {
    const WORDS: &'static [crate::words::Word<Self>] = &[
        crate::words::Word {
            word: "centre",
            value: PistonReference::Centre,
            help: "The piston at the time of the middle (zero-OPD) sample is removed: the scan is centred on the white-light fringe at that instant",
        },
        crate::words::Word {
            word: "mean",
            value: PistonReference::Mean,
            help: "The piston averaged over the scan is removed",
        },
        crate::words::Word {
            word: "absolute",
            value: PistonReference::Absolute,
            help: "Nothing is removed: the packet wanders with the absolute piston",
        },
    ];
}

impl PistonReference {
    /// Lowercase name.
    pub fn name(&self) -> &'static str {
        crate::words::Words::word(*self)
    }
}

#[cfg(feature = "internals")]
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

#[cfg(feature = "internals")]
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

#[cfg(feature = "internals")]
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

#[cfg(feature = "internals")]
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

#[cfg(feature = "internals")]
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

#[cfg(feature = "internals")]
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
