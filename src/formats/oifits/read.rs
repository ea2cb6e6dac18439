//! Reading `OI_VIS2` tables from OIFITS v1 or v2, and a pipeline's
//! estimates from them, matched to a set's rows in order.
//!
//! The file is read whole (its size bounds every allocation: a table whose
//! header announces more values than the file holds is refused before any
//! is read) and opened from memory by cfitsio. Every refusal is an
//! [`Error::Data`] naming the parameter, the HDU and what is accepted.

use super::mem::MemRead;
use super::status_text;
use crate::formats::Estimates;
use crate::{Error, Result};
use std::ffi::CString;
use std::os::raw::{c_char, c_int};
use std::path::Path;

/// Largest OIFITS file read, bytes (1 GiB: 40 million rows of V²).
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
    /// Rows.
    pub rows: usize,
    /// Channels per row (`NWAVE`).
    pub nwave: usize,
    /// `EFF_WAVE` of the `OI_WAVELENGTH` of the same `INSNAME`, m.
    pub eff_wave_m: Vec<f64>,
    /// `VIS2DATA`, `rows × nwave`, row after row.
    pub vis2data: Vec<f64>,
    /// `VIS2ERR`, same shape.
    pub vis2err: Vec<f64>,
    /// `FLAG`, same shape (true: bad).
    pub flag: Vec<bool>,
}

/// An open file and what refusals name.
struct Reader<'a> {
    mem: MemRead,
    bytes: u64,
    param: &'static str,
    path: &'a Path,
}

impl Reader<'_> {
    fn err(&self, location: impl Into<String>, reason: impl Into<String>) -> Error {
        Error::data(self.param, self.path, location, reason)
    }

    fn check(&self, status: c_int, location: &str, what: &str) -> Result<()> {
        match status {
            0 => Ok(()),
            s => Err(self.err(
                location,
                format!("{what}: {}; a valid OIFITS file is needed", status_text(s)),
            )),
        }
    }

    /// A string keyword of the current HDU (None when absent).
    fn key_str(&self, name: &str) -> Result<Option<String>> {
        let key = CString::new(name).map_err(|e| self.err("", e.to_string()))?;
        let mut value = [0 as c_char; 72];
        let mut status = 0;
        // SAFETY: the value buffer exceeds FLEN_VALUE (71); no comment read.
        unsafe {
            fitsio_sys::ffgkys(
                self.mem.fptr,
                key.as_ptr(),
                value.as_mut_ptr(),
                std::ptr::null_mut(),
                &mut status,
            )
        };
        match status {
            0 => Ok(Some(c_string(&value).trim_end().to_owned())),
            202 | 204 => Ok(None), // KEY_NO_EXIST, VALUE_UNDEFINED
            s => Err(self.err(format!("keyword {name}"), status_text(s))),
        }
    }

    /// An integer keyword of the current HDU (None when absent).
    fn key_int(&self, name: &str) -> Result<Option<i64>> {
        let key = CString::new(name).map_err(|e| self.err("", e.to_string()))?;
        let mut value: std::os::raw::c_long = 0;
        let mut status = 0;
        // SAFETY: writes one long; no comment read.
        unsafe {
            fitsio_sys::ffgkyj(
                self.mem.fptr,
                key.as_ptr(),
                &mut value,
                std::ptr::null_mut(),
                &mut status,
            )
        };
        match status {
            0 => Ok(Some(value as i64)),
            202 | 204 => Ok(None),
            s => Err(self.err(format!("keyword {name}"), status_text(s))),
        }
    }

    fn move_to(&self, hdu: usize) -> Result<()> {
        let mut status = 0;
        let mut typ = 0;
        // SAFETY: moves the open file to an HDU that ffthdu counted.
        unsafe { fitsio_sys::ffmahd(self.mem.fptr, hdu as c_int, &mut typ, &mut status) };
        self.check(status, &format!("HDU {hdu}"), "unreadable header")
    }

    fn rows(&self, at: &str) -> Result<usize> {
        let mut n = 0;
        let mut status = 0;
        // SAFETY: writes one LONGLONG.
        unsafe { fitsio_sys::ffgnrwll(self.mem.fptr, &mut n, &mut status) };
        self.check(status, at, "no row count")?;
        usize::try_from(n).map_err(|_| self.err(at, format!("{n} rows")))
    }

    /// Column `name`: its number (1-based) and repeat count.
    fn column(&self, name: &str, at: &str) -> Result<(c_int, usize)> {
        let mut templ = CString::new(name)
            .map_err(|e| self.err(at, e.to_string()))?
            .into_bytes_with_nul();
        let (mut colnum, mut typ, mut repeat, mut width) = (0, 0, 0, 0);
        let mut status = 0;
        // SAFETY: the template is NUL-terminated; outputs are plain ints.
        unsafe {
            fitsio_sys::ffgcno(
                self.mem.fptr,
                0,
                templ.as_mut_ptr() as *mut c_char,
                &mut colnum,
                &mut status,
            );
            fitsio_sys::ffgtclll(
                self.mem.fptr,
                colnum,
                &mut typ,
                &mut repeat,
                &mut width,
                &mut status,
            );
        }
        if status != 0 {
            return Err(self.err(
                format!("{at}, column {name}"),
                format!(
                    "missing or unreadable ({}); the standard requires it",
                    status_text(status)
                ),
            ));
        }
        let repeat = usize::try_from(repeat).unwrap_or(0);
        Ok((colnum, repeat))
    }

    /// `n` values must fit in the file: refused before allocating.
    fn fits_in_file(&self, n: usize, bytes_each: u64, at: &str) -> Result<()> {
        if (n as u64).saturating_mul(bytes_each) > self.bytes {
            return Err(self.err(
                at,
                format!(
                    "the header announces {n} values, more than the file's {} bytes hold; \
                     the file is truncated or its header is wrong",
                    self.bytes
                ),
            ));
        }
        Ok(())
    }

    /// `n` values (from row 1) of numeric column `colnum`, as f64.
    fn read_f64(&self, colnum: c_int, n: usize, at: &str) -> Result<Vec<f64>> {
        self.fits_in_file(n, 1, at)?;
        let mut out = vec![0.0; n];
        let (mut anynul, mut status) = (0, 0);
        if n > 0 {
            // SAFETY: `out` holds `n` doubles.
            unsafe {
                fitsio_sys::ffgcvd(
                    self.mem.fptr,
                    colnum,
                    1,
                    1,
                    n as i64,
                    f64::NAN,
                    out.as_mut_ptr(),
                    &mut anynul,
                    &mut status,
                )
            };
        }
        self.check(status, at, "values unreadable")?;
        Ok(out)
    }

    /// `n` values (from row 1) of logical column `colnum`.
    fn read_flags(&self, colnum: c_int, n: usize, at: &str) -> Result<Vec<bool>> {
        self.fits_in_file(n, 1, at)?;
        let mut out: Vec<c_char> = vec![0; n];
        let (mut anynul, mut status) = (0, 0);
        if n > 0 {
            // SAFETY: `out` holds `n` chars.
            unsafe {
                fitsio_sys::ffgcvl(
                    self.mem.fptr,
                    colnum,
                    1,
                    1,
                    n as i64,
                    0,
                    out.as_mut_ptr(),
                    &mut anynul,
                    &mut status,
                )
            };
        }
        self.check(status, at, "flags unreadable")?;
        Ok(out.into_iter().map(|c| c != 0).collect())
    }
}

fn c_string(buf: &[c_char]) -> String {
    buf.iter()
        .take_while(|&&c| c != 0)
        .map(|&c| c as u8 as char)
        .collect()
}

/// Reads every `OI_VIS2` table of `path` (named by `param`), in file
/// order, each with the `EFF_WAVE` of its `INSNAME`.
pub fn read_vis2_tables(path: &Path, param: &'static str) -> Result<Vec<Vis2Table>> {
    let bytes = read_bounded(path, param)?;
    let len = bytes.len() as u64;
    let mem = MemRead::open(bytes).map_err(|r| Error::data(param, path, "", r))?;
    let r = Reader {
        mem,
        bytes: len,
        param,
        path,
    };
    let mut nhdu = 0;
    let mut status = 0;
    // SAFETY: writes one int.
    unsafe { fitsio_sys::ffthdu(r.mem.fptr, &mut nhdu, &mut status) };
    r.check(status, "", "HDUs unreadable")?;
    let mut waves: Vec<(String, Vec<f64>)> = Vec::new();
    let mut tables = Vec::new();
    for hdu in 2..=nhdu.max(0) as usize {
        r.move_to(hdu)?;
        match r.key_str("EXTNAME")?.as_deref() {
            Some("OI_WAVELENGTH") => waves.push(wavelength_table(&r, hdu)?),
            Some("OI_VIS2") => tables.push(vis2_table(&r, hdu)?),
            _ => {}
        }
    }
    for t in &mut tables {
        let at = format!("HDU {} (OI_VIS2 INSNAME {})", t.hdu, t.insname);
        let Some((_, w)) = waves.iter().find(|(n, _)| *n == t.insname) else {
            return Err(r.err(
                at,
                "no OI_WAVELENGTH table of this INSNAME; the standard requires one",
            ));
        };
        if w.len() != t.nwave {
            return Err(r.err(
                at,
                format!("{} channels, its OI_WAVELENGTH has {}", t.nwave, w.len()),
            ));
        }
        t.eff_wave_m = w.clone();
    }
    Ok(tables)
}

fn read_bounded(path: &Path, param: &'static str) -> Result<Vec<u8>> {
    use std::io::Read;
    let file = crate::formats::open(path, param)?;
    let mut bytes = Vec::new();
    file.take(MAX_OIFITS_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| Error::file(Some(param), path, e))?;
    if bytes.len() as u64 > MAX_OIFITS_BYTES {
        return Err(Error::data(
            param,
            path,
            "",
            format!("larger than {MAX_OIFITS_BYTES} bytes"),
        ));
    }
    if bytes.len() < super::mem::BLOCK || bytes.len() % super::mem::BLOCK != 0 {
        return Err(Error::data(
            param,
            path,
            "",
            format!(
                "{} bytes, not a whole number of 2880-byte FITS blocks: truncated or not FITS",
                bytes.len()
            ),
        ));
    }
    Ok(bytes)
}

fn insname(r: &Reader, at: &str) -> Result<String> {
    r.key_str("INSNAME")?
        .ok_or_else(|| r.err(at, "no INSNAME keyword; the standard requires one"))
}

fn wavelength_table(r: &Reader, hdu: usize) -> Result<(String, Vec<f64>)> {
    let at = format!("HDU {hdu} (OI_WAVELENGTH)");
    let name = insname(r, &at)?;
    let rows = r.rows(&at)?;
    let (col, _) = r.column("EFF_WAVE", &at)?;
    Ok((
        name,
        r.read_f64(col, rows, &format!("{at}, column EFF_WAVE"))?,
    ))
}

fn vis2_table(r: &Reader, hdu: usize) -> Result<Vis2Table> {
    let at = format!("HDU {hdu} (OI_VIS2)");
    let insname = insname(r, &at)?;
    let revn = r.key_int("OI_REVN")?.unwrap_or(0);
    if !(1..=2).contains(&revn) {
        return Err(r.err(&at, format!("OI_REVN {revn}; OIFITS 1 or 2 is read")));
    }
    let rows = r.rows(&at)?;
    let (data_col, nwave) = r.column("VIS2DATA", &at)?;
    let (err_col, err_rep) = r.column("VIS2ERR", &at)?;
    let (flag_col, flag_rep) = r.column("FLAG", &at)?;
    if nwave == 0 || err_rep != nwave || flag_rep != nwave {
        return Err(r.err(
            &at,
            format!("VIS2DATA, VIS2ERR, FLAG hold {nwave}, {err_rep}, {flag_rep} values per row; the same NWAVE > 0 is needed"),
        ));
    }
    let n = rows.saturating_mul(nwave);
    Ok(Vis2Table {
        hdu,
        estimator: r.key_str(super::KEY_ESTIMATOR)?,
        insname,
        revn,
        rows,
        nwave,
        eff_wave_m: Vec::new(),
        vis2data: r.read_f64(data_col, n, &format!("{at}, column VIS2DATA"))?,
        vis2err: r.read_f64(err_col, n, &format!("{at}, column VIS2ERR"))?,
        flag: r.read_flags(flag_col, n, &format!("{at}, column FLAG"))?,
    })
}

/// A pipeline's estimates read from OIFITS, flagged rows left out.
#[derive(Debug, Clone, PartialEq)]
pub struct OifitsEstimates {
    /// The unflagged rows' estimates, in order.
    pub estimates: Estimates,
    /// Rows in the file (per estimator).
    pub rows: usize,
    /// Rows left out: flagged in any table read.
    pub flagged: usize,
    /// `INSNAME` of the tables read.
    pub insnames: Vec<String>,
}

/// What the file must match: the set's rows and band.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Expected {
    /// Rows of the set.
    pub rows: u64,
    /// The band's wavelengths (shortest, longest), m.
    pub band_m: (f64, f64),
}

pub use super::select::{read_oifits_estimates, truth_for_kept_rows};
