//! Malformed and truncated FITS files given to `score --estimates`: each
//! is refused with status 2 and one line naming `--estimates`, never a
//! panic, and never an allocation the file's size does not support (a
//! header announcing a billion rows is refused before any is read).

use std::path::Path;
use std::process::Command;

fn run(args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(args)
        .output()
        .expect("the binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// A synth set and a valid OIFITS of its estimates.
fn set(dir: &Path) -> (String, Vec<u8>) {
    let stem = dir.join("set").display().to_string();
    let (code, err) = run(&[
        "synth",
        "--out",
        &stem,
        "--rows",
        "200",
        "--samples",
        "32",
        "--source",
        "point",
        "--reference-blocks",
        "8",
        "--quiet",
    ]);
    assert_eq!(code, 0, "{err}");
    let sidecar = format!("{stem}.json");
    let est = dir.join("est.fits");
    let (code, err) = run(&[
        "estimate",
        "--sidecar",
        &sidecar,
        "--out",
        est.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    (sidecar, std::fs::read(&est).unwrap())
}

/// `bytes` with the header card `key` (8 characters, padded) given `value`.
fn with_card(bytes: &[u8], key: &str, value: &str, nth: usize) -> Vec<u8> {
    let mut out = bytes.to_vec();
    let k = format!("{key:<8}= ");
    let at = (0..bytes.len() / 80)
        .map(|c| c * 80)
        .filter(|&i| bytes[i..].starts_with(k.as_bytes()))
        .nth(nth)
        .expect("the card exists");
    let card = format!("{k}{value:>20}");
    out[at..at + 80].copy_from_slice(format!("{card:<80}").as_bytes());
    out
}

#[test]
fn malformed_fits_files_are_refused_cleanly() {
    let dir = tempfile::tempdir().unwrap();
    let (sidecar, good) = set(dir.path());
    let garbage: Vec<u8> = (0..2880u32).map(|i| (i * 7919 % 251) as u8).collect();
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        ("empty", Vec::new(), "2880-byte"),
        (
            "not a whole block",
            good[..good.len() - 100].to_vec(),
            "2880-byte",
        ),
        (
            "truncated to the headers",
            good[..2880 * 3].to_vec(),
            "--estimates",
        ),
        ("garbage", garbage, "--estimates"),
        (
            "csv text",
            b"v1_sq,v2_sq\n0.1,0.2\n".repeat(200)[..2880].to_vec(),
            "--estimates",
        ),
        (
            "a billion rows",
            with_card(&good, "NAXIS2", "1000000000", 3),
            "truncated or its header",
        ),
        (
            "negative rows",
            with_card(&good, "NAXIS2", "-5", 3),
            "--estimates",
        ),
        (
            "a huge repeat",
            with_card(&good, "TFORM5", "'2000000000D'", 2),
            "--estimates",
        ),
        (
            "no INSNAME",
            with_card(&good, "INSNAME", "'        '", 0),
            "--estimates",
        ),
        ("OI_REVN 7", with_card(&good, "OI_REVN", "7", 3), "OI_REVN"),
    ];
    for (what, bytes, words) in cases {
        let path = dir.path().join("bad.fits");
        std::fs::write(&path, &bytes).unwrap();
        let (code, err) = run(&[
            "score",
            "--sidecar",
            &sidecar,
            "--estimates",
            path.to_str().unwrap(),
        ]);
        assert_eq!(code, 2, "{what}: {err}");
        assert!(!err.contains("panicked"), "{what}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{what}: {err}");
        assert!(
            err.contains("--estimates") && err.contains(words),
            "{what}: {err}"
        );
    }
}
