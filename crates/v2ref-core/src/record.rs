//! What a computation was asked, as plain values in the units of the
//! command-line flags: the inputs every level of the library shares (the
//! spectrum, the source, where the fringe packet sits in a scan), and the
//! `inputs` object that the JSON answers of `bias`, `snr` and `piston` (CLI
//! and Python) carry are built from them (the crate `v2ref-commands`).
//!
//! It sits just above [`crate::formalism`], below the paper's effects
//! ([`crate::bias`], [`crate::noise`], [`crate::piston`]) whose answers
//! carry it. The records a public answer carries are public at
//! [`crate::simulator`] and [`crate::piston`] (for [`PistonReference`]).

use crate::error::{self, Result};
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
