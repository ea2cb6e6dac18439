//! Closed forms and identities of the foundation: quadrature rules, the
//! band and W, the spectral estimators' limits, the sampled interferogram
//! against its slow oracle, the DFT identities.

use num_complex::Complex64;
use v2ref_core::formalism::estimator::{
    all_bins, dft, noise_bias, raw_estimates, sampled_wide_band, v1_sq, v2_sq, v_mono, wide_band,
    BinWindow,
};
use v2ref_core::formalism::interferogram::{sinc, Interferogram, Sampling, SpectralNodes};
use v2ref_core::formalism::observation::{Frequency, Observation};
use v2ref_core::formalism::oracle::{interferogram_adaptive, naive_dft};
use v2ref_core::formalism::phase::SpectralPhase;
use v2ref_core::formalism::source::{Component, FluxProfile, Source};
use v2ref_core::formalism::spectrum::{Band, Spectrum};
use v2ref_core::math::quadrature::{gauss_kronrod_15, gauss_legendre, integrate, Tolerance};
use v2ref_core::tolerance::{
    BESSEL_ABS, CONVERGENCE_GROWTH_REL, DIRECT_SUM_REL, EPS, FFT_SUM_REL, NAIVE_DFT_ABS, NODES_REL,
    QUADRATURE_CHECK_REL, QUADRATURE_REL, RIEMANN_SUM_ABS, ROUNDING_REL, SAMPLED_VS_SPECTRAL_ABS,
    SQUARE_LAW_REL, ULPS,
};
use v2ref_core::Error;
use v2ref_core::{assert_abs_eq, assert_rel_eq};

fn disk_obs(spectrum: Spectrum, s_cpas: f64, pp_rad: f64) -> Observation {
    let phase = SpectralPhase::dispersion_peak_to_peak(&spectrum, pp_rad).unwrap();
    Observation::new(
        spectrum,
        Source::uniform_disk(43.0).unwrap(),
        Frequency::SpatialFreqCpas(s_cpas),
        phase,
    )
    .unwrap()
}

// ---- quadrature -----------------------------------------------------------

#[test]
fn kronrod_15_is_exact_to_degree_22_and_gauss_7_to_degree_13() {
    // ∫_{-1}^{1} x^p dx = 2/(p+1) for even p. A wrong node or weight in the
    // tables breaks exactness at these degrees.
    for p in (0..=22).step_by(2) {
        let (k, _) = gauss_kronrod_15(&|x: f64| x.powi(p), -1.0, 1.0);
        assert_rel_eq!(k, 2.0 / f64::from(p + 1), ROUNDING_REL);
    }
    // The G7 part: K15 − G7 is the error estimate, zero for degree ≤ 13.
    for p in (0..=12).step_by(2) {
        let (_, err) = gauss_kronrod_15(&|x: f64| x.powi(p), -1.0, 1.0);
        assert!(err < ROUNDING_REL, "degree {p}: K15 - G7 = {err:e}");
    }
    let (_, err) = gauss_kronrod_15(&|x: f64| x.powi(14), -1.0, 1.0);
    assert!(err > 1e-6, "G7 cannot be exact at degree 14");
}

#[test]
fn gauss_legendre_is_exact_to_degree_2n_minus_1() {
    for n in [1usize, 2, 5, 16, 33] {
        let (x, w) = gauss_legendre(n).unwrap();
        for p in (0..2 * n as i32).step_by(2) {
            let q: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(p)).sum();
            assert_rel_eq!(q, 2.0 / f64::from(p + 1), NODES_REL);
        }
    }
}

#[test]
fn adaptive_quadrature_converges_on_a_peaked_integrand() {
    // ∫_0^1 1/(1e-4 + (x-0.3)^2) dx = 100 (atan(70) + atan(30)).
    let f = |x: f64| 1.0 / (1e-4 + (x - 0.3).powi(2));
    let want = 100.0 * (70f64.atan() + 30f64.atan());
    let got = integrate(f, 0.0, 1.0, Tolerance::default());
    assert_rel_eq!(got, want, QUADRATURE_CHECK_REL);
}

#[test]
fn a_vector_integrand_is_refined_until_every_component_converges() {
    // √x and x^{1/3} have singular derivatives at 0: one K15 panel is off
    // by ~1e-4, so the result is right only if the error control of the
    // array type refines. ∫_0^1 = 2/3 and 3/4.
    let f = |x: f64| [x.sqrt(), x.cbrt()];
    let got = integrate(f, 0.0, 1.0, Tolerance::default());
    assert_rel_eq!(got[0], 2.0 / 3.0, QUADRATURE_CHECK_REL);
    assert_rel_eq!(got[1], 0.75, QUADRATURE_CHECK_REL);
}

/// ∫ f over [0, 1] and the number of evaluations of f it took.
fn integrate_counting(f: impl Fn(f64) -> f64, tol: Tolerance) -> (f64, usize) {
    let calls = std::cell::Cell::new(0usize);
    let value = integrate(
        |x| {
            calls.set(calls.get() + 1);
            f(x)
        },
        0.0,
        1.0,
        tol,
    );
    (value, calls.get())
}

#[test]
fn relative_and_rounding_targets_scale_with_the_integrand() {
    // With no absolute target the error control is scale-free: f and 2^20 f
    // are refined on the same panels, and the result scales bit for bit
    // (a power of two commutes with every rounding). Both the relative
    // target and the rounding floor (rel = 0) are checked.
    let f = |x: f64| (3.0 * x).exp() * x.sqrt();
    let c = 2f64.powi(20);
    for rel in [1e-9, 0.0] {
        let tol = Tolerance { abs: 0.0, rel };
        let (one, calls_one) = integrate_counting(f, tol);
        let (scaled, calls_scaled) = integrate_counting(|x| c * f(x), tol);
        assert_eq!(calls_one, calls_scaled, "rel = {rel}");
        assert_eq!(scaled.to_bits(), (c * one).to_bits(), "rel = {rel}");
        assert!(
            calls_one < 4000 * 15,
            "rel = {rel}: {calls_one} evaluations"
        );
    }
}

#[test]
fn an_integrand_that_never_converges_stops_at_4000_panels() {
    // sin(10⁵ x) over [0, 1]: 16 000 periods, more than 4000 panels can
    // resolve, so every panel keeps a nonzero error estimate and the loop
    // ends at the panel limit: 15 + 30 · 3999 evaluations.
    let (_, calls) = integrate_counting(|x| (1e5 * x).sin(), Tolerance { abs: 0.0, rel: 0.0 });
    assert_eq!(calls, 15 + 30 * 3999);
}

#[test]
fn a_singular_integrand_is_bisected_to_depth_40() {
    // ∫_0^1 x^{-1/2} = 2: the panel at 0 is bisected down to [0, 2^-40],
    // where the depth limit stops it, and what is left of the error is the
    // K15 error on that panel, √(2^-40) times the one on [0, 1] (x^{-1/2}
    // scales as h^{-1/2} over a panel of width h).
    let f = |x: f64| 1.0 / x.sqrt();
    let (got, calls) = integrate_counting(f, Tolerance { abs: 0.0, rel: 0.0 });
    // Once every panel that may still be bisected has a zero error
    // estimate, bisecting cannot help: the loop stops before the panel limit.
    assert!(calls < 15 + 30 * 3999, "{calls} evaluations");
    let (k15_unit, _) = gauss_kronrod_15(&f, 0.0, 1.0);
    let predicted = 2.0 + 2f64.powi(-20) * (k15_unit - 2.0);
    // The prediction is 4.4e-8 below 2 (depth 41 would leave 3.1e-8).
    assert_rel_eq!(got, predicted, QUADRATURE_CHECK_REL);
}

// ---- band and W -------------------------------------------------------------

#[test]
fn flat_band_has_the_closed_form_moments() {
    let band = Band::k();
    let sp = Spectrum::flat(band);
    let (lo, hi) = (1.0 / 2.4, 1.0 / 2.0);
    assert_rel_eq!(sp.support().0, lo, ULPS);
    assert_rel_eq!(sp.support().1, hi, ULPS);
    assert_rel_eq!(sp.sigma_eff_per_um(), 0.5 * (lo + hi), ROUNDING_REL);
    assert_rel_eq!(sp.w2_integral_um(), 1.0 / (hi - lo), QUADRATURE_REL);
    assert_rel_eq!(sp.mean_w(|_| 1.0), 1.0, ROUNDING_REL);
    assert_rel_eq!(
        sp.mean_w(|s| s * s),
        (hi.powi(3) - lo.powi(3)) / (3.0 * (hi - lo)),
        QUADRATURE_REL
    );
    // Riemann sums on a fine grid approach the integrals.
    let (s1, s2) = sp.grid_sums(1e-5).unwrap();
    assert!((s1 - 1.0).abs() < RIEMANN_SUM_ABS && (s2 * (hi - lo) - 1.0).abs() < RIEMANN_SUM_ABS);
}

#[test]
fn band_and_sampling_refuse_bad_input_with_the_parameter_named() {
    let name = |e: Error| e.param().unwrap_or("none").to_owned();
    assert_eq!(name(Band::new(-1.0, 0.4).unwrap_err()), "wavelength_um");
    assert_eq!(name(Band::new(f64::NAN, 0.4).unwrap_err()), "wavelength_um");
    assert_eq!(name(Band::new(2.2, 0.0).unwrap_err()), "bandwidth_um");
    assert_eq!(name(Band::new(2.2, 4.4).unwrap_err()), "bandwidth_um");
    assert_eq!(name(Source::uniform_disk(0.0).unwrap_err()), "diameter_mas");
    assert_eq!(name(Sampling::new(1, 0.5, false).unwrap_err()), "samples");
    assert_eq!(
        name(Sampling::new(128, f64::INFINITY, false).unwrap_err()),
        "dx_um"
    );
    let obs = disk_obs(Spectrum::flat(Band::k()), 10.0, 0.0);
    let coarse = Sampling::new(128, 1.0, false).unwrap();
    assert_eq!(name(coarse.check_aliasing(&obs).unwrap_err()), "dx_um");
    assert_eq!(
        name(
            Observation::new(
                Spectrum::flat(Band::k()),
                Source::Point,
                Frequency::SpatialFreqCpas(-1.0),
                SpectralPhase::zero()
            )
            .unwrap_err()
        ),
        "spatial_freq_cpas"
    );
}

// ---- spectral estimators ------------------------------------------------------

#[test]
fn monochromatic_band_gives_v1_equal_v2_equal_v_mono() {
    // The reference is mpmath's 2 J1(x)/x at 50 digits
    // (tests/data/bessel_reference.csv), not the crate's Bessel function: the
    // 43 mas disk is observed at S = x/(π θ), so that z = π θ S is x up to
    // the rounding of the S → B → S round trip (a few ε relative), which
    // moves |V| by at most 4 ε x |V'| with |V'| = |2 J2(x)/x| ≤ 1/2.
    let sp = Spectrum::monochromatic(2.2).unwrap();
    let theta_arcsec = 0.043;
    let mut count = 0;
    for line in include_str!("data/bessel_reference.csv").lines() {
        let row: Vec<&str> = line.split(',').collect();
        if row[0] != "value" {
            continue;
        }
        let x: f64 = row[1].parse().unwrap();
        if x > 16.0 {
            continue; // the first five lobes: S up to ~118 cycles/arcsec
        }
        let exact = row[4].parse::<f64>().unwrap().abs();
        let s = x / (std::f64::consts::PI * theta_arcsec);
        let wb = wide_band(&disk_obs(sp.clone(), s, 0.0));
        let tol = BESSEL_ABS + 4.0 * EPS * x * 0.5;
        assert_abs_eq!(wb.v_mono, exact, tol, "x = {x}: V_mono");
        assert_abs_eq!(wb.v1, exact, tol, "x = {x}: V1");
        assert_abs_eq!(wb.v2, exact, tol, "x = {x}: V2");
        count += 1;
    }
    assert!(count >= 40, "{count} reference points");
}

#[test]
fn bandwidth_bias_vanishes_as_the_band_narrows_with_the_square_of_its_width() {
    // Away from a null, V1 − V_mono and V2 − V_mono are even in Δσ and start
    // at Δσ²: halving the band divides them by 4.
    for s in [15.0, 40.0] {
        let dev = |width_um: f64| {
            let wb = wide_band(&disk_obs(
                Spectrum::flat(Band::new(2.2, width_um).unwrap()),
                s,
                0.0,
            ));
            (wb.v1 - wb.v_mono, wb.v2 - wb.v_mono)
        };
        let widths = [0.1, 0.05, 0.025];
        let d: Vec<(f64, f64)> = widths.iter().map(|&w| dev(w)).collect();
        for pair in d.windows(2) {
            let r1 = pair[0].0 / pair[1].0;
            let r2 = pair[0].1 / pair[1].1;
            assert_rel_eq!(r1, 4.0, SQUARE_LAW_REL, "S = {s}: V1 ratio");
            assert_rel_eq!(r2, 4.0, SQUARE_LAW_REL, "S = {s}: V2 ratio");
        }
        // tol: the 25 nm band's deviations are ~(25/400)² of the 400 nm band's ~4e-2 (the ledger's bandwidth claims), ~2e-4; a law linear in the width would give ~3e-3.
        assert!(d[2].0.abs() < 1e-3 && d[2].1.abs() < 1e-3);
    }
}

#[test]
fn point_source_without_phase_reads_one() {
    let obs = Observation::new(
        Spectrum::flat(Band::k()),
        Source::Point,
        Frequency::BaselineM(100.0),
        SpectralPhase::zero(),
    )
    .unwrap();
    assert_rel_eq!(v1_sq(&obs), 1.0, QUADRATURE_REL);
    assert_rel_eq!(v2_sq(&obs), 1.0, QUADRATURE_REL);
    assert_eq!(v_mono(&obs), 1.0);
}

#[test]
fn composite_of_identical_components_is_the_component() {
    // Flux-weighted sum of two copies of a disk, one with a line, is the disk.
    let disk = Source::uniform_disk(20.0).unwrap();
    let line = FluxProfile::gaussian_line_velocity(2.2, 30.0, 1e-4).unwrap();
    let comp = Source::composite(vec![
        Component {
            source: disk.clone(),
            flux: FluxProfile::Flat { flux: 1.0 },
        },
        Component {
            source: disk.clone(),
            flux: line,
        },
    ])
    .unwrap();
    for sigma in [0.42, 0.4545, 0.49] {
        let a = comp.visibility(sigma, 30.0);
        let b = disk.visibility(sigma, 30.0);
        assert!((a - b).norm() < ULPS);
    }
    // And a continuum of visibility 0.5 with an unresolved line of equal peak
    // flux density reads 0.75 at the line centre, 0.5 far from it.
    let lined = continuum_with_line(FluxProfile::GaussianLine {
        centre_per_um: 0.5,
        fwhm_per_um: 1e-5,
        peak: 1.0,
    });
    assert_rel_eq!(lined.visibility(0.5, 10.0).re, 0.75, ULPS);
    assert_rel_eq!(lined.visibility(0.4, 10.0).re, 0.5, ULPS);
    // Where no component has flux (a line alone, 200 FWHM away, where its
    // Gaussian underflows to 0) there is no fringe: V = 0, not 0/0.
    let alone = Source::composite(vec![Component {
        source: Source::Point,
        flux: FluxProfile::GaussianLine {
            centre_per_um: 0.5,
            fwhm_per_um: 1e-5,
            peak: 1.0,
        },
    }])
    .unwrap();
    assert_eq!(alone.visibility(0.5, 10.0), Complex64::new(1.0, 0.0));
    assert_eq!(alone.visibility(0.498, 10.0), Complex64::new(0.0, 0.0));
}

#[test]
fn a_velocity_line_has_its_centre_width_and_flux() {
    // The definition of a Gaussian line, checked from the profile itself:
    // peak at σ_c = 1/λ, half the peak at σ_c ± fwhm/2 with fwhm = σ_c v/c
    // (c exact in SI), and the flux as its area, by a trapezoid over ±8
    // FWHM (4 ln2 · 64 puts the tails below e^-177; on 4000 steps the
    // trapezoid of a Gaussian is exact to rounding).
    for (wavelength_um, fwhm_km_s, flux) in
        [(2.166, 30.0, 1e-4), (1.65, 250.0, 3.0), (0.8, 5.0, 7.5)]
    {
        let line = FluxProfile::gaussian_line_velocity(wavelength_um, fwhm_km_s, flux).unwrap();
        let FluxProfile::GaussianLine {
            centre_per_um,
            fwhm_per_um,
            peak,
        } = line
        else {
            panic!("{line:?} is not a Gaussian line");
        };
        assert_rel_eq!(centre_per_um, 1.0 / wavelength_um, ROUNDING_REL);
        assert_rel_eq!(
            fwhm_per_um,
            centre_per_um * fwhm_km_s / 299_792.458,
            ROUNDING_REL
        );
        assert_rel_eq!(line.at(centre_per_um), peak, ROUNDING_REL);
        // σ_c ± fwhm/2 is rounded to an ulp of σ_c: c/v ulps of the offset.
        let offset_rel = ROUNDING_REL * centre_per_um / fwhm_per_um;
        for side in [-0.5, 0.5] {
            assert_rel_eq!(
                line.at(centre_per_um + side * fwhm_per_um),
                0.5 * peak,
                offset_rel
            );
        }
        let steps = 4000;
        let (lo, h) = (
            centre_per_um - 8.0 * fwhm_per_um,
            16.0 * fwhm_per_um / steps as f64,
        );
        let area = h
            * (0..=steps)
                .map(|i| {
                    let end = if i == 0 || i == steps { 0.5 } else { 1.0 };
                    end * line.at(lo + i as f64 * h)
                })
                .sum::<f64>();
        assert_rel_eq!(area, flux, QUADRATURE_CHECK_REL);
    }
}

/// A continuum of visibility 0.5 and unit flux, with an unresolved
/// emission line of flux profile `line`.
fn continuum_with_line(line: FluxProfile) -> Source {
    Source::composite(vec![
        Component {
            source: Source::Constant {
                visibility: Complex64::new(0.5, 0.0),
            },
            flux: FluxProfile::Flat { flux: 1.0 },
        },
        Component {
            source: Source::Point,
            flux: line,
        },
    ])
    .unwrap()
}

/// A 50 % continuum with an unresolved 10 km/s emission line at 2.166 µm
/// (FWHM 1.5e-5 µm⁻¹, 1/5400 of the K band) whose peak equals the
/// continuum: V = 0.75 at the line centre.
fn narrow_line_obs() -> Observation {
    let mut line = FluxProfile::gaussian_line_velocity(2.166, 10.0, 1.0).unwrap();
    if let FluxProfile::GaussianLine { peak, .. } = &mut line {
        *peak = 1.0;
    }
    Observation::new(
        Spectrum::flat(Band::k()),
        continuum_with_line(line),
        Frequency::BaselineM(100.0),
        SpectralPhase::zero(),
    )
    .unwrap()
}

#[test]
fn a_narrow_line_is_not_stepped_over() {
    // The line moves V2 by ~5e-5 of the continuum's 0.5; a quadrature whose
    // nodes all fall outside it would read the continuum alone. Truth: a
    // uniform trapezoid of 2^17 steps over the flat band (34 steps per line
    // FWHM; the integrand is constant at both band edges, so the trapezoid
    // is exact to rounding), against the adaptive spectral forms and the
    // spectral nodes of the sampled path, which both place their panels at
    // the line's split points.
    let obs = narrow_line_obs();
    let (lo, hi) = obs.spectrum.support();
    let steps = 1usize << 17;
    let h = (hi - lo) / steps as f64;
    let (mut mean_v, mut mean_v2) = (Complex64::new(0.0, 0.0), 0.0);
    for i in 0..=steps {
        let end = if i == 0 || i == steps { 0.5 } else { 1.0 };
        let v = obs.source.visibility(lo + i as f64 * h, obs.baseline_m);
        mean_v += v * (end / steps as f64);
        mean_v2 += v.norm_sqr() * (end / steps as f64);
    }
    assert!(mean_v.re - 0.5 > 4e-5, "the line is in the truth: {mean_v}");
    assert_rel_eq!(v1_sq(&obs), mean_v2, QUADRATURE_CHECK_REL);
    assert_rel_eq!(v2_sq(&obs), mean_v.norm_sqr(), QUADRATURE_CHECK_REL);
    let nodes = SpectralNodes::new(&obs, 100.0, None).unwrap();
    let sum: Complex64 = nodes.amplitude.iter().sum();
    assert!(
        (sum - mean_v).norm() < QUADRATURE_CHECK_REL,
        "{sum} vs {mean_v}"
    );
}

// ---- sampled interferograms ----------------------------------------------------

#[test]
fn fast_synthesis_matches_the_adaptive_oracle() {
    // Flat, and with raised-cosine edges, whose kinks the nodes' panels
    // must respect (a panel across one converges only algebraically).
    let smooth = Spectrum::smooth_top_hat(Band::k(), 0.02).unwrap();
    for (integrating, pp, spectrum) in [
        (false, 0.0, Spectrum::flat(Band::k())),
        (true, 0.0, Spectrum::flat(Band::k())),
        (false, 1.5, Spectrum::flat(Band::k())),
        (false, 0.0, smooth),
    ] {
        let obs = disk_obs(spectrum, 33.0, pp);
        let sampling = Sampling::new(256, 0.5, integrating).unwrap();
        let fast = Interferogram::synthesize(&obs, &sampling, 1.0, None)
            .unwrap()
            .modulated;
        let slow = interferogram_adaptive(&obs, &sampling);
        assert_eq!((fast.len(), slow.len()), (256, 256));
        let worst = fast
            .iter()
            .zip(&slow)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(
            worst < QUADRATURE_CHECK_REL,
            "integrating {integrating}, {pp} rad: max error {worst:e}"
        );
    }
}

#[test]
fn white_light_fringe_of_a_point_source_is_the_continuum() {
    let obs = Observation::new(
        Spectrum::flat(Band::k()),
        Source::Point,
        Frequency::BaselineM(0.0),
        SpectralPhase::zero(),
    )
    .unwrap();
    let sampling = Sampling::new(128, 0.5, false).unwrap();
    let ifg = Interferogram::synthesize(&obs, &sampling, 10.0, None).unwrap();
    assert_rel_eq!(ifg.modulated[0], 10.0, QUADRATURE_REL);
    assert!(ifg
        .modulated
        .iter()
        // tol: not a tolerance: 10 is the fringe amplitude n V; QUADRATURE_REL is the tolerance.
        .all(|m| m.abs() <= 10.0 * (1.0 + QUADRATURE_REL)));
    assert_eq!(ifg.continuum, vec![10.0; 128]);
    // An OPD perturbation equal to a whole scan shift moves the fringe.
    let shift = vec![0.5; 128];
    let moved = Interferogram::synthesize(&obs, &sampling, 10.0, Some(&shift)).unwrap();
    assert_rel_eq!(moved.modulated[127], 10.0, QUADRATURE_CHECK_REL);
}

#[test]
fn integrating_detector_multiplies_a_monochromatic_fringe_by_sinc() {
    let obs = Observation::new(
        Spectrum::monochromatic(2.2).unwrap(),
        Source::Point,
        Frequency::BaselineM(0.0),
        SpectralPhase::zero(),
    )
    .unwrap();
    for spf in [2.5, 3.0, 4.0, 8.0] {
        let dx = 2.2 / spf;
        let m = |integrating| {
            Interferogram::synthesize(
                &obs,
                &Sampling::new(64, dx, integrating).unwrap(),
                1.0,
                None,
            )
            .unwrap()
            .modulated
        };
        let (a, b) = (m(false), m(true));
        let ratio = b[0] / a[0];
        assert_rel_eq!(ratio, sinc(1.0 / spf), QUADRATURE_REL);
    }
    assert_rel_eq!(sinc(0.5), 2.0 / std::f64::consts::PI, ULPS);
    assert_rel_eq!(
        1.0 / sinc(0.25).powi(2),
        std::f64::consts::PI.powi(2) / 8.0,
        ULPS
    );
}

#[test]
fn fft_matches_the_naive_dft_and_the_appendix_identities() {
    let samples: Vec<f64> = (0..100)
        .map(|i| ((i * 37 % 101) as f64 / 50.0 - 1.0) * 3.0)
        .collect();
    let fast = dft(&samples);
    let slow = naive_dft(&samples);
    // Lengths first: a zip over an empty oracle would compare nothing.
    assert_eq!((fast.len(), slow.len()), (100, 100));
    for (a, b) in fast.iter().zip(&slow) {
        assert!((a - b).norm() < NAIVE_DFT_ABS);
    }
    let n = samples.len() as f64;
    let all = all_bins(samples.len()).unwrap();
    let raw = raw_estimates(&fast, &all).unwrap();
    assert_rel_eq!(
        raw.v1_sq,
        n * samples.iter().map(|m| m * m).sum::<f64>(),
        FFT_SUM_REL
    );
    assert_rel_eq!(raw.v2_sq, (n * samples[0]).powi(2), DIRECT_SUM_REL);
}

#[test]
fn noise_bias_matches_its_definition() {
    // V2 bias over all bins is N² v_0; V1 bias is |K| Σ v_i; for a window the
    // V2 kernel is |Σ_k e^{-2πi ik/N}|², checked against a direct sum.
    let n = 16;
    let var: Vec<f64> = (0..n).map(|i| 1.0 + i as f64 * 0.1).collect();
    let all: Vec<usize> = (0..n).collect();
    let b = noise_bias(&var, &all).unwrap();
    assert_rel_eq!(b.v1_sq, n as f64 * var.iter().sum::<f64>(), ROUNDING_REL);
    assert_rel_eq!(b.v2_sq, (n * n) as f64 * var[0], DIRECT_SUM_REL);
    let window = [2usize, 3, 4];
    let direct: f64 = var
        .iter()
        .enumerate()
        .map(|(i, v)| {
            let k: Complex64 = window
                .iter()
                .map(|&k| {
                    Complex64::from_polar(
                        1.0,
                        -2.0 * std::f64::consts::PI * (i * k) as f64 / n as f64,
                    )
                })
                .sum();
            v * k.norm_sqr()
        })
        .sum();
    assert_rel_eq!(
        noise_bias(&var, &window).unwrap().v2_sq,
        direct,
        DIRECT_SUM_REL
    );
}

#[test]
#[ignore = "slow tier: long finely sampled scans against the spectral form (8 s)"]
fn long_finely_sampled_scans_converge_to_the_spectral_estimators() {
    // The finite-scan bias falls as the stroke grows; at 1024 µm it is below
    // SAMPLED_VS_SPECTRAL_ABS in V² at every tested frequency, with and
    // without dispersion (positive-frequency window).
    for s in [5.0, 20.0, 28.0, 45.0, 70.0] {
        for pp in [0.0, 2.0] {
            let obs = disk_obs(Spectrum::flat(Band::k()), s, pp);
            let spectral = (v1_sq(&obs), v2_sq(&obs));
            let mut last = f64::INFINITY;
            for n in [256usize, 1024, 4096] {
                let sampled = sampled_wide_band(
                    &obs,
                    &Sampling::new(n, 0.25, false).unwrap(),
                    BinWindow::Positive,
                )
                .unwrap();
                let err = (sampled.v1_sq - spectral.0)
                    .abs()
                    .max((sampled.v2_sq - spectral.1).abs());
                assert!(
                    err <= last * (1.0 + CONVERGENCE_GROWTH_REL) + QUADRATURE_CHECK_REL,
                    "S {s}, {pp} rad, N {n}: error {err:e} grew from {last:e}"
                );
                last = err;
            }
            assert!(last < SAMPLED_VS_SPECTRAL_ABS, "S {s}, {pp} rad: {last:e}");
        }
    }
}

#[test]
fn smooth_and_sloped_spectra_have_their_closed_form_moments() {
    let band = Band::k();
    let (lo, hi) = (band.sigma_min_per_um(), band.sigma_max_per_um());
    // Raised-cosine edges centred on the band edges keep the equivalent width
    // and, being symmetric, the centroid.
    let smooth = Spectrum::smooth_top_hat(band, 0.02).unwrap();
    assert_rel_eq!(smooth.sigma_eff_per_um(), 0.5 * (lo + hi), QUADRATURE_REL);
    let raw_area = smooth.mean_w(|_| 1.0);
    assert_rel_eq!(raw_area, 1.0, QUADRATURE_REL);
    assert_rel_eq!(
        smooth.weight(lo),
        0.5 * smooth.weight(0.5 * (lo + hi)),
        ROUNDING_REL
    );
    assert_eq!(smooth.weight(lo - 0.011), 0.0);
    assert!(Spectrum::smooth_top_hat(band, 0.5).is_err());
    // The widest edge accepted is the band's width itself, bound included.
    assert!(Spectrum::smooth_top_hat(band, hi - lo).is_ok());
    assert!(Spectrum::smooth_top_hat(band, (hi - lo) * (1.0 + 4.0 * EPS)).is_err());
    // Power law σ^p: σ_eff = (p+1)/(p+2) (hi^{p+2} − lo^{p+2}) / (hi^{p+1} − lo^{p+1}).
    for p in [-4.0f64, -1.5, 2.0, 3.0] {
        let sp = Spectrum::power_law(band, p).unwrap();
        let want = (p + 1.0) / (p + 2.0) * (hi.powf(p + 2.0) - lo.powf(p + 2.0))
            / (hi.powf(p + 1.0) - lo.powf(p + 1.0));
        assert_rel_eq!(sp.sigma_eff_per_um(), want, QUADRATURE_REL);
    }
    // A steep slope moves the effective wavenumber, hence S at fixed B.
    let blue = Spectrum::power_law(band, 4.0).unwrap();
    assert!(blue.sigma_eff_per_um() > Spectrum::flat(band).sigma_eff_per_um());
}

#[test]
fn each_shape_has_its_support_centre_and_width() {
    // The support bounds W (zero outside, positive just inside); the
    // centre and width are those of the nominal band (the expansion point
    // and scale of the dispersion phase), of the table's ends for a table.
    let band = Band::k();
    let (lo, hi) = (band.sigma_min_per_um(), band.sigma_max_per_um());
    let edge = 0.02;
    let (t_lo, t_hi) = (0.41, 0.52);
    let shapes = [
        (Spectrum::flat(band), (lo, hi), (lo, hi)),
        (Spectrum::power_law(band, 2.0).unwrap(), (lo, hi), (lo, hi)),
        (
            Spectrum::smooth_top_hat(band, edge).unwrap(),
            (lo - 0.5 * edge, hi + 0.5 * edge),
            (lo, hi),
        ),
        (
            Spectrum::tabulated(vec![t_lo, 0.45, t_hi], vec![1.0, 2.0, 0.5]).unwrap(),
            (t_lo, t_hi),
            (t_lo, t_hi),
        ),
    ];
    for (sp, (a, b), (nominal_lo, nominal_hi)) in shapes {
        assert_eq!(sp.support(), (a, b), "{sp:?}");
        let step = 1e-9;
        for outside in [0.1, a - step, b + step, 2.0] {
            assert_eq!(sp.weight(outside), 0.0, "{sp:?} at {outside}");
        }
        for inside in [a + step, b - step] {
            assert!(sp.weight(inside) > 0.0, "{sp:?} at {inside}");
        }
        assert_rel_eq!(
            sp.sigma_centre_per_um(),
            0.5 * (nominal_lo + nominal_hi),
            ROUNDING_REL
        );
        assert_rel_eq!(sp.width_per_um(), nominal_hi - nominal_lo, ROUNDING_REL);
    }
    // A table's weight at its end nodes is the nodes' own weight.
    let table = Spectrum::tabulated(vec![t_lo, 0.45, t_hi], vec![1.0, 2.0, 0.5]).unwrap();
    let apex = table.weight(0.45);
    assert_rel_eq!(table.weight(t_lo) / apex, 0.5, ROUNDING_REL);
    assert_rel_eq!(table.weight(t_hi) / apex, 0.25, ROUNDING_REL);
    // The raised-cosine edge: ½(1 + sin(π d/e)) of the plateau at a distance
    // d inside the band edge, so W(lo + d) + W(lo − d) is the plateau.
    let smooth = Spectrum::smooth_top_hat(band, edge).unwrap();
    let plateau = smooth.weight(0.5 * (lo + hi));
    // lo ± d is rounded to an ulp of lo: π lo/e ulps of the sine's argument.
    let position_abs = ROUNDING_REL * std::f64::consts::PI * hi / edge;
    for d in [0.25 * edge, 0.1 * edge, 0.4 * edge] {
        let inner = 0.5 * (1.0 + (std::f64::consts::PI * d / edge).sin());
        for (at, side) in [(lo + d, 1.0), (hi - d, 1.0), (lo - d, -1.0), (hi + d, -1.0)] {
            let want = if side > 0.0 { inner } else { 1.0 - inner };
            assert_abs_eq!(smooth.weight(at) / plateau, want, position_abs);
        }
    }
    let line = Spectrum::monochromatic(2.2).unwrap();
    assert_eq!(line.width_per_um(), 0.0);
    assert_eq!(line.sigma_centre_per_um(), 1.0 / 2.2);
}

#[test]
fn dispersion_phase_has_its_peak_to_peak_over_the_nominal_band() {
    // φ = ½ D (σ − σ0)²: 0 at the centre, P at both nominal band edges,
    // P/4 half way, whatever the shape's edges; no phase on a line.
    let band = Band::k();
    let (lo, hi) = (band.sigma_min_per_um(), band.sigma_max_per_um());
    for sp in [
        Spectrum::flat(band),
        Spectrum::smooth_top_hat(band, 0.03).unwrap(),
    ] {
        for p in [1.0, -2.5, 0.3] {
            let phi = SpectralPhase::dispersion_peak_to_peak(&sp, p).unwrap();
            let centre = 0.5 * (lo + hi);
            assert_eq!(phi.sigma0_per_um, sp.sigma_centre_per_um());
            assert_abs_eq!(phi.at(centre), 0.0, ROUNDING_REL);
            for edge in [lo, hi] {
                assert_rel_eq!(phi.at(edge), p, ROUNDING_REL);
                assert_rel_eq!(phi.at(0.5 * (centre + edge)), 0.25 * p, ROUNDING_REL);
            }
            assert!(!phi.is_zero());
        }
    }
    let d = 7.0;
    let phi = SpectralPhase::dispersion(0.45, d);
    assert_rel_eq!(phi.at(0.45 + 0.02), 0.5 * d * 0.02 * 0.02, ROUNDING_REL);
    let line = Spectrum::monochromatic(2.2).unwrap();
    assert!(SpectralPhase::dispersion_peak_to_peak(&line, 1.0)
        .unwrap()
        .is_zero());
    let none = SpectralPhase::zero();
    assert!(none.is_zero() && none.at(0.3) == 0.0 && none.at(0.5) == 0.0);
    let max = v2ref_core::bounds::DISPERSION_PP_MAX_RAD;
    for bad in [1.5 * max, -1.5 * max, f64::NAN] {
        assert!(
            SpectralPhase::dispersion_peak_to_peak(&Spectrum::flat(band), bad).is_err(),
            "{bad}"
        );
    }
}

#[test]
fn tabulated_spectrum_interpolates_linearly_in_wavenumber() {
    let sp = Spectrum::tabulated(vec![0.40, 0.45, 0.50], vec![0.0, 2.0, 0.0]).unwrap();
    // A triangle: σ_eff at its apex, ∫W² = 2/3 / (base/2) per unit area².
    assert_rel_eq!(sp.sigma_eff_per_um(), 0.45, ROUNDING_REL);
    assert_rel_eq!(sp.weight(0.425) / sp.weight(0.45), 0.5, ROUNDING_REL);
    assert_rel_eq!(sp.w2_integral_um(), 2.0 / 3.0 / 0.05, QUADRATURE_CHECK_REL);
    assert!(Spectrum::tabulated(vec![0.4], vec![1.0]).is_err());
    assert!(Spectrum::tabulated(vec![0.4, 0.4], vec![1.0, 1.0]).is_err());
    assert!(Spectrum::tabulated(vec![0.4, 0.5], vec![1.0, -1.0]).is_err());
    assert!(Spectrum::tabulated(vec![0.4, 0.5], vec![0.0, 0.0]).is_err());
    // Wavenumbers must be finite and > 0, even in increasing order.
    for bad in [-0.1, 0.0, f64::NAN, f64::NEG_INFINITY] {
        let refused = Spectrum::tabulated(vec![bad, 0.5], vec![1.0, 1.0]);
        assert!(
            matches!(refused, Err(Error::SpectrumTable { .. })),
            "{bad}: {refused:?}"
        );
    }
    // Weights whose squares underflow leave ∫W² = 0: no V1² weighting. On
    // a narrow axis ∫w and its square underflow too (0/0); on an axis 1e9
    // wide (∫w)² = 1e-322 survives and ∫W² is exactly 0.
    for (axis, w) in [(vec![0.4, 0.5], 1e-200), (vec![1.0, 1e9], 1e-170)] {
        let tiny = Spectrum::tabulated(axis, vec![w, w]);
        assert!(matches!(tiny, Err(Error::SpectrumTable { .. })), "{tiny:?}");
    }
    // The nodes are kept as given; the analytic shapes have none.
    let (nodes, weights) = (vec![0.40, 0.45, 0.50], vec![0.0, 2.0, 0.0]);
    assert_eq!(sp.table(), Some((&nodes[..], &weights[..])));
    assert_eq!(Spectrum::flat(Band::k()).table(), None);
    // Weights must be finite and ≥ 0, even where the area stays positive.
    for bad in [-0.5, f64::NAN, f64::INFINITY] {
        let refused = Spectrum::tabulated(vec![0.4, 0.5], vec![1.0, bad]);
        assert!(
            matches!(refused, Err(Error::SpectrumTable { .. })),
            "{bad}: {refused:?}"
        );
    }
}

#[test]
fn a_band_is_its_centre_and_width() {
    // λ0 = (1/σ_min + 1/σ_max)/2 and Δλ = 1/σ_min − 1/σ_max, the edges
    // computed from the accessors' values.
    for (centre, width) in [(2.2, 0.4), (1.65, 0.3), (0.8, 1.5)] {
        let band = Band::new(centre, width).unwrap();
        assert_eq!((band.centre_um(), band.width_um()), (centre, width));
        let (long, short) = (1.0 / band.sigma_min_per_um(), 1.0 / band.sigma_max_per_um());
        assert_rel_eq!(0.5 * (long + short), band.centre_um(), ROUNDING_REL);
        assert_rel_eq!(long - short, band.width_um(), ROUNDING_REL);
    }
    let k = Band::k();
    assert_eq!((k.centre_um(), k.width_um()), (2.2, 0.4));
}

/// The bins of each window by their definition (`BinWindow`'s table):
/// positive k = 1 … ⌈N/2⌉ − 1; band the positive k with k/(N δx) in the
/// support, bounds included; all 0 … N − 1. With N = 64 and δx = 0.5 µm,
/// δσ = 1/32 µm⁻¹ and every k δσ is exact, so bounds placed on bins 14 and
/// 16 (0.4375 and 0.5 µm⁻¹) must keep both; the K band (2.0–2.4 µm, so
/// 0.41667–0.5 µm⁻¹) holds 14, 15 and 16 (13/32 = 0.40625 is below).
#[test]
fn bin_windows_hold_the_bins_of_their_definition() {
    use v2ref_core::formalism::estimator::{band_bins, positive_bins};
    assert_eq!(positive_bins(8).unwrap(), vec![1, 2, 3]);
    assert_eq!(positive_bins(7).unwrap(), vec![1, 2, 3]);
    assert_eq!(positive_bins(2).unwrap(), Vec::<usize>::new());
    assert_eq!(all_bins(4).unwrap(), vec![0, 1, 2, 3]);
    assert_eq!(
        band_bins(64, 0.5, 14.0 / 32.0, 16.0 / 32.0).unwrap(),
        vec![14, 15, 16]
    );
    assert_eq!(band_bins(64, 0.5, 0.44, 0.49).unwrap(), vec![15]);
    // Only positive bins: 32/32 (Nyquist) and above are never kept.
    assert_eq!(band_bins(64, 0.5, 0.98, 2.0).unwrap(), Vec::<usize>::new());
    let k_band = Spectrum::flat(Band::k());
    assert_eq!(
        BinWindow::Band.bins(64, 0.5, &k_band).unwrap(),
        vec![14, 15, 16]
    );
    assert_eq!(
        BinWindow::Positive.bins(64, 0.5, &k_band).unwrap(),
        (1..32).collect::<Vec<_>>()
    );
    assert_eq!(
        BinWindow::All.bins(5, 0.5, &k_band).unwrap(),
        vec![0, 1, 2, 3, 4]
    );
}

/// The band window's tie rule (`band_bins`): a bin exactly on an edge is
/// kept, whatever the rounding. Bands and spacings are decimals on a
/// 0.05 µm grid (λ0 1.0–2.5 µm, Δλ 0.1–1.0 µm, δx 0.1–1.0 µm, N 2–96),
/// where bin k lies in the band exactly when `k λ_min ≤ N δx ≤ k λ_max`,
/// compared in integers (units of 0.025 µm): every window must equal that.
/// The grid holds thousands of bins exactly on an edge; the two float
/// forms of the edge test the rule replaces, `k/(N δx)` (the conventions'
/// words) and `k · (1/(N δx))` (the former code), each disagree with the
/// exact windows on some of them, which shows the test can fail.
#[test]
fn band_windows_keep_bins_exactly_on_an_edge() {
    use v2ref_core::formalism::estimator::{band_bins, positive_bins};
    let (mut windows, mut ties, mut quotient_wrong, mut product_wrong) = (0, 0, 0, 0);
    for centre in 20..=50u64 {
        for width in 2..=20u64 {
            let band = Band::new(centre as f64 / 20.0, width as f64 / 20.0).unwrap();
            let (lo, hi) = (band.sigma_min_per_um(), band.sigma_max_per_um());
            // λ_min, λ_max and N δx in units of 0.025 µm.
            let (lambda_min, lambda_max) = (2 * centre - width, 2 * centre + width);
            for step in 2..=20u64 {
                let dx_um = step as f64 / 20.0;
                for n in 2..=96usize {
                    let scan = n as u64 * 2 * step;
                    let exact: Vec<usize> = positive_bins(n)
                        .unwrap()
                        .into_iter()
                        .filter(|&k| k as u64 * lambda_min <= scan && scan <= k as u64 * lambda_max)
                        .collect();
                    ties += positive_bins(n)
                        .unwrap()
                        .into_iter()
                        .filter(|&k| k as u64 * lambda_min == scan || scan == k as u64 * lambda_max)
                        .count();
                    let float_window = |wavenumber: &dyn Fn(usize) -> f64| {
                        positive_bins(n)
                            .unwrap()
                            .into_iter()
                            .filter(|&k| (lo..=hi).contains(&wavenumber(k)))
                            .collect::<Vec<_>>()
                    };
                    let step_per_um = 1.0 / (n as f64 * dx_um);
                    quotient_wrong +=
                        usize::from(float_window(&|k| k as f64 / (n as f64 * dx_um)) != exact);
                    product_wrong +=
                        usize::from(float_window(&|k| k as f64 * step_per_um) != exact);
                    assert_eq!(
                        band_bins(n, dx_um, lo, hi).unwrap(),
                        exact,
                        "N = {n}, δx = {dx_um} µm, band {lo}–{hi} µm⁻¹"
                    );
                    windows += 1;
                }
            }
        }
    }
    println!(
        "{windows} windows, {ties} bins on an edge; k/(N δx) wrong in {quotient_wrong}, k·(1/(N δx)) in {product_wrong}"
    );
    assert!(ties > 1000, "{ties} ties: the grid must put bins on edges");
    assert!(quotient_wrong > 0 && product_wrong > 0);
}

/// `dft_phase(i, k, N)` is the angle −2π (i k mod N)/N itself, reduced to
/// (−2π, 0] (its doc): 3 · 5 = 15 ≡ 7 (mod 8) gives −7π/4, and with
/// N = 2²⁰, (N − 1)² ≡ 1 gives −2π/N, not a multiple of turns away (the
/// reduction is what keeps the phase exact for large i k; an unreduced
/// angle is off by whole turns and gives the same cos and sin only to
/// rounding, which no DFT comparison can see).
#[test]
fn dft_phase_is_the_reduced_angle() {
    use std::f64::consts::PI;
    use v2ref_core::formalism::estimator::dft_phase;
    assert_rel_eq!(dft_phase(3, 5, 8), -7.0 * PI / 4.0, ULPS);
    assert_eq!(dft_phase(0, 5, 8), 0.0);
    assert_eq!(dft_phase(4, 2, 8), 0.0);
    let n = 1usize << 20;
    assert_rel_eq!(dft_phase(n - 1, n - 1, n), -2.0 * PI / n as f64, ULPS);
}

#[test]
fn sampling_holds_the_scan_of_its_definition() {
    // Values exact in binary: N = 128, δx = 0.5 µm, Δx = N δx = 64 µm,
    // δσ = 1/Δx = 1/64 µm⁻¹.
    let s = Sampling::new(128, 0.5, false).unwrap();
    assert_eq!((s.samples(), s.dx_um(), s.integrating()), (128, 0.5, false));
    assert_eq!((s.stroke_um(), s.delta_sigma_per_um()), (64.0, 1.0 / 64.0));
    // A stroke rounds to the nearest number of samples: 10.3/0.5 = 20.6 → 21.
    let t = Sampling::from_stroke(10.3, 0.5, true).unwrap();
    assert_eq!(
        (t.samples(), t.stroke_um(), t.integrating()),
        (21, 10.5, true)
    );
    // DFT order, centred: non-negative OPDs first, then the negative ones.
    let opd = |n: usize| {
        let s = Sampling::new(n, 0.5, false).unwrap();
        (0..n).map(|i| s.opd_um(i)).collect::<Vec<_>>()
    };
    assert_eq!(opd(4), [0.0, 0.5, -1.0, -0.5]);
    assert_eq!(opd(5), [0.0, 0.5, 1.0, -1.0, -0.5]);
    // Refusals name the parameter.
    let param = |r: v2ref_core::Result<Sampling>| r.unwrap_err().param();
    let param = |r| param(r).unwrap();
    assert_eq!(param(Sampling::new(1, 0.5, false)), "samples");
    assert_eq!(param(Sampling::new(4, 0.0, false)), "dx_um");
    assert_eq!(param(Sampling::from_stroke(0.7, 0.5, false)), "stroke_um");
    assert!(Sampling::from_stroke(1.0, 0.5, false).is_ok()); // exactly 2 samples
                                                             // Aliasing: the K band (2.0–2.4 µm) reaches σ_max = 1/2.0 µm⁻¹, so δx
                                                             // must stay below 0.5/σ_max = 1 µm.
    let obs = Observation::new(
        Spectrum::flat(Band::k()),
        Source::Point,
        Frequency::BaselineM(10.0),
        SpectralPhase::zero(),
    )
    .unwrap();
    assert!(Sampling::new(64, 0.999, false)
        .unwrap()
        .check_aliasing(&obs)
        .is_ok());
    assert!(matches!(
        Sampling::new(64, 1.0, false).unwrap().check_aliasing(&obs),
        Err(Error::Aliasing { .. })
    ));
}

#[test]
fn sinc_is_one_at_zero_and_its_definition_near_zero() {
    // sin(πu)/(πu) from mpmath (sinpi, 40 digits), on both sides of the
    // switch to the Taylor series at |u| = 1e-4, to ULPS: the series is
    // exact to rounding there ((πu)⁶/5040 < 2e-22), and its (πu)⁴/120 term,
    // 8e-17 at the switch, matters at this tolerance only through a gross
    // error (taking (πu)⁴ for it moves sinc(9.9e-5) by 9e-15).
    let reference = [
        (1e-12, "1.0"),
        (1e-8, "0.99999999999999983551"),
        (1e-5, "0.99999999983550659332"),
        (9.9e-5, "0.9999999838780012888"),
        (1.01e-4, "0.99999998322002766855"),
        (0.3, "0.85839369133413977501"),
        (2.5, "0.12732395447351626862"),
    ];
    assert_eq!(sinc(0.0), 1.0);
    for (u, want) in reference {
        let want: f64 = want.parse().unwrap();
        assert_rel_eq!(sinc(u), want, ULPS, "sinc({u})");
        assert_eq!(sinc(-u), sinc(u), "sinc is even");
    }
}

#[test]
fn mean_counts_are_continuum_plus_modulation() {
    // n_i = c_i + m_i, sample by sample (exact in binary).
    let ifg = Interferogram {
        continuum: vec![10.0, 10.0, 10.0],
        modulated: vec![2.5, -4.0, 0.0],
    };
    assert_eq!(ifg.mean_counts(), [12.5, 6.0, 10.0]);
}

/// The words of each choice of the library (`crates/v2ref-core/src/words.rs`).
mod words {
    use v2ref_commands::parameters::SourceKind;
    use v2ref_core::conformance::estimate::BiasConvention;
    use v2ref_core::formalism::estimator::BinWindow;
    use v2ref_core::noise::Formula;
    use v2ref_core::piston::spectrum::PistonPsdModel;
    use v2ref_core::piston::PistonReference;
    use v2ref_core::simulator::RowLayout;
    use v2ref_core::words::Words;

    /// Each word is its value's serde name (what JSON writes), once, and
    /// names that value back; a word not listed is refused naming the
    /// parameter and the words.
    fn check<T: Words + serde::Serialize + std::fmt::Debug>() {
        let mut seen = Vec::new();
        for w in T::WORDS {
            assert_eq!(serde_json::to_value(w.value).unwrap(), w.word, "{w:?}");
            assert_eq!(w.value.word(), w.word);
            assert_eq!(T::from_word("p", w.word).unwrap(), w.value);
            assert!(!w.help.is_empty() && !seen.contains(&w.word), "{w:?}");
            seen.push(w.word);
        }
        let e = T::from_word("p", "nope").unwrap_err().to_string();
        assert!(
            e.contains(&format!("'nope' is not one of: {}", T::listed(", "))),
            "{e}"
        );
    }

    #[test]
    fn words_are_the_serde_names() {
        check::<BinWindow>();
        check::<BiasConvention>();
        check::<Formula>();
        check::<SourceKind>();
        check::<PistonReference>();
        check::<PistonPsdModel>();
        check::<RowLayout>();
        check::<v2ref_commands::plan::photometry::Band2Mass>();
        assert_eq!(BinWindow::listed(", "), "positive, band, all");
        assert_eq!(RowLayout::listed(" or "), "sequences or observation");
    }
}
