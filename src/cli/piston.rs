//! `v2ref piston`: the differential-piston Monte Carlo at one or more fringe
//! frequencies (paper, Section "Effect of differential piston").

use super::common::{ObservationArgs, OutputArgs, RunArgs, SamplingArgs, TurbulenceArgs};
use super::grid::{flatten, parse_fringe_hz, Grid};
use super::{finite_f64, print_json, progress_bar};
use std::process::ExitCode;
use v2ref::error::{Error, Result};
use v2ref::formalism::interferogram::Sampling;
use v2ref::formalism::observation::Observation;
use v2ref::piston::report::{PistonReport, PistonSetting};
use v2ref::piston::turbulence::{PistonPsdModel, PistonSpectrum};
use v2ref::piston::{sweep, Detector, PistonRun, RunSize, ScanSetup};
use v2ref::simulator::record::{InputsRecord, SamplingRecord};

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
    #[arg(long, value_parser = super::count_usize, default_value = "1000", allow_negative_numbers = true)]
    scans: usize,
    #[command(flatten)]
    run: RunArgs,
    #[command(flatten)]
    output: OutputArgs,
}

/// Runs `piston`.
pub fn run(args: Args) -> Result<ExitCode> {
    let obs = args.obs.observation()?;
    let sampling = args.sampling.sampling()?;
    sampling.check_aliasing(&obs)?;
    let freqs = fringe_frequencies(&flatten(&args.fringe_hz))?;
    check_scans(args.scans)?;
    v2ref::error::positive("aperture_m", args.turbulence.aperture_m)?;
    let turb = args.turbulence.turbulence(args.obs.wavelength_um)?;
    let spectrum = PistonSpectrum::new(turb, args.turbulence.aperture_m, obs.baseline_m)?
        .with_wind_angle_deg(args.wind_angle_deg)?
        .with_model(args.psd)?;
    args.turbulence
        .warn_if_outer_scale_infinite(obs.baseline_m, spectrum.rms_um());
    let detector = if sampling.integrating() {
        Detector::Integrating {
            sub_samples: args.turbulence.sub_samples,
        }
    } else {
        Detector::Sampled
    };
    let runs = simulate_each(&args, &obs, &spectrum, &sampling, detector, &freqs)?;
    let window = args.sampling.bins;
    let inputs = InputsRecord {
        observation: args.obs.record(&obs),
        sampling: Some(SamplingRecord::new(&sampling, window)),
        atmosphere: Some(args.turbulence.record(args.obs.wavelength_um)?),
    };
    let setting = PistonSetting {
        obs: &obs,
        spectrum: &spectrum,
        sampling: &sampling,
        detector,
        window,
        reference: args.turbulence.reference,
    };
    let answer = PistonReport::new(inputs, setting, &runs);
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

fn print_table(answer: &PistonReport) {
    outln!(
        "baseline {:.3} m ({:.2} cycles/arcsec), r0 {:.1} cm, tau0 {:.1} ms (0.314 r0/v; r0/v {:.1} ms), piston rms {:.2} um; {} detector, {} bins, packet reference {}; {} x {} um scans",
        answer.baseline_m,
        answer.spatial_freq_cpas,
        100.0 * answer.r0_m,
        1e3 * answer.tau0_s,
        1e3 * answer.r0_over_v_s,
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
