//! `v2ref piston`: the differential-piston Monte Carlo at one or more fringe
//! frequencies (paper, Section "Effect of differential piston").

use super::common::{
    warn_if_outer_scale_infinite, ObservedArgs, OutputArgs, RunArgs, TurbulenceArgs,
};
use super::flags::Flags;
use super::grid::{flatten, parse_fringe_hz, Grid};
use super::{finite_f64, print_json, progress_bar};
use std::process::ExitCode;
use v2ref_commands::commands::piston::{self, PistonRequest};
use v2ref_commands::report::piston::PistonReport;
use v2ref_core::piston::spectrum::PistonPsdModel;
use v2ref_core::Result;

/// Flags of `piston`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    observed: ObservedArgs,
    /// Fringe frequency f = v/λ0, Hz: a value, A:B:N (N values from A to B)
    /// or A:B:N:log (log-spaced); repeatable [default: 300 and 1000].
    #[arg(long = "fringe-hz", value_parser = parse_fringe_hz, allow_negative_numbers = true)]
    fringe_hz: Vec<Grid>,
    #[command(flatten)]
    turbulence: TurbulenceArgs,
    /// The differential-piston spectrum: the two-aperture integral, or the
    /// three-slope model (Conan et al. 1995 asymptotes) of the same variance.
    #[arg(long, value_parser = super::flags::choice::<PistonPsdModel>(), default_value = "two-aperture")]
    psd: PistonPsdModel,
    /// Wind direction from the baseline, degrees (two-aperture spectrum only;
    /// 0 = along the baseline).
    #[arg(long, default_value = "0", value_parser = finite_f64, allow_negative_numbers = true)]
    wind_angle_deg: f64,
    /// Number of consecutive scans per fringe frequency.
    #[arg(long, value_parser = super::count_usize, default_value = "1000", allow_negative_numbers = true)]
    scans: usize,
    /// Also σ(V²) of the mean of an observation of this many consecutive
    /// scans (1 to 1e12), from contiguous piston sequences
    /// (docs/conventions.md, "The observation's error").
    #[arg(long, value_parser = super::count_u64, allow_negative_numbers = true, conflicts_with = "observation_s")]
    observation_scans: Option<u64>,
    /// The same for an observation this long, s (> 0): n = ceil(T / scan time).
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true)]
    observation_s: Option<f64>,
    #[command(flatten)]
    run: RunArgs,
    #[command(flatten)]
    output: OutputArgs,
}

/// Runs `piston`.
pub fn run(args: Args) -> Result<ExitCode> {
    let mut p = args.observed.physical()?;
    args.turbulence.apply_to(&mut p)?;
    let req = PistonRequest {
        fringe_hz: flatten(&args.fringe_hz),
        bins: args.observed.sampling.bins,
        scans: args.scans,
        seed: args.run.seed,
        threads: args.run.threads,
        psd: args.psd,
        wind_angle_deg: args.wind_angle_deg,
        observation: match (args.observation_scans, args.observation_s) {
            (Some(n), _) => Some(piston::ObservationLength::Scans(n)),
            (None, Some(t)) => Some(piston::ObservationLength::Seconds(t)),
            (None, None) => None,
        },
    };
    let prepared = piston::prepare(&p, &req)?;
    let spectrum = &prepared.spectrum;
    warn_if_outer_scale_infinite(&p, spectrum.baseline_m(), spectrum.rms_um());
    let bar = progress_bar(
        (prepared.fringe_hz.len() * args.scans) as u64,
        args.output.quiet || args.output.json,
        "piston scans",
    );
    let tick = |k: u64| bar.inc(k);
    let answer = piston::run_with_observation(&prepared, &p, &req, Some(&tick))?;
    bar.finish_and_clear();
    if args.output.json {
        print_json(&answer);
    } else {
        print_table(&answer.report);
        if let Some(rows) = &answer.observation {
            super::piston_observation::print(rows);
        }
    }
    for c in &answer.report.three_slope_comparison {
        eprintln!("note: {}", c.note);
    }
    Ok(ExitCode::SUCCESS)
}

fn print_table(answer: &PistonReport) {
    outln!(
        "baseline {:.3} m ({:.2} cycles/arcsec), r0 {:.1} cm, tau0 {:.1} ms (0.314 r0/v; r0/v {:.1} ms), piston rms {:.2} um; {} detector, {} bins, packet reference {}; {} x {} um scans",
        answer.baseline_m,
        answer.spatial_freq_cpas,
        100.0 * answer.r0_m,
        1e3 * answer.tau0_s,
        1e3 * answer.r0_over_v_s,
        answer.piston_rms_um,
        answer.detector,
        answer.bins,
        answer.reference,
        answer.samples,
        answer.dx_um
    );
    let corners = answer.psd_corners_hz.map_or(String::new(), |[lo, hi]| {
        format!(" (corners {lo:.3} and {hi:.2} Hz)")
    });
    outln!(
        "{} piston spectrum{corners}, wind {} deg from the baseline; source V = {:.6}",
        answer.psd,
        answer.wind_angle_deg,
        answer.visibility
    );
    outln!("bias and scatter over scans of V (not V^2): V1 and V2 with piston minus without, then their standard deviation");
    outln!(
        "{:>10}  {:>9}  {:>22}  {:>22}  {:>22}  {:>22}",
        "f [Hz]",
        "V",
        "bias V1 (of V)",
        "bias V2 (of V)",
        "scatter V1 (of V)",
        "scatter V2 (of V)"
    );
    for r in &answer.results {
        outln!(
            "{:>10.2}  {:>9.6}  {:>+11.3e} ±{:>9.1e}  {:>+11.3e} ±{:>9.1e}  {:>11.3e} ±{:>9.1e}  {:>11.3e} ±{:>9.1e}",
            r.fringe_hz,
            answer.visibility,
            r.bias_v1,
            r.bias_v1_stderr,
            r.bias_v2,
            r.bias_v2_stderr,
            r.scatter_v1,
            r.scatter_v1_stderr,
            r.scatter_v2,
            r.scatter_v2_stderr
        );
    }
}
