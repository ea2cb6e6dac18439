//! The plan's candidates re-solved at the observation level: the fastest
//! settings of each estimator by the per-scan estimate get the number of
//! consecutive scans their observation needs ([`super::observation`]), and
//! the plan recommends among them.

use super::correlation::{scans_per_sequence, ScanCorrelation};
use super::observation::{observation_seed, solve_scans, stride_samples, AtPoint, ContiguousScans};
use super::reach::{merit, UNREACHABLE};
use super::{Estimator, PlanInputs, PlanPoint, ONE_NIGHT_S};
use crate::conformance::estimate::BiasConvention;
use crate::error::Result;
use crate::formalism::estimator::BinWindow;
use crate::montecarlo::{derive_seed, replicated_t_quantile};
use crate::noise::calibrated::Trials;
use crate::noise::Formula;
use crate::piston::sequences::correlation_time_s;
use crate::piston::spectrum::PistonSpectrum;
use crate::piston::{FringeTables, SharedSequences};
use crate::simulator::{simulate, Model};
use std::collections::BTreeMap;

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

/// σ per scan of the detector and photon noise under the convention, the
/// lower and upper ends of its interval: the exact closed form (both ends)
/// for `model`; for `counts` (whose bias is estimated from each row, and
/// so adds its own noise) a noise-only Monte Carlo's interval.
fn sigma_noise_per_scan(inputs: &PlanInputs, noisy: &Model, p: &PlanPoint) -> Result<[f64; 2]> {
    if inputs.bias == BiasConvention::Model {
        return Ok([p.sigma_noise_per_scan; 2]);
    }
    let size = Trials {
        trials: super::point_scans(inputs.scans, noisy.samples()).max(4000),
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
    Ok([
        (s.std - t * s.stderr_std).max(0.0),
        s.std + t * s.stderr_std,
    ])
}

/// The contiguous scans of one setting: the same sequences whatever the
/// observation's n and whatever else the grid holds (their length depends
/// on the setting and the atmosphere only, their seed on its fringe frequency).
fn contiguous(
    inputs: &PlanInputs,
    (sky, tables, shared): (&PistonSpectrum, &FringeTables, &SharedSequences),
    (fringe_hz, stroke_um): (f64, f64),
) -> Result<ContiguousScans> {
    let noisy = Model::new(&inputs.point_inputs(fringe_hz, stroke_um, true, false)?)?;
    let piston = noisy
        .sibling_with_piston_spectrum(
            &inputs.point_inputs(fringe_hz, stroke_um, false, true)?,
            sky.clone(),
        )?
        .sharing_fringe_tables(tables)
        .sharing_piston_sequences(shared);
    let t_s = 1.0 / (inputs.samples_per_fringe * fringe_hz);
    let stride = stride_samples(inputs, &piston, fringe_hz);
    let shape = (piston.samples(), stride, t_s);
    let per_sequence = scans_per_sequence(sky, shape, inputs.scans);
    let seed = observation_seed(inputs.seed, fringe_hz);
    ContiguousScans::simulate(
        &piston,
        Some(&noisy),
        BiasConvention::Model,
        (per_sequence, stride, t_s),
        seed,
        &|_| {},
    )
}

/// Re-solves point `p` at the observation level for σ(V²) = `target` on
/// the contiguous scans of its setting, with its noise per scan `noise`
/// (lower and upper ends).
fn resolve(
    (inputs, sky): (&PlanInputs, &PistonSpectrum),
    scans: &ContiguousScans,
    noise: [f64; 2],
    p: &mut PlanPoint,
    target: f64,
) {
    let e = match p.estimator {
        Estimator::V1 => 0,
        Estimator::V2 => 1,
    };
    let correlation_scans = correlation_time_s(sky) / scans.scan_period_s;
    let with_offset = inputs.bias == BiasConvention::Model;
    let correlation = ScanCorrelation::new(scans, (e, with_offset), correlation_scans);
    let start = p.scans_needed.unwrap_or(1.0);
    let at = AtPoint {
        scans,
        correlation: &correlation,
        point: p,
        convention: inputs.bias,
        sigma_noise_per_scan: noise,
    };
    let solved = solve_scans(&at, target, start, true);
    let lower = solve_scans(&at, target, start, false);
    let period = scans.scan_period_s;
    p.observation = solved;
    p.scans_needed = solved.map(|o| o.scans as f64);
    p.time_s = p.scans_needed.map(|n| n * period);
    p.time_lower_s = lower.map(|o| o.scans as f64 * period);
    p.exceeds_one_night = p.time_s.is_some_and(|t| t > ONE_NIGHT_S);
    if solved.is_none() {
        p.why_null = Some(UNREACHABLE);
    }
}

/// Settings simulated together between two prunings: fixed (not the
/// thread count), so which settings are pruned does not depend on it.
const WAVE: usize = 2;

/// One candidate setting: its grid points (indices) and the noise per
/// scan of each under the convention.
struct Setting {
    key: (f64, f64),
    points: Vec<(usize, [f64; 2])>,
    /// The least time any of its points could take: its noise alone at
    /// the lower end, no piston, no bias.
    least_time_s: f64,
}

/// The least time for σ(V²) = `target` from noise σ per scan
/// `noise_lower` alone, one scan and its dead time being `period_s`.
fn least_time_s(noise_lower: f64, target: f64, period_s: f64) -> f64 {
    (noise_lower * noise_lower / (target * target))
        .ceil()
        .max(1.0)
        * period_s
}

/// Re-solves each estimator's [`CANDIDATES`] fastest points (target mode),
/// in waves of [`WAVE`] settings (in parallel on the current pool) from the
/// one that could be fastest; the V1² and V2² points of one setting share
/// its simulation. Before each wave, a point whose noise alone needs more
/// time than the best solved point of its estimator is dropped (it cannot
/// win, nor tie: the tie rule compares the best's time with a point's
/// time at the lower ends, which is longer than its noise-only time); it
/// keeps its independent-scan estimate, marked as not solved.
pub(super) fn resolve_candidates(
    inputs: &PlanInputs,
    (sky, tables): (&PistonSpectrum, &FringeTables),
    points: &mut [PlanPoint],
    target: f64,
) -> Result<()> {
    use rayon::prelude::*;
    let mut settings = candidate_settings(inputs, points, target)?;
    settings.sort_by(|a, b| a.least_time_s.total_cmp(&b.least_time_s));
    let mut best = [f64::INFINITY; 2];
    let mut drawn: BTreeMap<u64, SharedSequences> = BTreeMap::new();
    for wave in settings.chunks_mut(WAVE) {
        for s in wave.iter_mut() {
            let p = &*points;
            s.points.retain(|&(i, noise)| {
                let period = p[i].scan_time_s + inputs.dead_time_s;
                least_time_s(noise[0], target, period) <= best[index(p[i].estimator)]
            });
        }
        let live: Vec<&Setting> = wave.iter().filter(|s| !s.points.is_empty()).collect();
        let mut frequencies: Vec<f64> = live.iter().map(|s| s.key.0).collect();
        frequencies.sort_by(f64::total_cmp);
        frequencies.dedup();
        // The settings of one fringe frequency scan one atmosphere (the
        // seed is the frequency's), drawn once: kept from one wave to the
        // next while that wave has a setting at the frequency (the
        // fastest settings are often a few strokes at the fastest
        // frequencies), so only the wave's frequencies are in memory.
        drawn.retain(|f, _| frequencies.iter().any(|g| g.to_bits() == *f));
        for f in &frequencies {
            drawn.entry(f.to_bits()).or_default();
        }
        let solve = |s: &Setting| -> Result<Vec<(usize, PlanPoint)>> {
            let shared = &drawn[&s.key.0.to_bits()];
            let scans = contiguous(inputs, (sky, tables, shared), s.key)?;
            Ok(s.points
                .iter()
                .map(|&(i, noise)| {
                    let mut p = points[i];
                    resolve((inputs, sky), &scans, noise, &mut p, target);
                    (i, p)
                })
                .collect())
        };
        let solved: Vec<Vec<Vec<(usize, PlanPoint)>>> = frequencies
            .par_iter()
            .map(|&f| {
                let same = live.iter().filter(|s| s.key.0 == f);
                same.map(|s| solve(s)).collect::<Result<Vec<_>>>()
            })
            .collect::<Result<_>>()?;
        for (i, p) in solved.into_iter().flatten().flatten() {
            if let Some(t) = p.time_s {
                best[index(p.estimator)] = best[index(p.estimator)].min(t);
            }
            points[i] = p;
        }
        crate::montecarlo::cancel::check()?;
    }
    Ok(())
}

fn index(e: Estimator) -> usize {
    match e {
        Estimator::V1 => 0,
        Estimator::V2 => 1,
    }
}

/// The candidates grouped by setting, with each point's noise per scan.
fn candidate_settings(
    inputs: &PlanInputs,
    points: &[PlanPoint],
    target: f64,
) -> Result<Vec<Setting>> {
    use rayon::prelude::*;
    let mut settings: Vec<Setting> = Vec::new();
    for i in candidates(points) {
        let key = (points[i].fringe_hz, points[i].stroke_um);
        match settings.iter_mut().find(|s| s.key == key) {
            Some(s) => s.points.push((i, [0.0; 2])),
            None => settings.push(Setting {
                key,
                points: vec![(i, [0.0; 2])],
                least_time_s: 0.0,
            }),
        }
    }
    settings.par_iter_mut().try_for_each(|s| {
        let noisy = Model::new(&inputs.point_inputs(s.key.0, s.key.1, true, false)?)?;
        for (i, noise) in s.points.iter_mut() {
            *noise = sigma_noise_per_scan(inputs, &noisy, &points[*i])?;
        }
        let period = points[s.points[0].0].scan_time_s + inputs.dead_time_s;
        s.least_time_s = s
            .points
            .iter()
            .map(|(_, noise)| least_time_s(noise[0], target, period))
            .fold(f64::INFINITY, f64::min);
        Ok::<(), crate::Error>(())
    })?;
    Ok(settings)
}
