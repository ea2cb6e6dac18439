//! `v2ref plan`: the estimator, fringe frequency, stroke and number of scans
//! that reach a target σ(V²) (or the σ reached in a time budget) for an
//! instrument, a source and a site (`v2ref_commands::plan`).

use super::common::{warn_if_outer_scale_infinite, ObservationArgs, TurbulenceArgs};
use super::flags::{DetectorArgs, Flags, NoiseArgs};
use super::{finite_f64, print_json, progress_bar};
use std::process::ExitCode;
use v2ref_commands::commands::plan::{self, PlanRequest};
use v2ref_commands::parameters::Physical;
use v2ref_commands::plan::photometry::{Band2Mass, Magnitude};
use v2ref_commands::plan::{human_duration, Estimator, Plan, PlanInputs, PlanPoint, Target};
use v2ref_core::conformance::estimate::BiasConvention;
use v2ref_core::piston::spectrum::PistonSpectrum;
use v2ref_core::{Error, Result};

/// Flags of `plan`.
#[derive(Debug, clap::Args)]
#[command(group = clap::ArgGroup::new("brightness").multiple(true))]
pub struct Args {
    #[command(flatten)]
    pub(super) instrument: super::instrument::InstrumentArgs,
    #[command(flatten)]
    obs: ObservationArgs,
    /// Samples per fringe at λ0 (δx = λ0 / this): 2 to 1000.
    #[arg(long, default_value = "4", value_parser = finite_f64, allow_negative_numbers = true)]
    samples_per_fringe: f64,
    #[command(flatten)]
    detector: DetectorArgs,
    /// Continuum photons per second at the detector in the band: > 0 to 1e15.
    #[arg(long, default_value = "1e6", value_parser = finite_f64, allow_negative_numbers = true)]
    photon_rate_per_s: f64,
    /// Instead of --photon-rate-per-s: the source's magnitude in
    /// --magnitude-band (2MASS J, H, Ks: zero points of Cohen, Wheaton &
    /// Megeath 2003, AJ 126, 1090; Johnson–Cousins V, R, I: Bessell,
    /// Castelli & Plez 1998, A&A 333, 231), converted over the flat band --wavelength-um,
    /// --bandwidth-nm, collected by two apertures --aperture-m, times
    /// --throughput. From -10 to 30.
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true,
          conflicts_with_all = ["photon_rate_per_s", "spectrum_csv"],
          requires = "magnitude_band", group = "brightness")]
    magnitude: Option<f64>,
    /// The band of --magnitude: 2MASS J, H, Ks or Johnson–Cousins V, R, I.
    #[arg(long, value_enum, requires = "magnitude")]
    magnitude_band: Option<MagnitudeBand>,
    /// Fraction of the source's photons counted in the sampled
    /// interferogram (atmosphere, optics, combiner outputs sampled, detector
    /// QE), 0 < T <= 1; with --magnitude (needed, unless --instrument's
    /// preset gives it), or with --targets for its rows' magnitudes.
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true, requires = "brightness")]
    pub(super) throughput: Option<f64>,
    #[command(flatten)]
    noise: NoiseArgs,
    /// Dead time between scans, s: 0 to 3.2e7 (a year).
    #[arg(long, default_value = "0", value_parser = finite_f64, allow_negative_numbers = true)]
    dead_time_s: f64,
    /// The detector's maximum sample (frame) rate, Hz, 1e-3 to 1e9: the
    /// grid's fringe frequencies stop at frame rate / --samples-per-fringe
    /// (the default grid then runs up to it, beyond 2000 Hz if the detector
    /// allows; a given grid is cut there and gains that edge), and a
    /// recommendation there is said to be the detector's edge [default: no
    /// detector limit: the grid as given].
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true)]
    frame_rate_hz: Option<f64>,
    #[command(flatten)]
    turbulence: TurbulenceArgs,
    /// Target σ of the averaged V², 1e-9 to 1 [default: 1e-3 when no
    /// --time-budget-s].
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true, conflicts_with = "time_budget_s")]
    target_sigma_v2: Option<f64>,
    /// Instead of a target σ, the time to spend, s (> 0 to 3.2e7): report
    /// the σ reached.
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true)]
    time_budget_s: Option<f64>,
    /// Fringe frequencies of the grid, Hz: a value, A:B:N or A:B:N:log;
    /// repeatable [default: 20:2000:20:log].
    #[arg(long = "fringe-hz", value_parser = super::grid::parse_fringe_hz, allow_negative_numbers = true)]
    fringe_hz: Vec<super::grid::Grid>,
    /// Strokes of the grid, µm (repeatable) [default: 16, 32, 64, 128].
    #[arg(long = "stroke-um", value_parser = finite_f64, allow_negative_numbers = true)]
    stroke_um: Vec<f64>,
    /// Scans of each grid point's piston Monte Carlo, 32 to 2^24 / (samples
    /// per scan at the grid's longest stroke), checked before computing; at
    /// most 2^21 samples per point (fewer scans on long scans): cut into up
    /// to 16 independent piston sequences spanning two correlation times
    /// B/v each, whose spread gives the standard errors.
    #[arg(long, value_parser = super::count_u64, default_value = "16000", allow_negative_numbers = true)]
    scans: u64,
    /// 1σ uncertainty of the uniform disk's diameter, mas (>= 0): the V²
    /// error it gives is printed beside the corrections.
    #[arg(long, default_value = "0", value_parser = finite_f64, allow_negative_numbers = true)]
    diameter_err_mas: f64,
    /// Where your pipeline takes the photon-noise bias's counts from:
    /// counts (each scan's own; unbiased for both estimators under piston)
    /// or model (the source's piston-free counts; off by the piston's shift
    /// of the fringe, predicted and added to the bias). The predicted mean
    /// and the noise follow it. plan defaults to counts, estimate to model:
    /// the plan's text says which it used at every use.
    #[arg(long, value_parser = super::flags::choice::<BiasConvention>(), default_value = "counts")]
    bias: BiasConvention,
    /// Also simulate the recommended observation (n consecutive scans
    /// through one atmosphere, photon and detector noise, --bias): the
    /// σ(V²) and mean achieved, with intervals, beside the promise. Its
    /// duration is announced before it starts.
    #[arg(long)]
    pub(super) verify: bool,
    /// Observations simulated by --verify: 32 to 1e6.
    #[arg(long, value_parser = super::count_u64, default_value = "256", allow_negative_numbers = true, requires = "verify")]
    pub(super) verify_observations: u64,
    /// Seed of the piston Monte Carlo.
    #[arg(long, value_parser = super::count_u64, default_value = "1", allow_negative_numbers = true)]
    seed: u64,
    /// Worker threads (0 = all cores); the answer does not depend on it.
    #[arg(long, value_parser = super::thread_count, default_value = "0", allow_negative_numbers = true)]
    pub(super) threads: usize,
    /// One JSON document (every term of every grid point) instead of the table.
    #[arg(long)]
    pub(super) json: bool,
    /// No progress bar.
    #[arg(long)]
    pub(super) quiet: bool,
    /// Also write the figure of σ(V²) reached against fringe frequency (SVG):
    /// the promise as lines, settings not solved for consecutive scans as open
    /// circles (σ_scan/√n, no promise).
    #[arg(long, value_name = "FILE")]
    svg: Option<std::path::PathBuf>,
    /// Also write the predicted observation at the recommended setting as
    /// OIFITS v2 (V², predicted σ, the biases to correct as keywords).
    #[arg(long, value_name = "FILE.fits")]
    oifits: Option<std::path::PathBuf>,
    #[command(flatten)]
    observing: super::oifits::ObservingArgs,
    /// Replace an existing output file (never a link, folder or device).
    #[arg(long)]
    pub(super) force: bool,
    /// Print every grid point (default: the five fastest of each estimator).
    #[arg(long)]
    all: bool,
    #[command(flatten)]
    pub(super) targets: super::targets::TargetsArgs,
}

/// The band of `--magnitude`: 2MASS (Cohen et al. 2003) or Johnson–Cousins
/// (Bessell et al. 1998). It must cover the observing band.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum MagnitudeBand {
    /// J, 1.235 µm, 1594 Jy.
    J,
    /// H, 1.662 µm, 1024 Jy.
    H,
    /// Ks, 2.159 µm, 666.7 Jy.
    Ks,
    /// Johnson V, 0.545 µm, 3640 Jy.
    V,
    /// Cousins R, 0.641 µm, 3080 Jy.
    R,
    /// Cousins I, 0.798 µm, 2550 Jy.
    I,
}

impl From<MagnitudeBand> for Band2Mass {
    fn from(b: MagnitudeBand) -> Band2Mass {
        match b {
            MagnitudeBand::J => Band2Mass::J,
            MagnitudeBand::H => Band2Mass::H,
            MagnitudeBand::Ks => Band2Mass::Ks,
            MagnitudeBand::V => Band2Mass::V,
            MagnitudeBand::R => Band2Mass::R,
            MagnitudeBand::I => Band2Mass::I,
        }
    }
}

/// The magnitude flags as a [`Magnitude`] collected by apertures of
/// `aperture_m`, when given.
fn magnitude(args: &Args, aperture_m: f64) -> Option<Magnitude> {
    Some(Magnitude {
        magnitude: args.magnitude?,
        band: args.magnitude_band?.into(),
        aperture_m,
        // NaN: none given; the preset's, or refused (InstrumentArgs::apply).
        throughput: args.throughput.unwrap_or(f64::NAN),
    })
}

/// The physical inputs and the plan's own options from the flags.
fn request(args: &Args) -> Result<(Physical, PlanRequest)> {
    let mut p = args.obs.physical()?;
    args.detector.apply_to(&mut p)?;
    args.noise.apply_to(&mut p)?;
    args.turbulence.apply_to(&mut p)?;
    let mut req = PlanRequest {
        samples_per_fringe: args.samples_per_fringe,
        photon_rate_per_s: args.photon_rate_per_s,
        magnitude: magnitude(args, p.aperture_m),
        dead_time_s: args.dead_time_s,
        frame_rate_hz: args.frame_rate_hz,
        fringe_hz: super::grid::flatten(&args.fringe_hz),
        stroke_um: args.stroke_um.clone(),
        target_sigma_v2: args.target_sigma_v2,
        time_budget_s: args.time_budget_s,
        scans: args.scans,
        seed: args.seed,
        diameter_err_mas: args.diameter_err_mas,
        bias: args.bias,
    };
    args.instrument.apply(&mut p, &mut req)?;
    Ok((p, req))
}

/// Runs `plan`.
pub fn run(args: Args) -> Result<ExitCode> {
    if args.instrument.print_list(args.json) {
        return Ok(ExitCode::SUCCESS);
    }
    if args.targets.targets.is_some() {
        let flags = super::targets::PlanFlags {
            throughput: (args.throughput).or(args.instrument.preset()?.map(|i| i.throughput)),
            force: args.force,
            verify_observations: args.verify.then_some(args.verify_observations),
            quiet: args.quiet,
            threads: args.threads,
            json: args.json,
        };
        return super::targets::run(&args.targets, flags, request(&args)?);
    }
    if let Some(p) = &args.oifits {
        v2ref_oifits::check_fits_extension(p, "oifits")?;
    }
    let observing = args.observing.resolve(args.oifits.is_some(), "--oifits")?;
    // Both files checked and locked before any work, written together.
    let svg = args.svg.iter().map(|p| (p.as_path(), "svg"));
    let targets: Vec<_> = svg
        .chain(args.oifits.iter().map(|p| (p.as_path(), "oifits")))
        .collect();
    let set = v2ref_files::atomic::set::OutputSet::begin(&targets, args.force)?;
    let (physical, req) = request(&args)?;
    let prepared = plan::prepare(&physical, &req)?;
    let piston = prepared.piston.clone();
    warn_if_outer_scale_infinite(&physical, piston.baseline_m(), piston.rms_um());
    let bar = progress_bar(prepared.points(), args.quiet || args.json, "plan");
    let mut answer = plan::run(prepared, args.threads, &|k| bar.inc(k))?;
    bar.finish_and_clear();
    if args.verify {
        let size = plan::verification(&answer, args.verify_observations)?;
        if !args.quiet {
            super::output::write_stderr_line(format_args!(
                "note: plan --verify: simulating {} scans of {} samples ({} observations of {} scans){}",
                size.scans(),
                size.samples,
                size.observations(),
                size.scans_per_observation,
                size.fewer_why().map_or(String::new(), |why| format!("; {why}"))
            ));
        }
        let bar = progress_bar(size.scans(), args.quiet || args.json, "plan --verify");
        plan::verify(&mut answer, &size, args.threads, &|k| bar.inc(k))?;
        bar.finish_and_clear();
    }
    set.write(|| {
        if let Some(path) = &args.svg {
            super::plan_svg::write(path, &answer.plan, &answer.inputs)?;
        }
        if let Some(path) = &args.oifits {
            let plan = (&answer.inputs, &answer.plan);
            if !v2ref_oifits::write_plan(path, "oifits", plan, &observing)? {
                errln!(
                    "note: --oifits: no setting reaches the target, so no observation is predicted; {} not written",
                    path.display()
                );
            }
        }
        Ok(())
    })?;
    if args.json {
        print_json(&answer);
    } else {
        print_table(&answer.inputs, &answer.plan, &piston, args.all)?;
        if let Some(v) = &answer.verification {
            super::plan_verify::print(v);
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// Rows of the table without `--all`, per estimator.
const ROWS_PER_ESTIMATOR: usize = 5;

/// The rows to print: every point with `all`, else each estimator's
/// fastest (least time, or least σ with a budget), in grid order.
fn table_rows(plan: &Plan, all: bool) -> Vec<&PlanPoint> {
    if all {
        return plan.points.iter().collect();
    }
    let merit = |p: &PlanPoint| p.sigma_reached.or(p.time_s).unwrap_or(f64::INFINITY);
    let mut rows = Vec::new();
    for e in [Estimator::V1, Estimator::V2] {
        let mut ours: Vec<&PlanPoint> = plan.points.iter().filter(|p| p.estimator == e).collect();
        ours.sort_by(|a, b| merit(a).total_cmp(&merit(b)));
        rows.extend(ours.into_iter().take(ROWS_PER_ESTIMATOR));
    }
    rows
}

fn name(e: Estimator) -> &'static str {
    match e {
        Estimator::V1 => "V1^2",
        Estimator::V2 => "V2^2",
        _ => "V^2",
    }
}

fn describe(p: &PlanPoint) -> String {
    let reach = match (p.sigma_reached, p.time_s) {
        (Some(s), Some(t)) => format!(
            "sigma(V^2) {s:.2e} in {} ({:.0} scans)",
            human_duration(t),
            p.scans_needed.unwrap_or(0.0)
        ),
        (None, Some(t)) => format!(
            "{:.0} {}scans, {}{}{}",
            p.scans_needed.unwrap_or(0.0),
            if p.observation.is_some() {
                "consecutive "
            } else {
                ""
            },
            human_duration(t),
            p.time_lower_s
                .filter(|_| p.observation.is_some())
                .map_or(String::new(), |lo| format!(
                    " (from {} with the piston terms at the lower ends of their intervals)",
                    human_duration(lo)
                )),
            if p.exceeds_one_night {
                " (WARNING: longer than one night, 10 h)"
            } else {
                ""
            }
        ),
        _ => "unreachable (piston bias above the target)".into(),
    };
    format!(
        "{} at {:.1} Hz, {:.0} um stroke ({} samples, {:.3} photons/sample): {reach}",
        name(p.estimator),
        p.fringe_hz,
        p.stroke_um,
        p.samples,
        p.photons_per_sample,
    )
}

/// How the recommended setting scans, and what the plan assumed of it:
/// the sample step, the stroke the samples span, the frame rate, the dead
/// time and the fringe tracking.
fn setting(p: &PlanPoint, inputs: &PlanInputs) {
    let dead = if inputs.dead_time_s > 0.0 {
        format!("dead time {} s between scans", inputs.dead_time_s)
    } else {
        "no dead time between scans (none given: --dead-time-s)".into()
    };
    outln!(
        "  scan: sample step {:.4} um (lambda0/{}), true stroke {:.3} um ({} samples x step), {:.0} frames/s, one scan {}; {dead}; tracking assumed: the fringe packet re-centred on each scan's mean piston (a perfect group-delay tracker: only the piston's wander within a scan moves the fringe)",
        p.dx_um,
        inputs.samples_per_fringe,
        p.stroke_um,
        p.samples,
        inputs.samples_per_fringe * p.fringe_hz,
        if p.scan_time_s < 1.0 {
            format!("{:.3} ms", p.scan_time_s * 1e3)
        } else {
            human_duration(p.scan_time_s)
        },
    );
}

/// The terms of a point, one per line, on V².
fn terms(p: &PlanPoint, confidence: f64) {
    outln!(
        "  per scan sigma(V^2) {:.2e} = noise {:.2e} (+) piston {:.2e} +/- {:.1e}; piston bias on V^2 {:+.2e} +/- {:.1e} ({} independent piston sequences; the plan uses the upper ends of the {:.0}% intervals: scatter {:.2e}, |bias| {:.2e})",
        p.sigma_per_scan,
        p.sigma_noise_per_scan,
        p.sigma_piston_per_scan,
        p.sigma_piston_stderr,
        p.bias_piston,
        p.bias_piston_stderr,
        p.piston_sequences,
        confidence * 100.0,
        p.sigma_piston_upper,
        p.bias_piston_upper,
    );
}

/// The observation's σ and mean, when the point was solved for them.
fn observation(p: &PlanPoint, inputs: &PlanInputs) {
    let Some(o) = p.observation else { return };
    outln!(
        "  observation of {} consecutive scans through one atmosphere: sigma(V^2) {:.2e} = noise {:.2e} (+) piston {:.2e} (upper end; measured {:.2e} +/- {:.1e}, inflation {:.2} over independent scans' {:.2e}{})",
        o.scans,
        o.sigma,
        o.sigma_noise,
        o.sigma_piston_upper,
        o.sigma_piston,
        o.sigma_piston_stderr,
        o.variance_inflation,
        o.sigma_piston_if_independent,
        o.extrapolated_from_scans.map_or(String::new(), |m| format!(
            "; measured at {m} scans and carried to n as 1/n"
        )),
    );
    outln!(
        "  {}",
        v2ref_commands::plan::inflation_words(o.variance_inflation)
    );
    outln!(
        "  predicted mean V^2 {:.5e} with {}: uncorrectable bias {:+.2e} +/- {:.1e} (piston {:+.2e}, convention {:+.2e})",
        o.predicted_mean,
        super::plan_verify::convention_words(inputs.bias),
        o.bias,
        o.bias_stderr,
        p.bias_piston,
        o.convention_offset,
    );
}

/// The deterministic biases the user must correct, against the target.
fn corrections(inputs: &PlanInputs, p: &PlanPoint) {
    let verdict = |ratio: f64| {
        if ratio >= 1.0 {
            format!("{ratio:.1}x the target: correct it")
        } else {
            format!("{ratio:.2}x the target")
        }
    };
    outln!(
        "  V^2: true (monochromatic) {:.5}; noise-free, piston-free estimate {:.5}",
        p.v_mono_sq,
        p.v_sq_sampled
    );
    outln!(
        "  correct (computed, deterministic): bandwidth+dispersion {:+.2e} on V^2 ({}); scan+detector {:+.2e} ({})",
        p.bias_bandwidth_dispersion,
        verdict(p.bandwidth_bias_over_target),
        p.bias_scan_detector,
        verdict(p.scan_bias_over_target)
    );
    if inputs.diameter_err_mas > 0.0 {
        let target = inputs.target.sigma_v2().unwrap_or(f64::NAN);
        outln!(
            "  the diameter's uncertainty ({} mas) moves V^2 by {:.2e} ({:.2}x the target): calibration, not noise, limits the accuracy where this is above 1",
            inputs.diameter_err_mas,
            p.v_sq_error_from_diameter,
            p.v_sq_error_from_diameter / target
        );
    }
}

fn print_table(inputs: &PlanInputs, plan: &Plan, piston: &PistonSpectrum, all: bool) -> Result<()> {
    let target = match inputs.target {
        Target::SigmaV2(s) => format!("target sigma(V^2) = {s:e}"),
        Target::TimeBudgetS(t) => format!("time budget {}", human_duration(t)),
        other => format!("target {other:?}"),
    };
    match &plan.recommended {
        Some(p) => {
            outln!("recommended ({target}): {}", describe(p));
            setting(p, inputs);
            terms(p, plan.confidence);
            observation(p, inputs);
            corrections(inputs, p);
            if let Some(note) = &plan.grid_edge {
                outln!("  NOTE: {note}");
            }
        }
        None => outln!(
            "no recommendation ({target}): {}",
            plan.no_v1_reason
                .as_deref()
                .or(plan.no_v2_reason.as_deref())
                .unwrap_or("see the rows below")
        ),
    }
    for (e, best, reason) in [
        (Estimator::V1, &plan.best_v1, &plan.no_v1_reason),
        (Estimator::V2, &plan.best_v2, &plan.no_v2_reason),
    ] {
        match (best, reason) {
            (Some(p), _) => outln!("best {}", describe(p)),
            (None, Some(r)) => outln!("best {}: none: {r}", name(e)),
            (None, None) => {}
        }
    }
    let turb = piston.turbulence();
    outln!(
        "site: baseline {:.1} m, seeing {:.3} arcsec at {} um (r0 {:.1} cm), wind {} m/s, outer scale {}, piston rms {:.1} um; {:.3e} photons/s",
        piston.baseline_m(),
        inputs.atmosphere.seeing_arcsec,
        inputs.atmosphere.wavelength_um,
        turb.r0_m() * 100.0,
        inputs.atmosphere.wind_mps,
        inputs
            .atmosphere
            .outer_scale_m
            .map_or("infinite".into(), |l0| format!("{l0} m")),
        piston.rms_um(),
        inputs.photon_rate_per_s
    );
    outln!("");
    let rows = table_rows(plan, all);
    if !all {
        outln!(
            "the {} fastest settings of each estimator ({} in all: --all or --json for every one); V^2 throughout",
            ROWS_PER_ESTIMATOR,
            plan.points.len()
        );
    }
    outln!(
        "{:>5} {:>9} {:>11} {:>14} {:>12} {:>13} {:>13} {:>11} {:>9} {:>10}",
        "est",
        "f [Hz]",
        "stroke [um]",
        "photons/sample",
        "sigma_noise",
        "sigma_piston",
        "bias_piston",
        "scans",
        "time",
        "sigma_reach"
    );
    for p in &rows {
        let count = p.scans_needed.map_or("-".into(), |n| format!("{n:.0}"));
        let time = p.time_s.map_or("-".into(), |t| {
            let mark = if p.observation.is_none() && matches!(inputs.target, Target::SigmaV2(_)) {
                "*"
            } else {
                ""
            };
            format!("{}{mark}", human_duration(t))
        });
        let reach = p.sigma_reached.map_or("-".into(), |s| format!("{s:.2e}"));
        outln!(
            "{:>5} {:>9.1} {:>11.0} {:>14.3} {:>12.2e} {:>13.2e} {:>+13.2e} {:>11} {:>9} {:>10}",
            name(p.estimator),
            p.fringe_hz,
            p.stroke_um,
            p.photons_per_sample,
            p.sigma_noise_per_scan,
            p.sigma_piston_per_scan,
            p.bias_piston,
            count,
            time,
            reach
        );
    }
    if rows.iter().any(|p| {
        p.observation.is_none() && p.time_s.is_some() && matches!(inputs.target, Target::SigmaV2(_))
    }) {
        outln!("  *: scans and time assume independent scans (sigma_scan^2/(target^2 - bias^2)); the plan solves the observation of consecutive scans for the fastest {} settings of each estimator (by the per-scan estimate) only, less those whose noise alone needs longer than the best solved", v2ref_commands::plan::CANDIDATES);
    }
    // What a "-" in the table stands for, once per reason shown.
    let mut reasons: Vec<&str> = Vec::new();
    for p in &rows {
        if let Some(r) = p
            .why_null
            .filter(|_| p.scans_needed.is_none() || p.sigma_reached.is_none())
        {
            if !reasons.contains(&r) {
                reasons.push(r);
            }
        }
    }
    for r in reasons {
        outln!("  -: {r}");
    }
    if plan.points.is_empty() {
        return Err(Error::Invalid {
            param: "fringe_hz",
            reason: "empty grid".into(),
        });
    }
    Ok(())
}
