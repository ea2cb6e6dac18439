//! `v2ref estimate`: per row of a file of interferograms, V1² and V2² raw,
//! bias-subtracted and normalized (`v2ref_core::conformance::estimate`), for a
//! window of bins, a bias convention and a calibrator.

use super::inputs::InputsArgs;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use v2ref_commands::commands::estimate::{
    estimate_rows, CalibratorRows, Configuration, RowsName, STREAM_ROWS,
};
use v2ref_core::conformance::estimate::{BiasConvention, RowEstimate, RowEstimator};
use v2ref_core::formalism::estimator::BinWindow;
use v2ref_core::{Error, Result};
use v2ref_files::atomic::set::OutputSet;
use v2ref_files::formats::{read_matrix, CsvRowWriter, NpyRowWriter, RowStream};

/// The columns written, in order.
pub use v2ref_commands::commands::ESTIMATE_COLUMNS as COLUMNS;

/// Flags of `estimate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Interferograms: .npy (float64, rows × N) or .csv (one row per line);
    /// default: the sidecar's .npy. With --sidecar, other rows than the
    /// set's may be any number but must have its N.
    #[arg(long, value_name = "FILE")]
    input: Option<PathBuf>,
    /// A synth sidecar (SET.json): the configuration comes from it, and the
    /// physical flags are refused.
    #[arg(long, value_name = "FILE", conflicts_with_all = ["ObservationArgs", "ScanArgs", "LightArgs", "PistonArgs", "TurbulenceArgs", "counts"])]
    sidecar: Option<PathBuf>,
    #[command(flatten)]
    inputs: InputsArgs,
    /// Without --sidecar: the rows hold the counts I_i (continuum not
    /// subtracted) rather than M_i = I_i − c_i.
    #[arg(long)]
    counts: bool,
    /// Fourier bins the estimators sum.
    #[arg(long, value_parser = super::flags::choice::<BinWindow>(), default_value = "positive")]
    bins: BinWindow,
    /// Where the photon bias takes the mean counts from.
    /// With piston (--fringe-hz) use counts: model subtracts the bias of
    /// the piston-free counts and is biased on V2² (tests/simulator.rs).
    #[arg(long, value_parser = super::flags::choice::<BiasConvention>(), default_value = "model")]
    bias: BiasConvention,
    /// `model` (the configuration's point source, noise-free) or a file of
    /// a calibrator's interferograms (same N and continuum convention):
    /// the mean of its bias-subtracted estimates.
    #[arg(long, default_value = "model", value_name = "model|FILE")]
    calibrator: String,
    /// Output file (.csv, .npy, or .fits for OIFITS v2: V², closed-form
    /// VIS2ERR, baseline and band); default: CSV on standard output. Any
    /// other extension is refused.
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// With --out FILE.fits: the estimators written, one INSNAME each.
    #[arg(long, value_enum, default_value = "both")]
    oifits_estimator: super::oifits::Which,
    #[command(flatten)]
    observing: super::oifits::ObservingArgs,
    /// Replace an existing output file (never a link, folder or device).
    #[arg(long)]
    force: bool,
    #[command(flatten)]
    memory: super::memory::MemoryArgs,
    /// Worker threads (0 = all cores); the answer does not depend on it.
    #[arg(long, value_parser = super::thread_count, default_value = "0", allow_negative_numbers = true)]
    threads: usize,
}

/// The configuration and the file to read.
struct Source {
    config: Configuration,
    input: PathBuf,
}

impl Source {
    /// How a refusal names the interferograms.
    fn name(&self) -> RowsName<'_> {
        RowsName {
            param: "input",
            path: Some(&self.input),
        }
    }
}

/// Runs `estimate`.
pub fn run(args: Args) -> Result<ExitCode> {
    args.memory.apply()?;
    let source = source(&args)?;
    // What is at the path first (a device, a link, a folder, a user's file),
    // then the format its extension names.
    let targets: Vec<_> = args.out.iter().map(|p| (p.as_path(), "out")).collect();
    let set = OutputSet::begin(&targets, args.force)?;
    super::oifits::check_estimates_out(args.out.as_deref())?;
    let fits = args.out.as_deref().is_some_and(v2ref_oifits::is_fits_path);
    let observing = args.observing.resolve(fits, "--out FILE.fits")?;
    set.write(|| estimate_and_write(&args, &source, &observing))
}

/// Estimates every row of the input and writes the answer to `--out` (or
/// standard output).
fn estimate_and_write(
    args: &Args,
    source: &Source,
    observing: &v2ref_oifits::ObservingContext,
) -> Result<ExitCode> {
    let (rows, cols) = match RowStream::open(&source.input, "input")? {
        Some(mut stream) => {
            // The answer is held whole (6 values a row): refused from the
            // header when it cannot fit.
            let answer_bytes = stream.rows() as u64 * std::mem::size_of::<RowEstimate>() as u64;
            v2ref_files::formats::check_budget(answer_bytes, "input", &source.input)?;
            let est = estimator(args, source, stream.rows(), stream.cols())?;
            let mut out = Vec::with_capacity(stream.rows());
            let mut block = Vec::new();
            while stream.next_block(STREAM_ROWS, &mut block)? > 0 {
                let at = (block.as_slice(), out.len());
                out.extend(estimate_rows(&est, source.name(), at, args.threads)?);
            }
            (out, stream.cols())
        }
        None => {
            let data = read_matrix(&source.input, "input")?;
            let est = estimator(args, source, data.rows, data.cols)?;
            let at = (data.data.as_slice(), 0);
            (
                estimate_rows(&est, source.name(), at, args.threads)?,
                data.cols,
            )
        }
    };
    if let Some(p) = args.out.as_ref().filter(|p| v2ref_oifits::is_fits_path(p)) {
        let inputs = source.config.inputs_for(source.name(), rows.len(), cols)?;
        let what = (args.bins, args.bias, args.oifits_estimator);
        super::oifits::write_estimates(p, &inputs, &rows, what, observing)?;
        return Ok(ExitCode::SUCCESS);
    }
    write(&args.out, &rows)?;
    Ok(ExitCode::SUCCESS)
}

/// The estimator of `rows` rows of `cols` samples under the flags.
fn estimator(args: &Args, source: &Source, rows: usize, cols: usize) -> Result<RowEstimator> {
    let inputs = source.config.inputs_for(source.name(), rows, cols)?;
    let calibrator = match args.calibrator.as_str() {
        "model" => None,
        path => Some((Path::new(path), read_matrix(Path::new(path), "calibrator")?)),
    };
    let calibrator = calibrator.as_ref().map(|(path, data)| CalibratorRows {
        name: RowsName {
            param: "calibrator",
            path: Some(path),
        },
        rows: &data.data,
        cols: data.cols,
    });
    let options = (args.bins, args.bias);
    let cs = source.config.continuum_subtracted;
    v2ref_commands::commands::estimate::estimator(&inputs, options, cs, calibrator, args.threads)
}

/// The `.npy` rows of the set whose sidecar is `sidecar_path`, named `npy`
/// in it (relative to its folder). A sidecar's names are JSON text, where
/// a name that is not UTF-8 can only be written lossily (U+FFFD for each
/// bad byte): when `npy` is the lossy form of the sidecar's own name with
/// `.npy` (how `synth` names a set), that name is the file, byte for byte.
/// A name with a folder in it (`../x`, `/etc/x`) is refused: a set's files
/// are beside its sidecar, and nothing else is read on a file's word.
fn set_rows_path(sidecar_path: &Path, npy: &str) -> Result<PathBuf> {
    let beside = sidecar_path.with_extension("npy");
    match beside.file_name() {
        Some(name) if name.to_string_lossy() == npy => Ok(beside),
        _ if Path::new(npy).file_name() == Some(std::ffi::OsStr::new(npy)) => {
            Ok(sidecar_path.parent().unwrap_or(Path::new(".")).join(npy))
        }
        _ => Err(Error::data(
            "sidecar",
            sidecar_path,
            "field data.npy",
            format!("{npy:?} is not a file name in the sidecar's folder; a set's files are beside its sidecar"),
        )),
    }
}

fn source(args: &Args) -> Result<Source> {
    match &args.sidecar {
        Some(path) => {
            let sidecar = super::score::read_sidecar(path)?;
            let default_input = set_rows_path(path, &sidecar.data.npy)?;
            if args.input.is_none() {
                // A name found in a file, not given: never read through a
                // link (nor waited on).
                v2ref_files::formats::open_found(&default_input, "sidecar").map(drop)?;
            }
            // A set a stopped run left half placed is refused here.
            let members = sidecar.members.clone().unwrap_or_default();
            let read = args.input.as_ref().unwrap_or(&default_input);
            let param = if args.input.is_some() {
                "input"
            } else {
                "sidecar"
            };
            v2ref_files::atomic::set::verify_member(path, &members, read, param)?;
            let config = Configuration::from_sidecar(sidecar);
            // Other rows than the set's (--input) may be as many as they
            // like, but of the set's N.
            Ok(match &args.input {
                Some(p) => Source {
                    config: Configuration {
                        set_rows: None,
                        ..config
                    },
                    input: p.clone(),
                },
                None => Source {
                    config,
                    input: default_input,
                },
            })
        }
        None => {
            let input = args.input.clone().ok_or_else(|| Error::Invalid {
                param: "input",
                reason:
                    "give the interferograms (--input FILE) or a synth sidecar (--sidecar SET.json)"
                        .into(),
            })?;
            let physical = args.inputs.physical()?;
            physical.refuse_channels("estimate")?;
            Ok(Source {
                config: Configuration::from_physical(&physical, !args.counts)?,
                input,
            })
        }
    }
}

/// Writes `rows` to `--out` (`.npy` or CSV) or standard output, a block of
/// rows at a time (no second copy of the answer).
fn write(out: &Option<PathBuf>, rows: &[RowEstimate]) -> Result<()> {
    let mut flat = Vec::new();
    let mut each_block = |write_rows: &mut dyn FnMut(&[f64]) -> Result<()>| {
        for block in rows.chunks(STREAM_ROWS) {
            flat.clear();
            flat.extend(block.iter().flat_map(RowEstimate::values));
            write_rows(&flat)?;
        }
        Ok::<(), Error>(())
    };
    match out {
        Some(p) if p.extension().is_some_and(|e| e == "npy") => {
            let mut w = NpyRowWriter::create(p, rows.len() as u64, COLUMNS.len(), "out")?;
            each_block(&mut |v| w.write_rows(v))?;
            w.finish()
        }
        Some(p) => {
            let mut w = CsvRowWriter::create(
                p,
                rows.len() as u64,
                COLUMNS.len(),
                Some(&COLUMNS.join(",")),
                "out",
            )?;
            each_block(&mut |v| w.write_rows(v))?;
            w.finish()
        }
        None => {
            let stdout = std::io::stdout();
            let mut w = std::io::BufWriter::new(stdout.lock());
            let fail = |e: std::io::Error| Error::file(Some("out"), "<stdout>", e);
            writeln!(w, "{}", COLUMNS.join(",")).map_err(fail)?;
            for r in rows {
                let v = r.values();
                writeln!(
                    w,
                    "{:?},{:?},{:?},{:?},{:?},{:?}",
                    v[0], v[1], v[2], v[3], v[4], v[5]
                )
                .map_err(fail)?;
            }
            w.flush().map_err(fail)
        }
    }
}
