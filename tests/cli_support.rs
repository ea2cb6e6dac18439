//! What several CLI test files share: running the binary with a deadline
//! (a reader that waits on a FIFO fails the test instead of hanging it),
//! making a FIFO, and the small set and one-point plan most file tests
//! start from.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// `synth` of a small set: 40 rows of 16 samples, 1000 photons, with CSV,
/// written as `set.*` in the folder it runs in.
pub(crate) const SMALL_SET: [&str; 11] = [
    "synth",
    "--rows",
    "40",
    "--photons",
    "1000",
    "--samples",
    "16",
    "--quiet",
    "--csv",
    "--out",
    "set",
];

/// The flags of a plan of one grid point with a short Monte Carlo, H band,
/// a target σ(V²) every target reaches (after `plan`).
pub(crate) const ONE_POINT_PLAN: [&str; 16] = [
    "--target-sigma-v2",
    "1e-2",
    "--wavelength-um",
    "1.65",
    "--bandwidth-nm",
    "300",
    "--fringe-hz",
    "500",
    "--stroke-um",
    "32",
    "--scans",
    "50",
    "--aperture-m",
    "1.8",
    "--quiet",
    "--seed=7",
];

/// Runs v2ref in `dir` (as `uid` when given: the cross-user cases, as
/// root), killed after `deadline_s` seconds (then the test fails, naming
/// the command): its exit status (None: ended by a signal) and stderr.
pub(crate) fn run_within(
    dir: &Path,
    args: &[&str],
    uid: Option<u32>,
    deadline_s: u64,
) -> (Option<i32>, String) {
    use std::os::unix::process::CommandExt as _;
    let mut c = Command::new(env!("CARGO_BIN_EXE_v2ref"));
    c.current_dir(dir)
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    if let Some(uid) = uid {
        c.uid(uid).gid(uid);
    }
    let mut child = c.spawn().unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(deadline_s) {
            child.kill().unwrap();
            let _ = child.wait();
            panic!("v2ref {args:?} did not end (killed after {deadline_s} s)");
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    let out = child.wait_with_output().unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Makes a FIFO at `path` (mode 0666).
pub(crate) fn mkfifo(path: &Path) {
    let c = std::ffi::CString::new(path.as_os_str().as_encoded_bytes()).unwrap();
    // SAFETY: a NUL-terminated path that lives through the call.
    assert_eq!(
        unsafe { libc::mkfifo(c.as_ptr(), 0o666) },
        0,
        "mkfifo {}",
        path.display()
    );
}
