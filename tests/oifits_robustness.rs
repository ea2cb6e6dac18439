//! Malformed, truncated and altered FITS files given to `score
//! --estimates`: each is refused with status 2 and one line naming
//! `--estimates`, never a panic, and never an allocation the file's size
//! does not support (a header announcing a billion rows is refused before
//! any is read). The structural checks are tried with the checksums
//! ignored (`--accept-checksum-mismatch`), so that each is reached; the
//! checksums on their own refuse any altered byte. The files that crashed
//! or fooled the former reader are kept in `tests/data/oifits_damaged/`.

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
        (
            "wider rows",
            with_card(&good, "NAXIS1", "630000", 3),
            "truncated or its header",
        ),
        (
            "a whole HDU cut off",
            good[..good.len() - 2880 * 7].to_vec(),
            "truncated",
        ),
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
            "--accept-checksum-mismatch",
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

fn score_status(sidecar: &str, path: &Path, extra: &[&str]) -> (i32, String) {
    let mut args = vec![
        "score",
        "--sidecar",
        sidecar,
        "--estimates",
        path.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    run(&args)
}

#[test]
fn a_file_changed_after_it_was_written_is_refused_by_its_checksums() {
    let dir = tempfile::tempdir().unwrap();
    let (sidecar, good) = set(dir.path());
    let path = dir.path().join("changed.fits");
    // One byte of a VIS2DATA value changed: the data's sum no longer matches.
    let mut data = good.clone();
    let last = data.len() - 2880 * 2;
    data[last] ^= 0x01;
    std::fs::write(&path, &data).unwrap();
    let (code, err) = score_status(&sidecar, &path, &[]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("DATASUM") && err.contains("--accept-checksum-mismatch"),
        "{err}"
    );
    let (code, err) = score_status(&sidecar, &path, &["--accept-checksum-mismatch"]);
    assert!(code == 0 || code == 1, "{err}");
    // A header card changed: its HDU's CHECKSUM no longer matches.
    std::fs::write(&path, with_card(&good, "OI_REVN", "1", 3)).unwrap();
    let (code, err) = score_status(&sidecar, &path, &[]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("CHECKSUM") && !err.contains("DATASUM"),
        "{err}"
    );
    // The file cut at any whole block is refused.
    for blocks in 1..good.len() / 2880 {
        std::fs::write(&path, &good[..blocks * 2880]).unwrap();
        let (code, err) = score_status(&sidecar, &path, &["--accept-checksum-mismatch"]);
        assert_eq!(code, 2, "{blocks} blocks: {err}");
    }
}

#[test]
fn the_files_that_crashed_or_fooled_the_former_reader_are_refused() {
    // Written by the former writer (no checksums); the former reader died
    // of a segmentation fault on the inflated sizes and scored the
    // truncated files (PASS for one block cut off).
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/oifits_damaged");
    let sidecar = dir.join("set.json");
    for name in [
        "naxis1_inflated",
        "naxis2_inflated",
        "truncated_one_block",
        "truncated_two_blocks",
    ] {
        let path = dir.join(format!("{name}.fits.gz"));
        let (code, err) = score_status(sidecar.to_str().unwrap(), &path, &[]);
        assert_eq!(code, 2, "{name}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{name}: {err}");
        assert!(err.contains("truncated"), "{name}: {err}");
    }
}

#[test]
fn a_gzipped_file_is_scored_as_the_plain_one() {
    let dir = tempfile::tempdir().unwrap();
    let (sidecar, good) = set(dir.path());
    let plain = dir.path().join("est.fits");
    let gz = dir.path().join("est.fits.gz");
    std::fs::write(&plain, &good).unwrap();
    let (code, err) = run(&[
        "estimate",
        "--sidecar",
        &sidecar,
        "--out",
        gz.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(std::fs::read(&gz).unwrap()[..2], [0x1f, 0x8b]);
    let json = |p: &Path| {
        let out = Command::new(env!("CARGO_BIN_EXE_v2ref"))
            .args([
                "score",
                "--sidecar",
                &sidecar,
                "--estimates",
                p.to_str().unwrap(),
                "--json",
            ])
            .output()
            .unwrap();
        let mut v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        v["estimates"] = serde_json::Value::Null;
        v
    };
    assert_eq!(json(&plain), json(&gz));
    // A gzip stream cut short is refused, naming gzip.
    let bytes = std::fs::read(&gz).unwrap();
    std::fs::write(&gz, &bytes[..bytes.len() / 2]).unwrap();
    let (code, err) = score_status(&sidecar, &gz, &[]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("gzip"), "{err}");
}
