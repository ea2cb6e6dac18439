//! The piston Monte Carlo: synthesised sequences against their spectrum,
//! the fast fringe against the slow ones, the integrating detector's
//! convergence, identities (no turbulence, multiplicative visibility,
//! centred all-bins V2), wind rescaling by simulation, determinism.

use std::f64::consts::PI;
use std::sync::{Arc, OnceLock};
use v2ref_core::formalism::estimator::BinWindow;
use v2ref_core::formalism::interferogram::{sinc, Sampling, SpectralNodes};
use v2ref_core::formalism::observation::{Frequency, Observation};
use v2ref_core::formalism::phase::SpectralPhase;
use v2ref_core::formalism::source::Source;
use v2ref_core::formalism::spectrum::{Band, Spectrum};
use v2ref_core::montecarlo::{RunningStats, Summary};
use v2ref_core::piston::spectrum::PistonSpectrum;
use v2ref_core::piston::transverse::TransverseTable;
use v2ref_core::piston::turbulence::Turbulence;
use v2ref_core::piston::{
    scan_samples, series_variance, simulate_piston, sweep, sweep_seed, synthesize_series, Detector,
    FringeTable, PistonReference, PistonRun, RunSize, ScanSetup,
};
use v2ref_core::tolerance::{
    ASYMPTOTIC_CORRECTION_REL, FRINGE_ORACLE_ABS, FRINGE_TABLE_CHECK_ABS, FRINGE_TABLE_REL,
    MC_SIGMAS, ROUNDING_REL, ULPS, VISIBILITY_SCALING_REL,
};
use v2ref_core::Error;
use v2ref_core::{assert_abs_eq, assert_within_sigmas};

fn obs(source: Source) -> Observation {
    Observation::new(
        Spectrum::flat(Band::k()),
        source,
        Frequency::BaselineM(18.0),
        SpectralPhase::zero(),
    )
    .unwrap()
}

fn spectrum(seeing: f64, wind: f64, baseline: f64) -> PistonSpectrum {
    let t = Turbulence::from_seeing(seeing, 2.2, wind, None).unwrap();
    // The paper's case shares one table of G across the tests (G depends on
    // the turbulence and D only; at opt-level 0, as in the mutation runs,
    // each table costs ~6 s).
    static PAPER: OnceLock<Arc<TransverseTable>> = OnceLock::new();
    if (seeing, wind) == (1.0, 10.0) {
        let table = PAPER.get_or_init(|| Arc::new(TransverseTable::new(t, 0.45).unwrap()));
        return PistonSpectrum::from_table(Arc::clone(table), baseline).unwrap();
    }
    PistonSpectrum::new(t, 0.45, baseline).unwrap()
}

fn run(
    o: &Observation,
    s: &PistonSpectrum,
    setup: ScanSetup,
    det: Detector,
    scans: usize,
    seed: u64,
    threads: usize,
) -> PistonRun {
    simulate_piston(
        o,
        s,
        &setup,
        &[det],
        &RunSize {
            scans,
            seed,
            threads,
        },
        None,
    )
    .unwrap()
    .pop()
    .unwrap()
}

#[test]
fn sample_variance_matches_the_spectrum_within_its_standard_error() {
    // 2000 independent sequences of 4096 samples at 20 ms on a 2 m baseline:
    // the closed-form variance of one sequence's mean square is Σ(2PΔν)².
    let s = spectrum(1.0, 10.0, 2.0);
    let psd = |nu: f64| s.psd_um2_per_hz(nu);
    let (dt, len, reps) = (0.02, 4096, 2000);
    let (want, sd_one) = series_variance(&psd, dt, len);
    let mean_sq: f64 = (0..reps)
        .map(|r| {
            let x = synthesize_series(&psd, dt, len, 1000 + r, 1).unwrap();
            x.iter().map(|v| v * v).sum::<f64>() / len as f64
        })
        .sum::<f64>()
        / reps as f64;
    let se = sd_one / (reps as f64).sqrt();
    assert!(
        (mean_sq - want).abs() < MC_SIGMAS * se,
        "mean square {mean_sq}, model {want} ± {se}"
    );
    assert!(
        (mean_sq - 1.02 * want).abs() > MC_SIGMAS * se,
        "no power: relative standard error {}",
        se / want
    );
    // The discrete sum falls short of the continuous variance by the
    // frequencies below 1/(4096 × 20 ms) that the sequence cannot hold; in
    // the ν^{−2/3} regime those carry ≈ 2 · 3 c (Δν/2)^{1/3}.
    let dnu = 1.0 / (len as f64 * dt);
    let missing = 2.0 * 3.0 * s.asymptote_low(1.0) * (0.5 * dnu).cbrt();
    let cont = s.variance_um2();
    assert!(want < cont && ((want + missing) / cont - 1.0).abs() < ASYMPTOTIC_CORRECTION_REL);
}

#[test]
fn periodogram_matches_the_spectrum_within_its_standard_error() {
    let s = spectrum(1.0, 10.0, 18.0);
    let psd = |nu: f64| s.psd_um2_per_hz(nu);
    let (dt, m) = (1e-3, 1 << 21);
    let x = synthesize_series(&psd, dt, m, 7, 0).unwrap();
    let spec = v2ref_core::formalism::estimator::dft(&x);
    let dnu = 1.0 / (m as f64 * dt);
    // P̂_k = |X_k|²/(M² Δν) has mean P(ν_k) and is exponential: average the
    // ratio over the bins from 0.02 to 100 Hz that avoid the cosine's zeros.
    let mut ratios = Vec::new();
    for (k, z) in spec.iter().enumerate().take(m / 2).skip(1) {
        let nu = k as f64 * dnu;
        let p = psd(nu);
        if !(0.02..100.0).contains(&nu) || p < 1e-3 * s.asymptote_mid(nu) {
            continue;
        }
        ratios.push(z.norm_sqr() / (m as f64 * m as f64 * dnu) / p);
    }
    let n = ratios.len() as f64;
    let mean = ratios.iter().sum::<f64>() / n;
    let se = 1.0 / n.sqrt(); // Exp(1): unit variance
    assert!(n > 100_000.0, "{n} bins");
    assert_within_sigmas!(mean, 1.0, se, MC_SIGMAS, "periodogram ratio");
    assert!((mean - 1.02).abs() > MC_SIGMAS * se, "no power");
    // Per decade too (the shape, not only the level).
    for (lo, hi) in [(0.05, 0.5), (0.5, 5.0), (5.0, 50.0)] {
        let sel: Vec<f64> = spec
            .iter()
            .enumerate()
            .take(m / 2)
            .skip(1)
            .filter_map(|(k, z)| {
                let nu = k as f64 * dnu;
                let p = psd(nu);
                ((lo..hi).contains(&nu) && p >= 1e-3 * s.asymptote_mid(nu))
                    .then(|| z.norm_sqr() / (m as f64 * m as f64 * dnu) / p)
            })
            .collect();
        let k = sel.len() as f64;
        let r = sel.iter().sum::<f64>() / k;
        assert!((r - 1.0).abs() < MC_SIGMAS / k.sqrt(), "{lo}-{hi} Hz: {r}");
    }
}

#[test]
fn lag_structure_function_matches_the_continuous_spectrum() {
    // ⟨(p(t+τ) − p(t))²⟩ = 4 ∫_0^∞ P(ν)(1 − cos 2πντ) dν, against the
    // sample mean over one long sequence; the standard error is the
    // closed form of the discrete modes, √Σ(2PΔν · 2(1 − cos))². A 0.5 m
    // baseline puts both corners near 5 Hz, so that thousands of modes
    // carry the structure function and 2 % is resolved.
    let s = spectrum(1.0, 10.0, 0.5);
    let psd = |nu: f64| s.psd_um2_per_hz(nu);
    let (dt, m) = (1e-2, 1 << 22);
    let x = synthesize_series(&psd, dt, m, 11, 0).unwrap();
    let dnu = 1.0 / (m as f64 * dt);
    for lag in [2usize, 10] {
        let tau = lag as f64 * dt;
        let sample: f64 = (0..m)
            .map(|i| (x[(i + lag) % m] - x[i]).powi(2))
            .sum::<f64>()
            / m as f64;
        let var_terms: f64 = (1..m / 2)
            .map(|k| {
                let nu = k as f64 * dnu;
                (2.0 * psd(nu) * dnu * 2.0 * (1.0 - (2.0 * PI * nu * tau).cos())).powi(2)
            })
            .sum();
        let se = var_terms.sqrt();
        let integrand = |u: f64| {
            let nu = u.exp();
            4.0 * nu * psd(nu) * (1.0 - (2.0 * PI * nu * tau).cos())
        };
        // Up to the sequence's Nyquist frequency, 50 Hz.
        let breaks: Vec<f64> = (0..=1591).map(|i| -12.0 + i as f64 * 0.01).collect();
        let model = v2ref_core::math::quadrature::integrate_pieces(
            &integrand,
            &breaks,
            v2ref_core::math::quadrature::Tolerance {
                abs: 0.0,
                rel: 1e-9,
            },
        );
        assert!(
            (sample - model).abs() < MC_SIGMAS * se,
            "lag {lag}: {sample} vs {model} ± {se}"
        );
        assert!(
            (sample - 1.02 * model).abs() > MC_SIGMAS * se,
            "no power: relative standard error {}",
            se / model
        );
    }
}

#[test]
fn series_are_deterministic_across_threads() {
    let s = spectrum(1.0, 10.0, 18.0);
    let psd = |nu: f64| s.psd_um2_per_hz(nu);
    let a = synthesize_series(&psd, 1e-3, 100_000, 3, 1).unwrap();
    let b = synthesize_series(&psd, 1e-3, 100_000, 3, 2).unwrap();
    assert_eq!(a, b);
}

#[test]
fn fringe_table_matches_the_nodes_and_the_adaptive_oracle() {
    for source in [Source::Point, Source::uniform_disk(43.0).unwrap()] {
        let o = obs(source);
        let table = FringeTable::new(&o, 60.0).unwrap();
        let nodes = SpectralNodes::new(&o, 60.0, None).unwrap();
        let mut worst: f64 = 0.0;
        for i in 0..4000 {
            let x = -59.9 + i as f64 * 0.029_953;
            worst = worst.max((table.fringe(x) - nodes.fringe(x)).abs());
        }
        assert!(worst < FRINGE_TABLE_CHECK_ABS, "table vs nodes {worst:e}");
        for x in [-41.3, -3.7, 0.0, 0.3, 12.9, 55.0] {
            let slow = v2ref_core::formalism::oracle::fringe_adaptive(&o, x, None);
            assert!(
                (table.fringe(x) - slow).abs() < FRINGE_ORACLE_ABS,
                "x = {x}"
            );
        }
    }
}

#[test]
fn integrating_detector_converges_to_the_sinc_filtered_fringe() {
    let o = obs(Source::Point);
    let table = FringeTable::new(&o, 80.0).unwrap();
    let setup = ScanSetup::paper(300.0);
    let sampling = Sampling::new(128, 0.5, true).unwrap();
    // No piston: the exact average is the sinc(σδx)-filtered fringe.
    let exact = SpectralNodes::new(&o, 80.0, Some(0.5)).unwrap();
    let err = |k: usize, piston: &dyn Fn(f64) -> f64, drift: f64| {
        let got = scan_samples(
            &table,
            &setup,
            Detector::Integrating { sub_samples: k },
            piston,
            0.0,
        )
        .unwrap();
        let nodes = SpectralNodes::new(&o, 80.0, Some(0.5 * (1.0 + drift))).unwrap();
        (0..128)
            .map(|i| {
                let x = sampling.opd_um(i);
                // Sample centre: nominal OPD plus the drift at its time.
                let j = (i + 64) % 128;
                let centre = x + piston(j as f64);
                (got[i] - nodes.fringe(centre)).abs()
            })
            .fold(0.0, f64::max)
    };
    let zero = |_: f64| 0.0;
    // Gauss–Legendre sub-samples converge geometrically: measured maximum
    // errors 8e-2, 1e-3, 1e-8, 2e-13, 1e-13 for K = 1, 2, 4, 6, 8.
    let e: Vec<f64> = [1, 2, 4, 6, 8]
        .iter()
        .map(|&k| err(k, &zero, 0.0))
        .collect();
    assert!(
        e[0] > 1e-2,
        "one sub-sample is the sampled detector: {}",
        e[0]
    );
    assert!(e[1] < e[0] / 10.0 && e[2] < e[1] / 1e4, "{e:?}");
    assert!(e[3] < FRINGE_TABLE_REL && e[4] < FRINGE_TABLE_REL, "{e:?}");
    // Same with the exact filter from the nodes at the centre OPD.
    let eight = scan_samples(
        &table,
        &setup,
        Detector::Integrating { sub_samples: 8 },
        zero,
        0.0,
    )
    .unwrap();
    assert!((0..128)
        .all(|i| (eight[i] - exact.fringe(sampling.opd_um(i))).abs() < FRINGE_TABLE_CHECK_ABS));
    // With a linear piston drift (1 + ε) the average is the fringe filtered
    // by sinc(σ δx (1 + ε)) at the sample centre: sub-sampling converges
    // to it too (the piston is interpolated by a cubic, exact for a line).
    let eps = 0.07;
    let drift = move |tau: f64| eps * 0.5 * (tau - 64.0);
    let e: Vec<f64> = [2, 4, 6].iter().map(|&k| err(k, &drift, eps)).collect();
    assert!(e[0] > e[1] && e[1] > e[2], "{e:?}");
    assert!(
        e[2] < FRINGE_TABLE_CHECK_ABS,
        "drift, 6 sub-samples: {:e}",
        e[2]
    );
}

#[test]
fn zero_turbulence_gives_zero_bias_and_scatter_exactly() {
    let o = obs(Source::uniform_disk(10.0).unwrap());
    for (seeing, baseline) in [(0.0, 18.0), (1.0, 0.0)] {
        let s = spectrum(seeing, 10.0, baseline);
        for det in [Detector::Sampled, Detector::Integrating { sub_samples: 4 }] {
            let r = run(&o, &s, ScanSetup::paper(300.0), det, 50, 1, 0);
            for w in &r.windows {
                for e in [w.v1, w.v2] {
                    assert_eq!((e.mean, e.std), (0.0, 0.0), "{:?}", w.window);
                }
            }
            assert_eq!(r.piston_rms_um, 0.0);
        }
    }
}

#[test]
fn piston_monte_carlo_is_deterministic_across_threads() {
    let o = obs(Source::Point);
    let s = spectrum(1.0, 10.0, 18.0);
    let det = Detector::Integrating { sub_samples: 4 };
    let a = run(&o, &s, ScanSetup::paper(200.0), det, 700, 5, 1);
    let b = run(&o, &s, ScanSetup::paper(200.0), det, 700, 5, 2);
    assert_eq!(a, b);
    let c = run(&o, &s, ScanSetup::paper(200.0), det, 700, 6, 2);
    assert_ne!(a, c);
}

#[test]
fn piston_is_multiplicative_in_a_grey_visibility() {
    let s = spectrum(1.0, 10.0, 18.0);
    let setup = ScanSetup::paper(150.0);
    let p = run(&obs(Source::Point), &s, setup, Detector::Sampled, 300, 9, 0);
    let grey = Source::Constant {
        visibility: num_complex::Complex64::new(0.3, 0.0),
    };
    let g = run(&obs(grey), &s, setup, Detector::Sampled, 300, 9, 0);
    for (wp, wg) in p.windows.iter().zip(&g.windows) {
        for (a, b) in [(wp.v1, wg.v1), (wp.v2, wg.v2)] {
            assert!(
                (b.mean - 0.3 * a.mean).abs() <= VISIBILITY_SCALING_REL * a.std.max(1e-300) + ULPS
            );
            assert!((b.std - 0.3 * a.std).abs() <= VISIBILITY_SCALING_REL * a.std + ULPS);
        }
        assert_abs_eq!(wg.v1_no_piston, 0.3, FRINGE_TABLE_REL);
    }
}

#[test]
fn centred_all_bins_v2_reads_one_sample_and_ignores_piston() {
    // With all N bins, V2 = N² M_0²: centring the packet on the middle
    // sample's piston leaves that sample untouched, while V1 still moves.
    let s = spectrum(1.0, 10.0, 18.0);
    let mut setup = ScanSetup::paper(100.0);
    setup.reference = PistonReference::Centre;
    let r = run(&obs(Source::Point), &s, setup, Detector::Sampled, 300, 2, 0);
    let all = r.window(BinWindow::All);
    assert!(
        all.v2.mean.abs() < ROUNDING_REL && all.v2.std < ROUNDING_REL,
        "{:?}",
        all.v2
    );
    assert!(all.v1.std > 1e-2);
    // The default (scan-mean) reference does move it.
    let r = run(
        &obs(Source::Point),
        &s,
        ScanSetup::paper(100.0),
        Detector::Sampled,
        300,
        2,
        0,
    );
    assert!(r.window(BinWindow::All).v2.std > 1e-3);
}

#[test]
fn wind_speed_rescales_the_fringe_frequency_axis() {
    // Bias and scatter at (f, v) equal those at (2f, 2v) within the Monte
    // Carlo error (independent sequences); at (f, 2v) they do not.
    let o = obs(Source::Point);
    let scans = 3000;
    let a = run(
        &o,
        &spectrum(1.0, 10.0, 18.0),
        ScanSetup::paper(120.0),
        Detector::Sampled,
        scans,
        21,
        0,
    );
    let b = run(
        &o,
        &spectrum(1.0, 20.0, 18.0),
        ScanSetup::paper(240.0),
        Detector::Sampled,
        scans,
        22,
        0,
    );
    let c = run(
        &o,
        &spectrum(1.0, 20.0, 18.0),
        ScanSetup::paper(120.0),
        Detector::Sampled,
        scans,
        23,
        0,
    );
    let z_mean = |x: Summary, y: Summary| (x.mean - y.mean) / x.stderr_mean.hypot(y.stderr_mean);
    let z_std = |x: Summary, y: Summary| (x.std - y.std) / x.stderr_std.hypot(y.stderr_std);
    let (wa, wb, wc) = (
        a.window(BinWindow::Positive),
        b.window(BinWindow::Positive),
        c.window(BinWindow::Positive),
    );
    for (x, y) in [(wa.v1, wb.v1), (wa.v2, wb.v2)] {
        assert!(z_mean(x, y).abs() < MC_SIGMAS, "bias z {}", z_mean(x, y));
        assert!(z_std(x, y).abs() < MC_SIGMAS, "scatter z {}", z_std(x, y));
    }
    assert!(
        z_std(wa.v1, wc.v1).abs() > MC_SIGMAS,
        "no power: {}",
        z_std(wa.v1, wc.v1)
    );
    assert!(
        z_mean(wa.v2, wc.v2).abs() > MC_SIGMAS,
        "no power: {}",
        z_mean(wa.v2, wc.v2)
    );
}

#[test]
fn run_statistics_are_the_running_statistics_of_the_differences() {
    // The results carry montecarlo::Summary: mean, std (n − 1) and their
    // standard errors from the sample fourth moment,
    // se(s²) = √((μ4 − (n−3)/(n−1) s⁴)/n), se(s) = se(s²)/(2s).
    let e = RunningStats::from_values(&[1.0, 2.0, 3.0, 4.0]).summary();
    assert_eq!(e.mean, 2.5);
    assert_abs_eq!(e.std, (5.0f64 / 3.0).sqrt(), ULPS);
    assert_abs_eq!(e.stderr_mean, (5.0f64 / 12.0).sqrt(), ULPS);
    // μ4 = (2·1.5⁴ + 2·0.5⁴)/4 = 2.5625; s² = 5/3; (n−3)/(n−1) = 1/3.
    let want = ((2.5625 - 25.0 / 27.0f64) / 4.0).sqrt() / (2.0 * (5.0f64 / 3.0).sqrt());
    assert_abs_eq!(e.stderr_std, want, ULPS);
}

#[test]
fn a_sweep_frequency_does_not_depend_on_the_others() {
    // Seeds are keyed by the fringe frequency: 300 Hz alone or after 120 Hz
    // gives the same run, equal to simulate at sweep_seed(seed, 300).
    let o = obs(Source::Point);
    let s = spectrum(1.0, 10.0, 18.0);
    let size = RunSize {
        scans: 20,
        seed: 5,
        threads: 0,
    };
    let det = [Detector::Sampled];
    let setup = ScanSetup::paper(1.0);
    let alone = sweep(&o, &s, &[300.0], &setup, &det, &size, None).unwrap();
    let both = sweep(&o, &s, &[120.0, 300.0], &setup, &det, &size, None).unwrap();
    assert_eq!(alone[0], both[1]);
    assert_ne!(both[0][0].seed, both[1][0].seed);
    let direct = run(
        &o,
        &s,
        ScanSetup::paper(300.0),
        Detector::Sampled,
        20,
        sweep_seed(5, 300.0),
        0,
    );
    assert_eq!(alone[0][0], direct);
}

#[test]
fn bad_input_is_refused_with_typed_errors() {
    let o = obs(Source::Point);
    let s = spectrum(1.0, 10.0, 18.0);
    let size = RunSize {
        scans: 10,
        seed: 1,
        threads: 0,
    };
    let go = |setup: ScanSetup, det: Detector, size: RunSize| {
        simulate_piston(&o, &s, &setup, &[det], &size, None)
    };
    assert!(matches!(
        go(ScanSetup::paper(0.0), Detector::Sampled, size),
        Err(Error::OutOfRange {
            param: "fringe_hz",
            ..
        })
    ));
    assert!(matches!(
        go(
            ScanSetup::paper(300.0),
            Detector::Integrating { sub_samples: 0 },
            size
        ),
        Err(Error::OutOfRange {
            param: "sub_samples",
            ..
        })
    ));
    assert!(matches!(
        go(
            ScanSetup::paper(300.0),
            Detector::Sampled,
            RunSize { scans: 1, ..size }
        ),
        Err(Error::OutOfRange { param: "scans", .. })
    ));
    let mut coarse = ScanSetup::paper(300.0);
    coarse.dx_um = 1.2;
    assert!(matches!(
        go(coarse, Detector::Sampled, size),
        Err(Error::Aliasing { .. })
    ));
    // sinc is the detector's transfer function used above.
    assert!((sinc(0.25) - (PI / 4.0).sin() / (PI / 4.0)).abs() < ULPS);
}

#[test]
fn sequence_length_is_even_smooth_and_short() {
    use v2ref_core::piston::sequence_length;
    for len in [1usize, 5, 127, 1000, 1_280_004, 128_004, 999_999] {
        let m = sequence_length(len);
        assert!(m >= len && m >= 4 && m.is_multiple_of(2), "{len} -> {m}");
        let mut r = m;
        for p in [2, 3, 5] {
            while r.is_multiple_of(p) {
                r /= p;
            }
        }
        assert_eq!(r, 1, "{len} -> {m} has a prime factor above 5");
        if len >= 1000 {
            // tol: not a tolerance: 5-smooth lengths above 1000 lie less than 10% apart, so the padding stays within 10%.
            assert!((m as f64) < 1.1 * len as f64, "{len} -> {m}");
        }
    }
}

#[test]
fn three_slope_series_match_their_spectrum_within_the_standard_error() {
    // As for the two-aperture integral: the mean square of the sequences
    // against Σ 2PΔν of the three-slope model, with power against 2 %
    // (2000 sequences: 0.3 % standard error).
    let s = spectrum(1.0, 10.0, 2.0)
        .with_model(v2ref_core::piston::spectrum::PistonPsdModel::ThreeSlope)
        .unwrap();
    let psd = |nu: f64| s.psd_um2_per_hz(nu);
    let (dt, len, reps) = (0.02, 4096, 2000);
    let (want, sd_one) = series_variance(&psd, dt, len);
    let mean_sq: f64 = (0..reps)
        .map(|r| {
            let x = synthesize_series(&psd, dt, len, 7000 + r, 1).unwrap();
            x.iter().map(|v| v * v).sum::<f64>() / len as f64
        })
        .sum::<f64>()
        / reps as f64;
    let se = sd_one / (reps as f64).sqrt();
    assert!(
        (mean_sq - want).abs() < MC_SIGMAS * se,
        "{mean_sq} vs {want} ± {se}"
    );
    assert!(
        (mean_sq - 1.02 * want).abs() > MC_SIGMAS * se,
        "no power: {}",
        se / want
    );
}

#[test]
fn a_sweep_at_1000_hz_alone_equals_1000_hz_after_100_hz_for_any_model_and_threads() {
    let o = obs(Source::Point);
    let det = [Detector::Sampled];
    for model in [
        v2ref_core::piston::spectrum::PistonPsdModel::TwoAperture,
        v2ref_core::piston::spectrum::PistonPsdModel::ThreeSlope,
    ] {
        let s = spectrum(1.0, 10.0, 18.0).with_model(model).unwrap();
        let size = |threads| RunSize {
            scans: 150,
            seed: 11,
            threads,
        };
        let setup = ScanSetup::paper(1000.0);
        let alone = sweep(&o, &s, &[1000.0], &setup, &det, &size(1), None).unwrap();
        let after = sweep(&o, &s, &[100.0, 1000.0], &setup, &det, &size(2), None).unwrap();
        assert_eq!(alone[0], after[1], "{model:?}");
    }
}
