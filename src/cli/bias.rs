//! `v2ref bias`: noise-free wide-band V1 and V2 for one configuration.

use super::common::{ObservationArgs, SamplingArgs};
use super::{print_json, print_rows};
use serde::Serialize;
use std::process::ExitCode;
use v2ref::formalism::estimator::{sampled_wide_band, wide_band, Pair, WideBand};
use v2ref::simulator::record::{InputsRecord, SamplingRecord};
use v2ref::Result;

/// N from which the finite scan takes seconds or more and shows a spinner
/// on a terminal: its cost grows as N² (synthesis of N samples, each a sum
/// over a spectral grid as fine as the scan resolves; docs/conventions.md).
const SLOW_SAMPLES: usize = 4096;

/// Flags of `bias`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    obs: ObservationArgs,
    #[command(flatten)]
    sampling: SamplingArgs,
    /// Also compute the finite-scan estimators from a sampled interferogram
    /// (implied by --stroke-um).
    #[arg(long)]
    finite_scan: bool,
    /// One JSON document instead of the table.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct FiniteScan {
    stroke_um: f64,
    samples: usize,
    dx_um: f64,
    integrating: bool,
    bins: String,
    v1_sq: f64,
    v2_sq: f64,
    v1: f64,
    v2: f64,
}

#[derive(Serialize)]
struct Answer {
    inputs: InputsRecord,
    #[serde(flatten)]
    infinite_scan: WideBand,
    #[serde(skip_serializing_if = "Option::is_none")]
    finite_scan: Option<FiniteScan>,
}

/// Runs `bias`.
pub fn run(args: Args) -> Result<ExitCode> {
    let obs = args.obs.observation()?;
    let wb = wide_band(&obs);
    let finite_scan = if args.finite_scan || args.sampling.scan.stroke_um.is_some() {
        let sampling = args.sampling.sampling()?;
        let window = args.sampling.bins;
        let n = sampling.samples();
        let bar = super::spinner(n < SLOW_SAMPLES, &format!("finite scan of {n} samples"));
        let Pair { v1_sq, v2_sq } = sampled_wide_band(&obs, &sampling, window)?;
        bar.finish_and_clear();
        Some(FiniteScan {
            stroke_um: sampling.stroke_um(),
            samples: sampling.samples(),
            dx_um: sampling.dx_um(),
            integrating: sampling.integrating(),
            bins: window.name().to_owned(),
            v1_sq,
            v2_sq,
            v1: v1_sq.sqrt(),
            v2: v2_sq.sqrt(),
        })
    } else {
        None
    };
    let sampling = finite_scan
        .as_ref()
        .map(|_| -> Result<SamplingRecord> {
            Ok(SamplingRecord::new(
                &args.sampling.sampling()?,
                args.sampling.bins,
            ))
        })
        .transpose()?;
    let answer = Answer {
        inputs: InputsRecord {
            observation: args.obs.record(&obs),
            sampling,
            atmosphere: None,
        },
        infinite_scan: wb,
        finite_scan,
    };
    if args.json {
        print_json(&answer);
    } else {
        let mut rows = vec![
            (
                "spatial frequency [cycles/arcsec]",
                format!("{:.6}", wb.spatial_freq_cpas),
            ),
            ("baseline [m]", format!("{:.6}", obs.baseline_m)),
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
