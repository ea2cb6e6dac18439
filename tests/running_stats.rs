//! `RunningStats` (the Monte Carlo accumulator) against answers computed
//! by hand on small samples, and its merge rule against a two-pass
//! computation on values with a large mean (issue 16: a variance divided by
//! n instead of n − 1 survived every other test, which compared the
//! accumulator only with itself).

use v2ref_core::assert_rel_eq;
use v2ref_core::montecarlo::RunningStats;
use v2ref_core::tolerance::{STREAMING_LARGE_MEAN_REL, ULPS};

/// [1, 2, 3, 4]: mean 5/2, Σ(x − x̄)² = 9/4 + 1/4 + 1/4 + 9/4 = 5, so the
/// unbiased variance is 5/3 (5/4 with the n denominator); Σ(x − x̄)³ = 0
/// by symmetry; Σ(x − x̄)⁴ = 2 (81/16) + 2 (1/16) = 41/4.
#[test]
fn one_two_three_four() {
    let s = RunningStats::from_values(&[1.0, 2.0, 3.0, 4.0]);
    assert_eq!(s.count, 4);
    assert_eq!(s.mean, 2.5);
    assert_eq!(s.m2, 5.0);
    assert_eq!(s.m3, 0.0);
    assert_eq!(s.m4, 10.25);
    assert_rel_eq!(s.variance(), 5.0 / 3.0, ULPS);
    assert_rel_eq!(s.std(), (5.0f64 / 3.0).sqrt(), ULPS);
    // √(var/n) = √(5/12).
    assert_rel_eq!(s.stderr_mean(), (5.0f64 / 12.0).sqrt(), ULPS);
    // √((μ4 − (n−3)/(n−1) s⁴)/n) with μ4 = 41/16, s⁴ = 25/9:
    // 41/16 − 25/27 = 707/432, over 4: 707/1728.
    assert_rel_eq!(s.stderr_variance(), (707.0f64 / 1728.0).sqrt(), ULPS);
    assert_rel_eq!(
        s.stderr_std(),
        (707.0f64 / 1728.0).sqrt() / (2.0 * (5.0f64 / 3.0).sqrt()),
        ULPS
    );
    let sum = s.summary();
    assert_eq!(
        (sum.count, sum.mean, sum.var, sum.std),
        (4, 2.5, s.variance(), s.std())
    );
    assert_eq!(
        (sum.stderr_mean, sum.stderr_var, sum.stderr_std),
        (s.stderr_mean(), s.stderr_variance(), s.stderr_std())
    );
}

/// A skewed sample: [0, 0, 0, 4] has mean 1, deviations −1, −1, −1, 3:
/// Σd² = 12 (variance 4), Σd³ = −3 + 27 = 24, Σd⁴ = 3 + 81 = 84.
#[test]
fn skewed_sample() {
    let s = RunningStats::from_values(&[0.0, 0.0, 0.0, 4.0]);
    assert_eq!((s.mean, s.m2, s.m3, s.m4), (1.0, 12.0, 24.0, 84.0));
    assert_eq!(s.variance(), 4.0);
    assert_eq!(s.std(), 2.0);
    assert_eq!(s.stderr_mean(), 1.0);
    // μ4 = 21, s⁴ = 16, (n−3)/(n−1) = 1/3: √((21 − 16/3)/4) = √(47/12).
    assert_rel_eq!(s.stderr_variance(), (47.0f64 / 12.0).sqrt(), ULPS);
}

/// The textbook sample [2, 4, 4, 4, 5, 5, 7, 9]: mean 5, Σd² = 32
/// (population variance 4, sample variance 32/7), deviations
/// −3, −1, −1, −1, 0, 0, 2, 4: Σd³ = −27 − 3 + 8 + 64 = 42,
/// Σd⁴ = 81 + 3 + 16 + 256 = 356.
#[test]
fn textbook_sample_and_order_independence() {
    let xs = [2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0];
    let s = RunningStats::from_values(&xs);
    assert_eq!(s.mean, 5.0);
    assert_rel_eq!(s.m2, 32.0, ULPS);
    assert_rel_eq!(s.m3, 42.0, ULPS);
    assert_rel_eq!(s.m4, 356.0, ULPS);
    assert_rel_eq!(s.variance(), 32.0 / 7.0, ULPS);
    let mut rev = xs;
    rev.reverse();
    let r = RunningStats::from_values(&rev);
    assert_rel_eq!(r.variance(), 32.0 / 7.0, ULPS);
    assert_rel_eq!(r.m3, 42.0, ULPS);
    assert_rel_eq!(r.m4, 356.0, ULPS);
}

#[test]
fn small_counts() {
    let empty = RunningStats::default();
    assert_eq!(empty.count, 0);
    assert!(empty.variance().is_nan());
    let one = RunningStats::from_values(&[7.0]);
    assert_eq!((one.count, one.mean, one.m2), (1, 7.0, 0.0));
    assert!(one.variance().is_nan());
    assert!(one.stderr_variance().is_nan());
    // Undefined statistics are NaN, never a finite number: below two values
    // every spread, below four the spread's standard errors (a constant
    // pair or triple does not have a zero error of s).
    for values in [
        &[][..],
        &[7.0],
        &[5.0, 5.0],
        &[5.0, 5.0, 5.0],
        &[1.0, 2.0, 4.0],
    ] {
        let r = RunningStats::from_values(values);
        assert!(r.stderr_std().is_nan(), "{values:?}");
        let s = r.summary();
        assert!(s.stderr_var.is_nan() && s.stderr_std.is_nan(), "{values:?}");
        if values.len() < 2 {
            assert!(
                s.var.is_nan() && s.std.is_nan() && s.stderr_mean.is_nan(),
                "{values:?}"
            );
        }
    }
    // Two values: var = (a − b)²/2.
    let two = RunningStats::from_values(&[3.0, 7.0]);
    assert_eq!(two.variance(), 8.0);
    // Below four values the variance's standard error is undefined.
    assert!(RunningStats::from_values(&[1.0, 2.0, 3.0])
        .stderr_variance()
        .is_nan());
    // A constant sample has zero spread and zero standard error of s.
    let flat = RunningStats::from_values(&[5.0; 6]);
    assert_eq!((flat.variance(), flat.stderr_std()), (0.0, 0.0));
}

#[test]
fn merge_of_small_samples_is_exact() {
    let mut a = RunningStats::from_values(&[1.0, 2.0]);
    a.merge(&RunningStats::from_values(&[3.0, 4.0]));
    assert_eq!(
        (a.count, a.mean, a.m2, a.m3, a.m4),
        (4, 2.5, 5.0, 0.0, 10.25)
    );
    assert_rel_eq!(a.variance(), 5.0 / 3.0, ULPS);
    // Unequal parts of the skewed sample, both ways round.
    for (p, q) in [
        (&[0.0][..], &[0.0, 0.0, 4.0][..]),
        (&[0.0, 0.0, 4.0][..], &[0.0][..]),
    ] {
        let mut m = RunningStats::from_values(p);
        m.merge(&RunningStats::from_values(q));
        assert_eq!((m.count, m.mean), (4, 1.0));
        assert_rel_eq!(m.m2, 12.0, ULPS);
        assert_rel_eq!(m.m3, 24.0, ULPS);
        assert_rel_eq!(m.m4, 84.0, ULPS);
        assert_rel_eq!(m.variance(), 4.0, ULPS);
    }
    // Merging with an empty accumulator changes nothing, either way.
    let s = RunningStats::from_values(&[2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0]);
    let mut e = RunningStats::default();
    e.merge(&s);
    assert_eq!(e, s);
    let mut t = s;
    t.merge(&RunningStats::default());
    assert_eq!(t, s);
}

/// 1000 values 10⁹ + u, u skewed in [0, 2): pushed in one pass and merged
/// from five unequal chunks, against a two-pass computation in which the
/// offset 10⁹ is subtracted exactly first (x − 10⁹ is exact by Sterbenz's
/// lemma for these x), so the reference has only rounding of order one.
#[test]
fn merge_matches_two_pass_at_a_large_mean() {
    const OFFSET: f64 = 1e9;
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let xs: Vec<f64> = (0..1000)
        .map(|_| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let u = (state >> 11) as f64 / (1u64 << 53) as f64;
            OFFSET + 2.0 * u * u
        })
        .collect();
    let d: Vec<f64> = xs.iter().map(|x| x - OFFSET).collect();
    let n = d.len() as f64;
    let shifted_mean = d.iter().sum::<f64>() / n;
    let c = |p: i32| d.iter().map(|x| (x - shifted_mean).powi(p)).sum::<f64>();
    let (m2, m3, m4) = (c(2), c(3), c(4));
    assert!(
        m3.abs() > 0.1 * m2.powf(1.5) / n.sqrt(),
        "the sample is skewed"
    );

    let one_pass = RunningStats::from_values(&xs);
    let mut merged = RunningStats::default();
    for chunk in [0..1, 1..100, 100..101, 101..637, 637..1000] {
        merged.merge(&RunningStats::from_values(&xs[chunk]));
    }
    for (what, s) in [("one pass", one_pass), ("merged", merged)] {
        assert_eq!(s.count, 1000, "{what}");
        // The mean, in units of the spread.
        let spread = (m2 / n).sqrt();
        assert!(
            (s.mean - (OFFSET + shifted_mean)).abs() <= STREAMING_LARGE_MEAN_REL * spread,
            "{what}: mean {} vs {}",
            s.mean,
            OFFSET + shifted_mean
        );
        assert_rel_eq!(s.m2, m2, STREAMING_LARGE_MEAN_REL, "{what}: m2");
        assert_rel_eq!(
            s.variance(),
            m2 / (n - 1.0),
            STREAMING_LARGE_MEAN_REL,
            "{what}: variance"
        );
        assert_rel_eq!(s.m4, m4, STREAMING_LARGE_MEAN_REL, "{what}: m4");
        assert!(
            (s.m3 - m3).abs() <= STREAMING_LARGE_MEAN_REL * m2.powf(1.5),
            "{what}: m3 {} vs {m3}",
            s.m3
        );
        eprintln!(
            "{what}: mean off by {:e} of the spread, m2 {:e}, m3 {:e} (of m2^1.5), m4 {:e} relative",
            (s.mean - (OFFSET + shifted_mean)).abs() / spread,
            (s.m2 / m2 - 1.0).abs(),
            (s.m3 - m3).abs() / m2.powf(1.5),
            (s.m4 / m4 - 1.0).abs()
        );
    }
}

/// `affine(a, b)` is the statistics of a·x + b: on the skewed sample
/// [1, 1, 1, 5] (mean 2, deviations −1, −1, −1, 3) with a = −2, b = 3 the
/// values are [1, 1, 1, −7], mean −1 (a mean of 1 would not tell a·x̄ from
/// a/x̄), deviations 2, 2, 2, −6: Σd² = 12 + 36 = 48, Σd³ = 24 − 216 = −192,
/// Σd⁴ = 48 + 1296 = 1344 (a², a³ and a⁴ times 12, 24, 84; an odd power
/// of a negative a is what tells a³ from |a|³ or a²).
#[test]
fn affine_map_of_a_skewed_sample() {
    let t = RunningStats::from_values(&[1.0, 1.0, 1.0, 5.0]).affine(-2.0, 3.0);
    assert_eq!(
        (t.count, t.mean, t.m2, t.m3, t.m4),
        (4, -1.0, 48.0, -192.0, 1344.0)
    );
    // The same numbers pushed directly.
    let direct = RunningStats::from_values(&[1.0, 1.0, 1.0, -7.0]);
    assert_eq!(
        (direct.mean, direct.m2, direct.m3, direct.m4),
        (-1.0, 48.0, -192.0, 1344.0)
    );
}
