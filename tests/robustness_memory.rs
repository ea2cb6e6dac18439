//! Memory, third round (issue 35): what a `.npy` header announces beyond
//! the memory budget (half the physical memory, `V2REF_MAX_MEMORY_GIB`) is
//! refused from the header, before any data are read (it was read until
//! the allocator aborted); the CSV readers hold parsed values, not the
//! file's text (peak memory of `estimate` measured against the file).

use std::path::Path;
use std::process::{Command, Output};

fn v2ref(dir: &Path, env: &[(&str, &str)], args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .current_dir(dir)
        .envs(env.iter().copied())
        .args(args)
        .output()
        .unwrap()
}

/// A `.npy` of `<f8` whose header claims `shape` and whose data are that
/// long (a sparse file: nothing is written but the header).
fn sparse_npy(path: &Path, shape: &str, data_bytes: u64) {
    let mut h = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': {shape}, }}");
    while (10 + h.len() + 1) % 64 != 0 {
        h.push(' ');
    }
    h.push('\n');
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    bytes.extend_from_slice(&(h.len() as u16).to_le_bytes());
    bytes.extend_from_slice(h.as_bytes());
    let f = std::fs::File::create(path).unwrap();
    std::io::Write::write_all(&mut &f, &bytes).unwrap();
    f.set_len(bytes.len() as u64 + data_bytes).unwrap();
}

fn refused_by_budget(out: &Output, flag: &str) {
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains(flag) && err.contains("memory budget") && err.contains("header"),
        "{err}"
    );
}

/// A 512 GiB and a 256 GiB `.npy` (sparse) are refused from its header by `estimate`
/// (whose answer it would not fit) and `score` (whose columns would not),
/// at once.
#[test]
fn a_header_beyond_the_memory_is_refused_from_the_header() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let set = [
        "synth",
        "--rows",
        "4",
        "--samples",
        "16",
        "--quiet",
        "--out",
        "set",
    ];
    assert!(v2ref(d, &[], &set).status.success());
    let rows: u64 = 1 << 34;
    sparse_npy(&d.join("huge_in.npy"), "(4294967296, 16)", (1 << 32) * 128);
    sparse_npy(&d.join("huge_est.npy"), &format!("({rows}, 2)"), rows * 16);
    let start = std::time::Instant::now();
    let estimate = v2ref(d, &[], &["estimate", "--input", "huge_in.npy"]);
    let score = [
        "score",
        "--sidecar",
        "set.json",
        "--estimates",
        "huge_est.npy",
    ];
    let score = v2ref(d, &[], &score);
    // Both from the header: well under a second each (reading 256 GiB is
    // minutes at the fastest).
    assert!(start.elapsed().as_secs() < 20, "{:?}", start.elapsed());
    refused_by_budget(&estimate, "--input");
    refused_by_budget(&score, "--estimates");
}

/// The budget is stated and can be set: 1 MiB refuses an estimates file
/// of 1.6 MB that the default budget takes.
#[test]
fn the_memory_budget_can_be_set() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let rows = 100_000u64;
    sparse_npy(&d.join("e.npy"), &format!("({rows}, 2)"), rows * 16);
    let set = [
        "synth",
        "--rows",
        "4",
        "--samples",
        "16",
        "--quiet",
        "--out",
        "set",
    ];
    assert!(v2ref(d, &[], &set).status.success());
    let score = ["score", "--sidecar", "set.json", "--estimates", "e.npy"];
    let small = v2ref(d, &[("V2REF_MAX_MEMORY_GIB", "0.001")], &score);
    refused_by_budget(&small, "--estimates");
    // With the default budget the file is read (and refused for its rows,
    // 100000 against the set's 4: not for its size).
    let err = String::from_utf8_lossy(&v2ref(d, &[], &score).stderr).into_owned();
    assert!(!err.contains("memory budget"), "{err}");
}

/// `--max-memory-gib` sets the budget of `score` and `estimate`, in place
/// of `V2REF_MAX_MEMORY_GIB`; a budget out of range, as a flag or in the
/// environment, is refused with status 2, naming it and the range.
#[test]
fn the_memory_budget_flag_sets_the_budget_and_wins_over_the_environment() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let rows = 100_000u64;
    sparse_npy(&d.join("e.npy"), &format!("({rows}, 2)"), rows * 16);
    sparse_npy(&d.join("in.npy"), &format!("({rows}, 16)"), rows * 128);
    let set = [
        "synth",
        "--rows",
        "4",
        "--samples",
        "16",
        "--quiet",
        "--out",
        "set",
    ];
    assert!(v2ref(d, &[], &set).status.success());
    let score = |budget: &str| {
        let args = ["score", "--sidecar", "set.json", "--estimates", "e.npy"];
        let mut args = args.to_vec();
        args.extend(["--max-memory-gib", budget]);
        args.iter().map(|a| (*a).to_owned()).collect::<Vec<_>>()
    };
    let run = |env: &[(&str, &str)], args: &[String]| {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        v2ref(d, env, &args)
    };
    let big_env = [("V2REF_MAX_MEMORY_GIB", "1000")];
    refused_by_budget(&run(&big_env, &score("0.001")), "--estimates");
    let small_env = [("V2REF_MAX_MEMORY_GIB", "0.001")];
    let err = String::from_utf8_lossy(&run(&small_env, &score("1")).stderr).into_owned();
    assert!(!err.contains("memory budget"), "{err}");
    // estimate holds 48 bytes of answer a row: 4.8 MB for these rows.
    let estimate = |budget: &str| {
        let args = ["estimate", "--input", "in.npy", "--max-memory-gib", budget];
        v2ref(d, &[], &args)
    };
    refused_by_budget(&estimate("0.001"), "--input");
    let err = String::from_utf8_lossy(&estimate("0.01").stderr).into_owned();
    assert!(!err.contains("memory budget"), "{err}");
    for bad in ["0", "-1", "nan", "2e6", "lots"] {
        let out = run(&[], &score(bad));
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{bad}: {err}");
        assert!(err.contains("--max-memory-gib"), "{bad}: {err}");
        assert!(err.lines().count() == 1, "{bad}: {err}");
    }
    let out = run(&[], &score("0"));
    assert!(String::from_utf8_lossy(&out.stderr).contains("above 0 and at most 1048576"));
    let plain: Vec<String> = score("1")[..5].to_vec();
    let out = run(&[("V2REF_MAX_MEMORY_GIB", "lots")], &plain);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("V2REF_MAX_MEMORY_GIB") && err.contains("above 0 and at most 1048576"),
        "{err}"
    );
}

/// The peak resident memory of `estimate` on a CSV set of `rows` rows
/// of 64 samples, and the CSV's size.
fn estimate_csv_peak(d: &Path, rows: u64) -> (u64, u64) {
    let name = format!("set{rows}");
    let set = [
        "synth",
        "--samples",
        "64",
        "--csv",
        "--quiet",
        "--out",
        &name,
    ];
    let rows_text = rows.to_string();
    let out = v2ref(d, &[], &[&set[..], &["--rows", &rows_text]].concat());
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = format!("{name}.csv");
    let size = std::fs::metadata(d.join(&csv)).unwrap().len();
    let child = Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .current_dir(d)
        .args([
            "estimate",
            "--input",
            &csv,
            "--sidecar",
            &format!("{name}.json"),
        ])
        .args(["--out", &format!("{name}.e.npy")])
        .spawn()
        .unwrap();
    let (status, peak_bytes) = wait_with_peak(child);
    assert!(status.success());
    (peak_bytes, size)
}

/// `estimate` streams a CSV a block of rows at a time, as a `.npy`: its
/// peak memory grows with the rows by the answer it holds (48 bytes a
/// row), not by the file's values (64 × 8 bytes a row, which a reader
/// holding them adds: 20 MB between these files; it held them, 2.2 × the
/// file, before). Measured as the growth between 10 000 and 40 000 rows
/// (2.9 and 11.4 MB of CSV), so that the program's own memory (its code,
/// one block of 8192 rows) cancels, in any build profile. `cargo run
/// --release -- estimate` on a CSV of 400 000 rows (114 MB) peaks at 30 MB,
/// 0.26 × the file (`/usr/bin/time -v`; it was 226 MB, 1.98 ×).
#[test]
fn estimate_streams_a_csv() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (small_peak, small_size) = estimate_csv_peak(d, 10_000);
    let (large_peak, large_size) = estimate_csv_peak(d, 40_000);
    assert!(large_size > 3 * small_size, "{small_size} {large_size}");
    let growth = large_peak.saturating_sub(small_peak);
    // The answer's growth is 30 000 × 48 bytes = 1.4 MB; 100 bytes a row
    // leaves room for the allocator and still refuses the values (512).
    let bound = 100 * 30_000;
    assert!(
        growth < bound,
        "peak {small_peak} B for 10 000 rows ({small_size} B of CSV), {large_peak} B for 40 000 ({large_size} B): growth {growth} B, bound {bound} B"
    );
}

/// A streamed CSV is refused at its fault as a CSV read whole is: a word
/// in the third block names its row and line (the header counted), a
/// short row after it is not reached, and a short row before a word is
/// named first (from the shape, before any value is read).
#[test]
fn a_streamed_csv_is_refused_at_its_first_fault() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let row = vec!["1.5"; 16].join(",");
    let mut lines: Vec<String> = vec![
        "# rows".into(),
        (0..16)
            .map(|i| format!("s{i}"))
            .collect::<Vec<_>>()
            .join(","),
    ];
    lines.extend((0..20_000).map(|_| row.clone()));
    lines[2 + 18_000] = row.replacen("1.5", "abc", 1);
    std::fs::write(d.join("word.csv"), lines.join("\n")).unwrap();
    let estimate = |file: &str| {
        let out = v2ref(d, &[], &["estimate", "--input", file, "--out", "e.csv"]);
        assert_eq!(out.status.code(), Some(2));
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    let err = estimate("word.csv");
    assert!(
        err.contains("--input")
            && err.contains("row 18001, column 1 (1-based, line 18003)")
            && err.contains("\"abc\" is not a number"),
        "{err}"
    );
    lines[2 + 19_000] = "1.5,2".into();
    std::fs::write(d.join("word_then_short.csv"), lines.join("\n")).unwrap();
    assert!(estimate("word_then_short.csv").contains("row 18001, column 1"));
    lines[2 + 100] = "1.5,2".into();
    std::fs::write(d.join("short_then_word.csv"), lines.join("\n")).unwrap();
    let err = estimate("short_then_word.csv");
    assert!(
        err.contains("row 101 (1-based, line 103)") && err.contains("2 columns"),
        "{err}"
    );
    assert!(!d.join("e.csv").exists());
}

/// Waits for `child`; its exit status and its peak resident memory, the
/// largest `VmHWM` of /proc/PID/status read every 2 ms once it runs v2ref
/// (before its exec the child shares this process's memory, whose peak
/// `wait4` would report: hundreds of MB of other tests).
fn wait_with_peak(mut child: std::process::Child) -> (std::process::ExitStatus, u64) {
    let status_file = format!("/proc/{}/status", child.id());
    let mut peak_kib = 0u64;
    loop {
        let text = std::fs::read_to_string(&status_file).unwrap_or_default();
        if text.lines().next() == Some("Name:\tv2ref") {
            let hwm = text.lines().find_map(|l| l.strip_prefix("VmHWM:"));
            let kib = hwm.and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok());
            peak_kib = peak_kib.max(kib.unwrap_or(0));
        }
        if let Some(status) = child.try_wait().unwrap() {
            assert!(peak_kib > 0, "the child's memory was never read");
            return (status, peak_kib * 1024);
        }
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
}
