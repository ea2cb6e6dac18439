//! Dispersion (paper, Section "Effect of chromatic dispersion", Fig. 2):
//! the Fresnel integrals against mpmath, the closed-form V2 of a point
//! source against the numerical path, V1's blindness to the phase, and the
//! fluoride-glass dispersion helper.

use proptest::prelude::*;
use v2ref_core::assert_rel_eq;
use v2ref_core::bias::dispersion;
use v2ref_core::formalism::estimator::{v1_sq, v2_sq};
use v2ref_core::formalism::observation::{Frequency, Observation};
use v2ref_core::formalism::phase::SpectralPhase;
use v2ref_core::formalism::source::Source;
use v2ref_core::formalism::spectrum::{Band, Spectrum};
use v2ref_core::math::special::{fresnel_c, fresnel_cs, fresnel_s, point_source_v2_sq};
use v2ref_core::tolerance::{
    CLOSED_FORM_VS_NUMERICAL, FINITE_DIFFERENCE_REL, FRESNEL_ABS, GLASS_DISPERSION_REL,
    LEADING_TERM_REL, POWER_FACTOR, RESIDUAL_CUBIC_REL, RESIDUAL_PHASE_REL, ROUNDING_REL,
    SECOND_DIFFERENCE_ABS, SMALL_P_EXPANSION_ABS, ULPS,
};

fn reference() -> Vec<Vec<String>> {
    include_str!("data/fresnel_reference.csv")
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| l.split(',').map(str::to_owned).collect())
        .collect()
}

/// Rows `(kind, x, value)` of tests/data/zblan_reference.csv.
fn zblan_reference() -> Vec<(String, f64, f64)> {
    include_str!("data/zblan_reference.csv")
        .lines()
        .filter(|l| !l.starts_with('#'))
        .skip(1)
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (
                f[0].to_owned(),
                f[1].parse().unwrap(),
                f[2].parse().unwrap(),
            )
        })
        .collect()
}

#[test]
fn zblan_index_and_dispersion_match_the_sellmeier_formula_in_mpmath() {
    // tests/data/zblan_reference.csv: Gan's formula in its wavelength form,
    // 50 digits, and its second derivative by mpmath (generator beside it).
    // The crate evaluates n from the wavenumber (a few roundings, far below
    // ROUNDING_REL) and D by a five-point difference (GLASS_DISPERSION_REL);
    // a wrong sign or operator moves n by ≥ 1e-4 and P by far more.
    let rows = zblan_reference();
    for (_, lambda, want) in rows.iter().filter(|r| r.0 == "n") {
        let got = dispersion::zblan_index(1.0 / lambda);
        assert_rel_eq!(got, *want, ROUNDING_REL, "n at {lambda} µm");
    }
    for (_, length_um, want) in rows.iter().filter(|r| r.0 == "p2p") {
        let got = dispersion::zblan_peak_to_peak_rad(1.0 / 2.4, 1.0 / 2.0, *length_um).unwrap();
        assert_rel_eq!(got, *want, GLASS_DISPERSION_REL, "P of {length_um} µm");
    }
    assert_eq!(rows.len(), 10);
}

#[test]
fn residual_phase_of_polynomial_indices_has_its_closed_form() {
    // φ = 2πσ n(σ) L less its value and slope at the band centre s0, peak to
    // peak over [s0 − a, s0 + a]. The slope comes from a central difference
    // (h = 1e-4 µm⁻¹) of a phase ~4e4 rad: ~1e-7 rad µm of rounding, ~4e-9
    // rad over the half-band, ~4e-10 of these 10-rad residuals, well inside
    // FINITE_DIFFERENCE_REL.
    use std::f64::consts::PI;
    let (s0, a, l) = (0.45, 0.04, 1e4);
    let (lo, hi) = (s0 - a, s0 + a);
    // n = 1.4 + bσ: residual 2πLb u², u = σ − s0, from 0 to 2πLb a².
    let b = 0.1;
    let got = dispersion::residual_peak_to_peak(|s| 1.4 + b * s, lo, hi, l).unwrap();
    assert_rel_eq!(got, 2.0 * PI * l * b * a * a, FINITE_DIFFERENCE_REL);
    // n = 1.4 + cσ²: residual 2πLc u²(u + 3 s0), from 0 (u = 0) to
    // 2πLc a²(a + 3 s0) (u = a): the cubic term makes the ends unequal.
    let c = 0.1;
    let got = dispersion::residual_peak_to_peak(|s| 1.4 + c * s * s, lo, hi, l).unwrap();
    assert_rel_eq!(
        got,
        2.0 * PI * l * c * a * a * (a + 3.0 * s0),
        RESIDUAL_CUBIC_REL
    );
    // With the opposite curvature the residual is ≤ 0: the peak-to-peak is
    // max − min = 0 − (−P), the same P (a sum max + min would give −P).
    let got = dispersion::residual_peak_to_peak(|s| 1.4 - c * s * s, lo, hi, l).unwrap();
    assert_rel_eq!(
        got,
        2.0 * PI * l * c * a * a * (a + 3.0 * s0),
        RESIDUAL_CUBIC_REL
    );
    // A constant index leaves nothing beyond the linear term (rounding only).
    // tol: a constant index leaves a linear phase, removed to the rounding of phases of order 2π n l σ; 1e-6 rad is far below the residuals compared elsewhere (tenths of a rad) and above that rounding.
    assert!(dispersion::residual_peak_to_peak(|_| 1.5, lo, hi, l).unwrap() < 1e-6);
}

#[test]
fn fresnel_matches_mpmath() {
    let mut n = 0;
    for row in reference().iter().filter(|r| r[0] == "value") {
        let x: f64 = row[1].parse().unwrap();
        let (c_ref, s_ref): (f64, f64) = (row[2].parse().unwrap(), row[3].parse().unwrap());
        let (c, s) = fresnel_cs(x);
        assert_eq!(
            (fresnel_c(x), fresnel_s(x)),
            (c, s),
            "the one-integral forms at {x}"
        );
        assert!(
            (c - c_ref).abs() <= FRESNEL_ABS,
            "C({x}) = {c}, mpmath {c_ref}"
        );
        assert!(
            (s - s_ref).abs() <= FRESNEL_ABS,
            "S({x}) = {s}, mpmath {s_ref}"
        );
        n += 1;
    }
    assert!(n > 150, "only {n} reference rows");
}

#[test]
fn fresnel_limits_and_symmetry() {
    assert_eq!(fresnel_cs(0.0), (0.0, 0.0));
    assert_eq!(fresnel_cs(f64::INFINITY), (0.5, 0.5));
    for x in [0.3, 1.49, 1.51, 7.0] {
        let (c, s) = fresnel_cs(x);
        assert_eq!(fresnel_cs(-x), (-c, -s));
    }
    // Small x: C ≈ x, S ≈ π x³/6.
    let (c, s) = fresnel_cs(1e-3);
    assert_rel_eq!(c, 1e-3, LEADING_TERM_REL);
    assert_rel_eq!(s, std::f64::consts::PI * 1e-9 / 6.0, LEADING_TERM_REL);
}

#[test]
fn point_source_closed_form_matches_mpmath_quadrature() {
    for row in reference().iter().filter(|r| r[0] == "v2point") {
        let p: f64 = row[1].parse().unwrap();
        let want: f64 = row[2].parse().unwrap();
        let got = point_source_v2_sq(p);
        assert!(
            (got - want).abs() < ROUNDING_REL,
            "P = {p}: {got} vs mpmath {want}"
        );
    }
    assert_eq!(point_source_v2_sq(0.0), 1.0);
}

fn k_band() -> Spectrum {
    Spectrum::flat(Band::k())
}

fn numerical_point_v2_sq(pp: f64) -> f64 {
    let band = k_band();
    let obs = Observation::new(
        band.clone(),
        Source::Point,
        Frequency::BaselineM(0.0),
        SpectralPhase::dispersion_peak_to_peak(&band, pp).unwrap(),
    )
    .unwrap();
    v2_sq(&obs)
}

#[test]
fn closed_form_matches_the_numerical_path_to_1e_10() {
    for k in 0..=40 {
        let pp = 0.1 * k as f64;
        let (a, b) = (numerical_point_v2_sq(pp), point_source_v2_sq(pp));
        assert!(
            (a - b).abs() < CLOSED_FORM_VS_NUMERICAL,
            "P = {pp}: {a} vs {b}"
        );
    }
    // And the check has power: a 1% error in P is seen.
    let (a, b) = (numerical_point_v2_sq(1.0), point_source_v2_sq(1.01));
    assert!((a - b).abs() > POWER_FACTOR * CLOSED_FORM_VS_NUMERICAL);
}

#[test]
fn dispersion_lowers_v2_monotonically_in_the_figure_range() {
    let v: Vec<f64> = [0.0, 1.0, 1.5, 2.0]
        .iter()
        .map(|&p| point_source_v2_sq(p))
        .collect();
    assert!(v.windows(2).all(|w| w[1] < w[0]), "{v:?}");
    // V2 of an unresolved source always loses to dispersion (|mean of a
    // unit phasor| < 1), by the numerical path as well.
    for p in [0.5, -0.5, 3.0] {
        // tol: a margin, not a rounding: a loss of V2² above 1e-3 tells dispersion's loss (several percent at 0.5 rad) from V2² = 1 up to rounding.
        assert!(numerical_point_v2_sq(p) < 1.0 - 1e-3);
    }
    // Small-P expansion: V2² ≈ 1 − 4P²/45.
    let p = 0.01;
    assert!((point_source_v2_sq(p) - (1.0 - 4.0 * p * p / 45.0)).abs() < SMALL_P_EXPANSION_ABS);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// V1² does not see the spectral phase (infinite scan), whatever the
    /// disk, the spatial frequency and the dispersion.
    #[test]
    fn v1_is_blind_to_dispersion(
        diameter in 1.0f64..100.0,
        s in 0.0f64..80.0,
        pp in -5.0f64..5.0,
        bandwidth in 0.05f64..0.6,
    ) {
        let band = Spectrum::flat(Band::new(2.2, bandwidth).unwrap());
        let obs = |p: f64| Observation::new(
            band.clone(),
            Source::UniformDisk { diameter_mas: diameter },
            Frequency::SpatialFreqCpas(s),
            SpectralPhase::dispersion_peak_to_peak(&band, p).unwrap(),
        ).unwrap();
        let (a, b) = (v1_sq(&obs(pp)), v1_sq(&obs(0.0)));
        prop_assert!((a - b).abs() <= ULPS, "{a} vs {b}");
    }
}

#[test]
fn glass_dispersion_identities() {
    // A constant index gives a phase linear in σ: no dispersion.
    let d0 = dispersion::dispersion_coefficient(|_| 1.5, 0.45, 1e4).unwrap();
    assert!(d0.abs() < SECOND_DIFFERENCE_ABS, "{d0}");
    // n = a + bσ: φ = 2πL(aσ + bσ²), D = 4πLb.
    let (b, l) = (0.01, 1e4);
    let d = dispersion::dispersion_coefficient(|s| 1.4 + b * s, 0.45, l).unwrap();
    let want = 4.0 * std::f64::consts::PI * l * b;
    assert_rel_eq!(d, want, FINITE_DIFFERENCE_REL);
    // Peak-to-peak scales linearly with the glass length.
    let (lo, hi) = (1.0 / 2.4, 1.0 / 2.0);
    let p1 = dispersion::zblan_peak_to_peak_rad(lo, hi, 1e4).unwrap();
    let p2 = dispersion::zblan_peak_to_peak_rad(lo, hi, 2e4).unwrap();
    assert!((p2 - 2.0 * p1).abs() < RESIDUAL_PHASE_REL * p2);
    // ZBLAN's index near 2.2 µm is about 1.49 (Gan 1995).
    let n = dispersion::zblan_index(1.0 / 2.2);
    assert!((1.48..1.50).contains(&n), "{n}");
    assert!(dispersion::dispersion_coefficient(|_| 1.5, -1.0, 1.0).is_err());
}
