//! Flags shared by several subcommands: the observation and sampling
//! (`bias`, `snr`, `simulate`, `piston`), the output (`--json`, `--quiet`)
//! and the Monte Carlo runs (`--seed`, `--threads`).

use super::flags::{choice, Flags};
pub use super::flags::{LightArgs, ObservationArgs, ScanArgs, TurbulenceArgs};
use v2ref_commands::parameters::Physical;
use v2ref_core::formalism::estimator::BinWindow;

/// How the interferogram is sampled, and the bins the estimators sum.
#[derive(Debug, Clone, clap::Args)]
pub struct SamplingArgs {
    #[command(flatten)]
    pub scan: ScanArgs,
    /// Fourier bins the estimators sum.
    #[arg(long, value_parser = choice::<BinWindow>(), default_value = "positive")]
    pub bins: BinWindow,
}

/// The observation and how it is sampled: the first flags of `bias`,
/// `snr` and `piston`.
#[derive(Debug, Clone, clap::Args)]
pub struct ObservedArgs {
    #[command(flatten)]
    obs: ObservationArgs,
    #[command(flatten)]
    pub sampling: SamplingArgs,
}

impl ObservedArgs {
    /// The physical inputs: these flags, the defaults for the rest.
    pub fn physical(&self) -> v2ref_core::Result<Physical> {
        let mut p = self.obs.physical()?;
        self.sampling.scan.apply_to(&mut p)?;
        Ok(p)
    }
}

/// Baselines beyond which an infinite outer scale overstates the piston
/// badly, m: with 1″ seeing in K and 0.45 m apertures, the Kolmogorov piston
/// rms on 20 m is 21.5 µm, five times its 4.1 µm for a 25 m outer scale,
/// and the ratio grows as B^(5/6) beyond (82 µm against 4.1 µm on 100 m).
pub const INFINITE_OUTER_SCALE_WARN_BASELINE_M: f64 = 20.0;

/// Warns on stderr when the outer scale of `p` is left infinite on a long
/// baseline: the Kolmogorov piston is then the pessimistic extreme.
pub fn warn_if_outer_scale_infinite(p: &Physical, baseline_m: f64, piston_rms_um: f64) {
    if p.outer_scale_m.is_none()
        && p.seeing_arcsec > 0.0
        && baseline_m > INFINITE_OUTER_SCALE_WARN_BASELINE_M
    {
        eprintln!(
            "warning: infinite outer scale on a {baseline_m:.1} m baseline: piston rms \
             {piston_rms_um:.1} um is the pessimistic extreme (measured outer scales \
             are 10-100 m; set --outer-scale-m)"
        );
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
