//! `v2ref piston`: the differential-piston Monte Carlo at one or more fringe
//! frequencies (paper, Section "Effect of differential piston").

use super::common::{ObservationArgs, OutputArgs, RunArgs, SamplingArgs, TurbulenceArgs};
use super::grid::{flatten, parse_fringe_hz, Grid};
use super::{finite_f64, print_json, progress_bar};
use serde::Serialize;
use std::process::ExitCode;
use v2ref::error::{Error, Result};
use v2ref::formalism::estimator::BinWindow;
use v2ref::formalism::interferogram::Sampling;
use v2ref::formalism::observation::Observation;
use v2ref::piston::turbulence::{PistonPsdModel, PistonSpectrum, Turbulence};
use v2ref::piston::{sweep, Detector, PistonRun, RunSize, ScanSetup};

/// Flags of `piston`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    obs: ObservationArgs,
    #[command(flatten)]
    sampling: SamplingArgs,
    /// Fringe frequency f = v/λ0, Hz: a value, A:B:N (N values from A to B)
    /// or A:B:N:log (log-spaced); repeatable [default: 300 and 1000].
    #[arg(long = "fringe-hz", value_parser = parse_fringe_hz, allow_negative_numbers = true)]
    fringe_hz: Vec<Grid>,
    #[command(flatten)]
    turbulence: TurbulenceArgs,
    /// The differential-piston spectrum: the two-aperture integral, or the
    /// three-slope model (Conan et al. 1995 asymptotes) of the same variance.
    #[arg(long, value_enum, default_value = "two-aperture")]
    psd: PistonPsdModel,
    /// Wind direction from the baseline, degrees (two-aperture spectrum only;
    /// 0 = along the baseline).
    #[arg(long, default_value = "0", value_parser = finite_f64, allow_negative_numbers = true)]
    wind_angle_deg: f64,
    /// Number of consecutive scans per fringe frequency.
    #[arg(long, default_value = "1000", allow_negative_numbers = true)]
    scans: usize,
    #[command(flatten)]
    run: RunArgs,
    #[command(flatten)]
    output: OutputArgs,
}

#[derive(Serialize)]
struct Row {
    fringe_hz: f64,
    bias_v1: f64,
    bias_v2: f64,
    scatter_v1: f64,
    scatter_v2: f64,
    bias_v1_stderr: f64,
    bias_v2_stderr: f64,
    scatter_v1_stderr: f64,
    scatter_v2_stderr: f64,
    v1_no_piston: f64,
    v2_no_piston: f64,
    scan_time_s: f64,
    residual_rms_um: f64,
    scans: usize,
    seed: u64,
}

#[derive(Serialize)]
struct Answer {
    /// |V| of the source at σ_eff on this baseline.
    visibility: f64,
    psd: &'static str,
    wind_angle_deg: f64,
    /// The three-slope corners (ν1, ν2), Hz, when that model is used.
    psd_corners_hz: Option<[f64; 2]>,
    detector: &'static str,
    bins: &'static str,
    reference: &'static str,
    baseline_m: f64,
    spatial_freq_cpas: f64,
    r0_m: f64,
    coherence_time_s: f64,
    piston_rms_um: f64,
    samples: usize,
    dx_um: f64,
    stroke_um: f64,
    results: Vec<Row>,
}

fn row(run: &PistonRun, window: BinWindow) -> Row {
    let w = run.window(window);
    Row {
        fringe_hz: run.fringe_hz,
        bias_v1: w.v1.mean,
        bias_v2: w.v2.mean,
        scatter_v1: w.v1.std,
        scatter_v2: w.v2.std,
        bias_v1_stderr: w.v1.stderr_mean,
        bias_v2_stderr: w.v2.stderr_mean,
        scatter_v1_stderr: w.v1.stderr_std,
        scatter_v2_stderr: w.v2.stderr_std,
        v1_no_piston: w.v1_no_piston,
        v2_no_piston: w.v2_no_piston,
        scan_time_s: run.scan_time_s,
        residual_rms_um: run.residual_rms_um,
        scans: run.scans,
        seed: run.seed,
    }
}

/// Runs `piston`.
pub fn run(args: Args) -> Result<ExitCode> {
    let obs = args.obs.observation()?;
    let sampling = args.sampling.sampling()?;
    sampling.check_aliasing(&obs)?;
    let freqs = fringe_frequencies(&flatten(&args.fringe_hz))?;
    check_scans(args.scans)?;
    v2ref::error::positive("aperture_m", args.turbulence.aperture_m)?;
    let turb = Turbulence::from_seeing(
        args.turbulence.seeing_arcsec,
        args.obs.wavelength_um,
        args.turbulence.wind_mps,
        args.turbulence.outer_scale_m,
    )?;
    let spectrum = PistonSpectrum::new(turb, args.turbulence.aperture_m, obs.baseline_m)?
        .with_wind_angle_deg(args.wind_angle_deg)?
        .with_model(args.psd)?;
    let detector = if sampling.integrating() {
        Detector::Integrating {
            sub_samples: args.turbulence.sub_samples,
        }
    } else {
        Detector::Sampled
    };
    let runs = simulate_each(&args, &obs, &spectrum, &sampling, detector, &freqs)?;
    let window = args.sampling.bins;
    let answer = Answer {
        visibility: obs
            .source
            .visibility(obs.spectrum.sigma_eff_per_um(), obs.baseline_m)
            .norm(),
        psd: args.psd.name(),
        wind_angle_deg: spectrum.wind_angle_deg(),
        psd_corners_hz: spectrum
            .three_slope()
            .map(|m| [m.corner_low_hz(), m.corner_high_hz()]),
        detector: detector.name(),
        bins: window.name(),
        reference: args.turbulence.reference.name(),
        baseline_m: obs.baseline_m,
        spatial_freq_cpas: obs.spatial_freq_cpas(),
        r0_m: turb.r0_m(),
        coherence_time_s: turb.coherence_time_s(),
        piston_rms_um: spectrum.rms_um(),
        samples: sampling.samples(),
        dx_um: sampling.dx_um(),
        stroke_um: sampling.stroke_um(),
        results: runs.iter().map(|r| row(r, window)).collect(),
    };
    if args.output.json {
        print_json(&answer);
    } else {
        print_table(&answer);
    }
    Ok(ExitCode::SUCCESS)
}

/// The `--fringe-hz` values (300 and 1000 Hz when none), each checked.
fn fringe_frequencies(given: &[f64]) -> Result<Vec<f64>> {
    let freqs = if given.is_empty() {
        vec![300.0, 1000.0]
    } else {
        given.to_vec()
    };
    for &f in &freqs {
        v2ref::error::in_range("fringe_hz", f, 1e-3, 1e7)?;
    }
    Ok(freqs)
}

/// Refuses fewer than 2 scans.
fn check_scans(scans: usize) -> Result<()> {
    if scans < 2 {
        return Err(Error::OutOfRange {
            param: "scans",
            value: scans as f64,
            accepted: ">= 2".into(),
        });
    }
    Ok(())
}

/// One piston Monte Carlo per fringe frequency, with a progress bar over
/// all scans.
fn simulate_each(
    args: &Args,
    obs: &Observation,
    spectrum: &PistonSpectrum,
    sampling: &Sampling,
    detector: Detector,
    freqs: &[f64],
) -> Result<Vec<PistonRun>> {
    let bar = progress_bar(
        (freqs.len() * args.scans) as u64,
        args.output.quiet || args.output.json,
        "piston scans",
    );
    let tick = |k: u64| bar.inc(k);
    let setup = ScanSetup {
        samples: sampling.samples(),
        dx_um: sampling.dx_um(),
        wavelength_um: args.obs.wavelength_um,
        fringe_hz: freqs[0],
        reference: args.turbulence.reference,
    };
    let size = RunSize {
        scans: args.scans,
        // Each frequency's seed is derived from the user's and the
        // frequency's value (piston::sweep_seed), not its place in the list.
        seed: args.run.seed,
        threads: args.run.threads,
    };
    let runs = sweep(
        obs,
        spectrum,
        freqs,
        &setup,
        &[detector],
        &size,
        Some(&tick),
    )?;
    let results: Vec<PistonRun> = runs.into_iter().flatten().collect();
    bar.finish_and_clear();
    Ok(results)
}

fn print_table(answer: &Answer) {
    outln!(
        "baseline {:.3} m ({:.2} cycles/arcsec), r0 {:.1} cm, tau0 {:.1} ms, piston rms {:.2} um; {} detector, {} bins, packet reference {}; {} x {} um scans",
        answer.baseline_m,
        answer.spatial_freq_cpas,
        100.0 * answer.r0_m,
        1e3 * answer.coherence_time_s,
        answer.piston_rms_um,
        answer.detector,
        answer.bins,
        answer.reference,
        answer.samples,
        answer.dx_um
    );
    let corners = answer.psd_corners_hz.map_or(String::new(), |[lo, hi]| {
        format!(" (corners {lo:.3} and {hi:.2} Hz)")
    });
    outln!(
        "{} piston spectrum{corners}, wind {} deg from the baseline; source V = {:.6}",
        answer.psd,
        answer.wind_angle_deg,
        answer.visibility
    );
    outln!("bias and scatter over scans of V (not V^2): V1 and V2 with piston minus without, then their standard deviation");
    outln!(
        "{:>10}  {:>9}  {:>22}  {:>22}  {:>22}  {:>22}",
        "f [Hz]",
        "V",
        "bias V1 (of V)",
        "bias V2 (of V)",
        "scatter V1 (of V)",
        "scatter V2 (of V)"
    );
    for r in &answer.results {
        outln!(
            "{:>10.2}  {:>9.6}  {:>+11.3e} ±{:>9.1e}  {:>+11.3e} ±{:>9.1e}  {:>11.3e} ±{:>9.1e}  {:>11.3e} ±{:>9.1e}",
            r.fringe_hz,
            answer.visibility,
            r.bias_v1,
            r.bias_v1_stderr,
            r.bias_v2,
            r.bias_v2_stderr,
            r.scatter_v1,
            r.scatter_v1_stderr,
            r.scatter_v2,
            r.scatter_v2_stderr
        );
    }
}
