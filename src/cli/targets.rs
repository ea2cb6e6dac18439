//! `v2ref plan --targets FILE`: every target of a CSV list planned with the
//! instrument's flags shared, one table of recommendations
//! (`v2ref_commands::commands::targets`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use v2ref_commands::commands::plan::PlanRequest;
use v2ref_commands::commands::targets::{self, SharedPlan, Status};
use v2ref_commands::parameters::Physical;
use v2ref_core::Result;

/// The flags of `plan` for a target list.
#[derive(Debug, clap::Args)]
pub struct TargetsArgs {
    /// Plan every target of this CSV list instead of one source: a header
    /// naming its columns (name, required; magnitude and band, together;
    /// diameter_mas; ra_deg, dec_deg, echoed), then one target a line; an
    /// empty cell or absent column takes the shared flag. Every other flag
    /// applies to every row. Writes one table (CSV, one row per target) to
    /// --out or stdout. A bad row is reported on stderr by its line, marked
    /// `error` in the table, and the others are planned: the exit status is
    /// then 2 (0 when every row was planned).
    #[arg(long, value_name = "FILE.csv", group = "brightness",
          conflicts_with_all = ["svg", "oifits"])]
    pub targets: Option<PathBuf>,
    /// With --targets: write the table to this CSV file (written whole or
    /// not at all; an existing file is refused without --force) instead of
    /// stdout.
    #[arg(long, value_name = "FILE.csv", requires = "targets")]
    pub out: Option<PathBuf>,
}

/// What of `plan`'s other flags the target list reads.
pub struct PlanFlags {
    /// A row's magnitude is collected with this throughput (--throughput,
    /// else the preset's).
    pub throughput: Option<f64>,
    /// --force.
    pub force: bool,
    /// Observations of --verify, if asked.
    pub verify_observations: Option<u64>,
    /// --quiet.
    pub quiet: bool,
    /// --threads.
    pub threads: usize,
    /// --json.
    pub json: bool,
}

/// Runs `plan --targets` with `plan`'s flags `o` and the shared inputs
/// `(physical, request)` they give.
pub fn run(args: &TargetsArgs, o: PlanFlags, shared: (Physical, PlanRequest)) -> Result<ExitCode> {
    let Some(list) = &args.targets else {
        return Ok(ExitCode::SUCCESS);
    };
    let outputs: Vec<(&Path, &'static str)> =
        args.out.iter().map(|p| (p.as_path(), "out")).collect();
    let set = v2ref_files::atomic::set::OutputSet::begin(&outputs, o.force)?;
    let rows = v2ref_files::formats::targets_csv::read_targets(list)?;
    let (physical, request) = shared;
    let shared = SharedPlan {
        physical,
        request,
        throughput: o.throughput,
        verify_observations: o.verify_observations,
    };
    let bar = super::progress_bar(rows.len() as u64, o.quiet, "plan --targets");
    let table = targets::plan_targets(&shared, &rows, o.threads, &|k| bar.inc(k))?;
    bar.finish_and_clear();
    for row in table.iter().filter(|r| r.status == Status::Error) {
        let reason = row.reason.as_deref().unwrap_or("");
        errln!("error: {} line {}: {reason}", list.display(), row.line);
    }
    let csv = targets::table_csv(&table);
    set.write(|| match &args.out {
        Some(path) => v2ref_files::atomic::write_text_atomic(path, &csv),
        None => Ok(()),
    })?;
    if o.json {
        super::print_json(&table);
    } else if args.out.is_none() {
        super::output::write_stdout_line(format_args!("{}", csv.trim_end()));
    }
    let bad = table.iter().any(|r| r.status == Status::Error);
    Ok(if bad {
        ExitCode::from(2)
    } else {
        ExitCode::SUCCESS
    })
}
