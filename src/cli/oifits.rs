//! The command line's OIFITS edge: which format an `--out` path asks for,
//! the flags that choose estimators and tables, and the calls into
//! the crate `v2ref-oifits` (which builds and reads every file).

use std::path::Path;
use v2ref_core::conformance::estimate::{BiasConvention, RowEstimate};
use v2ref_core::conformance::score::Estimator;
use v2ref_core::conformance::sidecar::{ConventionTruth, Sidecar};
use v2ref_core::formalism::estimator::BinWindow;
use v2ref_core::simulator::{Inputs, Model};
use v2ref_core::{Error, Result};
use v2ref_files::formats::{read_estimates, Estimates};
use v2ref_oifits::{self as oifits, docs, Expected, ObservingContext, ObservingSpec};

/// Which estimators an OIFITS file holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Which {
    /// Both, as two INSNAMEs (V2REF_V1SQ, V2REF_V2SQ).
    Both,
    /// V1² only.
    #[value(name = "v1_sq")]
    V1Sq,
    /// V2² only.
    #[value(name = "v2_sq")]
    V2Sq,
}

impl Which {
    fn estimators(self) -> &'static [Estimator] {
        match self {
            Which::Both => &docs::BOTH,
            Which::V1Sq => &docs::BOTH[..1],
            Which::V2Sq => &docs::BOTH[1..],
        }
    }

    /// The one estimator named (None for `both`).
    pub fn single(self) -> Option<Estimator> {
        match self {
            Which::Both => None,
            Which::V1Sq => Some(Estimator::V1Sq),
            Which::V2Sq => Some(Estimator::V2Sq),
        }
    }
}

/// Refuses an `--out` of `estimate` whose extension is none of .csv,
/// .npy and the FITS ones: a file is never written in a format its name
/// does not say.
pub fn check_estimates_out(out: Option<&Path>) -> Result<()> {
    let Some(p) = out else { return Ok(()) };
    let ext = p
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("csv") | Some("npy") => Ok(()),
        _ if oifits::is_fits_path(p) => Ok(()),
        _ => Err(Error::Invalid {
            param: "out",
            reason: format!(
                "{}: the extension names the format written; .csv, .npy or .fits (OIFITS v2; also .oifits, .fit)",
                p.display()
            ),
        }),
    }
}

/// The heading of [`ObservingArgs`] in `--help`.
const HEADING: &str = "OIFITS: target, date, site";

/// Where and when an OIFITS file says the observation was made: flags of
/// the commands that write one (`estimate --out FILE.fits`,
/// `synth --oifits`, `plan --oifits`), refused without such a file.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct ObservingArgs {
    /// The target's name (TARGET, OBJECT): 1 to 16 printable ASCII
    /// characters [default: V2REF_MODEL].
    #[arg(long, help_heading = HEADING, value_name = "NAME")]
    target_name: Option<String>,
    /// The target's right ascension (J2000), degrees, 0 to 360 (with
    /// --dec-deg) [default: 0].
    #[arg(long, help_heading = HEADING, value_parser = super::finite_f64, allow_negative_numbers = true)]
    ra_deg: Option<f64>,
    /// The target's declination (J2000), degrees, -90 to 90 (with
    /// --ra-deg) [default: 0].
    #[arg(long, help_heading = HEADING, value_parser = super::finite_f64, allow_negative_numbers = true)]
    dec_deg: Option<f64>,
    /// When the first row starts (DATE-OBS, UTC): YYYY-MM-DD or
    /// YYYY-MM-DDThh:mm:ss[.s] (at most 9 digits after the point; a leap
    /// second 23:59:60 on June 30 or December 31), from 1858-11-17
    /// [default: 2000-01-01].
    #[arg(long, help_heading = HEADING, value_name = "DATE")]
    date: Option<String>,
    /// The array: iota, vlti or chara (their sites), or the name (1 to 16
    /// characters) of the site --site-lon-deg, --site-lat-deg and
    /// --site-height-m place [default: iota].
    #[arg(long, help_heading = HEADING, value_name = "NAME")]
    site: Option<String>,
    /// The site's east longitude, degrees, -180 to 180 (WGS84; with --site).
    #[arg(long, help_heading = HEADING, value_parser = super::finite_f64, allow_negative_numbers = true)]
    site_lon_deg: Option<f64>,
    /// The site's geodetic latitude, degrees, -90 to 90 (WGS84; with --site).
    #[arg(long, help_heading = HEADING, value_parser = super::finite_f64, allow_negative_numbers = true)]
    site_lat_deg: Option<f64>,
    /// The site's height above the WGS84 ellipsoid, m, -500 to 6000 (with
    /// --site).
    #[arg(long, help_heading = HEADING, value_parser = super::finite_f64, allow_negative_numbers = true)]
    site_height_m: Option<f64>,
}

impl ObservingArgs {
    /// What the flags say.
    pub fn spec(&self) -> ObservingSpec {
        ObservingSpec {
            target_name: self.target_name.clone(),
            ra_deg: self.ra_deg,
            dec_deg: self.dec_deg,
            date: self.date.clone(),
            site: self.site.clone(),
            site_lon_deg: self.site_lon_deg,
            site_lat_deg: self.site_lat_deg,
            site_height_m: self.site_height_m,
        }
    }

    /// The observation the flags describe, checked; when no OIFITS file is
    /// written (`writes` false) any of them is refused, `file_flag` saying
    /// what writes one.
    pub fn resolve(&self, writes: bool, file_flag: &str) -> Result<ObservingContext> {
        self.spec().resolve_for(writes, file_flag)
    }
}

/// Writes `estimate`'s rows as OIFITS v2, where and when `observing` says.
pub fn write_estimates(
    path: &Path,
    inputs: &Inputs,
    rows: &[RowEstimate],
    (bins, bias, which): (BinWindow, BiasConvention, Which),
    observing: &ObservingContext,
) -> Result<()> {
    let model = Model::new(inputs)?;
    let columns = docs::columns_of(rows, which.estimators());
    let doc = docs::estimates_doc(&model, &columns, (bins, bias), observing)?;
    oifits::write_oifits(path, "out", &doc)
}

/// What `score` scores: the estimates (flagged rows left out), the rows
/// scored, the truth for them, and the rows flagged (None: not OIFITS).
pub struct ScoreInput {
    /// The estimates.
    pub estimates: Estimates,
    /// Rows scored.
    pub rows: u64,
    /// The truth for those rows.
    pub truth: ConventionTruth,
    /// Rows flagged in the OIFITS file (None for .csv and .npy).
    pub flagged: Option<u64>,
}

/// The OIFITS flags of `score` (ignored for .csv and .npy, refused when
/// given for them).
#[derive(Debug, Clone, Default)]
pub struct OifitsFlags {
    /// `--insname`.
    pub insname: Option<String>,
    /// `--estimator`.
    pub estimator: Option<Which>,
    /// `--target`.
    pub target: Option<String>,
    /// `--accept-checksum-mismatch`.
    pub accept_checksum_mismatch: bool,
}

/// Reads `score`'s estimates: OIFITS by extension, else .csv or .npy.
pub fn read_for_score(
    path: &Path,
    columns: Option<&[String]>,
    sidecar: &Sidecar,
    (truth, bins, bias): (&ConventionTruth, BinWindow, BiasConvention),
    flags: &OifitsFlags,
) -> Result<ScoreInput> {
    let rows = sidecar.data.rows;
    if !oifits::is_fits_path(path) {
        for (flag, given) in [
            ("insname", flags.insname.is_some()),
            ("estimator", flags.estimator.is_some()),
            ("target", flags.target.is_some()),
            ("accept_checksum_mismatch", flags.accept_checksum_mismatch),
        ] {
            if given {
                return Err(Error::Invalid {
                    param: flag,
                    reason: "applies to an OIFITS --estimates file only".into(),
                });
            }
        }
        return Ok(ScoreInput {
            estimates: read_estimates(path, columns)?,
            rows,
            truth: truth.clone(),
            flagged: None,
        });
    }
    if columns.is_some() {
        // An OIFITS file names its estimator per table (V2R_EST or --estimator).
        return Err(Error::Invalid {
            param: "columns",
            reason: "applies to a .npy --estimates file only; an OIFITS file's tables are chosen with --insname and --estimator".into(),
        });
    }
    let (lo, hi) = sidecar.inputs.spectrum.spectrum()?.support();
    let expected = Expected {
        rows,
        band_m: (1e-6 / hi, 1e-6 / lo),
        channels_m: None,
        bins,
        bias,
    };
    let choice = oifits::Choice {
        insname: flags.insname.as_deref(),
        estimator: flags.estimator.and_then(Which::single),
        target: flags.target.as_deref(),
        read: oifits::ReadOptions {
            accept_checksum_mismatch: flags.accept_checksum_mismatch,
        },
    };
    let read = oifits::read_oifits_estimates(path, &choice, &expected)?;
    for note in &read.notes {
        eprintln!("note: --estimates {}: {note}", path.display());
    }
    let kept = (read.rows - read.flagged) as u64;
    Ok(ScoreInput {
        estimates: read.estimates,
        rows: kept,
        truth: oifits::truth_for_kept_rows(truth, rows, kept),
        flagged: Some(read.flagged as u64),
    })
}

/// Writes a synth set's truth (window `positive`, convention `model`),
/// where and when `observing` says.
pub fn write_truth(path: &Path, sidecar: &Sidecar, observing: &ObservingContext) -> Result<()> {
    let window = (BinWindow::Positive, BiasConvention::Model);
    let doc = docs::truth_doc(sidecar, window, observing)?;
    oifits::write_oifits(path, "oifits", &doc)
}
