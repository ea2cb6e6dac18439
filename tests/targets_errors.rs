//! Issue 53's target-list and plan CLI errors, through the binary: a list
//! whose lines end in CR alone is read line by line; a list that is not
//! UTF-8 is bad input (status 2, one line naming the file and the line);
//! a number refused is told its bounds in a few digits; a control
//! character in a cell never reaches the terminal; `plan --instrument list
//! --json` prints JSON. None of these plans anything (each row is refused
//! before its plan), so each test runs in milliseconds.

use std::path::Path;
use std::process::{Command, Output};

fn v2ref(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(args)
        .output()
        .unwrap()
}

/// `plan --targets` of a list holding `bytes`, written in `dir`.
fn plan_list(dir: &Path, bytes: &[u8]) -> Output {
    let list = dir.join("list.csv");
    std::fs::write(&list, bytes).unwrap();
    v2ref(&["plan", "--targets", list.to_str().unwrap(), "--quiet"])
}

fn stderr_of(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// The list's rows are refused each for its own cell: line 2's band is
/// none, line 3's band has no magnitude. Written with each line end, the
/// messages are the same.
#[test]
fn cr_lf_and_crlf_line_ends_are_each_read_as_line_ends() {
    let dir = tempfile::tempdir().unwrap();
    let mut seen = Vec::new();
    for end in ["\n", "\r\n", "\r"] {
        let text = ["name,band", "A,Q", "B,H", ""].join(end);
        let out = plan_list(dir.path(), text.as_bytes());
        let err = stderr_of(&out);
        assert_eq!(out.status.code(), Some(2), "{end:?}: {err}");
        assert!(
            err.contains("line 2: band: 'Q' is not one of"),
            "{end:?}: {err}"
        );
        assert!(
            err.contains("line 3: magnitude and band: give both"),
            "{end:?}: {err}"
        );
        assert_eq!(err.lines().count(), 2, "{end:?}: {err}");
        seen.push((err, out.stdout));
    }
    assert!(seen.windows(2).all(|w| w[0] == w[1]), "{seen:?}");
}

#[test]
fn a_list_that_is_not_utf8_is_bad_input_naming_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let out = plan_list(dir.path(), b"name,diameter_mas\nA,1\n\xffB,2\n");
    let err = stderr_of(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("list.csv"), "{err}");
    assert!(err.contains("line 3") && err.contains("not UTF-8"), "{err}");
}

/// A run of this many digits is no bound a reader can take in.
const UNREADABLE_DIGITS: usize = 20;

fn longest_digit_run(text: &str) -> usize {
    text.split(|c: char| !c.is_ascii_digit())
        .map(str::len)
        .max()
        .unwrap_or(0)
}

#[test]
fn a_refused_diameter_is_told_its_bounds_readably() {
    let dir = tempfile::tempdir().unwrap();
    for (cell, said) in [
        ("NaN", "NaN is not a finite number"),
        ("inf", "inf is not a finite number"),
        ("-1", "-1 is outside 0 or more"),
        ("x", "'x' is not a number"),
    ] {
        let out = plan_list(
            dir.path(),
            format!("name,diameter_mas\nA,{cell}\n").as_bytes(),
        );
        let err = stderr_of(&out);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains(&format!("diameter_mas: {said}")), "{err}");
        assert!(err.contains("0 or more"), "{err}");
        assert!(longest_digit_run(&err) < UNREADABLE_DIGITS, "{err}");
    }
}

/// An escape sequence (ESC ... recolours, OSC ... BEL retitles the
/// window, CSI as one C1 byte) in a name or the header: no control byte on
/// stdout or stderr; the row is refused naming the character.
#[test]
fn control_characters_from_the_list_never_reach_the_terminal() {
    let dir = tempfile::tempdir().unwrap();
    let control = |bytes: &[u8]| {
        let text = String::from_utf8_lossy(bytes);
        text.chars()
            .find(|c| c.is_control() && *c != '\n')
            .map(|c| c.escape_unicode().to_string())
    };
    for name in ["\u{1b}[31mRED", "\u{1b}]0;title\u{7}", "bet\u{9b}2JAri"] {
        let out = plan_list(dir.path(), format!("name,band\n{name},Q\n").as_bytes());
        let err = stderr_of(&out);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert_eq!(control(&out.stderr), None, "stderr: {err:?}");
        assert_eq!(control(&out.stdout), None, "stdout");
        assert!(err.contains("name: holds the control character"), "{err}");
    }
    let out = plan_list(dir.path(), b"name,b\x1b[2Jand\nA,H\n");
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(control(&out.stderr), None, "{:?}", stderr_of(&out));
    assert!(
        stderr_of(&out).contains("b\\u{1b}[2Jand"),
        "{}",
        stderr_of(&out)
    );
}

#[test]
fn plan_instrument_list_json_prints_the_presets_as_json() {
    let out = v2ref(&["plan", "--instrument", "list", "--json"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr_of(&out));
    let listed: serde_json::Value = serde_json::from_slice(&out.stdout).expect("stdout is JSON");
    let names: Vec<&str> = listed
        .as_array()
        .unwrap()
        .iter()
        .map(|i| i["name"].as_str().unwrap())
        .collect();
    let presets = v2ref_commands::plan::instrument::INSTRUMENTS;
    assert_eq!(names, presets.map(|i| i.name));
    assert_eq!(listed[0]["frame_rate_hz"], presets[0].frame_rate_hz);
}
