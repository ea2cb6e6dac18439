//! `v2ref`: the command-line face of the library (contract in
//! `docs/conventions.md`). Every subcommand prints a table, or one JSON document
//! with `--json`; bad input exits with status 2 and one line naming the flag.

mod cli;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// Squared-visibility estimators V1² and V2² of Perrin & Ridgway: biases,
/// variances, SNR and Monte Carlo.
#[derive(Parser)]
#[command(name = "v2ref", version, about, long_about = None, arg_required_else_help = true, after_help = EXIT_STATUSES)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Noise-free wide-band V1 and V2 for one configuration.
    Bias(cli::bias::Args),
    /// Every claim of the paper: printed value, computed value, status.
    Claims(cli::claims::Args),
    /// Closed-form variances and SNRs of both estimators.
    Snr(cli::snr::Args),
    /// Monte Carlo of the estimators under detector and photon noise.
    Simulate(cli::simulate::Args),
    /// Piston Monte Carlo at one or more fringe frequencies.
    Piston(cli::piston::Args),
    /// The estimator, fringe frequency, stroke and scans that reach a target σ(V²).
    Plan(cli::plan::Args),
    /// Compare (--check) or rewrite (--update) golden/ from the code.
    Golden(cli::golden::Args),
    /// Regenerate every figure and table of the paper.
    Reproduce(cli::reproduce::Args),
    /// Write a set of test interferograms (.npy, CSV) and its sidecar with the truth.
    Synth(cli::synth::Args),
    /// Per-row V1² and V2² (raw, bias-subtracted, normalized) of a file of interferograms.
    Estimate(cli::estimate::Args),
    /// Score a pipeline's per-row estimates against a synth set's truth.
    Score(cli::score::Args),
}

/// The exit statuses, listed at the end of `v2ref --help`.
const EXIT_STATUSES: &str = "Exit status:
   0  success
   1  a failed verdict (score: FAIL; golden --check: a mismatch)
   2  bad input: a flag out of range, a file that cannot be read or is malformed,
      an output path whose folder does not exist or that would replace
      something (use --force for a regular file)
  74  an output that cannot be written: read-only or full file system,
      permission denied, standard output closed or failing
 130  interrupted by Ctrl-C (SIGINT); 143 by SIGTERM, 129 by SIGHUP: no
      partial output is left, a set of files is the old one or the new one

Run 'v2ref <COMMAND> --help' for the flags of a command and their ranges.";

fn main() -> ExitCode {
    // SIGINT, SIGTERM and SIGHUP stop any computation at once: the
    // temporaries are removed (what was there before stays), status 128 + N.
    cli::signals::install();
    let cli = match Cli::try_parse_from(cli::negative_numbers_joined(std::env::args_os())) {
        Ok(c) => c,
        Err(e) => return cli::clap_error(e),
    };
    // Every command runs in one pool of `--threads 0`'s size (capped, fewer
    // when the system refuses threads, said on stderr): rayon's global pool,
    // which panics when it cannot start, is never used.
    v2ref_core::montecarlo::pool::set_fewer_threads_notice(|asked, granted| {
        cli::output::write_stderr_line(format_args!(
            "note: the system gave {granted} of the {asked} threads asked (a process limit?); running on {granted}"
        ));
    });
    let result = v2ref_core::montecarlo::pool::install(0, None, || run(cli.command));
    let code = match result {
        Ok(code) => code,
        Err(e) => cli::fail(&e),
    };
    cli::output::flush_stdout();
    code
}

/// Runs one command.
fn run(command: Command) -> v2ref_core::Result<ExitCode> {
    match command {
        Command::Bias(a) => cli::bias::run(a),
        Command::Claims(a) => cli::claims::run(a),
        Command::Snr(a) => cli::snr::run(a),
        Command::Simulate(a) => cli::simulate::run(a),
        Command::Piston(a) => cli::piston::run(a),
        Command::Plan(a) => cli::plan::run(a),
        Command::Golden(a) => cli::golden::run(a),
        Command::Reproduce(a) => cli::reproduce::run(a),
        Command::Synth(a) => cli::synth::run(a),
        Command::Estimate(a) => cli::estimate::run(a),
        Command::Score(a) => cli::score::run(a),
    }
}
