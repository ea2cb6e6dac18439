//! The pipeline of `src/lib.rs` held to v2ref through the oracle route
//! (`v2ref::oracle`), as a pipeline's own `cargo test` does it: everything
//! in memory, nothing read from v2ref's repository.
//!
//! The correct estimator agrees with v2ref row by row and passes the
//! score; each planted bug is rejected by the score of a set with the
//! power to see it.

use downstream::{Instrument, Mistake, Pipeline};
use std::sync::OnceLock;
use v2ref::oracle::{BiasConvention, BinWindow, Estimates, ScoreReport, Set, POWERED_REL_ERROR};

/// Row-by-row agreement with v2ref's own estimates, relative to the
/// calibrated signal: the two compute the same sums in different orders
/// (a naive DFT here, v2ref's windowed sums there), so they differ by
/// rounding, ~1e-13 at N = 64 with photon counts of 50.
const ROW_AGREEMENT_REL: f64 = 1e-9;

/// What the pipeline knows of the set's instrument, from the route's
/// closed forms: the noise model, the mean counts, the calibrator's row.
fn instrument(set: &Set) -> Instrument {
    let inputs = &set.sidecar().inputs;
    Instrument {
        samples: set.samples(),
        read_noise: inputs.read_noise,
        photon_noise: inputs.photon_noise,
        mean_counts: set.mean_counts().to_vec(),
        calibrator_row: set.calibrator_row().to_vec(),
    }
}

/// The score of the pipeline with `mistake` on `set`, both estimators,
/// the positive window and the `model` convention (the pipeline's own).
fn score(set: &Set, mistake: Mistake) -> ScoreReport {
    let pipeline = Pipeline::new(&instrument(set), mistake);
    let (v1_sq, v2_sq) = pipeline.estimate_rows(set.rows());
    set.score(
        BinWindow::Positive,
        BiasConvention::Model,
        Estimates::default().v1_sq(&v1_sq).v2_sq(&v2_sq),
    )
    .unwrap()
}

/// The z-scores of a report, for the failure messages.
fn zs(r: &ScoreReport) -> String {
    r.estimators
        .iter()
        .map(|e| {
            format!(
                "{}: z_mean {:.2}, z_var {:.2}",
                e.estimator.name(),
                e.score.z_mean,
                e.score.z_var
            )
        })
        .collect::<Vec<_>>()
        .join("; ")
}

/// The powered `noise_both` set (photon and detector noise, even
/// N = 64), made once for every test of this file.
fn powered() -> &'static Set {
    static SET: OnceLock<Set> = OnceLock::new();
    SET.get_or_init(|| Set::powered("noise_both").unwrap())
}

#[test]
fn the_pipeline_agrees_with_v2ref_row_by_row() {
    for name in ["noise_both", "short_scan_odd", "bandwidth_disk"] {
        let set = Set::golden(name).unwrap();
        let pipeline = Pipeline::new(&instrument(&set), Mistake::None);
        let theirs = set
            .reference_estimates(BinWindow::Positive, BiasConvention::Model)
            .unwrap();
        let scale = set.truth().v1_sq_spectral.max(set.truth().v2_sq_spectral);
        for (row, r) in set.rows().zip(&theirs) {
            let (v1_sq, v2_sq) = pipeline.estimate(row);
            assert!(
                (v1_sq - r.v1_sq).abs() <= ROW_AGREEMENT_REL * scale,
                "{name}: V1² {v1_sq} against {}",
                r.v1_sq
            );
            assert!(
                (v2_sq - r.v2_sq).abs() <= ROW_AGREEMENT_REL * scale,
                "{name}: V2² {v2_sq} against {}",
                r.v2_sq
            );
        }
    }
}

#[test]
fn the_correct_pipeline_passes_every_piston_free_vector_and_the_powered_set() {
    for name in [
        "noise_gaussian",
        "noise_poisson",
        "noise_both",
        "bandwidth_disk",
        "dispersion",
        "short_scan_odd",
        "integrating",
    ] {
        let r = score(&Set::golden(name).unwrap(), Mistake::None);
        assert!(r.pass, "{name}: {}", zs(&r));
    }
    let r = score(powered(), Mistake::None);
    assert!(r.pass, "powered: {}", zs(&r));
    // The power the set was made for, as the score states it.
    for e in &r.estimators {
        assert!(e.score.min_detectable_rel_bias_mean <= POWERED_REL_ERROR);
        assert!(e.score.min_detectable_rel_bias_var <= POWERED_REL_ERROR);
    }
}

#[test]
fn a_forgotten_photon_bias_is_caught() {
    let r = score(
        &Set::golden("noise_poisson").unwrap(),
        Mistake::ForgottenPhotonBias,
    );
    assert!(!r.pass, "{}", zs(&r));
    let r = score(powered(), Mistake::ForgottenPhotonBias);
    assert!(!r.pass, "{}", zs(&r));
}

#[test]
fn a_wrong_bin_set_is_caught_at_even_n() {
    let set = powered();
    assert_eq!(set.samples() % 2, 0);
    let r = score(set, Mistake::DcAndNyquistBins);
    println!("DC and Nyquist bins, powered noise_both: {}", zs(&r));
    assert!(!r.pass, "{}", zs(&r));
}

#[test]
fn a_v2_bias_weighted_like_v1_is_caught() {
    let r = score(powered(), Mistake::V2BiasLikeV1);
    println!("V2 bias like V1, powered noise_both: {}", zs(&r));
    assert!(!r.pass, "{}", zs(&r));
    // The 1000-row vector alone does not see it: why the powered set.
    let small = score(&Set::golden("noise_both").unwrap(), Mistake::V2BiasLikeV1);
    println!("V2 bias like V1, noise_both (1000 rows): {}", zs(&small));
}
