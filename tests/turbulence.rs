//! The turbulence model: Kolmogorov constants and integrals against mpmath
//! (tests/data/turbulence_reference.csv, generator beside it), the piston
//! variance two independent ways, and the spectrum's asymptotes and corners.

use std::f64::consts::PI;
use std::sync::{Arc, OnceLock};
use v2ref_core::piston::spectrum::{
    differential_piston_variance_from_structure_um2, PistonPsdModel, PistonSpectrum,
};
use v2ref_core::piston::transverse::{transverse_integral, TransverseTable};
use v2ref_core::piston::turbulence::{
    profile_integral, psd_coefficient, r0_from_seeing_m, structure_coefficient, Turbulence,
};
use v2ref_core::tolerance::{
    ASYMPTOTIC_LIMIT_REL, CORNER_REL, DECADE_SLOPE_ABS, GAMMA_REL, LOW_FREQ_SLOPE_COEFF,
    LOW_FREQ_VALUE_COEFF, MID_FREQ_SLOPE_COEFF, MID_FREQ_VALUE_COEFF, PRINTED_3_DECIMALS_ABS,
    PSD_TABLE_CORNER_REL, PSD_TABLE_REL, PSD_TABLE_WIGGLE_REL, ROUNDING_REL, TURBULENCE_CHECK_REL,
    TURBULENCE_SPECTRAL_REL, TURBULENCE_TAIL_REL, ULPS,
};
use v2ref_core::{assert_abs_eq, Error};

const D: f64 = 0.45;

fn paper() -> Turbulence {
    Turbulence::from_seeing(1.0, 2.2, 10.0, None).unwrap()
}

/// The piston spectrum of [`paper`] for apertures of D on `baseline_m`,
/// every call sharing one table of G (G depends on the turbulence and D
/// only; at opt-level 0, as in the mutation runs, each table costs ~6 s).
fn paper_spectrum(baseline_m: f64) -> PistonSpectrum {
    static TABLE: OnceLock<Arc<TransverseTable>> = OnceLock::new();
    let table = TABLE.get_or_init(|| Arc::new(TransverseTable::new(paper(), D).unwrap()));
    PistonSpectrum::from_table(Arc::clone(table), baseline_m).unwrap()
}

fn reference(name: &str) -> Vec<(f64, f64)> {
    include_str!("data/turbulence_reference.csv")
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| l.split(',').collect::<Vec<_>>())
        .filter(|c| c[0] == name)
        .map(|c| (c[1].parse().unwrap(), c[2].parse().unwrap()))
        .collect()
}

fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

#[test]
fn kolmogorov_constants_match_mpmath() {
    let cd = reference("C_D")[0].1;
    let cphi = reference("C_Phi")[0].1;
    assert!(
        rel(structure_coefficient(), cd) < GAMMA_REL,
        "{}",
        structure_coefficient()
    );
    assert!(
        rel(psd_coefficient(), cphi) < GAMMA_REL,
        "{}",
        psd_coefficient()
    );
    // The profile integrals by Gamma functions against mpmath's quadrature.
    for (a, want) in reference("I") {
        assert!(rel(profile_integral(a), want) < GAMMA_REL, "I({a})");
    }
}

#[test]
fn r0_and_coherence_time_follow_the_conventions() {
    let r0 = r0_from_seeing_m(1.0, 2.2).unwrap();
    // λ/seeing, with 1 arcsec = π/648000 rad.
    assert!(rel(r0, 2.2e-6 * 648_000.0 / PI) < ULPS);
    let t = paper();
    assert!(rel(t.coherence_time_s(), r0 / 10.0) < ULPS);
    // The parameters read back as given; the wind changes only the wind.
    let l0 = Turbulence::from_seeing(0.8, 1.65, 7.5, Some(25.0)).unwrap();
    assert_eq!(
        (l0.wavelength_um(), l0.wind_mps(), l0.outer_scale_m()),
        (1.65, 7.5, Some(25.0))
    );
    assert_eq!(l0.r0_m(), r0_from_seeing_m(0.8, 1.65).unwrap());
    let gusty = l0.with_wind(20.0).unwrap();
    assert_eq!(
        (gusty.r0_m(), gusty.wavelength_um(), gusty.outer_scale_m()),
        (l0.r0_m(), 1.65, Some(25.0))
    );
    assert_eq!((t.outer_scale_m(), t.wavelength_um()), (None, 2.2));
    // The OPD spectrum does not depend on the wavelength when r0 ∝ λ^{6/5}.
    let t2 = Turbulence::new(r0 * (1.65f64 / 2.2).powf(1.2), 1.65, 10.0, None).unwrap();
    assert!(rel(t2.opd_psd(0.37), t.opd_psd(0.37)) < GAMMA_REL);
    // Seeing 0 is no turbulence.
    let none = Turbulence::from_seeing(0.0, 2.2, 10.0, None).unwrap();
    assert_eq!(none.opd_psd(1.0), 0.0);
    let s = PistonSpectrum::new(none, D, 18.0).unwrap();
    assert_eq!(s.variance_um2(), 0.0);
    assert_eq!(s.psd_um2_per_hz(1.0), 0.0);
}

#[test]
fn bad_parameters_are_typed_errors() {
    assert!(matches!(
        Turbulence::from_seeing(1.0, 2.2, 0.0, None),
        Err(Error::OutOfRange {
            param: "wind_mps",
            ..
        })
    ));
    assert!(matches!(
        Turbulence::from_seeing(-1.0, 2.2, 10.0, None),
        Err(Error::OutOfRange {
            param: "seeing_arcsec",
            ..
        })
    ));
    assert!(matches!(
        Turbulence::from_seeing(1.0, 2.2, 10.0, Some(-3.0)),
        Err(Error::OutOfRange {
            param: "outer_scale_m",
            ..
        })
    ));
    assert!(matches!(
        PistonSpectrum::new(paper(), 0.0, 18.0),
        Err(Error::OutOfRange {
            param: "aperture_m",
            ..
        })
    ));
    assert!(matches!(
        PistonSpectrum::new(paper(), D, f64::NAN),
        Err(Error::NotFinite {
            param: "baseline_m",
            ..
        })
    ));
}

#[test]
fn transverse_integral_matches_mpmath() {
    let t = paper();
    for (fx, want) in reference("G") {
        let direct = transverse_integral(&t, D, fx);
        // 1e-8: the tail beyond 100/D is added with the Bessel oscillation
        // averaged, which leaves ~3e-9 of G at f D = 3 (and 1e-11 at f D =
        // 1, below 1e-13 at f D ≤ 0.1).
        let tol = if fx * D <= 1.0 {
            TURBULENCE_CHECK_REL
        } else {
            TURBULENCE_TAIL_REL
        };
        assert!(rel(direct, want) < tol, "G({fx}) = {direct}, mpmath {want}");
    }
}

#[test]
fn the_table_of_g_matches_mpmath() {
    let s = paper_spectrum(18.0);
    for (fx, want) in reference("G") {
        // The tabulated spectrum at ν = v f_x (away from the cosine's zeros).
        let nu = 10.0 * fx;
        let factor = 4.0 * (PI * 18.0 * nu / 10.0).sin().powi(2);
        let tab = s.psd_um2_per_hz(nu) * 10.0 / factor;
        // Beyond f D ~ 1 the table under-resolves the surviving Bessel
        // wiggle (period 1/D), where P is below 1e-6 of its peak.
        let tol = if fx * D <= 1.0 {
            PSD_TABLE_REL
        } else {
            PSD_TABLE_WIGGLE_REL
        };
        assert!(rel(tab, want) < tol, "table G({fx}) = {tab}, mpmath {want}");
    }
}

#[test]
fn table_matches_direct_quadrature_over_the_range_that_carries_power() {
    let s = paper_spectrum(18.0);
    let mut worst: f64 = 0.0;
    // ν up to 3 v/D (beyond, P is below 1e-8 of its low-frequency value).
    for i in 0..60 {
        let nu = 1e-4 * 10f64.powf(i as f64 * 0.0895) * 1.0137;
        let (a, b) = (s.psd_um2_per_hz(nu), s.psd_direct_um2_per_hz(nu));
        if b > 0.0 {
            worst = worst.max(rel(a, b));
        }
    }
    // Catmull–Rom on 80 points per decade of ln G: ~3e-5 near the corner.
    assert!(
        worst < PSD_TABLE_CORNER_REL,
        "worst relative error {worst:e}"
    );
}

#[test]
fn variance_from_the_spectrum_equals_the_structure_function_and_mpmath() {
    let t = paper();
    let want = reference("var_sf")[0].1;
    let spectral = paper_spectrum(18.0).variance_um2();
    let pupil = differential_piston_variance_from_structure_um2(&t, D, 18.0);
    assert!(
        rel(pupil, want) < TURBULENCE_CHECK_REL,
        "pupil-plane {pupil}, mpmath {want}"
    );
    assert!(
        rel(spectral, want) < TURBULENCE_SPECTRAL_REL,
        "spectral {spectral}, mpmath {want}"
    );
    // Other geometries, including overlapping apertures (B < D).
    for (d, b) in [(0.45, 0.3), (1.8, 5.0), (8.0, 47.0), (0.1, 200.0)] {
        let a = PistonSpectrum::new(t, d, b).unwrap().variance_um2();
        let c = differential_piston_variance_from_structure_um2(&t, d, b);
        assert!(rel(a, c) < TURBULENCE_TAIL_REL, "D {d} B {b}: {a} vs {c}");
    }
    // For B ≫ D the variance tends to the point structure function.
    let far = PistonSpectrum::new(t, 0.01, 1000.0).unwrap().variance_um2();
    assert!(rel(far, t.opd_structure_function_um2(1000.0)) < ASYMPTOTIC_LIMIT_REL);
}

#[test]
fn variance_is_the_integral_of_the_temporal_spectrum() {
    let s = paper_spectrum(18.0);
    // ∫_{−∞}^{∞} P dν = 2 ∫_0^∞ P dν, in ln ν with tails from the asymptotes.
    let (lo, hi) = (1e-6_f64, 200.0_f64);
    let integrand = |u: f64| {
        let nu = u.exp();
        nu * s.psd_um2_per_hz(nu)
    };
    let mut breaks = vec![lo.ln()];
    while *breaks.last().unwrap() < hi.ln() {
        breaks.push(breaks.last().unwrap() + 0.01);
    }
    let body = v2ref_core::math::quadrature::integrate_pieces(
        &integrand,
        &breaks,
        v2ref_core::math::quadrature::Tolerance {
            abs: 0.0,
            rel: TURBULENCE_CHECK_REL,
        },
    );
    let low_tail = s.asymptote_low(lo) * lo * 3.0; // ∫_0^lo c ν^{−2/3} = 3 c lo^{1/3}
    let total = 2.0 * (body + low_tail);
    let want = s.variance_um2();
    assert!(
        rel(total, want) < PSD_TABLE_REL,
        "∫P = {total}, variance {want}"
    );
}

#[test]
fn asymptotes_slopes_and_corners() {
    let t = paper();
    let s = paper_spectrum(18.0);
    let v = 10.0;
    let slope = |f: &dyn Fn(f64) -> f64, x: f64| {
        let h = 1e-3;
        (f(x * (1.0 + h)).ln() - f(x * (1.0 - h)).ln()) / (2.0 * h)
    };
    // Low frequencies: P → (2πB)² K I(11/6) v^{-1/3} ν^{-2/3}, slope −2/3.
    for r in [1e-4, 1e-3, 1e-2] {
        let nu = r * s.corner_low_hz();
        let p = s.psd_direct_um2_per_hz(nu);
        assert!(
            rel(p, s.asymptote_low(nu)) < LOW_FREQ_VALUE_COEFF * r,
            "low ratio at {r}"
        );
        let sl = slope(&|x| s.psd_direct_um2_per_hz(x), nu);
        assert!(
            (sl + 2.0 / 3.0).abs() < LOW_FREQ_SLOPE_COEFF * r,
            "low slope {sl} at {r}"
        );
    }
    // Middle: G = v P / 2(1 − cos) → K I(11/6) f^{−8/3}; the relative error
    // falls as (f D)².
    let g = |fx: f64| transverse_integral(&t, D, fx);
    let mid_g = |fx: f64| s.asymptote_mid(v * fx) * v / 2.0;
    for fd in [1e-3, 1e-2] {
        let fx = fd / D;
        assert!(
            rel(g(fx), mid_g(fx)) < MID_FREQ_VALUE_COEFF * fd * fd,
            "mid at fD {fd}"
        );
        assert!((slope(&g, fx) + 8.0 / 3.0).abs() < MID_FREQ_SLOPE_COEFF * fd * fd);
    }
    // High: G → K 4/(π⁴D³) I(10/3) f^{−17/3}; the Bessel oscillation
    // survives the f_y integral with a relative amplitude ~ (f D)^{−1/2}.
    let high_g = |fx: f64| s.asymptote_high(v * fx) * v / 2.0;
    let mut last = f64::INFINITY;
    for fd in [10.0, 30.0, 100.0, 300.0] {
        let fx = fd / D;
        let e = rel(g(fx), high_g(fx));
        // tol: not a fixed tolerance: the relative amplitude ~ (f D)^{-1/2} of the oscillating term (comment above).
        assert!(e < 1.0 / fd.sqrt(), "high at fD {fd}: {e}");
        assert!(e < last, "high-frequency error does not fall at fD {fd}");
        last = e;
    }
    // Decade-averaged slope −17/3 between f D = 30 and 300.
    let decade = (g(300.0 / D) / g(30.0 / D)).ln() / 10f64.ln();
    assert!(
        (decade + 17.0 / 3.0).abs() < DECADE_SLOPE_ABS,
        "decade slope {decade}"
    );
    // Corners: the crossings of the asymptotes, 0.225 v/B and 0.299 v/D.
    let c1 = s.corner_low_hz();
    let c2 = s.corner_high_hz();
    assert!(rel(s.asymptote_low(c1), s.asymptote_mid(c1)) < CORNER_REL);
    assert!(rel(s.asymptote_mid(c2), s.asymptote_high(c2)) < CORNER_REL);
    assert!(rel(c1 * 18.0 / v, 1.0 / (2f64.sqrt() * PI)) < ROUNDING_REL);
    assert_abs_eq!(c2 * D / v, 0.2994, PRINTED_3_DECIMALS_ABS);
    // The computed spectrum turns there: its local slope passes half-way
    // between −8/3 and −17/3 within a factor 2 of the high corner.
    let mut x = 0.05 / D;
    while slope(&g, x) > -25.0 / 6.0 {
        x *= 1.01;
    }
    let ratio = x / (c2 / v);
    assert!(
        (0.5..2.0).contains(&ratio),
        "half-slope at {ratio} x corner"
    );
}

#[test]
fn the_middle_asymptote_is_the_period_average_of_the_spectrum() {
    // The middle asymptote is the cosine's average: average P over one
    // period of 2(1 − cos(2πBν/v)) on a long baseline.
    // (20 km: 0.5 mHz periods, 40 of them at 0.02 Hz, where f D = 9e-4.)
    let long = paper_spectrum(20_000.0);
    let period = 10.0 / 20_000.0;
    let nu0 = 0.02;
    let n = 40 * 64;
    let at = |i: usize| nu0 + (i as f64 + 0.5) / 64.0 * period;
    let avg: f64 = (0..n).map(|i| long.psd_um2_per_hz(at(i))).sum::<f64>() / n as f64;
    let mid_avg: f64 = (0..n).map(|i| long.asymptote_mid(at(i))).sum::<f64>() / n as f64;
    assert!(
        rel(avg, mid_avg) < ASYMPTOTIC_LIMIT_REL,
        "period average {avg} vs {mid_avg}"
    );
}

#[test]
fn von_karman_outer_scale_reduces_and_saturates_the_piston() {
    let k = paper();
    let vk = Turbulence::from_seeing(1.0, 2.2, 10.0, Some(20.0)).unwrap();
    // The outer-scale correction falls only as (B/L0)^{1/3}.
    let huge = Turbulence::from_seeing(1.0, 2.2, 10.0, Some(1e12)).unwrap();
    let rms = |t: Turbulence, b: f64| PistonSpectrum::new(t, D, b).unwrap().rms_um();
    assert!(rel(rms(huge, 18.0), rms(k, 18.0)) < ASYMPTOTIC_LIMIT_REL);
    assert!(rms(vk, 18.0) < rms(k, 18.0));
    // tol: Saturation: from 50 to 100 m the von Kármán piston grows by < 1 %,
    // the Kolmogorov one by 2^{5/6} roughly.
    assert!(rms(vk, 100.0) / rms(vk, 50.0) < 1.01);
    assert!(rms(k, 100.0) / rms(k, 50.0) > 1.7);
}

#[test]
fn seeing_quoted_at_another_wavelength_scales_r0_as_lambda_6_5() {
    use v2ref_core::piston::turbulence::seeing_at_wavelength_arcsec;
    use v2ref_core::tolerance::HAND_10_DIGITS_REL;
    // 1″ at 0.5 µm: r0 = 0.5 µm / 1″ = 0.1031324031 m there, and
    // 0.1031324031 × 4.4^1.2 = 0.6102929447 m at 2.2 µm (by hand).
    let k = seeing_at_wavelength_arcsec(1.0, 0.5, 2.2).unwrap();
    let t = Turbulence::from_seeing(k, 2.2, 10.0, None).unwrap();
    v2ref_core::assert_rel_eq!(t.r0_m(), 0.610_292_944_7, HAND_10_DIGITS_REL);
    // Identities: the same wavelength changes nothing; conversions compose;
    // zero seeing stays zero.
    assert_eq!(seeing_at_wavelength_arcsec(0.8, 1.65, 1.65).unwrap(), 0.8);
    let via_h = seeing_at_wavelength_arcsec(
        seeing_at_wavelength_arcsec(0.8, 0.5, 1.65).unwrap(),
        1.65,
        2.2,
    )
    .unwrap();
    v2ref_core::assert_rel_eq!(
        via_h,
        seeing_at_wavelength_arcsec(0.8, 0.5, 2.2).unwrap(),
        ROUNDING_REL
    );
    assert_eq!(seeing_at_wavelength_arcsec(0.0, 0.5, 2.2).unwrap(), 0.0);
    let e = seeing_at_wavelength_arcsec(1.0, 0.0, 2.2).unwrap_err();
    assert_eq!(e.param(), Some("seeing_wavelength_um"));
}

#[test]
fn cli_seeing_wavelength_flag_converts_before_the_piston() {
    let r0 = |extra: &[&str]| -> f64 {
        let mut args = vec![
            "piston",
            "--json",
            "--quiet",
            "--scans",
            "10",
            "--fringe-hz",
            "100",
        ];
        args.extend_from_slice(extra);
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_v2ref"))
            .args(&args)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        json["r0_m"].as_f64().unwrap()
    };
    // Quoted at the observing wavelength (the default), nothing changes.
    assert_eq!(r0(&["--seeing-wavelength-um", "2.2"]), r0(&[]));
    // 1″ at 0.5 µm is r0 = 0.6102929447 m in K (by hand, above).
    v2ref_core::assert_rel_eq!(
        r0(&["--seeing-wavelength-um", "0.5"]),
        0.610_292_944_7,
        v2ref_core::tolerance::HAND_10_DIGITS_REL
    );
}

/// `2 ∫_lo^hi P dν` in ln ν, plus the ν^{−2/3} tail below `lo` from
/// `low_coeff · ν^{−2/3}`.
fn two_sided_integral(psd: &dyn Fn(f64) -> f64, lo: f64, hi: f64, low_coeff: f64) -> f64 {
    let integrand = |u: f64| {
        let nu = u.exp();
        nu * psd(nu)
    };
    let mut breaks = vec![lo.ln()];
    while *breaks.last().unwrap() < hi.ln() {
        breaks.push(breaks.last().unwrap() + 0.01);
    }
    let body = v2ref_core::math::quadrature::integrate_pieces(
        &integrand,
        &breaks,
        v2ref_core::math::quadrature::Tolerance {
            abs: 0.0,
            rel: TURBULENCE_CHECK_REL,
        },
    );
    2.0 * (body + 3.0 * low_coeff * lo.cbrt())
}

#[test]
fn three_slope_model_has_its_slopes_corners_and_the_two_aperture_variance() {
    let two = paper_spectrum(18.0);
    let s = two.with_model(PistonPsdModel::ThreeSlope).unwrap();
    assert_eq!(s.model(), PistonPsdModel::ThreeSlope);
    let m = *s.three_slope().unwrap();
    // Corners 0.2 v/B and 0.3 v/D (Conan et al. 1995), near the exact
    // asymptote crossings of the two-aperture integral (0.225 v/B, 0.299 v/D).
    assert!(rel(m.corner_low_hz(), 0.2 * 10.0 / 18.0) < ULPS);
    assert!(rel(m.corner_high_hz(), 0.3 * 10.0 / D) < ULPS);
    // tol: the three-slope corners are rounded (0.2 v/B against the integral's 0.225 v/B, comment above): 11 % apart.
    assert!(rel(m.corner_low_hz(), two.corner_low_hz()) < 0.15);
    // tol: 0.3 v/D against the integral's 0.299 v/D: 0.3 % apart.
    assert!(rel(m.corner_high_hz(), two.corner_high_hz()) < 0.01);
    // Log-slopes inside each segment, and continuity at the corners.
    let p = |nu: f64| s.psd_um2_per_hz(nu);
    let slope = |a: f64, b: f64| (p(b) / p(a)).ln() / (b / a).ln();
    let (n1, n2) = (m.corner_low_hz(), m.corner_high_hz());
    for (a, b, want) in [
        (1e-3 * n1, 0.5 * n1, -2.0 / 3.0),
        (1.01 * n1, 0.99 * n2, -8.0 / 3.0),
        (1.01 * n2, 1e3 * n2, -17.0 / 3.0),
    ] {
        // tol: a log-log slope of a pure power law: rounding of two logarithms.
        assert_abs_eq!(slope(a, b), want, 1e-12);
    }
    for c in [n1, n2] {
        // tol: continuity across a corner: a step of 1e-12 moves a smooth function by ~1e-12 relative; 1e-10 catches a jump.
        assert!(rel(p(c * (1.0 - 1e-12)), p(c)) < 1e-10, "jump at {c}");
    }
    // ∫P dν = the two-aperture variance, by quadrature and by the closed form.
    let total = two_sided_integral(&p, 1e-6, 1e4, p(1e-6) * 1e-4);
    assert!(rel(total, two.variance_um2()) < PSD_TABLE_REL, "{total}");
    assert!(rel(m.variance_um2(), two.variance_um2()) < ROUNDING_REL);
    // A finite outer scale lowers the variance, not the corners.
    let l0 = PistonSpectrum::new(
        Turbulence::from_seeing(1.0, 2.2, 10.0, Some(25.0)).unwrap(),
        D,
        18.0,
    )
    .unwrap()
    .with_model(PistonPsdModel::ThreeSlope)
    .unwrap();
    // tol: a margin, not a rounding: a finite outer scale must lower the piston variance by at least a tenth.
    assert!(l0.three_slope().unwrap().variance_um2() < 0.9 * m.variance_um2());
    assert_eq!(l0.three_slope().unwrap().corner_low_hz(), n1);
    // The wind speed moves the corners with v.
    let fast = s.with_wind(20.0).unwrap();
    assert!(rel(fast.three_slope().unwrap().corner_low_hz(), 2.0 * n1) < ULPS);
}

#[test]
fn three_slope_model_refuses_a_wind_across_the_baseline() {
    let two = paper_spectrum(18.0);
    let three = two.with_model(PistonPsdModel::ThreeSlope).unwrap();
    assert!(matches!(
        three.with_wind_angle_deg(30.0),
        Err(Error::Invalid {
            param: "wind_angle_deg",
            ..
        })
    ));
    assert!(three.with_wind_angle_deg(180.0).is_ok());
    let nan = two.with_wind_angle_deg(f64::NAN).unwrap_err();
    assert_eq!(nan.param(), Some("wind_angle_deg"));
}

#[test]
fn wind_angle_zero_is_the_along_baseline_spectrum_bit_for_bit() {
    let s = paper_spectrum(18.0);
    let z = s.with_wind_angle_deg(0.0).unwrap();
    for k in 0..200 {
        let nu = 1e-3 * 1.07f64.powi(k);
        assert_eq!(
            s.psd_um2_per_hz(nu).to_bits(),
            z.psd_um2_per_hz(nu).to_bits()
        );
    }
}

#[test]
fn wind_across_the_baseline_keeps_the_variance_and_raises_the_low_asymptote() {
    let along = paper_spectrum(18.0);
    for angle in [90.0, 45.0] {
        let s = along.with_wind_angle_deg(angle).unwrap();
        let p = |nu: f64| s.psd_um2_per_hz(nu);
        // The variance does not depend on the direction.
        let lo = 1e-6;
        let total = two_sided_integral(&p, lo, 200.0, s.asymptote_low(lo) * lo.powf(2.0 / 3.0));
        assert!(
            rel(total, along.variance_um2()) < PSD_TABLE_CORNER_REL,
            "{angle} deg: ∫P = {total}, variance {}",
            along.variance_um2()
        );
        // Far below v/B the slope is −2/3 and the level (cos²θ + 3/2 sin²θ)
        // times the along-baseline one; far above, the middle asymptote.
        let (sin, cos) = angle.to_radians().sin_cos();
        for r in [1e-4, 1e-3] {
            let nu = r * along.corner_low_hz();
            let ratio = p(nu) / along.asymptote_low(nu);
            assert!(
                rel(ratio, cos * cos + 1.5 * sin * sin) < LOW_FREQ_VALUE_COEFF * 10.0 * r,
                "{angle} deg, {r}: ratio {ratio}"
            );
            assert!(rel(p(nu), s.asymptote_low(nu)) < LOW_FREQ_VALUE_COEFF * 10.0 * r);
        }
        let nu = (along.corner_low_hz() * along.corner_high_hz()).sqrt();
        assert!(
            // tol: the mid-range asymptote at the geometric mean of the corners: within 5 % there, where both neighbours' terms are smallest.
            rel(p(nu), along.asymptote_mid(nu)) < 0.05,
            "{angle} deg mid"
        );
    }
    // θ = 90° lifts the lowest frequencies by exactly 3/2, which the test
    // above could not mistake for the along-wind spectrum.
    let across = along.with_wind_angle_deg(90.0).unwrap();
    let nu = 1e-4 * along.corner_low_hz();
    assert!(across.psd_um2_per_hz(nu) > 1.4 * along.psd_um2_per_hz(nu));
}
