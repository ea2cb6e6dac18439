//! Writing OIFITS v2: the primary header and the tables `OI_TARGET`,
//! `OI_ARRAY`, then per `INSNAME` an `OI_WAVELENGTH` and an `OI_VIS2`
//! (mandatory columns, units and keywords of Duvert et al. 2017, tables
//! 5–11), built in memory by the safe writer [`super::fits_write`] and
//! written atomically.

use super::fits_write::{CardValue, Column, ColumnData, HduWriter};
use super::setting::Setting;
use super::{check_fits_extension, estimator_key, KEY_ESTIMATOR};
use crate::conformance::score::Estimator;
use crate::formats::atomic::TempTarget;
use crate::{Error, Result};
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

/// One `OI_VIS2` table (with its `OI_WAVELENGTH`): one row per
/// interferogram, one value per row and channel. The channels are the
/// document's ([`Setting::wavelengths_m`]: C of them, one when broadband);
/// the values are row after row, channel j of row r at `r·C + j`.
#[derive(Debug, Clone, PartialEq)]
pub struct Vis2Out {
    /// `INSNAME` (distinct per table).
    pub insname: String,
    /// The estimator (keyword `V2R_EST`); None for a model's V².
    pub estimator: Option<Estimator>,
    /// `VIS2DATA`, rows × C.
    pub vis2data: Vec<f64>,
    /// `VIS2ERR`, rows × C (its meaning stated in `keywords`).
    pub vis2err: Vec<f64>,
    /// `FLAG`, rows × C (true: bad).
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
    check_shapes(doc).map_err(|reason| Error::Invalid { param, reason })
}

/// Tables present, each with one `VIS2DATA`, `VIS2ERR` and `FLAG` per
/// row and channel.
fn check_shapes(doc: &OifitsDoc) -> std::result::Result<(), String> {
    if doc.tables.is_empty() {
        return Err("no OI_VIS2 table to write".into());
    }
    let channels = doc.setting.wavelengths_m().len();
    for t in &doc.tables {
        let n = t.vis2data.len();
        if n == 0 || n % channels != 0 || t.vis2err.len() != n || t.flag.len() != n {
            return Err(format!(
                "{}: {n} VIS2DATA, {} VIS2ERR, {} FLAG; one of each per row and channel \
                 ({channels} channels, at least one row)",
                t.insname,
                t.vis2err.len(),
                t.flag.len()
            ));
        }
    }
    Ok(())
}

fn gzip(bytes: &[u8]) -> std::io::Result<Vec<u8>> {
    let mut z = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
    z.write_all(bytes)?;
    z.finish()
}

/// The file's bytes: every HDU with its `CHECKSUM` and `DATASUM`; a
/// (row, channel) whose `VIS2DATA` or `VIS2ERR` is not a number is
/// flagged.
pub fn to_bytes(doc: &OifitsDoc) -> std::result::Result<Vec<u8>, String> {
    check_shapes(doc)?;
    let now = time::OffsetDateTime::now_utc();
    let stamp = format!(
        "{}T{:02}:{:02}:{:02}",
        date_text(now.date()),
        now.hour(),
        now.minute(),
        now.second()
    );
    let mut out = Vec::new();
    primary(doc, &date_text(now.date()))?.finish(&stamp, &mut out);
    target(&doc.setting)?.finish(&stamp, &mut out);
    array(&doc.setting)?.finish(&stamp, &mut out);
    for (i, t) in doc.tables.iter().enumerate() {
        let extver = i as i64 + 1;
        wavelength(&doc.setting, &t.insname, extver)?.finish(&stamp, &mut out);
        let mut t = t.clone();
        for (r, flag) in t.flag.iter_mut().enumerate() {
            *flag |= !(t.vis2data[r].is_finite() && t.vis2err[r].is_finite());
        }
        vis2(&doc.setting, &t, extver)?.finish(&stamp, &mut out);
    }
    Ok(out)
}

fn put_keys(h: &mut HduWriter, keys: &[Key]) -> std::result::Result<(), String> {
    for k in keys {
        let value = match &k.value {
            KeyValue::Str(s) => CardValue::Str(s),
            KeyValue::F64(v) => CardValue::Real(*v),
            KeyValue::Int(v) => CardValue::Int(*v),
        };
        h.key(&k.name, value, &k.comment)?;
    }
    Ok(())
}

fn primary(doc: &OifitsDoc, today: &str) -> std::result::Result<HduWriter, String> {
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
        Key::str("DATE", today, "UTC date the file was written"),
        Key::str("DATE-OBS", &s.date_obs, "UTC date of the first row"),
        Key::str("TELESCOP", &s.site.name, "array (two stations)"),
        Key::str("INSTRUME", &doc.tables[0].insname, "first INSNAME"),
        Key::str("OBSERVER", "v2ref", "no observer: computed"),
        Key::str("OBJECT", &s.target, "target"),
        insmode(s.wavelengths_m().len()),
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
    let mut h = HduWriter::primary();
    put_keys(&mut h, &keys)?;
    Ok(h)
}

/// `INSMODE`: one broadband channel, or C spectral channels.
fn insmode(channels: usize) -> Key {
    match channels {
        1 => Key::str(
            "INSMODE",
            "BROADBAND",
            "one channel: the estimators sum the band",
        ),
        c => Key::str(
            "INSMODE",
            "DISPERSED",
            &format!("{c} spectral channels, one estimate each"),
        ),
    }
}

/// A binary-table column: name, data (`repeat` per row), unit.
fn col<'a>(
    name: &'a str,
    repeat: usize,
    data: ColumnData<'a>,
    unit: &'static str,
) -> (Column<'a>, &'static str) {
    (Column { name, repeat, data }, unit)
}

/// The table `extname` of `cols` (units as `TUNITn`) and `keys`.
fn create(
    extname: &str,
    cols: &[(Column, &'static str)],
    keys: &[Key],
) -> std::result::Result<HduWriter, String> {
    let columns: Vec<Column> = cols.iter().map(|(c, _)| *c).collect();
    let mut h = HduWriter::bintable(extname, &columns)?;
    let mut all = vec![Key {
        name: "OI_REVN".into(),
        value: KeyValue::Int(2),
        comment: "revision of the OIFITS table definition".into(),
    }];
    for (i, (_, unit)) in cols.iter().enumerate().filter(|(_, (_, u))| !u.is_empty()) {
        all.push(Key::str(&format!("TUNIT{}", i + 1), unit, ""));
    }
    all.extend(keys.iter().cloned());
    put_keys(&mut h, &all)?;
    Ok(h)
}

fn target(s: &Setting) -> std::result::Result<HduWriter, String> {
    use ColumnData::{Str, F32, F64, I16};
    let zero = [0.0f64];
    create(
        "OI_TARGET",
        &[
            col("TARGET_ID", 1, I16(&[1]), ""),
            col("TARGET", 16, Str(&[&s.target]), ""),
            col("RAEP0", 1, F64(&[s.target_radec_deg.0]), "deg"),
            col("DECEP0", 1, F64(&[s.target_radec_deg.1]), "deg"),
            col("EQUINOX", 1, F32(&[2000.0]), "yr"),
            col("RA_ERR", 1, F64(&zero), "deg"),
            col("DEC_ERR", 1, F64(&zero), "deg"),
            col("SYSVEL", 1, F64(&zero), "m/s"),
            col("VELTYP", 8, Str(&["UNKNOWN"]), ""),
            col("VELDEF", 8, Str(&["OPTICAL"]), ""),
            col("PMRA", 1, F64(&zero), "deg/yr"),
            col("PMDEC", 1, F64(&zero), "deg/yr"),
            col("PMRA_ERR", 1, F64(&zero), "deg/yr"),
            col("PMDEC_ERR", 1, F64(&zero), "deg/yr"),
            col("PARALLAX", 1, F32(&[0.0]), "deg"),
            col("PARA_ERR", 1, F32(&[0.0]), "deg"),
            col("SPECTYP", 16, Str(&["UNKNOWN"]), ""),
        ],
        &[],
    )
}

fn array(s: &Setting) -> std::result::Result<HduWriter, String> {
    use ColumnData::{Str, F32, F64, I16};
    let centre = s.site.geocentric_m();
    let keys = [
        Key::str("ARRNAME", &s.site.name, "array"),
        Key::str("FRAME", "GEOCENTRIC", "coordinate frame of STAXYZ"),
        Key::f64("ARRAYX", centre[0], "[m] array centre, geocentric X"),
        Key::f64("ARRAYY", centre[1], "[m] array centre, geocentric Y"),
        Key::f64("ARRAYZ", centre[2], "[m] array centre, geocentric Z"),
    ];
    // The two stations half a baseline either side of the centre, east–west.
    let east = s.site.east();
    let station = |sign: f64| east.map(|e| sign * 0.5 * s.baseline_m * e);
    let staxyz: Vec<f64> = [station(-1.0), station(1.0)].concat();
    // OIFITS 2 requires DIAMETER and FOV; where the set has no aperture
    // both are NaN (FITS's undefined float), never a made-up 0. Field of
    // view: the telescopes' diffraction FWHM, λ/D.
    let diameter_m = s.diameter_m.filter(|d| *d > 0.0).unwrap_or(f64::NAN);
    let fov_arcsec = (s.eff_wave_m / diameter_m).to_degrees() * 3600.0;
    create(
        "OI_ARRAY",
        &[
            col("TEL_NAME", 16, Str(&["T1", "T2"]), ""),
            col("STA_NAME", 16, Str(&["S1", "S2"]), ""),
            col("STA_INDEX", 1, I16(&[1, 2]), ""),
            col("DIAMETER", 1, F32(&[diameter_m as f32; 2]), "m"),
            col("STAXYZ", 3, F64(&staxyz), "m"),
            col("FOV", 1, F64(&[fov_arcsec; 2]), "arcsec"),
            col("FOVTYPE", 6, Str(&["FWHM", "FWHM"]), ""),
        ],
        &keys,
    )
}

fn wavelength(s: &Setting, insname: &str, extver: i64) -> std::result::Result<HduWriter, String> {
    let keys = [
        Key::str("INSNAME", insname, "instrument (estimator)"),
        extver_key(extver),
    ];
    // One row per channel, in the channels' order (the columns of VIS2DATA).
    let (waves, bands): (Vec<f32>, Vec<f32>) = s
        .wavelengths_m()
        .iter()
        .map(|&(w, b)| (w as f32, b as f32))
        .unzip();
    create(
        "OI_WAVELENGTH",
        &[
            col("EFF_WAVE", 1, ColumnData::F32(&waves), "m"),
            col("EFF_BAND", 1, ColumnData::F32(&bands), "m"),
        ],
        &keys,
    )
}

/// `EXTVER`: tables of the same `EXTNAME` are told apart by it.
fn extver_key(extver: i64) -> Key {
    Key {
        name: "EXTVER".into(),
        value: KeyValue::Int(extver),
        comment: "version of this EXTNAME".into(),
    }
}

fn vis2(s: &Setting, t: &Vis2Out, extver: i64) -> std::result::Result<HduWriter, String> {
    use ColumnData::{Logical, F64, I16};
    let nwave = s.wavelengths_m().len();
    let dim = format!("({nwave})");
    let mut keys = vec![
        extver_key(extver),
        Key::str("DATE-OBS", &s.date_obs, "UTC date of the first row"),
        Key::str("ARRNAME", &s.site.name, ""),
        Key::str("INSNAME", &t.insname, ""),
        // The arrays are declared of NWAVE elements (one when broadband),
        // as OIFITS readers that shape columns by TDIM expect.
        Key::str("TDIM5", &dim, ""),
        Key::str("TDIM6", &dim, ""),
        Key::str("TDIM10", &dim, ""),
    ];
    if let Some(est) = t.estimator {
        keys.push(Key::str(
            KEY_ESTIMATOR,
            estimator_key(est),
            "v2ref estimator",
        ));
    }
    keys.extend(t.keywords.iter().cloned());
    let n = t.vis2data.len() / nwave;
    // OIFITS v2 keeps TIME at zero: the time is MJD.
    let mjd: Vec<f64> = (0..n).map(|r| s.mjd(r)).collect();
    let (target_id, zeros) = (vec![1i16; n], vec![0.0; n]);
    let (int_time, ucoord) = (vec![s.row_s(); n], vec![s.baseline_m; n]);
    let stations = [1i16, 2].repeat(n);
    let cols = [
        col("TARGET_ID", 1, I16(&target_id), ""),
        col("TIME", 1, F64(&zeros), "s"),
        col("MJD", 1, F64(&mjd), "day"),
        col("INT_TIME", 1, F64(&int_time), "s"),
        col("VIS2DATA", nwave, F64(&t.vis2data), ""),
        col("VIS2ERR", nwave, F64(&t.vis2err), ""),
        col("UCOORD", 1, F64(&ucoord), "m"),
        col("VCOORD", 1, F64(&zeros), "m"),
        col("STA_INDEX", 2, I16(&stations), ""),
        col("FLAG", nwave, Logical(&t.flag), ""),
    ];
    let mut h = create("OI_VIS2", &cols, &keys)?;
    if let Some(note) = &t.vis2data_note {
        note_column(&mut h, 5, note)?;
    }
    Ok(h)
}

/// Sets the comment of the `TTYPEn` card of column `n` (1-based).
fn note_column(h: &mut HduWriter, n: usize, note: &str) -> std::result::Result<(), String> {
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
    h.set_comment(&format!("TTYPE{n}"), &text)
}

/// `YYYY-MM-DD` of a UTC date.
fn date_text(d: time::Date) -> String {
    format!("{:04}-{:02}-{:02}", d.year(), u8::from(d.month()), d.day())
}
