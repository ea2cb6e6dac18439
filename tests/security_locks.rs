//! A lock name taken by a file v2ref did not make (issue 53): a hard link
//! to someone's file (the same user's, or, across users, a root-owned file
//! an unprivileged user linked there), a file of the user's own holding
//! something else than a process id, another user's symbolic link. Every
//! writer refuses it in one line naming the lock, and the file's bytes are
//! left as they were; a lock a killed run left (a process id) is taken
//! over. The cross-user cases plant as uid 65534 and run the writer as
//! root; they are skipped unless the tests run as root.

use super::cli_support::{ONE_POINT_PLAN, SMALL_SET};
use super::security_sets::{name_hash, run_as};
use std::os::unix::fs::{MetadataExt as _, PermissionsExt as _};
use std::os::unix::process::CommandExt as _;
use std::path::Path;
use std::process::Command;

/// A target list of one row for `plan --targets`.
const TARGETS: &str = "name,magnitude,band,diameter_mas,ra_deg,dec_deg\nalpha,5,H,1.0,10.5,-20\n";

/// One plan of one grid point with a short Monte Carlo, as
/// `tests/plan_targets.rs` runs it.
fn plan_args() -> Vec<&'static str> {
    let mut args = vec!["plan"];
    args.extend_from_slice(&ONE_POINT_PLAN);
    args
}

/// Each writer (its arguments after the shared ones) and the output names
/// it locks.
fn writers() -> Vec<(Vec<&'static str>, Vec<&'static str>)> {
    let mut synth = SMALL_SET.to_vec();
    *synth.last_mut().unwrap() = "new";
    let plan = |extra: &[&'static str]| {
        let mut args = plan_args();
        args.extend_from_slice(extra);
        args
    };
    let mut targets = plan_args();
    targets.extend_from_slice(&[
        "--throughput",
        "0.01",
        "--targets",
        "list.csv",
        "--out",
        "table.csv",
    ]);
    vec![
        (
            synth,
            vec!["new.npy", "new.csv", "new.json", "new.truth.fits"],
        ),
        (
            vec!["estimate", "--sidecar", "set.json", "--out", "est.csv"],
            vec!["est.csv"],
        ),
        (
            plan(&["--fringe-hz", "1000", "--svg", "p.svg"]),
            vec!["p.svg"],
        ),
        (plan(&["--oifits", "p.fits"]), vec!["p.fits"]),
        (targets, vec!["table.csv"]),
        (
            // --force: `gd` holds the planted lock, not golden data.
            vec![
                "golden", "--update", "--only", "vectors", "--dir", "gd", "--force",
            ],
            vec!["gd/vectors"],
        ),
        (vec!["reproduce", "--quick", "--out", "rep"], vec!["rep"]),
    ]
}

/// A sticky shared folder (1777) with a set (`set.*`) and a target list.
fn shared_folder() -> (tempfile::TempDir, std::path::PathBuf) {
    let root = tempfile::tempdir().unwrap();
    std::fs::set_permissions(root.path(), std::fs::Permissions::from_mode(0o755)).unwrap();
    let shared = root.path().join("shared");
    std::fs::create_dir(&shared).unwrap();
    std::fs::set_permissions(&shared, std::fs::Permissions::from_mode(0o1777)).unwrap();
    assert_eq!(run_as(&shared, &SMALL_SET, None).0, Some(0));
    std::fs::write(shared.join("list.csv"), TARGETS).unwrap();
    // The golden folder, world-writable as the shared one: its vectors'
    // lock is planted in it.
    std::fs::create_dir(shared.join("gd")).unwrap();
    std::fs::set_permissions(shared.join("gd"), std::fs::Permissions::from_mode(0o1777)).unwrap();
    (root, shared)
}

/// The lock of the output `name` (a path in `dir`).
fn lock_of(dir: &Path, name: &str) -> std::path::PathBuf {
    let target = dir.join(name);
    let file = target.file_name().unwrap().to_str().unwrap();
    target
        .parent()
        .unwrap()
        .join(format!(".v2ref-lock-{}", name_hash(file)))
}

/// Runs every writer with `plant(lock path)` done under each of its lock
/// names first, and checks each refused in one line naming a lock; the
/// planted locks are removed after each writer.
fn every_writer_refuses(shared: &Path, plant: &dyn Fn(&Path)) {
    for (args, names) in writers() {
        let locks: Vec<_> = names.iter().map(|n| lock_of(shared, n)).collect();
        for lock in &locks {
            plant(lock);
        }
        let (status, err) = run_as(shared, &args, None);
        assert_eq!(status, Some(2), "{args:?}: {err}");
        assert!(
            err.contains(".v2ref-lock-") && err.trim_end().lines().count() == 1,
            "{args:?}: {err}"
        );
        for lock in &locks {
            std::fs::remove_file(lock).unwrap();
        }
    }
}

/// A hard link of the user's own file under each writer's lock name: every
/// writer refuses, the file keeps its bytes. (On 25b05bd each writer
/// emptied the file and wrote its process id in it.)
#[test]
fn a_hard_link_at_a_lock_name_is_refused_and_its_file_kept() {
    let (_root, shared) = shared_folder();
    let log = shared.join("notes.log");
    let bytes = b"a user's notes, kept\n";
    std::fs::write(&log, bytes).unwrap();
    every_writer_refuses(&shared, &|lock| std::fs::hard_link(&log, lock).unwrap());
    assert_eq!(std::fs::read(&log).unwrap(), bytes);
}

/// A file of the user's own, with one link, that holds something other
/// than a process id under a lock name is refused and kept; one holding a
/// process id (the lock of a run that was killed) is taken over.
#[test]
fn a_lock_name_holding_anything_but_a_process_id_is_kept() {
    let (_root, shared) = shared_folder();
    let bytes = b"12 not a process id\n";
    every_writer_refuses(&shared, &|lock| std::fs::write(lock, bytes).unwrap());
    let lock = lock_of(&shared, "est.csv");
    std::fs::write(&lock, "4194304\n").unwrap();
    let (status, err) = run_as(
        &shared,
        &["estimate", "--sidecar", "set.json", "--out", "est.csv"],
        None,
    );
    assert_eq!(status, Some(0), "a killed run's lock is taken over: {err}");
    assert!(!lock.exists(), "the lock is removed after the run");
}

/// Whether the tests run as root (the cross-user cases need it).
fn root() -> bool {
    // SAFETY: `geteuid` takes no argument and cannot fail.
    let me = unsafe { libc::geteuid() };
    if me != 0 {
        eprintln!("skipped: needs root to plant as another user");
    }
    me == 0
}

/// Runs `ln` as uid 65534 (the user who plants), as `args`.
fn as_nobody(args: &[&str], dir: &Path) {
    let status = Command::new(args[0])
        .args(&args[1..])
        .current_dir(dir)
        .uid(65534)
        .gid(65534)
        .status()
        .unwrap();
    assert!(status.success(), "{args:?} as uid 65534");
}

/// Across users: in the sticky shared folder an unprivileged user
/// hard-links root's world-writable log under each of root's lock names;
/// every writer run by root refuses and the log keeps its bytes. (On
/// 25b05bd root's writers replaced the log with a process id.)
#[test]
fn another_users_hard_link_to_roots_file_is_never_a_lock() {
    if !root() {
        return;
    }
    let (_root, shared) = shared_folder();
    let log = shared.join("root.log");
    let bytes = b"root's log, world-writable\n";
    std::fs::write(&log, bytes).unwrap();
    std::fs::set_permissions(&log, std::fs::Permissions::from_mode(0o666)).unwrap();
    every_writer_refuses(&shared, &|lock| {
        as_nobody(
            &["ln", log.to_str().unwrap(), lock.to_str().unwrap()],
            &shared,
        );
        assert!(std::fs::symlink_metadata(lock).unwrap().nlink() >= 2);
    });
    assert_eq!(std::fs::read(&log).unwrap(), bytes);
}

/// Another user's symbolic link at a lock name: refused naming the lock
/// (on 25b05bd the kernel's "permission denied" was reported against the
/// output, not the lock).
#[test]
fn another_users_link_at_a_lock_name_is_reported_against_the_lock() {
    if !root() {
        return;
    }
    let (_root, shared) = shared_folder();
    every_writer_refuses(&shared, &|lock| {
        as_nobody(
            &["ln", "-s", "/nonexistent/elsewhere", lock.to_str().unwrap()],
            &shared,
        );
    });
}

/// Under a umask that leaves the user no access to what is made (0777),
/// `reproduce --out` and `golden --update` fail and leave nothing: no
/// temporary folder of mode 000, no folder made for the output. Run as uid
/// 65534 (root ignores modes); skipped unless the tests run as root. (On
/// 25b05bd `reproduce` left `.v2ref-tmp-…-rep` and `golden` left `gd`.)
#[test]
fn a_umask_that_leaves_no_access_leaves_nothing_behind() {
    if !root() {
        return;
    }
    let root_dir = tempfile::tempdir().unwrap();
    std::fs::set_permissions(root_dir.path(), std::fs::Permissions::from_mode(0o755)).unwrap();
    let dir = root_dir.path().join("mine");
    std::fs::create_dir(&dir).unwrap();
    std::os::unix::fs::chown(&dir, Some(65534), Some(65534)).unwrap();
    let runs: [&[&str]; 2] = [
        &["reproduce", "--quick", "--out", "rep"],
        &["golden", "--update", "--only", "vectors", "--dir", "gd"],
    ];
    for args in runs {
        let status = Command::new("sh")
            .arg("-c")
            .arg("umask 0777; exec \"$0\" \"$@\" 2>/dev/null")
            .arg(env!("CARGO_BIN_EXE_v2ref"))
            .args(args)
            .current_dir(&dir)
            .uid(65534)
            .gid(65534)
            .status()
            .unwrap();
        assert!(!status.success(), "{args:?} succeeded under umask 0777");
        let left: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert!(left.is_empty(), "{args:?} left {left:?}");
    }
}
