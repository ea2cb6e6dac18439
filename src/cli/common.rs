//! Flags shared by several subcommands: the observation and sampling
//! (`bias`, `snr`, `simulate`, `piston`), the output (`--json`, `--quiet`)
//! and the Monte Carlo runs (`--seed`, `--threads`).

use super::finite_f64;
use std::path::PathBuf;
use v2ref::formalism::estimator::BinWindow;
use v2ref::parameters::Physical;

pub use v2ref::parameters::SourceKind;

/// The band, the spectrum, the source, where in the (u, v) plane, dispersion.
#[derive(Debug, Clone, clap::Args)]
pub struct ObservationArgs {
    /// Centre wavelength λ0, µm: 0.001 to 100000. With --spectrum-csv it
    /// still sets λ0 of the fringe frequency f = v/λ0, of the samples per
    /// fringe and of the seeing: give the spectrum's centre.
    #[arg(long, default_value = "2.2", value_parser = finite_f64, allow_negative_numbers = true)]
    pub wavelength_um: f64,
    /// Full bandwidth Δλ, nm: the band [λ0 − Δλ/2, λ0 + Δλ/2], flat per
    /// unit wavenumber σ = 1/λ (not per unit wavelength: W(σ) is constant
    /// between 1/(λ0 + Δλ/2) and 1/(λ0 − Δλ/2)); 1e-12 λ0 to under 2 λ0.
    #[arg(long, default_value = "400", value_parser = finite_f64, allow_negative_numbers = true)]
    pub bandwidth_nm: f64,
    /// A tabulated S(σ)F(σ) instead of the flat band: CSV with header
    /// `wavelength_um,weight` or `wavenumber_per_um,weight`, the weight per
    /// unit wavenumber (`weight_per_wavenumber` says so explicitly;
    /// `weight_per_um` is per unit wavelength and is converted by λ²); a
    /// leading byte-order mark is fine; at most 100000 rows, 16 MiB.
    #[arg(long, value_name = "FILE")]
    pub spectrum_csv: Option<PathBuf>,
    /// Source model.
    #[arg(long, value_enum, default_value = "ud")]
    pub source: SourceKind,
    /// Uniform-disk diameter θ, mas: > 0 to 3.6e6 (1°).
    #[arg(long, default_value = "43", value_parser = finite_f64, allow_negative_numbers = true)]
    pub diameter_mas: f64,
    /// Spatial frequency S = B σ_eff, cycles/arcsec [default: 40, the
    /// paper's 18 m baseline in K]; 0 to 1e13.
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true, conflicts_with = "baseline_m")]
    pub spatial_freq_cpas: Option<f64>,
    /// Projected baseline B, m (instead of --spatial-freq-cpas): 0 to 1e9.
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true)]
    pub baseline_m: Option<f64>,
    /// Quadratic dispersion phase, peak-to-peak over the band, rad: −1e4 to
    /// 1e4.
    #[arg(long, default_value = "0", value_parser = finite_f64, allow_negative_numbers = true)]
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
    /// OPD stroke Δx, µm (sets N = Δx/δx; default: --samples × --dx-um).
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true)]
    pub stroke_um: Option<f64>,
    /// Sample spacing δx, µm.
    #[arg(long, default_value = "0.5", value_parser = finite_f64, allow_negative_numbers = true)]
    pub dx_um: f64,
    /// Number of samples N (ignored when --stroke-um is given). The finite
    /// scan costs about N² (N = 16384: about 10 s on two cores).
    #[arg(long, value_parser = super::count_usize, default_value = "128", allow_negative_numbers = true)]
    pub samples: usize,
    /// Integrating detector (each sample averages the fringe over δx).
    #[arg(long)]
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
    #[arg(long, value_enum, default_value = "positive")]
    pub bins: BinWindow,
}

/// The turbulence, the telescopes and the scans through the piston (§6).
#[derive(Debug, Clone, clap::Args)]
pub struct TurbulenceArgs {
    /// Wind speed, m/s (frozen flow along the baseline): > 0 to 343.
    #[arg(long, default_value = "10", value_parser = finite_f64, allow_negative_numbers = true)]
    pub wind_mps: f64,
    /// Seeing λ/r0, arcsec, at --seeing-wavelength-um: 0 (no turbulence)
    /// to 100.
    #[arg(long, default_value = "1", value_parser = finite_f64, allow_negative_numbers = true)]
    pub seeing_arcsec: f64,
    /// Wavelength at which --seeing-arcsec is quoted, µm (site monitors
    /// quote 0.5), 0.3 to 30 (where seeing is measured); converted to the observing wavelength
    /// by r0 ∝ λ^(6/5) [default: the observing wavelength --wavelength-um].
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true)]
    pub seeing_wavelength_um: Option<f64>,
    /// Telescope aperture diameter, m.
    #[arg(long, default_value = "0.45", value_parser = finite_f64, allow_negative_numbers = true)]
    pub aperture_m: f64,
    /// von Kármán outer scale, m [default: infinite].
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true)]
    pub outer_scale_m: Option<f64>,
    /// Sub-samples per sample of the integrating detector.
    #[arg(long, value_parser = super::count_usize, default_value_t = v2ref::piston::DEFAULT_SUB_SAMPLES, allow_negative_numbers = true)]
    pub sub_samples: usize,
    /// Where the fringe packet sits in each scan.
    #[arg(long, value_enum, default_value = "mean")]
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
    /// Visibility V scaling the fringe (m_0 = n V for a point source), 0 to 1.
    #[arg(long, default_value = "1", value_parser = finite_f64, allow_hyphen_values = true)]
    pub visibility: f64,
    /// Continuum photons per sample n (c = n): 0 to 1e12.
    #[arg(long, default_value = "10", value_parser = finite_f64, allow_hyphen_values = true)]
    pub photons: f64,
    /// Detector noise standard deviation σ_det, photons per sample: 0 to
    /// 1e12.
    #[arg(long, default_value = "0", value_parser = finite_f64, allow_hyphen_values = true)]
    pub read_noise: f64,
    /// No Poisson photon noise (detector noise only).
    #[arg(long)]
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
