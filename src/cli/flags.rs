//! The physical flags: clap's derive over `Option` fields (so that a flag
//! given is told from a default, which a preset may fill), each doc comment
//! the help text of the input's entry in
//! [`v2ref_commands::parameters::PARAMETERS`] (a test holds them to it).
//! The flags given are serialized (the others skipped) and read over the
//! defaults by [`Physical::overlay`], the same route as Python's keyword
//! arguments; a spectrum's file is read here, at the edge.

use super::{count_usize, finite_f64};
use serde::{Serialize, Serializer};
use std::path::PathBuf;
use v2ref_commands::parameters::{Physical, SourceKind};
use v2ref_core::record::PistonReference;
use v2ref_core::words::Words;
use v2ref_core::Result;

/// A group of physical flags: the inputs it was given set in `p`.
pub trait Flags: Serialize {
    /// Sets the inputs given by these flags in `p` (the rest as they are).
    fn apply_to(&self, p: &mut Physical) -> Result<()> {
        p.overlay(serde_json::to_value(self).expect("flags serialize as JSON"))
    }
}

/// A flag left off is not serialized (it gives nothing).
fn is_false(on: &bool) -> bool {
    !on
}

/// `--no-NAME` given: the input `NAME` is false.
fn negated<S: Serializer>(off: &bool, s: S) -> std::result::Result<S::Ok, S::Error> {
    (!off).serialize(s)
}

impl ObservationArgs {
    /// The physical inputs: these flags (the spectrum's file read), the
    /// defaults for the rest.
    pub fn physical(&self) -> Result<Physical> {
        let mut p = Physical::default();
        self.apply_to(&mut p)?;
        if let Some(path) = &self.spectrum_csv {
            let table = v2ref_files::formats::spectrum_csv::spectrum_from_csv_path(path)?;
            p.spectrum_csv = Some(v2ref_commands::parameters::SpectrumFile::new(path, table));
        }
        if let Some(path) = &self.channels_csv {
            let text = v2ref_files::formats::channels_csv::read_channels_text(path)?;
            p.channels_csv = Some(v2ref_commands::parameters::ChannelsFile::new(path, text));
        }
        Ok(p)
    }
}

/// The band, the spectrum, the source, where in the (u, v) plane, dispersion.
#[derive(Debug, Clone, Default, clap::Args, Serialize)]
pub struct ObservationArgs {
    /// Centre wavelength λ0, µm: 0.001 to 100000. With --spectrum-csv it still
    /// sets λ0 of the fringe frequency f = v/λ0, of the samples per fringe and
    /// of the seeing: give the spectrum's centre [default: 2.2]
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wavelength_um: Option<f64>,
    /// Full bandwidth Δλ, nm: 1e-12 λ0 to under 2 λ0. The band [λ0 − Δλ/2, λ0 +
    /// Δλ/2], flat per unit wavenumber σ = 1/λ (not per unit wavelength: W(σ)
    /// is constant between 1/(λ0 + Δλ/2) and 1/(λ0 − Δλ/2)) [default: 400]
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bandwidth_nm: Option<f64>,
    /// A tabulated S(σ)F(σ) instead of the flat band: a CSV file of at most
    /// 100000 rows, 16 MiB. Header `wavelength_um,weight` or
    /// `wavenumber_per_um,weight`, the weight per unit wavenumber
    /// (`weight_per_wavenumber` says so explicitly; `weight_per_um` is per unit
    /// wavelength and is converted by λ²); a leading byte-order mark is fine
    /// [default: the flat band of --wavelength-um and --bandwidth-nm]
    #[arg(long, value_name = "FILE", value_parser = clap::value_parser!(PathBuf))]
    #[serde(skip)]
    pub spectrum_csv: Option<PathBuf>,
    /// Spectral channels C of equal width in wavenumber over the band: 1 to
    /// 4096. bias, snr and simulate answer per channel (docs/conventions.md
    /// §16); one of --channels, --resolution or --channels-csv. 1: the wide
    /// band's numbers [default: the wide band, no channels]
    #[arg(long, value_parser = count_usize, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub channels: Option<usize>,
    /// Channels of spectral resolution R = λ/Δλ across the band: > 0 (at most
    /// 4096 channels over the band). Geometric edges, the whole number of
    /// channels nearest R; each channel must hold a DFT bin of the scan
    /// [default: the wide band, no channels]
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub resolution: Option<f64>,
    /// Channels' edges and responses from a table: a CSV file of at most 4096
    /// rows, 1 MiB. Header `wavelength_lo_um,wavelength_hi_um,response` or
    /// `wavenumber_lo_per_um,wavenumber_hi_per_um,response`, one row per
    /// channel by increasing axis value, the channels inside the band, neither
    /// overlapping nor out of order [default: the wide band, no channels]
    #[arg(long, value_name = "FILE", value_parser = clap::value_parser!(PathBuf))]
    #[serde(skip)]
    pub channels_csv: Option<PathBuf>,
    /// Source model: point or ud. ud: a uniform disk of diameter
    /// --diameter-mas; point: unresolved (V = 1) [default: ud]
    #[arg(long, value_parser = choice::<SourceKind>())]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub source: Option<SourceKind>,
    /// Uniform-disk diameter θ, mas: > 0 to 3.6e6 [default: 43]
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub diameter_mas: Option<f64>,
    /// Spatial frequency S = B σ_eff, cycles/arcsec: 0 to 1e13 (and B = S/σ_eff
    /// at most 1e9 m) [default: 40, the paper's 18 m baseline in K (or from
    /// --baseline-m)]
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true, conflicts_with = "baseline_m")]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spatial_freq_cpas: Option<f64>,
    /// Projected baseline B, m: 0 to 1e9. Instead of --spatial-freq-cpas
    /// [default: from --spatial-freq-cpas]
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub baseline_m: Option<f64>,
    /// Quadratic dispersion phase, peak-to-peak over the band, rad: -1e4 to 1e4
    /// [default: 0]
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dispersion_pp_rad: Option<f64>,
}

impl Flags for ObservationArgs {}

/// How the interferogram is scanned and sampled.
#[derive(Debug, Clone, Default, clap::Args, Serialize)]
pub struct ScanArgs {
    /// OPD stroke Δx, µm: N = Δx/δx, rounded, from 2 to 2^24 [default:
    /// --samples × --dx-um]
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stroke_um: Option<f64>,
    /// Sample spacing δx, µm: > 0 [default: 0.5]
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dx_um: Option<f64>,
    /// Number of samples N: 2 to 2^24. Ignored when --stroke-um is given. The
    /// finite scan costs about N² (N = 16384: about 10 s on two cores)
    /// [default: 128]
    #[arg(long, value_parser = count_usize, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub samples: Option<usize>,
    /// Integrating detector (each sample averages the fringe over δx)
    #[arg(long)]
    #[serde(skip_serializing_if = "is_false")]
    pub integrating: bool,
}

impl Flags for ScanArgs {}

/// The light: the fringe's visibility scale, the photons, the noise.
#[derive(Debug, Clone, Default, clap::Args, Serialize)]
pub struct LightArgs {
    /// Visibility V scaling the fringe: 0 to 1. m_0 = n V for a point source (a
    /// source of known V: --source point) [default: 1]
    #[arg(long, value_parser = finite_f64, allow_hyphen_values = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub visibility: Option<f64>,
    /// Continuum n (c = n), photons per sample: > 0 to 1e12 [default: 10]
    #[arg(long, value_parser = finite_f64, allow_hyphen_values = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub photons: Option<f64>,
    /// Detector noise standard deviation σ_det, photons per sample: 0 to 1e12
    /// [default: 0]
    #[arg(long, value_parser = finite_f64, allow_hyphen_values = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub read_noise: Option<f64>,
    /// Turns off: Poisson photon noise (when off, detector noise only)
    #[arg(long)]
    #[serde(
        rename = "photon_noise",
        serialize_with = "negated",
        skip_serializing_if = "is_false"
    )]
    pub no_photon_noise: bool,
}

impl Flags for LightArgs {}

/// The turbulence, the telescopes and the scans through the piston (§6).
#[derive(Debug, Clone, Default, clap::Args, Serialize)]
pub struct TurbulenceArgs {
    /// Wind speed, m/s: 0.001 to 343. Frozen flow along the baseline [default:
    /// 10]
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wind_mps: Option<f64>,
    /// Seeing λ/r0, arcsec: 0 to 100. Quoted at --seeing-wavelength-um; 0: no
    /// turbulence [default: 1]
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seeing_arcsec: Option<f64>,
    /// Wavelength at which --seeing-arcsec is quoted, µm: 0.3 to 30. Site
    /// monitors quote 0.5. Converted to the observing wavelength by r0 ∝
    /// λ^(6/5) [default: the observing wavelength --wavelength-um]
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seeing_wavelength_um: Option<f64>,
    /// Telescope aperture diameter, m: 0.001 to 1000 [default: 0.45]
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub aperture_m: Option<f64>,
    /// von Kármán outer scale, m: > 0 [default: infinite]
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub outer_scale_m: Option<f64>,
    /// Sub-samples per sample of the integrating detector under piston: 1 to 64
    /// [default: 6]
    #[arg(long, value_parser = count_usize, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sub_samples: Option<usize>,
    /// Where the fringe packet sits in each scan: centre, mean or absolute
    /// [default: mean]
    #[arg(long, value_parser = choice::<PistonReference>())]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reference: Option<PistonReference>,
}

impl Flags for TurbulenceArgs {}

/// The differential piston: on when `--fringe-hz` is given (its turbulence
/// is [`TurbulenceArgs`], flattened after it).
#[derive(Debug, Clone, Default, clap::Args, Serialize)]
pub struct PistonArgs {
    /// Fringe frequency f = v/λ0, Hz: 0.001 to 1e7. Adds the differential
    /// piston of §6 (consecutive scans through one piston sequence) [default:
    /// no piston]
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fringe_hz: Option<f64>,
}

impl Flags for PistonArgs {}

/// The detector and the fringe's visibility scale, among `plan`'s flags.
#[derive(Debug, Clone, Default, clap::Args, Serialize)]
pub struct DetectorArgs {
    /// Integrating detector (each sample averages the fringe over δx)
    #[arg(long)]
    #[serde(skip_serializing_if = "is_false")]
    pub integrating: bool,
    /// Visibility V scaling the fringe: 0 to 1. m_0 = n V for a point source (a
    /// source of known V: --source point) [default: 1]
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub visibility: Option<f64>,
}

impl Flags for DetectorArgs {}

/// The detector's noise, among `plan`'s flags.
#[derive(Debug, Clone, Default, clap::Args, Serialize)]
pub struct NoiseArgs {
    /// Detector noise standard deviation σ_det, photons per sample: 0 to 1e12
    /// [default: 0]
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true)]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub read_noise: Option<f64>,
    /// Turns off: Poisson photon noise (when off, detector noise only)
    #[arg(long)]
    #[serde(
        rename = "photon_noise",
        serialize_with = "negated",
        skip_serializing_if = "is_false"
    )]
    pub no_photon_noise: bool,
}

impl Flags for NoiseArgs {}

/// The parser of a choice of the library: its words ([`Words::WORDS`]),
/// each with its help, offered as clap's possible values.
pub fn choice<T: Words + Clone + Send + Sync>() -> impl clap::builder::TypedValueParser<Value = T> {
    use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser as _};
    let values = T::WORDS
        .iter()
        .map(|w| PossibleValue::new(w.word).help(w.help));
    PossibleValuesParser::new(values).try_map(|word| T::from_word("", &word))
}
