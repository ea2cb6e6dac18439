//! `v2ref reproduce`: regenerates every figure of the paper (CSV, JSON
//! metadata, SVG plot per panel) and the claims table (Markdown and JSON)
//! into one directory, atomically: everything is written to a fresh sibling
//! directory first and moved into place only when complete.

use super::{print_json, progress_bar};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use v2ref::claims::{evaluate, status_counts, to_markdown, ClaimResult, Effort};
use v2ref::{Error, Result};

/// Flags of `reproduce`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Output directory (replaced as a whole when the run succeeds).
    #[arg(long, default_value = "reproduction")]
    out: PathBuf,
    /// Fewer Monte Carlo scans and coarser grids, same code paths.
    #[arg(long)]
    quick: bool,
    /// One JSON document (claims and files) instead of the summary table.
    #[arg(long)]
    json: bool,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

#[derive(Serialize)]
struct Answer {
    out: String,
    effort: &'static str,
    claims: Vec<ClaimResult>,
    files: Vec<String>,
}

fn io_error(path: &Path, e: impl std::fmt::Display) -> Error {
    Error::Io {
        path: path.display().to_string(),
        reason: e.to_string(),
    }
}

fn write(dir: &Path, name: &str, contents: &str, files: &mut Vec<String>) -> Result<()> {
    let path = dir.join(name);
    std::fs::write(&path, contents).map_err(|e| io_error(&path, e))?;
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
    let effort = if args.quick {
        Effort::Quick
    } else {
        Effort::Full
    };
    let parent = match args.out.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = args
        .out
        .file_name()
        .ok_or_else(|| Error::Invalid {
            param: "out",
            reason: format!("{} is not a directory name", args.out.display()),
        })?
        .to_string_lossy()
        .into_owned();
    std::fs::create_dir_all(&parent).map_err(|e| io_error(&parent, e))?;
    let staging = parent.join(format!(".{name}.partial-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&staging);
    std::fs::create_dir_all(&staging).map_err(|e| io_error(&staging, e))?;
    let outcome = build(&staging, effort, args.quiet);
    let (claims, files) = match outcome {
        Ok(v) => v,
        Err(e) => {
            let _ = std::fs::remove_dir_all(&staging);
            return Err(e);
        }
    };
    if args.out.exists() {
        std::fs::remove_dir_all(&args.out).map_err(|e| io_error(&args.out, e))?;
    }
    std::fs::rename(&staging, &args.out).map_err(|e| io_error(&args.out, e))?;

    if args.json {
        print_json(&Answer {
            out: args.out.display().to_string(),
            effort: if args.quick { "quick" } else { "full" },
            claims,
            files,
        });
    } else {
        print_summary(&claims);
        println!(
            "\nwrote {} files into {}/ (figures as CSV + SVG, claims.md, claims.json)",
            files.len(),
            args.out.display()
        );
    }
    Ok(ExitCode::SUCCESS)
}

/// Computes and writes everything into `dir`; returns the claims and the
/// files written (relative names).
fn build(dir: &Path, effort: Effort, quiet: bool) -> Result<(Vec<ClaimResult>, Vec<String>)> {
    let bar = progress_bar(3, quiet, "figures");
    let mut files = Vec::new();
    let figures = v2ref::figures::all(effort)?;
    bar.inc(1);
    bar.set_message("plots");
    for fig in &figures {
        let meta = serde_json::json!({
            "id": fig.id,
            "caption": fig.caption,
            "monte_carlo": fig.monte_carlo,
            "parameters": fig.parameters,
            "tables": fig.tables.iter().map(|t| &t.name).collect::<Vec<_>>(),
            "generator": format!("v2ref {} reproduce{}", env!("CARGO_PKG_VERSION"), if effort == Effort::Quick { " --quick" } else { "" }),
        });
        let meta = serde_json::to_string_pretty(&meta).map_err(|e| io_error(dir, e))?;
        write(dir, &format!("{}.json", fig.id), &meta, &mut files)?;
        for table in &fig.tables {
            write(
                dir,
                &format!("{}.csv", table.name),
                &table.to_csv(),
                &mut files,
            )?;
            let svg = v2ref::plot::table_svg(fig, table)?;
            write(dir, &format!("{}.svg", table.name), &svg, &mut files)?;
        }
    }
    bar.inc(1);
    bar.set_message("claims");
    let claims = evaluate(effort);
    write(dir, "claims.md", &to_markdown(&claims), &mut files)?;
    let json = serde_json::to_string_pretty(&claims).map_err(|e| io_error(dir, e))?;
    write(dir, "claims.json", &json, &mut files)?;
    bar.inc(1);
    bar.finish_and_clear();
    Ok((claims, files))
}

fn print_summary(claims: &[ClaimResult]) {
    let fmt = |v: Option<f64>| v.map_or_else(|| "-".to_owned(), |x| format!("{x:.5}"));
    let w = claims.iter().map(|r| r.id.len()).max().unwrap_or(0);
    println!(
        "{:<w$}  {:>12}  {:>12}  status",
        "claim", "paper", "computed"
    );
    for r in claims {
        println!(
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
    println!("\n{} claims: {}", claims.len(), counts.join(", "));
}
