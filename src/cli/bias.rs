//! `v2ref bias`: noise-free wide-band V1 and V2 for one configuration.

use super::common::ObservedArgs;
use super::{print_json, print_rows};
use std::process::ExitCode;
use v2ref_core::Result;

/// N from which the finite scan takes seconds or more and shows a spinner
/// on a terminal: its cost grows as N² (synthesis of N samples, each a sum
/// over a spectral grid as fine as the scan resolves; docs/conventions.md).
pub const SLOW_SAMPLES: usize = 4096;

/// Seconds a finite scan of [`TIMED_SAMPLES`] samples takes at the least:
/// half of what it took on two cores (about 10 s, as `--samples`' help
/// says), since a time taken on one machine was off by 2× on another.
const TIMED_SECONDS_AT_LEAST: f64 = 5.0;

/// The samples of the timed finite scan ([`TIMED_SECONDS_AT_LEAST`]).
const TIMED_SAMPLES: f64 = 16384.0;

/// The least time a finite scan of `samples` samples takes, seconds: it
/// grows as N².
fn finite_scan_seconds_at_least(samples: usize) -> f64 {
    TIMED_SECONDS_AT_LEAST * (samples as f64 / TIMED_SAMPLES).powi(2)
}

/// Says, on stderr whatever it is and before any work, that a finite scan
/// of `samples` will take longer than [`super::output::NOTICE_S`]: a
/// warning, not progress, so neither a pipe nor a log silences it.
fn warn_if_long(samples: usize) {
    let least = finite_scan_seconds_at_least(samples);
    if least > super::output::NOTICE_S {
        errln!(
            "note: finite scan of {samples} samples: at least {} (its cost grows as the square of the samples); Ctrl-C stops it; fewer samples (--samples, --stroke-um, --dx-um) shorten it",
            super::output::duration_words(least)
        );
    }
}

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
    warn_if_long(n);
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
        if let Some(lines) = &answer.channels {
            super::channels::print_bias(lines);
        }
    }
    Ok(ExitCode::SUCCESS)
}

#[cfg(test)]
mod tests {
    use super::{finite_scan_seconds_at_least, SLOW_SAMPLES};
    use crate::cli::output::NOTICE_S;

    /// A scan of 2^24 samples is said to take months, one of the default
    /// 128 or of the spinner's threshold is not warned of.
    #[test]
    fn a_finite_scan_of_years_is_warned_of_and_a_short_one_is_not() {
        assert!(finite_scan_seconds_at_least(1 << 24) > 30.0 * 86400.0);
        assert!(finite_scan_seconds_at_least(SLOW_SAMPLES) < NOTICE_S);
        assert!(finite_scan_seconds_at_least(128) < NOTICE_S);
    }
}
