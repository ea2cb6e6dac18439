//! The plan's promise for the observation (n consecutive scans through one
//! atmosphere), checked by simulating it (`plan --verify`) in four regimes:
//! piston-dominated (a very bright star, a tight target, 8 m apertures on
//! 130 m in H) and noise-dominated (a faint star in K), each for V1² and
//! V2².
//!
//! - the achieved σ(V²) is within the promise: the lower end of its 90%
//!   interval is at most the promise (the promise takes the piston terms at
//!   the upper ends of their intervals, so it may be above the achieved σ,
//!   but it is not more than 1.6 times it: not a vacuous bound);
//! - in the piston-dominated regime the independent-scan formula
//!   σ_scan/√n fails: it is below the lower end of the achieved σ's
//!   interval (the test's power: the verification tells the two promises
//!   apart);
//! - the bias convention: in a faint visible case whose piston wanders
//!   within each scan, V2²'s mean under `model` and under `counts` differ
//!   by 0.19 (about 15 standard errors of the simulation); each
//!   convention's simulated mean is within [`PLAN_MEAN_SIGMAS`] standard
//!   errors of its own prediction and more than [`MC_SIGMAS`] from the
//!   other's (the band of 3 standard errors is ±0.04, a fifth of the
//!   offset). V1²'s offset is below 1e-4 on scans of many fringes (only
//!   the scan's sum of modulated counts enters it); on a two-fringe scan
//!   it is 1.3e-2, below the unpaired simulation's reach in seconds, so
//!   there the same rows are estimated both ways and their
//!   mean difference is checked against the predicted offset (within 3
//!   standard errors, and more than 5 from zero: 37 measured), each
//!   convention's mean against its own prediction.

use v2ref_commands::plan::verify::{size_at, verification_size, verify, Verification};
use v2ref_commands::plan::SEQUENCES;
use v2ref_commands::plan::{plan, Estimator, PlanInputs, PlanPoint, Target};
use v2ref_core::assert_within_sigmas;
use v2ref_core::conformance::estimate::{BiasConvention, RowEstimator};
use v2ref_core::formalism::estimator::BinWindow;
use v2ref_core::montecarlo::{replicated_summary, RunningStats, Summary};
use v2ref_core::piston::PistonReference;
use v2ref_core::piston::DEFAULT_SUB_SAMPLES;
use v2ref_core::simulator::{Inputs, Model, PistonInputs, SourceInput, SpectrumInput};
use v2ref_core::tolerance::{check_sigmas, MC_SIGMAS, PLAN_MEAN_SIGMAS};

/// A plan's inputs on a one-point grid.
struct Site {
    band: (f64, f64),
    baseline_m: f64,
    aperture_m: f64,
    outer_scale_m: f64,
    seeing_05: f64,
    wind_mps: f64,
    photon_rate_per_s: f64,
    read_noise: f64,
    fringe_hz: f64,
    stroke_um: f64,
    target: f64,
}

fn inputs(s: &Site, bias: BiasConvention) -> PlanInputs {
    PlanInputs {
        instrument: Inputs {
            spectrum: SpectrumInput::Flat {
                wavelength_um: s.band.0,
                bandwidth_nm: s.band.1,
            },
            source: SourceInput::Point,
            baseline_m: s.baseline_m,
            read_noise: s.read_noise,
            photon_noise: true,
            ..Inputs::default()
        },
        atmosphere: PistonInputs {
            fringe_hz: 1.0,
            wavelength_um: s.band.0,
            seeing_arcsec: s.seeing_05 * (s.band.0 / 0.5).powf(-0.2),
            wind_mps: s.wind_mps,
            aperture_m: s.aperture_m,
            outer_scale_m: Some(s.outer_scale_m),
            reference: PistonReference::Mean,
            sub_samples: DEFAULT_SUB_SAMPLES,
        },
        samples_per_fringe: 4.0,
        photon_rate_per_s: s.photon_rate_per_s,
        dead_time_s: 0.0,
        frame_rate_hz: None,
        fringe_hz: vec![s.fringe_hz],
        stroke_um: vec![s.stroke_um],
        target: Target::SigmaV2(s.target),
        scans: 4000,
        seed: 5,
        diameter_err_mas: 0.0,
        bias,
    }
}

/// The bright star: the piston dominates each scan's error.
const BRIGHT: Site = Site {
    band: (1.65, 300.0),
    baseline_m: 130.0,
    aperture_m: 8.0,
    outer_scale_m: 22.0,
    seeing_05: 0.8,
    wind_mps: 10.0,
    photon_rate_per_s: 1e11,
    read_noise: 1.0,
    fringe_hz: 1000.0,
    stroke_um: 16.0,
    target: 1e-4,
};

/// The faint star: the noise dominates.
const FAINT: Site = Site {
    band: (2.2, 400.0),
    baseline_m: 50.0,
    aperture_m: 1.8,
    outer_scale_m: 25.0,
    seeing_05: 0.8,
    wind_mps: 10.0,
    photon_rate_per_s: 2e6,
    read_noise: 2.0,
    fringe_hz: 800.0,
    stroke_um: 32.0,
    target: 3e-3,
};

/// The plan of `site` and its best point of `e`, verified with
/// `observations` simulated observations.
fn verified(site: &Site, e: Estimator, observations: u64) -> (PlanPoint, Verification) {
    let inputs = inputs(site, BiasConvention::Counts);
    let plan = plan(&inputs, 0, &|_| {}).unwrap();
    let p = match e {
        Estimator::V1 => plan.best_v1,
        Estimator::V2 => plan.best_v2,
        other => panic!("no best point for {other:?}"),
    }
    .expect("the target is reachable");
    let sky = inputs.atmosphere.spectrum(site.baseline_m).unwrap();
    let size = verification_size(&inputs, &sky, &p, observations).unwrap();
    let v = verify(&inputs, &sky, &p, &size, &|_| {}).unwrap();
    eprintln!(
        "{e:?}: n {} (inflation {:.2}), sigma_scan noise {:.2e} piston {:.2e}; promised {:.3e}, achieved {:.3e} [{:.3e}, {:.3e}], independent {:.3e}; mean predicted {:.6e} achieved {:.6e} +/- {:.1e}",
        v.scans_per_observation,
        p.observation.unwrap().variance_inflation,
        p.sigma_noise_per_scan,
        p.sigma_piston_per_scan,
        v.promised_sigma,
        v.achieved_sigma,
        v.achieved_sigma_interval[0],
        v.achieved_sigma_interval[1],
        v.sigma_if_independent,
        v.predicted_mean,
        v.achieved_mean,
        v.achieved_mean_stderr,
    );
    (p, v)
}

/// σ of the observation from the piston over that from the noise.
fn piston_over_noise(p: &PlanPoint) -> f64 {
    let o = p.observation.expect("re-solved at the observation level");
    o.sigma_piston / o.sigma_noise
}

/// The promise holds (the achieved σ at most [`MC_SIGMAS`] standard errors
/// above it) and is not vacuous (at most 1.5 times the achieved σ); the
/// mean is the predicted one within [`PLAN_MEAN_SIGMAS`] standard errors of
/// the difference.
fn assert_kept(v: &Verification) {
    let se = v.achieved_sigma_stderr;
    assert!(
        v.achieved_sigma <= v.promised_sigma + MC_SIGMAS * se,
        "achieved sigma above the promise: {v:?}"
    );
    assert!(
        // tol: the promise is an upper end, not more than half again the achieved σ: a promise that loose would be of no use.
        v.promised_sigma < 1.5 * v.achieved_sigma,
        "the promise is far above the achieved sigma: {v:?}"
    );
    let se_mean = v.achieved_mean_stderr.hypot(v.predicted_mean_stderr);
    assert_within_sigmas!(v.achieved_mean, v.predicted_mean, se_mean, PLAN_MEAN_SIGMAS);
}

/// The independent-scan promise σ_scan/√n is rejected: below the achieved
/// σ by more than [`MC_SIGMAS`] standard errors.
fn assert_independent_rejected(v: &Verification) {
    assert!(
        v.sigma_if_independent < v.achieved_sigma - MC_SIGMAS * v.achieved_sigma_stderr,
        "the independent-scan formula is not rejected: {v:?}"
    );
}

#[test]
#[ignore = "slow tier: observations simulated against a piston-dominated V1 plan (6 s)"]
fn piston_dominated_v1_keeps_the_promise_the_independent_formula_does_not() {
    let (p, v) = verified(&BRIGHT, Estimator::V1, 256);
    assert!(piston_over_noise(&p) > 2.0, "{p:?}");
    assert_kept(&v);
    assert_independent_rejected(&v);
}

#[test]
fn piston_dominated_v2_keeps_the_promise_the_independent_formula_does_not() {
    let (p, v) = verified(&BRIGHT, Estimator::V2, 256);
    assert!(piston_over_noise(&p) > 2.0, "{p:?}");
    assert_kept(&v);
    assert_independent_rejected(&v);
}

#[test]
fn noise_dominated_v1_keeps_the_promise() {
    let (p, v) = verified(&FAINT, Estimator::V1, 256);
    // tol: not a tolerance: the regime; piston below half the noise is noise-dominated.
    assert!(piston_over_noise(&p) < 0.5, "{p:?}");
    assert_kept(&v);
}

#[test]
#[ignore = "slow tier: observations simulated against a noise-dominated V2 plan (7 s)"]
fn noise_dominated_v2_keeps_the_promise() {
    let (p, v) = verified(&FAINT, Estimator::V2, 256);
    // tol: not a tolerance: the regime; piston below half the noise is noise-dominated.
    assert!(piston_over_noise(&p) < 0.5, "{p:?}");
    assert_kept(&v);
}

/// The faint visible star whose piston moves within each scan: 0.625 µm,
/// 50 nm on 50 m, 0.2 m apertures, 20 m/s wind, 5 photons per sample at
/// 250 Hz (16 µm, 102 samples, 0.1 s per scan). The `model` convention
/// subtracts V2²'s photon bias of the piston-free fringe: its bias kernel
/// |u_i|² reaches the fringe frequency (the positive window's
/// autocorrelation), so it holds the fringe's own counts, which the
/// piston's wander within the scan blurs; V2² under `model` comes out
/// 0.19 below `counts` (each scan's own counts), 15 standard errors of
/// these simulations (8192 scans each). V1²'s kernel is flat: only the
/// scan's sum of the modulated counts enters, about zero for a scan of 26
/// fringes.
const VISIBLE: Site = Site {
    band: (0.625, 50.0),
    baseline_m: 50.0,
    aperture_m: 0.2,
    outer_scale_m: 25.0,
    seeing_05: 1.0,
    wind_mps: 20.0,
    photon_rate_per_s: 5_000.0,
    read_noise: 0.5,
    fringe_hz: 250.0,
    stroke_um: 16.0,
    target: 0.5,
};

/// The same star on the shortest scan of the grid (1.25 µm: 8 samples, two
/// fringes) at 100 Hz: there the piston's wander leaves a sum of the
/// modulated counts over the scan, and V1²'s offset between the
/// conventions is about 1e-2.
const VISIBLE_SHORT: Site = Site {
    fringe_hz: 100.0,
    stroke_um: 1.25,
    photon_rate_per_s: 2_000.0,
    ..VISIBLE
};

/// The plan's point of `e` at `site` (a one-point grid) under `bias`.
fn planned(site: &Site, bias: BiasConvention, e: Estimator) -> (PlanInputs, PlanPoint) {
    let inputs = inputs(site, bias);
    let plan = plan(&inputs, 0, &|_| {}).unwrap();
    let p = match e {
        Estimator::V1 => plan.best_v1,
        Estimator::V2 => plan.best_v2,
        other => panic!("no best point for {other:?}"),
    };
    (inputs, p.expect("the target is reachable"))
}

/// The mean V² of `observations` simulated observations of `scans`
/// consecutive scans at the plan's point (`plan --verify`'s simulation),
/// estimated with the plan's convention.
fn achieved(
    inputs: &PlanInputs,
    site: &Site,
    p: &PlanPoint,
    scans: f64,
    observations: u64,
) -> Verification {
    let sky = inputs.atmosphere.spectrum(site.baseline_m).unwrap();
    let p = PlanPoint {
        scans_needed: Some(scans),
        ..*p
    };
    let size = verification_size(inputs, &sky, &p, observations).unwrap();
    verify(inputs, &sky, &p, &size, &|_| {}).unwrap()
}

/// `achieved` (value, standard error) against `predicted`: within
/// `sigmas` standard errors of their difference.
fn agrees(achieved: (f64, f64), predicted: (f64, f64), sigmas: f64) -> bool {
    check_sigmas(
        achieved.0,
        predicted.0,
        achieved.1.hypot(predicted.1),
        sigmas,
    )
    .is_ok()
}

/// V2²'s simulated mean under each convention: within 3 standard errors of
/// its own prediction (measured 0.1 and 0.03), more than [`MC_SIGMAS`]
/// from the other's (measured 14.7 and 15.7).
#[test]
fn v2_mean_follows_its_convention_and_rejects_the_other_in_a_faint_case() {
    let e = Estimator::V2;
    let (in_model, model) = planned(&VISIBLE, BiasConvention::Model, e);
    let (in_counts, counts) = planned(&VISIBLE, BiasConvention::Counts, e);
    let predicted = |p: &PlanPoint| {
        let o = p.observation.unwrap();
        (o.predicted_mean, o.bias_stderr)
    };
    let (p_model, p_counts) = (predicted(&model), predicted(&counts));
    for (inputs, p, own, other) in [
        (&in_model, &model, p_model, p_counts),
        (&in_counts, &counts, p_counts, p_model),
    ] {
        let v = achieved(inputs, &VISIBLE, p, 32.0, 256);
        let a = (v.achieved_mean, v.achieved_mean_stderr);
        eprintln!(
            "{:?} {e:?}: offset {:+.3e} +/- {:.1e}; achieved {:.4e} +/- {:.1e}, own prediction {:.4e} +/- {:.1e}, other {:.4e}",
            inputs.bias,
            p.observation.unwrap().convention_offset,
            p.observation.unwrap().convention_offset_stderr,
            a.0,
            a.1,
            own.0,
            own.1,
            other.0
        );
        assert!(
            agrees(a, own, PLAN_MEAN_SIGMAS),
            "{:?}: {a:?} against {own:?}",
            inputs.bias
        );
        assert!(
            !agrees(a, other, MC_SIGMAS),
            "{:?}: {a:?} does not reject {other:?}",
            inputs.bias
        );
    }
}

/// Per estimator, the mean of (V² under `model` − V² under `counts`) over
/// `rows` rows of the point's setting with piston and noise, each row
/// estimated both ways (paired: the noise and the piston common to both
/// cancel), with its standard error from the spread between the piston
/// sequences the rows are cut from.
fn paired_difference(inputs: &PlanInputs, site: &Site, p: &PlanPoint, rows: u64) -> [Summary; 2] {
    let sky = inputs.atmosphere.spectrum(site.baseline_m).unwrap();
    let setting = inputs
        .point_inputs(p.fringe_hz, p.stroke_um, true, true)
        .unwrap();
    let model = Model::with_piston_spectrum(&setting, sky).unwrap();
    let estimator = |bias| RowEstimator::new(&model, BinWindow::Positive, bias, true).unwrap();
    let (by_model, by_counts) = (
        estimator(BiasConvention::Model),
        estimator(BiasConvention::Counts),
    );
    let set = model.rows(rows, 11, 0).unwrap();
    let mut groups = vec![[RunningStats::default(); 2]; set.sequences()];
    let n = set.samples();
    set.fold_units(
        0,
        |first, block| {
            Ok(block
                .chunks_exact(n)
                .enumerate()
                .map(|(k, row)| {
                    let (m, c) = (
                        by_model.estimate(row).unwrap(),
                        by_counts.estimate(row).unwrap(),
                    );
                    (first + k as u64, [m.v1_sq - c.v1_sq, m.v2_sq - c.v2_sq])
                })
                .collect::<Vec<_>>())
        },
        |done| {
            for (s, d) in done {
                let g = &mut groups[set.sequence_of(s).unwrap()];
                g[0].push(d[0]);
                g[1].push(d[1]);
            }
        },
    )
    .unwrap();
    [0, 1].map(|e| replicated_summary(&groups.iter().map(|g| g[e]).collect::<Vec<_>>()))
}

/// V1²'s offset between the conventions, on the same simulated rows: the
/// predicted one within 3 standard errors (measured 0.7; the band is ±25 %
/// of the offset, the plan's own Monte Carlo error dominating it) and
/// more than [`MC_SIGMAS`] from zero (measured 37); each convention's
/// unpaired mean within 3 standard errors of its prediction (measured 0.9).
#[test]
fn v1_offset_between_the_conventions_is_the_predicted_one_on_a_short_scan() {
    let e = Estimator::V1;
    let (in_model, model) = planned(&VISIBLE_SHORT, BiasConvention::Model, e);
    let (in_counts, counts) = planned(&VISIBLE_SHORT, BiasConvention::Counts, e);
    let o = model.observation.unwrap();
    let d = paired_difference(&in_model, &VISIBLE_SHORT, &model, 16_384)[0];
    eprintln!(
        "{e:?}: offset predicted {:+.4e} +/- {:.1e}, simulated (model - counts, paired) {:+.4e} +/- {:.1e}",
        o.convention_offset, o.convention_offset_stderr, d.mean, d.stderr_mean
    );
    assert!(
        agrees(
            (d.mean, d.stderr_mean),
            (o.convention_offset, o.convention_offset_stderr),
            PLAN_MEAN_SIGMAS
        ),
        "{d:?} against {o:?}"
    );
    assert!(
        d.mean.abs() > MC_SIGMAS * d.stderr_mean,
        "the conventions agree: {d:?}"
    );
    // Each convention's own prediction holds, unpaired, too.
    for (inputs, p) in [(&in_model, &model), (&in_counts, &counts)] {
        let v = achieved(inputs, &VISIBLE_SHORT, p, 32.0, 256);
        let o = p.observation.unwrap();
        eprintln!(
            "{:?} {e:?}: achieved {:.4e} +/- {:.1e}, predicted {:.4e} +/- {:.1e}",
            inputs.bias, v.achieved_mean, v.achieved_mean_stderr, o.predicted_mean, o.bias_stderr
        );
        assert!(
            agrees(
                (v.achieved_mean, v.achieved_mean_stderr),
                (o.predicted_mean, o.bias_stderr),
                PLAN_MEAN_SIGMAS
            ),
            "{:?}: {v:?}",
            inputs.bias
        );
    }
}

/// `piston --observation-scans n --json` on the bright site of [`BRIGHT`].
fn piston_observation(extra: &[&str]) -> serde_json::Value {
    let mut args = vec![
        "piston",
        "--source",
        "point",
        "--wavelength-um",
        "1.65",
        "--bandwidth-nm",
        "300",
        "--baseline-m",
        "130",
        "--aperture-m",
        "8",
        "--outer-scale-m",
        "22",
        "--seeing-arcsec",
        "0.8",
        "--seeing-wavelength-um",
        "0.5",
        "--samples",
        "39",
        "--fringe-hz",
        "1000",
        "--scans",
        "200",
        "--quiet",
        "--json",
    ];
    args.extend(extra);
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(&args)
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    v["observation"][0].clone()
}

#[test]
fn piston_reports_the_observations_sigma_and_its_inflation() {
    // One scan: the mean is the scan, the inflation exactly 1.
    let one = piston_observation(&["--observation-scans", "1"]);
    assert_eq!(one["variance_inflation_v1"].as_f64(), Some(1.0));
    assert_eq!(one["sigma_v1_sq"], one["sigma_v1_sq_per_scan"]);
    // 1500 consecutive scans (17.7 s) share the piston: σ of their mean is
    // above σ_scan/√n by more than MC_SIGMAS standard errors, for both
    // estimators.
    let long = piston_observation(&["--observation-scans", "1500"]);
    for e in ["v1", "v2"] {
        let sigma = long[format!("sigma_{e}_sq")].as_f64().unwrap();
        let se = long[format!("sigma_{e}_sq_stderr")].as_f64().unwrap();
        let per_scan = long[format!("sigma_{e}_sq_per_scan")].as_f64().unwrap();
        let independent = per_scan / 1500f64.sqrt();
        assert!(
            independent < sigma - MC_SIGMAS * se,
            "{e}: {sigma} +/- {se} against {independent}"
        );
    }
    // The same observation given by its length.
    let seconds = long["duration_s"].as_f64().unwrap();
    let by_time = piston_observation(&["--observation-s", &format!("{}", seconds * 0.9999)]);
    assert_eq!(by_time["scans"].as_u64(), Some(1500));
    assert_eq!(by_time["sigma_v1_sq"], long["sigma_v1_sq"]);
}

/// `--verify-observations` delivers what it was asked or says why fewer
/// (issue 55: 64 asked, 32 delivered, no word): an observation of 10⁵
/// scans of 39 samples leaves room for 4 per simulated piston sequence
/// (2^24 samples, the memory bound), so 256 asked give 64 and the size
/// says so, naming the bound and the numbers; 32 asked are delivered with
/// no such word.
#[test]
fn fewer_verified_observations_than_asked_say_why() {
    let i = inputs(&BRIGHT, BiasConvention::Counts);
    let sky = i.atmosphere.spectrum(BRIGHT.baseline_m).unwrap();
    let n = 100_000_u64;
    let size = size_at(&i, &sky, (BRIGHT.fringe_hz, BRIGHT.stroke_um, n), 256).unwrap();
    let per_sequence = (1_usize << 24).saturating_sub(size.samples + 4) / size.stride;
    let delivered = SEQUENCES as u64 * (per_sequence as u64 / n);
    assert_eq!((size.samples, delivered), (39, 64));
    assert_eq!(size.observations(), delivered);
    assert_eq!(size.observations_requested, 256);
    let why = size.fewer_why().expect("fewer than asked: a reason");
    for words in [
        "64 of the 256",
        "memory",
        "16777216 samples",
        "4 observations",
    ] {
        assert!(why.contains(words), "{words:?} not in {why}");
    }
    let size = size_at(&i, &sky, (BRIGHT.fringe_hz, BRIGHT.stroke_um, n), 32).unwrap();
    assert!(size.observations() >= 32 && size.fewer_why().is_none());
}
