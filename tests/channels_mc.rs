//! Issue 54, the channels' Monte Carlo: each channel's mean and variance
//! against its closed form, the wide band as one channel bit for bit, and
//! the piston shared across channels — their correlation, and the honest
//! σ of a weighted mean of the channels against the Monte Carlo's spread.

use v2ref_core::assert_within_sigmas;
use v2ref_core::conformance::estimate::BiasConvention;
use v2ref_core::formalism::channels::Channels;
use v2ref_core::formalism::estimator::BinWindow;
use v2ref_core::noise::calibrated::Trials;
use v2ref_core::noise::Formula;
use v2ref_core::simulator::channels::{
    channel_expectations, channel_models, simulate_channels, ChannelRun,
};
use v2ref_core::simulator::{simulate, Inputs, Model, PistonInputs};
use v2ref_core::tolerance::MC_SIGMAS;

/// K band, 128 samples of 0.5 µm (bins 1/64 µm⁻¹ apart), three channels of
/// two bins each.
fn inputs(photons: f64, photon_noise: bool, piston: Option<PistonInputs>) -> Inputs {
    Inputs {
        photons,
        photon_noise,
        read_noise: if photon_noise { 2.0 } else { 0.0 },
        piston,
        ..Inputs::default()
    }
}

fn run(inputs: &Inputs, count: usize, trials: u64, seed: u64, threads: usize) -> ChannelRun {
    let spectrum = inputs.spectrum.spectrum().unwrap();
    let channels = Channels::equal(&spectrum, count).unwrap();
    let models = channel_models(inputs, &channels).unwrap();
    let size = Trials {
        trials,
        seed,
        threads,
    };
    simulate_channels(&models, BinWindow::Band, BiasConvention::Model, size).unwrap()
}

/// Each channel's Monte Carlo mean and variance within 5σ of the closed
/// forms of its own photons; a closed form off by 2 % would be rejected;
/// with the noise alone the channels are independent.
#[test]
fn each_channel_matches_its_closed_form_and_noise_leaves_channels_independent() {
    let inputs = inputs(600.0, true, None);
    let spectrum = inputs.spectrum.spectrum().unwrap();
    let models = channel_models(&inputs, &Channels::equal(&spectrum, 3).unwrap()).unwrap();
    let trials = 400_000;
    let r = run(&inputs, 3, trials, 21, 0);
    let mut variances = Vec::new();
    let closed = channel_expectations(&models, BinWindow::Band, Formula::Exact).unwrap();
    for (c, e) in closed.iter().enumerate() {
        let (var1, var2) = (e.var_v1_sq.unwrap(), e.var_v2_sq.unwrap());
        eprintln!(
            "channel {c}: V1² {} ± {} (closed {}), var {} ± {} (closed {var1}); V2² var {} ± {} (closed {var2})",
            r.v1_sq[c].mean, r.v1_sq[c].stderr_mean, e.mean_v1_sq, r.v1_sq[c].var,
            r.v1_sq[c].stderr_var, r.v2_sq[c].var, r.v2_sq[c].stderr_var
        );
        assert_within_sigmas!(r.v1_sq[c].mean, e.mean_v1_sq, r.v1_sq[c].stderr_mean);
        assert_within_sigmas!(r.v2_sq[c].mean, e.mean_v2_sq, r.v2_sq[c].stderr_mean);
        assert_within_sigmas!(r.v1_sq[c].var, var1, r.v1_sq[c].stderr_var);
        assert_within_sigmas!(r.v2_sq[c].var, var2, r.v2_sq[c].stderr_var);
        // Power: a variance 2 % off lies beyond the tolerance.
        assert!((r.v1_sq[c].var - 1.02 * var1).abs() > MC_SIGMAS * r.v1_sq[c].stderr_var);
        assert!((r.v2_sq[c].var - 1.02 * var2).abs() > MC_SIGMAS * r.v2_sq[c].stderr_var);
        variances.push(var1);
    }
    // Independent channels: each correlation within 5σ (1/√n) of zero.
    let rho = r.v1_sq_moments.correlation();
    eprintln!("noise-only correlation of V1²: {rho:?}");
    for (i, row) in rho.iter().enumerate() {
        for (j, &x) in row.iter().enumerate() {
            if i != j {
                assert!(
                    x.abs() < MC_SIGMAS / (trials as f64).sqrt(),
                    "rho[{i}][{j}] = {x}"
                );
            }
        }
    }
    // The weighted mean's variance is then Σ w² var_c, the closed forms'.
    let w = [1.0 / 3.0; 3];
    let (honest, se) = r.v1_sq_moments.combined_variance(&w);
    let independent: f64 = variances.iter().map(|v| v / 9.0).sum();
    eprintln!(
        "noise-only weighted mean: var {honest} ± {se}, independent closed form {independent}"
    );
    assert_within_sigmas!(honest, independent, se);
}

/// The wide band as one channel is `simulate` bit for bit, with and
/// without piston.
#[test]
fn one_channel_run_is_simulate_bit_for_bit() {
    for piston in [None, Some(PistonInputs::paper(300.0))] {
        let inputs = Inputs {
            samples: 64,
            ..inputs(10.0, true, piston)
        };
        let one = run(&inputs, 1, 3000, 5, 0);
        let size = Trials {
            trials: 3000,
            seed: 5,
            threads: 0,
        };
        let model = Model::new(&inputs).unwrap();
        let alone = simulate(
            &model,
            BinWindow::Band,
            BiasConvention::Model,
            Formula::Exact,
            size,
            &|_| {},
        );
        // Without piston `simulate` takes its fast path (raw moments,
        // normalized at the end): compared with the counts convention's
        // row-by-row path, which the channels' run shares.
        let alone = match piston {
            Some(_) => alone.unwrap(),
            None => simulate(
                &model,
                BinWindow::Band,
                BiasConvention::Counts,
                Formula::Exact,
                size,
                &|_| {},
            )
            .unwrap(),
        };
        let one = match piston {
            Some(_) => one,
            None => {
                let spectrum = inputs.spectrum.spectrum().unwrap();
                let models = channel_models(&inputs, &Channels::whole(&spectrum)).unwrap();
                simulate_channels(&models, BinWindow::Band, BiasConvention::Counts, size).unwrap()
            }
        };
        assert_eq!(one.v1_sq[0], alone.v1_sq);
        assert_eq!(one.v2_sq[0], alone.v2_sq);
    }
}

/// The piston dominates: one OPD for all channels correlates their errors,
/// and the weighted mean's σ is `√(wᵀΣw)` — the spread of an independent
/// run — not σ/√C; the run is the same bits on 1 and 2 threads.
#[test]
fn the_shared_piston_correlates_channels_and_sets_the_weighted_mean_sigma() {
    let inputs = inputs(1000.0, false, Some(PistonInputs::paper(300.0)));
    let trials = 4000;
    let a = run(&inputs, 3, trials, 31, 1);
    assert_eq!(
        a,
        run(&inputs, 3, trials, 31, 2),
        "same seed, other thread count"
    );
    let b = run(&inputs, 3, trials, 32, 0);
    let rho = a.v1_sq_moments.correlation();
    eprintln!("piston correlation of V1²: {rho:?}");
    eprintln!(
        "piston correlation of V2²: {:?}",
        a.v2_sq_moments.correlation()
    );
    let w = [1.0 / 3.0; 3];
    for (ma, mb, name) in [
        (&a.v1_sq_moments, &b.v1_sq_moments, "V1²"),
        (&a.v2_sq_moments, &b.v2_sq_moments, "V2²"),
    ] {
        let (honest, se_a) = ma.combined_variance(&w);
        let (spread, se_b) = mb.combined_variance(&w);
        let independent = ma.independent_variance(&w);
        let se = (se_a * se_a + se_b * se_b).sqrt();
        eprintln!(
            "{name}: honest var {honest} ± {se_a} (seed 31), spread {spread} ± {se_b} (seed 32), σ²/C form {independent}"
        );
        assert_within_sigmas!(honest, spread, se);
        // Power: the σ/√C form lies far outside the spread's tolerance.
        assert!(
            (spread - independent).abs() > 2.0 * MC_SIGMAS * se,
            "{name}"
        );
    }
}

/// The channels' models share one piston spectrum (its tables are
/// computed once per run, not once per channel: the cost of C channels),
/// and the run is the same bits as with a spectrum of its own per
/// channel, as the models had before they shared it.
#[test]
fn channels_share_one_piston_spectrum_and_keep_their_bits() {
    let inputs = Inputs {
        samples: 64,
        ..inputs(10.0, true, Some(PistonInputs::paper(300.0)))
    };
    let spectrum = inputs.spectrum.spectrum().unwrap();
    let shared = channel_models(&inputs, &Channels::equal(&spectrum, 2).unwrap()).unwrap();
    let table = |m: &Model| m.piston_spectrum.as_ref().unwrap().table().clone();
    assert!(
        std::sync::Arc::ptr_eq(&table(&shared[0]), &table(&shared[1])),
        "each channel has its own piston spectrum"
    );
    let mut own = shared.clone();
    for m in &mut own {
        let p = inputs.piston.as_ref().unwrap();
        m.piston_spectrum = Some(p.spectrum(m.observation.baseline_m).unwrap());
    }
    assert!(!std::sync::Arc::ptr_eq(&table(&own[0]), &table(&own[1])));
    let size = Trials {
        trials: 2000,
        seed: 9,
        threads: 0,
    };
    let run = |models: &[Model]| {
        simulate_channels(models, BinWindow::Band, BiasConvention::Model, size).unwrap()
    };
    assert_eq!(run(&shared), run(&own));
}
