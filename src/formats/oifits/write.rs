//! Writing OIFITS v2: the primary header and the tables `OI_TARGET`,
//! `OI_ARRAY`, then per `INSNAME` an `OI_WAVELENGTH` and an `OI_VIS2`
//! (mandatory columns, units and keywords of Duvert et al. 2017, tables
//! 5–11), built in memory by cfitsio and written atomically.

use super::mem::MemFits;
use super::setting::Setting;
use super::{check_fits_extension, estimator_key, KEY_ESTIMATOR};
use crate::conformance::score::Estimator;
use crate::formats::atomic::TempTarget;
use crate::{Error, Result};
use fitsio::hdu::FitsHdu;
use fitsio::tables::{ColumnDataType, ColumnDescription};
use fitsio::FitsFile;
use std::io::Write;
use std::path::Path;

/// Keyword of the primary header giving the number of HDUs written: a
/// file cut after a whole HDU is then refused, not read short.
pub const KEY_NHDU: &str = "V2R_NHDU";

/// A header keyword's value.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum KeyValue {
    /// A character string (at most 68 characters).
    Str(String),
    /// A real number.
    F64(f64),
    /// An integer.
    Int(i64),
}

/// A header keyword: name (≤ 8 characters), value, comment.
#[derive(Debug, Clone, PartialEq)]
pub struct Key {
    /// Name.
    pub name: String,
    /// Value.
    pub value: KeyValue,
    /// Comment.
    pub comment: String,
}

impl Key {
    /// A string keyword.
    pub fn str(name: &str, value: &str, comment: &str) -> Key {
        Key {
            name: name.into(),
            value: KeyValue::Str(value.into()),
            comment: comment.into(),
        }
    }

    /// A real keyword.
    pub fn f64(name: &str, value: f64, comment: &str) -> Key {
        Key {
            name: name.into(),
            value: KeyValue::F64(value),
            comment: comment.into(),
        }
    }
}

/// One `OI_VIS2` table (with its `OI_WAVELENGTH`): one broadband channel,
/// one row per interferogram.
#[derive(Debug, Clone, PartialEq)]
pub struct Vis2Out {
    /// `INSNAME` (distinct per table).
    pub insname: String,
    /// The estimator (keyword `V2R_EST`); None for a model's V².
    pub estimator: Option<Estimator>,
    /// `VIS2DATA`, one per row.
    pub vis2data: Vec<f64>,
    /// `VIS2ERR`, one per row (its meaning stated in `keywords`).
    pub vis2err: Vec<f64>,
    /// `FLAG`, one per row (true: bad).
    pub flag: Vec<bool>,
    /// More keywords of the `OI_VIS2` header.
    pub keywords: Vec<Key>,
    /// The comment of the `VIS2DATA` column's `TTYPE` card.
    pub vis2data_note: Option<String>,
}

/// A whole OIFITS file.
#[derive(Debug, Clone, PartialEq)]
pub struct OifitsDoc {
    /// The observation.
    pub setting: Setting,
    /// `OI_VIS2` tables (at least one).
    pub tables: Vec<Vis2Out>,
    /// More keywords of the primary header.
    pub keywords: Vec<Key>,
}

/// Writes `doc` to `path` (named by `param`) as OIFITS v2: refused unless
/// the extension is a FITS one, written atomically.
pub fn write_oifits(path: &Path, param: &'static str, doc: &OifitsDoc) -> Result<()> {
    check_fits_extension(path, param)?;
    check_doc(doc, param)?;
    let output_error = |reason: String| Error::Output {
        path: path.display().to_string(),
        reason,
    };
    let mut bytes = to_bytes(doc).map_err(output_error)?;
    if super::is_gzip_path(path) {
        bytes = gzip(&bytes).map_err(|e| output_error(format!("gzip: {e}")))?;
    }
    let (temp, mut file) = TempTarget::create(path, Some(param))?;
    file.write_all(&bytes)
        .and_then(|_| file.sync_all())
        .map_err(|e| temp.io(e))?;
    drop(file);
    temp.persist()
}

/// Tables present, each with one value per row in every column; a date
/// the rows' MJD can be counted from.
fn check_doc(doc: &OifitsDoc, param: &'static str) -> Result<()> {
    if super::observing::mjd_of_date(&doc.setting.date_obs).is_none() {
        return Err(Error::Invalid {
            param: "date",
            reason: format!(
                "{:?}: not a UTC date YYYY-MM-DD[Thh:mm:ss[.s]] from 1858-11-17",
                doc.setting.date_obs
            ),
        });
    }
    if doc.tables.is_empty() {
        return Err(Error::Invalid {
            param,
            reason: "no OI_VIS2 table to write".into(),
        });
    }
    for t in &doc.tables {
        let n = t.vis2data.len();
        if n == 0 || t.vis2err.len() != n || t.flag.len() != n {
            return Err(Error::Invalid {
                param,
                reason: format!(
                    "{}: {n} VIS2DATA, {} VIS2ERR, {} FLAG; one of each per row (at least one row)",
                    t.insname,
                    t.vis2err.len(),
                    t.flag.len()
                ),
            });
        }
    }
    Ok(())
}

fn gzip(bytes: &[u8]) -> std::io::Result<Vec<u8>> {
    let mut z = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
    z.write_all(bytes)?;
    z.finish()
}

/// The file's bytes: every HDU with its `CHECKSUM` and `DATASUM`; a row
/// whose `VIS2DATA` or `VIS2ERR` is not a number is flagged.
pub fn to_bytes(doc: &OifitsDoc) -> std::result::Result<Vec<u8>, String> {
    let mut mem = MemFits::create()?;
    let f = &mut mem.file;
    primary(f, doc)?;
    target(f, &doc.setting)?;
    array(f, &doc.setting)?;
    for (i, t) in doc.tables.iter().enumerate() {
        let extver = i as i64 + 1;
        wavelength(f, &doc.setting, &t.insname, extver)?;
        let mut t = t.clone();
        for (r, flag) in t.flag.iter_mut().enumerate() {
            *flag |= !(t.vis2data[r].is_finite() && t.vis2err[r].is_finite());
        }
        vis2(f, &doc.setting, &t, extver)?;
    }
    mem.into_bytes()
}

fn e(what: &str) -> impl Fn(fitsio::errors::Error) -> String + '_ {
    move |err| format!("{what}: {err}")
}

fn put_keys(f: &mut FitsFile, hdu: &FitsHdu, keys: &[Key]) -> std::result::Result<(), String> {
    for k in keys {
        let r = match &k.value {
            KeyValue::Str(s) => hdu.write_key(f, &k.name, (s.as_str(), k.comment.as_str())),
            KeyValue::F64(v) => hdu.write_key(f, &k.name, (*v, k.comment.as_str())),
            KeyValue::Int(v) => hdu.write_key(f, &k.name, (*v, k.comment.as_str())),
        };
        r.map_err(|err| format!("keyword {}: {err}", k.name))?;
    }
    Ok(())
}

fn primary(f: &mut FitsFile, doc: &OifitsDoc) -> std::result::Result<(), String> {
    let hdu = f.primary_hdu().map_err(e("primary HDU"))?;
    let s = &doc.setting;
    let soft = format!("v2ref {}", env!("CARGO_PKG_VERSION"));
    let mut keys = vec![
        Key::str(
            "CONTENT",
            "OIFITS2",
            "OIFITS version 2 (Duvert et al. 2017)",
        ),
        Key::str(
            "ORIGIN",
            "v2ref",
            "institution or software that wrote the file",
        ),
        Key::str("DATE", &today(), "UTC date the file was written"),
        Key::str("DATE-OBS", &s.date_obs, "UTC date of the first row"),
        Key::str("TELESCOP", &s.site.name, "array (two stations)"),
        Key::str("INSTRUME", &doc.tables[0].insname, "first INSNAME"),
        Key::str("OBSERVER", "v2ref", "no observer: computed"),
        Key::str("OBJECT", &s.target, "target"),
        Key::str(
            "INSMODE",
            "BROADBAND",
            "one channel: the estimators sum the band",
        ),
        Key::str(
            "OBSTECH",
            "SCAN",
            "scanned fringes, Fourier-domain estimators",
        ),
        Key::str("PROCSOFT", &soft, "software that wrote the file"),
        Key::str("PROG_ID", "N/A", "no observing programme"),
        Key::str(
            "REFERENC",
            "Perrin & Ridgway 2005",
            "estimators V1^2 and V2^2",
        ),
    ];
    keys.push(Key {
        name: KEY_NHDU.into(),
        value: KeyValue::Int(3 + 2 * doc.tables.len() as i64),
        comment: "HDUs in this file, the primary included".into(),
    });
    keys.extend(doc.keywords.iter().cloned());
    put_keys(f, &hdu, &keys)
}

/// A binary-table column: name, TFORM type and repeat, unit.
struct Col {
    name: &'static str,
    typ: ColumnDataType,
    repeat: usize,
    unit: &'static str,
}

const fn col(name: &'static str, typ: ColumnDataType, repeat: usize, unit: &'static str) -> Col {
    Col {
        name,
        typ,
        repeat,
        unit,
    }
}

/// Creates the table `extname` with `cols` (units as `TUNITn`) and
/// `keys`, and makes it current.
fn create(
    f: &mut FitsFile,
    extname: &str,
    cols: &[Col],
    keys: &[Key],
) -> std::result::Result<FitsHdu, String> {
    let descs = cols
        .iter()
        .map(|c| {
            ColumnDescription::new(c.name)
                .with_type(c.typ)
                .that_repeats(c.repeat)
                .create()
        })
        .collect::<fitsio::errors::Result<Vec<_>>>()
        .map_err(e(extname))?;
    let hdu = f.create_table(extname, &descs).map_err(e(extname))?;
    let mut all = vec![Key {
        name: "OI_REVN".into(),
        value: KeyValue::Int(2),
        comment: "revision of the OIFITS table definition".into(),
    }];
    for (i, c) in cols.iter().enumerate().filter(|(_, c)| !c.unit.is_empty()) {
        all.push(Key::str(&format!("TUNIT{}", i + 1), c.unit, ""));
    }
    all.extend(keys.iter().cloned());
    put_keys(f, &hdu, &all)?;
    Ok(hdu)
}

fn write_f64(
    f: &mut FitsFile,
    hdu: &FitsHdu,
    name: &str,
    v: &[f64],
) -> std::result::Result<(), String> {
    hdu.write_col(f, name, v).map(|_| ()).map_err(e(name))
}

fn write_i16(
    f: &mut FitsFile,
    hdu: &FitsHdu,
    name: &str,
    v: &[i16],
) -> std::result::Result<(), String> {
    hdu.write_col(f, name, v).map(|_| ()).map_err(e(name))
}

fn write_str(
    f: &mut FitsFile,
    hdu: &FitsHdu,
    name: &str,
    v: &[&str],
) -> std::result::Result<(), String> {
    let owned: Vec<String> = v.iter().map(|s| s.to_string()).collect();
    hdu.write_col(f, name, &owned).map(|_| ()).map_err(e(name))
}

fn write_f32(
    f: &mut FitsFile,
    hdu: &FitsHdu,
    name: &str,
    v: &[f32],
) -> std::result::Result<(), String> {
    hdu.write_col(f, name, v).map(|_| ()).map_err(e(name))
}

/// `FLAG` (logical, column `colno` from 1 of the table just written):
/// `fitsio` writes no logical column.
fn write_flag(f: &mut FitsFile, colno: i32, v: &[bool]) -> std::result::Result<(), String> {
    let mut bytes: Vec<std::os::raw::c_char> = v.iter().map(|&b| b as _).collect();
    let mut status = 0;
    // SAFETY: the file is open at this table; `bytes` holds `v.len()` values.
    unsafe {
        fitsio_sys::ffpcll(
            f.as_raw(),
            colno,
            1,
            1,
            v.len() as i64,
            bytes.as_mut_ptr(),
            &mut status,
        );
    }
    match status {
        0 => Ok(()),
        s => Err(format!("FLAG: {}", super::status_text(s))),
    }
}

fn target(f: &mut FitsFile, s: &Setting) -> std::result::Result<(), String> {
    use ColumnDataType::{Double, Float, Short, String as A};
    let cols = [
        col("TARGET_ID", Short, 1, ""),
        col("TARGET", A, 16, ""),
        col("RAEP0", Double, 1, "deg"),
        col("DECEP0", Double, 1, "deg"),
        col("EQUINOX", Float, 1, "yr"),
        col("RA_ERR", Double, 1, "deg"),
        col("DEC_ERR", Double, 1, "deg"),
        col("SYSVEL", Double, 1, "m/s"),
        col("VELTYP", A, 8, ""),
        col("VELDEF", A, 8, ""),
        col("PMRA", Double, 1, "deg/yr"),
        col("PMDEC", Double, 1, "deg/yr"),
        col("PMRA_ERR", Double, 1, "deg/yr"),
        col("PMDEC_ERR", Double, 1, "deg/yr"),
        col("PARALLAX", Float, 1, "deg"),
        col("PARA_ERR", Float, 1, "deg"),
        col("SPECTYP", A, 16, ""),
    ];
    let h = create(f, "OI_TARGET", &cols, &[])?;
    write_i16(f, &h, "TARGET_ID", &[1])?;
    write_str(f, &h, "TARGET", &[&s.target])?;
    write_f64(f, &h, "RAEP0", &[s.target_radec_deg.0])?;
    write_f64(f, &h, "DECEP0", &[s.target_radec_deg.1])?;
    for name in [
        "RA_ERR",
        "DEC_ERR",
        "SYSVEL",
        "PMRA",
        "PMDEC",
        "PMRA_ERR",
        "PMDEC_ERR",
    ] {
        write_f64(f, &h, name, &[0.0])?;
    }
    write_f32(f, &h, "EQUINOX", &[2000.0])?;
    write_f32(f, &h, "PARALLAX", &[0.0])?;
    write_f32(f, &h, "PARA_ERR", &[0.0])?;
    write_str(f, &h, "VELTYP", &["UNKNOWN"])?;
    write_str(f, &h, "VELDEF", &["OPTICAL"])?;
    write_str(f, &h, "SPECTYP", &["UNKNOWN"])
}

fn array(f: &mut FitsFile, s: &Setting) -> std::result::Result<(), String> {
    use ColumnDataType::{Double, Float, Short, String as A};
    let cols = [
        col("TEL_NAME", A, 16, ""),
        col("STA_NAME", A, 16, ""),
        col("STA_INDEX", Short, 1, ""),
        col("DIAMETER", Float, 1, "m"),
        col("STAXYZ", Double, 3, "m"),
        col("FOV", Double, 1, "arcsec"),
        col("FOVTYPE", A, 6, ""),
    ];
    let centre = s.site.geocentric_m();
    let keys = [
        Key::str("ARRNAME", &s.site.name, "array"),
        Key::str("FRAME", "GEOCENTRIC", "coordinate frame of STAXYZ"),
        Key::f64("ARRAYX", centre[0], "[m] array centre, geocentric X"),
        Key::f64("ARRAYY", centre[1], "[m] array centre, geocentric Y"),
        Key::f64("ARRAYZ", centre[2], "[m] array centre, geocentric Z"),
    ];
    let h = create(f, "OI_ARRAY", &cols, &keys)?;
    // The two stations half a baseline either side of the centre, east–west.
    let east = s.site.east();
    let station = |sign: f64| east.map(|e| sign * 0.5 * s.baseline_m * e);
    let staxyz: Vec<f64> = [station(-1.0), station(1.0)].concat();
    // Field of view: the telescopes' diffraction FWHM, λ/D.
    let fov_arcsec = if s.diameter_m > 0.0 {
        (s.eff_wave_m / s.diameter_m).to_degrees() * 3600.0
    } else {
        0.0
    };
    write_str(f, &h, "TEL_NAME", &["T1", "T2"])?;
    write_str(f, &h, "STA_NAME", &["S1", "S2"])?;
    write_i16(f, &h, "STA_INDEX", &[1, 2])?;
    write_f32(f, &h, "DIAMETER", &[s.diameter_m as f32; 2])?;
    write_f64(f, &h, "STAXYZ", &staxyz)?;
    write_f64(f, &h, "FOV", &[fov_arcsec; 2])?;
    write_str(f, &h, "FOVTYPE", &["FWHM", "FWHM"])
}

fn wavelength(
    f: &mut FitsFile,
    s: &Setting,
    insname: &str,
    extver: i64,
) -> std::result::Result<(), String> {
    let cols = [
        col("EFF_WAVE", ColumnDataType::Float, 1, "m"),
        col("EFF_BAND", ColumnDataType::Float, 1, "m"),
    ];
    let keys = [
        Key::str("INSNAME", insname, "instrument (estimator)"),
        extver_key(extver),
    ];
    let h = create(f, "OI_WAVELENGTH", &cols, &keys)?;
    write_f32(f, &h, "EFF_WAVE", &[s.eff_wave_m as f32])?;
    write_f32(f, &h, "EFF_BAND", &[s.eff_band_m as f32])
}

/// `EXTVER`: tables of the same `EXTNAME` are told apart by it.
fn extver_key(extver: i64) -> Key {
    Key {
        name: "EXTVER".into(),
        value: KeyValue::Int(extver),
        comment: "version of this EXTNAME".into(),
    }
}

fn vis2(
    f: &mut FitsFile,
    s: &Setting,
    t: &Vis2Out,
    extver: i64,
) -> std::result::Result<(), String> {
    use ColumnDataType::{Double, Logical, Short};
    let cols = [
        col("TARGET_ID", Short, 1, ""),
        col("TIME", Double, 1, "s"),
        col("MJD", Double, 1, "day"),
        col("INT_TIME", Double, 1, "s"),
        col("VIS2DATA", Double, 1, ""),
        col("VIS2ERR", Double, 1, ""),
        col("UCOORD", Double, 1, "m"),
        col("VCOORD", Double, 1, "m"),
        col("STA_INDEX", Short, 2, ""),
        col("FLAG", Logical, 1, ""),
    ];
    let mut keys = vec![
        extver_key(extver),
        Key::str("DATE-OBS", &s.date_obs, "UTC date of the first row"),
        Key::str("ARRNAME", &s.site.name, ""),
        Key::str("INSNAME", &t.insname, ""),
        // One channel: the arrays are declared of one element, as
        // OIFITS readers that shape columns by TDIM expect.
        Key::str("TDIM5", "(1)", ""),
        Key::str("TDIM6", "(1)", ""),
        Key::str("TDIM10", "(1)", ""),
    ];
    if let Some(est) = t.estimator {
        keys.push(Key::str(
            KEY_ESTIMATOR,
            estimator_key(est),
            "v2ref estimator",
        ));
    }
    keys.extend(t.keywords.iter().cloned());
    let h = create(f, "OI_VIS2", &cols, &keys)?;
    let n = t.vis2data.len();
    // OIFITS v2 keeps TIME at zero: the time is MJD.
    let mjd: Vec<f64> = (0..n).map(|r| s.mjd(r)).collect();
    write_i16(f, &h, "TARGET_ID", &vec![1; n])?;
    write_f64(f, &h, "TIME", &vec![0.0; n])?;
    write_f64(f, &h, "MJD", &mjd)?;
    write_f64(f, &h, "INT_TIME", &vec![s.row_s(); n])?;
    write_f64(f, &h, "VIS2DATA", &t.vis2data)?;
    write_f64(f, &h, "VIS2ERR", &t.vis2err)?;
    write_f64(f, &h, "UCOORD", &vec![s.baseline_m; n])?;
    write_f64(f, &h, "VCOORD", &vec![0.0; n])?;
    write_i16(f, &h, "STA_INDEX", &[1, 2].repeat(n))?;
    write_flag(f, 10, &t.flag)?;
    if let Some(note) = &t.vis2data_note {
        note_column(f, 5, note)?;
    }
    Ok(())
}

/// Sets the comment of the `TTYPEn` card of column `n` (1-based).
fn note_column(f: &mut FitsFile, n: usize, note: &str) -> std::result::Result<(), String> {
    let key = std::ffi::CString::new(format!("TTYPE{n}")).map_err(|e| e.to_string())?;
    let mut text: String = note
        .chars()
        .filter(|c| c.is_ascii() && !c.is_control())
        .collect();
    // The card `TTYPEn  = 'VIS2DATA'           / ` leaves 47 characters:
    // a longer note is cut at a word, never inside one.
    const ROOM: usize = 47;
    if text.len() > ROOM {
        let cut = text[..ROOM].rfind(' ').unwrap_or(ROOM);
        text.truncate(cut);
    }
    let com = std::ffi::CString::new(text).map_err(|e| e.to_string())?;
    let mut status = 0;
    // SAFETY: the file is open at the table; both strings are NUL-terminated.
    unsafe { fitsio_sys::ffmcom(f.as_raw(), key.as_ptr(), com.as_ptr(), &mut status) };
    match status {
        0 => Ok(()),
        s => Err(format!("TTYPE{n}: {}", super::status_text(s))),
    }
}

/// Today's UTC date, `YYYY-MM-DD` (civil from days since 1970, Hinnant).
fn today() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0);
    let z = (secs / 86_400) as i64 + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!("{y:04}-{m:02}-{d:02}")
}
