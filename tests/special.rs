//! Bessel functions against mpmath (tests/data/bessel_reference.csv, 50-digit
//! reference with its generator beside it).

use v2ref_core::math::special::SERIES_BELOW;
use v2ref_core::math::special::{bessel_j0, bessel_j0_j1, bessel_j1, bessel_j1_zero, jinc};
use v2ref_core::tolerance::{BESSEL_ABS, BESSEL_ZERO_REL, FINITE_DIFFERENCE_REL, ROUNDING_REL};

fn reference() -> Vec<Vec<String>> {
    include_str!("data/bessel_reference.csv")
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| l.split(',').map(str::to_owned).collect())
        .collect()
}

#[test]
fn j0_j1_jinc_match_mpmath_to_1e_14() {
    let mut worst = 0.0_f64;
    let mut count = 0;
    for row in reference().iter().filter(|r| r[0] == "value") {
        let x: f64 = row[1].parse().unwrap();
        let (j0, j1, jc): (f64, f64, f64) = (
            row[2].parse().unwrap(),
            row[3].parse().unwrap(),
            row[4].parse().unwrap(),
        );
        let (c0, c1) = bessel_j0_j1(x);
        assert_eq!(
            (bessel_j0(x), bessel_j1(x)),
            (c0, c1),
            "the one-order forms at {x}"
        );
        for (got, want, what) in [(c0, j0, "J0"), (c1, j1, "J1"), (jinc(x), jc, "jinc")] {
            let err = (got - want).abs();
            worst = worst.max(err);
            assert!(
                err <= BESSEL_ABS,
                "{what}({x}) = {got}, mpmath {want}, error {err:e}"
            );
        }
        // Below the series switch J1 ≈ x/2 is tiny: relative accuracy.
        if x > 0.0 && x < SERIES_BELOW {
            assert!(
                ((c1 - j1) / j1).abs() <= ROUNDING_REL,
                "J1({x}) = {c1}, mpmath {j1}"
            );
        }
        // Parity: J1 is odd, J0 and jinc even.
        let (m0, m1) = bessel_j0_j1(-x);
        assert_eq!((m0, m1), (c0, -c1));
        assert_eq!(jinc(-x), jinc(x));
        count += 1;
    }
    assert!(count > 250, "reference table too short: {count} rows");
    eprintln!("worst Bessel error over {count} points: {worst:e}");
}

#[test]
fn j1_zeros_match_mpmath() {
    let mut count = 0;
    for row in reference().iter().filter(|r| r[0] == "zero") {
        let s: u32 = row[1].parse().unwrap();
        let want: f64 = row[2].parse().unwrap();
        let got = bessel_j1_zero(s);
        assert!(
            ((got - want) / want).abs() <= BESSEL_ZERO_REL,
            "zero {s}: {got} vs {want}"
        );
        count += 1;
    }
    assert_eq!(count, 30);
    assert!(bessel_j1_zero(0).is_nan());
}

#[test]
fn wronskian_identity_holds() {
    // J1'(x) = J0(x) − J1(x)/x and the recurrence J0 + J2 = (2/x) J1 give,
    // with the derivative by central differences, an identity independent of
    // the tabulated values: d/dx[x J1(x)] = x J0(x).
    for k in 1..400 {
        let x = 0.25 * k as f64;
        let h = 1e-5;
        let d = ((x + h) * bessel_j0_j1(x + h).1 - (x - h) * bessel_j0_j1(x - h).1) / (2.0 * h);
        let want = x * bessel_j0_j1(x).0;
        assert!(
            (d - want).abs() < FINITE_DIFFERENCE_REL * x.max(1.0),
            "x = {x}: {d} vs {want}"
        );
    }
}
