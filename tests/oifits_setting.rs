//! Where and when an OIFITS file says the observation was made: the
//! target's name and J2000 position, the date, the array's site, set by
//! `--target-name`, `--ra-deg`, `--dec-deg`, `--date`, `--site` (a known
//! array, or `--site-lon-deg`/`--site-lat-deg`/`--site-height-m`) on every
//! command that writes a file, read back with the tests' plain reader (`tests/fits_plain.rs`, not v2ref's own
//! reader); the defaults unchanged; bad values refused with status 2
//! naming the flag and the range, nothing written.

use crate::fits_plain;
use std::path::Path;
use std::process::Command;

/// `v2ref ARGS`: its exit status and standard error.
fn v2ref(args: &[&str]) -> (i32, String) {
    let (code, _, err) = crate::run::v2ref(args);
    (code, err)
}

/// What a file says of the observation, read with the tests' plain reader.
#[derive(Debug)]
struct Said {
    object: String,
    date_obs: String,
    target: String,
    radec_deg: (f64, f64),
    arrname: String,
    array_xyz_m: [f64; 3],
    diameter_m: f32,
    first_mjd: f64,
    int_time_s: f64,
}

fn said(path: &Path) -> Said {
    let hdus = fits_plain::read(path);
    let p = &hdus[0];
    let t = fits_plain::hdu(&hdus, "OI_TARGET");
    let a = fits_plain::hdu(&hdus, "OI_ARRAY");
    let v = fits_plain::hdu(&hdus, "OI_VIS2");
    let date_obs = p.key("DATE-OBS").to_owned();
    assert_eq!(
        v.key("DATE-OBS"),
        date_obs,
        "OI_VIS2's DATE-OBS is the primary's"
    );
    Said {
        object: p.key("OBJECT").to_owned(),
        date_obs,
        target: t.text_col("TARGET")[0].clone(),
        radec_deg: (t.f64_col("RAEP0")[0], t.f64_col("DECEP0")[0]),
        arrname: a.key("ARRNAME").to_owned(),
        array_xyz_m: ["ARRAYX", "ARRAYY", "ARRAYZ"].map(|k| a.f64_key(k)),
        diameter_m: a.f32_col("DIAMETER")[0],
        first_mjd: v.f64_col("MJD")[0],
        int_time_s: v.f64_col("INT_TIME")[0],
    }
}

/// The three commands that write OIFITS, each with `extra` flags, into
/// `dir`: the set's truth (`synth --oifits`, piston on 1.8 m apertures),
/// its estimates (`estimate --out`) and a plan's file (`plan --oifits`).
fn write_all(dir: &Path, extra: &[&str]) -> [std::path::PathBuf; 3] {
    let stem = dir.join("set").display().to_string();
    let synth = [
        "synth",
        "--out",
        &stem,
        "--rows",
        "40",
        "--samples",
        "32",
        "--quiet",
        "--oifits",
        "--fringe-hz",
        "300",
        "--aperture-m",
        "1.8",
        "--seeing-arcsec",
        "0.5",
    ];
    let (code, err) = v2ref(&[&synth[..], extra].concat());
    assert_eq!(code, 0, "{err}");
    let est = dir.join("est.fits");
    let sidecar = format!("{stem}.json");
    let estimate = [
        "estimate",
        "--sidecar",
        &sidecar,
        "--out",
        est.to_str().unwrap(),
    ];
    let (code, err) = v2ref(&[&estimate[..], extra].concat());
    assert_eq!(code, 0, "{err}");
    let plan_file = dir.join("plan.fits");
    let plan = [
        "plan",
        "--quiet",
        "--fringe-hz",
        "300",
        "--stroke-um",
        "32",
        "--scans",
        "64",
        "--aperture-m",
        "1.8",
        "--oifits",
        plan_file.to_str().unwrap(),
    ];
    let (code, err) = v2ref(&[&plan[..], extra].concat());
    assert_eq!(code, 0, "{err}");
    [dir.join("set.truth.fits"), est, plan_file]
}

/// Geocentric positions of the sites, m, from astropy 8.0's
/// `EarthLocation.from_geodetic(lon, lat, height)` (WGS84): an
/// implementation of the ellipsoid independent of v2ref's.
const VLTI_XYZ_M: [f64; 3] = [1_946_404.341, -5_467_644.291, -2_642_728.201];
const IOTA_XYZ_M: [f64; 3] = [-1_937_286.176, -5_077_239.063, 3_332_729.380];
/// The site of `--site-lon-deg 10 --site-lat-deg 45 --site-height-m 100`.
const MINE_XYZ_M: [f64; 3] = [4_449_028.159, 784_483.702, 4_487_419.120];

fn assert_xyz(got: [f64; 3], want: [f64; 3], file: &Path) {
    for (g, w) in got.iter().zip(want) {
        // A millimetre: the constants' rounding.
        assert!(
            (g - w).abs() < 1e-3, // tol: a millimetre, the rounding of the constants above
            "{}: {got:?} != {want:?}",
            file.display()
        );
    }
}

/// fitsverify (HEASARC) finds nothing in `file`; skipped where it is not
/// installed, unless `V2REF_REQUIRE_FITSVERIFY` is set (as `.ci/run` does).
fn fitsverify_clean(file: &Path) {
    let Ok(out) = Command::new("fitsverify").arg(file).output() else {
        let required = std::env::var_os("V2REF_REQUIRE_FITSVERIFY").is_some();
        assert!(
            !required,
            "V2REF_REQUIRE_FITSVERIFY is set and fitsverify does not run"
        );
        return;
    };
    let report = String::from_utf8_lossy(&out.stdout);
    assert!(
        report.contains("Verification found 0 warning(s) and 0 error(s)"),
        "{}:\n{report}",
        file.display()
    );
}

#[test]
fn the_flags_say_where_and_when_in_every_file_written() {
    let dir = tempfile::tempdir().unwrap();
    let flags = [
        "--target-name",
        "HD 12345",
        "--ra-deg",
        "359.5",
        "--dec-deg",
        "-45.25",
        "--date",
        "2026-11-26T03:00:00",
        "--site",
        "vlti",
    ];
    for file in write_all(dir.path(), &flags) {
        let s = said(&file);
        assert_eq!(
            (s.object.as_str(), s.target.as_str()),
            ("HD 12345", "HD 12345")
        );
        assert_eq!(s.radec_deg, (359.5, -45.25), "{}", file.display());
        assert_eq!(s.date_obs, "2026-11-26T03:00:00");
        // MJD 61370 is 2026-11-26 (51544 + 9826 days from 2000-01-01); the
        // first row's middle is half a row after 03:00.
        let start = 61_370.0 + 3.0 / 24.0;
        let half_row = 0.5 * s.int_time_s / 86_400.0;
        assert!(
            (s.first_mjd - (start + half_row)).abs() < 1e-9, // tol: 86 us, rounding of an MJD near 6e4 in f64 is ~1e-11
            "{}: MJD {}",
            file.display(),
            s.first_mjd
        );
        assert_eq!(s.arrname, "VLTI");
        assert_xyz(s.array_xyz_m, VLTI_XYZ_M, &file);
        // The telescopes are the configuration's apertures (DIAMETER is
        // a 32-bit column).
        assert_eq!(s.diameter_m, 1.8_f32, "{}", file.display());
        fitsverify_clean(&file);
    }
    let mine = [
        "--site",
        "My 'Array",
        "--site-lon-deg",
        "10",
        "--site-lat-deg",
        "45",
        "--site-height-m",
        "100",
        "--date",
        "2024-02-29",
    ];
    let dir = tempfile::tempdir().unwrap();
    for file in write_all(dir.path(), &mine) {
        let s = said(&file);
        assert_eq!(
            (s.arrname.as_str(), s.date_obs.as_str()),
            ("My 'Array", "2024-02-29")
        );
        fitsverify_clean(&file);
        assert_xyz(s.array_xyz_m, MINE_XYZ_M, &file);
        // 2024-02-29 is MJD 60369 (a leap day).
        // tol: the first row starts within minutes of midnight (0.01 d = 14 min).
        assert!((s.first_mjd - 60_369.0).abs() < 0.01, "{}", s.first_mjd);
    }
}

#[test]
fn without_the_flags_a_file_says_what_it_said_before_them() {
    let dir = tempfile::tempdir().unwrap();
    for file in write_all(dir.path(), &[]) {
        let s = said(&file);
        assert_eq!(
            (s.object.as_str(), s.target.as_str()),
            ("V2REF_MODEL", "V2REF_MODEL")
        );
        assert_eq!(s.radec_deg, (0.0, 0.0));
        assert_eq!(
            (s.date_obs.as_str(), s.arrname.as_str()),
            ("2000-01-01", "IOTA")
        );
        // tol: the first row starts within minutes of midnight (0.01 d = 14 min).
        assert!((s.first_mjd - 51_544.0).abs() < 0.01, "{}", s.first_mjd);
        assert_xyz(s.array_xyz_m, IOTA_XYZ_M, &file);
    }
}

#[test]
fn a_bad_value_exits_2_naming_the_flag_and_its_range_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let stem = dir.path().join("set").display().to_string();
    let (code, err) = v2ref(&[
        "synth",
        "--out",
        &stem,
        "--rows",
        "20",
        "--samples",
        "32",
        "--quiet",
    ]);
    assert_eq!(code, 0, "{err}");
    let sidecar = format!("{stem}.json");
    let out = dir.path().join("est.fits");
    let cases: [(&[&str], &str, &str); 12] = [
        (&["--date", "2023-02-29"], "--date", "YYYY-MM-DD"),
        (&["--date", "2026-11-26T24:00:00"], "--date", "hh:mm:ss"),
        (&["--date", "1858-11-16"], "--date", "1858-11-17"),
        (
            &["--ra-deg", "360", "--dec-deg", "0"],
            "--ra-deg",
            "0 to 360",
        ),
        (
            &["--ra-deg", "-0.5", "--dec-deg", "0"],
            "--ra-deg",
            "0 to 360",
        ),
        (&["--ra-deg", "10"], "--dec-deg", "declination"),
        (
            &["--ra-deg", "10", "--dec-deg", "-90.5"],
            "--dec-deg",
            "-90 to 90",
        ),
        (
            &["--target-name", "A NAME OF 17 CHRS"],
            "--target-name",
            "1 to 16",
        ),
        (&["--site", "paranal"], "--site", "iota, vlti, chara"),
        (&["--site-lat-deg", "10"], "--site-lat-deg", "name"),
        (
            &["--site", "X", "--site-lon-deg", "1", "--site-lat-deg", "1"],
            "--site-height-m",
            "three",
        ),
        (
            &[
                "--site",
                "X",
                "--site-lon-deg",
                "190",
                "--site-lat-deg",
                "1",
                "--site-height-m",
                "0",
            ],
            "--site-lon-deg",
            "-180 to 180",
        ),
    ];
    for (flags, flag, range) in cases {
        let args = [
            &[
                "estimate",
                "--sidecar",
                &sidecar,
                "--out",
                out.to_str().unwrap(),
            ],
            flags,
        ]
        .concat();
        let (code, err) = v2ref(&args);
        assert_eq!(code, 2, "{flags:?}: {err}");
        let line = err.trim();
        assert!(
            line.lines().count() == 1
                && line.starts_with(&format!("error: {flag}:"))
                && line.contains(range),
            "{flags:?}: {err}"
        );
        assert!(!out.exists(), "{flags:?}: a file was written");
    }
}

#[test]
fn the_flags_are_refused_where_no_oifits_file_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let stem = dir.path().join("set").display().to_string();
    let synth = [
        "synth",
        "--out",
        &stem,
        "--rows",
        "20",
        "--samples",
        "32",
        "--quiet",
    ];
    let (code, err) = v2ref(&[&synth[..], &["--date", "2026-11-26"]].concat());
    assert_eq!(code, 2, "{err}");
    assert!(
        err.starts_with("error: --date: applies when an OIFITS file is written (--oifits)"),
        "{err}"
    );
    assert!(!dir.path().join("set.npy").exists());
    let (code, err) = v2ref(&synth);
    assert_eq!(code, 0, "{err}");
    let csv = dir.path().join("est.csv");
    let sidecar = format!("{stem}.json");
    let args = [
        "estimate",
        "--sidecar",
        &sidecar,
        "--out",
        csv.to_str().unwrap(),
        "--site",
        "vlti",
    ];
    let (code, err) = v2ref(&args);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--site: applies when an OIFITS file is written (--out FILE.fits)"),
        "{err}"
    );
    assert!(!csv.exists());
    let plan = [
        "plan",
        "--quiet",
        "--fringe-hz",
        "300",
        "--stroke-um",
        "32",
        "--scans",
        "64",
    ];
    let (code, err) = v2ref(&[&plan[..], &["--target-name", "X"]].concat());
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--target-name: applies when an OIFITS file is written (--oifits)"),
        "{err}"
    );
}
