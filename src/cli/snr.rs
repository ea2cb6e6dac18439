//! `v2ref snr`: closed-form expectations, variances and SNRs of V1² and V2²
//! (paper, Appendix), in the `published` or `exact` formula, with the
//! paper's window factor kept apart and the exact variance of the chosen
//! bin window beside it.

use super::common::{LightArgs, ObservedArgs};
use super::flags::Flags;
use super::{print_json, print_rows};
use std::process::ExitCode;
use v2ref_commands::report::noise::SnrReport;
use v2ref_core::noise::snr_value::snr_text;
use v2ref_core::noise::Formula;
use v2ref_core::Result;

/// Signal and noise flags shared by `snr` and `simulate`.
#[derive(Debug, Clone, clap::Args)]
pub struct NoiseArgs {
    #[command(flatten)]
    pub light: LightArgs,
    /// Formula: as printed in the paper, or exact.
    #[arg(long, value_parser = super::flags::choice::<Formula>(), default_value = "exact")]
    pub formula: Formula,
}

/// Flags of `snr`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    observed: ObservedArgs,
    #[command(flatten)]
    noise: NoiseArgs,
    /// One JSON document instead of the table.
    #[arg(long)]
    json: bool,
}

/// Runs `snr`.
pub fn run(args: Args) -> Result<ExitCode> {
    let mut p = args.observed.physical()?;
    args.noise.light.apply_to(&mut p)?;
    // Seconds or more (N in the thousands, N² work): a spinner on a terminal.
    let n = p.sampling()?.samples();
    let what = format!("snr: closed forms over {n} samples");
    let bar = super::spinner(n < super::bias::SLOW_SAMPLES, &what);
    let answer =
        v2ref_commands::commands::snr::answer(&p, args.observed.sampling.bins, args.noise.formula)?;
    bar.finish_and_clear();
    if args.json {
        print_json(&answer);
    } else {
        print_table(&answer);
    }
    Ok(ExitCode::SUCCESS)
}

fn print_table(a: &SnrReport) {
    let obs = &a.inputs.observation;
    let mut rows = vec![
        (
            "baseline [m]",
            format!(
                "{:.3} ({:.2} cycles/arcsec)",
                obs.baseline_m, obs.spatial_freq_cpas
            ),
        ),
        ("formula", format!("{:?}", a.formula).to_lowercase()),
        ("samples N", a.samples.to_string()),
        ("sum m_i^2 [photons^2]", format!("{:.6}", a.sum_m2)),
        ("m_0 [photons]", format!("{:.6}", a.m0)),
        ("bias V1^2 (all bins)", format!("{:.6e}", a.bias_v1_sq)),
        ("bias V2^2 (all bins)", format!("{:.6e}", a.bias_v2_sq)),
        ("var V1^2 (all bins)", format!("{:.6e}", a.var_v1_sq)),
        ("var V2^2 (all bins)", format!("{:.6e}", a.var_v2_sq)),
        ("SNR1 (all bins)", snr_text(a.snr1, 4)),
        ("SNR2 (all bins)", snr_text(a.snr2, 4)),
        (
            "paper window factor sqrt(dsigma/dsigma0)",
            format!("{:.4}", a.window_factor),
        ),
    ];
    if let Some(w) = &a.window_exact {
        rows.push((
            "window (exact)",
            format!("{} ({} bins)", w.window, w.stats.bins),
        ));
        rows.push(("SNR1 (window, exact)", snr_text(w.stats.snr1, 4)));
        rows.push(("SNR2 (window, exact)", snr_text(w.stats.snr2, 4)));
    }
    print_rows(&rows);
    if let Some(c) = &a.channels {
        super::channels::print_snr(c);
    }
}
