//! `piston`: the differential-piston Monte Carlo at one or more fringe
//! frequencies, in two steps so that an edge can warn and size its
//! progress before the computation: [`prepare`] checks everything and
//! builds the spectrum, [`run`] computes the answer.

use crate::error::{Error, Result};
use crate::formalism::estimator::BinWindow;
use crate::formalism::interferogram::Sampling;
use crate::formalism::observation::Observation;
use crate::parameters::Physical;
use crate::piston::spectrum::{PistonPsdModel, PistonSpectrum};
use crate::piston::{sweep, Detector, PistonRun, RunSize, ScanSetup};
use crate::record::{InputsRecord, SamplingRecord};
use crate::report::model_comparison::PsdComparison;
use crate::report::piston::{ComparisonNote, PistonReport, PistonSetting};

/// The fringe frequencies when none is given, Hz.
pub const DEFAULT_FRINGE_HZ: [f64; 2] = [300.0, 1000.0];

/// The options of `piston` beyond the physical inputs (whose `fringe_hz`
/// it does not use: the frequencies are these).
#[derive(Debug, Clone, PartialEq)]
pub struct PistonRequest {
    /// Fringe frequencies, Hz ([`DEFAULT_FRINGE_HZ`] when empty).
    pub fringe_hz: Vec<f64>,
    /// The bins the estimators sum.
    pub bins: BinWindow,
    /// Scans per fringe frequency (≥ 2).
    pub scans: usize,
    /// Seed.
    pub seed: u64,
    /// Worker threads (0: all); the answer does not depend on it.
    pub threads: usize,
    /// The differential-piston spectrum's model.
    pub psd: PistonPsdModel,
    /// Wind direction from the baseline, degrees.
    pub wind_angle_deg: f64,
    /// Also σ of the mean of an observation of this many consecutive
    /// scans, or of this long ([`ObservationLength`]).
    pub observation: Option<ObservationLength>,
}

/// The length of the observation `piston` reports σ of the mean for.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum ObservationLength {
    /// n consecutive scans.
    Scans(u64),
    /// Seconds: n = ⌈T / scan time⌉ at each fringe frequency.
    Seconds(f64),
}

/// The answer of `piston`: the per-scan report, and with an observation
/// length, σ of the mean of its consecutive scans at each frequency.
#[derive(Debug, Clone, serde::Serialize)]
pub struct PistonAnswer {
    /// The per-scan Monte Carlo.
    #[serde(flatten)]
    pub report: PistonReport,
    /// Per fringe frequency: the observation's σ(V²) from the piston.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub observation: Option<Vec<crate::plan::observation::ObservationPiston>>,
}

/// [`run`], and the observation's σ of `req.observation` at each fringe
/// frequency (noise-free V1², V2² of contiguous scans,
/// `plan::observation`).
pub fn run_with_observation(
    prepared: &Prepared,
    p: &Physical,
    req: &PistonRequest,
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> Result<PistonAnswer> {
    let report = run(prepared, p, req, progress)?;
    let Some(length) = req.observation else {
        return Ok(PistonAnswer {
            report,
            observation: None,
        });
    };
    let mut rows = Vec::new();
    for &f in &prepared.fringe_hz {
        let inputs = crate::simulator::Inputs {
            piston: Some(p.piston_inputs(f)?),
            read_noise: 0.0,
            photon_noise: false,
            ..p.inputs_unchecked()?
        };
        let model =
            crate::simulator::Model::with_piston_spectrum(&inputs, prepared.spectrum.clone())?;
        let scan_s = inputs.scan_setup().map_or(f64::NAN, |s| s.scan_time_s());
        let n = match length {
            ObservationLength::Scans(n) => n,
            ObservationLength::Seconds(t) => {
                crate::error::positive("observation_s", t)?;
                (t / scan_s).ceil().max(1.0) as u64
            }
        };
        let seed = crate::montecarlo::derive_seed(req.seed, "piston-observation", &[f]);
        let job = || {
            crate::plan::observation::observation_piston(
                &model,
                &prepared.spectrum,
                n,
                seed,
                &|_| {},
            )
        };
        rows.push(crate::montecarlo::in_pool(req.threads, job)?);
    }
    Ok(PistonAnswer {
        report,
        observation: Some(rows),
    })
}

/// A checked `piston` run, ready to compute.
pub struct Prepared {
    obs: Observation,
    sampling: Sampling,
    /// The differential-piston spectrum (its rms, for the edge's warning).
    pub spectrum: PistonSpectrum,
    /// The detector of every run.
    pub detector: Detector,
    /// The fringe frequencies, Hz, checked.
    pub fringe_hz: Vec<f64>,
}

/// Checks the inputs of `piston` and builds its spectrum (the cost of the
/// run is `fringe_hz.len() × scans` scans).
pub fn prepare(p: &Physical, req: &PistonRequest) -> Result<Prepared> {
    // No channels yet: refused, never the wide band's answer in their place.
    p.refuse_channels("piston")?;
    let obs = p.observation()?;
    let sampling = p.sampling()?;
    sampling.check_aliasing(&obs)?;
    let fringe_hz = fringe_frequencies(&req.fringe_hz)?;
    if req.scans < 2 {
        return Err(Error::OutOfRange {
            param: "scans",
            value: req.scans as f64,
            accepted: ">= 2".into(),
        });
    }
    crate::error::positive("aperture_m", p.aperture_m)?;
    let spectrum = PistonSpectrum::new(p.turbulence()?, p.aperture_m, obs.baseline_m)?
        .with_wind_angle_deg(req.wind_angle_deg)?
        .with_model(req.psd)?;
    let detector = if sampling.integrating() {
        Detector::Integrating {
            sub_samples: p.sub_samples,
        }
    } else {
        Detector::Sampled
    };
    Ok(Prepared {
        obs,
        sampling,
        spectrum,
        detector,
        fringe_hz,
    })
}

/// The frequencies given ([`DEFAULT_FRINGE_HZ`] when none), each checked.
fn fringe_frequencies(given: &[f64]) -> Result<Vec<f64>> {
    let freqs = if given.is_empty() {
        DEFAULT_FRINGE_HZ.to_vec()
    } else {
        given.to_vec()
    };
    for &f in &freqs {
        crate::error::in_range("fringe_hz", f, 1e-3, 1e7)?;
    }
    Ok(freqs)
}

/// The answer of a prepared `piston` run; `progress` counts scans.
pub fn run(
    prepared: &Prepared,
    p: &Physical,
    req: &PistonRequest,
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> Result<PistonReport> {
    let runs = run_frequencies(prepared, p, req, &prepared.fringe_hz, progress)?;
    report(prepared, p, req, &runs)
}

/// The runs of [`run`] at the frequencies `fringe_hz` (some of the
/// prepared ones: each frequency's run depends on its value only), one
/// per frequency.
pub fn run_frequencies(
    prepared: &Prepared,
    p: &Physical,
    req: &PistonRequest,
    fringe_hz: &[f64],
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> Result<Vec<PistonRun>> {
    let Prepared {
        obs,
        sampling,
        spectrum,
        detector,
        ..
    } = prepared;
    let setup = ScanSetup {
        samples: sampling.samples(),
        dx_um: sampling.dx_um(),
        wavelength_um: p.wavelength_um,
        fringe_hz: fringe_hz[0],
        reference: p.reference,
    };
    // Each frequency's seed is derived from the user's and the frequency's
    // value (piston::sweep_seed), not its place in the list.
    let size = RunSize {
        scans: req.scans,
        seed: req.seed,
        threads: req.threads,
    };
    let runs = sweep(
        obs,
        spectrum,
        fringe_hz,
        &setup,
        &[*detector],
        &size,
        progress,
    )?;
    Ok(runs.into_iter().flatten().collect())
}

/// [`run`]'s report of the runs at every prepared frequency, in order.
pub fn report(
    prepared: &Prepared,
    p: &Physical,
    req: &PistonRequest,
    runs: &[PistonRun],
) -> Result<PistonReport> {
    let Prepared {
        obs,
        sampling,
        spectrum,
        detector,
        fringe_hz,
    } = prepared;
    let setup = ScanSetup {
        samples: sampling.samples(),
        dx_um: sampling.dx_um(),
        wavelength_um: p.wavelength_um,
        fringe_hz: fringe_hz[0],
        reference: p.reference,
    };
    let inputs = InputsRecord {
        observation: p.record(obs),
        sampling: Some(SamplingRecord::new(sampling, req.bins)),
        atmosphere: Some(p.atmosphere_record()?),
    };
    let setting = PistonSetting {
        obs,
        spectrum,
        sampling,
        detector: *detector,
        window: req.bins,
        reference: p.reference,
    };
    let mut report = PistonReport::new(inputs, setting, runs);
    if spectrum.model() == PistonPsdModel::ThreeSlope {
        report.three_slope_comparison = three_slope_notes(spectrum, &setup, fringe_hz)?;
    }
    Ok(report)
}

/// Why the three-slope spectrum gives less piston than the two-aperture
/// one of the same site, at the scan time of each fringe frequency.
fn three_slope_notes(
    spectrum: &PistonSpectrum,
    setup: &ScanSetup,
    fringe_hz: &[f64],
) -> Result<Vec<ComparisonNote>> {
    fringe_hz
        .iter()
        .map(|&f| {
            let scan = ScanSetup {
                fringe_hz: f,
                ..*setup
            };
            let comparison = PsdComparison::new(spectrum, scan.scan_time_s())?;
            Ok(ComparisonNote {
                fringe_hz: f,
                note: format!("at {f:.2} Hz, {}", comparison.note()),
                comparison,
            })
        })
        .collect()
}
