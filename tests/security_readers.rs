//! No reader waits (issue 53): a FIFO wherever v2ref reads a file (a set's
//! member named by its sidecar, `--input` as `.npy` or `.csv`, `--sidecar`
//! of `estimate` and `score`, `--calibrator`, `--estimates`,
//! `--spectrum-csv`, `--targets`) is refused at once in one line naming it,
//! exit status 2; a run that waits is killed after 20 s and the test fails.
//! An estimates file of an extension no reader takes is refused naming
//! every extension the readers take, the OIFITS ones included.

use super::cli_support::{mkfifo, run_within, SMALL_SET};
use std::os::unix::fs::PermissionsExt as _;
use std::path::Path;

/// Runs v2ref in `dir`, killed after 20 s (then the test fails): its exit
/// status and stderr.
fn run_briefly(dir: &Path, args: &[&str]) -> (Option<i32>, String) {
    run_within(dir, args, None, 20)
}

/// A folder with a set (`set.*`, CSV too), its estimates and FIFOs named
/// `fifo.npy`, `fifo.csv`, `fifo.json`.
fn folder() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::set_permissions(dir.path(), std::fs::Permissions::from_mode(0o755)).unwrap();
    assert_eq!(run_briefly(dir.path(), &SMALL_SET).0, Some(0));
    let est = ["estimate", "--sidecar", "set.json", "--out", "est.csv"];
    assert_eq!(run_briefly(dir.path(), &est).0, Some(0));
    for name in ["fifo.npy", "fifo.csv", "fifo.json"] {
        mkfifo(&dir.path().join(name));
    }
    dir
}

fn refused_naming(args: &[&str], (status, err): (Option<i32>, String), name: &str) {
    assert_eq!(status, Some(2), "{args:?}: {err}");
    assert!(
        err.contains(name) && err.trim_end().lines().count() == 1,
        "{args:?}: {err}"
    );
}

/// Every route that reads a file given on the command line refuses a FIFO
/// at once. (On 25b05bd `--input fifo.npy`, `--sidecar` of estimate and
/// score, `--calibrator`, `--estimates fifo.npy` and `--spectrum-csv`
/// waited for a writer for ever.)
#[test]
fn a_fifo_given_to_any_reader_is_refused_at_once() {
    let dir = folder();
    let plan = [
        "plan",
        "--target-sigma-v2",
        "1e-2",
        "--fringe-hz",
        "500",
        "--stroke-um",
        "32",
        "--scans",
        "50",
        "--quiet",
    ];
    let mut spectrum = plan.to_vec();
    spectrum.extend_from_slice(&["--spectrum-csv", "fifo.csv"]);
    let mut targets = plan[..1].to_vec();
    targets.extend_from_slice(&["--targets", "fifo.csv", "--quiet"]);
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["estimate", "--input", "fifo.npy"], "fifo.npy"),
        (vec!["estimate", "--input", "fifo.csv"], "fifo.csv"),
        (vec!["estimate", "--sidecar", "fifo.json"], "fifo.json"),
        (
            vec![
                "estimate",
                "--sidecar",
                "set.json",
                "--calibrator",
                "fifo.npy",
            ],
            "fifo.npy",
        ),
        (
            vec!["score", "--sidecar", "fifo.json", "--estimates", "est.csv"],
            "fifo.json",
        ),
        (
            vec!["score", "--sidecar", "set.json", "--estimates", "fifo.npy"],
            "fifo.npy",
        ),
        (spectrum, "fifo.csv"),
        (targets, "fifo.csv"),
    ];
    for (args, name) in cases {
        let outcome = run_briefly(dir.path(), &args);
        refused_naming(&args, outcome, name);
    }
}

/// A set whose data file (named by its sidecar, not by the user) was
/// replaced by a FIFO is refused at once, naming it. (On 25b05bd
/// `estimate --sidecar` waited for ever.)
#[test]
fn a_fifo_in_place_of_a_sets_member_is_refused_at_once() {
    let dir = folder();
    std::fs::remove_file(dir.path().join("set.npy")).unwrap();
    mkfifo(&dir.path().join("set.npy"));
    let args = ["estimate", "--sidecar", "set.json"];
    let outcome = run_briefly(dir.path(), &args);
    refused_naming(&args, outcome, "set.npy");
}

/// An estimates file of an extension no reader takes (`.oidata`, none at
/// all) is refused naming every extension `score --estimates` reads: the
/// matrix ones and each of `v2ref_oifits::FITS_EXTENSIONS`. (On 25b05bd:
/// "accepted: .npy (float64) or .csv".)
#[test]
fn an_unknown_extension_is_refused_naming_every_accepted_one() {
    let dir = folder();
    for name in ["est.oidata", "est"] {
        std::fs::copy(dir.path().join("est.csv"), dir.path().join(name)).unwrap();
        let args = ["score", "--sidecar", "set.json", "--estimates", name];
        let (status, err) = run_briefly(dir.path(), &args);
        assert_eq!(status, Some(2), "{err}");
        for ext in [".npy", ".csv"].into_iter().map(str::to_owned).chain(
            v2ref_oifits::FITS_EXTENSIONS
                .iter()
                .map(|e| format!(".{e}")),
        ) {
            assert!(err.contains(&ext), "{name}: {ext} not named: {err}");
        }
    }
}

/// The files `golden --update` looks at in a folder it would replace (a
/// figure's `fig*.json`, `vectors/README.md`), names found in the folder,
/// are read without waiting and never through a link: a FIFO under such
/// a name leaves the folder refused at once as one golden did not write.
/// (On 25b05bd: both waited on the FIFO until killed.)
#[test]
fn a_fifo_in_a_golden_folder_is_never_waited_on() {
    for name in ["fig1.json", "vectors/README.md"] {
        let dir = tempfile::tempdir().unwrap();
        let gd = dir.path().join("gd");
        std::fs::create_dir_all(gd.join("vectors")).unwrap();
        std::fs::write(gd.join("keep.csv"), "a user's file\n").unwrap();
        mkfifo(&gd.join(name));
        let args = ["golden", "--update", "--dir", "gd"];
        let (status, err) = run_briefly(dir.path(), &args);
        assert_eq!(status, Some(2), "{name}: {err}");
        assert!(
            err.contains("gd") && err.contains("did not write"),
            "{name}: {err}"
        );
        assert_eq!(
            std::fs::read_to_string(gd.join("keep.csv")).unwrap(),
            "a user's file\n"
        );
    }
}
