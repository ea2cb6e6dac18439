//! `v2ref reproduce`: regenerates every figure of the paper (CSV, JSON
//! metadata, SVG plot per panel) and the claims table (Markdown and JSON)
//! into one directory, atomically: everything is written to a fresh sibling
//! directory first and moved into place only when complete.

use super::common::OutputArgs;
use super::{print_json, progress_bar};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use v2ref_core::{Error, Result};
use v2ref_reproduction::cases::Effort;
use v2ref_reproduction::claims::{evaluate, status_counts, to_markdown, ClaimResult};

/// Flags of `reproduce`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Output directory: a new one, or one an earlier `reproduce` wrote
    /// (it holds a `.v2ref-output` marker), replaced as a whole when the
    /// run succeeds. Any other existing folder is refused unless --force.
    #[arg(long, default_value = "reproduction")]
    out: PathBuf,
    /// Replace --out even if it is a folder v2ref did not write (its files
    /// are lost).
    #[arg(long)]
    force: bool,
    /// Fewer Monte Carlo scans and coarser grids, same code paths.
    #[arg(long)]
    quick: bool,
    #[command(flatten)]
    output: OutputArgs,
}

#[derive(Serialize)]
struct Answer {
    out: String,
    effort: &'static str,
    claims: Vec<ClaimResult>,
    files: Vec<String>,
}

fn write(dir: &Path, name: &str, contents: &str, files: &mut Vec<String>) -> Result<()> {
    let path = dir.join(name);
    std::fs::write(&path, contents).map_err(|e| Error::file(Some("out"), path, e))?;
    files.push(name.to_owned());
    Ok(())
}

/// Refuses to write over the project's golden data.
fn refuse_golden(out: &Path) -> Result<()> {
    let golden = Path::new(env!("CARGO_MANIFEST_DIR")).join("golden");
    let same = match (out.canonicalize(), golden.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    };
    if same || out.file_name().is_some_and(|n| n == "golden") {
        return Err(Error::Invalid {
            param: "out",
            reason: "reproduce never writes into golden/ (use `v2ref golden --update`)".into(),
        });
    }
    Ok(())
}

/// Runs `reproduce`.
pub fn run(args: Args) -> Result<ExitCode> {
    refuse_golden(&args.out)?;
    super::output::check_out_dir(&args.out, args.force)?;
    let effort = if args.quick {
        Effort::Quick
    } else {
        Effort::Full
    };
    let (claims, files) = v2ref_reproduction::golden::replace_dir_atomically(&args.out, |dir| {
        build(dir, effort, args.output.quiet)
    })?;
    if args.output.json {
        print_json(&Answer {
            out: args.out.display().to_string(),
            effort: if args.quick { "quick" } else { "full" },
            claims,
            files,
        });
    } else {
        print_summary(&claims);
        outln!(
            "\nwrote {} files into {}/ (figures as CSV + JSON + SVG, claims.md, claims.json)",
            files.len(),
            args.out.display()
        );
    }
    Ok(ExitCode::SUCCESS)
}

/// Computes and writes everything into `dir`; returns the claims and the
/// files written (relative names).
fn build(dir: &Path, effort: Effort, quiet: bool) -> Result<(Vec<ClaimResult>, Vec<String>)> {
    super::output::write_out_marker(dir)?;
    let bar = progress_bar(4, quiet, "figures");
    let figures = v2ref_reproduction::figures::all(effort)?;
    bar.inc(1);
    bar.set_message("plots");
    let generator = format!(
        "v2ref reproduce{}",
        if effort == Effort::Quick {
            " --quick"
        } else {
            ""
        }
    );
    let mut files = v2ref_reproduction::golden::write_figure_files(dir, &figures, &generator)?;
    for fig in &figures {
        for table in &fig.tables {
            let svg = v2ref_reproduction::plot::table_svg(fig, table)?;
            write(dir, &format!("{}.svg", table.name), &svg, &mut files)?;
        }
    }
    bar.inc(1);
    bar.set_message("Fig. 5 sensitivity");
    let sensitivity = v2ref_reproduction::claims::sensitivity::fig5_sensitivity(effort)?;
    write(
        dir,
        "fig5_sensitivity.csv",
        &sensitivity.to_csv(),
        &mut files,
    )?;
    write(
        dir,
        "fig5_sensitivity.md",
        &sensitivity.to_markdown(),
        &mut files,
    )?;
    bar.inc(1);
    bar.set_message("claims");
    let claims = evaluate(effort);
    write(dir, "claims.md", &to_markdown(&claims), &mut files)?;
    let json = serde_json::to_string_pretty(&claims).map_err(|e| Error::Output {
        path: dir.join("claims.json").display().to_string(),
        reason: e.to_string(),
    })?;
    write(dir, "claims.json", &json, &mut files)?;
    bar.inc(1);
    bar.finish_and_clear();
    Ok((claims, files))
}

fn print_summary(claims: &[ClaimResult]) {
    let fmt = |v: Option<f64>| v.map_or_else(|| "-".to_owned(), |x| format!("{x:.5}"));
    let w = claims.iter().map(|r| r.id.len()).max().unwrap_or(0);
    outln!(
        "{:<w$}  {:>12}  {:>12}  status",
        "claim",
        "paper",
        "computed"
    );
    for r in claims {
        outln!(
            "{:<w$}  {:>12}  {:>12}  {}",
            r.id,
            fmt(r.paper),
            fmt(r.computed),
            r.status.as_str()
        );
    }
    let counts: Vec<String> = status_counts(claims)
        .into_iter()
        .filter(|(_, n)| *n > 0)
        .map(|(s, n)| format!("{n} {}", s.as_str()))
        .collect();
    outln!("\n{} claims: {}", claims.len(), counts.join(", "));
}
