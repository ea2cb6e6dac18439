//! The differential-piston spectrum (crates/v2ref-core/src/piston/spectrum.rs, its transverse
//! integrals and table in crates/v2ref-core/src/piston/transverse.rs) piece by piece,
//! without the 721 quadratures of a real table of G, so that every test but
//! one runs in milliseconds at opt-level 0 (the mutation runs,
//! docs/mutation.md):
//!
//! - the table's interpolation on tables of known values
//!   ([`TransverseTable::from_ln_values`]): node values, the Catmull–Rom
//!   cubic against its Hermite form written out here, exactness for a power
//!   law and for a quadratic in ln f, the end extrapolation;
//! - P(ν) on such tables against its definition from G and S (module doc),
//!   for the wind along and across the baseline;
//! - the crosswind integral S against its definition summed half period by
//!   half period (no mean, no shortcut), the aperture filter and
//!   `2[1 − J0]` against published values and their series;
//! - the constructors' refusals and the three-slope model's wiring.
//!
//! The asymptotes, corners, G and the variance against mpmath are in
//! tests/turbulence.rs; `real_tables_hold_the_direct_quadratures_at_their_nodes`
//! (two real tables, ~12 s at opt-level 0) is the one slow test here.

use rand::{Rng, SeedableRng};
use std::f64::consts::PI;
use std::sync::Arc;
use v2ref_core::math::quadrature::{integrate_pieces, Tolerance};
use v2ref_core::piston::spectrum::{
    differential_piston_variance_from_structure_um2, two_one_minus_j0, PistonPsdModel,
    PistonSpectrum,
};
use v2ref_core::piston::three_slope::ThreeSlope;
use v2ref_core::piston::transverse::{
    aperture_filter, crosswind_integral, transverse_integral, TransverseTable,
};
use v2ref_core::piston::turbulence::Turbulence;
use v2ref_core::tolerance::{
    BESSEL_ABS, CROSSWIND_REL, IDENTITY_REL, LOW_FREQ_VALUE_COEFF, ROUNDING_REL, TABLE_LN_ABS,
    TURBULENCE_CHECK_REL, TURBULENCE_QUADRATURE_REL, ULPS,
};
use v2ref_core::{assert_abs_eq, assert_rel_eq, Error};

const D: f64 = 0.45;
/// The grid of a table: ln(f_x D) from ln 10⁻⁷ in steps of ln 10 / 80
/// (the module's documented grid, written out again here).
const GRID_LN_START: f64 = -7.0 * std::f64::consts::LN_10;
const GRID_STEP: f64 = std::f64::consts::LN_10 / 80.0;
const GRID_POINTS: usize = 721;

fn paper() -> Turbulence {
    Turbulence::from_seeing(1.0, 2.2, 10.0, None).unwrap()
}

/// f_x (m⁻¹) at the fractional grid position `t`.
fn fx_at(t: f64) -> f64 {
    (GRID_LN_START + t * GRID_STEP).exp() / D
}

/// A table of D holding `ln_values`.
fn table(ln_values: Vec<f64>) -> TransverseTable {
    TransverseTable::from_ln_values(paper(), D, ln_values).unwrap()
}

/// `n` values of ln G drawn uniformly in [−3, 3] (not monotone, not
/// smooth: every coefficient of the cubic matters).
fn random_values(n: usize, seed: u64) -> Vec<f64> {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
    (0..n).map(|_| rng.gen_range(-3.0..3.0)).collect()
}

/// The cubic Hermite interpolant of `y` at fractional index `t` in
/// [0, n − 1], tangents by central differences `(y[k+1] − y[k−1])/2`, with
/// the ghost values `2y[0] − y[1]` and `2y[n−1] − y[n−2]` beyond the ends;
/// a line with the end slope outside. Written in the Hermite basis
/// h00, h10, h01, h11 (the crate uses the Catmull–Rom polynomial form).
fn hermite_oracle(y: &[f64], t: f64) -> f64 {
    let n = y.len();
    let last = (n - 1) as f64;
    if t < 0.0 {
        return y[0] + (y[1] - y[0]) * t;
    }
    if t > last {
        return y[n - 1] + (y[n - 1] - y[n - 2]) * (t - last);
    }
    let at = |k: isize| -> f64 {
        if k < 0 {
            2.0 * y[0] - y[1]
        } else if k as usize >= n {
            2.0 * y[n - 1] - y[n - 2]
        } else {
            y[k as usize]
        }
    };
    let i = (t.floor() as isize).min(n as isize - 2);
    let u = t - i as f64;
    let m1 = (at(i + 1) - at(i - 1)) / 2.0;
    let m2 = (at(i + 2) - at(i)) / 2.0;
    let h00 = 2.0 * u.powi(3) - 3.0 * u * u + 1.0;
    let h10 = u.powi(3) - 2.0 * u * u + u;
    let h01 = -2.0 * u.powi(3) + 3.0 * u * u;
    let h11 = u.powi(3) - u * u;
    h00 * at(i) + h10 * m1 + h01 * at(i + 1) + h11 * m2
}

// ---------------------------------------------------------------- the table

#[test]
fn the_grid_is_80_points_per_decade_from_1e_minus_7() {
    let t = table(vec![0.0; GRID_POINTS]);
    assert_rel_eq!(t.grid_fx_per_m(0) * D, 1e-7, ROUNDING_REL);
    assert_rel_eq!(t.grid_fx_per_m(80) * D, 1e-6, ROUNDING_REL);
    assert_rel_eq!(t.grid_fx_per_m(720) * D, 1e2, ROUNDING_REL);
    assert_rel_eq!(t.grid_fx_per_m(417), fx_at(417.0), ROUNDING_REL);
}

#[test]
fn a_table_returns_its_values_at_its_nodes() {
    for (n, seed) in [(GRID_POINTS, 1), (2, 2), (3, 3), (5, 4)] {
        let y = random_values(n, seed);
        let t = table(y.clone());
        for (i, &want) in y.iter().enumerate() {
            let got = t.g(t.grid_fx_per_m(i)).ln();
            assert_abs_eq!(got, want, TABLE_LN_ABS);
        }
    }
}

#[test]
fn between_nodes_the_table_is_the_catmull_rom_cubic() {
    // n = 4 and 5 put every segment next to an end; 721 is a real table.
    for (n, seed) in [(2, 11), (3, 12), (4, 13), (5, 14), (GRID_POINTS, 15)] {
        let y = random_values(n, seed);
        let t = table(y.clone());
        for i in 0..n - 1 {
            for u in [0.013, 0.25, 0.5, 0.77, 0.991] {
                let pos = i as f64 + u;
                let got = t.g(fx_at(pos)).ln();
                assert_abs_eq!(got, hermite_oracle(&y, pos), TABLE_LN_ABS);
            }
        }
    }
}

#[test]
fn a_quadratic_in_ln_f_is_interpolated_exactly_away_from_the_ends() {
    // Central-difference tangents are exact for a quadratic, so the cubic
    // Hermite interpolant is the quadratic itself on every segment whose
    // four points are real nodes (identity, not a comparison with a
    // formula of the same form).
    let q = |t: f64| 0.7 - 0.31 * t + 0.0042 * t * t;
    let y: Vec<f64> = (0..40).map(|k| q(k as f64)).collect();
    let tab = table(y);
    for i in 1..37 {
        for u in [0.1, 0.5, 0.9] {
            let pos = i as f64 + u;
            assert_abs_eq!(tab.g(fx_at(pos)).ln(), q(pos), TABLE_LN_ABS);
        }
    }
    // The ghost nodes make the end segments linear-extrapolated, not the
    // quadratic: the end segments of this table are not exact.
    let pos = 0.5;
    assert!((tab.g(fx_at(pos)).ln() - q(pos)).abs() > 1e3 * TABLE_LN_ABS);
}

#[test]
fn a_power_law_is_reproduced_everywhere_and_extended() {
    // ln G linear in ln f_x: G = c (f_x D)^{−p}, exact on every segment
    // (the ghosts continue the line) and in both extrapolations.
    let (ln_c, p) = (1.3, 8.0 / 3.0);
    let power = |fx: f64| (ln_c - p * (fx * D).ln()).exp();
    let tab = power_table(f64::exp(ln_c), p);
    for pos in [
        -50.0, -0.5, 0.0, 0.3, 1.7, 359.4, 718.6, 719.5, 720.0, 725.0, 900.0,
    ] {
        let fx = fx_at(pos);
        // tol: the table's cubic interpolation of a smooth power law, exact to rounding amplified by the ~10³ dynamic range of the table's steps.
        assert_rel_eq!(tab.g(fx), power(fx), 1e3 * ROUNDING_REL);
    }
}

#[test]
fn beyond_its_ends_the_table_continues_its_end_slopes() {
    let y = random_values(9, 21);
    let tab = table(y.clone());
    for pos in [-40.0, -3.0, -0.2, 8.2, 11.0, 60.0] {
        assert_abs_eq!(
            tab.g(fx_at(pos)).ln(),
            hermite_oracle(&y, pos),
            // tol: the oracle recomputes the Hermite cubic in another order: a hundred times the table's own rounding.
            TABLE_LN_ABS * 1e2
        );
    }
    // Rising at the low end too (a real G falls): f_x → 0 sends it to 0.
    let rising = table(vec![0.0, 1.0, 0.5]);
    assert_abs_eq!(rising.g(fx_at(-2.0)).ln(), -2.0, TABLE_LN_ABS);
}

#[test]
fn no_turbulence_and_no_frequency() {
    // An empty table (zero turbulence) is 0 everywhere, f_x = 0 included.
    let empty = table(Vec::new());
    for fx in [0.0, 1e-3, 10.0] {
        assert_eq!(empty.g(fx), 0.0);
    }
    // f_x ≤ 0 is the infinite G of the f_x → 0 limit, whatever the table's
    // end slope (here rising towards f_x → 0, falling and flat).
    for y in [vec![0.0, -1.0], vec![0.0, 1.0], vec![2.0, 2.0]] {
        let t = table(y);
        assert_eq!(t.g(0.0), f64::INFINITY);
        assert_eq!(t.g(-1.0), f64::INFINITY);
    }
    // A real table of zero turbulence is empty (and costs nothing).
    let none =
        TransverseTable::new(Turbulence::new(f64::INFINITY, 2.2, 10.0, None).unwrap(), D).unwrap();
    assert_eq!(none.g(0.1), 0.0);
    assert_eq!(none.g(0.0), 0.0);
}

#[test]
fn tables_refuse_bad_geometry() {
    let t = paper();
    let param = |e: Error| e.param();
    assert_eq!(
        param(TransverseTable::new(t, 0.0).unwrap_err()),
        Some("aperture_m")
    );
    assert_eq!(
        param(TransverseTable::new(t, -1.0).unwrap_err()),
        Some("aperture_m")
    );
    assert_eq!(
        param(TransverseTable::crosswind(t, D, 0.0).unwrap_err()),
        Some("crosswind_m")
    );
    assert_eq!(
        param(TransverseTable::crosswind(t, 0.0, 3.0).unwrap_err()),
        Some("aperture_m")
    );
    assert_eq!(
        param(TransverseTable::from_ln_values(t, D, vec![1.0]).unwrap_err()),
        Some("ln_values")
    );
    assert_eq!(
        param(TransverseTable::from_ln_values(t, -D, vec![1.0, 2.0]).unwrap_err()),
        Some("aperture_m")
    );
    let tab = TransverseTable::crosswind(t, 0.8, 3.0).unwrap();
    assert_eq!(tab.turbulence(), &t);
    assert_eq!(tab.aperture_m(), 0.8);
}

// ------------------------------------------------------------- the spectrum

/// G = c_g (f_x D)^{−8/3} and S = c_s (f_x D)^{−2} as tables (exact power
/// laws, see `a_power_law_is_reproduced_everywhere_and_extended`).
const C_G: f64 = 3.0;
const C_S: f64 = 0.5;
fn power_table(c: f64, p: f64) -> TransverseTable {
    table(
        (0..GRID_POINTS)
            .map(|i| c.ln() - p * (GRID_LN_START + i as f64 * GRID_STEP))
            .collect(),
    )
}
fn g_law(fx: f64) -> f64 {
    C_G * (fx * D).powf(-8.0 / 3.0)
}
fn s_law(fx: f64) -> f64 {
    C_S * (fx * D).powf(-2.0)
}

fn along(baseline_m: f64) -> PistonSpectrum {
    PistonSpectrum::from_table(Arc::new(power_table(C_G, 8.0 / 3.0)), baseline_m).unwrap()
}

/// `along(B)` with the wind at `angle_deg` and S the power law; checks the
/// baseline across the wind the spectrum asks a table for.
fn at_angle(baseline_m: f64, angle_deg: f64) -> PistonSpectrum {
    along(baseline_m)
        .with_wind_angle_deg_from(angle_deg, |across_m| {
            let want = baseline_m * angle_deg.to_radians().sin().abs();
            assert_rel_eq!(across_m, want, ROUNDING_REL);
            Ok(power_table(C_S, 2.0))
        })
        .unwrap()
}

/// `2[1 − cos x]`, from its series `x² − x⁴/12 + x⁶/360` below x = 10⁻²
/// (where 1 − cos would lose ~log10(2/x²) digits).
fn two_one_minus_cos(x: f64) -> f64 {
    // tol: not a tolerance: the switch to the series, below which 1 - cos x loses ~log10(2/x²) digits (doc above).
    if x.abs() < 1e-2 {
        x * x * (1.0 - x * x / 12.0 + x.powi(4) / 360.0)
    } else {
        2.0 * (1.0 - x.cos())
    }
}

#[test]
fn along_the_baseline_p_is_the_baseline_factor_times_g_over_v() {
    // P(ν) = 2[1 − cos(2πBν/v)] G(ν/v) / v (module doc), here with
    // 2[1 − cos x] = 4 sin²(x/2) written the other way.
    for (b, v) in [(18.0, 10.0), (47.0, 3.5), (0.3, 25.0)] {
        let s = along(b).with_wind(v).unwrap();
        assert_eq!(s.wind_mps(), v);
        for nu in [1e-3, 0.0371, 0.5, 2.2, 13.0, 141.3] {
            let want = two_one_minus_cos(2.0 * PI * b * nu / v) * g_law(nu / v) / v;
            assert_rel_eq!(s.psd_um2_per_hz(nu), want, IDENTITY_REL);
            assert_eq!(s.psd_um2_per_hz(-nu), s.psd_um2_per_hz(nu));
        }
        // Zero at ν = 0 (not 0 · ∞), and at the baseline factor's zeros.
        assert_eq!(s.psd_um2_per_hz(0.0), 0.0);
        // tol: a zero of the baseline factor 2[1 - cos], rounded: ~1e-31 of the spectrum half-way, 1e-25 leaves room while a missing factor gives O(1).
        assert!(s.psd_um2_per_hz(v / b) < 1e-25 * s.psd_um2_per_hz(0.5 * v / b));
    }
    let zero_baseline = along(0.0);
    assert_eq!(zero_baseline.psd_um2_per_hz(1.0), 0.0);
    assert_eq!(zero_baseline.variance_um2(), 0.0);
}

#[test]
fn the_direct_spectrum_is_the_baseline_factor_times_the_quadrature_of_g() {
    let t = paper();
    for (b, v) in [(18.0, 10.0), (5.0, 31.0)] {
        let s = PistonSpectrum::new(t, D, b).unwrap().with_wind(v).unwrap();
        for nu in [0.01, 0.7, 9.0] {
            let g = transverse_integral(&t, D, nu / v);
            let want = two_one_minus_cos(2.0 * PI * b * nu / v) * g / v;
            assert_rel_eq!(s.psd_direct_um2_per_hz(nu), want, IDENTITY_REL);
            assert_eq!(s.psd_direct_um2_per_hz(-nu), s.psd_direct_um2_per_hz(nu));
        }
        assert_eq!(s.psd_direct_um2_per_hz(0.0), 0.0);
    }
}

#[test]
fn across_the_baseline_p_combines_g_and_s() {
    // P v = 4 sin²(a/2) G + 2 cos(a) S, a = 2πνB cos θ / v (module doc).
    let (b, v) = (18.0, 10.0);
    for angle in [30.0, -30.0, 60.0, 135.0, 90.0, -250.0] {
        let s = at_angle(b, angle).with_wind(v).unwrap();
        assert_rel_eq!(s.wind_angle_deg(), angle, ROUNDING_REL);
        let cos = f64::to_radians(angle).cos();
        for nu in [1e-3, 0.0371, 0.5, 2.2, 13.0] {
            let fx = nu / v;
            let a = 2.0 * PI * nu * b * cos / v;
            let want = (two_one_minus_cos(a) * g_law(fx) + 2.0 * a.cos() * s_law(fx)) / v;
            assert_rel_eq!(s.psd_um2_per_hz(nu), want, IDENTITY_REL);
            assert_eq!(s.psd_um2_per_hz(-nu), s.psd_um2_per_hz(nu));
        }
    }
    // Square across: 2 S / v, the G term gone.
    let across = at_angle(b, 90.0);
    for nu in [1e-3, 0.5, 13.0] {
        assert_rel_eq!(
            across.psd_um2_per_hz(nu),
            2.0 * s_law(nu / 10.0) / 10.0,
            // tol: two evaluations of one power law a few operations apart: ten roundings.
            ULPS * 10.0
        );
    }
}

#[test]
fn a_wind_along_the_baseline_either_way_needs_no_crosswind_table() {
    let s = along(18.0);
    for angle in [0.0, 180.0, -180.0, 360.0, -360.0] {
        let same = s
            .with_wind_angle_deg_from(angle, |_| panic!("no table of S at {angle} deg"))
            .unwrap();
        for nu in [1e-3, 0.5, 13.0] {
            assert_eq!(
                same.psd_um2_per_hz(nu).to_bits(),
                s.psd_um2_per_hz(nu).to_bits()
            );
        }
    }
    // A zero baseline has no crosswind part whatever the angle.
    let z = along(0.0)
        .with_wind_angle_deg_from(45.0, |_| panic!("no table of S for B = 0"))
        .unwrap();
    assert_eq!(z.psd_um2_per_hz(1.0), 0.0);
    // A crosswind table's failure is the spectrum's.
    let e = along(18.0)
        .with_wind_angle_deg_from(45.0, |_| TransverseTable::crosswind(paper(), D, -1.0))
        .unwrap_err();
    assert_eq!(e.param(), Some("crosswind_m"));
}

#[test]
fn spectra_refuse_bad_geometry_and_keep_what_they_were_given() {
    let t = paper();
    let tab = Arc::new(TransverseTable::new(t, 0.8).unwrap());
    let s = PistonSpectrum::from_table(Arc::clone(&tab), 33.0).unwrap();
    assert!(Arc::ptr_eq(s.table(), &tab));
    assert_eq!(s.turbulence(), &t);
    assert_eq!(s.aperture_m(), 0.8);
    assert_eq!(s.baseline_m(), 33.0);
    assert_eq!(s.wind_mps(), t.wind_mps());
    assert_eq!(s.wind_angle_deg(), 0.0);
    assert_eq!(s.model(), PistonPsdModel::TwoAperture);
    assert!(s.three_slope().is_none());
    let w = s.with_wind(4.0).unwrap();
    assert_eq!(w.wind_mps(), 4.0);
    assert!(Arc::ptr_eq(w.table(), &tab), "with_wind shares the table");
    assert_eq!(w.turbulence().wind_mps(), t.wind_mps());

    let param = |r: Result<PistonSpectrum, Error>| r.unwrap_err().param();
    assert_eq!(param(PistonSpectrum::new(t, 0.0, 18.0)), Some("aperture_m"));
    assert_eq!(param(PistonSpectrum::new(t, D, -1.0)), Some("baseline_m"));
    assert_eq!(
        param(PistonSpectrum::new(t, D, f64::NAN)),
        Some("baseline_m")
    );
    assert_eq!(param(s.with_wind(0.0)), Some("wind_mps"));
    assert_eq!(param(s.with_wind(-3.0)), Some("wind_mps"));
    assert_eq!(param(s.with_wind_angle_deg(360.5)), Some("wind_angle_deg"));
    assert_eq!(param(s.with_wind_angle_deg(-361.0)), Some("wind_angle_deg"));
    assert_eq!(
        param(s.with_wind_angle_deg(f64::NAN)),
        Some("wind_angle_deg")
    );
}

#[test]
fn the_three_slope_model_takes_the_variance_wind_and_geometry() {
    let t = paper();
    let (b, d) = (18.0, D);
    let two = PistonSpectrum::new(t, d, b).unwrap();
    let three = two.with_model(PistonPsdModel::ThreeSlope).unwrap();
    assert_eq!(three.model(), PistonPsdModel::ThreeSlope);
    let want = ThreeSlope::new(two.variance_um2(), t.wind_mps(), b, d).unwrap();
    let got = three.three_slope().unwrap();
    assert_eq!(got, &want);
    for nu in [1e-3, 0.3, 5.0, 60.0] {
        assert_eq!(three.psd_um2_per_hz(nu), want.psd_um2_per_hz(nu));
    }
    // Another wind moves the corners with v and keeps the variance.
    let fast = three.with_wind(25.0).unwrap();
    let want = ThreeSlope::new(two.variance_um2(), 25.0, b, d).unwrap();
    assert_eq!(fast.three_slope().unwrap(), &want);
    assert_ne!(want.corner_low_hz(), got.corner_low_hz());
    // Back to the two-aperture integral.
    let back = three.with_model(PistonPsdModel::TwoAperture).unwrap();
    assert_eq!(back.model(), PistonPsdModel::TwoAperture);
    assert!(back.three_slope().is_none());
    // The three-slope model has no wind direction but the baseline's.
    assert!(three.with_wind_angle_deg(180.0).is_ok());
    for angle in [45.0, 90.0, -10.0] {
        let e = three.with_wind_angle_deg(angle).unwrap_err();
        assert_eq!(e.param(), Some("wind_angle_deg"));
        let e = two
            .with_wind_angle_deg(angle)
            .unwrap()
            .with_model(PistonPsdModel::ThreeSlope)
            .unwrap_err();
        assert_eq!(e.param(), Some("wind_angle_deg"));
        assert!(e.to_string().contains("three-slope"), "{e}");
    }
}

#[test]
fn the_deviation_is_the_square_root_of_the_variance() {
    for b in [0.0, 0.3, 18.0] {
        let s = PistonSpectrum::new(paper(), D, b).unwrap();
        assert_eq!(s.rms_um(), s.variance_um2().sqrt());
    }
    let none = Turbulence::new(f64::INFINITY, 2.2, 10.0, None).unwrap();
    let s = PistonSpectrum::new(none, D, 18.0).unwrap();
    assert_eq!(s.variance_um2(), 0.0);
    assert_eq!(s.psd_um2_per_hz(1.0), 0.0);
}

// ------------------------------------------------- the integrals and factors

/// S(f_x) by its definition, `∫ Φ_opd A 2 sin²(π f_y b) df_y`, integrated
/// half period by half period of the sine out to 100/D (the crate's
/// integral stops at 64 half periods and uses the mean of 2 sin² beyond,
/// and returns G when f_x b > 6), with the same averaged tail beyond as G.
fn crosswind_by_half_periods(t: &Turbulence, d: f64, fx: f64, b: f64) -> f64 {
    let f_max = (100.0 / d).max(100.0 * fx);
    let integrand = |fy: f64| {
        let f = (fx * fx + fy * fy).sqrt();
        let s = (PI * fy * b).sin();
        t.opd_psd(f) * aperture_filter(f, d) * 2.0 * s * s
    };
    let mut breaks = vec![0.0];
    let mut x = fx.min(0.25 / b);
    while x < 0.5 / b {
        breaks.push(x);
        x *= 2.0;
    }
    let half_periods = (f_max * 2.0 * b).floor() as usize;
    breaks.extend((1..=half_periods).map(|k| k as f64 * 0.5 / b));
    breaks.push(f_max);
    let tail =
        t.opd_psd_scale() * 4.0 / (PI.powi(4) * d.powi(3)) * (3.0 / 17.0) * f_max.powf(-17.0 / 3.0);
    let tol = Tolerance {
        abs: 0.0,
        rel: TURBULENCE_QUADRATURE_REL,
    };
    2.0 * (integrate_pieces(&integrand, &breaks, tol) + tail)
}

#[test]
fn the_crosswind_integral_is_its_definition() {
    let t = paper();
    // S/G runs from 1e-7 (f_x b ≪ 1) to 1 (f_x b → 6).
    for (b, fxd) in [
        (0.2, 1e-3),
        (0.2, 2.0),
        (3.0, 1e-5),
        (3.0, 0.1),
        (3.0, 0.8),
        (12.73, 1e-3),
        (12.73, 0.1),
        (40.0, 0.01),
    ] {
        let fx = fxd / D;
        let s = crosswind_integral(&t, D, fx, b);
        assert_rel_eq!(s, crosswind_by_half_periods(&t, D, fx, b), CROSSWIND_REL);
    }
    // Beyond f_x b = 6 it is G; on either side of that line, the same to
    // ~the cosine transform exp(−2π f_x b) ≈ 1e-16 and the mean's error.
    let b = 12.0;
    let g_at = |fxb: f64| transverse_integral(&t, D, fxb / b);
    assert_eq!(crosswind_integral(&t, D, 6.01 / b, b), g_at(6.01));
    assert_rel_eq!(
        crosswind_integral(&t, D, 5.99 / b, b),
        g_at(5.99),
        CROSSWIND_REL
    );
    // Zero turbulence.
    let none = Turbulence::new(f64::INFINITY, 2.2, 10.0, None).unwrap();
    assert_eq!(crosswind_integral(&none, D, 0.1, 3.0), 0.0);
    assert_eq!(transverse_integral(&none, D, 0.1), 0.0);
}

#[test]
fn the_aperture_filter_is_the_squared_airy_amplitude() {
    // A(f) = [2 J1(πDf)/(πDf)]²; J1(1) = 0.44005058574493351596 (Abramowitz
    // & Stegun, Table 9.1; mpmath besselj(1, 1)).
    assert_eq!(aperture_filter(0.0, D), 1.0);
    let j1_of_1: f64 = 0.440_050_585_744_933_5;
    assert_rel_eq!(
        aperture_filter(1.0 / (PI * D), D),
        (2.0 * j1_of_1).powi(2),
        // tol: J1(1) to the 16 digits typed, squared and scaled: ten roundings.
        10.0 * ULPS
    );
    // Zero at the first zero of J1, j₁,₁ = 3.83170597020751231561 (A&S 9.5).
    let first_zero = 3.831_705_970_207_512 / (PI * D);
    // tol: the squared J1 at its tabulated zero, typed to 16 digits: (~1e-16)², far below 1e-28, while a wrong argument gives O(1e-2).
    assert!(aperture_filter(first_zero, D) < 1e-28);
    // A function of D f only.
    assert_rel_eq!(
        aperture_filter(0.9, D),
        aperture_filter(1.8, D / 2.0),
        ROUNDING_REL
    );
}

#[test]
fn two_one_minus_j0_is_its_series_and_the_bessel_function() {
    // 2[1 − J0(z)] = 2 Σ_{k≥1} (−1)^{k+1} (z/2)^{2k} / (k!)², summed to
    // convergence (no cancellation below z = 1: each term ≤ z²/16 of the
    // last), across the crate's switch from its series to J0 at z = 1e-2.
    let series = |z: f64| {
        let (mut term, mut sum) = (1.0, 0.0);
        for k in 1..20 {
            term *= -(z / 2.0) * (z / 2.0) / (k * k) as f64;
            sum -= 2.0 * term;
        }
        sum
    };
    for z in [1e-8, 1e-5, 3e-4, 2e-3, 7e-3, 9.99e-3] {
        assert_rel_eq!(two_one_minus_j0(z), series(z), ROUNDING_REL);
    }
    // From J0: 1 − J0 is ~z²/4, so J0's absolute error is its error.
    for z in [1e-2, 0.05, 0.5, 1.0] {
        // tol: 2(1 - J0): twice J0's absolute error.
        assert_abs_eq!(two_one_minus_j0(z), series(z), 2.0 * BESSEL_ABS);
    }
    // J0(10) = −0.245935764451348335 (A&S Table 9.1).
    assert_abs_eq!(
        two_one_minus_j0(10.0),
        2.0 * (1.0 + 0.245_935_764_451_348_3),
        // tol: 2(1 - J0): twice J0's absolute error.
        2.0 * BESSEL_ABS
    );
    assert_eq!(two_one_minus_j0(0.0), 0.0);
}

// ----------------------------------------------------------- the real tables

#[test]
fn real_tables_hold_the_direct_quadratures_at_their_nodes() {
    let t = paper();
    let g = TransverseTable::new(t, D).unwrap();
    let b = 12.73;
    let s = TransverseTable::crosswind(t, D, b).unwrap();
    for i in [0, 1, 80, 333, 500, 719, 720] {
        let fx = g.grid_fx_per_m(i);
        assert_rel_eq!(g.g(fx), transverse_integral(&t, D, fx), TABLE_LN_ABS);
        assert_rel_eq!(s.g(fx), crosswind_integral(&t, D, fx, b), TABLE_LN_ABS);
    }
    // Between nodes, the cubic of the table's own values.
    let ln_nodes: Vec<f64> = (0..GRID_POINTS)
        .map(|i| g.g(g.grid_fx_per_m(i)).ln())
        .collect();
    for pos in [-3.0, 0.4, 250.5, 719.9, 722.0] {
        assert_abs_eq!(
            g.g(fx_at(pos)).ln(),
            hermite_oracle(&ln_nodes, pos),
            TABLE_LN_ABS
        );
    }
}

#[test]
fn kolmogorov_integrals_scale_with_the_aperture() {
    // Without an outer scale the only lengths are D, 1/f_x and b:
    // G(f_x; D) = D^{8/3} g(f_x D), S(f_x; D, b) = D^{8/3} s(f_x D, b/D)
    // and σ_p²(B, D) = D^{5/3} v(B/D). Every cut-off of the quadratures
    // (100/D, the low split, the half periods) scales the same way, so
    // each pair agrees to the quadratures' convergence.
    let t = paper();
    let d0 = D;
    for d in [0.05, 8.0] {
        let k = (d / d0).powf(8.0 / 3.0);
        for fxd in [1e-3, 0.1, 1.0] {
            let g = transverse_integral(&t, d, fxd / d);
            let g0 = transverse_integral(&t, d0, fxd / d0);
            assert_rel_eq!(g, k * g0, TURBULENCE_CHECK_REL);
            let b_over_d = 7.0;
            let s = crosswind_integral(&t, d, fxd / d, b_over_d * d);
            let s0 = crosswind_integral(&t, d0, fxd / d0, b_over_d * d0);
            assert_rel_eq!(s, k * s0, TURBULENCE_CHECK_REL);
        }
        for b_over_d in [0.6, 40.0] {
            let var = |d: f64| {
                PistonSpectrum::new(t, d, b_over_d * d)
                    .unwrap()
                    .variance_um2()
            };
            let pupil =
                |d: f64| differential_piston_variance_from_structure_um2(&t, d, b_over_d * d);
            let k = (d / d0).powf(5.0 / 3.0);
            assert_rel_eq!(var(d), k * var(d0), TURBULENCE_CHECK_REL);
            assert_rel_eq!(pupil(d), k * pupil(d0), TURBULENCE_CHECK_REL);
        }
    }
}

#[test]
fn across_the_wind_the_low_asymptote_is_raised_by_cos2_plus_three_halves_sin2() {
    let t = paper();
    let along = PistonSpectrum::new(t, D, 18.0).unwrap();
    for angle in [30.0, 45.0, 90.0, 120.0, -60.0] {
        let s = along.with_wind_angle_deg(angle).unwrap();
        let (sin, cos) = f64::to_radians(angle).sin_cos();
        for nu in [1e-3, 0.2] {
            let ratio = s.asymptote_low(nu) / along.asymptote_low(nu);
            assert_rel_eq!(ratio, cos * cos + 1.5 * sin * sin, ROUNDING_REL);
            // The middle and high asymptotes do not depend on θ.
            assert_eq!(s.asymptote_mid(nu), along.asymptote_mid(nu));
            assert_eq!(s.asymptote_high(nu), along.asymptote_high(nu));
        }
    }
    // Square across, P = 2 S / v: far below v/B, S from its quadrature
    // meets the raised asymptote (the relative error falls as ν/corner).
    let across = along.with_wind_angle_deg(90.0).unwrap();
    let r = 1e-4;
    let nu = r * along.corner_low_hz();
    let v = t.wind_mps();
    let p = 2.0 * crosswind_integral(&t, D, nu / v, 18.0) / v;
    // tol: 10 r: the relative error falls as ν/corner = r; LOW_FREQ_VALUE_COEFF is its coefficient and 10 its margin.
    assert_rel_eq!(p, across.asymptote_low(nu), LOW_FREQ_VALUE_COEFF * 10.0 * r);
}
