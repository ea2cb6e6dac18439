//! The examples run and say what they claim.

#[path = "../examples/check_against_golden.rs"]
mod check_against_golden;

#[path = "../examples/bias_budget.rs"]
mod bias_budget;

use std::f64::consts::PI;
use std::path::Path;
use v2ref_core::assert_abs_eq;
use v2ref_core::formalism::source::ARCSEC_PER_MAS;
use v2ref_core::math::special::jinc;
use v2ref_core::tolerance::{BESSEL_ABS, EXAMPLE_GOLDEN_ABS, IDENTITY_ABS};

#[test]
#[ignore = "slow tier: the third-party example against the golden data (11 s)"]
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

/// The budget's numbers are what they must be: V mono is the uniform
/// disk's |2 J1(z)/z| at z = π θ S (the Bessel closed form), and V1 does
/// not see the dispersion (it weights |V|² only, so the phase cancels).
/// Power: the visibility of a disk 1 % larger differs from the budget's
/// by more than the tolerance at every baseline but the shortest few.
#[test]
fn bias_budget_states_true_numbers() {
    let rows = bias_budget::budget().expect("the example runs");
    assert_eq!(rows.len(), 11);
    let disk = |theta_mas: f64, s: f64| jinc(PI * theta_mas * ARCSEC_PER_MAS * s).abs();
    let mut planted_caught = 0;
    for r in &rows {
        assert_abs_eq!(
            r.v_mono.abs(),
            disk(bias_budget::DIAMETER_MAS, r.s_cpas),
            BESSEL_ABS
        );
        assert_abs_eq!(r.dv1_disp, r.dv1_band, IDENTITY_ABS);
        let planted = disk(1.01 * bias_budget::DIAMETER_MAS, r.s_cpas);
        if (planted - r.v_mono.abs()).abs() > BESSEL_ABS {
            planted_caught += 1;
        }
    }
    assert!(planted_caught > rows.len() / 2, "{planted_caught}");
    bias_budget::main().expect("the example prints");
}
