//! Robustness of the command line, table-driven: malformed and extreme
//! invocations, each asserting the exit status, that the one-line message
//! names the flag, that nothing panics, and that no file or folder that
//! was there before the run was touched.
//!
//! Every case runs in a fresh folder holding a user's folder (`keep/`, with
//! a file in it) and a user's file (`file.txt`); after the run the folder's
//! whole content (names and bytes) must be as it was. The categories are
//! listed in [`CATEGORIES`]; `the_table_covers_every_category` keeps the
//! table at 100 cases or more.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// How a case must end.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Expect {
    /// Status 2, one line on stderr naming this text (the flag), nothing on
    /// stdout.
    Refused(&'static str),
    /// Status 0, no `null`, `NaN` or `inf` in stdout; stdout contains this.
    Answers(&'static str),
}

use Expect::{Answers, Refused};

/// One invocation: its category, arguments, and how it must end.
struct Case {
    category: &'static str,
    args: &'static [&'static str],
    expect: Expect,
}

const fn case(category: &'static str, args: &'static [&'static str], expect: Expect) -> Case {
    Case {
        category,
        args,
        expect,
    }
}

/// The categories of the table.
const CATEGORIES: &[&str] = &[
    "overflow",
    "range",
    "number",
    "count",
    "threads",
    "file",
    "output",
    "undefined",
    "usage",
];

/// The table: one row per invocation.
#[rustfmt::skip]
const CASES: &[Case] = &[
    // --- overflow: values whose intermediates would leave the f64 range.
    case("overflow", &["bias", "--wavelength-um", "1e308"], Refused("--wavelength-um")),
    case("overflow", &["bias", "--wavelength-um", "1e-300"], Refused("--wavelength-um")),
    case("overflow", &["bias", "--dispersion-pp-rad", "1e308"], Refused("--dispersion-pp-rad")),
    case("overflow", &["bias", "--dispersion-pp-rad", "-1e308"], Refused("--dispersion-pp-rad")),
    case("overflow", &["bias", "--diameter-mas", "1e300"], Refused("--diameter-mas")),
    case("overflow", &["bias", "--baseline-m", "1e300"], Refused("--baseline-m")),
    case("overflow", &["bias", "--spatial-freq-cpas", "1e300"], Refused("--spatial-freq-cpas")),
    case("overflow", &["snr", "--photons", "1e308"], Refused("--photons")),
    case("overflow", &["snr", "--read-noise", "1e308"], Refused("--read-noise")),
    case("overflow", &["snr", "--wavelength-um", "1e308"], Refused("--wavelength-um")),
    case("overflow", &["piston", "--wind-mps", "1e308", "--scans", "4"], Refused("--wind-mps")),
    case("overflow", &["piston", "--wavelength-um", "1e308", "--scans", "4"], Refused("--wavelength-um")),
    case("overflow", &["simulate", "--photons", "1e308", "--trials", "10"], Refused("--photons")),
    case("overflow", &["simulate", "--read-noise", "1e300", "--trials", "10"], Refused("--read-noise")),
    case("overflow", &["synth", "--photons", "1e308", "--out", "new/set"], Refused("--photons")),
    case("overflow", &["plan", "--wavelength-um", "1e308"], Refused("--wavelength-um")),
    case("overflow", &["plan", "--photon-rate-per-s", "1e308"], Refused("--photon-rate-per-s")),
    case("overflow", &["plan", "--samples-per-fringe", "1e308"], Refused("--samples-per-fringe")),
    case("overflow", &["plan", "--dead-time-s", "1e308"], Refused("--dead-time-s")),
    case("overflow", &["plan", "--time-budget-s", "1e308"], Refused("--time-budget-s")),
    case("overflow", &["plan", "--target-sigma-v2", "1e-300"], Refused("--target-sigma-v2")),
    case("overflow", &["bias", "--bandwidth-nm", "1e308"], Refused("--bandwidth-nm")),
    case("overflow", &["bias", "--dx-um", "1e308", "--finite-scan"], Refused("--dx-um")),
    case("overflow", &["bias", "--stroke-um", "1e308"], Refused("--stroke-um")),
    // --- range: values outside the physical range.
    case("range", &["bias", "--wavelength-um", "0"], Refused("--wavelength-um")),
    case("range", &["bias", "--wavelength-um", "-2.2"], Refused("--wavelength-um")),
    case("range", &["bias", "--wavelength-um", "1e-4"], Refused("--wavelength-um")),
    case("range", &["bias", "--wavelength-um", "2e5"], Refused("--wavelength-um")),
    case("range", &["bias", "--bandwidth-nm", "0"], Refused("--bandwidth-nm")),
    case("range", &["bias", "--bandwidth-nm", "-1"], Refused("--bandwidth-nm")),
    case("range", &["bias", "--bandwidth-nm", "4400"], Refused("--bandwidth-nm")),
    case("range", &["bias", "--diameter-mas", "0"], Refused("--diameter-mas")),
    case("range", &["bias", "--diameter-mas", "-1"], Refused("--diameter-mas")),
    case("range", &["bias", "--diameter-mas", "4e6"], Refused("--diameter-mas")),
    case("range", &["bias", "--baseline-m", "-1"], Refused("--baseline-m")),
    case("range", &["bias", "--baseline-m", "2e9"], Refused("--baseline-m")),
    case("range", &["bias", "--spatial-freq-cpas", "-3"], Refused("--spatial-freq-cpas")),
    case("range", &["bias", "--dispersion-pp-rad", "2e4"], Refused("--dispersion-pp-rad")),
    case("range", &["bias", "--dx-um", "0", "--finite-scan"], Refused("--dx-um")),
    case("range", &["bias", "--dx-um", "-0.5", "--finite-scan"], Refused("--dx-um")),
    case("range", &["bias", "--dx-um", "5", "--finite-scan"], Refused("--dx-um")),
    case("range", &["bias", "--stroke-um", "0"], Refused("--stroke-um")),
    case("range", &["bias", "--stroke-um", "-64"], Refused("--stroke-um")),
    case("range", &["snr", "--photons", "-1"], Refused("--photons")),
    case("range", &["snr", "--photons", "2e12"], Refused("--photons")),
    case("range", &["snr", "--read-noise", "-1"], Refused("--read-noise")),
    case("range", &["snr", "--visibility", "1.5"], Refused("--visibility")),
    case("range", &["snr", "--visibility", "-0.1"], Refused("--visibility")),
    case("range", &["piston", "--wind-mps", "0", "--scans", "4"], Refused("--wind-mps")),
    case("range", &["piston", "--wind-mps", "-10", "--scans", "4"], Refused("--wind-mps")),
    case("range", &["piston", "--wind-mps", "400", "--scans", "4"], Refused("--wind-mps")),
    case("range", &["piston", "--seeing-arcsec", "-1", "--scans", "4"], Refused("--seeing-arcsec")),
    case("range", &["piston", "--aperture-m", "0", "--scans", "4"], Refused("--aperture-m")),
    case("range", &["piston", "--aperture-m", "-1", "--scans", "4"], Refused("--aperture-m")),
    case("range", &["piston", "--outer-scale-m", "0", "--scans", "4"], Refused("--outer-scale-m")),
    case("range", &["piston", "--fringe-hz", "0", "--scans", "4"], Refused("--fringe-hz")),
    case("range", &["piston", "--fringe-hz", "-300", "--scans", "4"], Refused("--fringe-hz")),
    case("range", &["simulate", "--photons", "0", "--trials", "10"], Refused("--photons")),
    case("range", &["plan", "--samples-per-fringe", "1.5"], Refused("--samples-per-fringe")),
    case("range", &["plan", "--target-sigma-v2", "2"], Refused("--target-sigma-v2")),
    case("range", &["simulate", "--visibility", "2", "--trials", "10"], Refused("--visibility")),
    case("range", &["simulate", "--fringe-hz", "0", "--trials", "10"], Refused("--fringe-hz")),
    case("range", &["score", "--sidecar", "no.json", "--estimates", "no.csv", "--alpha", "2"], Refused("--")),
    // --- number: text that is not a number, or not finite.
    case("number", &["bias", "--wavelength-um", "abc"], Refused("--wavelength-um")),
    case("number", &["bias", "--wavelength-um", "nan"], Refused("--wavelength-um")),
    case("number", &["bias", "--wavelength-um", "inf"], Refused("--wavelength-um")),
    case("number", &["bias", "--wavelength-um=-inf"], Refused("--wavelength-um")),
    case("number", &["bias", "--wavelength-um", ""], Refused("--wavelength-um")),
    case("number", &["bias", "--wavelength-um", "1e999"], Refused("--wavelength-um")),
    case("number", &["bias", "--wavelength-um", "2,2"], Refused("--wavelength-um")),
    case("number", &["bias", "--bandwidth-nm", "0x10"], Refused("--bandwidth-nm")),
    case("number", &["snr", "--photons", "NaN"], Refused("--photons")),
    case("number", &["snr", "--read-noise", "infinity"], Refused("--read-noise")),
    case("number", &["piston", "--wind-mps", "ten", "--scans", "4"], Refused("--wind-mps")),
    case("number", &["bias", "--diameter-mas", "43mas"], Refused("--diameter-mas")),
    // --- count: integers (rows, samples, trials, seeds).
    case("count", &["simulate", "--trials", "1e12x"], Refused("--trials")),
    case("count", &["simulate", "--trials", "-5"], Refused("--trials")),
    case("count", &["simulate", "--trials", "1.5"], Refused("--trials")),
    case("count", &["simulate", "--trials", "0"], Refused("--trials")),
    case("count", &["simulate", "--trials", "1"], Refused("--trials")),
    case("count", &["simulate", "--trials", "1e20"], Refused("--trials")),
    case("count", &["simulate", "--trials", "99999999999999999999999"], Refused("--trials")),
    case("count", &["simulate", "--trials", ""], Refused("--trials")),
    case("count", &["bias", "--samples", "-128", "--finite-scan"], Refused("--samples")),
    case("count", &["bias", "--samples", "0", "--finite-scan"], Refused("--samples")),
    case("count", &["bias", "--samples", "1", "--finite-scan"], Refused("--samples")),
    case("count", &["bias", "--samples", "128.5", "--finite-scan"], Refused("--samples")),
    case("count", &["bias", "--samples", "1e300", "--finite-scan"], Refused("--samples")),
    case("count", &["bias", "--samples", "1e9", "--finite-scan"], Refused("--samples")),
    case("count", &["piston", "--scans", "-1"], Refused("--scans")),
    case("count", &["piston", "--scans", "0"], Refused("--scans")),
    case("count", &["piston", "--scans", "many"], Refused("--scans")),
    case("count", &["simulate", "--seed", "-1", "--trials", "10"], Refused("--seed")),
    case("count", &["simulate", "--seed", "1e30", "--trials", "10"], Refused("--seed")),
    case("count", &["piston", "--sub-samples", "-3", "--scans", "4"], Refused("--sub-samples")),
    case("count", &["synth", "--rows", "-1", "--out", "new/set"], Refused("--rows")),
    case("count", &["synth", "--rows", "0", "--out", "new/set"], Refused("--rows")),
    case("count", &["synth", "--reference-blocks", "x", "--out", "new/set"], Refused("--reference-blocks")),
    case("count", &["plan", "--scans", "-2"], Refused("--scans")),
    // --- threads: the cap and its parsing.
    case("threads", &["simulate", "--threads", "100000000", "--trials", "10"], Refused("--threads")),
    case("threads", &["simulate", "--threads", "1e8", "--trials", "10"], Refused("--threads")),
    case("threads", &["simulate", "--threads", "-1", "--trials", "10"], Refused("--threads")),
    case("threads", &["piston", "--threads", "99999", "--scans", "4"], Refused("--threads")),
    case("threads", &["plan", "--threads", "4096"], Refused("--threads")),
    case("threads", &["estimate", "--threads", "1000000", "--input", "x.npy"], Refused("--threads")),
    case("threads", &["synth", "--threads", "65536", "--out", "new/set"], Refused("--threads")),
    case("threads", &["simulate", "--threads", "2", "--trials", "10", "--quiet", "--json"], Answers("mean_v1_sq")),
    // --- file: inputs read from files.
    case("file", &["bias", "--spectrum-csv", "missing.csv"], Refused("--spectrum-csv")),
    case("file", &["bias", "--spectrum-csv", "keep"], Refused("--spectrum-csv")),
    case("file", &["bias", "--spectrum-csv", "/dev/zero"], Refused("--spectrum-csv")),
    case("file", &["bias", "--spectrum-csv", "file.txt"], Refused("--spectrum-csv")),
    case("file", &["bias", "--spectrum-csv", "bom.csv", "--json"], Answers("v_mono")),
    case("file", &["bias", "--spectrum-csv", "tiny_axis.csv"], Refused("--spectrum-csv")),
    case("file", &["bias", "--spectrum-csv", "ragged.csv"], Refused("--spectrum-csv")),
    case("file", &["bias", "--spectrum-csv", "binary.csv"], Refused("--spectrum-csv")),
    case("file", &["estimate", "--input", "missing.npy", "--samples", "16"], Refused("--input")),
    case("file", &["estimate", "--input", "file.txt", "--samples", "16"], Refused("--input")),
    case("file", &["score", "--sidecar", "missing.json", "--estimates", "file.txt"], Refused("--sidecar")),
    case("file", &["score", "--sidecar", "file.txt", "--estimates", "file.txt"], Refused("--sidecar")),
    case("file", &["score", "--sidecar", "zeros.json", "--estimates", "file.txt"], Refused("--sidecar")),
    case("file", &["estimate", "--input", "zeros.csv", "--samples", "16"], Refused("--input")),
    case("file", &["bias", "--spectrum-csv", "zeros.csv"], Refused("--spectrum-csv")),
    // --- output: folders and files that must not be lost.
    case("output", &["reproduce", "--quick", "--out", "keep"], Refused("--out")),
    case("output", &["reproduce", "--quick", "--out", "file.txt"], Refused("--out")),
    case("output", &["reproduce", "--quick", "--out", "file.txt", "--force"], Refused("--out")),
    case("output", &["reproduce", "--quick", "--out", "golden"], Refused("--out")),
    case("output", &["reproduce", "--quick", "--out", "file.txt/sub"], Refused("--out")),
    case("output", &["golden", "--check", "--dir", "keep"], Refused("--dir")),
    case("output", &["golden", "--check", "--dir", "missing"], Refused("--dir")),
    case("output", &["golden", "--check", "--update"], Refused("--")),
    case("output", &["golden"], Refused("--check")),
    // --- undefined: results with no finite value are said in words.
    case("undefined", &["bias", "--samples", "2", "--finite-scan"], Refused("--samples")),
    case("undefined", &["snr", "--no-photon-noise", "--json"], Answers("\"infinite\"")),
    case("undefined", &["snr", "--no-photon-noise"], Answers("infinite (no noise)")),
    case("undefined", &["snr", "--no-photon-noise", "--visibility", "0", "--json"], Answers("\"undefined\"")),
    case("undefined", &["snr", "--no-photon-noise", "--visibility", "0"], Answers("undefined (no signal")),
    case("undefined", &["snr", "--photons", "1e12", "--json"], Answers("snr1")),
    case("undefined", &["bias", "--wavelength-um", "1e5", "--bandwidth-nm", "1e4", "--json"], Answers("v2_sq")),
    case("undefined", &["bias", "--wavelength-um", "1e-3", "--bandwidth-nm", "0.1", "--json"], Answers("v2_sq")),
    case("undefined", &["bias", "--dispersion-pp-rad", "1e4", "--json"], Answers("v2_sq")),
    case("undefined", &["bias", "--diameter-mas", "3.6e6", "--json"], Answers("v1_sq")),
    case("undefined", &["bias", "--baseline-m", "1e9", "--json"], Answers("v1_sq")),
    case("undefined", &["piston", "--wind-mps", "343", "--scans", "4", "--json", "--quiet"], Answers("bias_v1")),
    // --- usage: the command line itself.
    case("usage", &["bias", "--no-such-flag"], Refused("--no-such-flag")),
    case("usage", &["bias", "--wavelength-um"], Refused("--wavelength-um")),
    case("usage", &["bias", "--source", "star"], Refused("--source")),
    case("usage", &["bias", "--bins", "some"], Refused("--bins")),
    case("usage", &["bias", "--baseline-m", "18", "--spatial-freq-cpas", "40"], Refused("--")),
    case("usage", &["snr", "--formula", "guess"], Refused("--formula")),
    case("usage", &["simulate", "--bias", "maybe"], Refused("--bias")),
    case("usage", &["piston", "--reference", "left"], Refused("--reference")),
    case("usage", &["nosuchcommand"], Refused("nosuchcommand")),
    case("usage", &["estimate"], Refused("--input")),
    case("usage", &["score"], Refused("--")),
];

/// A fresh working folder with a user's folder, a user's file and the CSV
/// fixtures the file cases read.
fn workspace() -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let p = dir.path();
    std::fs::create_dir(p.join("keep")).unwrap();
    std::fs::write(p.join("keep/user.txt"), "a user's notes\n").unwrap();
    std::fs::write(p.join("file.txt"), "a user's file\n").unwrap();
    std::fs::write(
        p.join("bom.csv"),
        "\u{feff}wavelength_um,weight\n2.0,1\n2.2,1\n2.4,1\n",
    )
    .unwrap();
    std::fs::write(
        p.join("tiny_axis.csv"),
        "wavenumber_per_um,weight\n1e-300,1\n2e-300,1\n",
    )
    .unwrap();
    std::fs::write(p.join("ragged.csv"), "wavelength_um,weight\n2.0,1,3\n").unwrap();
    std::fs::write(p.join("binary.csv"), [0xff_u8, 0xfe, 0x00, 0x41]).unwrap();
    // Endless inputs behind ordinary names.
    #[cfg(unix)]
    for name in ["zeros.csv", "zeros.json"] {
        std::os::unix::fs::symlink("/dev/zero", p.join(name)).unwrap();
    }
    dir
}

/// Every file under `root` with its bytes (folders as empty entries, links
/// as their targets).
fn snapshot(root: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![root.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap().flatten() {
            let path = entry.path();
            let rel = path.strip_prefix(root).unwrap().to_path_buf();
            let kind = entry.file_type().unwrap();
            if kind.is_symlink() {
                // A link's target, not what it points to (/dev/zero).
                let target = std::fs::read_link(&path).unwrap();
                out.insert(rel, target.to_string_lossy().as_bytes().to_vec());
            } else if kind.is_dir() {
                out.insert(rel, Vec::new());
                stack.push(path);
            } else {
                out.insert(rel, std::fs::read(&path).unwrap());
            }
        }
    }
    out
}

fn run_in(dir: &Path, args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Fields that are `null` when the part they describe is absent (no piston,
/// no outer scale); any other `null` would be a non-finite number.
const ABSENT_PARTS: &[&str] = &["\"piston\"", "\"piston_effect\"", "\"outer_scale_m\""];

fn is_unexplained_null(line: &str) -> bool {
    line.contains("null")
        && !ABSENT_PARTS
            .iter()
            .any(|key| line.trim_start().starts_with(key))
}

/// Checks one case; returns a description of what went wrong, if anything.
fn check(case: &Case) -> Option<String> {
    let dir = workspace();
    let before = snapshot(dir.path());
    let (code, stdout, stderr) = run_in(dir.path(), case.args);
    let args = case.args;
    let mut bad = Vec::new();
    if stderr.contains("panicked") || code == 101 {
        bad.push(format!("panicked: {stderr}"));
    }
    match case.expect {
        Refused(flag) => {
            if code != 2 {
                bad.push(format!("exit {code}, expected 2"));
            }
            if !stdout.is_empty() {
                bad.push(format!("wrote to stdout: {stdout}"));
            }
            if stderr.trim_end().lines().count() != 1 {
                bad.push(format!("not one line on stderr: {stderr}"));
            }
            if !stderr.contains(flag) {
                bad.push(format!("stderr does not name {flag}: {stderr}"));
            }
        }
        Answers(text) => {
            if code != 0 {
                bad.push(format!("exit {code}, expected 0: {stderr}"));
            }
            for word in ["NaN", "inf,", "inf\n"] {
                if stdout.contains(word) {
                    bad.push(format!("stdout holds {word:?}: {stdout}"));
                }
            }
            if let Some(line) = stdout.lines().find(|l| is_unexplained_null(l)) {
                bad.push(format!(
                    "stdout holds a null that is not an absent part: {line}"
                ));
            }
            if !stdout.contains(text) {
                bad.push(format!("stdout lacks {text:?}: {stdout}"));
            }
        }
    }
    let after = snapshot(dir.path());
    if before != after {
        let changed: Vec<_> = before
            .keys()
            .chain(after.keys())
            .filter(|k| before.get(*k) != after.get(*k))
            .collect();
        bad.push(format!("the folder changed: {changed:?}"));
    }
    (!bad.is_empty()).then(|| format!("{args:?}: {}", bad.join("; ")))
}

#[test]
fn the_table_covers_every_category() {
    assert!(CASES.len() >= 100, "{} cases", CASES.len());
    for c in CASES {
        assert!(CATEGORIES.contains(&c.category), "{}", c.category);
    }
    for cat in CATEGORIES {
        let n = CASES.iter().filter(|c| c.category == *cat).count();
        assert!(n >= 3, "category {cat}: {n} cases");
    }
}

#[test]
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

/// Runs `args` with stdout (or stderr) on `/dev/full`.
fn to_full_disk(args: &[&str], stderr_full: bool) -> i32 {
    let full = || {
        std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .expect("/dev/full")
    };
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_v2ref"));
    cmd.args(args);
    if stderr_full {
        cmd.stderr(Stdio::from(full())).stdout(Stdio::null());
    } else {
        cmd.stdout(Stdio::from(full())).stderr(Stdio::piped());
    }
    let out = cmd.output().expect("the binary runs");
    out.status.code().unwrap_or(-1)
}

#[test]
#[cfg(target_os = "linux")]
fn a_full_disk_on_stdout_is_an_error() {
    for args in [
        &["bias", "--json"][..],
        &["bias"][..],
        &["snr"][..],
        &["claims", "--help"][..],
    ] {
        let code = to_full_disk(args, false);
        assert_eq!(code, 74, "{args:?} on a full disk: exit {code}");
    }
}

#[test]
#[cfg(target_os = "linux")]
fn an_unwritable_stderr_does_not_panic() {
    for args in [
        &["bias", "--wavelength-um", "-1"][..],
        &["bias", "--nope"][..],
    ] {
        let code = to_full_disk(args, true);
        assert_eq!(code, 2, "{args:?} with stderr on a full disk: exit {code}");
    }
}

/// A reader that closes its pipe while the command computes (`claims`
/// computes for 40 s before it prints: the slow tier; a reader gone before
/// a quick answer is tests/robustness_files/status.rs).
#[test]
#[ignore = "slow tier: the full claims (40 s) behind a closed pipe"]
fn a_reader_that_closes_early_ends_with_74_and_no_message() {
    let mut child = Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(["claims"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    // Close the pipe without reading.
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(74), "{:?}", out);
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// A user's folder is refused and kept (that `reproduce` replaces a folder
/// it wrote and removes a killed run's temporaries is checked with the run
/// of tests/reproduce.rs: a quick reproduction costs 10 s).
#[test]
fn reproduce_leaves_a_users_folder_alone() {
    let dir = workspace();
    // A user's folder is refused, and kept, unless --force.
    let before = snapshot(&dir.path().join("keep"));
    let (code, _, stderr) = run_in(dir.path(), &["reproduce", "--quick", "--out", "keep"]);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("--out") && stderr.contains("--force"),
        "{stderr}"
    );
    assert_eq!(before, snapshot(&dir.path().join("keep")));
}
