//! The truth of a synth set: what each estimator should give, under every
//! window of bins and bias convention, and how much a set of this size
//! scatters around it.
//!
//! - Closed forms where they exist (no piston): the mean of both
//!   conventions (`(signal + exact bias − subtracted bias)/C`, and the
//!   counts convention subtracts an unbiased estimate of the exact bias, so
//!   its mean is the same), and the variance of the `model` convention (the
//!   exact windowed variance, [`crate::noise::window_variance`]).
//! - Everything else from an independent reference run: `blocks`
//!   replicates of the set (same configuration and size, seeds
//!   [`reference_seed`]`(seed, b)`, an independent piston sequence each),
//!   estimated the same way. The mean of the block means and of the block
//!   variances are the truth; their spread over blocks is the spread of a
//!   set of this size — including the correlation of consecutive piston
//!   scans, which the naive `var/rows` would miss.

use crate::conformance::estimate::{BiasConvention, RowEstimator, BIAS_CONVENTIONS};
use crate::conformance::sidecar::{
    ConventionTruth, EstimatorTruth, ReferenceRun, Truth, TruthSource, WindowTruth,
};
use crate::error::Result;
use crate::formalism::estimator::{
    dft, noise_bias, raw_estimates, wide_band, BinWindow, Pair, BIN_WINDOWS,
};
use crate::montecarlo::{derive_seed, RunningStats};
use crate::noise::calibrated::{expectation, CalibratedExpectation};
use crate::noise::Formula;
use crate::simulator::Model;

/// The size of a set and of its reference run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TruthSize {
    /// Rows of the set.
    pub rows: u64,
    /// The set's seed.
    pub seed: u64,
    /// Replicates of the set in the reference run (0: none).
    pub reference_blocks: u64,
    /// Worker threads (0: all); the truth does not depend on it.
    pub threads: usize,
}

/// The seed of replicate `block` of the reference run of a set of seed
/// `seed`.
pub fn reference_seed(seed: u64, block: u64) -> u64 {
    derive_seed(seed, "reference", &[block as f64])
}

/// One estimator of one window and convention, over the blocks: the mean
/// and variance of each block.
#[derive(Debug, Clone, Default)]
struct BlockMoments {
    means: RunningStats,
    vars: RunningStats,
}

/// The windows whose calibrator has a fringe (others are left out of the
/// truth).
fn usable_windows(model: &Model) -> Vec<BinWindow> {
    BIN_WINDOWS
        .iter()
        .copied()
        .filter(|&w| model.calibrated_setup(w).calibration().is_ok())
        .collect()
}

/// The truth of a set of `size.rows` rows of `model`; `progress` is called
/// with the rows of the reference run done since its last call.
pub fn truth(model: &Model, size: TruthSize, progress: &(dyn Fn(u64) + Sync)) -> Result<Truth> {
    let obs = &model.observation;
    let wb = wide_band(obs);
    let v2 = model.inputs.visibility * model.inputs.visibility;
    let windows = usable_windows(model);
    let reference = reference_run(model, &windows, size, progress)?;
    let piston = model.inputs.piston.is_some();
    let mut out = Vec::new();
    for (w, blocks) in windows.iter().zip(&reference) {
        out.push(window_truth(model, *w, blocks, size, piston)?);
    }
    Ok(Truth {
        sigma_eff_per_um: wb.sigma_eff_per_um,
        spatial_freq_cpas: wb.spatial_freq_cpas,
        v_sigma_eff: model.inputs.visibility * wb.v_mono,
        v1_sq_spectral: v2 * wb.v1_sq,
        v2_sq_spectral: v2 * wb.v2_sq,
        windows: out,
        reference_run: ReferenceRun {
            seed: reference_seed(size.seed, 0),
            blocks: size.reference_blocks,
            rows_per_block: size.rows,
        },
    })
}

/// Per window, per convention: the block moments of V1² and V2².
type Reference = Vec<Vec<[BlockMoments; 2]>>;

/// The reference run: `size.reference_blocks` replicates of the set.
fn reference_run(
    model: &Model,
    windows: &[BinWindow],
    size: TruthSize,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Reference> {
    let estimators = windows
        .iter()
        .map(|&w| {
            BIAS_CONVENTIONS
                .iter()
                .map(|&c| RowEstimator::new(model, w, c, true))
                .collect::<Result<Vec<_>>>()
        })
        .collect::<Result<Vec<_>>>()?;
    let mut acc: Reference = vec![vec![Default::default(); BIAS_CONVENTIONS.len()]; windows.len()];
    let n = model.samples();
    for b in 0..size.reference_blocks {
        let rows = model.rows(size.rows, reference_seed(size.seed, b), size.threads)?;
        let parts = rows.map_units(0..rows.units(), size.threads, |_, block| {
            let mut s =
                vec![vec![[RunningStats::default(); 2]; BIAS_CONVENTIONS.len()]; windows.len()];
            for row in block.chunks_exact(n) {
                for (sw, ew) in s.iter_mut().zip(&estimators) {
                    for (sc, e) in sw.iter_mut().zip(ew) {
                        let r = e.estimate(row);
                        sc[0].push(r.v1_sq);
                        sc[1].push(r.v2_sq);
                    }
                }
            }
            progress((block.len() / n) as u64);
            s
        });
        for (wi, aw) in acc.iter_mut().enumerate() {
            for (ci, ac) in aw.iter_mut().enumerate() {
                for (k, moments) in ac.iter_mut().enumerate() {
                    let mut total = RunningStats::default();
                    for p in &parts {
                        total.merge(&p[wi][ci][k]);
                    }
                    moments.means.push(total.mean);
                    moments.vars.push(total.variance());
                }
            }
        }
    }
    Ok(acc)
}

fn window_truth(
    model: &Model,
    window: BinWindow,
    blocks: &[[BlockMoments; 2]],
    size: TruthSize,
    piston: bool,
) -> Result<WindowTruth> {
    let setup = model.calibrated_setup(window);
    let calibration = setup.calibration()?;
    let signal = raw_estimates(&dft(&setup.signal.modulated), &setup.bins);
    let closed = if piston {
        None
    } else {
        Some(expectation(&setup, &model.noise, Formula::Exact)?)
    };
    // Without photon noise the counts convention subtracts the model's bias.
    let same_estimator = !model.noise.photon;
    let mut conventions = Vec::new();
    for (&bias, moments) in BIAS_CONVENTIONS.iter().zip(blocks) {
        let var_closed = |c: &CalibratedExpectation, k: usize| {
            let v = if k == 0 { c.var_v1_sq } else { c.var_v2_sq };
            v.filter(|_| bias == BiasConvention::Model || same_estimator)
        };
        let mean_closed =
            |c: &CalibratedExpectation, k: usize| if k == 0 { c.mean_v1_sq } else { c.mean_v2_sq };
        let one = |k: usize| {
            estimator_truth(
                closed.as_ref().map(|c| mean_closed(c, k)),
                closed.as_ref().and_then(|c| var_closed(c, k)),
                &moments[k],
                size.rows,
                !piston,
            )
        };
        if let (Some(v1_sq), Some(v2_sq)) = (one(0), one(1)) {
            conventions.push(ConventionTruth { bias, v1_sq, v2_sq });
        }
    }
    Ok(WindowTruth {
        bins: window,
        bin_indices: setup.bins.clone(),
        calibration,
        noise_free: Pair {
            v1_sq: signal.v1_sq / calibration.v1_sq,
            v2_sq: signal.v2_sq / calibration.v2_sq,
        },
        model_bias: noise_bias(&model.sample_variance(), &setup.bins),
        conventions,
    })
}

/// Combines the closed forms (where given) with the reference run's block
/// moments; None when neither gives a value.
fn estimator_truth(
    mean_closed: Option<f64>,
    var_closed: Option<f64>,
    blocks: &BlockMoments,
    rows: u64,
    independent_rows: bool,
) -> Option<EstimatorTruth> {
    let have_blocks = blocks.means.count >= 2;
    let sqrt_b = (blocks.means.count as f64).sqrt();
    let (mean, mean_source, stderr_mean) = match mean_closed {
        Some(m) => (m, TruthSource::ClosedForm, 0.0),
        None if have_blocks => (
            blocks.means.mean,
            TruthSource::ReferenceRun,
            blocks.means.std() / sqrt_b,
        ),
        None => return None,
    };
    let (var, var_source, stderr_var) = match var_closed {
        Some(v) => (v, TruthSource::ClosedForm, 0.0),
        None if have_blocks => (
            blocks.vars.mean,
            TruthSource::ReferenceRun,
            blocks.vars.std() / sqrt_b,
        ),
        None => return None,
    };
    // Independent rows: the mean of a set scatters as sqrt(var/rows) exactly.
    let set_stderr_mean = if independent_rows {
        (var / rows as f64).sqrt()
    } else {
        blocks.means.std()
    };
    Some(EstimatorTruth {
        mean,
        var,
        mean_source,
        var_source,
        stderr_mean,
        stderr_var,
        set_stderr_mean,
        set_stderr_var: have_blocks.then(|| blocks.vars.std()),
    })
}
