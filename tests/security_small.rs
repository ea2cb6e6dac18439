//! Issue 43's smaller findings, one test each (tests/README.md, "Issue
//! 43, smaller findings", lists them with what each did on 4865b29): the
//! OIFITS reader within the memory budget and a bounded header, rows of
//! no listed target, an ambiguous `--target`, more HDUs than announced,
//! a FIFO as `--input`, negative numbers with exponents, leap seconds and
//! over-long dates, a truth's negative variance, `plan --svg` with nothing
//! to plot, fractional seeds, and the progress bar on a dumb terminal.
//!
//! The OIFITS files are made here byte by byte (FITS 4.0 binary tables):
//! a pipeline's file, not v2ref's writer's.

use std::path::Path;
use std::process::Command;

use crate::run::v2ref;

/// One 80-byte card.
fn card(text: &str) -> Vec<u8> {
    assert!(text.len() <= 80, "{text}");
    format!("{text:<80}").into_bytes()
}

/// `KEY = value` (the value as FITS writes it: `'text'`, `T`, a number).
fn key(k: &str, v: &str) -> Vec<u8> {
    card(&format!("{k:<8}= {v:>20}"))
}

/// A header of `cards` and `END`, then `data`, each padded to 2880-byte blocks.
fn hdu(cards: &[Vec<u8>], data: &[u8]) -> Vec<u8> {
    let mut out: Vec<u8> = cards.concat();
    out.extend(card("END"));
    out.resize(out.len().next_multiple_of(2880), b' ');
    let mut d = data.to_vec();
    d.resize(d.len().next_multiple_of(2880), 0);
    out.extend(d);
    out
}

fn primary(extra: &[Vec<u8>]) -> Vec<u8> {
    let mut cards = vec![key("SIMPLE", "T"), key("BITPIX", "8"), key("NAXIS", "0")];
    cards.extend_from_slice(extra);
    hdu(&cards, &[])
}

/// A binary table `extname` of `columns` (TTYPE, TFORM, bytes per row),
/// its keywords `extra`, rows already encoded big-endian.
fn table(extname: &str, extra: &[Vec<u8>], columns: &[(&str, &str)], rows: &[Vec<u8>]) -> Vec<u8> {
    let width = rows.first().map_or(0, Vec::len);
    let mut cards = vec![
        key("XTENSION", "'BINTABLE'"),
        key("BITPIX", "8"),
        key("NAXIS", "2"),
        key("NAXIS1", &width.to_string()),
        key("NAXIS2", &rows.len().to_string()),
        key("PCOUNT", "0"),
        key("GCOUNT", "1"),
        key("TFIELDS", &columns.len().to_string()),
    ];
    for (n, (name, form)) in columns.iter().enumerate() {
        cards.push(key(&format!("TTYPE{}", n + 1), &format!("'{name}'")));
        cards.push(key(&format!("TFORM{}", n + 1), &format!("'{form}'")));
    }
    cards.push(key("EXTNAME", &format!("'{extname}'")));
    cards.extend_from_slice(extra);
    hdu(&cards, &rows.concat())
}

/// A pipeline's OIFITS v2 file: OI_TARGET of `targets` (id, name), one
/// OI_WAVELENGTH at 2.2 µm, one OI_VIS2 of `rows` (TARGET_ID, V²), a
/// minute apart; `primary_extra` in the primary header.
fn oifits(targets: &[(i16, &str)], rows: &[(i16, f64)], primary_extra: &[Vec<u8>]) -> Vec<u8> {
    let revn = key("OI_REVN", "2");
    let ins = key("INSNAME", "'PIPE'");
    let target_rows: Vec<Vec<u8>> = targets
        .iter()
        .map(|(id, name)| {
            let mut r = id.to_be_bytes().to_vec();
            r.extend(format!("{name:<16}").into_bytes());
            r
        })
        .collect();
    let vis2_rows: Vec<Vec<u8>> = rows
        .iter()
        .enumerate()
        .map(|(i, (id, v2))| {
            let mut r = id.to_be_bytes().to_vec();
            r.extend((60_000.0 + i as f64 / 1440.0).to_be_bytes());
            r.extend(v2.to_be_bytes());
            r.extend(0.1f64.to_be_bytes());
            r.push(b'F');
            r
        })
        .collect();
    [
        primary(primary_extra),
        table(
            "OI_TARGET",
            std::slice::from_ref(&revn),
            &[("TARGET_ID", "1I"), ("TARGET", "16A")],
            &target_rows,
        ),
        table(
            "OI_WAVELENGTH",
            &[revn.clone(), ins.clone()],
            &[("EFF_WAVE", "1E")],
            &[2.2e-6f32.to_be_bytes().to_vec()],
        ),
        table(
            "OI_VIS2",
            &[revn, ins],
            &[
                ("TARGET_ID", "1I"),
                ("MJD", "1D"),
                ("VIS2DATA", "1D"),
                ("VIS2ERR", "1D"),
                ("FLAG", "1L"),
            ],
            &vis2_rows,
        ),
    ]
    .concat()
}

const ROWS: usize = 8;

/// A synth set of `ROWS` rows in `dir` (made once): its sidecar.
fn sidecar(dir: &Path) -> String {
    let stem = dir.join("set").display().to_string();
    if dir.join("set.json").exists() {
        return format!("{stem}.json");
    }
    let rows = ROWS.to_string();
    let (code, _, err) = v2ref(&[
        "synth",
        "--out",
        &stem,
        "--rows",
        &rows,
        "--samples",
        "32",
        "--quiet",
    ]);
    assert_eq!(code, 0, "{err}");
    format!("{stem}.json")
}

/// `score --estimator v2_sq` of the OIFITS `bytes` written to `dir/name`.
fn score_oifits(dir: &Path, name: &str, bytes: &[u8], extra: &[&str]) -> (i32, String) {
    let side = sidecar(dir);
    let file = dir.join(name);
    std::fs::write(&file, bytes).unwrap();
    let mut args = vec![
        "score",
        "--sidecar",
        &side,
        "--estimates",
        file.to_str().unwrap(),
        "--estimator",
        "v2_sq",
    ];
    args.extend_from_slice(extra);
    let (code, _, err) = v2ref(&args);
    (code, err)
}

fn one_line_refusal(code: i32, err: &str, words: &[&str]) {
    assert_eq!(code, 2, "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    for w in words {
        assert!(err.contains(w), "{w:?} not in {err}");
    }
}

#[test]
fn a_gzip_inflating_past_the_memory_budget_is_refused_naming_it() {
    // 900 gzip members of 1 MiB of zeros each: a 1 MB file that inflates
    // to 900 MiB (4865b29 held it all, then called it "not FITS").
    let dir = tempfile::tempdir().unwrap();
    let mut gzip = Command::new("gzip")
        .args(["-c", "-9"])
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .expect("gzip runs");
    use std::io::Write;
    let mut stdin = gzip.stdin.take().unwrap();
    stdin.write_all(&vec![0u8; 1 << 20]).unwrap();
    drop(stdin);
    let member = gzip.wait_with_output().unwrap().stdout;
    let bomb = member.repeat(900);
    assert!(bomb.len() < 2 << 20, "{}", bomb.len());
    let (code, err) = score_oifits(
        dir.path(),
        "bomb.fits.gz",
        &bomb,
        &["--max-memory-gib", "0.05"],
    );
    one_line_refusal(
        code,
        &err,
        &["--estimates", "memory budget", "--max-memory-gib"],
    );
    // The environment's budget, as Python's readers take it.
    let side = sidecar(dir.path());
    let out = Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(["score", "--sidecar", &side, "--estimates"])
        .arg(dir.path().join("bomb.fits.gz"))
        .env("V2REF_MAX_MEMORY_GIB", "0.05")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    one_line_refusal(out.status.code().unwrap(), &err, &["V2REF_MAX_MEMORY_GIB"]);
}

#[test]
fn a_plain_oifits_over_the_budget_is_refused_from_its_size() {
    let dir = tempfile::tempdir().unwrap();
    let mut big = primary(&[]);
    big.resize((64usize << 20).next_multiple_of(2880), 0);
    let (code, err) = score_oifits(dir.path(), "big.fits", &big, &["--max-memory-gib", "0.01"]);
    one_line_refusal(code, &err, &["memory budget", "0.01 GiB"]);
}

#[test]
fn a_header_of_400000_cards_is_refused_by_the_bound() {
    let dir = tempfile::tempdir().unwrap();
    let filler: Vec<Vec<u8>> = (0..400_000)
        .map(|i| key(&format!("K{}", i % 10_000_000), "1"))
        .collect();
    let file = oifits(&[(1, "STAR")], &[(1, 0.5); ROWS], &filler);
    let (code, err) = score_oifits(dir.path(), "long.fits", &file, &[]);
    one_line_refusal(code, &err, &["HDU 1", "100000 cards"]);
}

#[test]
fn a_table_of_999_columns_and_a_long_header_is_read() {
    // Every keyword looked up once per column: the index keeps this linear.
    let mut filler: Vec<Vec<u8>> = (0..90_000).map(|i| key(&format!("H{i}"), "1")).collect();
    filler.push(key("V2R_EST", "'V2SQ'"));
    let names: Vec<String> = (0..999).map(|i| format!("C{i}")).collect();
    let columns: Vec<(&str, &str)> = names.iter().map(|n| (n.as_str(), "1B")).collect();
    let bytes = [
        primary(&[]),
        table("EXTRA", &filler, &columns, &[vec![7u8; 999]]),
    ]
    .concat();
    let hdus = v2ref_oifits::fits::parse(&bytes).unwrap();
    let t = v2ref_oifits::table::Table::new(&hdus[1]).unwrap();
    assert_eq!(t.columns.len(), 999);
    assert_eq!(t.columns[998].name, "C998");
    assert_eq!(hdus[1].header.str("V2R_EST"), Some("V2SQ"));
}

#[test]
fn rows_of_a_target_absent_from_oi_target_are_refused_with_their_row() {
    let dir = tempfile::tempdir().unwrap();
    let mut rows = vec![(1i16, 0.5); ROWS];
    rows[3].0 = 7;
    let file = oifits(&[(1, "STAR")], &rows, &[]);
    let (code, err) = score_oifits(dir.path(), "lost.fits", &file, &["--target", "STAR"]);
    one_line_refusal(code, &err, &["HDU 4", "row 4", "TARGET_ID 7", "OI_TARGET"]);
    // Every row of an unlisted target (4865b29 scored them).
    let file = oifits(&[(1, "STAR")], &[(7, 0.5); ROWS], &[]);
    let (code, err) = score_oifits(dir.path(), "lost.fits", &file, &[]);
    one_line_refusal(code, &err, &["row 1", "TARGET_ID 7"]);
}

#[test]
fn a_target_number_that_is_another_targets_name_is_ambiguous() {
    // Target 1 is named "2"; target 2 is STAR. `--target 2` picked the
    // one named "2" on 4865b29 without a word.
    let dir = tempfile::tempdir().unwrap();
    let rows: Vec<(i16, f64)> = (0..2 * ROWS).map(|r| (1 + (r % 2) as i16, 0.5)).collect();
    let file = oifits(&[(1, "2"), (2, "STAR")], &rows, &[]);
    let (code, err) = score_oifits(dir.path(), "two.fits", &file, &["--target", "2"]);
    one_line_refusal(
        code,
        &err,
        &["--target", "ambiguous", "TARGET_ID 1", "TARGET_ID 2"],
    );
    // Either, named unambiguously, is read.
    for name in ["STAR", "1"] {
        let (code, err) = score_oifits(dir.path(), "two.fits", &file, &["--target", name]);
        assert!(code == 0 || code == 1, "{name}: {err}");
    }
}

#[test]
fn more_hdus_than_announced_is_not_called_truncated() {
    // Issue 53: an HDU count other than V2R_NHDU, in a file that is not
    // the first HDUs of those v2ref writes (so not a cut one), was edited:
    // read, with a note saying so (refused before).
    let dir = tempfile::tempdir().unwrap();
    for (written, change) in [("3", "added"), ("5", "removed")] {
        let file = oifits(
            &[(1, "STAR")],
            &[(1, 0.5); ROWS],
            &[key("V2R_NHDU", written)],
        );
        let (code, err) = score_oifits(dir.path(), "edited.fits", &file, &[]);
        assert!(code == 0 || code == 1, "{err}");
        let note = format!("written with {written} HDUs and holds 4: HDUs were {change}");
        assert!(err.contains(&note), "{note:?} not in {err}");
        assert!(!err.contains("truncated"), "{err}");
    }
}

#[test]
fn a_fifo_as_input_is_refused_without_waiting() {
    // 4865b29 opened it twice (its shape, then its values): with no
    // writer it waited for ever, with one it read nothing the second time.
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("rows.csv");
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    let mut child = Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(["estimate", "--samples", "32", "--input"])
        .arg(&fifo)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let start = std::time::Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > std::time::Duration::from_secs(30) {
            child.kill().unwrap();
            panic!("estimate --input FIFO still waits after 30 s");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    one_line_refusal(
        out.status.code().unwrap(),
        &err,
        &["--input", "FIFO", "regular file"],
    );
}

#[test]
fn negative_numbers_with_a_signed_exponent_are_numbers() {
    // clap's test of a negative number takes -1e3 but not -1e-3, which it
    // split into flags: "unexpected argument '-1' found" on 4865b29.
    let dir = tempfile::tempdir().unwrap();
    let stem = dir.path().join("set").display().to_string();
    let synth = |stem: &str, ra: &str, dec: &str| {
        v2ref(&[
            "synth",
            "--out",
            stem,
            "--rows",
            "4",
            "--samples",
            "8",
            "--quiet",
            "--oifits",
            "--ra-deg",
            ra,
            "--dec-deg",
            dec,
        ])
    };
    let (code, _, err) = synth(&stem, "1e+1", "-1e-3");
    assert_eq!(code, 0, "{err}");
    // The value reaches its own check: -1e+3 degrees is out of range.
    let (code, _, err) = synth(&format!("{stem}2"), "10", "-1e+3");
    one_line_refusal(code, &err, &["--dec-deg", "-90 to 90"]);
    let (code, _, err) = v2ref(&["snr", "--dispersion-pp-rad", "-2.5E-1", "--json"]);
    assert_eq!(code, 0, "{err}");
}

#[test]
fn a_leap_second_is_a_date_and_an_over_long_date_is_refused_not_cut() {
    let dir = tempfile::tempdir().unwrap();
    let stem = |n: &str| dir.path().join(n).display().to_string();
    let synth = |stem: &str, date: &str| {
        v2ref(&[
            "synth",
            "--out",
            stem,
            "--rows",
            "4",
            "--samples",
            "8",
            "--quiet",
            "--oifits",
            "--date",
            date,
        ])
    };
    let (code, _, err) = synth(&stem("leap"), "2016-12-31T23:59:60.5");
    assert_eq!(code, 0, "{err}");
    let truth = std::fs::read(dir.path().join("leap.truth.fits")).unwrap();
    let text = String::from_utf8_lossy(&truth);
    assert!(
        text.contains("'2016-12-31T23:59:60.5'"),
        "DATE-OBS as given"
    );
    // Only 23:59:60, and only where UTC inserts leap seconds.
    for bad in ["2016-12-30T23:59:60", "2016-12-31T23:58:60"] {
        let (code, _, err) = synth(&stem("bad"), bad);
        one_line_refusal(code, &err, &["--date", "leap second"]);
    }
    // 80 digits of a second were cut to fit the card on 4865b29.
    let long = format!("2026-11-26T00:00:01.{}", "1".repeat(80));
    let (code, _, err) = synth(&stem("long"), &long);
    one_line_refusal(code, &err, &["--date", "at most 9 digits"]);
    assert!(!dir.path().join("long.truth.fits").exists());
}

#[test]
fn plan_svg_with_nothing_to_plot_is_bad_input() {
    // 4865b29: status 74, as if the file could not be written.
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("plan.svg");
    let (code, _, err) = v2ref(&["plan", "--svg", svg.to_str().unwrap(), "--fringe-hz", "100"]);
    one_line_refusal(code, &err, &["--svg", "nothing to plot", "--fringe-hz"]);
    assert!(!svg.exists());
}

#[test]
fn a_seed_that_is_not_a_whole_number_is_refused_not_rounded() {
    let dir = tempfile::tempdir().unwrap();
    let synth = |name: &str, seed: &str| {
        let stem = dir.path().join(name).display().to_string();
        v2ref(&[
            "synth",
            "--out",
            &stem,
            "--rows",
            "4",
            "--samples",
            "8",
            "--quiet",
            "--seed",
            seed,
        ])
    };
    // A float rounds 1.0000000000000001 to 1 (4865b29 took it as seed 1).
    for bad in [
        "1.5",
        "1.0000000000000001",
        "1e-1",
        "9007199254740993.5",
        "1e3.5",
    ] {
        let (code, _, err) = synth("bad", bad);
        assert_eq!(code, 2, "{bad}: {err}");
        assert!(
            err.contains("--seed") && err.contains("whole number"),
            "{bad}: {err}"
        );
    }
    for (name, good) in [
        ("a", "1e6"),
        ("b", "1_000_000"),
        ("c", "1.5e3"),
        ("d", "1000000"),
    ] {
        let (code, _, err) = synth(name, good);
        assert_eq!(code, 0, "{good}: {err}");
    }
    let bytes = |n: &str| std::fs::read(dir.path().join(format!("{n}.npy"))).unwrap();
    assert_eq!(bytes("a"), bytes("b"));
    assert_eq!(bytes("a"), bytes("d"));
    // Exact beyond 2^53: the digits, not a float's neighbour.
    let (code, _, err) = synth("e", "9007199254740993");
    assert_eq!(code, 0, "{err}");
    let (code, _, err) = synth("f", "9.007199254740993e15");
    assert_eq!(code, 0, "{err}");
    assert_eq!(bytes("e"), bytes("f"));
}

/// Runs `v2ref ARGS` with its standard error on a pseudo-terminal and
/// `TERM=term`: what it wrote there.
#[cfg(unix)]
fn stderr_on_a_terminal(args: &[&str], term: &str) -> Vec<u8> {
    use std::io::Read;
    use std::os::fd::FromRawFd;
    let (mut master, mut slave) = (-1, -1);
    // SAFETY: openpty writes two descriptors; null name, termios, winsize.
    let r = unsafe {
        libc::openpty(
            &mut master,
            &mut slave,
            std::ptr::null_mut(),
            std::ptr::null(),
            std::ptr::null(),
        )
    };
    assert_eq!(r, 0, "openpty");
    // SAFETY: both descriptors are ours, each owned once from here.
    let (master, slave) = unsafe {
        (
            std::fs::File::from_raw_fd(master),
            std::fs::File::from_raw_fd(slave),
        )
    };
    let status = Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(args)
        .env("TERM", term)
        .env("NO_COLOR", "1")
        .stdout(std::process::Stdio::null())
        .stderr(slave)
        .status()
        .unwrap();
    assert!(status.success());
    let mut out = Vec::new();
    // SAFETY: the master's flags are read and set non-blocking: what is
    // buffered is read, then EAGAIN ends the read.
    unsafe {
        let flags = libc::fcntl(std::os::fd::AsRawFd::as_raw_fd(&master), libc::F_GETFL);
        libc::fcntl(
            std::os::fd::AsRawFd::as_raw_fd(&master),
            libc::F_SETFL,
            flags | libc::O_NONBLOCK,
        );
    }
    let mut buf = [0u8; 4096];
    let mut master = master;
    while let Ok(n) = master.read(&mut buf) {
        if n == 0 {
            break;
        }
        out.extend_from_slice(&buf[..n]);
    }
    out
}

#[cfg(unix)]
#[test]
fn a_dumb_terminal_gets_no_escape_codes() {
    // A run of about a second, long enough for the bar to be drawn.
    let args = [
        "simulate",
        "--trials",
        "3000000",
        "--samples",
        "32",
        "--json",
    ];
    let dumb = stderr_on_a_terminal(&args, "dumb");
    assert!(!dumb.contains(&0x1b), "{}", String::from_utf8_lossy(&dumb));
    // Power: the same run on a capable terminal draws its bar with them.
    let capable = stderr_on_a_terminal(&args, "xterm");
    assert!(
        capable.contains(&0x1b),
        "{}",
        String::from_utf8_lossy(&capable)
    );
}

#[test]
fn a_truth_with_a_negative_variance_is_refused_not_scored() {
    let dir = tempfile::tempdir().unwrap();
    let side = sidecar(dir.path());
    let est = dir.path().join("est.csv");
    let (code, _, err) = v2ref(&[
        "estimate",
        "--sidecar",
        &side,
        "--out",
        est.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let score = || {
        v2ref(&[
            "score",
            "--sidecar",
            &side,
            "--estimates",
            est.to_str().unwrap(),
        ])
    };
    let (code, _, err) = score();
    assert!(code == 0 || code == 1, "{err}");
    // Every convention's V2² variance made negative (4865b29 scored it).
    let mut json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&side).unwrap()).unwrap();
    for window in json["truth"]["windows"].as_array_mut().unwrap() {
        for convention in window["conventions"].as_array_mut().unwrap() {
            let var = convention["v2_sq"]["var"].as_f64().unwrap();
            convention["v2_sq"]["var"] = serde_json::json!(-var);
        }
    }
    std::fs::write(&side, serde_json::to_string_pretty(&json).unwrap()).unwrap();
    let (code, _, err) = score();
    one_line_refusal(code, &err, &["var is -", "variance", ">= 0"]);
}
