//! `plan`: the estimator, fringe frequency, stroke and number of scans that
//! reach a target σ(V²) (or the σ reached in a time budget), in two steps
//! so that an edge can warn and size its progress before the grid runs:
//! [`prepare`] checks the inputs and builds the piston spectrum, [`run`]
//! computes the answer.

use crate::conformance::estimate::BiasConvention;
use crate::error::{Error, Result};
use crate::parameters::Physical;
use crate::piston::spectrum::PistonSpectrum;
use crate::plan::photometry::Magnitude;
use crate::plan::verify::{verification_size, Verification, VerificationSize};
use crate::plan::{default_grid, Plan, PlanInputs, SeeingGiven, Target};
use crate::simulator::Inputs;
use serde::Serialize;

/// σ(V²) aimed at when neither a target nor a time budget is given.
pub const DEFAULT_TARGET_SIGMA_V2: f64 = 1e-3;

/// The options of `plan` beyond the physical inputs (whose sampling,
/// photons and fringe frequency it does not use: it sweeps its own).
#[derive(Debug, Clone, PartialEq)]
pub struct PlanRequest {
    /// Samples per fringe at λ0.
    pub samples_per_fringe: f64,
    /// Photons per second at the detector (unless `magnitude` is given).
    pub photon_rate_per_s: f64,
    /// The source's magnitude, whose photon rate replaces
    /// `photon_rate_per_s`.
    pub magnitude: Option<Magnitude>,
    /// Dead time between scans, s.
    pub dead_time_s: f64,
    /// The detector's maximum sample rate, Hz: the grid's fringe
    /// frequencies are cut (and the default grid extended) to frame rate /
    /// samples per fringe (None: no detector limit, the grid as given).
    pub frame_rate_hz: Option<f64>,
    /// Fringe frequencies of the grid, Hz (the default grid when empty).
    pub fringe_hz: Vec<f64>,
    /// Strokes of the grid, µm (the default grid when empty).
    pub stroke_um: Vec<f64>,
    /// σ(V²) to reach (at most one of this and `time_budget_s`).
    pub target_sigma_v2: Option<f64>,
    /// Time budget, s.
    pub time_budget_s: Option<f64>,
    /// Scans of each piston Monte Carlo.
    pub scans: u64,
    /// Seed.
    pub seed: u64,
    /// The source diameter's uncertainty, mas.
    pub diameter_err_mas: f64,
    /// The bias convention of the user's pipeline.
    pub bias: BiasConvention,
}

/// How the photon rate was obtained from a magnitude (echoed in the
/// answer).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Photometry {
    /// The magnitude, its band, the apertures and the throughput.
    #[serde(flatten)]
    pub magnitude: Magnitude,
    /// The band's zero point, Jy.
    pub zero_point_jy: f64,
    /// The band's isophotal wavelength, µm.
    pub isophotal_wavelength_um: f64,
    /// The two apertures' collecting area, m².
    pub collecting_area_m2: f64,
    /// The photon rate at the detector over the observing band, photons/s.
    pub photon_rate_per_s: f64,
    /// Where the zero point comes from.
    pub reference: &'static str,
}

/// The answer of `plan`: what it used, and the plan.
#[derive(Debug, Clone, Serialize)]
pub struct PlanAnswer {
    /// The inputs as used (the seeing at the observing wavelength).
    pub inputs: PlanInputs,
    /// The seeing as given.
    pub seeing_as_given: SeeingGiven,
    /// The photometry, when the rate came from a magnitude.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub photometry: Option<Photometry>,
    /// Every grid point and the recommendation.
    #[serde(flatten)]
    pub plan: Plan,
    /// The recommended observation simulated (`verify`), beside its promise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub verification: Option<Verification>,
}

/// A checked plan, ready to run.
pub struct Prepared {
    /// The plan's inputs.
    pub inputs: PlanInputs,
    /// The differential-piston spectrum (its rms, for the edge's warning).
    pub piston: PistonSpectrum,
    seeing_as_given: SeeingGiven,
    photometry: Option<Photometry>,
}

impl Prepared {
    /// Grid points the run computes (its progress counts them).
    pub fn points(&self) -> u64 {
        (self.inputs.fringe_hz.len() * self.inputs.stroke_um.len()) as u64
    }
}

/// The target of the plan.
fn target(req: &PlanRequest) -> Result<Target> {
    match (req.target_sigma_v2, req.time_budget_s) {
        (Some(_), Some(_)) => Err(Error::Invalid {
            param: "time_budget_s",
            reason: "give target_sigma_v2 or time_budget_s, not both".into(),
        }),
        (_, Some(b)) => Ok(Target::TimeBudgetS(b)),
        (Some(s), None) => Ok(Target::SigmaV2(s)),
        (None, None) => Ok(Target::SigmaV2(DEFAULT_TARGET_SIGMA_V2)),
    }
}

/// The photometry of `magnitude` over the band of `p`.
fn photometry(p: &Physical, m: Magnitude) -> Result<Photometry> {
    Ok(Photometry {
        magnitude: m,
        zero_point_jy: m.band.zero_point_jy(),
        isophotal_wavelength_um: m.band.isophotal_wavelength_um(),
        collecting_area_m2: m.collecting_area_m2(),
        photon_rate_per_s: m.photon_rate_per_s(p.wavelength_um, p.bandwidth_nm * 1e-3)?,
        reference: m.band.zero_point_reference(),
    })
}

/// Checks the inputs of `plan` and builds its piston spectrum.
pub fn prepare(p: &Physical, req: &PlanRequest) -> Result<Prepared> {
    // No channels yet: refused, never the wide band's answer in their place.
    p.refuse_channels("plan")?;
    let photometry = req.magnitude.map(|m| photometry(p, m)).transpose()?;
    let (default_f, default_s) = default_grid();
    let or_default = |given: &[f64], default: Vec<f64>| {
        if given.is_empty() {
            default
        } else {
            given.to_vec()
        }
    };
    let inputs = PlanInputs {
        // The sampling, photons and piston are set per grid point.
        instrument: Inputs {
            piston: None,
            ..p.inputs_unchecked()?
        },
        atmosphere: p.piston_inputs(1.0)?,
        samples_per_fringe: req.samples_per_fringe,
        photon_rate_per_s: photometry.map_or(req.photon_rate_per_s, |m| m.photon_rate_per_s),
        dead_time_s: req.dead_time_s,
        frame_rate_hz: req.frame_rate_hz,
        fringe_hz: match req.frame_rate_hz {
            Some(rate) if rate.is_finite() && rate > 0.0 => {
                crate::plan::detector_grid(&req.fringe_hz, rate / req.samples_per_fringe)
            }
            _ => or_default(&req.fringe_hz, default_f),
        },
        stroke_um: or_default(&req.stroke_um, default_s),
        target: target(req)?,
        scans: req.scans,
        seed: req.seed,
        diameter_err_mas: req.diameter_err_mas,
        bias: req.bias,
    };
    inputs.validate()?;
    let piston = inputs.atmosphere.spectrum(inputs.instrument.baseline_m)?;
    Ok(Prepared {
        inputs,
        piston,
        seeing_as_given: SeeingGiven {
            arcsec: p.seeing_arcsec,
            wavelength_um: p.seeing_wavelength_um.unwrap_or(p.wavelength_um),
        },
        photometry,
    })
}

/// The answer of a prepared plan; `progress` counts grid points.
pub fn run(
    prepared: Prepared,
    threads: usize,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<PlanAnswer> {
    let plan = crate::plan::plan(&prepared.inputs, threads, progress)?;
    Ok(PlanAnswer {
        inputs: prepared.inputs,
        seeing_as_given: prepared.seeing_as_given,
        photometry: prepared.photometry,
        plan,
        verification: None,
    })
}

/// The size of the verification of `answer`'s recommendation with
/// `observations` simulated observations (for its announced cost), or why
/// there is none to verify.
pub fn verification(answer: &PlanAnswer, observations: u64) -> Result<VerificationSize> {
    let p = answer.plan.recommended.ok_or_else(|| Error::Invalid {
        param: "verify",
        reason: "the plan recommends nothing to verify".into(),
    })?;
    let sky = answer
        .inputs
        .atmosphere
        .spectrum(answer.inputs.instrument.baseline_m)?;
    verification_size(&answer.inputs, &sky, &p, observations)
}

/// Simulates the recommended observation of `answer` ([`verification`]'s
/// size) and records what it achieved in the answer; `progress` counts
/// scans.
pub fn verify(
    answer: &mut PlanAnswer,
    size: &VerificationSize,
    threads: usize,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<()> {
    let Some(p) = answer.plan.recommended else {
        return Err(Error::Invalid {
            param: "verify",
            reason: "the plan recommends nothing to verify".into(),
        });
    };
    let inputs = &answer.inputs;
    let sky = inputs.atmosphere.spectrum(inputs.instrument.baseline_m)?;
    let v = crate::montecarlo::in_pool(threads, || {
        crate::plan::verify::verify(inputs, &sky, &p, size, progress)
    })?;
    answer.verification = Some(v);
    Ok(())
}

/// [`verify`] with the simulated observations' means of V1² and V2² given
/// (reduced from the units of [`crate::units::verify::VerifyJob`]).
pub fn record_verification(
    answer: &mut PlanAnswer,
    size: &VerificationSize,
    block_means: [crate::montecarlo::Summary; 2],
) -> Result<()> {
    let Some(p) = answer.plan.recommended else {
        return Err(Error::Invalid {
            param: "verify",
            reason: "the plan recommends nothing to verify".into(),
        });
    };
    let v = crate::plan::verify::verification_of(&answer.inputs, &p, size, block_means)?;
    answer.verification = Some(v);
    Ok(())
}
