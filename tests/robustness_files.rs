//! Robustness of the command line, second round (issue 28): files whose
//! header lies, outputs that must not be overwritten, inputs outside the
//! range where a result means anything, and the exit status of each kind
//! of failure (2 bad input, 74 output not written, 130 interrupted).
//!
//! The table runs each case in a fresh folder of fixtures and checks the
//! status, the one line naming the flag, that nothing panicked and that no
//! file of the folder changed; the functions below it cover what a table
//! cannot (full and read-only file systems, a closed stdout, `--force`).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// How a case must end.
#[derive(Clone, Copy, Debug)]
enum Expect {
    /// Status 2, one line on stderr naming the flag and holding the words.
    Refused(&'static str, &'static str),
    /// Status 74, one line on stderr naming the flag.
    NotWritten(&'static str),
}
use Expect::{NotWritten, Refused};

struct Case {
    kind: &'static str,
    args: &'static [&'static str],
    expect: Expect,
}

const fn case(kind: &'static str, args: &'static [&'static str], expect: Expect) -> Case {
    Case { kind, args, expect }
}

/// The kinds of the table, each with at least 4 cases.
const KINDS: &[&str] = &["header", "overwrite", "meaningless", "status"];

#[rustfmt::skip]
const CASES: &[Case] = &[
    // --- header: a .npy whose header claims what its data cannot hold.
    case("header", &["estimate", "--input", "wrap.npy"], Refused("--input", "claims")),
    case("header", &["estimate", "--input", "wrap3.npy"], Refused("--input", "claims")),
    case("header", &["estimate", "--input", "hdr.npy"], Refused("--input", "header claims")),
    case("header", &["estimate", "--input", "good.npy", "--calibrator", "wrap.npy"], Refused("--calibrator", "claims")),
    case("header", &["estimate", "--input", "good.npy", "--calibrator", "hdr.npy"], Refused("--calibrator", "header")),
    case("header", &["estimate", "--input", "short.npy"], Refused("--input", "truncated")),
    case("header", &["estimate", "--input", "v9.npy"], Refused("--input", "version 9")),
    case("header", &["plan", "--fringe-hz", "1:1e6:10000", "--stroke-um", "10", "--stroke-um", "20", "--stroke-um", "30", "--svg", "file.txt"], Refused("--svg", "--force")),
    // --- overwrite: nothing a user has is replaced without --force, and
    // links, folders, devices and FIFOs never.
    case("overwrite", &["synth", "--out", "user", "--rows", "4", "--quiet"], Refused("--out", "--force")),
    case("overwrite", &["synth", "--out", "user2", "--csv", "--rows", "4", "--quiet"], Refused("--out", "user2.csv")),
    case("overwrite", &["estimate", "--input", "good.npy", "--out", "file.txt"], Refused("--out", "--force")),
    case("overwrite", &["estimate", "--input", "good.npy", "--out", "link.csv"], Refused("--out", "symbolic link")),
    case("overwrite", &["estimate", "--input", "good.npy", "--out", "link.csv", "--force"], Refused("--out", "symbolic link")),
    case("overwrite", &["estimate", "--input", "good.npy", "--out", "fifo.csv", "--force"], Refused("--out", "FIFO")),
    case("overwrite", &["estimate", "--input", "good.npy", "--out", "/dev/null", "--force"], Refused("--out", "device")),
    case("overwrite", &["estimate", "--input", "good.npy", "--out", "keep", "--force"], Refused("--out", "folder")),
    case("overwrite", &["estimate", "--input", "good.npy", "--out", "missing/e.csv"], Refused("--out", "does not exist")),
    case("overwrite", &["estimate", "--input", "good.npy", "--out", "file.txt/e.csv"], Refused("--out", "not a folder")),
    case("overwrite", &["synth", "--out", "missing/set", "--rows", "4"], Refused("--out", "does not exist")),
    case("overwrite", &["synth", "--out", "link", "--rows", "4", "--force"], Refused("--out", "symbolic link")),
    case("overwrite", &["plan", "--svg", "link.csv", "--force"], Refused("--svg", "symbolic link")),
    case("overwrite", &["golden", "--update", "--dir", "keep"], Refused("--dir", "--force")),
    case("overwrite", &["golden", "--update", "--dir", "file.txt"], Refused("--dir", "not a folder")),
    // --- meaningless: inputs where no result has a meaning.
    case("meaningless", &["estimate", "--input", "zeros.npy"], Refused("--input", "no light")),
    case("meaningless", &["piston", "--seeing-arcsec", "100", "--seeing-wavelength-um", "0.001", "--scans", "10"], Refused("--seeing-wavelength-um", "0.3 to 30")),
    case("meaningless", &["plan", "--seeing-wavelength-um", "1e5", "--scans", "64"], Refused("--seeing-wavelength-um", "0.3 to 30")),
    case("meaningless", &["estimate", "--input", "zeros.csv"], Refused("--input", "no light")),
    case("meaningless", &["estimate", "--input", "good.npy", "--calibrator", "zeros.npy"], Refused("--calibrator", "no light")),
    case("meaningless", &["simulate", "--trials", "2"], Refused("--trials", "at least 4")),
    case("meaningless", &["simulate", "--trials", "3"], Refused("--trials", "at least 4")),
    case("meaningless", &["snr", "--samples", "2"], Refused("--samples", "no bin")),
    case("meaningless", &["piston", "--wind-mps", "5e-324", "--scans", "4"], Refused("--wind-mps", "0.001")),
    case("meaningless", &["piston", "--aperture-m", "1e300", "--scans", "4"], Refused("--aperture-m", "1000")),
    case("meaningless", &["piston", "--aperture-m", "1e-308", "--scans", "4"], Refused("--aperture-m", "0.001")),
    case("meaningless", &["plan", "--aperture-m", "1e300"], Refused("--aperture-m", "1000")),
    case("meaningless", &["score", "--sidecar", "set.json", "--estimates", "est.csv", "--alpha", "1e-20"], Refused("--alpha", "resolved")),
    // --- status: outputs that cannot be written.
    case("status", &["estimate", "--input", "good.npy", "--out", "/sys/v2ref-e.csv"], NotWritten("--out")),
    case("status", &["synth", "--out", "/sys/v2ref-set", "--rows", "4", "--quiet"], NotWritten("--out")),
    case("status", &["estimate", "--input", "good.npy", "--out", "/sys/v2ref-e.npy"], NotWritten("--out")),
    case("status", &["reproduce", "--quick", "--out", "/sys/v2ref-out"], NotWritten("--out")),
];

/// Writes a `.npy` of the header text `shape` and `data` bytes.
fn npy(dir: &Path, name: &str, shape: &str, data: &[u8]) {
    let mut h = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': {shape}, }}");
    while (10 + h.len() + 1) % 64 != 0 {
        h.push(' ');
    }
    h.push('\n');
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    bytes.extend_from_slice(&(h.len() as u16).to_le_bytes());
    bytes.extend_from_slice(h.as_bytes());
    bytes.extend_from_slice(data);
    std::fs::write(dir.join(name), bytes).unwrap();
}

/// A fresh folder of fixtures: a user's folder and files, a link, a FIFO,
/// and `.npy` files good and bad.
fn workspace() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::create_dir(d.join("keep")).unwrap();
    std::fs::write(d.join("keep/notes.txt"), "mine\n").unwrap();
    std::fs::write(d.join("file.txt"), "a user's file\n").unwrap();
    for f in ["user.npy", "user.json", "user2.csv"] {
        std::fs::write(d.join(f), "the user's data\n").unwrap();
    }
    std::os::unix::fs::symlink("file.txt", d.join("link.csv")).unwrap();
    std::os::unix::fs::symlink("file.txt", d.join("link.npy")).unwrap();
    let fifo = Command::new("mkfifo").arg(d.join("fifo.csv")).status();
    assert!(fifo.is_ok_and(|s| s.success()), "mkfifo");
    let good: Vec<u8> = (0..2 * 16)
        .flat_map(|i| (100.0 + (i as f64).sin()).to_le_bytes())
        .collect();
    npy(d, "good.npy", "(2, 16)", &good);
    npy(d, "zeros.npy", "(2, 16)", &[0u8; 2 * 16 * 8]);
    npy(d, "wrap.npy", "(4294967296, 4294967296)", &[]);
    npy(d, "wrap3.npy", "(3, 6148914691236517206)", &[0u8; 16]);
    npy(d, "short.npy", "(2, 16)", &good[..100]);
    let mut v9 = std::fs::read(d.join("good.npy")).unwrap();
    v9[6] = 9;
    std::fs::write(d.join("v9.npy"), v9).unwrap();
    let mut hdr = b"\x93NUMPY\x02\x00".to_vec();
    hdr.extend_from_slice(&u32::MAX.to_le_bytes());
    hdr.extend_from_slice(b"{'descr': '<f8'");
    std::fs::write(d.join("hdr.npy"), hdr).unwrap();
    let zeros_row = vec!["0"; 16].join(",");
    std::fs::write(d.join("zeros.csv"), format!("{zeros_row}\n{zeros_row}\n")).unwrap();
    dir
}

/// Every file under `root` (links and FIFOs by their kind) and its bytes.
fn snapshot(root: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![root.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(&dir).unwrap().flatten() {
            let p = e.path();
            let t = e.file_type().unwrap();
            if t.is_dir() {
                stack.push(p.clone());
                out.insert(p, b"<dir>".to_vec());
            } else if t.is_file() {
                out.insert(p.clone(), std::fs::read(&p).unwrap());
            } else {
                out.insert(p, format!("{t:?}").into_bytes());
            }
        }
    }
    out
}

fn run_in(dir: &Path, args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .output()
        .expect("the binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn check(case: &Case) -> Option<String> {
    let dir = workspace();
    let before = snapshot(dir.path());
    let (code, stdout, stderr) = run_in(dir.path(), case.args);
    let mut bad = Vec::new();
    let (status, flag, words) = match case.expect {
        Refused(flag, words) => (2, flag, words),
        NotWritten(flag) => (74, flag, flag),
    };
    if stderr.contains("panicked") || code == 101 {
        bad.push(format!("panicked: {stderr}"));
    }
    if code != status {
        bad.push(format!("exit {code}, expected {status}"));
    }
    if !stdout.is_empty() {
        bad.push(format!("wrote to stdout: {stdout}"));
    }
    if stderr.trim_end().lines().count() != 1 {
        bad.push(format!("not one line on stderr: {stderr}"));
    }
    if !stderr.contains(flag) || !stderr.contains(words) {
        bad.push(format!(
            "stderr does not name {flag} and {words:?}: {stderr}"
        ));
    }
    if before != snapshot(dir.path()) {
        bad.push("the folder changed".into());
    }
    (!bad.is_empty()).then(|| format!("{:?}: {}", case.args, bad.join("; ")))
}

#[test]
fn the_table_covers_every_kind() {
    for kind in KINDS {
        let n = CASES.iter().filter(|c| c.kind == *kind).count();
        assert!(n >= 4, "kind {kind}: {n} cases");
    }
    assert!(CASES.iter().all(|c| KINDS.contains(&c.kind)));
}

#[test]
#[cfg(target_os = "linux")]
fn every_case_ends_as_its_table_says() {
    let failures: Vec<String> = CASES.iter().filter_map(check).collect();
    assert!(
        failures.is_empty(),
        "{} of {} cases failed:\n{}",
        failures.len(),
        CASES.len(),
        failures.join("\n")
    );
}

#[path = "robustness_files/status.rs"]
mod status;
