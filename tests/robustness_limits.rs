//! Limits of the machine, third round (issue 35): under a process limit
//! (`RLIMIT_NPROC`) a run gets fewer threads than asked, says so on stderr
//! and gives the same answer (it panicked: rayon's global pool could not
//! start); `RAYON_NUM_THREADS` is capped like `--threads`; a progress bar
//! whose redraw thread is refused does not crash the run.
//!
//! A process limit binds only a user other than root, so each run is made
//! as `nobody` (uid 65534) by a test running as root; run as another user,
//! the tests say so and check nothing (CI runs as root).

use std::os::unix::process::CommandExt as _;
use std::process::{Command, Output};

const NOBODY: libc::uid_t = 65534;

/// The limit counts every process of the user: one test's runs at a time.
static ONE_USER_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// `v2ref args` as `nobody` with at most `tasks` processes and threads;
/// None when this test cannot change user.
fn limited(tasks: u64, env: &[(&str, &str)], args: &[&str]) -> Option<Output> {
    // SAFETY: reads this process's real user id; no memory is involved.
    if unsafe { libc::getuid() } != 0 {
        eprintln!("not root: RLIMIT_NPROC cannot be tested here");
        return None;
    }
    let _alone = ONE_USER_AT_A_TIME
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_v2ref"));
    cmd.args(args).envs(env.iter().copied()).current_dir("/");
    // SAFETY: between fork and exec the closure only makes three system
    // calls (async-signal-safe), allocates nothing and takes no lock.
    unsafe {
        cmd.pre_exec(move || {
            let limit = libc::rlimit {
                rlim_cur: tasks,
                rlim_max: tasks,
            };
            if libc::setgid(NOBODY) != 0
                || libc::setuid(NOBODY) != 0
                || libc::setrlimit(libc::RLIMIT_NPROC, &limit) != 0
            {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
    Some(cmd.output().unwrap())
}

/// A pseudo-terminal: its controlling side and the terminal a child writes
/// to (so that v2ref draws its progress bar).
fn pseudo_terminal() -> (std::fs::File, std::fs::File) {
    use std::os::fd::FromRawFd as _;
    // SAFETY: each call gets its arguments from the one before, checked;
    // `name` is a NUL-terminated buffer of the length given; each opened
    // descriptor is owned by exactly one File.
    unsafe {
        let master = libc::posix_openpt(libc::O_RDWR | libc::O_NOCTTY);
        assert!(master >= 0, "{}", std::io::Error::last_os_error());
        assert!(libc::grantpt(master) == 0 && libc::unlockpt(master) == 0);
        let mut name = [0 as libc::c_char; 128];
        assert_eq!(libc::ptsname_r(master, name.as_mut_ptr(), name.len()), 0);
        let slave = libc::open(name.as_ptr(), libc::O_RDWR | libc::O_NOCTTY);
        assert!(slave >= 0, "{}", std::io::Error::last_os_error());
        (
            std::fs::File::from_raw_fd(master),
            std::fs::File::from_raw_fd(slave),
        )
    }
}

/// With stderr a terminal, a run draws its progress bar, whose redraw
/// thread the process limit refuses: the bar is then redrawn only as it
/// advances, and the run answers as it does unlimited (it panicked,
/// status 101, in indicatif's `enable_steady_tick`).
#[test]
fn a_progress_bar_without_its_thread_does_not_crash() {
    // SAFETY: reads this process's real user id; no memory is involved.
    if unsafe { libc::getuid() } != 0 {
        eprintln!("not root: RLIMIT_NPROC cannot be tested here");
        return;
    }
    let free = Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(SIMULATE)
        .output()
        .unwrap();
    let (master, terminal) = pseudo_terminal();
    // The terminal's output is read as it comes (a full terminal blocks
    // its writer), until the child closes it.
    let reader = std::thread::spawn(move || {
        let mut drawn = Vec::new();
        let _ = std::io::Read::read_to_end(&mut &master, &mut drawn);
        drawn
    });
    let _alone = ONE_USER_AT_A_TIME
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_v2ref"));
    cmd.args(SIMULATE).current_dir("/").stderr(terminal);
    // SAFETY: as in `limited`: three async-signal-safe calls, no
    // allocation, no lock. The main thread and the signal thread: the
    // work runs on the main thread, and there is no room for the bar's.
    unsafe {
        cmd.pre_exec(|| {
            let limit = libc::rlimit {
                rlim_cur: 2,
                rlim_max: 2,
            };
            if libc::setgid(NOBODY) != 0
                || libc::setuid(NOBODY) != 0
                || libc::setrlimit(libc::RLIMIT_NPROC, &limit) != 0
            {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
    let out = cmd.output().unwrap();
    drop(cmd);
    let drawn = String::from_utf8_lossy(&reader.join().unwrap()).into_owned();
    assert_eq!(out.status.code(), Some(0), "{drawn}");
    assert!(drawn.contains("simulate"), "no bar was drawn: {drawn:?}");
    assert_eq!(out.stdout, free.stdout);
}

const SIMULATE: &[&str] = &["simulate", "--trials", "200", "--seed", "3", "--json"];

/// With room for one worker only, `simulate` runs on it, says so, and
/// answers what it answers on every core; `--threads 8` too.
#[test]
fn a_process_limit_gives_fewer_threads_and_the_same_answer() {
    let free = Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(SIMULATE)
        .output()
        .unwrap();
    assert!(free.status.success());
    for threads in ["0", "8"] {
        let args: Vec<&str> = SIMULATE
            .iter()
            .copied()
            .chain(["--threads", threads])
            .collect();
        // The main thread, the signal thread and one more.
        let Some(out) = limited(3, &[], &args) else {
            return;
        };
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "--threads {threads}: {err}");
        assert!(err.contains("note: the system gave 1 of"), "{err}");
        assert_eq!(out.stdout, free.stdout, "--threads {threads}");
    }
}

/// `RAYON_NUM_THREADS=999` starts no more threads than `--threads` may ask
/// for: under a limit a little above that cap, no thread is refused.
#[test]
fn rayon_num_threads_is_capped_like_threads() {
    let cap = v2ref_core::montecarlo::max_threads() as u64;
    let env = [("RAYON_NUM_THREADS", "999")];
    let Some(out) = limited(cap + 4, &env, SIMULATE) else {
        return;
    };
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(!err.contains("note"), "{err}");
}
