//! Reading `OI_VIS2` tables from OIFITS v1 or v2, and a pipeline's
//! estimates from them, matched to a set's rows in order.
//!
//! The file is read whole (at most [`MAX_OIFITS_BYTES`], after gunzip for
//! `.fits.gz`) and parsed in safe Rust ([`super::fits`], [`super::table`]):
//! every size a header announces is checked against the bytes of the file
//! before a value is read, so a damaged header is refused, never followed.
//! `CHECKSUM`/`DATASUM` are verified where present ([`super::integrity`]).
//! Every refusal is an [`Error::Data`] naming the parameter, the HDU (its
//! number, `EXTNAME` and `INSNAME`) and what is accepted.

use super::fits::{self, Hdu, Refusal};
use super::integrity::ReadOptions;
use super::table::Table;
use crate::{Error, Result};
use std::path::Path;

/// Largest OIFITS file read, bytes (1 GiB: 40 million rows of V²); for a
/// `.fits.gz`, the size once decompressed.
pub const MAX_OIFITS_BYTES: u64 = 1 << 30;

/// One `OI_VIS2` table, with the wavelengths of its `INSNAME`.
#[derive(Debug, Clone, PartialEq)]
pub struct Vis2Table {
    /// Its HDU number (1-based, the primary is 1).
    pub hdu: usize,
    /// `INSNAME` (trailing blanks removed).
    pub insname: String,
    /// `OI_REVN` (1 or 2).
    pub revn: i64,
    /// `V2R_EST` where present (`V1SQ`, `V2SQ`).
    pub estimator: Option<String>,
    /// `V2R_BINS` where present: the window of bins the values sum.
    pub bins: Option<String>,
    /// `V2R_BIAS` where present: the bias convention they subtract.
    pub bias: Option<String>,
    /// Rows.
    pub rows: usize,
    /// Channels per row (`NWAVE`).
    pub nwave: usize,
    /// `EFF_WAVE` of the `OI_WAVELENGTH` of the same `INSNAME`, m, one
    /// per channel.
    pub eff_wave_m: Vec<f64>,
    /// `EFF_BAND` of that `OI_WAVELENGTH`, m, one per channel (NaN where
    /// it has no such column).
    pub eff_band_m: Vec<f64>,
    /// `TARGET_ID` of each row (1 where the table has no such column).
    pub target_id: Vec<i64>,
    /// `MJD` of each row, days (0 where the table has no such column).
    pub mjd: Vec<f64>,
    /// `UCOORD` of each row, m (NaN where the table has no such column).
    pub ucoord_m: Vec<f64>,
    /// `VCOORD` of each row, m (NaN where the table has no such column).
    pub vcoord_m: Vec<f64>,
    /// `VIS2DATA`, `rows × nwave`, row after row.
    pub vis2data: Vec<f64>,
    /// `VIS2ERR`, same shape.
    pub vis2err: Vec<f64>,
    /// `FLAG`, same shape (true: bad).
    pub flag: Vec<bool>,
}

/// What an OIFITS file holds for scoring: its `OI_VIS2` tables and its
/// targets.
#[derive(Debug, Clone, PartialEq)]
pub struct OifitsFile {
    /// `OI_VIS2` tables, in file order.
    pub tables: Vec<Vis2Table>,
    /// `OI_TARGET`'s (`TARGET_ID`, `TARGET`) pairs, in order (empty when
    /// the file has no `OI_TARGET`).
    pub targets: Vec<(i64, String)>,
    /// What was accepted that a reader should know, one line each: HDUs
    /// without checksums in a signed file, a v2ref file edited after it
    /// was written.
    pub notes: Vec<String>,
}

/// Reads every `OI_VIS2` table of `path` (named by `param`), in file
/// order, each with the `EFF_WAVE` of its `INSNAME`; checksums verified.
pub fn read_vis2_tables(path: &Path, param: &'static str) -> Result<Vec<Vis2Table>> {
    Ok(read_oifits_file(path, param, ReadOptions::default())?.tables)
}

/// Reads the `OI_VIS2` tables and the targets of `path` (named by
/// `param`).
pub fn read_oifits_file(
    path: &Path,
    param: &'static str,
    options: ReadOptions,
) -> Result<OifitsFile> {
    let bytes = read_bounded(path, param)?;
    parse_oifits(&bytes, options).map_err(|r| Error::data(param, path, r.location, r.reason))
}

/// [`read_oifits_file`] on a file's bytes.
pub fn parse_oifits(
    bytes: &[u8],
    options: ReadOptions,
) -> std::result::Result<OifitsFile, Refusal> {
    let hdus = fits::parse(bytes)?;
    let notes = super::integrity::check(&hdus, options)?;
    let mut waves: Vec<Wavelengths> = Vec::new();
    let mut tables = Vec::new();
    let mut targets = Vec::new();
    for hdu in hdus.iter().skip(1) {
        match hdu.header.str("EXTNAME") {
            Some("OI_WAVELENGTH") => waves.push(wavelength_table(hdu)?),
            Some("OI_VIS2") => tables.push(vis2_table(hdu)?),
            Some("OI_TARGET") => targets.extend(target_table(hdu)?),
            _ => {}
        }
    }
    for t in &mut tables {
        let at = t.at();
        let Some(w) = waves.iter().find(|w| w.insname == t.insname) else {
            return Err(fits::refuse(
                at,
                "no OI_WAVELENGTH table of this INSNAME; the standard requires one",
            ));
        };
        if w.eff_wave_m.len() != t.nwave {
            return Err(fits::refuse(
                at,
                format!(
                    "{} channels, its OI_WAVELENGTH has {}",
                    t.nwave,
                    w.eff_wave_m.len()
                ),
            ));
        }
        t.eff_wave_m.clone_from(&w.eff_wave_m);
        t.eff_band_m.clone_from(&w.eff_band_m);
    }
    if !targets.is_empty() {
        check_targets_listed(&tables, &targets)?;
    }
    Ok(OifitsFile {
        tables,
        targets,
        notes,
    })
}

/// Refuses a row whose `TARGET_ID` is not in `OI_TARGET`: the row is of
/// no known target, and choosing a target by name could not see it.
fn check_targets_listed(
    tables: &[Vis2Table],
    targets: &[(i64, String)],
) -> std::result::Result<(), Refusal> {
    for t in tables {
        let unlisted = t
            .target_id
            .iter()
            .position(|id| !targets.iter().any(|(i, _)| i == id));
        if let Some(r) = unlisted {
            let ids: Vec<String> = targets.iter().map(|(i, _)| i.to_string()).collect();
            return Err(fits::refuse(
                format!("{}, row {}", t.at(), r + 1),
                format!(
                    "TARGET_ID {} is not in OI_TARGET (its TARGET_IDs: {}): a row of no listed target",
                    t.target_id[r],
                    ids.join(", ")
                ),
            ));
        }
    }
    Ok(())
}

/// The file's bytes, gunzipped when they start with gzip's magic number;
/// at most [`MAX_OIFITS_BYTES`] either way, and no more than the memory
/// budget ([`crate::formats::memory_budget`]): a plain file is refused from
/// its size before it is read, a `.fits.gz` as soon as its inflation
/// passes the budget (a 1 MB file of zeros inflates to 1 GiB).
fn read_bounded(path: &Path, param: &'static str) -> Result<Vec<u8>> {
    use std::io::Read;
    let budget = crate::formats::memory_budget()?;
    let limit = MAX_OIFITS_BYTES.min(budget);
    crate::formats::csv::check_regular(path, param)?;
    let file = crate::formats::open(path, param)?;
    let size = file.metadata().map(|m| m.len()).unwrap_or(0);
    if size > limit {
        return Err(too_large(path, param, size, budget, ""));
    }
    let mut bytes = Vec::new();
    file.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| Error::file(Some(param), path, e))?;
    if bytes.len() as u64 > limit {
        return Err(too_large(
            path,
            param,
            bytes.len() as u64,
            budget,
            "more than ",
        ));
    }
    if bytes.starts_with(&[0x1f, 0x8b]) {
        // The compressed bytes are held while inflating: both count.
        let room = limit - bytes.len() as u64;
        let mut plain = Vec::new();
        flate2::read::MultiGzDecoder::new(&bytes[..])
            .take(room + 1)
            .read_to_end(&mut plain)
            .map_err(|e| {
                Error::data(
                    param,
                    path,
                    "",
                    format!("a gzip file that does not decompress ({e}): truncated or damaged"),
                )
            })?;
        let held = (bytes.len() + plain.len()) as u64;
        if held > limit {
            return Err(too_large(path, param, held, budget, "more than "));
        }
        bytes = plain;
    }
    Ok(bytes)
}

/// The refusal of a file that takes `need` bytes to hold (`more`: "more
/// than " where reading stopped), over [`MAX_OIFITS_BYTES`] or `budget`.
fn too_large(path: &Path, param: &'static str, need: u64, budget: u64, more: &str) -> Error {
    if budget < MAX_OIFITS_BYTES {
        return crate::formats::budget::over_budget(need, budget, param, path, "", more);
    }
    Error::data(
        param,
        path,
        "",
        format!("{more}{need} bytes, larger than {MAX_OIFITS_BYTES} bytes"),
    )
}

fn insname(hdu: &Hdu) -> std::result::Result<String, Refusal> {
    hdu.header
        .str("INSNAME")
        .filter(|s| !s.is_empty())
        .map(str::to_owned)
        .ok_or_else(|| fits::refuse(hdu.at(), "no INSNAME keyword; the standard requires one"))
}

/// One `OI_WAVELENGTH` table: its `INSNAME` and channels.
struct Wavelengths {
    insname: String,
    eff_wave_m: Vec<f64>,
    eff_band_m: Vec<f64>,
}

fn wavelength_table(hdu: &Hdu) -> std::result::Result<Wavelengths, Refusal> {
    let insname = insname(hdu)?;
    let t = Table::new(hdu)?;
    let eff_wave_m = t.reals(t.column("EFF_WAVE")?)?;
    // EFF_BAND is mandatory, but a pipeline's own file may lack it, and
    // scoring does not need it: NaN then, never a made-up width.
    let eff_band_m = match t.column("EFF_BAND") {
        Ok(c) => t.reals(c)?,
        Err(_) => vec![f64::NAN; eff_wave_m.len()],
    };
    Ok(Wavelengths {
        insname,
        eff_wave_m,
        eff_band_m,
    })
}

fn target_table(hdu: &Hdu) -> std::result::Result<Vec<(i64, String)>, Refusal> {
    let t = Table::new(hdu)?;
    let ids = t.reals(t.column("TARGET_ID")?)?;
    let names = t.strings(t.column("TARGET")?)?;
    Ok(ids.into_iter().map(|i| i as i64).zip(names).collect())
}

fn vis2_table(hdu: &Hdu) -> std::result::Result<Vis2Table, Refusal> {
    let at = hdu.at();
    let insname = insname(hdu)?;
    let revn = hdu.header.int("OI_REVN").unwrap_or(0);
    if !(1..=2).contains(&revn) {
        return Err(fits::refuse(
            &at,
            format!("OI_REVN {revn}; OIFITS 1 or 2 is read"),
        ));
    }
    let t = Table::new(hdu)?;
    let (data, err, flag) = (
        t.column("VIS2DATA")?,
        t.column("VIS2ERR")?,
        t.column("FLAG")?,
    );
    let nwave = data.repeat;
    if nwave == 0 || err.repeat != nwave || flag.repeat != nwave {
        return Err(fits::refuse(
            &at,
            format!(
                "VIS2DATA, VIS2ERR, FLAG hold {nwave}, {}, {} values per row; the same NWAVE > 0 is needed",
                err.repeat, flag.repeat
            ),
        ));
    }
    // TARGET_ID, MJD, UCOORD and VCOORD are mandatory, but a pipeline's
    // own file may lack them: then its rows are of one target, in the
    // order written, on a baseline not said (NaN, never a made-up 0).
    let one_per_row = |name: &str, absent: f64| -> std::result::Result<Vec<f64>, Refusal> {
        let Ok(c) = t.column(name) else {
            return Ok(vec![absent; t.rows]);
        };
        if c.repeat != 1 {
            return Err(fits::refuse(
                format!("{at}, column {name}"),
                format!("{} values per row; one is needed", c.repeat),
            ));
        }
        t.reals(c)
    };
    let key = |k: &str| hdu.header.str(k).map(str::to_owned);
    Ok(Vis2Table {
        hdu: hdu.number,
        estimator: key(super::KEY_ESTIMATOR),
        bins: key(super::KEY_BINS),
        bias: key(super::KEY_BIAS),
        insname,
        revn,
        rows: t.rows,
        nwave,
        eff_wave_m: Vec::new(),
        eff_band_m: Vec::new(),
        target_id: one_per_row("TARGET_ID", 1.0)?
            .into_iter()
            .map(|i| i as i64)
            .collect(),
        mjd: one_per_row("MJD", 0.0)?,
        ucoord_m: one_per_row("UCOORD", f64::NAN)?,
        vcoord_m: one_per_row("VCOORD", f64::NAN)?,
        vis2data: t.reals(data)?,
        vis2err: t.reals(err)?,
        flag: t.logicals(flag)?,
    })
}

impl Vis2Table {
    /// `HDU n (EXTNAME OI_VIS2, INSNAME X)`: where the table is.
    pub fn at(&self) -> String {
        fits::place(self.hdu, Some("OI_VIS2"), Some(&self.insname))
    }
}
