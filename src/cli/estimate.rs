//! `v2ref estimate`: per row of a file of interferograms, V1² and V2² raw,
//! bias-subtracted and normalized (`v2ref::conformance::estimate`), for a
//! window of bins, a bias convention and a calibrator.

use super::inputs::InputsArgs;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use v2ref::conformance::estimate::{BiasConvention, RowEstimate, RowEstimator};
use v2ref::formalism::estimator::BinWindow;
use v2ref::formats::{read_matrix, CsvRowWriter, NpyRowWriter, NpyRows};
use v2ref::simulator::{Inputs, Model};
use v2ref::{Error, Result};

/// The columns written, in order.
pub use v2ref::commands::ESTIMATE_COLUMNS as COLUMNS;

/// Flags of `estimate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Interferograms: .npy (float64, rows × N) or .csv (one row per line);
    /// default: the sidecar's .npy.
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
    #[arg(long, value_enum, default_value = "positive")]
    bins: BinWindow,
    /// Where the photon bias takes the mean counts from.
    /// With piston (--fringe-hz) use counts: model subtracts the bias of
    /// the piston-free counts and is biased on V2² (tests/simulator.rs).
    #[arg(long, value_enum, default_value = "model")]
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
    /// Replace an existing output file (never a link, folder or device).
    #[arg(long)]
    force: bool,
    /// Worker threads (0 = all cores); the answer does not depend on it.
    #[arg(long, value_parser = super::thread_count, default_value = "0", allow_negative_numbers = true)]
    threads: usize,
}

/// The configuration and the file to read.
struct Source {
    inputs: Inputs,
    input: PathBuf,
    continuum_subtracted: bool,
    expected_rows: Option<u64>,
}

/// Rows estimated at a time from a streamed `.npy` (8 MB at N = 128).
const STREAM_ROWS: usize = 8192;

/// Runs `estimate`.
pub fn run(args: Args) -> Result<ExitCode> {
    let source = source(&args)?;
    // What is at the path first (a device, a link, a folder, a user's file),
    // then the format its extension names.
    if let Some(out) = &args.out {
        v2ref::formats::check_output_file(out, "out", args.force)?;
    }
    super::oifits::check_estimates_out(args.out.as_deref())?;
    let (rows, cols) = match NpyRows::open(&source.input, "input")? {
        Some(mut stream) => {
            let est = estimator(&args, &source, stream.rows, stream.cols)?;
            let mut out = Vec::with_capacity(stream.rows);
            let mut block = Vec::new();
            while stream.next_block(STREAM_ROWS, &mut block)? > 0 {
                refuse_dark_rows(&block, stream.cols, out.len(), &source.input, "input")?;
                out.extend(est.estimate_rows(&block, args.threads)?);
            }
            (out, stream.cols)
        }
        None => {
            let data = read_matrix(&source.input, "input")?;
            let est = estimator(&args, &source, data.rows, data.cols)?;
            refuse_dark_rows(&data.data, data.cols, 0, &source.input, "input")?;
            (est.estimate_rows(&data.data, args.threads)?, data.cols)
        }
    };
    if let Some(p) = args
        .out
        .as_ref()
        .filter(|p| v2ref::formats::oifits::is_fits_path(p))
    {
        let inputs = check_shape(&source, rows.len(), cols)?;
        super::oifits::write_estimates(
            p,
            &inputs,
            &rows,
            args.bins,
            args.bias,
            args.oifits_estimator,
        )?;
        return Ok(ExitCode::SUCCESS);
    }
    write(&args.out, &rows)?;
    Ok(ExitCode::SUCCESS)
}

/// The estimator of `rows` rows of `cols` samples under the flags.
fn estimator(args: &Args, source: &Source, rows: usize, cols: usize) -> Result<RowEstimator> {
    let inputs = check_shape(source, rows, cols)?;
    let cost = v2ref::commands::cost::estimate(&inputs, rows as u64, args.threads)?;
    super::output::announce("estimate", &cost);
    let model = Model::new(&inputs)?;
    let est = RowEstimator::new(&model, args.bins, args.bias, source.continuum_subtracted)?;
    match args.calibrator.as_str() {
        "model" => Ok(est),
        path => {
            let cal = calibration(args, &model, path, source.continuum_subtracted)?;
            est.with_calibration(cal)
        }
    }
}

fn source(args: &Args) -> Result<Source> {
    match &args.sidecar {
        Some(path) => {
            let sidecar = super::score::read_sidecar(path)?;
            let folder = path.parent().unwrap_or(Path::new("."));
            let (input, expected_rows) = match &args.input {
                Some(p) => (p.clone(), None),
                None => (folder.join(&sidecar.data.npy), Some(sidecar.data.rows)),
            };
            Ok(Source {
                inputs: sidecar.inputs,
                input,
                continuum_subtracted: sidecar.continuum_subtracted,
                expected_rows,
            })
        }
        None => {
            let input = args.input.clone().ok_or_else(|| Error::Invalid {
                param: "input",
                reason:
                    "give the interferograms (--input FILE) or a synth sidecar (--sidecar SET.json)"
                        .into(),
            })?;
            Ok(Source {
                inputs: args.inputs.inputs_unchecked()?,
                input,
                continuum_subtracted: !args.counts,
                expected_rows: None,
            })
        }
    }
}

/// The inputs with N from the file (without a sidecar) or checked against
/// it (with one).
fn check_shape(source: &Source, rows: usize, cols: usize) -> Result<Inputs> {
    if let Some(expected) = source.expected_rows {
        if rows as u64 != expected {
            return Err(Error::data(
                "input",
                &source.input,
                "",
                format!("{rows} rows; its sidecar says {expected}"),
            ));
        }
    }
    let mut inputs = source.inputs.clone();
    if inputs.samples != cols {
        if source.expected_rows.is_some() || source.inputs.piston.is_some() {
            return Err(Error::data(
                "input",
                &source.input,
                "",
                format!(
                    "{} columns; the configuration has {} samples per row",
                    cols, inputs.samples
                ),
            ));
        }
        inputs.samples = cols;
    }
    inputs.validate()?;
    Ok(inputs)
}

/// The calibration measured on a calibrator's file.
fn calibration(
    args: &Args,
    model: &Model,
    path: &str,
    continuum_subtracted: bool,
) -> Result<v2ref::formalism::estimator::Pair> {
    let path = Path::new(path);
    let data = read_matrix(path, "calibrator")?;
    if data.cols != model.samples() {
        return Err(Error::data(
            "calibrator",
            path,
            "",
            format!(
                "{} columns; the interferograms have {}",
                data.cols,
                model.samples()
            ),
        ));
    }
    refuse_dark_rows(&data.data, data.cols, 0, path, "calibrator")?;
    let cal_model = model.calibrator_model()?;
    let est = RowEstimator::new(&cal_model, args.bins, args.bias, continuum_subtracted)?;
    est.calibration_from_rows(&data.data, args.threads)
}

fn write(out: &Option<PathBuf>, rows: &[RowEstimate]) -> Result<()> {
    let flat: Vec<f64> = rows.iter().flat_map(RowEstimate::values).collect();
    match out {
        Some(p) if p.extension().is_some_and(|e| e == "npy") => {
            let mut w = NpyRowWriter::create(p, rows.len() as u64, COLUMNS.len(), "out")?;
            w.write_rows(&flat)?;
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
            w.write_rows(&flat)?;
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

/// Refuses a row of zeros in the file `path` (`first` rows before `rows`).
fn refuse_dark_rows(
    rows: &[f64],
    cols: usize,
    first: usize,
    path: &Path,
    param: &'static str,
) -> Result<()> {
    match v2ref::conformance::estimate::first_dark_row(rows, cols) {
        Some(r) => Err(Error::data(
            param,
            path,
            format!("row {} (1-based)", first + r + 1),
            v2ref::conformance::estimate::DARK_ROW,
        )),
        None => Ok(()),
    }
}
