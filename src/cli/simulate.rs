//! `v2ref simulate`: Monte Carlo of both estimators on noisy sampled
//! interferograms, bias-subtracted (in the `--formula` chosen) and
//! normalized by the noise-free estimate of a calibrator (point source,
//! V = 1, same photons), so that an unbiased estimator of a source of
//! visibility V has mean V².

use super::common::{ObservationArgs, OutputArgs, RunArgs, SamplingArgs};
use super::snr::{NoiseArgs, MAX_WINDOW_SAMPLES};
use super::{print_json, print_rows, progress_bar};
use serde::Serialize;
use std::process::ExitCode;
use v2ref::formalism::estimator::{dft, raw_estimates};
use v2ref::noise::simulation::{simulate_noisy, NoisySpec};
use v2ref::noise::window_variance::window_stats;
use v2ref::noise::{window_bias, Formula};
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
    if !(2..=MAX_TRIALS).contains(&args.trials) {
        return Err(Error::OutOfRange {
            param: "trials",
            value: args.trials as f64,
            accepted: format!("2 to {MAX_TRIALS}"),
        });
    }
    let noise = args.noise.noise()?;
    let formula = args.noise.formula;
    let (ifg, cal, sampling, bins, _) = args.noise.interferograms(&args.obs, &args.sampling)?;
    let calib = raw_estimates(&dft(&cal.modulated), &bins);
    if !(calib.v1_sq > 0.0 && calib.v2_sq > 0.0) {
        return Err(Error::Invalid {
            param: "bins",
            reason: "the window holds no fringe of the calibrator (nothing to normalize by); choose --bins all or positive, or more photons".into(),
        });
    }
    let bias = window_bias(formula, &noise, &ifg.modulated, &ifg.continuum, &bins);
    let spec = NoisySpec {
        modulated: ifg.modulated.clone(),
        continuum: ifg.continuum.clone(),
        noise,
        bins: bins.clone(),
    };
    let bar = progress_bar(args.trials, args.output.quiet, "simulate");
    let run = simulate_noisy(&spec, args.trials, args.run.seed, args.run.threads, &|t| bar.inc(t))?;
    bar.finish_and_clear();
    // (x − bias)/calibration, exactly, on the accumulated moments.
    let normalized = |raw: &v2ref::montecarlo::RunningStats, bias: f64, scale: f64| {
        raw.affine(1.0 / scale, -bias / scale).summary()
    };
    let v1 = normalized(&run.v1_sq, bias.v1_sq, calib.v1_sq);
    let v2 = normalized(&run.v2_sq, bias.v2_sq, calib.v2_sq);
    let true_bias = window_bias(
        Formula::Exact,
        &noise,
        &ifg.modulated,
        &ifg.continuum,
        &bins,
    );
    let signal = raw_estimates(&dft(&ifg.modulated), &bins);
    let exact = if sampling.samples() <= MAX_WINDOW_SAMPLES {
        Some(window_stats(
            &ifg.modulated,
            &ifg.mean_counts(),
            &noise,
            &bins,
        )?)
    } else {
        None
    };
    let answer = Answer {
        formula,
        bins: format!("{:?}", args.sampling.bins).to_lowercase(),
        samples: sampling.samples(),
        mean_v1_sq: v1.mean,
        mean_v2_sq: v2.mean,
        var_v1_sq: v1.var,
        var_v2_sq: v2.var,
        stderr_mean_v1_sq: v1.stderr_mean,
        stderr_mean_v2_sq: v2.stderr_mean,
        stderr_var_v1_sq: v1.stderr_var,
        stderr_var_v2_sq: v2.stderr_var,
        expected_mean_v1_sq: (signal.v1_sq + true_bias.v1_sq - bias.v1_sq) / calib.v1_sq,
        expected_mean_v2_sq: (signal.v2_sq + true_bias.v2_sq - bias.v2_sq) / calib.v2_sq,
        expected_var_v1_sq: exact
            .as_ref()
            .map(|w| w.var_v1_sq / (calib.v1_sq * calib.v1_sq)),
        expected_var_v2_sq: exact
            .as_ref()
            .map(|w| w.var_v2_sq / (calib.v2_sq * calib.v2_sq)),
        trials: args.trials,
        seed: args.run.seed,
    };
    if args.output.json {
        print_json(&answer);
    } else {
        let opt = |v: Option<f64>| v.map_or("-".to_owned(), |x| format!("{x:.6e}"));
        print_rows(&[
            ("formula", format!("{:?}", formula).to_lowercase()),
            ("bins", answer.bins.clone()),
            ("trials", answer.trials.to_string()),
            ("seed", answer.seed.to_string()),
            (
                "mean V1^2",
                format!(
                    "{:.6} +- {:.2e} (expected {:.6})",
                    v1.mean, v1.stderr_mean, answer.expected_mean_v1_sq
                ),
            ),
            (
                "mean V2^2",
                format!(
                    "{:.6} +- {:.2e} (expected {:.6})",
                    v2.mean, v2.stderr_mean, answer.expected_mean_v2_sq
                ),
            ),
            (
                "var V1^2",
                format!(
                    "{:.6e} +- {:.2e} (expected {})",
                    v1.var,
                    v1.stderr_var,
                    opt(answer.expected_var_v1_sq)
                ),
            ),
            (
                "var V2^2",
                format!(
                    "{:.6e} +- {:.2e} (expected {})",
                    v2.var,
                    v2.stderr_var,
                    opt(answer.expected_var_v2_sq)
                ),
            ),
            (
                "SNR1 (Monte Carlo)",
                format!("{:.4}", v1.mean / v1.var.sqrt()),
            ),
            (
                "SNR2 (Monte Carlo)",
                format!("{:.4}", v2.mean / v2.var.sqrt()),
            ),
        ]);
    }
    Ok(ExitCode::SUCCESS)
}
