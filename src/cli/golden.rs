//! `v2ref golden --check | --update [--dir DIR] [--json]`: compares the
//! golden data in DIR (default `golden`) with the code, or rewrites it.
//!
//! `--check` exits 0 when everything matches and 1 otherwise, naming each
//! mismatch on stderr (one line each); `--update` writes atomically. Exactly
//! one of the two is required (status 2 otherwise).

use super::print_json;
use serde::Serialize;
use std::path::PathBuf;
use std::process::ExitCode;
use v2ref_core::{Error, Result};
use v2ref_reproduction::golden;

/// Flags of `golden`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Recompute every figure and compare with DIR.
    #[arg(long, conflicts_with = "update")]
    check: bool,
    /// Recompute every figure and rewrite DIR (atomically).
    #[arg(long)]
    update: bool,
    /// The golden directory.
    #[arg(long, default_value = "golden")]
    dir: PathBuf,
    /// One JSON document instead of text.
    #[arg(long)]
    json: bool,
    /// Only this part of the golden data.
    #[arg(long, value_enum)]
    only: Option<Part>,
    /// With --update: replace DIR even when it does not hold golden data
    /// v2ref wrote.
    #[arg(long)]
    force: bool,
}

/// A part of the golden data.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Part {
    /// The figures' tables (golden/*.csv, *.json).
    Figures,
    /// The conformance vectors (golden/vectors/).
    Vectors,
}

#[derive(Serialize)]
struct MismatchJson {
    table: String,
    detail: String,
}

#[derive(Serialize)]
struct CheckJson {
    checked: usize,
    mismatched: usize,
    mismatches: Vec<MismatchJson>,
}

#[derive(Serialize)]
struct UpdateJson {
    dir: String,
    files: Vec<String>,
}

/// Exit status when the golden data and the code disagree.
const EXIT_MISMATCH: u8 = 1;

/// Runs `golden`.
pub fn run(args: Args) -> Result<ExitCode> {
    if args.check == args.update {
        return Err(Error::Invalid {
            param: "check",
            reason: "give exactly one of --check or --update".into(),
        });
    }
    let figures = args.only != Some(Part::Vectors);
    let vectors = args.only != Some(Part::Figures);
    if args.update {
        check_update_dir(&args.dir, args.force)?;
        let mut files = Vec::new();
        if figures {
            // Replaces the whole folder: the vectors are written after it,
            // or carried over when only the figures are asked for.
            let keep: &[&str] = if vectors {
                &[]
            } else {
                &[super::vectors::VECTORS_DIR]
            };
            files.extend(golden::update(&args.dir, keep)?);
        }
        if vectors {
            files.extend(super::vectors::update(&args.dir)?);
        }
        if args.json {
            print_json(&UpdateJson {
                dir: args.dir.display().to_string(),
                files: files.iter().map(|f| f.display().to_string()).collect(),
            });
        } else {
            for f in &files {
                outln!("wrote {}", f.display());
            }
        }
        return Ok(ExitCode::SUCCESS);
    }
    if !holds_golden_data(&args.dir) {
        return Err(Error::Invalid {
            param: "dir",
            reason: format!(
                "{}: no golden data here (no .csv or .json files; run from the repository root, or give --dir)",
                args.dir.display()
            ),
        });
    }
    let mut report = if figures {
        golden::check(&args.dir)?
    } else {
        golden::Report::default()
    };
    if vectors {
        let (checked, bad) = super::vectors::check(&args.dir)?;
        report.checked += checked;
        report.mismatches.extend(
            bad.into_iter()
                .map(|m| v2ref_reproduction::table::Mismatch {
                    table: m.file,
                    detail: m.detail,
                }),
        );
    }
    if args.json {
        print_json(&CheckJson {
            checked: report.checked,
            mismatched: report.mismatches.len(),
            mismatches: report
                .mismatches
                .iter()
                .map(|m| MismatchJson {
                    table: m.table.clone(),
                    detail: m.detail.clone(),
                })
                .collect(),
        });
    } else {
        outln!(
            "checked {} tables in {}: {} mismatch(es)",
            report.checked,
            args.dir.display(),
            report.mismatches.len()
        );
    }
    for m in &report.mismatches {
        errln!("mismatch: {}: {}", m.table, m.detail);
    }
    Ok(if report.mismatches.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(EXIT_MISMATCH)
    })
}

/// Whether `dir` is a folder holding at least one `.csv` or `.json` file
/// (checked before minutes of computing, so that a wrong folder is not
/// reported as every table missing).
fn holds_golden_data(dir: &std::path::Path) -> bool {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return false;
    };
    entries.flatten().any(|e| {
        let path = e.path();
        path.extension().is_some_and(|x| x == "csv" || x == "json")
    })
}

/// Refuses, before any work, to replace with `--update` a folder v2ref did
/// not write: DIR must be new, empty, or hold a figure's metadata written by
/// `golden --update` (a `fig*.json` naming its generator) or its vectors
/// (`vectors/README.md` saying so), else `--force`.
fn check_update_dir(dir: &std::path::Path, force: bool) -> Result<()> {
    let refuse = |reason: &str| Error::Invalid {
        param: "dir",
        reason: format!("{}: {reason}", dir.display()),
    };
    match std::fs::symlink_metadata(dir) {
        Err(_) => return Ok(()),
        Ok(m) if !m.is_dir() => return Err(refuse("exists and is not a folder; give a folder")),
        Ok(_) => {}
    }
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Ok(());
    };
    let entries: Vec<_> = entries.flatten().map(|e| e.path()).collect();
    let written_by_golden = entries.iter().any(|p| {
        let name = p.file_name().map(|n| n.to_string_lossy().into_owned());
        name.is_some_and(|n| n.starts_with("fig") && n.ends_with(".json"))
            && golden::read_golden(p).is_ok_and(|t| t.contains(golden::GENERATOR))
    });
    let vectors_readme = dir.join(super::vectors::VECTORS_DIR).join("README.md");
    let vectors_by_golden = golden::read_golden(&vectors_readme)
        .is_ok_and(|t| t.contains(super::vectors::GENERATED_BY));
    if force || entries.is_empty() || written_by_golden || vectors_by_golden {
        Ok(())
    } else {
        Err(refuse(
            "is a folder golden --update did not write (no fig*.json naming its generator, no vectors/README.md of its own) and would be replaced; give a new folder or --force",
        ))
    }
}
