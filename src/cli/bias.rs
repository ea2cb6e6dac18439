//! `v2ref bias`: noise-free wide-band V1 and V2 for one configuration.

use super::common::ObservedArgs;
use super::{print_json, print_rows};
use std::process::ExitCode;
use v2ref_core::Result;

/// N from which the finite scan takes seconds or more and shows a spinner
/// on a terminal: its cost grows as N² (synthesis of N samples, each a sum
/// over a spectral grid as fine as the scan resolves; docs/conventions.md).
pub const SLOW_SAMPLES: usize = 4096;

/// Flags of `bias`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    observed: ObservedArgs,
    /// Also compute the finite-scan estimators from a sampled interferogram
    /// (implied by --stroke-um).
    #[arg(long)]
    finite_scan: bool,
    /// One JSON document instead of the table.
    #[arg(long)]
    json: bool,
}

/// Runs `bias`.
pub fn run(args: Args) -> Result<ExitCode> {
    let p = args.observed.physical()?;
    let finite = v2ref_commands::commands::bias::wants_finite_scan(&p, args.finite_scan);
    let n = if finite { p.sampling()?.samples() } else { 0 };
    let what = format!("finite scan of {n} samples");
    let bar = super::spinner(n < SLOW_SAMPLES, &what);
    let answer =
        v2ref_commands::commands::bias::answer(&p, args.observed.sampling.bins, args.finite_scan)?;
    bar.finish_and_clear();
    let wb = answer.infinite_scan;
    if args.json {
        print_json(&answer);
    } else {
        let mut rows = vec![
            (
                "spatial frequency [cycles/arcsec]",
                format!("{:.6}", wb.spatial_freq_cpas),
            ),
            (
                "baseline [m]",
                format!("{:.6}", answer.inputs.observation.baseline_m),
            ),
            ("sigma_eff [1/um]", format!("{:.9}", wb.sigma_eff_per_um)),
            ("V mono", format!("{:.9}", wb.v_mono)),
            ("V1 (infinite scan)", format!("{:.9}", wb.v1)),
            ("V2 (infinite scan)", format!("{:.9}", wb.v2)),
            ("V1 - V mono", format!("{:+.3e}", wb.v1 - wb.v_mono)),
            ("V2 - V mono", format!("{:+.3e}", wb.v2 - wb.v_mono)),
        ];
        if let Some(fs) = &answer.finite_scan {
            rows.push(("stroke [um]", format!("{}", fs.stroke_um)));
            rows.push(("V1 (finite scan)", format!("{:.9}", fs.v1)));
            rows.push(("V2 (finite scan)", format!("{:.9}", fs.v2)));
        }
        print_rows(&rows);
    }
    Ok(ExitCode::SUCCESS)
}
