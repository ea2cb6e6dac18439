//! Every public function of the stable surface (the facade `v2ref`, listed
//! in crates/v2ref/public-api/default.txt; a path the prelude or `oracle`
//! re-exports is driven once, under its home module) driven with arbitrary
//! inputs — NaN, ±∞, negative and zero values, counts up to 2^64 − 1, empty
//! and mismatched slices — and held to issue 45's rule: a typed error in
//! the library's own words, or finite numbers, or a panic where the function
//! documents it (`# Panics`). A count the function could check never
//! allocates or loops without bound: the huge counts below would abort or
//! hang the test if it did. (`tests/public_misuse.rs` holds the cases a
//! pipeline's crate met, one by one; `surface_properties_sets.rs` the
//! piston, the simulator, the conformance kit, the oracle and the Monte
//! Carlo's statistics.)
//!
//! Scalar closed forms of one real (`sinc`, `jinc`, a PSD at a frequency)
//! follow `f64::sin`: NaN in, NaN out; every finite input gives a finite
//! value.

use proptest::prelude::*;
use std::sync::OnceLock;
use v2ref::formalism::estimator::{self as est, Pair};
use v2ref::formalism::interferogram::{sinc, Interferogram, Sampling, SpectralNodes};
use v2ref::formalism::observation::{Frequency, Observation};
use v2ref::formalism::phase::SpectralPhase;
use v2ref::formalism::source::{Component, FluxProfile, Source};
use v2ref::formalism::spectrum::{Band, Spectrum};
use v2ref::Error;

pub(crate) const CASES: u32 = 24;

/// A scan's most samples, the bound of the bins' lists (`MAX_BINS`, 2^24).
const MAX_BINS: usize = 1 << 24;

/// `prop_assert!` of a condition whose text holds braces.
/// `cases` cases drawn from a fixed seed: the same inputs on every run
/// (a property test that fails does so every time, never by chance).
pub fn fixed_seed(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x5eed_2026_1128),
        ..ProptestConfig::default()
    }
}

macro_rules! hold {
    ($e:expr) => {{
        let ok: bool = $e;
        prop_assert!(ok);
    }};
}

/// Any f64, the awkward ones often.
pub(crate) fn any_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(0.0),
        Just(-0.0),
        Just(-1.0),
        Just(f64::MAX),
        Just(f64::MIN_POSITIVE),
        -1e3..1e3f64,
        prop::num::f64::ANY,
    ]
}

/// Any count, huge ones often.
pub(crate) fn any_count() -> impl Strategy<Value = usize> {
    prop_oneof![
        Just(0usize),
        Just(1),
        Just(1 << 40),
        Just(usize::MAX),
        0usize..64,
        any::<usize>()
    ]
}

pub(crate) fn any_u64() -> impl Strategy<Value = u64> {
    any_count().prop_map(|n| n as u64)
}

/// A refusal in the library's words: it names a parameter (or its data)
/// and no command-line flag.
pub(crate) fn in_words(e: &Error) -> bool {
    let text = e.to_string();
    !text.is_empty() && !text.contains("--")
}

pub(crate) fn finite(xs: impl IntoIterator<Item = f64>) -> bool {
    xs.into_iter().all(f64::is_finite)
}

/// Ok with finite values, or a typed error in the library's words.
pub(crate) fn held<T>(r: Result<T, Error>, values: impl Fn(&T) -> Vec<f64>) -> bool {
    match r {
        Ok(v) => finite(values(&v)),
        Err(e) => in_words(&e),
    }
}

pub(crate) fn obs() -> &'static Observation {
    static OBS: OnceLock<Observation> = OnceLock::new();
    OBS.get_or_init(|| {
        Observation::new(
            Spectrum::flat(Band::k()),
            Source::uniform_disk(2.0).unwrap(),
            Frequency::BaselineM(30.0),
            SpectralPhase::zero(),
        )
        .unwrap()
    })
}

fn sampling() -> Sampling {
    Sampling::new(64, 0.3, true).unwrap()
}

// ---- formalism -----------------------------------------------------------

proptest! {
    #![proptest_config(crate::surface_properties::fixed_seed(CASES))]

    #[test]
    fn dynamic_range_is_finite_or_refused(n in any_f64(), dv in any_f64(), dphi in any_f64()) {
        let r = v2ref::formalism::dynamic_range::dynamic_range(n, dv, dphi);
        hold!(held(r, |x| vec![*x]));
    }

    #[test]
    fn a_band_and_its_spectra_are_finite_or_refused(
        centre in any_f64(), width in any_f64(), index in any_f64(), edge in any_f64(),
        sigma in any_f64(), extra in prop::collection::vec(any_f64(), 0..4),
    ) {
        let k = Band::k();
        prop_assert!(finite([k.centre_um(), k.width_um(), k.sigma_min_per_um(), k.sigma_max_per_um()]));
        let band = Band::new(centre, width);
        hold!(held(band.clone(), |b| vec![b.centre_um(), b.width_um(), b.sigma_min_per_um(), b.sigma_max_per_um()]));
        let band = band.unwrap_or(k);
        let spectra = [
            Ok(Spectrum::flat(band)),
            Spectrum::monochromatic(centre),
            Spectrum::power_law(band, index),
            Spectrum::smooth_top_hat(band, edge),
        ];
        for s in spectra {
            hold!(held(s.clone(), |s| spectrum_values(s, sigma, &extra)));
        }
    }

    #[test]
    fn a_tabulated_spectrum_is_finite_or_refused(
        sigma in prop::collection::vec(any_f64(), 0..6),
        weight in prop::collection::vec(any_f64(), 0..6),
        at in any_f64(),
    ) {
        let s = Spectrum::tabulated(sigma.clone(), weight.clone());
        hold!(held(s, |s| spectrum_values(s, at, &[])));
        let csv: String = sigma.iter().zip(&weight).map(|(a, b)| format!("{a},{b}\n")).collect();
        hold!(held(Spectrum::from_csv_str(&csv), |s| spectrum_values(s, at, &[])));
    }

    #[test]
    fn any_text_is_a_spectrum_or_refused(text in ".{0,80}") {
        hold!(held(Spectrum::from_csv_str(&text), |s| spectrum_values(s, 0.45, &[])));
    }

    #[test]
    fn a_source_and_its_visibility_are_finite_or_refused(
        d in any_f64(), wl in any_f64(), fwhm in any_f64(), flux in any_f64(),
        sigma in -10.0..10.0f64, baseline in -1e3..1e3f64, at in any_f64(),
    ) {
        let vis = |s: &Source| {
            let v = s.visibility(sigma, baseline);
            let mut out = vec![v.re, v.im];
            out.extend(s.features_per_um());
            out
        };
        hold!(held(Source::uniform_disk(d), vis));
        let line = FluxProfile::gaussian_line_velocity(wl, fwhm, flux);
        hold!(held(line.clone(), |f| if at.is_finite() { vec![f.at(at)] } else { vec![] }));
        if let Ok(flux) = line {
            let c = vec![Component { source: Source::Point, flux }];
            hold!(held(Source::composite(c), vis));
        }
        prop_assert!(Source::composite(vec![]).is_err());
    }

    #[test]
    fn a_phase_and_an_observation_are_finite_or_refused(
        s0 in any_f64(), d in any_f64(), pp in any_f64(), freq in any_f64(), base in any_f64(),
        sigma in 0.0..10.0f64,
    ) {
        let p = SpectralPhase::dispersion(s0, d);
        // tol: not a tolerance: the inputs whose phase (quadratic in them) cannot overflow.
        if s0.is_finite() && d.is_finite() && d.abs() < 1e100 && s0.abs() < 1e100 {
            prop_assert!(p.at(sigma).is_finite());
        }
        let _ = SpectralPhase::zero().is_zero();
        let phase = SpectralPhase::dispersion_peak_to_peak(&Spectrum::flat(Band::k()), pp);
        hold!(held(phase.clone(), |p| vec![p.at(sigma)]));
        for f in [Frequency::SpatialFreqCpas(freq), Frequency::BaselineM(base)] {
            let o = Observation::new(Spectrum::flat(Band::k()), Source::Point, f, phase.clone().unwrap_or(SpectralPhase::zero()));
            hold!(held(o, |o| {
                let a = o.fringe_amplitude(sigma);
                vec![o.spatial_freq_cpas(), a.re, a.im, o.calibrator().spatial_freq_cpas()]
            }));
        }
    }

    #[test]
    fn a_sampling_is_finite_or_refused(n in any_count(), dx in any_f64(), stroke in any_f64(), i in any_count()) {
        for s in [Sampling::new(n, dx, true), Sampling::from_stroke(stroke, dx, false)] {
            hold!(held(s, |s| {
                let _ = (s.samples(), s.integrating(), s.check_aliasing(obs()).map_err(|e| assert!(in_words(&e))));
                let opd = std::panic::catch_unwind(|| s.opd_um(i));
                assert_eq!(opd.is_ok(), i < s.samples(), "opd_um panics past the scan, as documented");
                vec![s.dx_um(), s.stroke_um(), s.delta_sigma_per_um(), opd.unwrap_or(0.0)]
            }));
        }
    }

    #[test]
    fn sinc_is_finite_at_every_finite_argument(u in any_f64()) {
        prop_assert!(!u.is_finite() || sinc(u).is_finite());
    }

    /// The spectral nodes of any scan length: as many as a scan can need,
    /// or a typed error — never terabytes.
    #[test]
    fn spectral_nodes_are_bounded(max_opd in any_f64(), dx in prop::option::of(any_f64()), x in -1e3..1e3f64) {
        let count = SpectralNodes::count(obs(), max_opd);
        let nodes = SpectralNodes::new(obs(), max_opd, dx);
        hold!(held(nodes, |n| {
            assert!(n.sigma_per_um.len() <= count);
            let mut v = n.sigma_per_um.clone();
            v.push(n.fringe(x));
            v
        }));
    }

    #[test]
    fn an_interferogram_is_finite_or_refused(
        photons in any_f64(), n in 2usize..40, dx in 0.05..2.0f64,
        perturbation in prop::option::of(prop::collection::vec(any_f64(), 0..42)),
    ) {
        let s = Sampling::new(n, dx, true).unwrap();
        let i = Interferogram::synthesize(obs(), &s, photons, perturbation.as_deref());
        hold!(held(i, |i| {
            assert_eq!(i.modulated.len(), n);
            [i.modulated.clone(), i.continuum.clone(), i.mean_counts()].concat()
        }));
    }

    #[test]
    fn the_estimators_are_finite_or_refused(window in prop::sample::select(est::BIN_WINDOWS.to_vec()), n in 2usize..40, dx in 0.05..2.0f64) {
        let wb = est::wide_band(obs());
        prop_assert!(finite([est::v1_sq(obs()), est::v2_sq(obs()), wb.v1_sq, wb.v2_sq, wb.v_mono]));
        let s = Sampling::new(n, dx, false).unwrap();
        hold!(held(est::sampled_wide_band(obs(), &s, window), |p| vec![p.v1_sq, p.v2_sq]));
        let _ = window.name();
    }

    /// Bins of any count: the list, or the documented panic past a scan's
    /// most samples (before anything is allocated).
    #[test]
    fn bins_of_any_count_are_listed_or_panic_as_documented(
        n in any_count(), dx in any_f64(), lo in any_f64(), hi in any_f64(),
        window in prop::sample::select(est::BIN_WINDOWS.to_vec()),
    ) {
        let small = n <= MAX_BINS;
        let lists = std::panic::catch_unwind(|| {
            [est::positive_bins(n).unwrap(), est::all_bins(n).unwrap(), est::band_bins(n, dx, lo, hi).unwrap(), window.bins(n, dx, &Spectrum::flat(Band::k())).unwrap()]
        });
        match lists {
            Ok(l) => prop_assert!(small && l.iter().all(|b| b.iter().all(|&k| k < n))),
            Err(_) => prop_assert!(!small),
        }
    }

    /// The DFT and the raw estimators of any samples: finite for samples
    /// whose squares do not overflow; bins past the spectrum panic as
    /// documented (a slice shorter than stated).
    #[test]
    fn the_dft_and_the_raw_estimators_are_finite(
        m in prop::collection::vec(-1e100..1e100f64, 0..24),
        bins in prop::collection::vec(0usize..30, 0..6),
        variance in prop::collection::vec(0.0..1e6f64, 0..24),
    ) {
        let b = est::dft(&m);
        let naive = v2ref::formalism::oracle::naive_dft(&m);
        prop_assert_eq!(b.len(), m.len());
        prop_assert!(finite(b.iter().chain(&naive).flat_map(|c| [c.re, c.im])));
        let raw = std::panic::catch_unwind(|| est::raw_estimates(&b, &bins).unwrap());
        let bias = std::panic::catch_unwind(|| est::noise_bias(&variance, &bins).unwrap());
        match raw {
            Ok(p) => prop_assert!(finite([p.v1_sq, p.v2_sq]) && bins.iter().all(|&k| k < m.len())),
            Err(_) => prop_assert!(bins.iter().any(|&k| k >= m.len())),
        }
        if let Ok(p) = bias {
            prop_assert!(finite([p.v1_sq, p.v2_sq]));
        }
    }
}

fn spectrum_values(s: &Spectrum, sigma: f64, extra: &[f64]) -> Vec<f64> {
    let (lo, hi) = s.support();
    let mut v = vec![
        lo,
        hi,
        s.sigma_centre_per_um(),
        s.width_per_um(),
        s.sigma_eff_per_um(),
    ];
    if !s.is_monochromatic() {
        v.extend([s.w2_integral_um(), s.mean_w(|_| 1.0), s.mean_w2(|x| x)]);
        v.extend([s.mean_w_split(|x| x, &[]), s.mean_w2_split(|_| 1.0, &[])]);
    }
    if sigma.is_finite() {
        v.extend([s.raw_weight(sigma), s.weight(sigma)]);
    }
    if let Some((a, b)) = s.table() {
        v.extend(a.iter().chain(b));
    }
    let finite_extra: Vec<f64> = extra.iter().copied().filter(|x| x.is_finite()).collect();
    v.extend(s.pieces(&finite_extra));
    if let Err(e) = s.grid_sums(sigma).map(|(a, b)| v.extend([a, b])) {
        assert!(in_words(&e));
    }
    v
}

// ---- math ------------------------------------------------------------------

proptest! {
    #![proptest_config(crate::surface_properties::fixed_seed(CASES))]

    /// Any bounds and tolerance: a finite integral of a finite integrand,
    /// in a bounded number of panels (the test would hang otherwise).
    #[test]
    fn an_integral_is_finite(a in -1e3..1e3f64, b in -1e3..1e3f64, abs in any_f64(), rel in any_f64()) {
        use v2ref::math::quadrature::{integrate, Tolerance};
        let value = integrate(|x: f64| (3.0 * x).sin() / (1.0 + x * x), a, b, Tolerance { abs, rel });
        prop_assert!(value.is_finite());
    }

    #[test]
    fn special_functions_are_finite(z in any_f64(), s in any::<u32>()) {
        use v2ref::math::special::{bessel_j1_zero, jinc, point_source_v2_sq};
        prop_assert!(!z.is_finite() || (jinc(z).is_finite() && point_source_v2_sq(z).is_finite()));
        let zero = std::panic::catch_unwind(|| bessel_j1_zero(s));
        prop_assert!(zero.map_or(true, |x| x.is_finite() && (s == 0 || x > 0.0)));
    }
}

// ---- bias ------------------------------------------------------------------

proptest! {
    #![proptest_config(crate::surface_properties::fixed_seed(CASES))]

    #[test]
    fn the_bandwidth_curve_is_finite_or_refused(grid in prop::collection::vec(any_f64(), 0..4)) {
        let c = v2ref::bias::bandwidth::curve(&Spectrum::flat(Band::k()), &Source::Point, &SpectralPhase::zero(), &grid);
        hold!(held(c, |c| c.iter().flat_map(|w| [w.v1_sq, w.v2_sq, w.v_mono]).collect()));
    }

    #[test]
    fn dispersion_is_finite_or_refused(s in any_f64(), lo in any_f64(), hi in any_f64(), len in any_f64()) {
        use v2ref::bias::dispersion::*;
        hold!(held(dispersion_coefficient(zblan_index, s, len), |d| vec![*d]));
        hold!(held(zblan_peak_to_peak_rad(lo, hi, len), |d| vec![*d]));
        hold!(held(residual_peak_to_peak(zblan_index, lo, hi, len), |d| vec![*d]));
        let _ = zblan_index(s);
    }

    #[test]
    fn the_finite_scan_bias_is_finite_or_refused(
        u in any_f64(), n in any_count(), bins in prop::collection::vec(0usize..80, 0..4),
        c1 in any_f64(), c2 in any_f64(), kernel in prop::sample::select(vec![v2ref::bias::finite_scan::Kernel::Dirichlet, v2ref::bias::finite_scan::Kernel::Sinc]),
    ) {
        use v2ref::bias::finite_scan::*;
        // tol: not a tolerance: the bin offsets a scan of n samples can have.
        if u.is_finite() && u.abs() < 1e12 && (1..=1 << 24).contains(&n) {
            let k = kernel.at(u, n);
            prop_assert!(finite([k.re, k.im]));
        }
        let s = Sampling::new(16, 0.3, true).unwrap();
        let conv = convolution_bins(obs(), &s, &bins, kernel);
        hold!(held(conv, |c| c.iter().flat_map(|z| [z.re, z.im]).collect()));
        let calibrator = Some(Pair { v1_sq: c1, v2_sq: c2 });
        for method in [Method::Dft, Method::Convolution(kernel)] {
            hold!(held(finite_scan_bias(obs(), &s, method, calibrator), |b| vec![b.v1, b.v2]));
        }
    }

    #[test]
    fn the_integrating_detector_is_finite_or_refused(p in 2.0..1e6f64, dx in any_f64()) {
        use v2ref::bias::integration::*;
        prop_assert!(finite([monochromatic_contrast(p), monochromatic_norm_factor(p)]));
        hold!(held(calibrated(obs(), dx), |c| vec![c.v1_sq, c.v2_sq]));
        hold!(held(calibrated_bias(obs(), dx), |b| vec![b.v1, b.v2]));
        hold!(held(wide_band_loss(obs(), dx), |c| vec![c.v1_sq, c.v2_sq]));
    }

    #[test]
    fn a_line_case_is_finite_or_refused(vc in any_f64(), vl in any_f64(), r in any_f64(), w in any_f64(), off in any_f64()) {
        use v2ref::bias::line::*;
        let case = LineCase { continuum_visibility: vc, line_visibility: vl, flux_ratio: r, width_elements: w, offset_elements: off, ..LineCase::paper() };
        let both = |c: &ChannelVisibility| vec![c.unweighted, c.flux_weighted];
        hold!(held(channel_visibility(&case), both));
        hold!(held(top_hat_closed_form(&case), both));
    }

    #[test]
    fn the_normalization_curve_is_finite_or_refused(dx in any_f64(), samples in prop::collection::vec(any_count(), 0..3)) {
        let c = v2ref::bias::normalization::deviation_curve(&Spectrum::flat(Band::k()), dx, &samples);
        hold!(held(c, |c| c.clone()));
    }
}

// ---- noise -----------------------------------------------------------------

proptest! {
    #![proptest_config(crate::surface_properties::fixed_seed(CASES))]

    #[test]
    fn a_noise_model_and_its_moments_are_finite_or_refused(sigma in any_f64(), photon in any::<bool>(), m in -1e6..1e6f64, n in any_f64()) {
        use v2ref::noise::*;
        hold!(held(NoiseModel::detector(sigma), |_| vec![]));
        let model = NoiseModel::new(sigma, photon);
        hold!(held(model, |model| {
            let c = model.cumulants(n);
            let mo = moments(model, m, n);
            assert_eq!(c.is_err(), mo.is_err());
            match (c, mo) {
                (Ok(c), Ok(mo)) => [vec![c.k2, c.k3, c.k4], mo.raw.to_vec(), mo.central.to_vec()].concat(),
                (Err(e), _) => { assert!(in_words(&e) && ((model.photon && !(0.0..=1e12).contains(&n)) || m.abs() > 1e12)); vec![] }
                _ => vec![],
            }
        }));
        let _ = NoiseModel::photon();
    }

    #[test]
    fn the_appendix_and_the_window_variance_are_finite_or_refused(
        m in prop::collection::vec(-1e3..1e3f64, 0..12), counts in prop::collection::vec(any_f64(), 0..12),
        bins in prop::collection::vec(0usize..14, 0..4), formula in prop::sample::select(vec![v2ref::noise::Formula::Published, v2ref::noise::Formula::Exact]),
    ) {
        use v2ref::noise::*;
        let noise = NoiseModel::new(1.5, true).unwrap();
        let a = appendix_stats(&m, &counts, &noise, formula);
        hold!(held(a, |a| vec![a.var_v1_sq, a.var_v2_sq, a.bias_v1_sq, a.bias_v2_sq, a.signal_v1_sq, a.signal_v2_sq]));
        let w = v2ref::noise::window_variance::window_stats(&m, &counts, &noise, &bins);
        hold!(held(w, |w| vec![w.var_v1_sq, w.var_v2_sq, w.bias_v1_sq, w.bias_v2_sq, w.signal_v1_sq, w.signal_v2_sq]));
    }

    #[test]
    fn the_worked_example_is_finite_or_refused(samples in any_count(), dx in any_f64(), photons in any_f64(), visibility in any_f64()) {
        use v2ref::noise::*;
        let setup = ExampleSetup { samples, dx_um: dx, integrating: true, zero_start: false, photons, visibility };
        let r = worked_example(&setup, Formula::Exact);
        hold!(held(r, |w| vec![w.sum_m2_over_n2, w.photon.0, w.photon.1, w.detector.0, w.detector.1]));
    }

    #[test]
    fn the_calibrated_expectation_is_finite_or_refused(photons in any_f64(), visibility in any_f64(), window in prop::sample::select(est::BIN_WINDOWS.to_vec())) {
        use v2ref::noise::calibrated::*;
        let setup = CalibratedSetup::new(obs(), &sampling(), photons, visibility, window);
        hold!(held(setup.clone(), |s| s.calibration().map_or(vec![], |c| vec![c.v1_sq, c.v2_sq])));
        if let Ok(setup) = setup {
            let e = expectation(&setup, &v2ref::noise::NoiseModel::photon(), v2ref::noise::Formula::Exact);
            hold!(held(e, |e| [vec![e.mean_v1_sq, e.mean_v2_sq], e.var_v1_sq.into_iter().chain(e.var_v2_sq).collect()].concat()));
        }
    }

    /// Any spec and trial count: a run, or a typed error before any trial.
    #[test]
    fn a_noisy_run_is_finite_or_refused(
        modulated in prop::collection::vec(any_f64(), 0..6), continuum in prop::collection::vec(any_f64(), 0..6),
        bins in prop::collection::vec(0usize..8, 0..3), threads in any_count(),
        trials in prop_oneof![0u64..100, Just((1u64 << 40) + 1), Just(u64::MAX)],
    ) {
        use v2ref::noise::simulation::*;
        let noise = v2ref::noise::NoiseModel::new(1.0, true).unwrap();
        let spec = NoisySpec { modulated, continuum, noise, bins };
        let r = simulate_noisy(&spec, trials, 1, threads, &|_| {});
        hold!(held(r, |r| vec![r.v1_sq.mean, r.v2_sq.mean]));
    }
}

pub(crate) use hold;
