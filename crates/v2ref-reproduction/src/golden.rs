//! Golden data: the figures' curves stored in `golden/` and checked against
//! the code.
//!
//! Layout: one CSV per figure panel (`<table>.csv`, a header of
//! `name [unit]` cells then rows with 17 significant digits, see
//! [`crate::table::Table::to_csv`]) and one JSON per figure
//! (`<fig>.json`: id, caption, parameters, whether Monte Carlo, its tables,
//! the generator command and the crate version).
//!
//! [`check`] recomputes every figure of [`crate::figures::all`] at
//! [`Effort::Full`] and compares cell by cell: deterministic tables to
//! `tolerance::GOLDEN_REL` (1e-12) relative (floor `tolerance::GOLDEN_ABS`, 1e-14), Monte Carlo tables
//! exactly (same seed, same bits). It returns every mismatch, including
//! missing or extra files and changed parameters. [`update`] rewrites the
//! directory atomically: everything is written into a temporary sibling
//! directory that then replaces the old one by rename, so an interrupted
//! update leaves the old data whole.

use crate::cases::Effort;
use crate::error::{Error, Result};
use crate::table::{compare_tables, Figure, Mismatch, Table};
use crate::tolerance::{GOLDEN_ABS, GOLDEN_REL};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The command that regenerates `golden/`.
pub const GENERATOR: &str = "cargo run --release -- golden --update";

/// One table in a figure's metadata.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TableMeta {
    /// Table name (file stem).
    pub name: String,
    /// File name, `<name>.csv`.
    pub file: String,
    /// Column headers, `name [unit]`.
    pub columns: Vec<String>,
    /// Number of data rows.
    pub rows: usize,
}

/// A figure's metadata file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FigureMeta {
    /// `fig0` … `fig5`.
    pub id: String,
    /// What it shows.
    pub caption: String,
    /// Whether the numbers are Monte Carlo estimates (compared exactly).
    pub monte_carlo: bool,
    /// Every parameter the curves depend on.
    pub parameters: serde_json::Value,
    /// Its panels.
    pub tables: Vec<TableMeta>,
    /// The command that wrote it.
    pub generator: String,
    /// The crate version that wrote it.
    pub crate_version: String,
}

impl FigureMeta {
    /// The metadata of `fig`.
    pub fn of(fig: &Figure) -> FigureMeta {
        FigureMeta {
            id: fig.id.clone(),
            caption: fig.caption.clone(),
            monte_carlo: fig.monte_carlo,
            parameters: fig.parameters.clone(),
            tables: fig
                .tables
                .iter()
                .map(|t| TableMeta {
                    name: t.name.clone(),
                    file: format!("{}.csv", t.name),
                    columns: t.columns.iter().map(|c| c.header()).collect(),
                    rows: t.rows.len(),
                })
                .collect(),
            generator: GENERATOR.to_owned(),
            crate_version: env!("CARGO_PKG_VERSION").to_owned(),
        }
    }
}

/// The outcome of a check.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Report {
    /// Tables compared.
    pub checked: usize,
    /// Every difference found.
    pub mismatches: Vec<Mismatch>,
}

/// A failed file operation on `path` (inside the golden folder).
/// Largest golden file read, bytes (the largest v2ref writes is about
/// 0.5 MB: a bound, not a size any golden file comes near).
pub const MAX_GOLDEN_FILE_BYTES: u64 = 64 << 20;

/// The text of the golden file `path`, a name found in the golden folder:
/// never read through a link, a FIFO or device refused without waiting
/// on it, at most [`MAX_GOLDEN_FILE_BYTES`].
pub fn read_golden(path: &Path) -> Result<String> {
    let accepted = "a file written by golden --update";
    v2ref_files::formats::read_found_text(path, "dir", MAX_GOLDEN_FILE_BYTES, accepted)
}

fn io(path: &Path, e: std::io::Error) -> Error {
    Error::file(None, path, e)
}

/// An output that could not be produced (no system error behind it).
fn output(path: &Path, e: impl std::fmt::Display) -> Error {
    Error::Output {
        path: path.display().to_string(),
        reason: e.to_string(),
    }
}

/// Whether two JSON values are equal, numbers to [`GOLDEN_REL`] (JSON
/// number parsing is not guaranteed to round-trip the last bit).
fn same_json(a: &serde_json::Value, b: &serde_json::Value) -> bool {
    use serde_json::Value;
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => match (x.as_f64(), y.as_f64()) {
            (Some(x), Some(y)) => x == y || (x - y).abs() <= GOLDEN_REL * x.abs().max(y.abs()),
            _ => x == y,
        },
        (Value::Array(x), Value::Array(y)) => {
            x.len() == y.len() && x.iter().zip(y).all(|(p, q)| same_json(p, q))
        }
        (Value::Object(x), Value::Object(y)) => {
            x.len() == y.len()
                && x.iter()
                    .all(|(k, v)| y.get(k).is_some_and(|w| same_json(v, w)))
        }
        _ => a == b,
    }
}

/// Compares `figures` with the golden data in `dir`.
pub fn check_figures(dir: &Path, figures: &[Figure]) -> Report {
    let mut report = Report::default();
    let mut found: Vec<Mismatch> = Vec::new();
    let push = |found: &mut Vec<Mismatch>, table: &str, detail: String| {
        found.push(Mismatch {
            table: table.to_owned(),
            detail,
        })
    };
    let mut checked = 0;
    for fig in figures {
        let meta_path = dir.join(format!("{}.json", fig.id));
        match read_golden(&meta_path)
            .map_err(|e| e.to_string())
            .and_then(|t| {
                serde_json::from_str::<FigureMeta>(&t)
                    .map_err(|e| format!("{}: {e}", meta_path.display()))
            }) {
            Err(e) => push(&mut found, &fig.id, e),
            Ok(meta) => {
                if !same_json(&meta.parameters, &fig.parameters) {
                    push(
                        &mut found,
                        &fig.id,
                        "the parameters differ from the golden metadata".into(),
                    );
                }
                if meta.monte_carlo != fig.monte_carlo {
                    push(&mut found, &fig.id, "the Monte Carlo flag differs".into());
                }
                let golden_names: Vec<&str> = meta.tables.iter().map(|t| t.name.as_str()).collect();
                for name in &golden_names {
                    if !fig.tables.iter().any(|t| t.name == *name) {
                        push(&mut found, name, "in golden but no longer computed".into());
                    }
                }
            }
        }
        let (rel, abs) = if fig.monte_carlo {
            (0.0, 0.0)
        } else {
            (GOLDEN_REL, GOLDEN_ABS)
        };
        for table in &fig.tables {
            checked += 1;
            let path = dir.join(format!("{}.csv", table.name));
            let golden = read_golden(&path).and_then(|text| Table::from_csv(&table.name, &text));
            match golden {
                Err(e) => push(&mut found, &table.name, e.to_string()),
                Ok(g) => found.extend(compare_tables(&g, table, rel, abs)),
            }
        }
    }
    // Figures stored but no longer computed.
    if let Ok(entries) = std::fs::read_dir(dir) {
        let mut extra: Vec<String> = entries
            .filter_map(|e| e.ok())
            .filter_map(|e| e.file_name().into_string().ok())
            .filter_map(|n| n.strip_suffix(".json").map(str::to_owned))
            .filter(|id| !figures.iter().any(|f| &f.id == id))
            .collect();
        extra.sort();
        for id in extra {
            found.push(Mismatch {
                table: id,
                detail: "in golden but no longer computed".into(),
            });
        }
    }
    report.checked = checked;
    report.mismatches = found;
    report
}

/// Recomputes every figure at full effort and compares with `dir`.
pub fn check(dir: &Path) -> Result<Report> {
    let figures = crate::figures::all(Effort::Full)?;
    Ok(check_figures(dir, &figures))
}

/// Writes each figure's tables (`<table>.csv`) and metadata (`<fig>.json`,
/// with `generator` as the command that wrote it) into the existing
/// directory `dir`. Returns the file names written.
pub fn write_figure_files(dir: &Path, figures: &[Figure], generator: &str) -> Result<Vec<String>> {
    let mut files = Vec::new();
    for fig in figures {
        for table in &fig.tables {
            let name = format!("{}.csv", table.name);
            let p = dir.join(&name);
            std::fs::write(&p, table.to_csv()).map_err(|e| io(&p, e))?;
            files.push(name);
        }
        let name = format!("{}.json", fig.id);
        let p = dir.join(&name);
        let mut meta = FigureMeta::of(fig);
        meta.generator = generator.to_owned();
        let json = serde_json::to_string_pretty(&meta).map_err(|e| output(&p, e))?;
        std::fs::write(&p, json + "\n").map_err(|e| io(&p, e))?;
        files.push(name);
    }
    Ok(files)
}

/// Replaces the directory `dir` as a whole: `fill` writes into a fresh
/// temporary sibling, which then takes `dir`'s place by rename. If `fill`
/// fails, or the rename does, the old `dir` is left as it was and nothing
/// half-written remains. The crate's one atomic writer
/// ([`crate::atomic::replace_folder`]: `dir` locked for the run, the
/// temporaries of dead processes removed first).
pub fn replace_dir_atomically<T>(dir: &Path, fill: impl FnOnce(&Path) -> Result<T>) -> Result<T> {
    crate::atomic::replace_folder(dir, None, fill)
}

/// Checks, before any work, that [`replace_dir_atomically`] can write next
/// to `dir` ([`crate::atomic::check_folder_parent`]).
pub fn check_parent_writable(dir: &Path) -> Result<()> {
    crate::atomic::check_folder_parent(dir, None)
}

/// Writes `figures` into `dir` atomically ([`replace_dir_atomically`]).
/// Returns the files written (paths inside `dir`).
pub fn write_figures(dir: &Path, figures: &[Figure]) -> Result<Vec<PathBuf>> {
    let names = replace_dir_atomically(dir, |tmp| write_figure_files(tmp, figures, GENERATOR))?;
    Ok(names.into_iter().map(|n| dir.join(n)).collect())
}

/// Recomputes every figure at full effort and rewrites `dir`, carrying
/// the sub-folders named in `keep` over unchanged (`golden --update --only
/// figures` keeps `vectors/`: the folder is replaced whole, and a sub-folder
/// not carried over would be deleted).
pub fn update(dir: &Path, keep: &[&str]) -> Result<Vec<PathBuf>> {
    check_parent_writable(dir)?;
    let figures = crate::figures::all(Effort::Full)?;
    let names = replace_dir_atomically(dir, |tmp| {
        for sub in keep {
            copy_flat_folder(&dir.join(sub), &tmp.join(sub))?;
        }
        write_figure_files(tmp, &figures, GENERATOR)
    })?;
    Ok(names.into_iter().map(|n| dir.join(n)).collect())
}

/// Copies the files of the folder `from` (not its sub-folders: the golden
/// vectors' folder has none) into a new folder `to`; nothing when `from`
/// does not exist.
fn copy_flat_folder(from: &Path, to: &Path) -> Result<()> {
    let io = |e| Error::file(Some("dir"), from, e);
    let entries = match std::fs::read_dir(from) {
        Ok(entries) => entries,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(e) => return Err(io(e)),
    };
    std::fs::create_dir(to).map_err(io)?;
    for entry in entries {
        let entry = entry.map_err(io)?;
        if entry.file_type().map_err(io)?.is_file() {
            std::fs::copy(entry.path(), to.join(entry.file_name())).map_err(io)?;
        }
    }
    Ok(())
}
