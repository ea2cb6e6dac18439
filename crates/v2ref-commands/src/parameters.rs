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
//! The edges fill it through serde: the CLI serializes the flags it was
//! given and Python converts its keyword arguments to JSON, and
//! [`Physical::overlay`] deserializes them over the defaults (an unknown
//! name refused with the nearest one, a value of the wrong type naming its
//! field). [`PARAMETERS`] states each one's unit, accepted range and help
//! text (the library's checks in [`crate::bounds`] and the constructors
//! enforce the ranges): adding a physical input is a field here and an
//! entry there.

use crate::error::{Error, Result};
use crate::formalism::interferogram::Sampling;
use crate::formalism::observation::{Frequency, Observation};
use crate::formalism::phase::SpectralPhase;
use crate::formalism::source::Source;
use crate::formalism::spectrum::{Band, Spectrum};
use crate::noise::NoiseModel;
use crate::piston::turbulence::{seeing_at_wavelength_arcsec, Turbulence};
use crate::record::{AtmosphereRecord, ObservationRecord, PistonReference};
use crate::simulator::{Inputs, PistonInputs, SourceInput, SpectrumInput};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

mod channels;
mod table;

pub use channels::{renamed_channels, ChannelsFile, CHANNEL_INPUTS};
pub use table::{refer_to, Parameter, PARAMETERS};

/// Every physical input of one configuration (see the module doc). Field
/// names are the Python keyword arguments and, with `_` as `-`, the CLI's
/// flags (`photon_noise` is turned off by `--no-photon-noise`). Missing
/// fields take [`Physical::DEFAULT`]'s; an unknown one is refused.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Physical {
    /// Centre wavelength λ0, µm.
    pub wavelength_um: f64,
    /// Full bandwidth Δλ, nm (flat per unit wavenumber).
    pub bandwidth_nm: f64,
    /// A tabulated S(σ)F(σ) instead of the flat band: a CSV file's table,
    /// read by the edges ([`SpectrumFile`]).
    #[serde(skip_deserializing)]
    pub spectrum_csv: Option<SpectrumFile>,
    /// C spectral channels of equal width in wavenumber over the band
    /// (`crate::formalism::channels::Channels::equal`).
    pub channels: Option<usize>,
    /// Channels of resolving power R = λ/Δλ across the band
    /// (`crate::formalism::channels::Channels::from_resolution`).
    pub resolution: Option<f64>,
    /// Channels' edges and responses from a CSV file's text, read by the
    /// edges ([`ChannelsFile`]).
    #[serde(skip_deserializing)]
    pub channels_csv: Option<ChannelsFile>,
    /// Source model.
    pub source: SourceKind,
    /// Uniform-disk diameter θ, mas.
    pub diameter_mas: f64,
    /// Spatial frequency S = B σ_eff, cycles/arcsec (default
    /// [`DEFAULT_SPATIAL_FREQ_CPAS`] when no baseline is given either).
    pub spatial_freq_cpas: Option<f64>,
    /// Projected baseline B, m (instead of the spatial frequency).
    pub baseline_m: Option<f64>,
    /// Quadratic dispersion phase, peak-to-peak over the band, rad.
    pub dispersion_pp_rad: f64,
    /// OPD stroke Δx, µm (sets N = Δx/δx; else N = `samples`).
    pub stroke_um: Option<f64>,
    /// Sample spacing δx, µm.
    pub dx_um: f64,
    /// Number of samples N (ignored when `stroke_um` is given).
    pub samples: usize,
    /// Integrating detector (each sample averages the fringe over δx).
    pub integrating: bool,
    /// Visibility V scaling the fringe.
    pub visibility: f64,
    /// Continuum photons per sample n.
    pub photons: f64,
    /// Detector noise standard deviation σ_det, photons per sample.
    pub read_noise: f64,
    /// Poisson photon noise on (else detector noise only).
    pub photon_noise: bool,
    /// Fringe frequency f = v/λ0, Hz: the differential piston is on when
    /// given.
    pub fringe_hz: Option<f64>,
    /// Wind speed, m/s (frozen flow along the baseline).
    pub wind_mps: f64,
    /// Seeing λ/r0, arcsec, at `seeing_wavelength_um`.
    pub seeing_arcsec: f64,
    /// Where the seeing is quoted, µm (default: the observing wavelength).
    pub seeing_wavelength_um: Option<f64>,
    /// Telescope aperture diameter, m.
    pub aperture_m: f64,
    /// von Kármán outer scale, m (None: infinite).
    pub outer_scale_m: Option<f64>,
    /// Sub-samples per sample of the integrating detector under piston.
    pub sub_samples: usize,
    /// Where the fringe packet sits in each scan.
    pub reference: PistonReference,
}

impl Physical {
    /// The defaults: the paper's K-band case, a 43 mas disk at 40
    /// cycles/arcsec, 400 nm at 2.2 µm, 128 samples of 0.5 µm, 10 photons
    /// per sample.
    pub const DEFAULT: Physical = Physical {
        wavelength_um: 2.2,
        bandwidth_nm: 400.0,
        spectrum_csv: None,
        channels: None,
        resolution: None,
        channels_csv: None,
        source: SourceKind::Ud,
        diameter_mas: 43.0,
        spatial_freq_cpas: None,
        baseline_m: None,
        dispersion_pp_rad: 0.0,
        stroke_um: None,
        dx_um: 0.5,
        samples: 128,
        integrating: false,
        visibility: 1.0,
        photons: 10.0,
        read_noise: 0.0,
        photon_noise: true,
        fringe_hz: None,
        wind_mps: 10.0,
        seeing_arcsec: 1.0,
        seeing_wavelength_um: None,
        aperture_m: 0.45,
        outer_scale_m: None,
        sub_samples: crate::piston::DEFAULT_SUB_SAMPLES,
        reference: PistonReference::Mean,
    };
}

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
/// The edges read the file (`spectrum_from_csv_path` of the crate `v2ref-files`) and
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

/// The message for `name`, which is no physical input: the nearest
/// input's name offered when it is close (at most a third of its letters
/// changed).
pub fn unknown_input(name: &str) -> String {
    match nearest_input(name) {
        Some(near) => format!("{name}: not a physical input; did you mean '{near}'?"),
        None => format!("{name}: not a physical input"),
    }
}

/// The physical input's name nearest to `name` in edits, when at most a
/// third of its letters differ.
pub fn nearest_input(name: &str) -> Option<&'static str> {
    PARAMETERS
        .iter()
        .map(|p| (strsim::levenshtein(name, p.name), p.name))
        .min()
        .filter(|(d, near)| 3 * d <= near.len().max(name.len()))
        .map(|(_, near)| near)
}

impl Default for Physical {
    /// [`Physical::DEFAULT`].
    fn default() -> Self {
        Physical::DEFAULT
    }
}

impl Physical {
    /// These inputs with the values of `given`, a JSON object of field names
    /// and values as serde reads [`Physical`] (a null leaves the field as
    /// it is), or [`Error::Invalid`] naming the first field refused: a name
    /// that is no field (with the nearest one), a spectrum's table (which
    /// the edges read from its file), a value of the wrong type. Nothing is
    /// changed unless every value is taken.
    pub fn overlay(&mut self, given: serde_json::Value) -> Result<()> {
        use serde_json::{Map, Value};
        let Value::Object(given) = given else {
            return Err(Error::Invalid {
                param: "physical inputs",
                reason: format!("{given}: not a map of input names to values"),
            });
        };
        let mut all = match serde_json::to_value(&*self) {
            Ok(Value::Object(m)) => m,
            _ => unreachable!("a struct serializes as a JSON object"),
        };
        all.remove("spectrum_csv");
        all.remove("channels_csv");
        for (name, value) in given.into_iter().filter(|(_, v)| !v.is_null()) {
            let entry = match Parameter::named(&name) {
                Some(p) if !p.name.ends_with("_csv") => p,
                Some(p) => {
                    return Err(Error::Invalid {
                        param: p.name,
                        reason: "a table is read by the edges from its file".into(),
                    })
                }
                None => {
                    return Err(Error::Invalid {
                        param: "physical inputs",
                        reason: unknown_input(&name),
                    })
                }
            };
            let alone = Value::Object(Map::from_iter([(name.clone(), value.clone())]));
            if let Err(e) = serde_json::from_value::<Physical>(alone) {
                let reason = match (&value, &all[&name]) {
                    // A choice: its words, as the library's parsers say them.
                    (Value::String(w), Value::String(_)) => {
                        format!(
                            "'{w}' is not one of: {}",
                            entry.accepted.replace(" or ", ", ")
                        )
                    }
                    _ => e.to_string(),
                };
                return Err(Error::Invalid {
                    param: entry.name,
                    reason,
                });
            }
            all.insert(name, value);
        }
        let mut next: Physical =
            serde_json::from_value(Value::Object(all)).expect("each value was read alone");
        next.spectrum_csv = self.spectrum_csv.take();
        next.channels_csv = self.channels_csv.take();
        *self = next;
        Ok(())
    }

    /// Refuses a non-finite number and the spatial frequency given with the
    /// baseline (each edge calls it once, after filling the inputs).
    pub fn check(&self) -> Result<()> {
        let numbers = [
            ("wavelength_um", Some(self.wavelength_um)),
            ("bandwidth_nm", Some(self.bandwidth_nm)),
            ("resolution", self.resolution),
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
        ];
        for (param, v) in numbers {
            if let Some(v) = v.filter(|v| !v.is_finite()) {
                return Err(Error::Invalid {
                    param,
                    reason: format!("{v} is not a finite number"),
                });
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

#[cfg(test)]
mod tests {
    use super::{Physical, PARAMETERS};
    use serde_json::{json, Value};

    /// Each field, given alone, moves exactly that field (a value read
    /// into the wrong field, or dropped, fails); a null changes nothing.
    #[test]
    fn each_field_overlays_itself() {
        let d = serde_json::to_value(Physical::default()).unwrap();
        for p in PARAMETERS.iter().filter(|p| !p.name.ends_with("_csv")) {
            let want = match &d[p.name] {
                Value::Bool(b) => json!(!b),
                Value::Number(n) if n.is_u64() => json!(n.as_u64().unwrap() + 1),
                Value::Number(x) => json!(x.as_f64().unwrap() + 0.5),
                Value::String(w) if w == "ud" => json!("point"),
                Value::String(_) => json!("centre"),
                _ if p.name == "channels" => json!(3),
                _ => json!(1.5),
            };
            let mut q = Physical::default();
            let mut given = json!({ p.name: want });
            if p.name != "samples" {
                given["samples"] = Value::Null;
            }
            q.overlay(given).unwrap();
            let got = serde_json::to_value(q).unwrap();
            for o in &PARAMETERS {
                let expected = if o.name == p.name { &want } else { &d[o.name] };
                assert_eq!(&got[o.name], expected, "{} moved {}", p.name, o.name);
            }
        }
    }

    /// An unknown name is refused with the nearest one, a value of the
    /// wrong type or a spectrum's table naming the field, and nothing is
    /// changed by a refused overlay.
    #[test]
    fn a_bad_name_or_value_is_refused_naming_it() {
        let mut p = Physical::default();
        let e = p.overlay(json!({"wavelenth_um": 1.0})).unwrap_err();
        assert!(
            e.to_string().contains("did you mean 'wavelength_um'?"),
            "{e}"
        );
        let e = p.overlay(json!({"zzz": 1.0})).unwrap_err().to_string();
        assert!(!e.contains("did you mean"), "{e}");
        let e = p
            .overlay(json!({"photons": 3.0, "samples": 1.5}))
            .unwrap_err();
        assert_eq!(e.param(), Some("samples"));
        let e = p.overlay(json!({"source": "disk"})).unwrap_err();
        assert_eq!(e.param(), Some("source"));
        assert!(
            e.to_string().contains("'disk' is not one of: point, ud"),
            "{e}"
        );
        let e = p.overlay(json!({"spectrum_csv": "a.csv"})).unwrap_err();
        assert_eq!(e.param(), Some("spectrum_csv"));
        let e = p.overlay(json!({"channels_csv": "c.csv"})).unwrap_err();
        assert_eq!(e.param(), Some("channels_csv"));
        assert_eq!(p, Physical::default());
    }
}
