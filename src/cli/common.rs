//! Flags shared by several subcommands: the observation and sampling
//! (`bias`, `snr`, `simulate`, `piston`), the output (`--json`, `--quiet`)
//! and the Monte Carlo runs (`--seed`, `--threads`).

use super::finite_f64;
use std::path::PathBuf;
use v2ref::formalism::estimator::BinWindow;
use v2ref::parameters::{Parameter, Physical};
use v2ref::words::Words;

pub use v2ref::parameters::SourceKind;

/// The defaults of the physical flags: the library's one declaration.
pub const DEFAULTS: Physical = Physical::DEFAULT;

/// The `--help` of the flag of the physical input `p`, from its one
/// declaration ([`Parameter::describe`]; other inputs named by their
/// flags), with what leaving it unset means where it may be unset.
pub fn help(p: &Parameter) -> String {
    let text = p.describe(&|n| super::flag_of(n));
    let text = text.trim_end_matches('.');
    match p.unset(&|n| super::flag_of(n)) {
        unset if unset.is_empty() => text.to_owned(),
        unset => format!("{text} [default: {unset}]"),
    }
}

/// The `--help` of `--no-NAME`, the flag that turns the input `p` off.
pub fn help_off(p: &Parameter) -> String {
    format!("Turns off: {}", help(p))
}

/// The parser of a choice of the library: its words ([`Words::WORDS`]),
/// each with its help, offered as clap's possible values.
pub fn choice<T: Words + Clone + Send + Sync>() -> impl clap::builder::TypedValueParser<Value = T> {
    use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser as _};
    let values = T::WORDS
        .iter()
        .map(|w| PossibleValue::new(w.word).help(w.help));
    PossibleValuesParser::new(values).try_map(|word| T::from_word("", &word))
}

/// The band, the spectrum, the source, where in the (u, v) plane, dispersion.
#[derive(Debug, Clone, clap::Args)]
pub struct ObservationArgs {
    #[arg(long, help = help(&Parameter::WAVELENGTH_UM), default_value_t = DEFAULTS.wavelength_um, value_parser = finite_f64, allow_negative_numbers = true)]
    pub wavelength_um: f64,
    #[arg(long, help = help(&Parameter::BANDWIDTH_NM), default_value_t = DEFAULTS.bandwidth_nm, value_parser = finite_f64, allow_negative_numbers = true)]
    pub bandwidth_nm: f64,
    #[arg(long, help = help(&Parameter::SPECTRUM_CSV), value_name = "FILE")]
    pub spectrum_csv: Option<PathBuf>,
    #[arg(long, help = help(&Parameter::SOURCE), value_parser = choice::<SourceKind>(), default_value = DEFAULTS.source.word())]
    pub source: SourceKind,
    #[arg(long, help = help(&Parameter::DIAMETER_MAS), default_value_t = DEFAULTS.diameter_mas, value_parser = finite_f64, allow_negative_numbers = true)]
    pub diameter_mas: f64,
    #[arg(long, help = help(&Parameter::SPATIAL_FREQ_CPAS), value_parser = finite_f64, allow_negative_numbers = true, conflicts_with = "baseline_m")]
    pub spatial_freq_cpas: Option<f64>,
    #[arg(long, help = help(&Parameter::BASELINE_M), value_parser = finite_f64, allow_negative_numbers = true)]
    pub baseline_m: Option<f64>,
    #[arg(long, help = help(&Parameter::DISPERSION_PP_RAD), default_value_t = DEFAULTS.dispersion_pp_rad, value_parser = finite_f64, allow_negative_numbers = true)]
    pub dispersion_pp_rad: f64,
}

impl ObservationArgs {
    /// Sets the inputs these flags hold in `p`.
    pub fn apply_to(&self, p: &mut Physical) {
        p.wavelength_um = self.wavelength_um;
        p.bandwidth_nm = self.bandwidth_nm;
        p.spectrum_csv = self.spectrum_csv.clone();
        p.source = self.source;
        p.diameter_mas = self.diameter_mas;
        p.spatial_freq_cpas = self.spatial_freq_cpas;
        p.baseline_m = self.baseline_m;
        p.dispersion_pp_rad = self.dispersion_pp_rad;
    }

    /// The physical inputs: these flags, the defaults for the rest.
    pub fn physical(&self) -> Physical {
        let mut p = Physical::default();
        self.apply_to(&mut p);
        p
    }
}

/// How the interferogram is scanned and sampled.
#[derive(Debug, Clone, clap::Args)]
pub struct ScanArgs {
    #[arg(long, help = help(&Parameter::STROKE_UM), value_parser = finite_f64, allow_negative_numbers = true)]
    pub stroke_um: Option<f64>,
    #[arg(long, help = help(&Parameter::DX_UM), default_value_t = DEFAULTS.dx_um, value_parser = finite_f64, allow_negative_numbers = true)]
    pub dx_um: f64,
    #[arg(long, help = help(&Parameter::SAMPLES), default_value_t = DEFAULTS.samples, value_parser = super::count_usize, allow_negative_numbers = true)]
    pub samples: usize,
    #[arg(long, help = help(&Parameter::INTEGRATING))]
    pub integrating: bool,
}

impl ScanArgs {
    /// Sets the inputs these flags hold in `p`.
    pub fn apply_to(&self, p: &mut Physical) {
        p.stroke_um = self.stroke_um;
        p.dx_um = self.dx_um;
        p.samples = self.samples;
        p.integrating = self.integrating;
    }
}

/// How the interferogram is sampled, and the bins the estimators sum.
#[derive(Debug, Clone, clap::Args)]
pub struct SamplingArgs {
    #[command(flatten)]
    pub scan: ScanArgs,
    /// Fourier bins the estimators sum.
    #[arg(long, value_parser = choice::<BinWindow>(), default_value = "positive")]
    pub bins: BinWindow,
}

/// The turbulence, the telescopes and the scans through the piston (§6).
#[derive(Debug, Clone, clap::Args)]
pub struct TurbulenceArgs {
    #[arg(long, help = help(&Parameter::WIND_MPS), default_value_t = DEFAULTS.wind_mps, value_parser = finite_f64, allow_negative_numbers = true)]
    pub wind_mps: f64,
    #[arg(long, help = help(&Parameter::SEEING_ARCSEC), default_value_t = DEFAULTS.seeing_arcsec, value_parser = finite_f64, allow_negative_numbers = true)]
    pub seeing_arcsec: f64,
    #[arg(long, help = help(&Parameter::SEEING_WAVELENGTH_UM), value_parser = finite_f64, allow_negative_numbers = true)]
    pub seeing_wavelength_um: Option<f64>,
    #[arg(long, help = help(&Parameter::APERTURE_M), default_value_t = DEFAULTS.aperture_m, value_parser = finite_f64, allow_negative_numbers = true)]
    pub aperture_m: f64,
    #[arg(long, help = help(&Parameter::OUTER_SCALE_M), value_parser = finite_f64, allow_negative_numbers = true)]
    pub outer_scale_m: Option<f64>,
    #[arg(long, help = help(&Parameter::SUB_SAMPLES), default_value_t = DEFAULTS.sub_samples, value_parser = super::count_usize, allow_negative_numbers = true)]
    pub sub_samples: usize,
    #[arg(long, help = help(&Parameter::REFERENCE), value_parser = choice::<v2ref::piston::PistonReference>(), default_value = DEFAULTS.reference.word())]
    pub reference: v2ref::piston::PistonReference,
}

/// Baselines beyond which an infinite outer scale overstates the piston
/// badly, m: with 1″ seeing in K and 0.45 m apertures, the Kolmogorov piston
/// rms on 20 m is 21.5 µm, five times its 4.1 µm for a 25 m outer scale,
/// and the ratio grows as B^(5/6) beyond (82 µm against 4.1 µm on 100 m).
pub const INFINITE_OUTER_SCALE_WARN_BASELINE_M: f64 = 20.0;

impl TurbulenceArgs {
    /// Sets the inputs these flags hold in `p`.
    pub fn apply_to(&self, p: &mut Physical) {
        p.wind_mps = self.wind_mps;
        p.seeing_arcsec = self.seeing_arcsec;
        p.seeing_wavelength_um = self.seeing_wavelength_um;
        p.aperture_m = self.aperture_m;
        p.outer_scale_m = self.outer_scale_m;
        p.sub_samples = self.sub_samples;
        p.reference = self.reference;
    }

    /// Warns on stderr when the outer scale is left infinite on a long
    /// baseline: the Kolmogorov piston is then the pessimistic extreme.
    pub fn warn_if_outer_scale_infinite(&self, baseline_m: f64, piston_rms_um: f64) {
        if self.outer_scale_m.is_none()
            && self.seeing_arcsec > 0.0
            && baseline_m > INFINITE_OUTER_SCALE_WARN_BASELINE_M
        {
            eprintln!(
                "warning: infinite outer scale on a {baseline_m:.1} m baseline: piston rms \
                 {piston_rms_um:.1} um is the pessimistic extreme (measured outer scales \
                 are 10-100 m; set --outer-scale-m)"
            );
        }
    }
}

/// Output flags of the subcommands that draw progress on stderr.
#[derive(Debug, Clone, clap::Args)]
pub struct OutputArgs {
    /// One JSON document instead of the table.
    #[arg(long)]
    pub json: bool,
    /// No progress bar or spinner.
    #[arg(long)]
    pub quiet: bool,
}

/// Flags of the Monte Carlo runs.
#[derive(Debug, Clone, clap::Args)]
pub struct RunArgs {
    /// Seed of the generators.
    #[arg(long, value_parser = super::count_u64, default_value = "1", allow_negative_numbers = true)]
    pub seed: u64,
    /// Worker threads (0 = all cores; at most 4 × the cores, at least 16
    /// allowed); the answer does not depend on it.
    #[arg(long, value_parser = super::thread_count, default_value = "0", allow_negative_numbers = true)]
    pub threads: usize,
}

/// The light: the fringe's visibility scale, the photons, the noise.
#[derive(Debug, Clone, clap::Args)]
pub struct LightArgs {
    #[arg(long, help = help(&Parameter::VISIBILITY), default_value_t = DEFAULTS.visibility, value_parser = finite_f64, allow_hyphen_values = true)]
    pub visibility: f64,
    #[arg(long, help = help(&Parameter::PHOTONS), default_value_t = DEFAULTS.photons, value_parser = finite_f64, allow_hyphen_values = true)]
    pub photons: f64,
    #[arg(long, help = help(&Parameter::READ_NOISE), default_value_t = DEFAULTS.read_noise, value_parser = finite_f64, allow_hyphen_values = true)]
    pub read_noise: f64,
    #[arg(long, help = help_off(&Parameter::PHOTON_NOISE))]
    pub no_photon_noise: bool,
}

impl LightArgs {
    /// Sets the inputs these flags hold in `p`.
    pub fn apply_to(&self, p: &mut Physical) {
        p.visibility = self.visibility;
        p.photons = self.photons;
        p.read_noise = self.read_noise;
        p.photon_noise = !self.no_photon_noise;
    }
}
