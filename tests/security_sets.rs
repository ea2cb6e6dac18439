//! Security of the readers and writers of sets (issue 43), against the
//! release binary: a folder of files someone else made (planted commit
//! records, links to decoy files OUTSIDE the test's folder, FIFOs, links to
//! `/dev/zero`, huge sparse files, another user's files, records of 3 000
//! members) cannot make any reader or writer touch anything but the run's
//! own set. Every case is run through every reader (`estimate --sidecar`,
//! `estimate --calibrator`, `score`) and every writer (`synth --out`,
//! `estimate --out`); the decoys are checked untouched (content and
//! mtime), the readers are checked to change nothing in the folder (a
//! snapshot of the whole folder before and after), and nothing may hang
//! (each run is killed, and the test failed, after 60 s).
//!
//! The cases that need another user run the binary as uid 65534 when the
//! tests run as root (as in CI's container), and are skipped otherwise.

use super::cli_support::{mkfifo, run_within};
use std::ffi::OsString;
use std::os::unix::fs::{MetadataExt as _, PermissionsExt as _};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The name hash of a target's lock and of the old commit record.
pub(crate) fn name_hash(name: &str) -> String {
    let h = name.bytes().fold(0xcbf2_9ce4_8422_2325_u64, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    });
    format!("{h:016x}")
}

/// Runs v2ref in `dir` (as `uid` when given), killed after 60 s: its exit
/// status (None: ended by a signal) and stderr.
pub(crate) fn run_as(dir: &Path, args: &[&str], uid: Option<u32>) -> (Option<i32>, String) {
    run_within(dir, args, uid, 60)
}

fn run(dir: &Path, args: &[&str]) -> (Option<i32>, String) {
    run_as(dir, args, None)
}

/// Every entry under `dir` (not followed): name, kind, size, mtime and, for
/// a regular file, its first 64 KiB.
fn snapshot(dir: &Path) -> Vec<(PathBuf, u32, u64, i64, i64, Vec<u8>)> {
    let mut out = Vec::new();
    let mut names: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    names.sort();
    for p in names {
        let m = std::fs::symlink_metadata(&p).unwrap();
        let head = if m.is_file() && m.mode() & 0o444 != 0 && !is_special_name(&p) {
            use std::io::Read as _;
            let mut v = Vec::new();
            let f = std::fs::File::open(&p).unwrap();
            f.take(1 << 16).read_to_end(&mut v).unwrap();
            v
        } else {
            Vec::new()
        };
        out.push((
            p.clone(),
            m.mode(),
            m.len(),
            m.mtime(),
            m.mtime_nsec(),
            head,
        ));
        if m.is_dir() {
            out.extend(snapshot(&p));
        }
    }
    out
}

fn is_special_name(p: &Path) -> bool {
    p.file_name().is_some_and(|n| n == "fifo")
}

/// A test's folders: `shared` (the folder of someone else's files, where
/// v2ref runs) and `outside` (decoys that nothing may touch).
struct Scene {
    _root: tempfile::TempDir,
    shared: PathBuf,
    outside: PathBuf,
}

impl Scene {
    /// A set (`synth --csv`) and its estimates in `shared`; decoys outside.
    fn new() -> Scene {
        let root = tempfile::tempdir().unwrap();
        std::fs::set_permissions(root.path(), std::fs::Permissions::from_mode(0o755)).unwrap();
        let (shared, outside) = (root.path().join("shared"), root.path().join("outside"));
        std::fs::create_dir(&shared).unwrap();
        std::fs::create_dir(&outside).unwrap();
        std::fs::set_permissions(&shared, std::fs::Permissions::from_mode(0o1777)).unwrap();
        for name in ["decoy.txt", "decoy-old", "decoy-temp", ".bashrc"] {
            std::fs::write(outside.join(name), format!("decoy {name}\n")).unwrap();
        }
        std::fs::create_dir(outside.join("folder")).unwrap();
        std::fs::write(outside.join("folder/inner.txt"), "inner\n").unwrap();
        let synth = [
            "synth",
            "--rows",
            "400",
            "--photons",
            "1000",
            "--samples",
            "16",
            "--quiet",
            "--csv",
            "--out",
            "set",
        ];
        assert_eq!(run(&shared, &synth).0, Some(0));
        let est = ["estimate", "--sidecar", "set.json", "--out", "est.csv"];
        assert_eq!(run(&shared, &est).0, Some(0));
        Scene {
            _root: root,
            shared,
            outside,
        }
    }

    /// Runs every reader, then every writer, in `shared` (as `uid`), and
    /// checks: the decoys untouched, the readers changed nothing, nothing
    /// hung. Returns each run's status and stderr, readers first.
    fn every_reader_and_writer(&self, uid: Option<u32>) -> Vec<(Option<i32>, String)> {
        let decoys = snapshot(&self.outside);
        let before = snapshot(&self.shared);
        let readers: [&[&str]; 3] = [
            &["estimate", "--sidecar", "set.json"],
            &[
                "estimate",
                "--sidecar",
                "set.json",
                "--calibrator",
                "set.npy",
            ],
            &["score", "--sidecar", "set.json", "--estimates", "est.csv"],
        ];
        let mut outcomes = Vec::new();
        for args in readers {
            outcomes.push(run_as(&self.shared, args, uid));
            assert!(
                snapshot(&self.shared) == before,
                "the reader {args:?} changed the folder"
            );
            assert!(
                snapshot(&self.outside) == decoys,
                "the reader {args:?} touched a decoy"
            );
        }
        let writers: [&[&str]; 2] = [
            &[
                "synth",
                "--rows",
                "400",
                "--photons",
                "1000",
                "--samples",
                "16",
                "--quiet",
                "--csv",
                "--out",
                "set",
                "--force",
                "--seed",
                "7",
            ],
            &[
                "estimate",
                "--sidecar",
                "set.json",
                "--out",
                "est.csv",
                "--force",
            ],
        ];
        for args in writers {
            outcomes.push(run_as(&self.shared, args, uid));
            assert!(
                snapshot(&self.outside) == decoys,
                "the writer {args:?} touched a decoy"
            );
        }
        outcomes
    }

    fn path(&self, name: &str) -> PathBuf {
        self.shared.join(name)
    }
}

fn hex(p: &Path) -> String {
    p.as_os_str()
        .as_encoded_bytes()
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// A commit record of the format v2ref wrote before issue 43 (its
/// checksum unkeyed, so anyone could forge one): `target` in the shared
/// folder, the "old file kept aside" a decoy outside.
fn forged_record(target: &Path, temp: &Path, old: &Path) -> Vec<u8> {
    let text = format!(
        "v2ref commit record 1\npid 4194304\nforce 1\nmember {} {} {}\n",
        hex(target),
        hex(temp),
        hex(old)
    );
    let sum = name_hash(&text);
    format!("{text}sum {sum}\n").into_bytes()
}

/// Planted commit records (the format before issue 43) naming decoys
/// outside as their members' old files and temporaries: no reader and no
/// writer reads, follows or removes anything they name; the records
/// themselves are left as they are. (Before, every reader "rolled the set
/// forward" and deleted the decoys.)
#[test]
fn a_forged_commit_record_is_never_acted_on() {
    let s = Scene::new();
    let shared = std::fs::canonicalize(&s.shared).unwrap();
    for (k, member) in ["set.json", "set.npy", "est.csv"].iter().enumerate() {
        let old = s
            .outside
            .join(if k == 0 { "decoy-old" } else { "decoy.txt" });
        let record = forged_record(&shared.join(member), &s.outside.join("decoy-temp"), &old);
        let name = format!(".v2ref-journal-{}", name_hash(member));
        std::fs::write(s.path(&name), record).unwrap();
    }
    for (status, err) in s.every_reader_and_writer(None) {
        assert_eq!(status, Some(0), "{err}");
    }
    let left = std::fs::read_dir(&s.shared).unwrap().filter(|e| {
        e.as_ref()
            .unwrap()
            .file_name()
            .to_string_lossy()
            .starts_with(".v2ref-journal-")
    });
    assert_eq!(left.count(), 3, "a record was acted on (removed)");
}

/// Records that are a FIFO, a link to `/dev/zero`, a sparse file of
/// 400 MiB, or a record of 3 000 members: ignored, no reader hangs or
/// reads them. (Before, the FIFO hung every reader and the others were read
/// whole.)
#[test]
fn a_record_that_is_a_fifo_a_device_a_huge_file_or_huge_is_ignored() {
    let s = Scene::new();
    let path = |m: &str| s.path(&format!(".v2ref-journal-{}", name_hash(m)));
    mkfifo(&path("set.json"));
    std::os::unix::fs::symlink("/dev/zero", path("set.npy")).unwrap();
    std::fs::File::create(path("est.csv"))
        .unwrap()
        .set_len(400 << 20)
        .unwrap();
    let shared = std::fs::canonicalize(&s.shared).unwrap();
    let mut many = String::from("v2ref commit record 1\npid 4194304\nforce 0\n");
    for k in 0..3000 {
        let t = shared.join(format!("m{k}"));
        many += &format!(
            "member {} {} -\n",
            hex(&t),
            hex(&s.outside.join("decoy.txt"))
        );
    }
    let many = format!("{many}sum {}\n", name_hash(&many));
    std::fs::write(path("set.csv"), many).unwrap();
    let start = Instant::now();
    for (status, err) in s.every_reader_and_writer(None) {
        assert_eq!(status, Some(0), "{err}");
    }
    assert!(
        start.elapsed() < Duration::from_secs(50),
        "{:?}",
        start.elapsed()
    );
}

/// What a writer finds under its lock's name (a link to a decoy outside,
/// a FIFO, a folder) is refused in one line naming it, never opened
/// through or truncated; readers take no lock and are not stopped.
/// (Before, a link made `synth --out` truncate the decoy.)
#[test]
fn a_link_or_fifo_at_a_lock_name_is_refused_and_never_followed() {
    for kind in ["link", "fifo", "folder"] {
        let s = Scene::new();
        let lock = s.path(&format!(".v2ref-lock-{}", name_hash("set.npy")));
        match kind {
            "link" => std::os::unix::fs::symlink(s.outside.join("decoy.txt"), &lock).unwrap(),
            "fifo" => mkfifo(&lock),
            _ => std::fs::create_dir(&lock).unwrap(),
        }
        let outcomes = s.every_reader_and_writer(None);
        for (status, err) in &outcomes[..3] {
            assert_eq!(*status, Some(0), "{kind}: a reader: {err}");
        }
        let (status, err) = &outcomes[3];
        assert_eq!(*status, Some(2), "{kind}: synth: {err}");
        assert!(
            err.contains(".v2ref-lock-") && err.lines().count() == 1,
            "{kind}: {err}"
        );
    }
}

/// The stale sweep of a writer removes only v2ref's own temporaries whose
/// lock is free: a user's file named like an earlier version's temporary,
/// a link or a FIFO under a temporary's name, a folder without v2ref's
/// marker, or a marker that is a link, all stay (a dead writer's own
/// temporary is removed). (Before, `.data.2024.01.tmp` was removed as the
/// temporary of "process 2024".)
#[test]
fn the_sweep_removes_only_its_own_unlocked_temporaries() {
    let s = Scene::new();
    let keep = [
        ".data.2024.01.tmp",
        ".out.tmp-4194304",
        ".v2ref-tmp-4194304-0-link",
        ".v2ref-tmp-4194304-0-dir",
    ];
    std::fs::write(s.path(keep[0]), "a user's file\n").unwrap();
    std::fs::create_dir(s.path(keep[1])).unwrap();
    std::fs::write(s.path(keep[1]).join(".v2ref-output"), "").unwrap();
    std::os::unix::fs::symlink(s.outside.join("decoy.txt"), s.path(keep[2])).unwrap();
    std::fs::create_dir(s.path(keep[3])).unwrap();
    std::os::unix::fs::symlink(
        s.outside.join("decoy.txt"),
        s.path(keep[3]).join(".v2ref-temporary"),
    )
    .unwrap();
    std::fs::write(s.path(".v2ref-tmp-4194304-0-set.npy"), "a dead writer's\n").unwrap();
    for (status, err) in s.every_reader_and_writer(None) {
        assert_eq!(status, Some(0), "{err}");
    }
    for k in keep {
        assert!(
            std::fs::symlink_metadata(s.path(k)).is_ok(),
            "{k} was removed"
        );
    }
    assert!(
        !s.path(".v2ref-tmp-4194304-0-set.npy").exists(),
        "a dead writer's temporary stayed"
    );
}

/// Another user's files under v2ref's names (run as uid 65534 in a sticky
/// shared folder, the files root's): a lock of root's is refused, a
/// temporary or a record of root's is neither removed nor read. Skipped
/// unless the tests run as root.
#[test]
fn another_users_files_are_never_used_or_removed() {
    // SAFETY: `geteuid` takes no argument and cannot fail.
    if unsafe { libc::geteuid() } != 0 {
        eprintln!("skipped: needs root to run v2ref as another user");
        return;
    }
    let s = Scene::new();
    for f in std::fs::read_dir(&s.shared).unwrap() {
        let p = f.unwrap().path();
        std::os::unix::fs::lchown(&p, Some(65534), Some(65534)).unwrap();
    }
    let roots = [
        ".v2ref-tmp-4194304-0-set.npy".to_owned(),
        format!(".v2ref-lock-{}", name_hash("est.csv")),
    ];
    for r in &roots {
        std::fs::write(s.path(r), "root's\n").unwrap();
        std::fs::set_permissions(s.path(r), std::fs::Permissions::from_mode(0o666)).unwrap();
    }
    let outcomes = s.every_reader_and_writer(Some(65534));
    for (status, err) in &outcomes[..4] {
        assert_eq!(*status, Some(0), "{err}");
    }
    let (status, err) = &outcomes[4];
    assert_eq!(*status, Some(2), "estimate --out under root's lock: {err}");
    for r in &roots {
        assert_eq!(
            std::fs::read(s.path(r)).unwrap(),
            b"root's\n",
            "{r} was used"
        );
    }
}

/// A sidecar naming its data outside its folder (`../outside/…`, an
/// absolute path) is refused, the file it names never read.
#[test]
fn a_sidecar_naming_a_file_elsewhere_is_refused() {
    let s = Scene::new();
    std::fs::copy(s.path("set.npy"), s.outside.join("decoy.npy")).unwrap();
    let text = std::fs::read_to_string(s.path("set.json")).unwrap();
    for name in [
        "../outside/decoy.npy".to_owned(),
        s.outside.join("decoy.npy").display().to_string(),
    ] {
        let forged = text.replace("\"npy\": \"set.npy\"", &format!("\"npy\": {name:?}"));
        std::fs::write(s.path("far.json"), forged).unwrap();
        let (status, err) = run(&s.shared, &["estimate", "--sidecar", "far.json"]);
        assert_eq!(status, Some(2), "{name}: {err}");
        assert!(
            err.contains("data.npy") && err.lines().count() == 1,
            "{err}"
        );
    }
}

/// `--out DIR/` (a folder meant) is refused instead of writing `DIR.npy`
/// beside the folder.
#[test]
fn an_output_ending_in_a_slash_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("d")).unwrap();
    for out in ["d/", "new/", "d/."] {
        let (status, err) = run(
            dir.path(),
            &[
                "synth",
                "--rows",
                "8",
                "--samples",
                "8",
                "--quiet",
                "--out",
                out,
            ],
        );
        assert_eq!(status, Some(2), "{out}: {err}");
        assert!(err.contains("names a folder"), "{err}");
    }
    let names: Vec<OsString> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names, ["d"]);
}

/// Moving the output folder while a run writes leaves neither its lock
/// files nor its temporaries in the moved folder: they are removed
/// through the folder as opened, wherever it is now.
#[test]
fn moving_the_output_folder_during_a_run_leaves_no_lock_file() {
    let root = tempfile::tempdir().unwrap();
    let (a, b) = (root.path().join("a"), root.path().join("b"));
    std::fs::create_dir(&a).unwrap();
    let child = Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .current_dir(root.path())
        .args([
            "synth",
            "--rows",
            "200000",
            "--samples",
            "64",
            "--quiet",
            "--out",
            "a/set",
        ])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while !std::fs::read_dir(&a).unwrap().any(|e| {
        e.unwrap()
            .file_name()
            .to_string_lossy()
            .starts_with(".v2ref-tmp-")
    }) {
        assert!(start.elapsed() < Duration::from_secs(60));
        std::thread::sleep(Duration::from_millis(5));
    }
    std::fs::rename(&a, &b).unwrap();
    // The run fails (its sidecar's folder is gone) or places its set in
    // the moved folder; either way nothing of its own is left there.
    let out = child.wait_with_output().unwrap();
    let left: Vec<String> = std::fs::read_dir(&b)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    let stray: Vec<&String> = left.iter().filter(|n| n.starts_with(".v2ref-")).collect();
    assert!(
        stray.is_empty(),
        "{stray:?} left; {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// A folder is replaced only by a folder: a regular file (or a link) at
/// the target is refused and left as it was. (Before, the one-step swap
/// exchanged the file out of the target, reported success, and the next
/// writer removed it as a stale temporary.)
#[test]
fn a_file_at_a_folder_target_is_never_swapped_out() {
    use v2ref_reproduction::golden::replace_dir_atomically;
    let tmp = tempfile::tempdir().unwrap();
    let target = tmp.path().join("out");
    std::fs::write(&target, "a user's file\n").unwrap();
    let link = tmp.path().join("link");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    let fill = |d: &Path| {
        std::fs::write(d.join("a.txt"), "x").map_err(|e| v2ref_core::Error::file(None, d, e))
    };
    for t in [&target, &link] {
        assert!(replace_dir_atomically(t, fill).is_err(), "{}", t.display());
    }
    assert_eq!(std::fs::read(&target).unwrap(), b"a user's file\n");
    let mut names: Vec<OsString> = std::fs::read_dir(tmp.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    names.sort();
    assert_eq!(names, ["link", "out"]);
}

/// `reproduce --out` and `golden --update` in a folder where nothing can
/// be created (read-only to the user that runs them: uid 65534) are
/// refused and leave nothing. Skipped unless the tests run as root.
#[test]
fn an_uncreatable_folder_is_refused_and_left_empty() {
    // SAFETY: `geteuid` takes no argument and cannot fail.
    if unsafe { libc::geteuid() } != 0 {
        eprintln!("skipped: needs root to run v2ref as another user");
        return;
    }
    let root = tempfile::tempdir().unwrap();
    std::fs::set_permissions(root.path(), std::fs::Permissions::from_mode(0o755)).unwrap();
    let ro = root.path().join("ro");
    std::fs::create_dir(&ro).unwrap();
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o555)).unwrap();
    let runs: [&[&str]; 2] = [
        &["reproduce", "--out", "ro/figs", "--quick"],
        &["golden", "--update", "--dir", "ro/golden"],
    ];
    for args in runs {
        let (status, err) = run_as(root.path(), args, Some(65534));
        assert_ne!(status, Some(0), "{args:?}: {err}");
        assert_eq!(
            std::fs::read_dir(&ro).unwrap().count(),
            0,
            "{args:?} left something"
        );
    }
}
