//! `v2ref synth`: a set of test interferograms for a pipeline — the rows as
//! NumPy `.npy` (float64, one row per scan, columns in the order of
//! `sample_opd_um`), optionally CSV, and a JSON sidecar with every input
//! and the truth (`v2ref_core::conformance::sidecar`).

use super::common::RunArgs;
use super::inputs::InputsArgs;
use super::progress_bar;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use v2ref_core::conformance::sidecar::Sidecar;
use v2ref_core::conformance::synth::{synthesize, SetSize};
use v2ref_core::conformance::truth::{default_reference_blocks, reference_rows_per_block};
use v2ref_core::simulator::{Model, RowLayout, RowTiming};
use v2ref_core::{Error, Result};
use v2ref_files::atomic::{set::OutputSet, write_text_atomic};
use v2ref_files::formats::{CsvRowWriter, NpyRowWriter};

/// Flags of `synth`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    inputs: InputsArgs,
    /// The set's path without extension: writes OUT.npy, OUT.json (the
    /// sidecar) and, with --csv, OUT.csv.
    #[arg(long, value_name = "PATH")]
    out: PathBuf,
    /// Number of rows (scans).
    #[arg(long, value_parser = super::count_u64, default_value = "1000", allow_negative_numbers = true)]
    rows: u64,
    /// Also write the rows as CSV (one row per line, no header).
    #[arg(long)]
    csv: bool,
    /// Also write the truth (expected V1², V2² of every row, window
    /// positive, convention model) as OIFITS v2: OUT.truth.fits.
    #[arg(long)]
    oifits: bool,
    #[command(flatten)]
    observing: super::oifits::ObservingArgs,
    /// Write the counts I_i instead of the modulated samples M_i = I_i − c_i.
    #[arg(long)]
    keep_continuum: bool,
    /// How the rows lie in time through the piston (with --fringe-hz).
    /// sequences: cut from up to 16 independent piston sequences, scans
    /// spread over two correlation times in each — the statistics of one
    /// scan (per-scan bias and scatter). observation: --observations
    /// observations of rows/observations consecutive scans (one scan and
    /// --dead-time-s apart) — the observation a plan recommends, to check
    /// its promise for the mean of n consecutive scans; each reads the
    /// start of its own piston sequence, at least 4 times longer and two
    /// correlation times B/v, so its drift is kept. The sidecar's `layout`
    /// records it.
    #[arg(long, value_parser = super::flags::choice::<RowLayout>(), default_value = "sequences")]
    layout: RowLayout,
    /// With --layout observation: independent observations (each its own
    /// atmosphere, keyed by its index), 1 to 1e6, dividing --rows; their
    /// piston together within 2^24 samples.
    #[arg(long, value_parser = super::count_u64, default_value = "1", allow_negative_numbers = true)]
    observations: u64,
    /// With --layout observation: dead time between consecutive scans, s,
    /// 0 to 3.2e7 (a year), as `plan --dead-time-s`.
    #[arg(long, default_value = "0", value_parser = super::finite_f64, allow_negative_numbers = true)]
    dead_time_s: f64,
    /// Blocks of the truth's reference run: 0 (closed forms only), or 8 to
    /// 1000; default 16 with piston (replicates of the set, whose spread the
    /// score divides by, as Student-t with blocks − 1 degrees of freedom),
    /// 8 without (pooled independent rows, for the counts convention's
    /// variance and the spread of a set's variance).
    #[arg(long, value_parser = super::count_u64, allow_negative_numbers = true)]
    reference_blocks: Option<u64>,
    #[command(flatten)]
    run: RunArgs,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
    /// Replace an existing output file (never a link, folder or device).
    #[arg(long)]
    force: bool,
}

/// Runs `synth`.
pub fn run(args: Args) -> Result<ExitCode> {
    args.inputs.physical()?.refuse_channels("synth")?;
    let inputs = args.inputs.inputs()?;
    let timing = RowTiming::new(args.layout, args.observations, args.dead_time_s)?;
    let observing = args.observing.resolve(args.oifits, "--oifits")?;
    let reference_blocks = args
        .reference_blocks
        .unwrap_or_else(|| default_reference_blocks(inputs.piston.is_some()));
    v2ref_core::bounds::check_set_size(args.rows, inputs.samples, reference_blocks)?;
    // Every file of the set checked and locked before any work; they
    // appear together at the end, or none does.
    let stem = Stem::new(&args.out)?;
    let mut targets = vec![stem.npy.as_path(), stem.json.as_path()];
    if args.csv {
        targets.push(&stem.csv);
    }
    let fits = truth_fits_path(&args.out);
    if args.oifits {
        targets.push(&fits);
    }
    let targets: Vec<_> = targets.into_iter().map(|p| (p, "out")).collect();
    let set = OutputSet::begin(&targets, args.force)?;
    let piston = inputs.piston.is_some();
    let reference_rows =
        reference_blocks * reference_rows_per_block(args.rows, reference_blocks, piston);
    let model = Model::new(&inputs)?;
    args.inputs.warn_about(&model);
    let spec = SetSpec {
        rows: args.rows,
        seed: args.run.seed,
        reference_blocks,
        threads: args.run.threads,
        csv: args.csv,
        keep_continuum: args.keep_continuum,
        layout: timing,
    };
    let bar = progress_bar(args.rows + reference_rows, args.quiet, "synth");
    set.write(|| {
        let sidecar = write_data(&model, &spec, &args.out, &|k| bar.inc(k))?;
        bar.finish_and_clear();
        if args.oifits {
            super::oifits::write_truth(&fits, &sidecar, &observing)?;
        }
        write_sidecar(&args.out, sidecar).map(drop)
    })?;
    Ok(ExitCode::SUCCESS)
}

/// What to write of a set.
#[derive(Debug, Clone, Copy)]
pub struct SetSpec {
    /// Rows.
    pub rows: u64,
    /// Seed.
    pub seed: u64,
    /// Blocks of the reference run.
    pub reference_blocks: u64,
    /// Worker threads (0: all); the files do not depend on it.
    pub threads: usize,
    /// Also write CSV.
    pub csv: bool,
    /// Write the counts rather than the continuum-subtracted samples.
    pub keep_continuum: bool,
    /// How the rows lie in time through the piston.
    pub layout: RowTiming,
}

/// Writes the set of `model` described by `spec` at `out` (.npy, .json and
/// optionally .csv beside it); returns the sidecar.
pub fn write_set(
    model: &Model,
    spec: &SetSpec,
    out: &Path,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Sidecar> {
    let sidecar = write_data(model, spec, out, progress)?;
    write_sidecar(out, sidecar)
}

/// Writes the sidecar of the set at `out` (`OUT.json`), last: inside a set
/// ([`OutputSet::write`]) it lists the files written before it, with their
/// sizes and checksums, which readers check.
pub fn write_sidecar(out: &Path, mut sidecar: Sidecar) -> Result<Sidecar> {
    let stem = Stem::new(out)?;
    sidecar.members = v2ref_files::atomic::set::staged_members()?;
    let json = serde_json::to_string_pretty(&sidecar).map_err(|e| Error::Output {
        path: stem.json.display().to_string(),
        reason: e.to_string(),
    })?;
    write_text_atomic(&stem.json, &(json + "\n"))?;
    Ok(sidecar)
}

/// Writes the data files of the set of `model` described by `spec` at
/// `out` (.npy, optionally .csv); returns its sidecar, to be written last
/// ([`write_sidecar`]).
fn write_data(
    model: &Model,
    spec: &SetSpec,
    out: &Path,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Sidecar> {
    let stem = Stem::new(out)?;
    let samples = model.inputs.samples;
    let mut npy = NpyRowWriter::create(&stem.npy, spec.rows, samples, "out")?;
    let mut csv = if spec.csv {
        Some(CsvRowWriter::create(
            &stem.csv, spec.rows, samples, None, "out",
        )?)
    } else {
        None
    };
    let size = SetSize {
        rows: spec.rows,
        seed: spec.seed,
        reference_blocks: spec.reference_blocks,
        threads: spec.threads,
        keep_continuum: spec.keep_continuum,
        layout: spec.layout,
    };
    let names = (
        stem.file_name(&stem.npy),
        spec.csv.then(|| stem.file_name(&stem.csv)),
    );
    let mut sink = |rows: &[f64]| -> Result<()> {
        npy.write_rows(rows)?;
        if let Some(c) = csv.as_mut() {
            c.write_rows(rows)?;
        }
        Ok(())
    };
    let sidecar = synthesize(model, &size, names, &mut sink, progress)?;
    npy.finish()?;
    if let Some(c) = csv {
        c.finish()?;
    }
    Ok(sidecar)
}

/// The three paths of a set.
struct Stem {
    npy: PathBuf,
    csv: PathBuf,
    json: PathBuf,
}

impl Stem {
    fn new(out: &Path) -> Result<Stem> {
        v2ref_files::atomic::target::check_file_name(out, "out")?;
        let Some(name) = out.file_name().filter(|n| !n.is_empty()) else {
            return Err(Error::Invalid {
                param: "out",
                reason: format!("{}: needs a file name (the set's stem)", out.display()),
            });
        };
        // The name as given, bytes and all (not made valid UTF-8).
        let with = |ext: &str| {
            let mut n = name.to_os_string();
            n.push(ext);
            out.with_file_name(n)
        };
        let stem = Stem {
            npy: with(".npy"),
            csv: with(".csv"),
            json: with(".json"),
        };
        for p in [&stem.npy, &stem.csv, &stem.json] {
            if p.is_dir() {
                return Err(Error::Invalid {
                    param: "out",
                    reason: format!("{} is a folder", p.display()),
                });
            }
        }
        Ok(stem)
    }

    fn file_name(&self, p: &Path) -> String {
        p.file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default()
    }
}

/// The truth's OIFITS file of the set `out` (`synth --oifits`): `OUT.truth.fits`.
fn truth_fits_path(out: &Path) -> PathBuf {
    let mut name = out.file_name().unwrap_or_default().to_os_string();
    name.push(".truth.fits");
    out.with_file_name(name)
}
