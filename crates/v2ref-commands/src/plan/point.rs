//! One grid point of the plan: both estimators' deterministic terms, the
//! exact noise per scan and the piston Monte Carlo of the setting, keyed
//! by its fringe frequency (so a point's terms do not depend on the grid,
//! and the strokes of one frequency scan one atmosphere: their sequences
//! are drawn once, and their difference is not blurred by independent
//! draws).

use super::*;

/// The two estimators' points at one grid point.
pub(super) fn grid_point(
    inputs: &PlanInputs,
    (sky, tables, shared): (&PistonSpectrum, &FringeTables, &SharedSequences),
    fringe_hz: f64,
    stroke_um: f64,
) -> Result<[PlanPoint; 2]> {
    let noisy = Model::new(&inputs.point_inputs(fringe_hz, stroke_um, true, false)?)?;
    let window = BinWindow::Positive;
    let closed = expectation(
        &noisy.calibrated_setup(window),
        &noisy.noise,
        Formula::Exact,
    )?;
    let wb = wide_band(&noisy.observation);
    let vis2 = noisy.inputs.visibility * noisy.inputs.visibility;
    let piston_model = noisy
        .sibling_with_piston_spectrum(
            &inputs.point_inputs(fringe_hz, stroke_um, false, true)?,
            sky.clone(),
        )?
        .sharing_fringe_tables(tables)
        .sharing_piston_sequences(shared);
    let scans = point_scans(inputs.scans, noisy.samples());
    let size = Trials {
        trials: scans,
        seed: derive_seed(inputs.seed, "plan", &[fringe_hz]),
        // 0: the pool the grid runs on. A pool per point built inside the
        // grid's pool nests each waiting worker's stolen points on its
        // stack (a 10000-point grid overflowed it).
        threads: 0,
    };
    let mc = simulate(
        &piston_model,
        window,
        BiasConvention::Model,
        Formula::Exact,
        size,
        &|_| {},
    )?;
    let t_s = 1.0 / (inputs.samples_per_fringe * fringe_hz);
    let t_factor = replicated_t_quantile(CONFIDENCE, mc_sequences(scans));
    let target = match inputs.target {
        Target::SigmaV2(t) => t,
        Target::TimeBudgetS(_) => f64::NAN,
    };
    let diameter_error = v_sq_error_from_diameter(inputs, &noisy)?;
    let point = |estimator: Estimator| {
        let (spectral, sampled, var_noise, piston) = match estimator {
            Estimator::V1 => (wb.v1_sq, closed.mean_v1_sq, closed.var_v1_sq, &mc.v1_sq),
            Estimator::V2 => (wb.v2_sq, closed.mean_v2_sq, closed.var_v2_sq, &mc.v2_sq),
        };
        let var_noise = var_noise.unwrap_or(f64::NAN);
        let sigma = (var_noise + piston.var).sqrt();
        let bias_bandwidth_dispersion = vis2 * (spectral - wb.v_mono * wb.v_mono);
        let bias_scan_detector = sampled - vis2 * spectral;
        let mut p = PlanPoint {
            estimator,
            fringe_hz,
            stroke_um: noisy.sampling.stroke_um(),
            samples: noisy.samples(),
            dx_um: noisy.sampling.dx_um(),
            photons_per_sample: noisy.inputs.photons,
            scan_time_s: noisy.samples() as f64 * t_s,
            v_mono_sq: vis2 * wb.v_mono * wb.v_mono,
            bias_bandwidth_dispersion,
            bias_scan_detector,
            v_sq_sampled: sampled,
            sigma_noise_per_scan: var_noise.sqrt(),
            sigma_piston_per_scan: piston.std,
            sigma_piston_stderr: piston.stderr_std,
            bias_piston: piston.mean - sampled,
            bias_piston_stderr: piston.stderr_mean,
            sigma_per_scan: sigma,
            piston_sequences: mc_sequences(scans),
            sigma_piston_upper: piston.std + t_factor * piston.stderr_std,
            bias_piston_upper: (piston.mean - sampled).abs() + t_factor * piston.stderr_mean,
            scans_needed: None,
            time_s: None,
            time_lower_s: None,
            time_noise_only_s: None,
            exceeds_one_night: false,
            bandwidth_bias_over_target: bias_bandwidth_dispersion.abs() / target,
            scan_bias_over_target: bias_scan_detector.abs() / target,
            v_sq_error_from_diameter: diameter_error,
            sigma_reached: None,
            why_null: None,
            observation: None,
        };
        let lower = Bounds {
            sigma_piston: (piston.std - t_factor * piston.stderr_std).max(0.0),
            bias: ((piston.mean - sampled).abs() - t_factor * piston.stderr_mean).max(0.0),
        };
        reach(&mut p, inputs, lower);
        p
    };
    Ok([point(Estimator::V1), point(Estimator::V2)])
}

/// Most samples (scans × N) of one grid point's piston Monte Carlo: 2^21,
/// about 0.2 core-seconds. A point of N samples simulates
/// [`point_scans`] scans: the plan's `scans`, or fewer on long scans (a
/// long scan is slow, and its piston terms need fewer scans for the same
/// standard error than the time it takes). The grid's cost is then
/// bounded whatever the strokes.
pub const POINT_SAMPLES: u64 = 1 << 21;

/// Scans of the piston Monte Carlo of a grid point of `samples` samples:
/// `scans`, at most [`POINT_SAMPLES`] samples in all, at least 32 (two
/// sequences of 16).
pub fn point_scans(scans: u64, samples: usize) -> u64 {
    let least = 2 * crate::piston::sequences::MIN_SCANS_PER_SEQUENCE as u64;
    scans.min((POINT_SAMPLES / samples.max(1) as u64).max(least))
}

/// The independent piston sequences of a Monte Carlo of `scans` scans.
fn mc_sequences(scans: u64) -> usize {
    crate::piston::sequences::sequence_split(usize::try_from(scans).unwrap_or(usize::MAX)).0
}

/// |dV²/dθ|·δθ for a uniform disk with `diameter_err_mas` (0 otherwise),
/// by central difference at the model's spatial frequency.
fn v_sq_error_from_diameter(inputs: &PlanInputs, model: &Model) -> Result<f64> {
    let err = inputs.diameter_err_mas;
    let crate::simulator::SourceInput::Ud { diameter_mas } = inputs.instrument.source else {
        return Ok(0.0);
    };
    if err == 0.0 {
        return Ok(0.0);
    }
    let s_cpas = model.observation.spatial_freq_cpas();
    let v_sq = |theta: f64| {
        let v = crate::formalism::source::uniform_disk_visibility(theta.max(0.0), s_cpas);
        v * v
    };
    let h = (err * 1e-3).min(diameter_mas * 1e-3).max(1e-9);
    let slope = (v_sq(diameter_mas + h) - v_sq(diameter_mas - h)) / (2.0 * h);
    let vis2 = model.inputs.visibility * model.inputs.visibility;
    Ok((vis2 * slope * err).abs())
}
