//! Robustness of the library's public entry points: fed extreme finite
//! values (zeros, subnormals, the largest and smallest normal numbers,
//! random magnitudes over the whole exponent range, both signs), each
//! returns a finite answer or a typed error naming a parameter, never a
//! panic, a NaN or an infinity.
//!
//! The one documented exception is an SNR whose variance is exactly zero
//! (no noise): infinite or undefined by definition, written in words by the
//! front ends (`v2ref_core::noise::snr_value`); the test checks that it occurs
//! only then.

use proptest::prelude::*;
use v2ref_core::formalism::estimator::{sampled_wide_band, wide_band, BinWindow};
use v2ref_core::formalism::interferogram::Sampling;
use v2ref_core::formalism::observation::{Frequency, Observation};
use v2ref_core::formalism::phase::SpectralPhase;
use v2ref_core::formalism::source::Source;
use v2ref_core::formalism::spectrum::{Band, Spectrum};
use v2ref_core::noise::calibrated::CalibratedSetup;
use v2ref_core::noise::{appendix_stats, Formula, NoiseModel};
use v2ref_core::piston::turbulence::{r0_from_seeing_m, Turbulence};
use v2ref_core::Error;

/// Extreme finite values of either sign, and ordinary ones.
fn extreme() -> impl Strategy<Value = f64> {
    let magnitude = prop_oneof![
        Just(0.0),
        Just(f64::MIN_POSITIVE),
        Just(5e-324),
        Just(f64::MAX),
        Just(1e308),
        Just(1e-300),
        Just(1.0),
        (-320.0..308.0_f64).prop_map(|e| 10f64.powf(e)),
        (0.01..1e4_f64),
    ];
    (magnitude, any::<bool>()).prop_map(|(m, negative)| if negative { -m } else { m })
}

/// Mostly positive extreme values (most physical inputs are magnitudes).
fn extreme_positive() -> impl Strategy<Value = f64> {
    prop_oneof![3 => extreme().prop_map(f64::abs), 1 => extreme()]
}

/// An error must name the library parameter it refuses and be one line.
fn check_error(e: &Error) {
    assert!(e.param().is_some(), "error names no parameter: {e}");
    assert!(!e.to_string().contains('\n'), "not one line: {e}");
}

fn check_finite(what: &str, values: &[f64]) {
    for (i, v) in values.iter().enumerate() {
        assert!(v.is_finite(), "{what}[{i}] = {v}");
    }
}

/// The observation of the flags' model, or the error (checked).
fn observation(
    wavelength_um: f64,
    bandwidth_um: f64,
    diameter_mas: f64,
    baseline_m: f64,
    dispersion_rad: f64,
) -> Option<Observation> {
    let built = Band::new(wavelength_um, bandwidth_um).and_then(|band| {
        let spectrum = Spectrum::flat(band);
        let phase = SpectralPhase::dispersion_peak_to_peak(&spectrum, dispersion_rad)?;
        let source = Source::uniform_disk(diameter_mas)?;
        Observation::new(spectrum, source, Frequency::BaselineM(baseline_m), phase)
    });
    match built {
        Ok(obs) => Some(obs),
        Err(e) => {
            check_error(&e);
            None
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    #[test]
    fn infinite_scan_estimators_are_finite_or_refused(
        wavelength_um in extreme_positive(),
        bandwidth_fraction in extreme_positive(),
        diameter_mas in extreme_positive(),
        baseline_m in extreme_positive(),
        dispersion_rad in extreme(),
    ) {
        let bandwidth_um = wavelength_um * bandwidth_fraction;
        if let Some(obs) = observation(wavelength_um, bandwidth_um, diameter_mas, baseline_m, dispersion_rad) {
            let wb = wide_band(&obs);
            check_finite("wide_band", &[wb.v_mono, wb.v1, wb.v2, wb.v1_sq, wb.v2_sq, wb.spatial_freq_cpas, wb.sigma_eff_per_um, obs.baseline_m]);
        }
    }

    #[test]
    fn finite_scan_estimators_are_finite_or_refused(
        samples in prop_oneof![Just(0usize), Just(1), Just(2), Just(3), 4usize..64, Just(usize::MAX)],
        dx_um in extreme(),
        stroke_um in extreme(),
        use_stroke in any::<bool>(),
        diameter_mas in extreme_positive(),
    ) {
        let Some(obs) = observation(2.2, 0.4, diameter_mas, 18.0, 0.0) else { return Ok(()) };
        let sampling = if use_stroke {
            Sampling::from_stroke(stroke_um, dx_um, false)
        } else {
            Sampling::new(samples, dx_um, false)
        };
        let sampling = match sampling {
            Ok(s) if s.samples() <= 4096 => s,
            Ok(_) => return Ok(()),
            Err(e) => { check_error(&e); return Ok(()) }
        };
        for window in [BinWindow::Positive, BinWindow::Band, BinWindow::All] {
            match sampled_wide_band(&obs, &sampling, window) {
                Ok(p) => check_finite("sampled_wide_band", &[p.v1_sq, p.v2_sq]),
                Err(e) => check_error(&e),
            }
        }
    }

    #[test]
    fn closed_form_noise_is_finite_or_refused(
        photons in extreme(),
        visibility in extreme(),
        read_noise in extreme(),
        photon_noise in any::<bool>(),
        samples in 3usize..64,
    ) {
        let Some(obs) = observation(2.2, 0.4, 1.0, 18.0, 0.0) else { return Ok(()) };
        let Ok(sampling) = Sampling::new(samples, 0.5, false) else { return Ok(()) };
        let noise = match NoiseModel::new(read_noise, photon_noise) {
            Ok(n) => n,
            Err(e) => { check_error(&e); return Ok(()) }
        };
        let setup = match CalibratedSetup::new(&obs, &sampling, photons, visibility, BinWindow::Positive) {
            Ok(s) => s,
            Err(e) => { check_error(&e); return Ok(()) }
        };
        let ifg = &setup.signal;
        check_finite("modulated", &ifg.modulated);
        check_finite("continuum", &ifg.continuum);
        for formula in [Formula::Published, Formula::Exact] {
            match appendix_stats(&ifg.modulated, &ifg.continuum, &noise, formula) {
                Ok(st) => {
                    check_finite("appendix_stats", &[st.sum_m2, st.m0, st.bias_v1_sq, st.bias_v2_sq, st.var_v1_sq, st.var_v2_sq]);
                    // An SNR may be non-finite only without noise (var = 0).
                    for (snr, var) in [(st.snr1, st.var_v1_sq), (st.snr2, st.var_v2_sq)] {
                        prop_assert!(snr.is_finite() || var == 0.0, "SNR {snr} with variance {var}");
                    }
                }
                Err(e) => check_error(&e),
            }
        }
    }

    #[test]
    fn turbulence_is_finite_or_refused(
        seeing_arcsec in extreme(),
        wavelength_um in extreme_positive(),
        wind_mps in extreme_positive(),
        outer_scale_m in prop::option::of(extreme_positive()),
    ) {
        let r0 = match r0_from_seeing_m(seeing_arcsec, wavelength_um) {
            Ok(r0) => r0,
            Err(e) => { check_error(&e); return Ok(()) }
        };
        // r0 = +inf stands for no turbulence (zero seeing, or seeing so
        // small that λ/seeing overflows: the same limit); never 0 or NaN.
        prop_assert!(r0 > 0.0, "r0 = {r0}");
        if let Err(e) = Turbulence::new(r0, wavelength_um, wind_mps, outer_scale_m) {
            check_error(&e);
        }
    }

    #[test]
    fn tabulated_spectra_are_usable_or_refused(
        first in extreme_positive(),
        step in extreme_positive(),
        weights in prop::collection::vec(extreme(), 2..6),
    ) {
        let sigma: Vec<f64> = (0..weights.len()).map(|i| first + step * i as f64).collect();
        match Spectrum::tabulated(sigma, weights) {
            Ok(sp) => check_finite("tabulated", &[sp.sigma_eff_per_um(), sp.width_per_um(), sp.sigma_centre_per_um()]),
            Err(e) => check_error(&e),
        }
    }

    #[test]
    fn spectrum_csv_text_is_usable_or_refused(
        a in extreme(),
        b in extreme(),
        w in extreme(),
        bom in any::<bool>(),
        wavelength_axis in any::<bool>(),
    ) {
        let header = if wavelength_axis { "wavelength_um,weight" } else { "wavenumber_per_um,weight" };
        let text = format!("{}{header}\n{a:e},{w:e}\n{b:e},1\n", if bom { "\u{feff}" } else { "" });
        match Spectrum::from_csv_str(&text) {
            Ok(sp) => check_finite("from_csv_str", &[sp.sigma_eff_per_um(), sp.width_per_um()]),
            Err(e) => check_error(&e),
        }
    }
}

#[test]
fn a_byte_order_mark_is_not_part_of_the_header() {
    let plain = Spectrum::from_csv_str("wavelength_um,weight\n2.0,1\n2.4,1\n").unwrap();
    let bom = Spectrum::from_csv_str("\u{feff}wavelength_um,weight\n2.0,1\n2.4,1\n").unwrap();
    assert_eq!(plain.sigma_eff_per_um(), bom.sigma_eff_per_um());
}

#[test]
fn the_bounds_are_where_the_refusals_start() {
    use v2ref_core::bounds::*;
    // Inside: answered; just outside: refused naming the parameter.
    assert!(Band::new(WAVELENGTH_MAX_UM, 1.0).is_ok());
    assert_eq!(
        Band::new(WAVELENGTH_MAX_UM * 1.01, 1.0)
            .unwrap_err()
            .param(),
        Some("wavelength_um")
    );
    assert!(Band::new(WAVELENGTH_MIN_UM, WAVELENGTH_MIN_UM / 10.0).is_ok());
    assert_eq!(
        Band::new(WAVELENGTH_MIN_UM * 0.99, 1e-5)
            .unwrap_err()
            .param(),
        Some("wavelength_um")
    );
    assert!(Source::uniform_disk(DIAMETER_MAX_MAS).is_ok());
    assert_eq!(
        Source::uniform_disk(DIAMETER_MAX_MAS * 1.01)
            .unwrap_err()
            .param(),
        Some("diameter_mas")
    );
    assert!(NoiseModel::new(PHOTONS_MAX, true).is_ok());
    assert_eq!(
        NoiseModel::new(PHOTONS_MAX * 1.01, true)
            .unwrap_err()
            .param(),
        Some("read_noise")
    );
    let spectrum = Spectrum::flat(Band::new(2.2, 0.4).unwrap());
    assert!(SpectralPhase::dispersion_peak_to_peak(&spectrum, -DISPERSION_PP_MAX_RAD).is_ok());
    assert_eq!(
        SpectralPhase::dispersion_peak_to_peak(&spectrum, DISPERSION_PP_MAX_RAD * 1.01)
            .unwrap_err()
            .param(),
        Some("peak_to_peak_rad")
    );
    assert!(Turbulence::new(0.1, 2.2, WIND_MAX_MPS, None).is_ok());
    assert_eq!(
        Turbulence::new(0.1, 2.2, WIND_MAX_MPS * 1.01, None)
            .unwrap_err()
            .param(),
        Some("wind_mps")
    );
}

#[test]
fn v2_at_the_dispersion_bound_still_follows_the_fresnel_law() {
    // For a flat band and large peak-to-peak P, |V2| of a point source falls
    // as 1/sqrt(P) (stationary phase of the quadratic phase); the bound is
    // where the quadrature still resolves it: a 4x larger P gives half V2.
    let spectrum = Spectrum::flat(Band::new(2.2, 0.4).unwrap());
    let v2 = |p: f64| {
        let phase = SpectralPhase::dispersion_peak_to_peak(&spectrum, p).unwrap();
        let obs = Observation::new(
            spectrum.clone(),
            Source::Point,
            Frequency::BaselineM(18.0),
            phase,
        )
        .unwrap();
        wide_band(&obs).v2
    };
    let bound = v2ref_core::bounds::DISPERSION_PP_MAX_RAD;
    let ratio = v2(bound / 4.0) / v2(bound);
    // A leading-order law (edge terms of relative order 1/sqrt P); a
    // quadrature that no longer resolves the phase is off by 20 % or more.
    v2ref_core::assert_rel_eq!(ratio, 2.0, v2ref_core::tolerance::SCALING_LAW_REL);
}
