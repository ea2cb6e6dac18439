//! OIFITS files as pipelines write and edit them, through `score`
//! (issue 53): a target written with a leading blank is chosen by its name;
//! an HDU appended without checksums to a signed file is read and named; a
//! v2ref file with an HDU added is read with a note, one cut after a whole
//! HDU is refused saying how to read it; a checksum refusal names the
//! HDU's EXTNAME and INSNAME in one line. The files are written by the
//! suite's own FITS writer (`fits_plain`) or by v2ref and then edited
//! byte by byte here; the Python suite edits them with astropy
//! (tests/python/test_oifits_as_written.py).

use crate::fits_plain::{self, Card, Column};
use crate::run::v2ref;
use std::path::Path;

const ROWS: usize = 40;
const BLOCK: usize = 2880;

/// A synth set of `ROWS` rows: its sidecar, its estimates as OIFITS
/// (`est.fits`) and their V2² in order.
fn set(dir: &Path) -> (String, Vec<u8>, Vec<f64>) {
    let stem = dir.join("set").display().to_string();
    let rows = ROWS.to_string();
    let ok = |args: &[&str]| {
        let (code, _, err) = v2ref(args);
        assert_eq!(code, 0, "{args:?}: {err}");
    };
    ok(&[
        "synth",
        "--out",
        &stem,
        "--rows",
        &rows,
        "--samples",
        "32",
        "--source",
        "point",
        "--reference-blocks",
        "8",
        "--quiet",
    ]);
    let sidecar = format!("{stem}.json");
    let (fits, csv) = (dir.join("est.fits"), dir.join("est.csv"));
    for out in [&fits, &csv] {
        ok(&[
            "estimate",
            "--sidecar",
            &sidecar,
            "--out",
            out.to_str().unwrap(),
        ]);
    }
    let text = std::fs::read_to_string(csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let k = header.iter().position(|c| *c == "v2_sq").unwrap();
    let v2 = lines
        .map(|l| l.split(',').nth(k).unwrap().parse().unwrap())
        .collect();
    (sidecar, std::fs::read(fits).unwrap(), v2)
}

/// `score --json` of `bytes` written as `name` in `dir`: (status, stderr).
fn score(dir: &Path, sidecar: &str, name: &str, bytes: &[u8], extra: &[&str]) -> (i32, String) {
    let file = dir.join(name);
    std::fs::write(&file, bytes).unwrap();
    let mut args = vec![
        "score",
        "--sidecar",
        sidecar,
        "--estimates",
        file.to_str().unwrap(),
        "--json",
    ];
    args.extend_from_slice(extra);
    let (code, _, err) = v2ref(&args);
    (code, err)
}

/// The byte offsets where the HDUs of a FITS file start.
fn hdu_starts(bytes: &[u8]) -> Vec<usize> {
    (0..bytes.len() / BLOCK)
        .map(|b| b * BLOCK)
        .filter(|&at| {
            bytes[at..].starts_with(b"SIMPLE  =") || bytes[at..].starts_with(b"XTENSION=")
        })
        .collect()
}

/// Where the data of the HDU starting at `at` start: after its END card's
/// block.
fn data_start(bytes: &[u8], at: usize) -> usize {
    let end = (at..bytes.len())
        .step_by(80)
        .find(|&c| bytes[c..c + 80] == *format!("{:<80}", "END").as_bytes())
        .unwrap();
    (end + 80).next_multiple_of(BLOCK)
}

/// One binary table of no checksum, as the suite's own writer lays it out
/// (its file less the primary HDU).
fn unsigned_table(dir: &Path) -> Vec<u8> {
    let path = dir.join("extra.fits");
    let columns = vec![Column::F64("X", vec![1.0])];
    fits_plain::write(
        &path,
        &[("LATER", vec![("OI_REVN", Card::Int(2))], columns)],
    );
    std::fs::read(path).unwrap()[BLOCK..].to_vec()
}

#[test]
fn a_target_written_with_a_leading_blank_is_scored_by_its_name() {
    let dir = tempfile::tempdir().unwrap();
    let (sidecar, _, v2) = set(dir.path());
    let n = ROWS + 2;
    let ids: Vec<i16> = (0..n).map(|r| if r < ROWS { 1 } else { 2 }).collect();
    let mut values = v2.clone();
    values.extend([0.9, 0.9]);
    let pipe = || vec![("OI_REVN", Card::Int(1)), ("INSNAME", Card::Str("MIRCX"))];
    let path = dir.path().join("mircx.fits");
    fits_plain::write(
        &path,
        &[
            (
                "OI_TARGET",
                vec![("OI_REVN", Card::Int(1))],
                vec![
                    Column::I16("TARGET_ID", vec![1, 2]),
                    Column::Text("TARGET", 16, vec![" bet Ari".into(), "HD 2".into()]),
                ],
            ),
            (
                "OI_WAVELENGTH",
                pipe(),
                vec![Column::F32("EFF_WAVE", vec![2.2e-6])],
            ),
            (
                "OI_VIS2",
                pipe(),
                vec![
                    Column::I16("TARGET_ID", ids),
                    Column::F64("MJD", (0..n).map(|r| 6e4 + r as f64 / 1440.0).collect()),
                    Column::F64("VIS2DATA", values),
                    Column::F64("VIS2ERR", vec![0.1; n]),
                    Column::Logical("FLAG", vec![false; n]),
                ],
            ),
        ],
    );
    assert_eq!(fits_plain::read(&path)[1].text_col("TARGET")[0], " bet Ari");
    let bytes = std::fs::read(&path).unwrap();
    for name in ["bet Ari", " bet Ari", "bet Ari "] {
        let extra = ["--estimator", "v2_sq", "--target", name];
        let (code, err) = score(dir.path(), &sidecar, "mircx.fits", &bytes, &extra);
        assert!(code == 0 || code == 1, "{name:?}: {err}");
    }
}

#[test]
fn a_checksum_refusal_names_the_tables_extname_and_insname_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let (sidecar, mut bytes, _) = set(dir.path());
    let last = *hdu_starts(&bytes).last().unwrap();
    // A byte of the first row of the last table (V2SQ's OI_VIS2).
    let at = data_start(&bytes, last) + 20;
    bytes[at] ^= 0x01;
    let (code, err) = score(dir.path(), &sidecar, "flipped.fits", &bytes, &[]);
    assert_eq!(code, 2, "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    for words in [
        "HDU 7 (EXTNAME OI_VIS2, INSNAME V2REF_V2SQ)",
        "DATASUM and CHECKSUM do not match",
    ] {
        assert!(err.contains(words), "{words:?} not in {err}");
    }
}

#[test]
fn an_hdu_appended_without_checksums_is_read_and_named_in_a_note() {
    let dir = tempfile::tempdir().unwrap();
    let (sidecar, mut bytes, _) = set(dir.path());
    let (code, err) = score(dir.path(), &sidecar, "est.fits", &bytes, &[]);
    assert!((code == 0 || code == 1) && !err.contains("note"), "{err}");
    bytes.extend(unsigned_table(dir.path()));
    let (code, err) = score(dir.path(), &sidecar, "later.fits", &bytes, &[]);
    assert!(code == 0 || code == 1, "{err}");
    let notes: Vec<&str> = err.lines().filter(|l| l.starts_with("note: ")).collect();
    assert_eq!(notes.len(), 2, "{err}");
    assert!(
        notes[0].contains("written with 7 HDUs and holds 8: HDUs were added"),
        "{err}"
    );
    assert!(
        notes[1].contains("HDU 8 (EXTNAME LATER) carries no CHECKSUM or DATASUM"),
        "{err}"
    );
}

#[test]
fn a_v2ref_file_cut_after_a_whole_hdu_is_refused_saying_how_to_read_it() {
    let dir = tempfile::tempdir().unwrap();
    let (sidecar, bytes, _) = set(dir.path());
    let last = *hdu_starts(&bytes).last().unwrap();
    let (code, err) = score(dir.path(), &sidecar, "cut.fits", &bytes[..last], &[]);
    assert_eq!(code, 2, "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    for words in [
        "HDU 1 (primary), keyword V2R_NHDU",
        "holds the first 6",
        "truncated",
        "set V2R_NHDU to 6 or delete the keyword",
    ] {
        assert!(err.contains(words), "{words:?} not in {err}");
    }
}
