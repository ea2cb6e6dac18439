//! Exit statuses a table cannot drive: full and read-only file systems
//! (a small tmpfs, where the test may mount one), a closed or full stdout,
//! `--force`, a user's folder named like a temporary, a bare `v2ref`.

use super::{run_in, snapshot, workspace};
use std::path::Path;
use std::process::{Command, Stdio};

/// A tmpfs of `kb` KiB mounted on `dir/name` (None where mounting is not
/// allowed: the cases that need one are then skipped, and say so).
struct Mount(std::path::PathBuf);

impl Mount {
    fn new(dir: &Path, name: &str, options: &str) -> Option<Mount> {
        let at = dir.join(name);
        std::fs::create_dir(&at).ok()?;
        let ok = Command::new("mount")
            .args(["-t", "tmpfs", "-o", options, "tmpfs"])
            .arg(&at)
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success());
        if ok {
            Some(Mount(at))
        } else {
            eprintln!("skipped: cannot mount a tmpfs here");
            None
        }
    }
}

impl Drop for Mount {
    fn drop(&mut self) {
        let _ = Command::new("umount").arg(&self.0).status();
    }
}

/// Interferograms big enough (2000 × 16) that their estimates fill 16 KiB.
fn big_npy(dir: &Path) {
    let data: Vec<u8> = (0..2000 * 16)
        .flat_map(|i| (100.0 + (i as f64 * 0.37).sin()).to_le_bytes())
        .collect();
    super::npy(dir, "big.npy", "(2000, 16)", &data);
}

#[test]
#[cfg(target_os = "linux")]
fn a_full_or_read_only_file_system_is_status_74_and_leaves_nothing() {
    let dir = workspace();
    big_npy(dir.path());
    let Some(full) = Mount::new(dir.path(), "full", "size=16k") else {
        return;
    };
    for out in ["full/e.csv", "full/e.npy"] {
        let (code, stdout, stderr) = run_in(
            dir.path(),
            &["estimate", "--input", "big.npy", "--out", out],
        );
        assert_eq!(code, 74, "{out}: {stderr}");
        assert!(
            stdout.is_empty() && stderr.contains("--out") && stderr.contains("space"),
            "{stderr}"
        );
        assert_eq!(
            std::fs::read_dir(&full.0).unwrap().count(),
            0,
            "a partial file stayed"
        );
    }
    let (code, _, stderr) = run_in(
        dir.path(),
        &["synth", "--out", "full/set", "--rows", "2000", "--quiet"],
    );
    assert_eq!(code, 74, "{stderr}");
    assert_eq!(
        std::fs::read_dir(&full.0).unwrap().count(),
        0,
        "a partial set stayed"
    );
    let ro = Mount::new(dir.path(), "ro", "size=64k,ro").expect("a tmpfs mounts where another did");
    for args in [
        &["estimate", "--input", "good.npy", "--out", "ro/e.csv"][..],
        &["synth", "--out", "ro/set", "--rows", "4", "--quiet"][..],
        &["reproduce", "--quick", "--out", "ro/figs", "--quiet"][..],
        &[
            "golden",
            "--update",
            "--dir",
            "ro/golden",
            "--only",
            "vectors",
        ][..],
    ] {
        let (code, _, stderr) = run_in(dir.path(), args);
        assert_eq!(code, 74, "{args:?}: {stderr}");
        assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    }
    drop(ro);
}

#[test]
#[cfg(target_os = "linux")]
fn a_full_stdout_is_74_for_every_writer() {
    let dir = workspace();
    for args in [
        &["estimate", "--input", "good.npy"][..],
        &["snr"][..],
        &["simulate", "--trials", "8", "--quiet"][..],
        &[
            "plan",
            "--fringe-hz",
            "100",
            "--stroke-um",
            "16",
            "--scans",
            "32",
            "--json",
            "--quiet",
        ][..],
    ] {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_v2ref"))
            .args(args)
            .current_dir(dir.path())
            .stdout(Stdio::from(full))
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(74), "{args:?}");
    }
}

/// A reader gone before the first write: stdout is a socket whose other
/// end is closed before the command starts (a pipe's read end closed after
/// the spawn races with a command that answers at once: under load the
/// answer was sometimes written first, and the test failed with status 0).
#[test]
fn a_closed_stdout_is_74_without_a_message() {
    let dir = workspace();
    for args in [&["bias"][..], &["estimate", "--input", "good.npy"][..]] {
        let (ours, theirs) = std::os::unix::net::UnixStream::pair().unwrap();
        drop(ours);
        let child = Command::new(env!("CARGO_BIN_EXE_v2ref"))
            .args(args)
            .current_dir(dir.path())
            .stdout(Stdio::from(std::os::fd::OwnedFd::from(theirs)))
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let out = child.wait_with_output().unwrap();
        assert_eq!(out.status.code(), Some(74), "{args:?}: {out:?}");
        assert!(
            out.stderr.is_empty(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

#[test]
fn force_replaces_a_regular_file_and_only_that() {
    let dir = workspace();
    let d = dir.path();
    std::fs::write(d.join("mine.csv"), "a user's table\n").unwrap();
    let (code, _, stderr) = run_in(
        d,
        &[
            "estimate", "--input", "good.npy", "--out", "mine.csv", "--force",
        ],
    );
    assert_eq!(code, 0, "{stderr}");
    let text = std::fs::read_to_string(d.join("mine.csv")).unwrap();
    assert!(text.starts_with("v1_sq_raw,"), "{text}");
    // --force replaces a file, never writes CSV under another format's name.
    let (code, _, stderr) = run_in(
        d,
        &[
            "estimate", "--input", "good.npy", "--out", "file.txt", "--force",
        ],
    );
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("extension"), "{stderr}");
    let text = std::fs::read_to_string(d.join("file.txt")).unwrap();
    assert_eq!(text, "a user's file\n");
    let (code, _, stderr) = run_in(
        d,
        &[
            "synth", "--out", "user", "--rows", "4", "--quiet", "--force",
        ],
    );
    assert_eq!(code, 0, "{stderr}");
    assert!(std::fs::read_to_string(d.join("user.json"))
        .unwrap()
        .contains("v2ref-synth-1"));
    // A new name needs no --force, and a second run to it does.
    let (code, _, _) = run_in(d, &["estimate", "--input", "good.npy", "--out", "new.npy"]);
    assert_eq!(code, 0);
    let before = snapshot(d);
    let (code, _, stderr) = run_in(d, &["estimate", "--input", "good.npy", "--out", "new.npy"]);
    assert_eq!(code, 2, "{stderr}");
    assert_eq!(before, snapshot(d));
}

// A user's folder named like a killed run's temporary stays while v2ref's
// own leftovers go: checked with the run of tests/reproduce.rs (a quick
// reproduction costs 10 s).

#[test]
fn a_bare_v2ref_lists_the_commands_and_how_to_get_help() {
    let dir = workspace();
    let (code, stdout, stderr) = run_in(dir.path(), &[]);
    assert_eq!(code, 2);
    assert!(stdout.is_empty());
    for word in ["Usage: v2ref <COMMAND>", "estimate", "score", "--help"] {
        assert!(stderr.contains(word), "{word}: {stderr}");
    }
}

#[test]
fn the_help_documents_every_status() {
    let dir = workspace();
    let (code, stdout, _) = run_in(dir.path(), &["--help"]);
    assert_eq!(code, 0);
    for word in ["Exit status", " 2 ", " 74 ", " 1 ", " 130 "] {
        assert!(stdout.contains(word), "{word}: {stdout}");
    }
}

/// Starts `args` in `dir`, sends SIGINT after `after`, and returns the
/// status and how long the process took to end after the signal.
#[cfg(unix)]
fn interrupt(dir: &Path, args: &[&str], after: std::time::Duration) -> (Option<i32>, f64) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(args)
        .current_dir(dir)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    std::thread::sleep(after);
    let sent = std::time::Instant::now();
    let killed = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let status = child.wait().unwrap();
    (status.code(), sent.elapsed().as_secs_f64())
}

#[test]
#[cfg(unix)]
fn ctrl_c_stops_long_runs_within_a_second_and_leaves_nothing() {
    let dir = workspace();
    let d = dir.path();
    let before = snapshot(d);
    let half = std::time::Duration::from_millis(1500);
    for args in [
        &["simulate", "--trials", "1e12", "--quiet"][..],
        &["synth", "--rows", "16777216", "--out", "huge", "--quiet"][..],
        &[
            "plan",
            "--fringe-hz",
            "1:1e6:10000",
            "--stroke-um",
            "10",
            "--stroke-um",
            "20",
            "--stroke-um",
            "30",
            "--quiet",
            "--svg",
            "plan.svg",
        ][..],
        &[
            "piston",
            "--scans",
            "131055",
            "--fringe-hz",
            "1:1e4:2000",
            "--quiet",
        ][..],
        // Last: it may end, and write, before the signal.
        &["estimate", "--input", "good.npy", "--out", "e.csv"][..],
    ] {
        let (code, took) = interrupt(d, args, half);
        // A run that ended before the signal (estimate of 2 rows) is 0.
        assert!(matches!(code, Some(130) | Some(0)), "{args:?}: {code:?}");
        assert!(took < 1.0, "{args:?}: {took} s after Ctrl-C");
        if args[0] != "estimate" {
            assert_eq!(code, Some(130), "{args:?}");
            assert_eq!(before, snapshot(d), "{args:?} left output behind");
        }
    }
}

/// The first line `v2ref ARGS` writes on stderr (the run is then
/// killed): the read waits for it, so no sleep is needed.
fn first_stderr_line(args: &[&str]) -> String {
    use std::io::BufRead;
    let dir = workspace();
    let mut child = Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(args)
        .current_dir(dir.path())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut line = String::new();
    let stderr = child.stderr.take().unwrap();
    std::io::BufReader::new(stderr)
        .read_line(&mut line)
        .unwrap();
    let _ = child.kill();
    let _ = child.wait();
    line
}

/// A long run whose stderr is no terminal (no bar, so no ETA) says once,
/// from its rate measured after its first step, how long it has left and
/// how to stop it: 1e12 trials of 128 samples are days at any rate this
/// machine reaches (the note's unit, h at the least, is > 2 h). No
/// prediction comes before the run (the old cost laws' "predicted to take"
/// note failed this test).
#[test]
fn a_long_run_says_how_long_it_has_left_at_its_measured_rate() {
    let note = first_stderr_line(&["simulate", "--trials", "1e12"]);
    let (left, rest) = note
        .strip_prefix("note: simulate: about ")
        .and_then(|n| n.split_once(" left at the present rate ("))
        .unwrap_or_else(|| panic!("{note}"));
    assert!(
        [" h", " days", " years"].iter().any(|u| left.ends_with(u)),
        "{note}"
    );
    assert!(
        rest.contains(" of 1000000000000 steps done); Ctrl-C stops it"),
        "{note}"
    );
}

/// A run that ends within the rate's probe (a short finite scan, which
/// counts no steps) says nothing on stderr.
#[test]
fn a_short_run_says_nothing_on_stderr() {
    let dir = workspace();
    let out = Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(["bias", "--finite-scan", "--samples", "1024"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert!(out.status.success());
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}
