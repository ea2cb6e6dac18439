//! The plan's candidates re-solved at the observation level: the fastest
//! settings of each estimator by the per-scan estimate get the number of
//! consecutive scans their observation needs ([`super::observation`]), and
//! the plan recommends among them.

use super::observation::{
    observation_seed, scans_per_sequence, solve_scans, stride_samples, AtPoint, ContiguousScans,
    BLOCKS_PER_SEQUENCE,
};
use super::reach::{merit, UNREACHABLE};
use super::{Estimator, PlanInputs, PlanPoint, ONE_NIGHT_S};
use crate::conformance::estimate::BiasConvention;
use crate::error::Result;
use crate::formalism::estimator::BinWindow;
use crate::montecarlo::{derive_seed, replicated_t_quantile};
use crate::noise::calibrated::Trials;
use crate::noise::Formula;
use crate::piston::turbulence::PistonSpectrum;
use crate::simulator::{simulate, Model};

/// Settings of each estimator re-solved at the observation level: the
/// fastest by the per-scan estimate (the table's rows).
pub const CANDIDATES: usize = 5;

/// The indices of each estimator's [`CANDIDATES`] fastest reachable
/// points by the per-scan estimate.
fn candidates(points: &[PlanPoint]) -> Vec<usize> {
    let mut chosen = Vec::new();
    for e in [Estimator::V1, Estimator::V2] {
        let mut ours: Vec<(f64, usize)> = points
            .iter()
            .enumerate()
            .filter(|(_, p)| p.estimator == e)
            .filter_map(|(i, p)| merit(p).map(|m| (m, i)))
            .collect();
        ours.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        chosen.extend(ours.into_iter().take(CANDIDATES).map(|(_, i)| i));
    }
    chosen
}

/// σ per scan of the detector and photon noise under the convention: the
/// exact closed form for `model`; for `counts` (whose bias is estimated
/// from each row, and so adds its own noise) the upper end of a noise-only
/// Monte Carlo's interval.
fn sigma_noise_per_scan(inputs: &PlanInputs, noisy: &Model, p: &PlanPoint) -> Result<f64> {
    if inputs.bias == BiasConvention::Model {
        return Ok(p.sigma_noise_per_scan);
    }
    let size = Trials {
        trials: inputs.scans.max(4000),
        seed: derive_seed(
            inputs.seed,
            "plan-counts-noise",
            &[p.fringe_hz, p.stroke_um],
        ),
        threads: 0,
    };
    let window = BinWindow::Positive;
    let run = simulate(noisy, window, inputs.bias, Formula::Exact, size, &|_| {})?;
    let s = match p.estimator {
        Estimator::V1 => run.v1_sq,
        Estimator::V2 => run.v2_sq,
    };
    let t = replicated_t_quantile(super::CONFIDENCE, 2 * size.trials as usize);
    Ok(s.std + t * s.stderr_std)
}

/// The contiguous scans at one setting, long enough for `n` consecutive
/// scans (or as long as the memory allows).
fn contiguous(
    inputs: &PlanInputs,
    sky: &PistonSpectrum,
    (fringe_hz, stroke_um): (f64, f64),
    n: u64,
) -> Result<(ContiguousScans, Model)> {
    let piston = Model::with_piston_spectrum(
        &inputs.point_inputs(fringe_hz, stroke_um, false, true)?,
        sky.clone(),
    )?;
    let noisy = Model::new(&inputs.point_inputs(fringe_hz, stroke_um, true, false)?)?;
    let t_s = 1.0 / (inputs.samples_per_fringe * fringe_hz);
    let stride = stride_samples(inputs, &piston, fringe_hz);
    let shape = (piston.samples(), stride, t_s);
    let per_sequence = scans_per_sequence(
        sky,
        shape,
        (n.saturating_mul(BLOCKS_PER_SEQUENCE), n),
        (inputs.scans, true),
    )
    .unwrap_or(1);
    let seed = observation_seed(inputs.seed, fringe_hz, stroke_um);
    let scans = ContiguousScans::simulate(
        &piston,
        Some(&noisy),
        BiasConvention::Model,
        (per_sequence, stride, t_s),
        seed,
        &|_| {},
    )?;
    Ok((scans, noisy))
}

/// Re-solves point `p` at the observation level for σ(V²) = `target` on
/// the contiguous scans `shared` of its setting (simulated again, longer,
/// when n outgrows them); `noisy` is the setting's noise model.
fn resolve(
    inputs: &PlanInputs,
    sky: &PistonSpectrum,
    (shared, noisy): (&ContiguousScans, &Model),
    p: &mut PlanPoint,
    target: f64,
) -> Result<()> {
    let start = p.scans_needed.unwrap_or(1.0);
    let sigma_noise = sigma_noise_per_scan(inputs, noisy, p)?;
    let mut longer: Option<ContiguousScans> = None;
    let mut solved = None;
    for _ in 0..3 {
        let scans = longer.as_ref().unwrap_or(shared);
        let at = AtPoint {
            scans,
            point: p,
            convention: inputs.bias,
            sigma_noise_per_scan: sigma_noise,
        };
        solved = solve_scans(&at, target, start, true);
        let fewer_blocks = |o: &super::ObservationError| {
            o.scans.saturating_mul(BLOCKS_PER_SEQUENCE) > scans.per_sequence() as u64
        };
        let Some(o) = solved.filter(fewer_blocks) else {
            break;
        };
        // n outgrew the sequences: simulate longer ones, if they fit.
        let (more, _) = contiguous(inputs, sky, (p.fringe_hz, p.stroke_um), o.scans)?;
        if more.per_sequence() <= scans.per_sequence() {
            break;
        }
        longer = Some(more);
    }
    let at = AtPoint {
        scans: longer.as_ref().unwrap_or(shared),
        point: p,
        convention: inputs.bias,
        sigma_noise_per_scan: sigma_noise,
    };
    let lower = solve_scans(&at, target, start, false);
    let period = shared.scan_period_s;
    p.observation = solved;
    p.scans_needed = solved.map(|o| o.scans as f64);
    p.time_s = p.scans_needed.map(|n| n * period);
    p.time_lower_s = lower.map(|o| o.scans as f64 * period);
    p.exceeds_one_night = p.time_s.is_some_and(|t| t > ONE_NIGHT_S);
    if solved.is_none() {
        p.why_null = Some(UNREACHABLE);
    }
    Ok(())
}

/// Re-solves each estimator's [`CANDIDATES`] fastest points (target mode),
/// the settings in parallel on the current pool; the V1² and V2² points of
/// one setting share its simulation.
pub(super) fn resolve_candidates(
    inputs: &PlanInputs,
    sky: &PistonSpectrum,
    points: &mut [PlanPoint],
    target: f64,
) -> Result<()> {
    use rayon::prelude::*;
    let mut settings: Vec<((f64, f64), Vec<usize>)> = Vec::new();
    for i in candidates(points) {
        let key = (points[i].fringe_hz, points[i].stroke_um);
        match settings.iter_mut().find(|(k, _)| *k == key) {
            Some((_, group)) => group.push(i),
            None => settings.push((key, vec![i])),
        }
    }
    let solved: Vec<Vec<(usize, PlanPoint)>> = settings
        .par_iter()
        .map(|(key, group)| {
            let n = group
                .iter()
                .filter_map(|&i| points[i].scans_needed)
                .fold(1.0, f64::max);
            let (shared, noisy) = contiguous(inputs, sky, *key, n as u64)?;
            group
                .iter()
                .map(|&i| {
                    let mut p = points[i];
                    resolve(inputs, sky, (&shared, &noisy), &mut p, target).map(|()| (i, p))
                })
                .collect::<Result<Vec<_>>>()
        })
        .collect::<Result<_>>()?;
    for (i, p) in solved.into_iter().flatten() {
        points[i] = p;
    }
    Ok(())
}
