//! `v2ref simulate`: the end-to-end simulator's Monte Carlo — noisy
//! interferograms with every effect at once (band, source, dispersion,
//! scan, detector, piston with `--fringe-hz`, photon and detector noise),
//! each row bias-subtracted (`--bias`, `--formula`) and normalized by the
//! calibrator (point source, V = 1, same photons), so that an unbiased
//! estimator of a source of visibility V has mean V².

use super::common::{OutputArgs, RunArgs};
use super::inputs::InputsArgs;
use super::{print_json, print_rows, progress_bar};
use std::process::ExitCode;
use v2ref_commands::parameters::Physical;
use v2ref_commands::report::simulator::{check_trials, Estimation, SimulateReport};
use v2ref_core::conformance::estimate::BiasConvention;
use v2ref_core::formalism::channels::Channels;
use v2ref_core::formalism::estimator::BinWindow;
use v2ref_core::noise::calibrated::Trials;
use v2ref_core::noise::Formula;
use v2ref_core::simulator::{simulate, Model};
use v2ref_core::Result;

/// Flags of `simulate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    inputs: InputsArgs,
    /// Fourier bins the estimators sum.
    #[arg(long, value_parser = super::flags::choice::<BinWindow>(), default_value = "positive")]
    bins: BinWindow,
    /// Where the photon bias takes the mean counts from: the model's
    /// noise-free counts, or each row's own counts.
    /// With piston (--fringe-hz) use counts: model subtracts the bias of
    /// the piston-free counts and is biased on V2² (tests/simulator.rs).
    #[arg(long, value_parser = super::flags::choice::<BiasConvention>(), default_value = "model")]
    bias: BiasConvention,
    /// Formula of the subtracted bias: as printed in the paper, or exact.
    #[arg(long, value_parser = super::flags::choice::<Formula>(), default_value = "exact")]
    formula: Formula,
    /// Number of noisy interferograms (rows).
    #[arg(long, value_parser = super::count_u64, default_value = "100000", allow_negative_numbers = true)]
    trials: u64,
    #[command(flatten)]
    run: RunArgs,
    #[command(flatten)]
    output: OutputArgs,
}

/// Runs `simulate`.
pub fn run(args: Args) -> Result<ExitCode> {
    check_trials(args.trials)?;
    let physical = args.inputs.physical()?;
    if let Some(channels) = v2ref_commands::commands::channels::given(&physical)? {
        return run_channels(&args, &physical, channels);
    }
    let inputs = args.inputs.inputs()?;
    let model = Model::new(&inputs)?;
    args.inputs.warn_about(&model);
    let bar = progress_bar(args.trials, args.output.quiet, "simulate");
    let size = Trials {
        trials: args.trials,
        seed: args.run.seed,
        threads: args.run.threads,
    };
    let run = simulate(&model, args.bins, args.bias, args.formula, size, &|t| {
        bar.inc(t)
    })?;
    bar.finish_and_clear();
    let estimation = Estimation {
        window: args.bins,
        bias: args.bias,
        formula: args.formula,
    };
    let answer = SimulateReport::new(inputs, estimation, size, &run);
    if args.output.json {
        print_json(&answer);
    } else {
        print_table(&answer);
    }
    Ok(ExitCode::SUCCESS)
}

/// Runs `simulate` per spectral channel (the shared-piston Monte Carlo).
fn run_channels(
    args: &Args,
    physical: &Physical,
    (channels, input): (Channels, &'static str),
) -> Result<ExitCode> {
    let what = format!("simulate: {} channels", channels.count());
    let bar = super::spinner(args.output.quiet, &what);
    let size = Trials {
        trials: args.trials,
        seed: args.run.seed,
        threads: args.run.threads,
    };
    let estimation = Estimation {
        window: args.bins,
        bias: args.bias,
        formula: args.formula,
    };
    let answer = v2ref_commands::commands::channels_simulate::simulate(
        physical,
        (&channels, input),
        estimation,
        size,
    )?;
    bar.finish_and_clear();
    if args.output.json {
        print_json(&answer);
    } else {
        super::channels::print_simulate(&answer);
    }
    Ok(ExitCode::SUCCESS)
}

fn print_table(a: &SimulateReport) {
    let opt = |v: Option<f64>, p: usize| v.map_or("-".to_owned(), |x| format!("{x:.p$e}"));
    let mean = |m: f64, se: f64, e: Option<f64>| {
        let e = e.map_or("-".to_owned(), |x| format!("{x:.6}"));
        format!("{m:.6} +- {se:.2e} (expected {e})")
    };
    let var =
        |v: f64, se: f64, e: Option<f64>| format!("{v:.6e} +- {se:.2e} (expected {})", opt(e, 6));
    let mut rows = vec![
        ("formula", format!("{:?}", a.formula).to_lowercase()),
        ("bins", a.bins.clone()),
        ("bias", a.bias.name().to_owned()),
        ("trials", a.trials.to_string()),
        ("seed", a.seed.to_string()),
        (
            "baseline",
            format!("{:.3} m, {} samples", a.inputs.baseline_m, a.samples),
        ),
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
            v2ref_core::noise::snr_value::snr_text(a.mean_v1_sq / a.var_v1_sq.sqrt(), 4),
        ),
        (
            "SNR2 (Monte Carlo)",
            v2ref_core::noise::snr_value::snr_text(a.mean_v2_sq / a.var_v2_sq.sqrt(), 4),
        ),
    ];
    if let Some(p) = &a.piston {
        rows.push((
            "piston",
            format!(
                "{} Hz, scan {:.3e} s, rms {:.2} um, residual {:.3} um",
                p.fringe_hz, p.scan_time_s, p.piston_rms_um, p.residual_rms_um
            ),
        ));
    }
    if let Some(e) = &a.piston_effect {
        rows.push((
            "piston bias on V1, V2 (not squared)",
            format!("{:+.3e}, {:+.3e}", e.v1.mean, e.v2.mean),
        ));
        rows.push((
            "piston scatter on V1, V2",
            format!("{:.3e}, {:.3e}", e.v1.std, e.v2.std),
        ));
    }
    print_rows(&rows);
}
