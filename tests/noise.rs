//! Closed forms of `noise` and `window_variance`: identities, the slow
//! oracle, property tests. (Monte Carlo checks: `tests/noise_mc.rs`.)

use proptest::prelude::*;
use v2ref_core::formalism::estimator::{dft, noise_bias, positive_bins, raw_estimates};
use v2ref_core::noise::window_variance::{
    quadratic_forms, two_sided_band_bins, variance_by_moments, window_stats,
};
use v2ref_core::noise::{
    self, appendix_stats, example_interferogram, moments, published, raw_moment,
    raw_moments_from_cumulants, var_m2, worked_example, ExampleSetup, Formula, NoiseModel,
};
use v2ref_core::tolerance::{CANCELLATION_ABS, IDENTITY_ABS, IDENTITY_REL, NONNEGATIVE_REL};
use v2ref_core::{assert_abs_eq, assert_rel_eq};
use v2ref_reproduction::cases::appendix_setup;

fn gauss(s: f64) -> NoiseModel {
    NoiseModel::detector(s).unwrap()
}

#[test]
fn cumulant_recursion_gives_textbook_moments() {
    // Gaussian N(m, s²): E X⁴ = m⁴ + 6m²s² + 3s⁴; Poisson(λ): Touchard
    // polynomials λ⁴ + 6λ³ + 7λ² + λ (independent textbook forms).
    let g = raw_moments_from_cumulants(&[1.5, 4.0, 0.0, 0.0]);
    // E X² = m² + s² = 2.25 + 4
    assert_rel_eq!(g[2], 6.25, IDENTITY_REL);
    // The printed ⟨M²⟩ = m² + σ², at σ = 1.3 (σ = 2 has σ + σ = σ·σ).
    assert_rel_eq!(
        published::gaussian_m2(1.5, 1.3),
        raw_moments_from_cumulants(&[1.5, 1.69])[2],
        IDENTITY_REL
    );
    assert_rel_eq!(g[4], published::gaussian_m4(1.5, 2.0), IDENTITY_REL);
    let l = 3.7;
    let p = raw_moments_from_cumulants(&[l, l, l, l]);
    assert_rel_eq!(p[2], published::photon_m2(l), IDENTITY_REL);
    assert_rel_eq!(p[4], published::photon_m4(l), IDENTITY_REL);
    // Sixth Touchard polynomial: λ⁶ + 15λ⁵ + 65λ⁴ + 90λ³ + 31λ² + λ.
    let p6 = raw_moments_from_cumulants(&[l; 6])[6];
    let t6 = l.powi(6) + 15.0 * l.powi(5) + 65.0 * l.powi(4) + 90.0 * l.powi(3) + 31.0 * l * l + l;
    assert_rel_eq!(p6, t6, IDENTITY_REL);
}

#[test]
fn closed_moments_match_the_generic_recursion() {
    for noise in [
        gauss(0.7),
        NoiseModel::photon(),
        NoiseModel::new(1.3, true).unwrap(),
    ] {
        for &(m, c) in &[(0.0, 5.0), (3.0, 4.0), (-2.0, 6.0), (10.0, 10.0)] {
            let mo = moments(&noise, m, m + c).unwrap();
            for r in 0..=4 {
                assert_abs_eq!(
                    mo.raw[r],
                    raw_moment(&noise, m, m + c, r),
                    IDENTITY_ABS + IDENTITY_REL * (raw_moment(&noise, m, m + c, r)).abs()
                );
            }
            let v = mo.raw[4] - mo.raw[2] * mo.raw[2];
            assert_rel_eq!(var_m2(&noise, m, m + c), v, IDENTITY_REL);
            // central moments: E(M − m)^r from the raw ones.
            let c3 = mo.raw[3] - 3.0 * m * mo.raw[2] + 2.0 * m.powi(3);
            assert_abs_eq!(
                mo.central[3],
                c3,
                CANCELLATION_ABS + IDENTITY_REL * (c3).abs()
            );
        }
    }
}

#[test]
fn central_moments_are_the_textbook_ones() {
    // Gaussian: E(M − m)² = σ², E(M − m)³ = 0, E(M − m)⁴ = 3σ⁴. Poisson of
    // mean n (M = I − c): n, n and n + 3n².
    let mo = moments(&gauss(1.7), 4.0, 9.0).unwrap();
    let s2 = 1.7 * 1.7;
    for (got, want) in mo.central.iter().zip([1.0, 0.0, s2, 0.0, 3.0 * s2 * s2]) {
        assert_abs_eq!(*got, want, IDENTITY_ABS + IDENTITY_REL * (want).abs());
    }
    let n = 6.5;
    let mo = moments(&NoiseModel::photon(), 2.0, n).unwrap();
    for (got, want) in mo.central.iter().zip([1.0, 0.0, n, n, n + 3.0 * n * n]) {
        assert_abs_eq!(*got, want, IDENTITY_ABS + IDENTITY_REL * (want).abs());
    }
}

#[test]
fn published_photon_moments_are_those_of_the_count_not_of_m() {
    // With no continuum (c = 0) M = I and the printed forms are exact ...
    let p = NoiseModel::photon();
    let n = 20.0;
    assert_rel_eq!(
        moments(&p, n, n).unwrap().raw[4],
        published::photon_m4(n),
        IDENTITY_REL
    );
    assert_rel_eq!(
        var_m2(&p, n, n),
        published::photon_var_term(n),
        IDENTITY_REL
    );
    // ... with c = n − m they are not: var(M²) = 4m²n + 4mn + 2n² + n.
    let m = 10.0;
    assert_rel_eq!(
        var_m2(&p, m, n),
        4.0 * m * m * n + 4.0 * m * n + 2.0 * n * n + n
    );
    assert!((published::photon_var_term(n) / var_m2(&p, m, n) - 1.0).abs() > 1.0);
}

#[test]
fn detector_formulas_agree_published_and_exact() {
    let ifg = example_interferogram(&appendix_setup()).unwrap();
    let d = gauss(2.0);
    let a = appendix_stats(&ifg.modulated, &ifg.continuum, &d, Formula::Exact).unwrap();
    let b = appendix_stats(&ifg.modulated, &ifg.continuum, &d, Formula::Published).unwrap();
    assert_rel_eq!(a.var_v1_sq, b.var_v1_sq, IDENTITY_REL);
    assert_rel_eq!(a.var_v2_sq, b.var_v2_sq, IDENTITY_REL);
    // The printed closed forms 2N²σ²[2Σm² + Nσ²] and 2N⁴σ²[2m0² + σ²].
    let (nn, s2) = (128.0_f64, 4.0);
    assert_rel_eq!(
        a.var_v1_sq,
        2.0 * nn * nn * s2 * (2.0 * a.sum_m2 + nn * s2),
        IDENTITY_REL
    );
    assert_rel_eq!(
        a.var_v2_sq,
        2.0 * nn.powi(4) * s2 * (2.0 * a.m0 * a.m0 + s2),
        IDENTITY_REL
    );
}

#[test]
fn worked_examples_follow_from_sum_m2() {
    // SNR2 depends on m0 and σ only: 1/√(0.08·2.04) for σ = 0.2 n, m0 = n.
    let w = worked_example(&appendix_setup(), Formula::Published).unwrap();
    assert_rel_eq!(w.detector.1, 1.0 / (0.08_f64 * 2.04).sqrt(), IDENTITY_REL);
    // SNR1 = s / √(0.08 (2 s + 0.04 N)) with s = Σm²/n².
    let s = w.sum_m2_over_n2;
    assert_rel_eq!(
        w.detector.0,
        s / (0.08 * (2.0 * s + 0.04 * 128.0)).sqrt(),
        IDENTITY_REL
    );
    // Photon SNR2 with n0 = 20, m0 = 10: printed 100/√(20·1721), exact 100/√9620.
    assert_rel_eq!(w.photon.1, 100.0 / (20.0_f64 * 1721.0).sqrt(), IDENTITY_REL);
    let e = worked_example(&appendix_setup(), Formula::Exact).unwrap();
    assert_rel_eq!(e.photon.1, 100.0 / 9620.0_f64.sqrt(), IDENTITY_REL);
    // tol: Σ m²/n² of a flat band: ≈ 1/(2 δx Δσ) = 12 less the truncated tails.
    assert!(s > 11.0 && s < 12.0, "{s}");
    // The one-sided scan holds about half the fringe power.
    let z = worked_example(
        &ExampleSetup {
            zero_start: true,
            ..appendix_setup()
        },
        Formula::Published,
    )
    .unwrap();
    // tol: a zero-start scan keeps about half the fringe power of a centred one (0.55 with the packet's edge): 0.05 is the margin of this rough fraction, not a rounding.
    assert!((z.sum_m2_over_n2 / s - 0.55).abs() < 0.05);
}

#[test]
fn window_all_bins_equals_appendix() {
    let ifg = example_interferogram(&ExampleSetup {
        samples: 32,
        ..appendix_setup()
    })
    .unwrap();
    let all: Vec<usize> = (0..32).collect();
    for noise in [
        gauss(2.0),
        NoiseModel::photon(),
        NoiseModel::new(2.0, true).unwrap(),
    ] {
        let w = window_stats(&ifg.modulated, &ifg.mean_counts(), &noise, &all).unwrap();
        let a = appendix_stats(&ifg.modulated, &ifg.continuum, &noise, Formula::Exact).unwrap();
        assert_rel_eq!(w.var_v1_sq, a.var_v1_sq, IDENTITY_REL);
        assert_rel_eq!(w.var_v2_sq, a.var_v2_sq, IDENTITY_REL);
        assert_rel_eq!(w.bias_v1_sq, a.bias_v1_sq, IDENTITY_REL);
        assert_rel_eq!(w.bias_v2_sq, a.bias_v2_sq, IDENTITY_REL);
        assert_rel_eq!(w.signal_v1_sq, a.signal_v1_sq, IDENTITY_REL);
    }
}

#[test]
fn window_variance_matches_the_four_index_oracle() {
    // N = 8, arbitrary means, Poisson + detector noise, several windows.
    let m = [3.0, -1.0, 2.5, 0.5, -2.0, 1.0, 0.0, 4.0];
    let counts: Vec<f64> = m.iter().map(|x| x + 5.0).collect();
    let noise = NoiseModel::new(0.8, true).unwrap();
    for bins in [
        vec![1, 2],
        vec![1, 7],
        vec![0, 3, 4, 5],
        (0..8).collect::<Vec<_>>(),
    ] {
        let (a1, a2) = quadratic_forms(8, &bins);
        let w = window_stats(&m, &counts, &noise, &bins).unwrap();
        assert_rel_eq!(
            w.var_v1_sq,
            variance_by_moments(&a1, &m, &counts, &noise),
            IDENTITY_REL
        );
        assert_rel_eq!(
            w.var_v2_sq,
            variance_by_moments(&a2, &m, &counts, &noise),
            IDENTITY_REL
        );
        // the bias is estimator::noise_bias of the per-sample variance
        let v: Vec<f64> = counts
            .iter()
            .map(|&c| noise.cumulants(c).unwrap().k2)
            .collect();
        let nb = noise_bias(&v, &bins).unwrap();
        assert_rel_eq!(w.bias_v1_sq, nb.v1_sq, IDENTITY_REL);
        assert_rel_eq!(w.bias_v2_sq, nb.v2_sq, IDENTITY_REL);
        // the signal is the noise-free raw estimator
        let r = raw_estimates(&dft(&m), &bins).unwrap();
        assert_rel_eq!(w.signal_v1_sq, r.v1_sq, IDENTITY_REL);
        assert_abs_eq!(
            w.signal_v2_sq,
            r.v2_sq,
            CANCELLATION_ABS + IDENTITY_REL * (r.v2_sq).abs()
        );
    }
}

#[test]
fn white_noise_window_factor_holds_only_without_signal() {
    // Pure detector noise, no fringe. B_k and B_{N−k} are conjugate, so the
    // all-bins sum counts each independent |B_k|² twice: var = 2N³σ⁴. A
    // one-sided window of |K| bins (independent exponential powers of mean
    // Nσ²) has var |K|N²σ⁴, ratio 2N/|K|; its two-sided version (2|K| bins,
    // the same powers doubled) has 4|K|N²σ⁴, ratio N/(2|K|).
    let n = 64;
    let zeros = vec![0.0; n];
    let counts = vec![10.0; n];
    let noise = gauss(1.0);
    let all: Vec<usize> = (0..n).collect();
    let k: Vec<usize> = (5..=10).collect();
    let wa = window_stats(&zeros, &counts, &noise, &all).unwrap();
    let wk = window_stats(&zeros, &counts, &noise, &k).unwrap();
    assert_rel_eq!(
        wa.var_v1_sq / wk.var_v1_sq,
        2.0 * n as f64 / k.len() as f64,
        IDENTITY_REL
    );
    let k2: Vec<usize> = k.iter().flat_map(|&b| [b, n - b]).collect();
    let wk2 = window_stats(&zeros, &counts, &noise, &k2).unwrap();
    assert_rel_eq!(
        wa.var_v1_sq / wk2.var_v1_sq,
        n as f64 / k2.len() as f64,
        IDENTITY_REL
    );
    // With the fringe, the signal × noise term is not reduced.
    let ifg = example_interferogram(&appendix_setup()).unwrap();
    let obs = noise::example_observation();
    let (lo, hi) = obs.spectrum.support();
    let w2 = two_sided_band_bins(128, 0.5, lo, hi);
    let a = window_stats(
        &ifg.modulated,
        &ifg.mean_counts(),
        &gauss(2.0),
        &(0..128).collect::<Vec<_>>(),
    )
    .unwrap();
    let b = window_stats(&ifg.modulated, &ifg.mean_counts(), &gauss(2.0), &w2).unwrap();
    let factor = 128.0 / w2.len() as f64;
    // tol: a margin on the window's gain, not a rounding: the white-noise argument divides the variance by the factor; at least a fifth of that gain must remain.
    assert!(a.var_v1_sq / b.var_v1_sq < 0.2 * factor);
    // tol: the window keeps nearly all of the fringe
    assert!((b.signal_v1_sq / a.signal_v1_sq - 1.0).abs() < 0.01);
}

#[test]
fn positive_window_bins_match_the_estimator_module() {
    let k = positive_bins(16).unwrap();
    assert_eq!(k, (1..8).collect::<Vec<_>>());
}

#[test]
fn bad_input_is_a_typed_error() {
    assert!(NoiseModel::new(-1.0, false).is_err());
    assert!(NoiseModel::new(f64::NAN, false).is_err());
    assert!(appendix_stats(&[1.0, 2.0], &[1.0], &gauss(1.0), Formula::Exact).is_err());
    assert!(appendix_stats(
        &[-5.0, 2.0],
        &[1.0, 1.0],
        &NoiseModel::photon(),
        Formula::Exact
    )
    .is_err());
    assert!(window_stats(&[1.0, 2.0], &[1.0, 1.0], &gauss(1.0), &[2]).is_err());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn variances_are_non_negative(
        m in prop::collection::vec(-5.0f64..5.0, 2..24),
        c in 5.0f64..50.0,
        s in 0.0f64..5.0,
        photon in any::<bool>(),
        f in 0u8..2,
    ) {
        let noise = NoiseModel::new(s, photon).unwrap();
        let cont = vec![c; m.len()];
        let formula = if f == 0 { Formula::Exact } else { Formula::Published };
        let a = appendix_stats(&m, &cont, &noise, formula).unwrap();
        prop_assert!(a.var_v1_sq >= 0.0 && a.var_v2_sq >= 0.0);
        let counts: Vec<f64> = m.iter().map(|x| x + c).collect();
        let k: Vec<usize> = (1..m.len() / 2 + 1).collect();
        let w = window_stats(&m, &counts, &noise, &k).unwrap();
        prop_assert!(w.var_v1_sq >= -NONNEGATIVE_REL * w.var_v1_sq.abs().max(1.0));
        prop_assert!(w.var_v2_sq >= -NONNEGATIVE_REL * w.var_v2_sq.abs().max(1.0));
    }

    #[test]
    fn detector_variance_scales_as_fourth_power(
        m in prop::collection::vec(-5.0f64..5.0, 2..24),
        s in 0.1f64..5.0,
        k in 0.1f64..10.0,
    ) {
        // Scaling signal and σ_det together by k scales var V1², V2² by k⁴
        // and leaves the SNRs unchanged.
        let cont = vec![0.0; m.len()];
        let a = appendix_stats(&m, &cont, &gauss(s), Formula::Exact).unwrap();
        let mk: Vec<f64> = m.iter().map(|x| x * k).collect();
        let b = appendix_stats(&mk, &cont, &gauss(s * k), Formula::Exact).unwrap();
        prop_assert!((b.var_v1_sq / a.var_v1_sq / k.powi(4) - 1.0).abs() < IDENTITY_REL);
        prop_assert!((b.var_v2_sq / a.var_v2_sq / k.powi(4) - 1.0).abs() < IDENTITY_REL);
        // At fixed signal the variance grows with σ_det.
        let c = appendix_stats(&m, &cont, &gauss(s * 1.5), Formula::Exact).unwrap();
        prop_assert!(c.var_v1_sq > a.var_v1_sq && c.var_v2_sq > a.var_v2_sq);
    }

    #[test]
    fn snr2_ignores_n_and_snr1_falls_with_n(
        s in 0.1f64..5.0,
        extra in 1usize..500,
        photon in any::<bool>(),
    ) {
        let ifg = example_interferogram(&ExampleSetup { samples: 32, ..appendix_setup() }).unwrap();
        let noise = NoiseModel::new(s, photon).unwrap();
        for f in [Formula::Exact, Formula::Published] {
            let (a1, a2) = noise::snr_with_extra_samples(&ifg.modulated, &ifg.continuum, &noise, f, 0).unwrap();
            let (b1, b2) = noise::snr_with_extra_samples(&ifg.modulated, &ifg.continuum, &noise, f, extra).unwrap();
            prop_assert!((a2 / b2 - 1.0).abs() < IDENTITY_REL);
            prop_assert!(b1 < a1);
        }
    }
}

#[test]
fn published_detector_terms_are_exact_for_any_read_noise() {
    // The printed detector-noise variance 2σ²(2m² + σ²) and bias σ² are the
    // exact Gaussian ones; checked at σ ≠ 2 (where σ + σ = σ·σ would hide a
    // slip) and σ < 1.
    for s in [0.7, 1.3, 3.1] {
        let d = gauss(s);
        for m in [0.0, 2.5, -4.0] {
            assert_rel_eq!(
                published::detector_var_term(m, s),
                var_m2(&d, m, 0.0),
                IDENTITY_REL
            );
            for formula in [Formula::Exact, Formula::Published] {
                assert_rel_eq!(
                    noise::sample_bias(formula, &d, m, 10.0),
                    s * s,
                    IDENTITY_REL
                );
            }
        }
    }
}

#[test]
fn photon_bias_is_the_mean_count_exact_and_the_modulation_published() {
    // Exact: κ2 = σ² + n (n the mean total count); printed: σ² + m.
    let both = NoiseModel::new(0.7, true).unwrap();
    let (m, n) = (3.0, 11.0);
    assert_rel_eq!(
        noise::sample_bias(Formula::Exact, &both, m, n),
        0.49 + 11.0,
        IDENTITY_REL
    );
    assert_rel_eq!(
        noise::sample_bias(Formula::Published, &both, m, n),
        0.49 + 3.0,
        IDENTITY_REL
    );
}

#[test]
fn a_sample_with_zero_mean_count_is_accepted_and_a_negative_one_refused() {
    // Visibility 1 in a fringe trough: m = −c, no photons expected there.
    let p = NoiseModel::photon();
    let ok = appendix_stats(&[5.0, -5.0], &[5.0, 5.0], &p, Formula::Exact).unwrap();
    assert_rel_eq!(ok.sum_m2, 50.0, IDENTITY_REL);
    assert!(appendix_stats(&[5.0, -5.5], &[5.0, 5.0], &p, Formula::Exact).is_err());
}

#[test]
fn expectation_is_the_signal_with_the_exact_bias_and_off_by_the_continuum_with_the_printed_one() {
    // ⟨V1²_raw⟩ − bias = N Σ m² + N Σ κ2_i − N Σ b_i: the exact bias b = κ2
    // leaves the signal; the printed photon bias b = σ² + m leaves
    // N Σ (n_i − m_i) = N Σ c_i over V1² and N² c_0 over V2².
    let (m, c) = ([5.0, 3.0, -1.0, -4.0], [10.0, 12.0, 9.0, 6.0]);
    let noise = NoiseModel::new(1.3, true).unwrap();
    let exact = appendix_stats(&m, &c, &noise, Formula::Exact).unwrap();
    assert_rel_eq!(exact.expectation_v1_sq, 4.0 * 51.0, IDENTITY_REL);
    assert_rel_eq!(exact.expectation_v2_sq, 16.0 * 25.0, IDENTITY_REL);
    let printed = appendix_stats(&m, &c, &noise, Formula::Published).unwrap();
    let (sum_c, n) = (37.0, 4.0);
    assert_rel_eq!(
        printed.expectation_v1_sq,
        n * 51.0 + n * sum_c,
        IDENTITY_REL
    );
    assert_rel_eq!(
        printed.expectation_v2_sq,
        n * n * 25.0 + n * n * 10.0,
        IDENTITY_REL
    );
}

#[test]
fn paper_window_factor_is_the_root_of_the_bandwidth_ratio() {
    // √((1/δx)/Δσ_0): δx = 0.25 µm, Δσ_0 = 1 µm⁻¹ → √4; δx = 0.5, Δσ_0 = 1/8 → √16.
    assert_rel_eq!(noise::paper_window_factor(0.25, 1.0), 2.0, IDENTITY_REL);
    assert_rel_eq!(noise::paper_window_factor(0.5, 0.125), 4.0, IDENTITY_REL);
}

#[test]
fn empty_samples_add_their_noise_to_v1_sq_only() {
    // Extra samples (m = 0, continuum the mean c̄ of the packet's) add
    // var(M²) = κ4 + 2κ2² = c̄ + 2c̄² (photon noise) each to Σ var(M_i²):
    // SNR_1 = Σm² / √(Σ var_i + E(c̄ + 2c̄²)); SNR_2 reads sample 0 only.
    let (m, c) = ([6.0, -2.0, 1.0], [4.0, 8.0, 6.0]);
    let p = NoiseModel::photon();
    let extra = 17;
    let base = appendix_stats(&m, &c, &p, Formula::Exact).unwrap();
    let (snr1, snr2) = noise::snr_with_extra_samples(&m, &c, &p, Formula::Exact, extra).unwrap();
    let var_sum: f64 = m
        .iter()
        .zip(&c)
        .map(|(&mi, &ci)| var_m2(&p, mi, mi + ci))
        .sum();
    let c_mean: f64 = 6.0;
    let expected = 41.0 / (var_sum + extra as f64 * (c_mean + 2.0 * c_mean * c_mean)).sqrt();
    assert_rel_eq!(snr1, expected, IDENTITY_REL);
    assert_rel_eq!(snr2, base.snr2, IDENTITY_REL);
    let (same1, _) = noise::snr_with_extra_samples(&m, &c, &p, Formula::Exact, 0).unwrap();
    assert_rel_eq!(same1, base.snr1, IDENTITY_REL);
}

/// The smallest total number of samples with SNR_1 ≤ SNR_2, by walking the
/// number of empty samples one at a time (the slow oracle of the bisection).
fn crossover_by_walking(m: &[f64], c: &[f64], noise: &NoiseModel) -> usize {
    (0..)
        .find(|&extra| {
            let (a, b) = noise::snr_with_extra_samples(m, c, noise, Formula::Exact, extra).unwrap();
            a <= b
        })
        .map(|extra| m.len() + extra)
        .unwrap()
}

#[test]
fn crossover_bisection_matches_the_walk_and_the_closed_form() {
    // Detector noise: var(M²) = 4m²σ² + 2σ⁴, so SNR_1 ≤ SNR_2 from
    // E ≥ ((Σm²)²/SNR_2² − Σ var_i) / 2σ⁴ empty samples on.
    let c = [10.0; 3];
    for (m, s) in [
        ([3.0, 2.0, 1.5], 1.1),
        ([4.0, -3.5, 2.2], 0.9),
        ([2.5, 2.0, -1.0], 1.7),
    ] {
        let d = gauss(s);
        let var: Vec<f64> = m.iter().map(|&mi| var_m2(&d, mi, 0.0)).collect();
        let sum_m2: f64 = m.iter().map(|x| x * x).sum();
        let snr2 = m[0] * m[0] / var[0].sqrt();
        let extra = ((sum_m2 * sum_m2 / (snr2 * snr2) - var.iter().sum::<f64>())
            / (2.0 * s.powi(4)))
        .ceil()
        .max(0.0) as usize;
        let found = noise::crossover_samples(&m, &c, &d, Formula::Exact)
            .unwrap()
            .unwrap();
        assert_eq!(found, 3 + extra, "m = {m:?}, σ = {s}");
        assert_eq!(
            found,
            crossover_by_walking(&m, &c, &d),
            "m = {m:?}, σ = {s}"
        );
    }
    // Already crossed: the packet alone.
    let d = gauss(1.0);
    assert_eq!(
        noise::crossover_samples(&[5.0, 0.1], &[10.0; 2], &d, Formula::Exact).unwrap(),
        Some(2)
    );
}

#[test]
fn abcd_variance_is_that_of_two_squared_gaussian_differences() {
    // A − C and B − D are Gaussian with means (N V/2)(cos φ, sin φ) and
    // variance 2σ²: var X² = 4μ²s² + 2s⁴ for each, summed.
    for (photons, v, s, phase) in [(100.0, 0.6, 1.5, 0.3), (40.0, 1.0, 0.4, 2.0)] {
        let diff = gauss(s * std::f64::consts::SQRT_2);
        let amp = photons * v / 2.0;
        let two_squares =
            var_m2(&diff, amp * f64::cos(phase), 0.0) + var_m2(&diff, amp * f64::sin(phase), 0.0);
        assert_rel_eq!(
            noise::abcd_detector_variance(photons, v, s),
            two_squares,
            IDENTITY_REL
        );
    }
    assert_rel_eq!(noise::colavita_detector_variance(0.5), 1.0, IDENTITY_REL);
    assert_rel_eq!(
        noise::abcd_detector_variance(80.0, 0.0, 0.5),
        noise::colavita_detector_variance(0.5),
        IDENTITY_REL
    );
}

#[test]
fn window_stats_refuses_unmatched_samples_and_gives_signal_over_root_variance() {
    let noise = NoiseModel::new(0.8, true).unwrap();
    let param = |e: v2ref_core::Error| e.param().unwrap_or("none").to_owned();
    for (m, counts) in [(vec![1.0, 2.0], vec![5.0, 5.0, 5.0]), (vec![], vec![])] {
        let e = window_stats(&m, &counts, &noise, &[0]).unwrap_err();
        assert_eq!(
            param(e),
            "samples",
            "{} and {} samples",
            m.len(),
            counts.len()
        );
    }
    let m = [3.0, -1.0, 2.5, 0.5];
    let counts = [8.0, 4.0, 7.5, 5.5];
    let w = window_stats(&m, &counts, &noise, &[1, 3]).unwrap();
    assert_rel_eq!(w.snr1, w.signal_v1_sq / w.var_v1_sq.sqrt(), IDENTITY_REL);
    assert_rel_eq!(w.snr2, w.signal_v2_sq / w.var_v2_sq.sqrt(), IDENTITY_REL);
    assert!(w.snr1 > 0.0 && w.snr2 > 0.0);
}
