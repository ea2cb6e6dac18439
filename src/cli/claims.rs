//! `v2ref claims`: every claim of the ledger with the computed value and status.

use super::common::OutputArgs;
use super::print_json;
use std::process::ExitCode;
use v2ref_core::Result;
use v2ref_reproduction::cases::Effort;
use v2ref_reproduction::claims::evaluate;

/// Flags of `claims`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Smaller Monte Carlo runs (same code paths).
    #[arg(long)]
    quick: bool,
    #[command(flatten)]
    output: OutputArgs,
}

/// Runs `claims`.
pub fn run(args: Args) -> Result<ExitCode> {
    let effort = if args.quick {
        Effort::Quick
    } else {
        Effort::Full
    };
    let spinner = super::spinner(
        args.output.quiet,
        "computing every claim (Monte Carlo included)",
    );
    let results = evaluate(effort);
    spinner.finish_and_clear();
    if args.output.json {
        print_json(&results);
        return Ok(ExitCode::SUCCESS);
    }
    let fmt = |v: Option<f64>| v.map_or_else(|| "-".to_owned(), |x| format!("{x:.6}"));
    let id_width = results.iter().map(|r| r.id.len()).max().unwrap_or(0);
    outln!(
        "{:<id_width$}  {:>12}  {:>12}  {:<11}  note",
        "claim",
        "paper",
        "computed",
        "status"
    );
    for r in &results {
        outln!(
            "{:<id_width$}  {:>12}  {:>12}  {:<11}  {}",
            r.id,
            fmt(r.paper),
            fmt(r.computed),
            r.status.as_str(),
            r.note
        );
    }
    Ok(ExitCode::SUCCESS)
}
