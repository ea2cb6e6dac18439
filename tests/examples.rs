//! The examples run and say what they claim.

#[path = "../examples/check_against_golden.rs"]
mod check_against_golden;

#[path = "../examples/bias_budget.rs"]
#[allow(dead_code)]
mod bias_budget;

use std::path::Path;
use v2ref::tolerance::EXAMPLE_GOLDEN_ABS;

#[test]
fn third_party_check_passes_on_the_golden_data_and_catches_an_error() {
    let golden = Path::new(env!("CARGO_MANIFEST_DIR")).join("golden");
    let worst =
        check_against_golden::check(&golden, EXAMPLE_GOLDEN_ABS).expect("agrees with golden");
    assert!(worst < EXAMPLE_GOLDEN_ABS);
    // A golden file with one checked value (row 13) moved by 1e-4 must make the check fail.
    let dir = tempfile::tempdir().unwrap();
    for f in ["fig1_v1.csv", "fig1_v2.csv"] {
        std::fs::copy(golden.join(f), dir.path().join(f)).unwrap();
    }
    let path = dir.path().join("fig1_v2.csv");
    let text = std::fs::read_to_string(&path).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    let mut cells: Vec<String> = lines[14].split(',').map(str::to_owned).collect();
    let last = cells.len() - 1;
    let v: f64 = cells[last].parse().unwrap();
    cells[last] = format!("{:e}", v + 1e-4);
    lines[14] = cells.join(",");
    std::fs::write(&path, lines.join("\n") + "\n").unwrap();
    assert!(check_against_golden::check(dir.path(), EXAMPLE_GOLDEN_ABS).is_err());
}

#[test]
fn bias_budget_runs() {
    bias_budget::main().expect("the example runs");
}
