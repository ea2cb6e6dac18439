//! `v2ref score`: a pipeline's per-row estimates of a synth set scored
//! against the set's truth (formulas in `v2ref_core::conformance::score`).
//! Exit status 0 on pass, 1 on fail, 2 on bad input.

use super::{print_json, print_rows};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use v2ref_core::conformance::estimate::BiasConvention;
use v2ref_core::conformance::score::{score_report, ScoreReport, DEFAULT_ALPHA};
use v2ref_core::conformance::sidecar::Sidecar;
use v2ref_core::formalism::estimator::BinWindow;
use v2ref_core::{Error, Result};

/// Exit status of a failed verdict.
pub const EXIT_FAIL: u8 = 1;

/// Flags of `score`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The set's JSON sidecar (written by `v2ref synth`).
    #[arg(long)]
    sidecar: PathBuf,
    /// The pipeline's per-row estimates: .csv with a header naming the
    /// columns (v1_sq and/or v2_sq read, others ignored), a float64 .npy,
    /// or OIFITS (.fits, .oifits, .fit; v1 or v2): OI_VIS2, one channel,
    /// rows in the set's order, FLAGged rows left out and counted.
    #[arg(long)]
    estimates: PathBuf,
    /// Names of the .npy file's columns, in order (v1_sq and v2_sq are
    /// read, other names ignored); default v1_sq,v2_sq.
    #[arg(long, value_delimiter = ',')]
    columns: Option<Vec<String>>,
    /// OIFITS: read only the OI_VIS2 tables of this INSNAME.
    #[arg(long, value_name = "NAME")]
    insname: Option<String>,
    /// OIFITS: the estimator of tables without a V2R_EST keyword (a
    /// pipeline's own file); default: as the keyword says.
    #[arg(long, value_enum)]
    estimator: Option<super::oifits::Which>,
    /// OIFITS: read only the rows of this target (its TARGET name in
    /// OI_TARGET, or its TARGET_ID); needed when the rows are of several.
    #[arg(long, value_name = "NAME|ID")]
    target: Option<String>,
    /// OIFITS: read a file whose CHECKSUM or DATASUM does not match its
    /// bytes (refused by default: it changed after it was written).
    #[arg(long)]
    accept_checksum_mismatch: bool,
    /// Window of bins the estimates sum.
    #[arg(long, value_parser = super::flags::choice::<BinWindow>(), default_value = "positive")]
    bins: BinWindow,
    /// Bias convention the estimates subtract.
    #[arg(long, value_parser = super::flags::choice::<BiasConvention>(), default_value = "model")]
    bias: BiasConvention,
    /// Family-wise false-alarm rate of the verdict (Bonferroni over the
    /// tests made).
    #[arg(long, default_value_t = DEFAULT_ALPHA, value_parser = super::finite_f64)]
    alpha: f64,
    #[command(flatten)]
    memory: super::memory::MemoryArgs,
    /// Print one JSON document instead of a table.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct Answer<'a> {
    sidecar: String,
    estimates: String,
    bins: BinWindow,
    bias: BiasConvention,
    rows: u64,
    /// OIFITS: rows flagged, left out.
    #[serde(skip_serializing_if = "Option::is_none")]
    flagged: Option<u64>,
    #[serde(flatten)]
    report: &'a ScoreReport,
}

/// Reads and checks a sidecar ([`Sidecar::from_json`]).
pub fn read_sidecar(path: &Path) -> Result<Sidecar> {
    Sidecar::from_json(&v2ref_files::formats::read_sidecar_text(path)?, path)
}

/// Runs `score`.
pub fn run(args: Args) -> Result<ExitCode> {
    args.memory.apply()?;
    v2ref_core::conformance::score::critical_z(args.alpha, 1)?;
    let sc = read_sidecar(&args.sidecar)?;
    let truth = sc.truth(args.bins, args.bias).ok_or_else(|| {
        Error::data(
            "sidecar",
            &args.sidecar,
            "field truth.windows",
            format!(
                "no truth for --bins {} --bias {}; pick a window and convention the set has",
                args.bins.name(),
                args.bias.name()
            ),
        )
    })?;
    let flags = super::oifits::OifitsFlags {
        insname: args.insname.clone(),
        estimator: args.estimator,
        target: args.target.clone(),
        accept_checksum_mismatch: args.accept_checksum_mismatch,
    };
    let input = super::oifits::read_for_score(
        &args.estimates,
        args.columns.as_deref(),
        &sc,
        (truth, args.bins, args.bias),
        &flags,
    )?;
    if let Some(flagged) = input.flagged {
        let floor = v2ref_oifits::min_unflagged_rows(sc.data.rows);
        if input.rows < floor {
            return Ok(too_few_rows(&args, sc.data.rows, flagged, floor));
        }
    }
    let (est, rows) = (&input.estimates, input.rows);
    let report = score_report(
        est.v1_sq.as_deref(),
        est.v2_sq.as_deref(),
        &input.truth,
        rows,
        args.alpha,
    )
    .map_err(|e| match e {
        // Name the file the estimates came from.
        Error::Invalid {
            param: "estimates",
            reason,
        } => Error::data("estimates", &args.estimates, "", reason),
        other => other,
    })?;
    if args.json {
        print_json(&Answer {
            sidecar: args.sidecar.display().to_string(),
            estimates: args.estimates.display().to_string(),
            bins: args.bins,
            bias: args.bias,
            rows,
            flagged: input.flagged,
            report: &report,
        });
    } else {
        print_table(&args, rows, &report);
        if let Some(k) = input.flagged.filter(|&k| k > 0) {
            outln!("({k} FLAGged rows left out; {rows} scored)");
        }
    }
    Ok(if report.pass {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(EXIT_FAIL)
    })
}

/// The verdict "too few rows": more of the set's rows are FLAGged than
/// the score can stand for (status [`EXIT_FAIL`]).
fn too_few_rows(args: &Args, set_rows: u64, flagged: u64, floor: u64) -> ExitCode {
    let kept = set_rows - flagged;
    if args.json {
        print_json(&serde_json::json!({
            "sidecar": args.sidecar.display().to_string(),
            "estimates": args.estimates.display().to_string(),
            "bins": args.bins,
            "bias": args.bias,
            "rows": kept,
            "flagged": flagged,
            "min_rows": floor,
            "verdict": "too few rows",
            "pass": false,
        }));
    } else {
        outln!(
            "FAIL: too few rows: {kept} unflagged of {set_rows} ({flagged} FLAGged); \
             at least {floor} are scored"
        );
    }
    ExitCode::from(EXIT_FAIL)
}

fn verdict(pass: bool) -> &'static str {
    if pass {
        "PASS"
    } else {
        "FAIL"
    }
}

/// Says when the z are normal equivalents of Student-t ratios.
fn dof_note(r: &ScoreReport) -> String {
    match r.estimators.iter().find_map(|s| s.score.dof) {
        Some(nu) => format!("; z are the normal equivalents of t with {nu} degrees of freedom"),
        None => String::new(),
    }
}

fn print_table(args: &Args, rows: u64, r: &ScoreReport) {
    print_rows(&[
        ("sidecar", args.sidecar.display().to_string()),
        ("estimates", args.estimates.display().to_string()),
        ("bins", args.bins.name().to_owned()),
        ("bias", args.bias.name().to_owned()),
        ("rows", rows.to_string()),
        (
            "threshold",
            format!(
                "|z| <= {:.4} (alpha {}, Bonferroni over {} tests){}",
                r.z_crit,
                r.alpha,
                r.tests,
                dof_note(r)
            ),
        ),
    ]);
    outln!();
    outln!(
        "{:<6}  {:>14}  {:>14}  {:>8}  {:>14}  {:>14}  {:>8}  {:>10}  {:>10}  verdict",
        "",
        "mean",
        "expected",
        "z_mean",
        "var",
        "expected",
        "z_var",
        "mdb_mean",
        "mdb_var"
    );
    for s in &r.estimators {
        let e = &s.score;
        outln!(
            "{:<6}  {:>14.7e}  {:>14.7e}  {:>8.3}  {:>14.7e}  {:>14.7e}  {:>8.3}  {:>10.3e}  {:>10.3e}  {}",
            s.estimator.name(),
            e.mean,
            e.expected_mean,
            e.z_mean,
            e.var,
            e.expected_var,
            e.z_var,
            e.min_detectable_rel_bias_mean,
            e.min_detectable_rel_bias_var,
            verdict(e.pass)
        );
    }
    outln!();
    outln!("mdb: min detectable relative bias (caught with probability 0.9)");
    outln!("{}", verdict(r.pass));
}
