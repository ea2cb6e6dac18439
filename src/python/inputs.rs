//! The physical keyword arguments of the Python functions, with the CLI's
//! defaults, turned into the library's objects exactly as the CLI's flags
//! are (`src/cli/common.rs`, `src/cli/inputs.rs`).

use super::{parse_enum, Fail};
use crate::error::{Error, Result};
use crate::formalism::interferogram::Sampling;
use crate::formalism::observation::{Frequency, Observation};
use crate::formalism::phase::SpectralPhase;
use crate::formalism::source::Source;
use crate::formalism::spectrum::{Band, Spectrum};
use crate::piston::PistonReference;
use crate::simulator::record::{AtmosphereRecord, ObservationRecord};
use crate::simulator::{Inputs, PistonInputs, SourceInput, SpectrumInput};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// Every physical keyword argument (the CLI's flags, `-` as `_`).
#[derive(Debug, Clone)]
pub struct Physical {
    pub wavelength_um: f64,
    pub bandwidth_nm: f64,
    pub spectrum_csv: Option<PathBuf>,
    pub source: String,
    pub diameter_mas: f64,
    pub spatial_freq_cpas: Option<f64>,
    pub baseline_m: Option<f64>,
    pub dispersion_pp_rad: f64,
    pub stroke_um: Option<f64>,
    pub dx_um: f64,
    pub samples: usize,
    pub integrating: bool,
    pub visibility: f64,
    pub photons: f64,
    pub read_noise: f64,
    pub photon_noise: bool,
    pub fringe_hz: Option<f64>,
    pub wind_mps: f64,
    pub seeing_arcsec: f64,
    pub seeing_wavelength_um: Option<f64>,
    pub aperture_m: f64,
    pub outer_scale_m: Option<f64>,
    pub sub_samples: usize,
    pub reference: String,
}

/// The names accepted in the physical dictionary.
pub const NAMES: &[&str] = &[
    "wavelength_um",
    "bandwidth_nm",
    "spectrum_csv",
    "source",
    "diameter_mas",
    "spatial_freq_cpas",
    "baseline_m",
    "dispersion_pp_rad",
    "stroke_um",
    "dx_um",
    "samples",
    "integrating",
    "visibility",
    "photons",
    "read_noise",
    "photon_noise",
    "fringe_hz",
    "wind_mps",
    "seeing_arcsec",
    "seeing_wavelength_um",
    "aperture_m",
    "outer_scale_m",
    "sub_samples",
    "reference",
];

fn item<'py, T: FromPyObject<'py>>(d: &Bound<'py, PyDict>, key: &str, default: T) -> PyResult<T> {
    match d.get_item(key)? {
        Some(v) if !v.is_none() => v.extract().map_err(|e| {
            pyo3::exceptions::PyTypeError::new_err(format!(
                "{key}: {}",
                e.value(d.py())
                    .str()
                    .map(|s| s.to_string())
                    .unwrap_or_default()
            ))
        }),
        _ => Ok(default),
    }
}

/// A finite float (the CLI's `finite_f64` parser).
fn finite(key: &'static str, v: f64) -> Result<f64> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Error::Invalid {
            param: key,
            reason: format!("{v} is not a finite number"),
        })
    }
}

impl Physical {
    /// The physical inputs in `d` (missing or None: the CLI's default).
    pub fn from_dict(d: &Bound<'_, PyDict>) -> PyResult<Physical> {
        for (k, _) in d.iter() {
            let k: String = k.extract()?;
            if !NAMES.contains(&k.as_str()) {
                return Err(pyo3::exceptions::PyTypeError::new_err(format!(
                    "{k}: not a keyword argument (accepted: {})",
                    NAMES.join(", ")
                )));
            }
        }
        let p = Physical {
            wavelength_um: item(d, "wavelength_um", 2.2)?,
            bandwidth_nm: item(d, "bandwidth_nm", 400.0)?,
            spectrum_csv: item(d, "spectrum_csv", None)?,
            source: item(d, "source", "ud".to_owned())?,
            diameter_mas: item(d, "diameter_mas", 43.0)?,
            spatial_freq_cpas: item(d, "spatial_freq_cpas", None)?,
            baseline_m: item(d, "baseline_m", None)?,
            dispersion_pp_rad: item(d, "dispersion_pp_rad", 0.0)?,
            stroke_um: item(d, "stroke_um", None)?,
            dx_um: item(d, "dx_um", 0.5)?,
            samples: item(d, "samples", 128usize)?,
            integrating: item(d, "integrating", false)?,
            visibility: item(d, "visibility", 1.0)?,
            photons: item(d, "photons", 10.0)?,
            read_noise: item(d, "read_noise", 0.0)?,
            photon_noise: item(d, "photon_noise", true)?,
            fringe_hz: item(d, "fringe_hz", None)?,
            wind_mps: item(d, "wind_mps", 10.0)?,
            seeing_arcsec: item(d, "seeing_arcsec", 1.0)?,
            seeing_wavelength_um: item(d, "seeing_wavelength_um", None)?,
            aperture_m: item(d, "aperture_m", 0.45)?,
            outer_scale_m: item(d, "outer_scale_m", None)?,
            sub_samples: item(d, "sub_samples", crate::piston::DEFAULT_SUB_SAMPLES)?,
            reference: item(d, "reference", "mean".to_owned())?,
        };
        p.check_finite().map_err(|e| e.into_py_err())?;
        if p.spatial_freq_cpas.is_some() && p.baseline_m.is_some() {
            return Err(Error::Invalid {
                param: "baseline_m",
                reason: "cannot be used with spatial_freq_cpas (give one of them)".into(),
            }
            .into_py_err());
        }
        Ok(p)
    }

    /// The seeing at the observing wavelength, arcsec (converted from
    /// `seeing_wavelength_um` when given).
    pub fn seeing_at_observing_arcsec(&self) -> Result<f64> {
        crate::piston::turbulence::seeing_at_wavelength_arcsec(
            self.seeing_arcsec,
            self.seeing_wavelength_um.unwrap_or(self.wavelength_um),
            self.wavelength_um,
        )
    }

    fn check_finite(&self) -> Result<()> {
        for (k, v) in [
            ("wavelength_um", Some(self.wavelength_um)),
            ("bandwidth_nm", Some(self.bandwidth_nm)),
            ("diameter_mas", Some(self.diameter_mas)),
            ("spatial_freq_cpas", self.spatial_freq_cpas),
            ("baseline_m", self.baseline_m),
            ("dispersion_pp_rad", Some(self.dispersion_pp_rad)),
            ("stroke_um", self.stroke_um),
            ("dx_um", Some(self.dx_um)),
            ("visibility", Some(self.visibility)),
            ("photons", Some(self.photons)),
            ("read_noise", Some(self.read_noise)),
            ("fringe_hz", self.fringe_hz),
            ("wind_mps", Some(self.wind_mps)),
            ("seeing_arcsec", Some(self.seeing_arcsec)),
            ("seeing_wavelength_um", self.seeing_wavelength_um),
            ("aperture_m", Some(self.aperture_m)),
            ("outer_scale_m", self.outer_scale_m),
        ] {
            if let Some(v) = v {
                finite(k, v)?;
            }
        }
        Ok(())
    }

    /// The source kind.
    fn source_kind(&self) -> Result<bool> {
        match self.source.as_str() {
            "point" => Ok(false),
            "ud" => Ok(true),
            other => Err(Error::Invalid {
                param: "source",
                reason: format!("'{other}' is not one of: point, ud"),
            }),
        }
    }

    /// Where the fringe packet sits.
    pub fn reference(&self) -> Result<PistonReference> {
        parse_enum(
            "reference",
            &self.reference,
            &["centre", "mean", "absolute"],
        )
    }

    /// The spectrum (as `ObservationArgs::spectrum`).
    pub fn spectrum(&self) -> Result<Spectrum> {
        match &self.spectrum_csv {
            Some(path) => Spectrum::from_csv_path(path),
            None => Ok(Spectrum::flat(Band::new(
                self.wavelength_um,
                self.bandwidth_um()?,
            )?)),
        }
    }

    /// `bandwidth_nm` in µm, checked in nm (as the CLI).
    fn bandwidth_um(&self) -> Result<f64> {
        crate::bounds::check_bandwidth("bandwidth_nm", 1e3, self.wavelength_um, self.bandwidth_nm)?;
        Ok(self.bandwidth_nm * 1e-3)
    }

    /// The source.
    pub fn source(&self) -> Result<Source> {
        if self.source_kind()? {
            Source::uniform_disk(self.diameter_mas)
        } else {
            Ok(Source::Point)
        }
    }

    /// The observation (as `ObservationArgs::observation`).
    pub fn observation(&self) -> Result<Observation> {
        let spectrum = self.spectrum()?;
        let frequency = match (self.spatial_freq_cpas, self.baseline_m) {
            (_, Some(b)) => Frequency::BaselineM(b),
            (Some(s), None) => Frequency::SpatialFreqCpas(s),
            (None, None) => Frequency::SpatialFreqCpas(40.0),
        };
        let phase = SpectralPhase::dispersion_peak_to_peak(&spectrum, self.dispersion_pp_rad)?;
        Observation::new(spectrum, self.source()?, frequency, phase)
    }

    /// The sampling (as `ScanArgs::sampling`).
    /// The source as the simulator's inputs and the records state it.
    pub fn source_input(&self) -> Result<SourceInput> {
        Ok(if self.source_kind()? {
            SourceInput::Ud {
                diameter_mas: self.diameter_mas,
            }
        } else {
            SourceInput::Point
        })
    }

    /// The record of `obs` (made from this dictionary) for a JSON answer.
    pub fn record(&self, obs: &Observation) -> Result<ObservationRecord> {
        Ok(ObservationRecord::new(
            obs,
            self.source_input()?,
            (self.wavelength_um, self.bandwidth_nm),
            self.dispersion_pp_rad,
        ))
    }

    /// The atmosphere's record for a JSON answer.
    pub fn atmosphere_record(&self) -> Result<AtmosphereRecord> {
        Ok(AtmosphereRecord {
            seeing_arcsec: self.seeing_arcsec,
            seeing_wavelength_um: self.seeing_wavelength_um.unwrap_or(self.wavelength_um),
            seeing_at_observing_arcsec: self.seeing_at_observing_arcsec()?,
            wavelength_um: self.wavelength_um,
            wind_mps: self.wind_mps,
            aperture_m: self.aperture_m,
            outer_scale_m: self.outer_scale_m.into(),
            reference: self.reference()?,
            sub_samples: self.sub_samples,
        })
    }

    pub fn sampling(&self) -> Result<Sampling> {
        match self.stroke_um {
            Some(stroke) => Sampling::from_stroke(stroke, self.dx_um, self.integrating),
            None => Sampling::new(self.samples, self.dx_um, self.integrating),
        }
    }

    /// The noise model.
    pub fn noise(&self) -> Result<crate::noise::NoiseModel> {
        crate::noise::NoiseModel::new(self.read_noise, self.photon_noise)
    }

    /// The inputs, checked (as `InputsArgs::inputs`).
    pub fn inputs(&self) -> Result<Inputs> {
        let inputs = self.inputs_unchecked()?;
        inputs.validate()?;
        Ok(inputs)
    }

    /// The inputs before the checks that involve N (as
    /// `InputsArgs::inputs_unchecked`).
    pub fn inputs_unchecked(&self) -> Result<Inputs> {
        let obs = self.observation()?;
        let sampling = self.sampling()?;
        let reference = self.reference()?;
        let seeing_arcsec = self.seeing_at_observing_arcsec()?;
        Ok(Inputs {
            spectrum: SpectrumInput::from_spectrum(
                &obs.spectrum,
                (self.wavelength_um, self.bandwidth_nm),
            ),
            source: self.source_input()?,
            baseline_m: obs.baseline_m,
            dispersion_pp_rad: self.dispersion_pp_rad,
            samples: sampling.samples(),
            dx_um: sampling.dx_um(),
            integrating: sampling.integrating(),
            photons: self.photons,
            visibility: self.visibility,
            read_noise: self.read_noise,
            photon_noise: self.photon_noise,
            piston: self.fringe_hz.map(|f| PistonInputs {
                fringe_hz: f,
                wavelength_um: self.wavelength_um,
                seeing_arcsec,
                wind_mps: self.wind_mps,
                aperture_m: self.aperture_m,
                outer_scale_m: self.outer_scale_m,
                reference,
                sub_samples: self.sub_samples,
            }),
        })
    }
}
