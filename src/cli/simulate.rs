//! `v2ref simulate`: Monte Carlo of both estimators on noisy sampled
//! interferograms, bias-subtracted (in the `--formula` chosen) and
//! normalized by the noise-free estimate of a calibrator (point source,
//! V = 1, same photons), so that an unbiased estimator of a source of
//! visibility V has mean V².

use super::common::{ObservationArgs, OutputArgs, RunArgs, SamplingArgs};
use super::snr::NoiseArgs;
use super::{print_json, print_rows, progress_bar};
use serde::Serialize;
use std::process::ExitCode;
use v2ref::noise::calibrated::{calibrated_run, CalibratedRun, Trials};
use v2ref::noise::Formula;
use v2ref::{Error, Result};

/// Largest number of trials accepted.
pub const MAX_TRIALS: u64 = 1 << 40;

/// Flags of `simulate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    obs: ObservationArgs,
    #[command(flatten)]
    sampling: SamplingArgs,
    #[command(flatten)]
    noise: NoiseArgs,
    /// Number of noisy interferograms.
    #[arg(long, default_value = "100000", allow_negative_numbers = true)]
    trials: u64,
    #[command(flatten)]
    run: RunArgs,
    #[command(flatten)]
    output: OutputArgs,
}

#[derive(Serialize)]
struct Answer {
    formula: Formula,
    bins: String,
    samples: usize,
    mean_v1_sq: f64,
    mean_v2_sq: f64,
    var_v1_sq: f64,
    var_v2_sq: f64,
    stderr_mean_v1_sq: f64,
    stderr_mean_v2_sq: f64,
    stderr_var_v1_sq: f64,
    stderr_var_v2_sq: f64,
    /// Closed-form expectation of the normalized V1² (exact noise, this
    /// formula's bias).
    expected_mean_v1_sq: f64,
    /// Same for V2².
    expected_mean_v2_sq: f64,
    /// Exact closed-form variance of the normalized V1² over the window.
    expected_var_v1_sq: Option<f64>,
    /// Same for V2².
    expected_var_v2_sq: Option<f64>,
    trials: u64,
    seed: u64,
}

/// Runs `simulate`.
pub fn run(args: Args) -> Result<ExitCode> {
    check_trials(args.trials)?;
    let noise = args.noise.noise()?;
    let obs = args.obs.observation()?;
    let sampling = args.sampling.sampling()?;
    let setup = args.noise.setup(&obs, &sampling, args.sampling.bins)?;
    let bar = progress_bar(args.trials, args.output.quiet, "simulate");
    let size = Trials {
        trials: args.trials,
        seed: args.run.seed,
        threads: args.run.threads,
    };
    let run = calibrated_run(&setup, &noise, args.noise.formula, size, &|t| bar.inc(t))?;
    bar.finish_and_clear();
    let answer = answer(&args, sampling.samples(), &run);
    if args.output.json {
        print_json(&answer);
    } else {
        print_table(&answer);
    }
    Ok(ExitCode::SUCCESS)
}

/// Refuses fewer than 2 or more than [`MAX_TRIALS`] trials.
fn check_trials(trials: u64) -> Result<()> {
    if (2..=MAX_TRIALS).contains(&trials) {
        Ok(())
    } else {
        Err(Error::OutOfRange {
            param: "trials",
            value: trials as f64,
            accepted: format!("2 to {MAX_TRIALS}"),
        })
    }
}

fn answer(args: &Args, samples: usize, run: &CalibratedRun) -> Answer {
    let (v1, v2, e) = (&run.v1_sq, &run.v2_sq, &run.expected);
    Answer {
        formula: args.noise.formula,
        bins: args.sampling.bins.name().to_owned(),
        samples,
        mean_v1_sq: v1.mean,
        mean_v2_sq: v2.mean,
        var_v1_sq: v1.var,
        var_v2_sq: v2.var,
        stderr_mean_v1_sq: v1.stderr_mean,
        stderr_mean_v2_sq: v2.stderr_mean,
        stderr_var_v1_sq: v1.stderr_var,
        stderr_var_v2_sq: v2.stderr_var,
        expected_mean_v1_sq: e.mean_v1_sq,
        expected_mean_v2_sq: e.mean_v2_sq,
        expected_var_v1_sq: e.var_v1_sq,
        expected_var_v2_sq: e.var_v2_sq,
        trials: args.trials,
        seed: args.run.seed,
    }
}

fn print_table(a: &Answer) {
    let opt = |v: Option<f64>| v.map_or("-".to_owned(), |x| format!("{x:.6e}"));
    let mean = |m: f64, se: f64, e: f64| format!("{m:.6} +- {se:.2e} (expected {e:.6})");
    let var =
        |v: f64, se: f64, e: Option<f64>| format!("{v:.6e} +- {se:.2e} (expected {})", opt(e));
    print_rows(&[
        ("formula", format!("{:?}", a.formula).to_lowercase()),
        ("bins", a.bins.clone()),
        ("trials", a.trials.to_string()),
        ("seed", a.seed.to_string()),
        (
            "mean V1^2",
            mean(a.mean_v1_sq, a.stderr_mean_v1_sq, a.expected_mean_v1_sq),
        ),
        (
            "mean V2^2",
            mean(a.mean_v2_sq, a.stderr_mean_v2_sq, a.expected_mean_v2_sq),
        ),
        (
            "var V1^2",
            var(a.var_v1_sq, a.stderr_var_v1_sq, a.expected_var_v1_sq),
        ),
        (
            "var V2^2",
            var(a.var_v2_sq, a.stderr_var_v2_sq, a.expected_var_v2_sq),
        ),
        (
            "SNR1 (Monte Carlo)",
            format!("{:.4}", a.mean_v1_sq / a.var_v1_sq.sqrt()),
        ),
        (
            "SNR2 (Monte Carlo)",
            format!("{:.4}", a.mean_v2_sq / a.var_v2_sq.sqrt()),
        ),
    ]);
}
