//! The physical inputs of one configuration, declared once.
//!
//! [`Physical`] holds every physical input that the commands share (the
//! band or spectrum, the source, where in the (u, v) plane, dispersion, the
//! scan and detector, the light and noise, the fringe frequency and the
//! atmosphere), with its default in [`Physical::default`]. Both edges fill
//! it — the CLI from its flags, Python from its keyword arguments (the same
//! names, `-` as `_`) — and hand it to the builders below, which make the
//! library's objects ([`Observation`], [`Sampling`], [`Inputs`], …). So a
//! default, a conversion or a check lives in one place; tests check that
//! the CLI's flag defaults and the Python signatures agree with it.
//!
//! [`PARAMETERS`] states each one's unit, accepted range and help text (the
//! library's checks in [`crate::bounds`] and the constructors enforce the
//! ranges): the CLI's `--help`, the Python docstrings and the docs' input
//! table are rendered from it. Both are written by one list of entries in
//! `parameters/table.rs`: adding a physical input is one entry there.

use crate::error::{Error, Result};
use crate::formalism::interferogram::Sampling;
use crate::formalism::observation::{Frequency, Observation};
use crate::formalism::phase::SpectralPhase;
use crate::formalism::source::Source;
use crate::formalism::spectrum::{Band, Spectrum};
use crate::noise::NoiseModel;
use crate::piston::turbulence::{seeing_at_wavelength_arcsec, Turbulence};
use crate::record::{AtmosphereRecord, ObservationRecord};
use crate::simulator::{Inputs, PistonInputs, SourceInput, SpectrumInput};
use serde::Serialize;
use std::path::{Path, PathBuf};

mod declare;
mod table;

pub use declare::{Input, Kind, Value};
pub use table::{refer_to, Parameter, Physical, PARAMETERS};

/// The source model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
pub enum SourceKind {
    /// Unresolved (V = 1).
    Point,
    /// Uniform disk of diameter --diameter-mas.
    Ud,
}

impl crate::words::Words for SourceKind {
    const WORDS: &'static [crate::words::Word<Self>] = &[
        crate::words::Word {
            word: "point",
            value: SourceKind::Point,
            help: "Unresolved (V = 1)",
        },
        crate::words::Word {
            word: "ud",
            value: SourceKind::Ud,
            help: "Uniform disk of diameter --diameter-mas",
        },
    ];
}

/// Library parameter names (in errors, [`crate::Error::param`]) whose
/// keyword is not the same name: the physical input or the edges' argument
/// that sets them.
const KEYWORD_OF_PARAM: &[(&str, &str)] = &[
    ("spectrum", "spectrum_csv"),
    ("peak_to_peak_rad", "dispersion_pp_rad"),
    ("photons_per_sample", "photons"),
    ("truth", "sidecar"),
];

/// The keyword that sets the library parameter `param` (the Python keyword
/// argument; the CLI's flag is `--` and it with `_` as `-`): an entry of
/// `KEYWORD_OF_PARAM`, else `param` with `-` as `_`.
pub fn keyword_of(param: &str) -> String {
    let p = param.replace('-', "_");
    KEYWORD_OF_PARAM
        .iter()
        .find(|(k, _)| *k == p)
        .map_or(p, |(_, f)| (*f).to_owned())
}

/// The spatial frequency when neither it nor the baseline is given,
/// cycles/arcsec: the paper's 18 m baseline in K.
pub const DEFAULT_SPATIAL_FREQ_CPAS: f64 = 40.0;

/// A tabulated spectrum and the name of the CSV file it was read from.
/// The edges read the file (`read_spectrum_file` of the crate `v2ref-files`, feature `files`) and
/// hand the table over: the numerics read no file. The name is kept for
/// what names the input (it is serialized as the name, and so is not read
/// back); the records hold the table.
#[derive(Debug, Clone, PartialEq)]
pub struct SpectrumFile {
    path: PathBuf,
    spectrum: Spectrum,
}

impl SpectrumFile {
    /// The table `spectrum`, read from the file `path`.
    pub fn new(path: &Path, spectrum: Spectrum) -> SpectrumFile {
        SpectrumFile {
            path: path.to_owned(),
            spectrum,
        }
    }

    /// The file's name.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The table.
    pub fn spectrum(&self) -> &Spectrum {
        &self.spectrum
    }
}

impl Serialize for SpectrumFile {
    /// As the file's name, the value the user gave.
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        self.path.serialize(s)
    }
}

impl Default for Physical {
    /// [`Physical::DEFAULT`].
    fn default() -> Self {
        Physical::DEFAULT
    }
}

impl Physical {
    /// Refuses a non-finite number and the spatial frequency given with the
    /// baseline (each edge calls it once, after filling the inputs).
    pub fn check(&self) -> Result<()> {
        for p in &PARAMETERS {
            match self.get(p) {
                Value::Number(v) if !v.is_finite() => {
                    return Err(Error::Invalid {
                        param: p.name,
                        reason: format!("{v} is not a finite number"),
                    })
                }
                _ => {}
            }
        }
        if self.spatial_freq_cpas.is_some() && self.baseline_m.is_some() {
            return Err(Error::Invalid {
                param: "baseline_m",
                reason: "cannot be used with spatial_freq_cpas (give one of them)".into(),
            });
        }
        Ok(())
    }

    /// The spectrum: the CSV table, else the band flat per unit wavenumber.
    pub fn spectrum(&self) -> Result<Spectrum> {
        match &self.spectrum_csv {
            Some(file) => Ok(file.spectrum().clone()),
            None => Ok(Spectrum::flat(Band::new(
                self.wavelength_um,
                self.bandwidth_um()?,
            )?)),
        }
    }

    /// `bandwidth_nm` in µm, for [`Band::new`]: checked here in nm so that
    /// a refusal quotes the number the user typed; the rule is
    /// [`crate::bounds::check_bandwidth`].
    fn bandwidth_um(&self) -> Result<f64> {
        crate::bounds::check_bandwidth("bandwidth_nm", 1e3, self.wavelength_um, self.bandwidth_nm)?;
        Ok(self.bandwidth_nm * 1e-3)
    }

    /// The source.
    pub fn source(&self) -> Result<Source> {
        match self.source {
            SourceKind::Point => Ok(Source::Point),
            SourceKind::Ud => Source::uniform_disk(self.diameter_mas),
        }
    }

    /// The source as the simulator's inputs and the records state it.
    pub fn source_input(&self) -> SourceInput {
        match self.source {
            SourceKind::Point => SourceInput::Point,
            SourceKind::Ud => SourceInput::Ud {
                diameter_mas: self.diameter_mas,
            },
        }
    }

    /// Where in the (u, v) plane: the baseline when given, else the spatial
    /// frequency (default [`DEFAULT_SPATIAL_FREQ_CPAS`]).
    pub fn frequency(&self) -> Frequency {
        match (self.spatial_freq_cpas, self.baseline_m) {
            (_, Some(b)) => Frequency::BaselineM(b),
            (Some(s), None) => Frequency::SpatialFreqCpas(s),
            (None, None) => Frequency::SpatialFreqCpas(DEFAULT_SPATIAL_FREQ_CPAS),
        }
    }

    /// The observation: spectrum, source, frequency and dispersion phase.
    pub fn observation(&self) -> Result<Observation> {
        let spectrum = self.spectrum()?;
        let phase = SpectralPhase::dispersion_peak_to_peak(&spectrum, self.dispersion_pp_rad)?;
        Observation::new(spectrum, self.source()?, self.frequency(), phase)
    }

    /// The record of `obs` (made from these inputs) for a JSON answer.
    pub fn record(&self, obs: &Observation) -> ObservationRecord {
        ObservationRecord::new(
            obs,
            self.source_input(),
            (self.wavelength_um, self.bandwidth_nm),
            self.dispersion_pp_rad,
        )
    }

    /// The sampling: from the stroke when given, else N samples.
    pub fn sampling(&self) -> Result<Sampling> {
        match self.stroke_um {
            Some(stroke) => Sampling::from_stroke(stroke, self.dx_um, self.integrating),
            None => Sampling::new(self.samples, self.dx_um, self.integrating),
        }
    }

    /// The noise model.
    pub fn noise(&self) -> Result<NoiseModel> {
        NoiseModel::new(self.read_noise, self.photon_noise)
    }

    /// The seeing at the observing wavelength, arcsec (r0 ∝ λ^(6/5) from
    /// where it was quoted).
    pub fn seeing_at_observing_arcsec(&self) -> Result<f64> {
        seeing_at_wavelength_arcsec(
            self.seeing_arcsec,
            self.seeing_wavelength_um.unwrap_or(self.wavelength_um),
            self.wavelength_um,
        )
    }

    /// The turbulence at the observing wavelength.
    pub fn turbulence(&self) -> Result<Turbulence> {
        Turbulence::from_seeing(
            self.seeing_at_observing_arcsec()?,
            self.wavelength_um,
            self.wind_mps,
            self.outer_scale_m,
        )
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
            reference: self.reference,
            sub_samples: self.sub_samples,
        })
    }

    /// The atmosphere and telescopes of the piston at `fringe_hz`.
    pub fn piston_inputs(&self, fringe_hz: f64) -> Result<PistonInputs> {
        Ok(PistonInputs {
            fringe_hz,
            wavelength_um: self.wavelength_um,
            seeing_arcsec: self.seeing_at_observing_arcsec()?,
            wind_mps: self.wind_mps,
            aperture_m: self.aperture_m,
            outer_scale_m: self.outer_scale_m,
            reference: self.reference,
            sub_samples: self.sub_samples,
        })
    }

    /// The simulator's inputs, checked ([`Inputs::validate`]).
    pub fn inputs(&self) -> Result<Inputs> {
        let inputs = self.inputs_unchecked()?;
        inputs.validate()?;
        Ok(inputs)
    }

    /// The simulator's inputs before the checks that involve N (a file's
    /// width may still set it).
    pub fn inputs_unchecked(&self) -> Result<Inputs> {
        let obs = self.observation()?;
        let sampling = self.sampling()?;
        // Checked with or without the piston, as the seeing is always given.
        self.seeing_at_observing_arcsec()?;
        Ok(Inputs {
            spectrum: SpectrumInput::from_spectrum(
                &obs.spectrum,
                (self.wavelength_um, self.bandwidth_nm),
            ),
            source: self.source_input(),
            baseline_m: obs.baseline_m,
            dispersion_pp_rad: self.dispersion_pp_rad,
            samples: sampling.samples(),
            dx_um: sampling.dx_um(),
            integrating: sampling.integrating(),
            photons: self.photons,
            visibility: self.visibility,
            read_noise: self.read_noise,
            photon_noise: self.photon_noise,
            piston: self.fringe_hz.map(|f| self.piston_inputs(f)).transpose()?,
        })
    }
}
