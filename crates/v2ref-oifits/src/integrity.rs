//! Whether an OIFITS file is as it was written: `CHECKSUM`/`DATASUM`
//! verified HDU by HDU where an HDU carries them (FITS requires neither,
//! and a pipeline may append an HDU without them to a signed file), and
//! the count of HDUs v2ref writes in its own files (`V2R_NHDU`).
//!
//! What is accepted comes back as notes, one line each, for the reader's
//! caller to show: a file read is never silently other than it was written.

use super::fits::{checksum_mismatches, refuse, Hdu, Refusal};
use super::write::KEY_NHDU;

/// How damage is treated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ReadOptions {
    /// Read an HDU whose `CHECKSUM` or `DATASUM` does not match its bytes
    /// (refused by default: the file changed after it was written).
    pub accept_checksum_mismatch: bool,
}

/// The notes on `hdus` (a whole file), or the refusal of a file changed
/// after it was written: a checksum that does not match (unless
/// `options` accept it), or a file that ends early.
pub(crate) fn check(hdus: &[Hdu], options: ReadOptions) -> Result<Vec<String>, Refusal> {
    if !options.accept_checksum_mismatch {
        hdus.iter().try_for_each(verify)?;
    }
    let mut notes: Vec<String> = hdu_count(hdus)?.into_iter().collect();
    notes.extend(unsigned_note(hdus));
    Ok(notes)
}

/// Refuses an HDU whose `CHECKSUM` or `DATASUM` does not match its
/// bytes, or that has one without the other: writers write the pair, so
/// a lone one tells of a card damaged out of its name (which would take
/// the check of that header with it).
fn verify(hdu: &Hdu) -> Result<(), Refusal> {
    let anyway =
        "--accept-checksum-mismatch (Python: accept_checksum_mismatch=True) reads it anyway";
    let has = |k: &str| hdu.header.get(k).is_some();
    if has("CHECKSUM") != has("DATASUM") {
        let (present, absent) = if has("CHECKSUM") {
            ("CHECKSUM", "DATASUM")
        } else {
            ("DATASUM", "CHECKSUM")
        };
        return Err(refuse(
            hdu.at(),
            format!(
                "{present} without {absent}: they are written together, so the header was damaged; {anyway}"
            ),
        ));
    }
    let bad = checksum_mismatches(hdu);
    if bad.is_empty() {
        return Ok(());
    }
    let verb = if bad.len() == 1 { "does" } else { "do" };
    Err(refuse(
        hdu.at(),
        format!(
            "{} {verb} not match the bytes: the file changed after it was written; {anyway}",
            bad.join(" and ")
        ),
    ))
}

/// The note naming the HDUs that carry neither `CHECKSUM` nor `DATASUM`
/// in a file where others do (none where all or none carry them).
fn unsigned_note(hdus: &[Hdu]) -> Option<String> {
    let unsigned: Vec<String> = hdus
        .iter()
        .filter(|h| h.header.get("CHECKSUM").is_none() && h.header.get("DATASUM").is_none())
        .map(Hdu::at)
        .collect();
    if unsigned.is_empty() || unsigned.len() == hdus.len() {
        return None;
    }
    let (what, verb) = match unsigned.len() {
        1 => ("its bytes are", "carries"),
        _ => ("their bytes are", "carry"),
    };
    Some(format!(
        "{} {verb} no CHECKSUM or DATASUM (FITS requires neither): {what} read unverified; \
         the other HDUs' checksums are verified",
        unsigned.join("; ")
    ))
}

/// The note on a v2ref file whose count of HDUs is not the `V2R_NHDU` it
/// was written with, or the refusal of one that ends early.
///
/// A file cut just after a whole HDU holds the first HDUs of those
/// written, each intact: it cannot be told from one whose last HDUs were
/// removed, and is refused (the keyword exists to catch it). A file that
/// holds more HDUs, or not the first ones of those written (an HDU
/// removed from the middle, as an editor such as astropy does), was
/// edited, not cut: each HDU it holds was parsed whole, and is read, with
/// a note.
fn hdu_count(hdus: &[Hdu]) -> Result<Option<String>, Refusal> {
    let Some(written) = hdus[0].header.int(KEY_NHDU) else {
        return Ok(None);
    };
    let held = hdus.len() as i64;
    if written == held {
        return Ok(None);
    }
    let at = format!("{}, keyword {KEY_NHDU}", hdus[0].at());
    if held < written && holds_the_first_written(hdus) {
        return Err(refuse(
            at,
            format!(
                "the file was written with {written} HDUs and holds the first {held}: it is truncated \
                 after a whole HDU, or its last HDUs were removed, which cannot be told apart; \
                 if they were removed on purpose, set {KEY_NHDU} to {held} or delete the keyword"
            ),
        ));
    }
    let change = if held > written {
        "HDUs were added to it"
    } else {
        "HDUs were removed from it (not only its last ones)"
    };
    Ok(Some(format!(
        "{at}: the file was written with {written} HDUs and holds {held}: {change} after it was \
         written; each HDU it holds is whole and is read"
    )))
}

/// `EXTNAME` and `EXTVER` (0: none written) of HDU `i` (0-based) of a
/// file v2ref writes: the primary, `OI_TARGET`, `OI_ARRAY`, then an
/// `OI_WAVELENGTH` and an `OI_VIS2` per table, of `EXTVER` 1, 2, ….
fn written_layout(i: usize) -> (Option<&'static str>, i64) {
    match i {
        0 => (None, 0),
        1 => (Some("OI_TARGET"), 0),
        2 => (Some("OI_ARRAY"), 0),
        _ => {
            let extver = ((i - 3) / 2 + 1) as i64;
            let name = if (i - 3) % 2 == 0 {
                "OI_WAVELENGTH"
            } else {
                "OI_VIS2"
            };
            (Some(name), extver)
        }
    }
}

/// True when `hdus` are, in order, the first HDUs of a file v2ref wrote.
fn holds_the_first_written(hdus: &[Hdu]) -> bool {
    hdus.iter().enumerate().all(|(i, h)| {
        let (name, extver) = written_layout(i);
        h.header.str("EXTNAME") == name && (extver == 0 || h.header.int("EXTVER") == Some(extver))
    })
}
