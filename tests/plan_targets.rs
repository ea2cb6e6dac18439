//! `plan --targets`: a target list planned with shared flags. Bad rows are
//! reported by line and marked, the others planned; a row's plan depends on
//! its content, not its place; the shared flags reach every row; the
//! table's numbers are the single plan's. Every plan here is one grid point
//! of a bright H-band source with a short piston Monte Carlo (well under a
//! second each).

use std::process::{Command, Output};
use v2ref_commands::commands::plan::PlanRequest;
use v2ref_commands::commands::targets::{
    parse_targets, plan_targets, target_seed, SharedPlan, Status, Target, TargetRow, COLUMNS,
};
use v2ref_commands::parameters::Physical;
use v2ref_commands::plan::photometry::{Band2Mass, Magnitude};
use v2ref_core::conformance::estimate::BiasConvention;

/// The shared flags: one grid point, a short Monte Carlo, H band, a
/// target σ(V²) every row reaches.
const SHARED: [&str; 16] = super::cli_support::ONE_POINT_PLAN;

fn v2ref(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(args)
        .output()
        .unwrap()
}

/// `plan --targets list` with the shared flags and `extra`.
fn plan_list(list: &std::path::Path, extra: &[&str]) -> Output {
    let mut args = vec!["plan", "--targets", list.to_str().unwrap()];
    args.extend_from_slice(&SHARED);
    args.extend_from_slice(extra);
    v2ref(&args)
}

/// The CSV table as rows of cells by column name.
fn table(stdout: &[u8]) -> Vec<std::collections::HashMap<String, String>> {
    let text = String::from_utf8(stdout.to_vec()).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header, COLUMNS, "the header is the table's columns");
    lines
        .map(|l| {
            // No cell of these tables holds a comma.
            let cells: Vec<&str> = l.split(',').collect();
            assert_eq!(cells.len(), header.len(), "{l}");
            header
                .iter()
                .zip(cells)
                .map(|(h, c)| (h.to_string(), c.to_string()))
                .collect()
        })
        .collect()
}

const THREE: &str = "name,magnitude,band,diameter_mas,ra_deg,dec_deg
alpha,5,H,1.0,10.5,-20
beta,6,H,,200,45
gamma,4.5,h,2,1,1
";

#[test]
fn a_bad_row_is_reported_by_its_line_and_the_others_are_planned() {
    let dir = tempfile::tempdir().unwrap();
    let list = dir.path().join("season.csv");
    // Line 4 is bad (its magnitude is not a number); a comment and a blank
    // line count as lines.
    let text =
        "# season\nname,magnitude,band,diameter_mas\nalpha,5,H,1\nbeta,5x,H,1\n\ngamma,6,H,2\n";
    std::fs::write(&list, text).unwrap();
    let out = plan_list(&list, &["--throughput", "0.01"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    let said: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(said.len(), 1, "{stderr}");
    assert!(
        said[0].contains("line 4") && said[0].contains("magnitude"),
        "{stderr}"
    );
    let rows = table(&out.stdout);
    let names: Vec<&str> = rows.iter().map(|r| r["TARGET"].as_str()).collect();
    assert_eq!(names, ["alpha", "beta", "gamma"], "every row, in order");
    let status: Vec<&str> = rows.iter().map(|r| r["status"].as_str()).collect();
    assert_eq!(status, ["ok", "error", "ok"]);
    assert_eq!(rows[1]["line"], "4");
    assert!(rows[1]["reason"].contains("not a number"));
    for r in [&rows[0], &rows[2]] {
        assert!(r["time_s"].parse::<f64>().unwrap() > 0.0, "{r:?}");
        assert_eq!(r["estimator"], "v1");
    }
    // All rows good: exit 0.
    std::fs::write(&list, THREE).unwrap();
    let out = plan_list(&list, &["--throughput", "0.01"]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn rows_faults_are_named_and_a_bad_header_refuses_the_list() {
    let text = "name,magnitude,band,ra_deg\n,5,H,1\na,5,K,1\nb,5,,1\nc,50,H,1\nd,5,H,400\na,6,H,1\ne,5,H\n";
    let rows = parse_targets(text).unwrap();
    let faults: Vec<(u64, &str)> = rows
        .iter()
        .map(|r| {
            r.as_ref()
                .map_or_else(|f| (f.line, f.reason.as_str()), |t| (t.line, ""))
        })
        .collect();
    let expect = [
        (2, "name: missing"),
        (3, "band: 'K'"),
        (4, "magnitude and band"),
        (5, "magnitude: 50 is outside"),
        (6, "ra_deg: 400 is outside"),
        (7, "name: 'a' already on line 3"),
        (8, "3 cells where the header has 4"),
    ];
    assert_eq!(faults.len(), expect.len());
    for ((line, reason), (l, r)) in faults.iter().zip(expect) {
        assert_eq!(*line, l);
        assert!(reason.starts_with(r), "line {line}: {reason}");
    }
    for bad in [
        "magnitude,band\n5,H\n",
        "name,colour\na,red\n",
        "name,name\na,b\n",
        "",
        "name\n",
    ] {
        let e = parse_targets(bad).unwrap_err();
        assert_eq!(e.param(), Some("targets"), "{bad:?}: {e}");
    }
}

/// The shared inputs of the library tests (as the CLI's SHARED flags).
fn shared() -> SharedPlan {
    SharedPlan {
        physical: Physical {
            wavelength_um: 1.65,
            bandwidth_nm: 300.0,
            aperture_m: 1.8,
            ..Physical::default()
        },
        request: PlanRequest {
            samples_per_fringe: 4.0,
            photon_rate_per_s: 1e6,
            magnitude: None,
            dead_time_s: 0.0,
            frame_rate_hz: None,
            fringe_hz: vec![500.0],
            stroke_um: vec![32.0],
            target_sigma_v2: Some(1e-2),
            time_budget_s: None,
            scans: 50,
            seed: 7,
            diameter_err_mas: 0.0,
            bias: BiasConvention::Counts,
        },
        throughput: Some(0.01),
        verify_observations: None,
    }
}

fn planned(text: &str) -> Vec<TargetRow> {
    let rows = parse_targets(text).unwrap();
    plan_targets(&shared(), &rows, 1, &|_| {}).unwrap()
}

/// A row's plan is keyed by its content: reordering the list and adding a
/// row change no bit of the other rows' answers (their line numbers aside).
/// The seed matters to the numbers (two rows alike but for their name
/// differ), so a seed taken from the row's position would fail this.
#[test]
fn a_rows_plan_does_not_depend_on_its_place_or_on_the_other_rows() {
    let first = planned(THREE);
    let reordered = "name,magnitude,band,diameter_mas,ra_deg,dec_deg
gamma,4.5,h,2,1,1
delta,5,H,1.0,10.5,-20
alpha,5,H,1.0,10.5,-20
beta,6,H,,200,45
";
    let second = planned(reordered);
    assert!(first.iter().chain(&second).all(|r| r.status == Status::Ok));
    for a in &first {
        let b = second.iter().find(|b| b.target == a.target).unwrap();
        assert_eq!(
            TargetRow {
                line: 0,
                ..a.clone()
            },
            TargetRow {
                line: 0,
                ..b.clone()
            }
        );
    }
    // alpha and delta differ only by name: different seeds, different numbers.
    let (alpha, delta) = (&second[2], &second[1]);
    assert_ne!(alpha.seed, delta.seed);
    assert_ne!(alpha.sigma_v2, delta.sigma_v2);
    assert_eq!(alpha.photon_rate_per_s, delta.photon_rate_per_s);
}

/// Every other flag is shared (the grid, the rate, the diameter), a row's
/// cell overrides it, and the table's numbers are those of `plan --json`
/// run alone for that target with its seed.
#[test]
fn shared_flags_reach_every_row_and_the_numbers_are_the_single_plans() {
    let dir = tempfile::tempdir().unwrap();
    let list = dir.path().join("list.csv");
    std::fs::write(
        &list,
        "name,magnitude,band,diameter_mas\nbright,5,H,\nplain,,,3\n",
    )
    .unwrap();
    let shared = [
        "--photon-rate-per-s",
        "2e6",
        "--diameter-mas",
        "1.5",
        "--throughput",
        "0.02",
    ];
    let out = plan_list(&list, &shared);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let rows = table(&out.stdout);
    let number =
        |r: &std::collections::HashMap<String, String>, k: &str| r[k].parse::<f64>().unwrap();
    let (bright, plain) = (&rows[0], &rows[1]);
    for r in &rows {
        assert_eq!(number(r, "fringe_hz"), 500.0, "the shared grid");
    }
    assert_eq!(number(bright, "diameter_mas"), 1.5, "the shared diameter");
    assert_eq!(number(plain, "diameter_mas"), 3.0, "the row's diameter");
    assert_eq!(number(plain, "photon_rate_per_s"), 2e6, "the shared rate");
    let magnitude = Magnitude {
        magnitude: 5.0,
        band: Band2Mass::H,
        aperture_m: 1.8,
        throughput: 0.02,
    };
    let rate = magnitude.photon_rate_per_s(1.65, 0.3).unwrap();
    assert_eq!(
        number(bright, "photon_rate_per_s"),
        rate,
        "the row's magnitude, shared throughput"
    );
    // `plain` planned alone, with its seed: the same numbers, bit for bit.
    let t = Target {
        line: 3,
        name: "plain".into(),
        magnitude: None,
        band: None,
        diameter_mas: Some(3.0),
        ra_deg: None,
        dec_deg: None,
    };
    let seed = target_seed(7, &t).to_string();
    assert_eq!(plain["seed"], seed);
    let mut args = vec![
        "plan",
        "--json",
        "--photon-rate-per-s",
        "2e6",
        "--diameter-mas",
        "3",
    ];
    args.extend_from_slice(&SHARED[..15]);
    args.extend_from_slice(&["--seed", &seed]);
    let alone = v2ref(&args);
    assert!(
        alone.status.success(),
        "{}",
        String::from_utf8_lossy(&alone.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&alone.stdout).unwrap();
    let p = &json["recommended"];
    assert_eq!(p["time_s"].as_f64(), Some(number(plain, "time_s")));
    assert_eq!(p["scans_needed"].as_f64(), Some(number(plain, "scans")));
    assert_eq!(
        p["observation"]["sigma"].as_f64(),
        Some(number(plain, "sigma_v2"))
    );
    assert!(number(plain, "sigma_v2_lower") <= number(plain, "sigma_v2"));
}

#[test]
fn the_table_file_is_written_whole_and_not_replaced_without_force() {
    let dir = tempfile::tempdir().unwrap();
    let list = dir.path().join("list.csv");
    std::fs::write(&list, "name\nonly\n").unwrap();
    let table_path = dir.path().join("table.csv");
    std::fs::write(&table_path, "mine\n").unwrap();
    let out_flag = ["--out", table_path.to_str().unwrap()];
    let out = plan_list(&list, &out_flag);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(std::fs::read_to_string(&table_path).unwrap(), "mine\n");
    let out = plan_list(&list, &[&out_flag[..], &["--force"]].concat());
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.stdout.is_empty(), "the table goes to --out, not stdout");
    let rows = table(std::fs::read_to_string(&table_path).unwrap().as_bytes());
    assert_eq!(rows.len(), 1);
    assert_eq!(rows[0]["status"], "ok");
    // A folder given as the list: refused in one line, exit 2.
    let out = plan_list(dir.path(), &[]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("regular file"));
}

/// With verification, a planned row carries the verdict (the ratio inside
/// its interval); a row no setting reaches is `unreachable` with the
/// plan's reason, not an error, and is not verified.
#[test]
fn verified_rows_carry_the_verdict_and_unreachable_rows_their_reason() {
    let mut verified = shared();
    verified.verify_observations = Some(32);
    let rows = parse_targets("name,magnitude,band,diameter_mas\nbright,4,H,1\n").unwrap();
    let table = plan_targets(&verified, &rows, 1, &|_| {}).unwrap();
    let row = &table[0];
    assert_eq!(row.status, Status::Ok);
    let ratio = row.verify_sigma_ratio.unwrap();
    let (lo, hi) = (
        row.verify_sigma_ratio_lower.unwrap(),
        row.verify_sigma_ratio_upper.unwrap(),
    );
    assert!(lo <= ratio && ratio <= hi && lo > 0.0, "{row:?}");
    assert!(row.verify_sigma_kept.is_some() && row.verify_mean_kept.is_some());
    // A target below the piston bias of a 1 mas disk at this setting
    // (about 1e-3).
    verified.request.target_sigma_v2 = Some(1e-4);
    let table = plan_targets(&verified, &rows, 1, &|_| {}).unwrap();
    let row = &table[0];
    assert_eq!(row.status, Status::Unreachable, "{row:?}");
    assert!(
        row.reason.as_deref().unwrap().contains("piston bias"),
        "{row:?}"
    );
    assert_eq!((row.estimator, row.verify_sigma_ratio), (None, None));
}
