//! Issue 54, deliverables 4 and 6: the conformance kit in spectral
//! channels — a dispersed set's rows (C × N a row, channel after channel)
//! and each channel's truth, the wide band as one channel bit for bit, the
//! rows of each channel as the channels' Monte Carlo draws them, v2ref's
//! own per-channel estimates passing the set's one family-wise test with
//! and without piston, the test's power (a 2 % error in one channel, two
//! channels swapped), its threshold against statrs, the false-alarm rate
//! over seeds, and the refusals of bad input.

use statrs::distribution::{ContinuousCDF, Normal};
use v2ref_commands::commands::estimate::{
    channel_estimators, estimate_channel_rows, estimator, CalibratorRows, Configuration, RowsName,
};
use v2ref_core::conformance::channel_score::score_channels;
use v2ref_core::conformance::channels::synthesize_channels;
use v2ref_core::conformance::score::DEFAULT_ALPHA;
use v2ref_core::conformance::synth::SetSize;
use v2ref_core::montecarlo::{unit_rng, RunningStats};
use v2ref_core::noise::calibrated::Trials;
use v2ref_core::noise::Formula;
use v2ref_core::oracle::{
    BiasConvention, BinWindow, Channels, Estimates, Inputs, PistonInputs, Set, Sidecar,
    SourceInput, SpectrumInput,
};
use v2ref_core::simulator::channels::{channel_expectations, channel_models, simulate_channels};
use v2ref_core::simulator::{RowLayout, ROWS_PER_UNIT};
use v2ref_core::tolerance::MC_SIGMAS;
use v2ref_core::{assert_rel_eq, assert_within_sigmas};

const WINDOW: BinWindow = BinWindow::Band;
const MODEL: BiasConvention = BiasConvention::Model;

/// H band (1.65 µm, 300 nm), 128 samples of 0.5 µm (bins 1/64 µm⁻¹ apart:
/// each of 6 equal channels, 0.0185 µm⁻¹ wide, holds a bin), a 10 mas
/// uniform disk whose V² falls by a quarter across the band, photon noise.
fn h_band(photons: f64, piston: Option<PistonInputs>) -> Inputs {
    Inputs {
        spectrum: SpectrumInput::Flat {
            wavelength_um: 1.65,
            bandwidth_nm: 300.0,
        },
        source: SourceInput::Ud { diameter_mas: 10.0 },
        samples: 128,
        dx_um: 0.5,
        photons,
        piston,
        ..Inputs::default()
    }
}

fn equal(inputs: &Inputs, count: usize) -> Channels {
    Channels::equal(&inputs.spectrum.spectrum().unwrap(), count).unwrap()
}

/// Per channel, one estimator's values (`v2_sq` or `v1_sq`) of v2ref's
/// own estimates.
fn own(set: &Set, pick: fn(&v2ref_core::oracle::RowEstimate) -> f64) -> Vec<Vec<f64>> {
    set.reference_channel_estimates(WINDOW, MODEL)
        .unwrap()
        .iter()
        .map(|c| c.iter().map(pick).collect())
        .collect()
}

fn both<'a>(v1: &'a [Vec<f64>], v2: &'a [Vec<f64>]) -> Vec<Estimates<'a>> {
    v1.iter()
        .zip(v2)
        .map(|(a, b)| Estimates::default().v1_sq(a).v2_sq(b))
        .collect()
}

fn set_size(rows: u64, seed: u64, blocks: u64, threads: usize, keep: bool) -> SetSize {
    SetSize {
        rows,
        seed,
        reference_blocks: blocks,
        threads,
        keep_continuum: keep,
        layout: RowLayout::default().into(),
    }
}

/// The rows and sidecar of `synthesize_channels`.
fn synth(inputs: &Inputs, channels: &Channels, size: &SetSize) -> (Vec<f64>, Sidecar) {
    let mut rows = Vec::new();
    let mut sink = |b: &[f64]| {
        rows.extend_from_slice(b);
        Ok(())
    };
    let names = ("set.npy".to_owned(), None);
    let sidecar = synthesize_channels(inputs, channels, size, names, &mut sink, &|_| {}).unwrap();
    (rows, sidecar)
}

/// One channel over the whole band is the wide-band set: the same rows
/// and truth, bit for bit, with and without piston; its sidecar differs
/// only by saying so.
#[test]
fn one_channel_is_the_wide_band_set_bit_for_bit() {
    for piston in [None, Some(PistonInputs::paper(300.0))] {
        let inputs = Inputs {
            samples: 32,
            photons: 50.0,
            piston,
            ..Inputs::default()
        };
        let wide = Set::synthesize(&inputs, 300, 9).unwrap();
        let whole = Channels::whole(&inputs.spectrum.spectrum().unwrap());
        let one = Set::synthesize_channels(&inputs, &whole, 300, 9).unwrap();
        assert_eq!(one.channels(), 1);
        assert!(one.values() == wide.values(), "rows differ");
        let listed = one.sidecar().channels.as_ref().unwrap();
        assert_eq!(listed.len(), 1);
        assert_eq!(&listed[0].truth, wide.truth());
        assert_eq!(one.truth(), wide.truth());
        assert_eq!(
            listed[0].continuum_photons,
            wide.sidecar().continuum_photons
        );
        assert_eq!(listed[0].photon_share, 1.0);
        let mut back = one.sidecar().clone();
        (back.channels, back.data.channels) = (None, None);
        assert_eq!(&back, wide.sidecar());
        // Power: another seed changes the rows.
        let other = Set::synthesize_channels(&inputs, &whole, 300, 10).unwrap();
        assert!(other.values() != wide.values());
    }
}

/// Channel j's samples of every row are what channel j draws when the
/// channels draw in order from each unit's one generator (rebuilt here
/// from `channel_models` and `Rows::fill_unit`), across a unit boundary,
/// with and without piston, on 1 and 2 threads; with the continuum kept
/// each channel's own c_i is added.
#[test]
fn each_channels_rows_are_the_channels_draws() {
    for piston in [None, Some(PistonInputs::paper(300.0))] {
        let inputs = Inputs {
            samples: 48,
            dx_um: 0.9,
            photons: 30.0,
            piston,
            ..Inputs::default()
        };
        let channels = equal(&inputs, 3);
        // Across a unit boundary without piston; a short set with it.
        let rows = match piston {
            None => ROWS_PER_UNIT + 37,
            Some(_) => 300,
        };
        // The set on 2 threads, the draws below on 1.
        let (values, sidecar) = synth(&inputs, &channels, &set_size(rows, 4, 0, 2, false));
        let models = channel_models(&inputs, &channels).unwrap();
        let sets: Vec<_> = models.iter().map(|m| m.rows(rows, 4, 1).unwrap()).collect();
        let mut drawn = vec![Vec::new(); 3];
        for u in 0..sets[0].units() {
            let mut rng = unit_rng(4, u);
            for (s, d) in sets.iter().zip(&mut drawn) {
                s.fill_unit(u, &mut rng, d).unwrap();
            }
        }
        let n = 48;
        // Power: the channels' draws differ from each other.
        assert!(drawn[0] != drawn[1]);
        for (j, d) in drawn.iter().enumerate() {
            let mine: Vec<f64> = values
                .chunks_exact(3 * n)
                .flat_map(|r| &r[j * n..(j + 1) * n])
                .copied()
                .collect();
            assert!(&mine == d, "channel {j} differs from its draws");
        }
        assert_eq!(sidecar.data.channels, Some(3));
        assert_eq!(sidecar.channel_count(), 3);
        // Kept continuum: the same draws plus each channel's c_i (without
        // piston: its sequence is long to draw again).
        if piston.is_some() {
            continue;
        }
        let (kept, kept_sidecar) = synth(&inputs, &channels, &set_size(rows, 4, 0, 1, true));
        let listed = kept_sidecar.channels.unwrap();
        for (row, (k, m)) in kept
            .chunks_exact(3 * n)
            .zip(values.chunks_exact(3 * n))
            .enumerate()
        {
            for j in 0..3 {
                for i in 0..n {
                    let c = listed[j].continuum_photons[i];
                    assert_eq!(k[j * n + i], m[j * n + i] + c, "row {row} channel {j}");
                }
            }
        }
    }
}

/// Each channel's truth is its own channel's: without piston its means
/// and its `model` variance are the channel's closed forms
/// (`channel_expectations`, exact: the truth's stated error is 0), and
/// its means and both conventions' variances lie within 5σ (the truth's
/// own stated error and an independent Monte Carlo's, combined) of
/// `simulate_channels` run on other seeds; the Monte Carlo rejects each
/// mean made 2 % larger.
#[test]
fn each_channels_truth_is_its_closed_form_and_its_monte_carlo() {
    let inputs = h_band(600.0, None);
    let channels = equal(&inputs, 6);
    let set = Set::synthesize_channels(&inputs, &channels, 1000, 3).unwrap();
    let models = channel_models(&inputs, &channels).unwrap();
    let closed = channel_expectations(&models, WINDOW, Formula::Exact).unwrap();
    for (j, e) in closed.iter().enumerate() {
        let t = set.expected_channel(j, WINDOW, MODEL).unwrap();
        assert_within_sigmas!(
            t.v1_sq.mean,
            e.mean_v1_sq,
            t.v1_sq.stderr_mean.max(f64::MIN_POSITIVE)
        );
        assert_within_sigmas!(
            t.v2_sq.mean,
            e.mean_v2_sq,
            t.v2_sq.stderr_mean.max(f64::MIN_POSITIVE)
        );
        assert_rel_eq!(t.v1_sq.var, e.var_v1_sq.unwrap());
        assert_rel_eq!(t.v2_sq.var, e.var_v2_sq.unwrap());
    }
    for bias in [BiasConvention::Model, BiasConvention::Counts] {
        let size = Trials {
            trials: 100_000,
            seed: 77,
            threads: 0,
        };
        let mc = simulate_channels(&models, WINDOW, bias, size).unwrap();
        for j in 0..6 {
            let t = set.expected_channel(j, WINDOW, bias).unwrap();
            for (truth, run) in [(&t.v1_sq, &mc.v1_sq[j]), (&t.v2_sq, &mc.v2_sq[j])] {
                let se_mean = run.stderr_mean.hypot(truth.stderr_mean);
                let se_var = run.stderr_var.hypot(truth.stderr_var);
                eprintln!(
                    "{} channel {j}: mean {} vs truth {} ± {se_mean}; var {} vs {} ± {se_var}",
                    bias.name(),
                    run.mean,
                    truth.mean,
                    run.var,
                    truth.var
                );
                assert_within_sigmas!(run.mean, truth.mean, se_mean);
                assert_within_sigmas!(run.var, truth.var, se_var);
                // Power: a mean 2 % off lies beyond the tolerance.
                assert!((run.mean - 1.02 * truth.mean).abs() > MC_SIGMAS * se_mean);
            }
        }
    }
}

/// v2ref's own per-channel estimates pass the set's one test, 6 H-band
/// channels, without piston and with it; the power each channel's score
/// states is printed.
#[test]
fn own_estimates_pass_every_channel_with_and_without_piston() {
    for (piston, rows) in [(None, 3000), (Some(PistonInputs::paper(300.0)), 300)] {
        let inputs = h_band(600.0, piston);
        let set = Set::synthesize_channels(&inputs, &equal(&inputs, 6), rows, 11).unwrap();
        let v1 = own(&set, |r| r.v1_sq);
        let v2 = own(&set, |r| r.v2_sq);
        let report = set.score_channels(WINDOW, MODEL, &both(&v1, &v2)).unwrap();
        eprintln!("{report}");
        assert!(report.pass, "{report}");
        assert_eq!((report.tests, report.channels.len()), (24, 6));
        // The counts convention too.
        let counts: Vec<Vec<f64>> = set
            .reference_channel_estimates(WINDOW, BiasConvention::Counts)
            .unwrap()
            .iter()
            .map(|c| c.iter().map(|r| r.v2_sq).collect())
            .collect();
        let e: Vec<Estimates> = counts
            .iter()
            .map(|x| Estimates::default().v2_sq(x))
            .collect();
        let r = set
            .score_channels(WINDOW, BiasConvention::Counts, &e)
            .unwrap();
        assert!(r.pass, "{r}");
    }
}

/// The set's power: where each channel's stated smallest detectable error
/// of the V2² mean is under 2 %, a pipeline 2 % off in one channel's V2²
/// fails the set (that channel alone out), and a pipeline that swaps two
/// channels fails it.
#[test]
fn a_two_percent_error_in_one_channel_and_a_swap_fail_the_set() {
    let inputs = h_band(600.0, None);
    let set = Set::synthesize_channels(&inputs, &equal(&inputs, 6), 3000, 5).unwrap();
    let v1 = own(&set, |r| r.v1_sq);
    let v2 = own(&set, |r| r.v2_sq);
    let good = set.score_channels(WINDOW, MODEL, &both(&v1, &v2)).unwrap();
    assert!(good.pass, "{good}");
    for c in &good.channels {
        let power = c.estimators[1].score.min_detectable_rel_bias_mean;
        // tol: the 2 % error planted below must be within the stated reach.
        assert!(power < 0.02, "stated power {power}: the set is too small");
    }
    let mut off = v2.clone();
    off[3].iter_mut().for_each(|x| *x *= 1.02);
    let bad = set.score_channels(WINDOW, MODEL, &both(&v1, &off)).unwrap();
    eprintln!("{bad}");
    assert!(!bad.pass, "{bad}");
    let out: Vec<bool> = bad.channels.iter().map(|c| c.pass).collect();
    assert_eq!(out, [true, true, true, false, true, true]);
    let (mut s1, mut s2) = (v1.clone(), v2.clone());
    s1.swap(0, 5);
    s2.swap(0, 5);
    let swapped = set.score_channels(WINDOW, MODEL, &both(&s1, &s2)).unwrap();
    eprintln!("{swapped}");
    assert!(!swapped.pass && !swapped.channels[0].pass && !swapped.channels[5].pass);
}

/// The threshold is one Bonferroni quantile over every test of every
/// channel, `Φ⁻¹(1 − α/(2·C·2·E))`, computed here with statrs: 6 channels
/// with both estimators (24 tests), 4 with V2² alone (8 tests).
#[test]
fn the_threshold_is_bonferroni_over_every_channel() {
    let inputs = h_band(600.0, None);
    let set = Set::synthesize_channels(&inputs, &equal(&inputs, 6), 200, 1).unwrap();
    let v1 = own(&set, |r| r.v1_sq);
    let v2 = own(&set, |r| r.v2_sq);
    let phi = Normal::new(0.0, 1.0).unwrap();
    let r = set.score_channels(WINDOW, MODEL, &both(&v1, &v2)).unwrap();
    assert_rel_eq!(
        r.z_crit,
        phi.inverse_cdf(1.0 - DEFAULT_ALPHA / (2.0 * 6.0 * 2.0 * 2.0))
    );
    assert_eq!(r.tests, 24);
    for c in &r.channels {
        assert!(c.estimators.iter().all(|e| e.score.z_crit == r.z_crit));
    }
    let truths: Vec<_> = (0..4)
        .map(|j| set.expected_channel(j, WINDOW, MODEL).unwrap())
        .collect();
    let e: Vec<Estimates> = v2[..4]
        .iter()
        .map(|x| Estimates::default().v2_sq(x))
        .collect();
    let four = score_channels(&e, &truths, 200, 0.01).unwrap();
    assert_eq!(four.tests, 8);
    assert_rel_eq!(four.z_crit, phi.inverse_cdf(1.0 - 0.01 / (2.0 * 4.0 * 2.0)));
}

/// Over 24 seeds of a small piston-free 4-channel set, each channel's
/// z-scores of V1² and V2² (mean and variance, 96 of each) have mean 0 and
/// standard deviation 1 within 5 standard errors: the truth's σ is honest
/// in every channel.
#[test]
fn z_scores_over_seeds_are_standard_normal_in_every_channel() {
    let inputs = Inputs {
        samples: 128,
        dx_um: 0.5,
        photons: 200.0,
        ..Inputs::default()
    };
    let channels = equal(&inputs, 4);
    let mut z = [RunningStats::default(); 4];
    for seed in 0..24 {
        let (values, sidecar) = synth(&inputs, &channels, &set_size(400, seed, 0, 0, false));
        let est = channel_estimators(&inputs, &channels, (WINDOW, MODEL), true, None, 0).unwrap();
        let name = RowsName {
            param: "interferograms",
            path: None,
        };
        let per = estimate_channel_rows(&est, name, (&values, 0), 0).unwrap();
        let v1: Vec<Vec<f64>> = per
            .iter()
            .map(|c| c.iter().map(|r| r.v1_sq).collect())
            .collect();
        let v2: Vec<Vec<f64>> = per
            .iter()
            .map(|c| c.iter().map(|r| r.v2_sq).collect())
            .collect();
        let listed = sidecar.channels.as_ref().unwrap();
        let truths: Vec<_> = listed
            .iter()
            .map(|c| {
                let w = c.truth.windows.iter().find(|w| w.bins == WINDOW).unwrap();
                w.conventions.iter().find(|t| t.bias == MODEL).unwrap()
            })
            .collect();
        let r = score_channels(&both(&v1, &v2), &truths, 400, DEFAULT_ALPHA).unwrap();
        for (k, kind) in z.iter_mut().enumerate() {
            for c in &r.channels {
                let s = &c.estimators[k / 2].score;
                kind.push(if k % 2 == 0 { s.z_mean } else { s.z_var });
            }
        }
    }
    for (k, s) in z.iter().enumerate() {
        let n = s.count as f64;
        eprintln!("z {k}: mean {} sd {} over {n}", s.mean, s.std());
        assert_within_sigmas!(s.mean, 0.0, 1.0 / n.sqrt());
        assert_within_sigmas!(s.std(), 1.0, 1.0 / (2.0 * (n - 1.0)).sqrt());
        // Power: a σ a third too small (z 1.5 times too wide) is rejected.
        assert!((1.5 * s.std() - 1.0).abs() > MC_SIGMAS / (2.0 * (n - 1.0)).sqrt());
    }
}

/// Bad input, each a typed error naming the parameter and what to fix:
/// estimates of another number of channels, a channel with no estimator,
/// rows not a whole number of C × N values, a calibrator of another
/// width, a sidecar whose channels overlap or leave the band (its JSON
/// edited), and the wide-band methods on a dispersed set.
#[test]
fn bad_channel_input_is_refused_naming_what_to_fix() {
    let inputs = Inputs {
        samples: 48,
        dx_um: 0.9,
        photons: 30.0,
        ..Inputs::default()
    };
    let channels = equal(&inputs, 3);
    let set = Set::synthesize_channels(&inputs, &channels, 50, 2).unwrap();
    let v2 = own(&set, |r| r.v2_sq);
    let two: Vec<Estimates> = v2[..2]
        .iter()
        .map(|x| Estimates::default().v2_sq(x))
        .collect();
    let e = set.score_channels(WINDOW, MODEL, &two).unwrap_err();
    assert_eq!(e.param(), Some("estimates"));
    assert!(e.to_string().contains("has 3 channels"), "{e}");
    let mut none: Vec<Estimates> = v2.iter().map(|x| Estimates::default().v2_sq(x)).collect();
    none[1] = Estimates::default();
    let e = set.score_channels(WINDOW, MODEL, &none).unwrap_err();
    assert!(e.to_string().contains("channel 2 has no estimator"), "{e}");
    let short: Vec<Vec<f64>> = v2.iter().map(|x| x[..49].to_vec()).collect();
    let e: Vec<Estimates> = short
        .iter()
        .map(|x| Estimates::default().v2_sq(x))
        .collect();
    let e = set.score_channels(WINDOW, MODEL, &e).unwrap_err();
    assert!(e.to_string().contains("channel 1: 49 rows"), "{e}");
    // Rows of another width.
    let est = channel_estimators(&inputs, &channels, (WINDOW, MODEL), true, None, 1).unwrap();
    let name = RowsName {
        param: "interferograms",
        path: None,
    };
    let e = estimate_channel_rows(&est, name, (&set.values()[..3 * 48 * 2 - 1], 0), 1).unwrap_err();
    assert_eq!(e.param(), Some("interferograms"));
    assert!(e.to_string().contains("C x N = 3 x 48"), "{e}");
    let cal = CalibratorRows {
        name: RowsName {
            param: "calibrator",
            path: None,
        },
        rows: &set.values()[..48 * 4],
        cols: 48,
    };
    let e =
        channel_estimators(&inputs, &channels, (WINDOW, MODEL), true, Some(cal), 1).unwrap_err();
    assert_eq!(e.param(), Some("calibrator"));
    assert!(e.to_string().contains("C = 3 channels of N = 48"), "{e}");
    // A non-finite value names its row and channel.
    let mut bad = set.values()[..3 * 48 * 4].to_vec();
    bad[2 * 144 + 48 + 5] = f64::NAN;
    let e = estimate_channel_rows(&est, name, (&bad, 0), 1).unwrap_err();
    assert!(e.to_string().contains("channel 2"), "{e}");
    assert!(e.to_string().contains("row 3"), "{e}");
    // A sidecar edited: overlapping channels, a channel out of the band.
    let json = set.sidecar_json();
    let sidecar = Sidecar::from_json(&json, std::path::Path::new("set.json")).unwrap();
    assert_eq!(sidecar.channels().unwrap().unwrap(), channels);
    let edit = |j: usize, k: usize, shift: f64| {
        let mut v: serde_json::Value = serde_json::from_str(&json).unwrap();
        let edge = &mut v["channels"][j]["wavenumber_edges_per_um"][k];
        *edge = (edge.as_f64().unwrap() + shift).into();
        serde_json::to_string_pretty(&v).unwrap()
    };
    // Channel 2 starting inside channel 1; channel 1 starting below the band.
    let (overlap, outside) = (edit(1, 0, -0.005), edit(0, 0, -0.05));
    for (what, text) in [("overlap", overlap), ("lies outside the band", outside)] {
        assert_ne!(text, json);
        let edited = Sidecar::from_json(&text, std::path::Path::new("set.json")).unwrap();
        let e = edited.channels().unwrap_err();
        assert_eq!(e.param(), Some("channels"), "{e}");
        assert!(e.to_string().contains(what), "{e}");
        let e = Configuration::read_sidecar(edited).unwrap_err();
        assert_eq!(e.param(), Some("channels"));
    }
    // The sidecar's configuration knows its channels: rows of C x N values.
    let config = Configuration::read_sidecar(sidecar).unwrap();
    assert_eq!(config.channel_count(), 3);
    let e = config.inputs_for(name, 50, 3 * 48 + 1).unwrap_err();
    assert!(e.to_string().contains("C = 3 channels"), "{e}");
    assert_eq!(config.inputs_for(name, 50, 3 * 48).unwrap().samples, 48);
    // The wide-band methods refuse a dispersed set; a channel it lacks.
    let e = set
        .score(WINDOW, MODEL, Estimates::default().v2_sq(&v2[0]))
        .unwrap_err();
    assert_eq!(e.param(), Some("channels"));
    assert!(set.reference_estimates(WINDOW, MODEL).is_err());
    let e = set.expected_channel(3, WINDOW, MODEL).unwrap_err();
    assert_eq!(e.param(), Some("channel"));
    // Channels of another spectrum.
    let k = Channels::equal(&h_band(1.0, None).spectrum.spectrum().unwrap(), 3).unwrap();
    let e = Set::synthesize_channels(&inputs, &k, 50, 2).unwrap_err();
    assert_eq!(e.param(), Some("channels"));
}

/// The estimate command's channel estimators: one channel over the whole
/// band is the wide-band estimator bit for bit; a calibrator's rows of
/// C × N values normalize each channel by its own channel of them.
#[test]
fn channel_estimators_of_one_channel_are_the_wide_band_estimator() {
    let inputs = Inputs {
        samples: 32,
        photons: 80.0,
        ..Inputs::default()
    };
    let set = Set::synthesize(&inputs, 200, 6).unwrap();
    let whole = Channels::whole(&inputs.spectrum.spectrum().unwrap());
    let name = RowsName {
        param: "interferograms",
        path: None,
    };
    let est = channel_estimators(&inputs, &whole, (WINDOW, MODEL), true, None, 1).unwrap();
    let per = estimate_channel_rows(&est, name, (set.values(), 0), 1).unwrap();
    let alone = estimator(&inputs, (WINDOW, MODEL), true, None, 1).unwrap();
    assert_eq!(per[0], alone.estimate_rows(set.values(), 1).unwrap());
    // A calibrator: a point source's dispersed rows.
    let point = Inputs {
        source: SourceInput::Point,
        samples: 128,
        dx_um: 0.5,
        ..h_band(600.0, None)
    };
    let channels = equal(&point, 6);
    let cal = Set::synthesize_channels(&point, &channels, 400, 8).unwrap();
    let rows = CalibratorRows {
        name: RowsName {
            param: "calibrator",
            path: None,
        },
        rows: cal.values(),
        cols: 6 * 128,
    };
    let by_cal =
        channel_estimators(&point, &channels, (WINDOW, MODEL), true, Some(rows), 1).unwrap();
    let by_model = channel_estimators(&point, &channels, (WINDOW, MODEL), true, None, 1).unwrap();
    for (j, (c, m)) in by_cal.iter().zip(&by_model).enumerate() {
        // The calibration from its own rows: the model's within the noise
        // of 400 rows (a point source normalizes to 1).
        let (from_rows, model) = (c.calibration().v2_sq, m.calibration().v2_sq);
        let t = cal.expected_channel(j, WINDOW, MODEL).unwrap();
        let se = t.v2_sq.set_stderr_mean * model;
        eprintln!("channel {j}: calibration {from_rows} vs model {model} ± {se}");
        assert_within_sigmas!(from_rows, model, se);
        assert_ne!(from_rows, model);
    }
}
