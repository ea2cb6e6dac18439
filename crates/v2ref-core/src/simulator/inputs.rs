//! Every physical input of an end-to-end simulation, as plain numbers in
//! the units of the command-line flags: what a synth set's sidecar records
//! (`inputs`), what `v2ref estimate` reads back, and what the library builds
//! its objects from ([`Inputs::observation`], [`Inputs::sampling`], …).

use crate::error::{self, Result};
use crate::formalism::interferogram::Sampling;
use crate::formalism::observation::{Frequency, Observation};
use crate::formalism::phase::SpectralPhase;
use crate::formalism::spectrum::{Band, Spectrum};
use crate::noise::NoiseModel;
use crate::piston::scan::{Detector, ScanSetup, DEFAULT_SUB_SAMPLES};
use crate::piston::spectrum::PistonSpectrum;
use crate::piston::turbulence::Turbulence;
use crate::record::PistonReference;
use serde::{Deserialize, Serialize};

pub use crate::record::{SourceInput, SpectrumInput};

/// The differential piston of §6: turbulence, telescopes and the scan speed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PistonInputs {
    /// Fringe frequency f = v/λ0, Hz.
    pub fringe_hz: f64,
    /// λ0 that defines the fringe frequency and the seeing, µm.
    pub wavelength_um: f64,
    /// Seeing λ0/r0 at `wavelength_um`, arcsec (0: no turbulence).
    pub seeing_arcsec: f64,
    /// Wind speed, m/s (frozen flow along the baseline).
    pub wind_mps: f64,
    /// Telescope aperture diameter, m.
    pub aperture_m: f64,
    /// von Kármán outer scale, m (None: infinite, Kolmogorov).
    pub outer_scale_m: Option<f64>,
    /// Where the fringe packet sits in each scan.
    pub reference: PistonReference,
    /// Gauss–Legendre sub-samples per sample of the integrating detector.
    pub sub_samples: usize,
}

impl PistonInputs {
    /// The paper's conditions (1″ seeing at 2.2 µm, 10 m/s, 0.45 m
    /// apertures, infinite outer scale, packet on the scan-mean piston) at
    /// fringe frequency `fringe_hz`.
    pub fn paper(fringe_hz: f64) -> PistonInputs {
        PistonInputs {
            fringe_hz,
            wavelength_um: 2.2,
            seeing_arcsec: 1.0,
            wind_mps: 10.0,
            aperture_m: 0.45,
            outer_scale_m: None,
            reference: PistonReference::Mean,
            sub_samples: DEFAULT_SUB_SAMPLES,
        }
    }

    /// The differential-piston spectrum on `baseline_m`.
    pub fn spectrum(&self, baseline_m: f64) -> Result<PistonSpectrum> {
        crate::bounds::check_aperture_m(self.aperture_m)?;
        let turb = Turbulence::from_seeing(
            self.seeing_arcsec,
            self.wavelength_um,
            self.wind_mps,
            self.outer_scale_m,
        )?;
        PistonSpectrum::new(turb, self.aperture_m, baseline_m)
    }
}

/// Every physical input of one end-to-end configuration.
///
/// # Example
///
/// ```
/// use v2ref_core::simulator::Inputs;
/// // The defaults: a 43 mas disk at 40 cycles/arcsec in the full K band,
/// // 128 samples of 0.5 µm, 10 photons per sample, photon noise only.
/// let inputs = Inputs::default();
/// let json = serde_json::to_string(&inputs).unwrap();
/// let back: Inputs = serde_json::from_str(&json).unwrap();
/// assert_eq!(back, inputs);
/// assert_eq!(inputs.sampling()?.samples(), 128);
/// # Ok::<(), v2ref_core::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Inputs {
    /// S(σ)F(σ).
    pub spectrum: SpectrumInput,
    /// The source.
    pub source: SourceInput,
    /// Projected baseline B, m (S = B σ_eff).
    pub baseline_m: f64,
    /// Quadratic dispersion phase, peak-to-peak over the band, rad.
    pub dispersion_pp_rad: f64,
    /// N, samples per scan.
    pub samples: usize,
    /// δx, µm.
    pub dx_um: f64,
    /// Integrating detector (each sample averages the fringe over δx).
    pub integrating: bool,
    /// Continuum photons per sample c (the flux of one beam pair at the
    /// detector during one sample).
    pub photons: f64,
    /// Visibility V scaling the fringe (0 to 1): the modulated samples are
    /// V times those of the source.
    pub visibility: f64,
    /// Detector noise standard deviation σ_det, photons per sample.
    pub read_noise: f64,
    /// Poisson photon noise on the counts.
    pub photon_noise: bool,
    /// Differential piston (None: none).
    pub piston: Option<PistonInputs>,
}

impl Default for Inputs {
    fn default() -> Inputs {
        Inputs {
            spectrum: SpectrumInput::Flat {
                wavelength_um: 2.2,
                bandwidth_nm: 400.0,
            },
            source: SourceInput::Ud { diameter_mas: 43.0 },
            baseline_m: 40.0
                / (Spectrum::flat(Band::k()).sigma_eff_per_um()
                    * crate::formalism::spectrum::CPAS_PER_M_PER_INV_UM),
            dispersion_pp_rad: 0.0,
            samples: 128,
            dx_um: 0.5,
            integrating: false,
            photons: 10.0,
            visibility: 1.0,
            read_noise: 0.0,
            photon_noise: true,
            piston: None,
        }
    }
}

impl Inputs {
    /// The observation (spectrum, source, baseline, dispersion).
    pub fn observation(&self) -> Result<Observation> {
        let spectrum = self.spectrum.spectrum()?;
        let phase = SpectralPhase::dispersion_peak_to_peak(&spectrum, self.dispersion_pp_rad)?;
        Observation::new(
            spectrum,
            self.source.source()?,
            Frequency::BaselineM(self.baseline_m),
            phase,
        )
    }

    /// The sampling.
    pub fn sampling(&self) -> Result<Sampling> {
        Sampling::new(self.samples, self.dx_um, self.integrating)
    }

    /// The noise model.
    pub fn noise(&self) -> Result<NoiseModel> {
        NoiseModel::new(self.read_noise, self.photon_noise)
    }

    /// The detector as the piston scans see it.
    pub fn detector(&self) -> Detector {
        match (self.integrating, &self.piston) {
            (false, _) => Detector::Sampled,
            (true, p) => Detector::Integrating {
                sub_samples: p.map_or(DEFAULT_SUB_SAMPLES, |p| p.sub_samples),
            },
        }
    }

    /// The scan setup of the piston scans, if there is piston.
    pub fn scan_setup(&self) -> Option<ScanSetup> {
        self.piston.map(|p| ScanSetup {
            samples: self.samples,
            dx_um: self.dx_um,
            wavelength_um: p.wavelength_um,
            fringe_hz: p.fringe_hz,
            reference: p.reference,
        })
    }

    /// Checks every value (the first refusal is returned).
    pub fn validate(&self) -> Result<()> {
        let obs = self.observation()?;
        self.sampling()?.check_aliasing(&obs)?;
        self.noise()?;
        crate::bounds::positive_at_most("photons", self.photons, crate::bounds::PHOTONS_MAX)?;
        error::in_range("visibility", self.visibility, 0.0, 1.0)?;
        if let Some(p) = &self.piston {
            p.spectrum(obs.baseline_m)?;
            self.scan_setup().map_or(Ok(()), |s| s.validate())?;
            self.detector().sub_samples()?;
        }
        Ok(())
    }
}
