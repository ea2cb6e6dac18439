//! The stable surface's functions under arbitrary inputs, second part
//! (`surface_properties.rs` states the rule and holds the first): the
//! piston, the simulator, the conformance kit, the oracle route, the Monte
//! Carlo's statistics and the errors.

use crate::surface_properties::{
    any_count, any_f64, any_u64, finite, held, hold, in_words, obs, CASES,
};
use proptest::prelude::*;
use std::sync::OnceLock;
use v2ref::formalism::estimator::{self as est, Pair};
use v2ref::Error;

// ---- piston ------------------------------------------------------------------

proptest! {
    #![proptest_config(crate::surface_properties::fixed_seed(8))]

    #[test]
    fn the_atmosphere_is_finite_or_refused(
        r0 in any_f64(), wl in any_f64(), wind in any_f64(), outer in prop::option::of(any_f64()),
        seeing in any_f64(), f in any_f64(), rho in any_f64(),
    ) {
        use v2ref::piston::turbulence::Turbulence;
        let values = |t: &Turbulence| {
            let mut v = vec![t.r0_m(), t.wavelength_um(), t.wind_mps(), t.coherence_time_s(), t.tau0_s(), t.opd_psd_scale()];
            v.extend(t.outer_scale_m());
            if f.is_finite() && f > 0.0 { v.push(t.opd_psd(f)); }
            if (0.0..1e100).contains(&rho) { v.push(t.opd_structure_function_um2(rho)); }
            if let Err(e) = t.with_wind(wind).map(|w| v.push(w.wind_mps())) { assert!(in_words(&e)); }
            v
        };
        hold!(held(Turbulence::new(r0, wl, wind, outer), values));
        hold!(held(Turbulence::from_seeing(seeing, wl, wind, outer), values));
    }

    #[test]
    fn the_three_slope_spectrum_is_finite_or_refused(var in any_f64(), wind in any_f64(), b in any_f64(), d in any_f64(), nu in any_f64()) {
        let t = v2ref::piston::three_slope::ThreeSlope::new(var, wind, b, d);
        hold!(held(t, |t| {
            let mut v = vec![t.corner_low_hz(), t.corner_high_hz(), t.variance_um2()];
            if nu.is_finite() && nu > 0.0 { v.push(t.psd_um2_per_hz(nu)); }
            v
        }));
    }

    /// Any telescope and baseline: the piston spectrum, or a typed error;
    /// any scan count: a stride, and a run refused before it starts when
    /// past its range.
    #[test]
    fn the_piston_spectrum_and_runs_are_finite_or_refused(
        aperture in any_f64(), baseline in any_f64(), wind in any_f64(), angle in any_f64(),
        nu in any_f64(), scans in any_count(), threads in any_count(), fringe in any_f64(),
    ) {
        use v2ref::piston::spectrum::{PistonPsdModel, PistonSpectrum, TransverseTable};
        use v2ref::piston::*;
        let turb = v2ref::piston::turbulence::Turbulence::from_seeing(0.8, 2.2, 10.0, Some(25.0)).unwrap();
        hold!(held(TransverseTable::new(turb, aperture), |t| vec![t.aperture_m(), t.g(1.0), t.grid_fx_per_m(0)]));
        let spectrum = PistonSpectrum::new(turb, aperture, baseline);
        hold!(held(spectrum.clone(), |s| spectrum_facts(s, nu)));
        let Ok(spectrum) = spectrum else { return Ok(()) };
        let _ = (spectrum.table().aperture_m(), spectrum.turbulence().r0_m(), PistonPsdModel::ThreeSlope.name());
        hold!(held(spectrum.with_wind(wind), |s| spectrum_facts(s, nu)));
        hold!(held(PistonSpectrum::from_table(spectrum.table().clone(), baseline), |s| spectrum_facts(s, nu)));
        let _ = (spectrum.table().turbulence().r0_m(), spectrum.table().tabulate());
        hold!(held(spectrum.with_model(PistonPsdModel::ThreeSlope), |s| spectrum_facts(s, nu)));
        if angle.is_nan() || angle.abs() > 1e3 {
            hold!(held(spectrum.with_wind_angle_deg(angle), |s| spectrum_facts(s, nu)));
        }
        let setup = ScanSetup::paper(fringe);
        hold!(held(setup.validate().map(|()| setup), |s| vec![s.opd_speed_um_per_s(), s.sample_time_s(), s.scan_time_s()]));
        let setup = ScanSetup::paper(500.0);
        let (k, per) = sequence_split(scans);
        prop_assert!(k >= 1 && k.saturating_mul(per) >= scans);
        let _ = scan_stride(&spectrum, &setup, scans);
        let size = RunSize { scans: [0, 1 << 40, usize::MAX][scans % 3], seed: 1, threads };
        let run = simulate_piston(obs(), &spectrum, &setup, &[Detector::Sampled], &size, None);
        prop_assert!(run.is_err(), "{} scans are refused up front", size.scans);
        let _ = (Detector::Sampled.name(), setup.reference.name());
    }

    #[test]
    fn a_piston_series_is_finite_or_refused(value in any_f64(), dt in any_f64(), len in prop_oneof![0usize..4096, Just(1usize << 40), Just(usize::MAX)], threads in any_count()) {
        let s = v2ref::piston::synthesize_series(&|_| value, dt, len, 3, threads);
        hold!(held(s, |s| s.clone()));
    }
}

fn spectrum_facts(s: &v2ref::piston::spectrum::PistonSpectrum, nu: f64) -> Vec<f64> {
    let mut v = vec![
        s.aperture_m(),
        s.baseline_m(),
        s.wind_mps(),
        s.wind_angle_deg(),
        s.variance_um2(),
        s.rms_um(),
    ];
    // (On a zero baseline there is no differential piston, and the low
    // corner v/(√2 π B) is at infinity: the one non-finite fact, by its
    // formula.)
    if s.baseline_m() > 0.0 {
        v.extend([s.corner_low_hz(), s.corner_high_hz()]);
    }
    s.tabulate();
    let _ = (s.model(), s.three_slope());
    if nu.is_finite() && nu > 0.0 {
        v.extend([s.psd_um2_per_hz(nu), s.psd_direct_um2_per_hz(nu)]);
        v.extend([
            s.asymptote_low(nu),
            s.asymptote_mid(nu),
            s.asymptote_high(nu),
        ]);
    }
    v
}

// ---- simulator, conformance, oracle -----------------------------------------

use v2ref::oracle::{BiasConvention, Inputs, Set, BIAS_CONVENTIONS};

/// A small set (120 rows of 16 samples), made once.
fn set() -> &'static Set {
    static SET: OnceLock<Set> = OnceLock::new();
    SET.get_or_init(|| {
        let inputs = Inputs {
            samples: 16,
            photons: 80.0,
            visibility: 0.7,
            ..Inputs::default()
        };
        Set::synthesize(&inputs, 120, 5).unwrap()
    })
}

proptest! {
    #![proptest_config(crate::surface_properties::fixed_seed(CASES))]

    /// Any physical inputs: a model whose facts are finite, or a typed error.
    #[test]
    fn any_inputs_make_a_model_or_are_refused(
        baseline in any_f64(), pp in any_f64(), samples in any_count(), dx in any_f64(),
        photons in any_f64(), visibility in any_f64(), read_noise in any_f64(),
    ) {
        use v2ref::simulator::Model;
        let inputs = Inputs { baseline_m: baseline, dispersion_pp_rad: pp, samples: samples.min(64).max(if samples > 64 { samples } else { 0 }), dx_um: dx, photons, visibility, read_noise, ..Inputs::default() };
        let checked = inputs.validate();
        hold!(held(checked.clone(), |_| vec![]));
        let model = Model::new(&inputs);
        prop_assert_eq!(model.is_ok(), checked.is_ok());
        hold!(held(model, |m| {
            let _ = (inputs.detector(), inputs.scan_setup(), inputs.observation().unwrap(), inputs.sampling().unwrap(), inputs.noise().unwrap());
            let mut v = [m.sample_opd_um(), m.sample_variance()].concat();
            assert!(est::BIN_WINDOWS.iter().all(|&w| m.bins(w).iter().all(|&k| k < m.samples())));
            let c = m.calibrated_setup(est::BinWindow::Positive).calibration().unwrap();
            v.extend([c.v1_sq, c.v2_sq]);
            v.extend(m.calibrator_model().unwrap().sample_variance());
            v
        }));
    }

    /// Any row count, seed and thread count: the rows, or a typed error
    /// before any is drawn; any unit or sequence index: its facts, or a
    /// typed error.
    #[test]
    fn any_row_count_is_drawn_or_refused(rows in prop_oneof![0u64..50, Just(1u64 << 40), Just(u64::MAX)], threads in any_count(), u in any::<u64>(), obs_count in any::<u64>(), dead in any_f64(), batch in any::<u64>()) {
        use v2ref::simulator::{RowLayout, RowTiming};
        let model = set().model();
        for layout in [RowLayout::Sequences, RowLayout::Observation] {
            let _ = RowLayout::from_name(layout.name()).unwrap();
            hold!(held(RowTiming::new(layout, obs_count, dead), |t| vec![t.dead_time_s]));
        }
        hold!(held(RowTiming::observation(obs_count, dead), |t| vec![t.dead_time_s]));
        prop_assert!(RowLayout::from_name("--rows").is_err());
        // Rows are drawn lazily: any count is accepted, nothing allocated.
        let drawn = model.rows(rows, 7, threads);
        let Ok(r) = drawn else { return Ok(()) };
        prop_assert_eq!((r.rows(), r.seed(), r.samples()), (rows, 7, 16));
        let _ = (r.model().samples(), r.piston_facts(), r.layout(), r.sequences(), r.piston_free_row());
        // An index past the set, or a row of another length: a typed error.
        prop_assert_eq!(r.unit_rows(u).is_ok(), u < r.units());
        prop_assert_eq!(r.sequence_of(u).is_ok(), u < r.rows());
        let mut out = vec![0.0; (u % 40) as usize];
        let len = out.len();
        let row = r.noise_free_row(u % 3, &mut out).map(|()| out);
        prop_assert!(row.map_or(len != 16 || u % 3 >= rows, finite));
        if rows > 50 { return Ok(()); }
        let mut seen = 0u64;
        let streamed = r.stream(1, batch, |b: &[f64]| { seen += b.len() as u64; Ok(()) });
        prop_assert!(streamed.is_ok() && seen == rows * 16);
        let mapped = r.map_units(0..r.units().min(3), 1, |_, b| Ok(b.len()));
        prop_assert!(mapped.is_ok());
        let folded = r.fold_units(1, |_, b| Ok(b.len()), |_| ());
        prop_assert!(folded.is_ok());
        let filled = v2ref::montecarlo::run_units(1, 1, 1, |_, rng| {
            let mut out = Vec::new();
            r.fill_unit(u, rng, &mut out).map(|()| out)
        }).unwrap();
        prop_assert!(filled[0].as_ref().map_or(u >= r.units(), |o| finite(o.iter().copied())));
        if let Some(layout) = r.layout() { let _ = layout.row_start(u); }
    }

    /// Any row: its estimate, or a typed error (never cut to length).
    #[test]
    fn any_rows_are_estimated_or_refused(
        // (Samples near 1e154 and above overflow the squares: the rows'
        // path does not refuse them yet — see `try_estimate` in
        // tests/public_misuse.rs for the single row, which does.)
        values in prop::collection::vec(prop_oneof![Just(f64::NAN), Just(f64::INFINITY), Just(0.0), -1e6..1e6f64], 0..40),
        threads in any_count(), c1 in any_f64(), c2 in any_f64(), window in prop::sample::select(est::BIN_WINDOWS.to_vec()),
        bias in prop::sample::select(BIAS_CONVENTIONS.to_vec()), subtracted in any::<bool>(),
    ) {
        use v2ref::conformance::estimate::{RowEstimator, RowFault};
        let model = set().model();
        let Ok(e) = RowEstimator::new(model, window, bias, subtracted) else { return Ok(()) };
        let _ = (e.samples(), bias.name(), e.calibration());
        let rows_ok = values.len() % 16 == 0 && finite(values.iter().copied());
        let est = |r: &RowEstimator| r.try_estimate_rows(&values, threads);
        if let Ok(rows) = est(&e) {
            prop_assert!(values.len() % 16 == 0 && rows.iter().all(|x| finite(x.values())));
        }
        hold!(held(e.estimate_rows(&values, threads), |r| r.iter().flat_map(|x| x.values()).collect()));
        hold!(held(e.calibration_from_rows(&values, threads), |c| vec![c.v1_sq, c.v2_sq]));
        let cal = e.clone().with_calibration(Pair { v1_sq: c1, v2_sq: c2 });
        hold!(held(cal, |c| c.calibration().v1_sq.is_finite().then_some(vec![]).unwrap_or(vec![f64::NAN])));
        let fault = RowFault::of_row(3, &values);
        prop_assert!(fault.is_some() || finite(values.iter().copied()));
        if let Some(f) = RowFault::first(fault, None) { prop_assert!(!f.location(0).is_empty() && !f.reason().is_empty()); }
        let _ = rows_ok;
    }

    /// Any pipeline's estimates and any truth: a score of finite z, or a
    /// typed error.
    #[test]
    fn any_estimates_score_finite_or_are_refused(
        v1 in prop::collection::vec(any_f64(), 0..130), take in 0usize..130, alpha in any_f64(), rows in any_u64(),
        mean in any_f64(), var in any_f64(),
    ) {
        use v2ref::conformance::score::score;
        use v2ref::oracle::{score_report, Estimates};
        let truth = set().expected(est::BinWindow::Positive, BiasConvention::Model).unwrap();
        let mut t = truth.v1_sq;
        (t.mean, t.var) = (mean, var);
        let s = |r: &v2ref::oracle::EstimatorScore| vec![r.z_mean, r.z_var, r.mean, r.var];
        hold!(held(score(&v1, &t, rows, alpha), s));
        hold!(held(score(&v1, &truth.v1_sq, set().len() as u64, alpha), s));
        let est = set().reference_estimates(est::BinWindow::Positive, BiasConvention::Model).unwrap();
        let v2: Vec<f64> = est.iter().take(take).map(|r| r.v2_sq).collect();
        let report = |r: &v2ref::oracle::ScoreReport| r.estimators.iter().flat_map(|n| s(&n.score)).collect();
        hold!(held(score_report(Some(&v1), Some(&v2), truth, rows, alpha), report));
        let scored = set().score(est::BinWindow::Positive, BiasConvention::Model, Estimates::default().v2_sq(&v2));
        prop_assert_eq!(scored.is_ok(), v2.len() == set().len());
        hold!(held(scored, report));
    }

    /// Any set size: the set, or a typed error before anything is drawn;
    /// any name: a catalogued set, or a typed error.
    #[test]
    fn any_set_is_made_or_refused(rows in prop_oneof![Just(0u64), Just(1u64 << 40), Just(u64::MAX)], name in "[a-z_-]{0,12}", text in ".{0,40}") {
        prop_assert!(Set::synthesize(&Inputs::default(), rows, 1).is_err());
        prop_assert!(Set::golden(&name).is_err() && Set::powered(&name).is_err());
        let sidecar = v2ref::conformance::sidecar::Sidecar::from_json(&text, std::path::Path::new("set.json"));
        prop_assert!(sidecar.map_err(|e| assert!(in_words(&e))).is_err());
        let mut vector = v2ref::conformance::vectors::catalogue().remove(0);
        vector.inputs.samples = rows as usize;
        hold!(held(v2ref::oracle::powered_rows(&vector), |r| vec![*r as f64]));
        let size = v2ref::conformance::truth::TruthSize { rows, seed: 1, reference_blocks: rows, threads: 1 };
        hold!(held(v2ref::conformance::truth::truth(set().model(), size, &|_| {}), |_| vec![]));
    }
}

/// The set's own facts are finite and agree with one another.
#[test]
fn a_set_states_finite_facts() {
    let s = set();
    assert!(!s.is_empty() && s.values().len() == s.len() * s.samples());
    assert_eq!(s.rows().count(), s.len());
    assert!(finite(
        s.calibrator_row().iter().chain(s.mean_counts()).copied()
    ));
    let back =
        v2ref::conformance::sidecar::Sidecar::from_json(&s.sidecar_json(), "set.json".as_ref())
            .unwrap();
    assert_eq!(back.seed, s.sidecar().seed);
    for w in est::BIN_WINDOWS {
        let c = s.closed_form(w).unwrap();
        assert!(finite([c.mean_v1_sq, c.mean_v2_sq]));
        for b in BIAS_CONVENTIONS {
            assert!(s.sidecar().truth(w, b).is_some() == s.expected(w, b).is_ok());
        }
    }
    assert!(v2ref::oracle::worst_min_detectable(s.truth())
        .unwrap()
        .is_none_or(f64::is_finite));
    let m = v2ref::conformance::sidecar::Member::new("a".into(), 1, 2);
    assert_eq!(m.bytes, 1);
}

// ---- montecarlo, errors ------------------------------------------------------

proptest! {
    #![proptest_config(crate::surface_properties::fixed_seed(CASES))]

    /// Statistics of finite values are finite from two values on.
    #[test]
    fn running_statistics_are_finite(values in prop::collection::vec(-1e100..1e100f64, 2..20), a in -1e3..1e3f64, b in -1e3..1e3f64) {
        use v2ref::montecarlo::{replicated_summary, RunningStats};
        let mut s = RunningStats::from_values(&values);
        s.push(values[0]);
        s.merge(&RunningStats::from_values(&values[1..]));
        let t = s.affine(a, b);
        let sum = t.summary();
        prop_assert!(finite([s.variance(), s.std(), s.stderr_mean(), s.stderr_variance(), s.stderr_std(), sum.mean, sum.var]));
        let r = replicated_summary(&[s, t]);
        prop_assert!(finite([r.mean, r.stderr_mean]));
        let units = v2ref::montecarlo::run_units(3, 4, 2, |u, _| u).unwrap();
        prop_assert_eq!(units, vec![0, 1, 2, 3]);
    }

    #[test]
    fn an_error_names_its_parameter(param in "[a-z_]{1,12}", text in ".{0,20}") {
        let param: &'static str = Box::leak(param.into_boxed_str());
        let e = Error::data(param, "set.npy", "row 3", text.clone());
        prop_assert_eq!(e.param(), Some(param));
        prop_assert!(in_words(&e) && e.to_string().contains(&e.detail()));
        let io = std::io::Error::other("x");
        prop_assert_eq!(Error::file(Some(param), "p", io).param(), Some(param));
        let size = Set::synthesize(&Inputs::default(), 0, 1).unwrap_err();
        prop_assert_eq!(size.renamed("rows", "trials").param(), Some("trials"));
    }
}
