//! What the plan's answer says beside the numbers: the inputs as they were
//! used, the seeing as given, durations a person reads, and why an
//! estimator has no recommendation.

use super::{Estimator, Plan, CONFIDENCE};
use crate::simulator::{Inputs, PistonInputs};
use serde::Serialize;

/// The seeing as the user gave it (the plan's inputs hold it converted to
/// the observing wavelength by r0 ∝ λ^(6/5)).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SeeingGiven {
    /// λ/r0, arcsec, at `wavelength_um`.
    pub arcsec: f64,
    /// Where it was quoted, µm.
    pub wavelength_um: f64,
}

/// The instrument as the plan used it: without the per-grid-point
/// placeholders (samples, δx, photons per sample, piston).
pub(super) fn echo_instrument<S: serde::Serializer>(
    i: &Inputs,
    s: S,
) -> std::result::Result<S::Ok, S::Error> {
    #[derive(Serialize)]
    struct Used<'a> {
        spectrum: &'a crate::simulator::SpectrumInput,
        source: &'a crate::simulator::SourceInput,
        baseline_m: f64,
        dispersion_pp_rad: f64,
        integrating: bool,
        visibility: f64,
        read_noise: f64,
        photon_noise: bool,
    }
    Used {
        spectrum: &i.spectrum,
        source: &i.source,
        baseline_m: i.baseline_m,
        dispersion_pp_rad: i.dispersion_pp_rad,
        integrating: i.integrating,
        visibility: i.visibility,
        read_noise: i.read_noise,
        photon_noise: i.photon_noise,
    }
    .serialize(s)
}

/// The atmosphere as the plan used it, without the per-point fringe
/// frequency; the seeing is the one at `wavelength_um`.
pub(super) fn echo_atmosphere<S: serde::Serializer>(
    a: &PistonInputs,
    s: S,
) -> std::result::Result<S::Ok, S::Error> {
    #[derive(Serialize)]
    struct Used {
        wavelength_um: f64,
        seeing_at_observing_arcsec: f64,
        wind_mps: f64,
        aperture_m: f64,
        outer_scale_m: crate::record::OuterScale,
        reference: crate::piston::PistonReference,
        sub_samples: usize,
    }
    Used {
        wavelength_um: a.wavelength_um,
        seeing_at_observing_arcsec: a.seeing_arcsec,
        wind_mps: a.wind_mps,
        aperture_m: a.aperture_m,
        outer_scale_m: a.outer_scale_m.into(),
        reference: a.reference,
        sub_samples: a.sub_samples,
    }
    .serialize(s)
}

/// A duration in the unit a person reads it in: seconds below two minutes,
/// minutes below two hours, hours below two days, days beyond, with three
/// significant figures.
///
/// ```
/// use v2ref_commands::plan::human_duration;
/// assert_eq!(human_duration(42.0), "42.0 s");
/// assert_eq!(human_duration(1_168_782.9), "13.5 d");
/// assert_eq!(human_duration(5400.0), "90.0 min");
/// ```
pub fn human_duration(seconds: f64) -> String {
    let (value, unit) = match seconds {
        s if s < 120.0 => (s, "s"),
        s if s < 7200.0 => (s / 60.0, "min"),
        s if s < 172_800.0 => (s / 3600.0, "h"),
        s => (s / 86_400.0, "d"),
    };
    let decimals = if value >= 100.0 {
        0
    } else if value >= 10.0 {
        1
    } else {
        2
    };
    let decimals = if unit == "s" && value < 100.0 {
        1
    } else {
        decimals
    };
    format!("{value:.decimals$} {unit}")
}

/// Why an estimator has no recommended point, in one line (None when it
/// has one).
pub fn no_recommendation_reason(plan: &Plan, e: Estimator) -> Option<String> {
    let best = match e {
        Estimator::V1 => plan.best_v1,
        Estimator::V2 => plan.best_v2,
    };
    if best.is_some() {
        return None;
    }
    let ours = || plan.points.iter().filter(|p| p.estimator == e);
    if ours().all(|p| p.why_null == Some(super::reach::SHORT_BUDGET)) {
        return Some(format!(
            "no setting of the grid: {}",
            super::reach::SHORT_BUDGET
        ));
    }
    let least_bias = ours()
        .map(|p| p.bias_piston_upper)
        .fold(f64::INFINITY, f64::min);
    Some(format!(
        "no setting of the grid reaches the target: the piston bias (upper end of its {:.0}% interval) is at least {least_bias:.2e} everywhere",
        CONFIDENCE * 100.0
    ))
}

/// Where the recommendation sits on an edge of the grid, in one line (None
/// inside it, or on a grid of one value; a stroke is on an edge when its
/// whole samples are those of the grid's shortest or longest stroke,
/// whatever the rounding to whole samples did to it): the best setting may then lie
/// outside the grid, which the plan does not search; the user widens it
/// (`--fringe-hz`, `--stroke-um`) within what the detector allows (it
/// reads `samples per fringe × f` frames per second).
pub fn grid_edge_note(plan: &Plan, inputs: &super::PlanInputs) -> Option<String> {
    let p = plan.recommended?;
    let edge = |values: &[f64], v: f64| {
        let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        match () {
            _ if lo == hi => None,
            _ if v >= hi => Some(("top", lo, hi)),
            _ if v <= lo => Some(("bottom", lo, hi)),
            _ => None,
        }
    };
    let mut notes = Vec::new();
    let at_detector = inputs
        .fringe_hz_max()
        .is_some_and(|most| p.fringe_hz >= most * (1.0 - 1e-12));
    if at_detector {
        notes.push(format!(
            "the fringe frequency {:.1} Hz is the detector's edge ({} frames/s at {} samples per fringe): a faster fringe needs a faster detector or fewer samples per fringe, not a wider grid",
            p.fringe_hz,
            inputs.frame_rate_hz.unwrap_or(f64::NAN),
            inputs.samples_per_fringe
        ));
    } else if let Some((side, lo, hi)) = edge(&inputs.fringe_hz, p.fringe_hz) {
        notes.push(format!(
            "the fringe frequency {:.1} Hz is the {side} of the grid ({lo:.1} to {hi:.1} Hz; {:.0} detector frames/s at {:.1} Hz)",
            p.fringe_hz,
            inputs.samples_per_fringe * hi,
            hi
        ));
    }
    // In the grid's own terms: a stroke is planned as whole samples, so
    // the point's true stroke (N δx) may lie a little above or below the
    // grid value it came from; its sample count is what the grid's
    // strokes are compared by.
    let whole_samples = |stroke_um: f64| (stroke_um / p.dx_um).round();
    let grid_samples: Vec<f64> = inputs.stroke_um.iter().map(|&s| whole_samples(s)).collect();
    if let Some((side, _, _)) = edge(&grid_samples, p.samples as f64) {
        let lo = inputs
            .stroke_um
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
        let hi = inputs
            .stroke_um
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max);
        notes.push(format!(
            "the stroke {:.3} um ({} whole samples of {:.4} um) is the {side} of the grid ({lo} to {hi} um)",
            p.stroke_um, p.samples, p.dx_um
        ));
    }
    if notes.len() == 1 && at_detector {
        return Some(format!("on the detector's edge: {}", notes[0]));
    }
    let widen = if inputs.frame_rate_hz.is_some() {
        "widen the grid (--fringe-hz up to the detector's edge, --stroke-um) within what the delay line allows"
    } else {
        "widen the grid (--fringe-hz, --stroke-um) within what the detector and the delay line allow, or give the detector's --frame-rate-hz to search up to its edge"
    };
    (!notes.is_empty()).then(|| {
        format!(
            "on the edge of the grid: {}; the best setting may lie beyond it, which the plan did not search: {widen}",
            notes.join("; ")
        )
    })
}

/// What an observation's variance inflation
/// ([`super::ObservationError::variance_inflation`]) is, and why it lies on
/// its side of 1, in one line for the plan's text.
///
/// The inflation is `n σ²_piston(n) / σ²_piston,scan`: the piston variance
/// of the mean of n consecutive scans over that of n independent scans.
/// Above 1, consecutive scans share the piston's slow wander. Below 1, the
/// scans' errors cancel: the fringe is re-centred on each scan's mean
/// piston, so a scan's error follows the piston's drift within the scan,
/// and the drifts of n consecutive scans add up to the observation's net
/// drift, bounded by the piston's rms; the variance of their mean then
/// falls faster than 1/n, as 1/n² over many correlation times (measured
/// with `v2ref piston --observation-scans` in H on 100 m at 1000 Hz:
/// inflation 6.1 at n = 10 and 100, 0.93 at 1000, 0.35 at 2000).
///
/// ```
/// use v2ref_commands::plan::inflation_words;
/// assert!(inflation_words(0.07).contains("below 1"));
/// assert!(inflation_words(3.0).contains("above 1"));
/// ```
pub fn inflation_words(inflation: f64) -> String {
    let what = "inflation: the piston variance of the mean of n consecutive scans over that of n independent scans (n sigma_piston(n)^2 / sigma_piston per scan^2; 1 for independent scans)";
    let why = if inflation < 1.0 {
        "below 1 here: with the fringe re-centred on each scan's mean piston, a scan's piston error follows the piston's drift within the scan, and over n scans those drifts add up to the net drift of the observation, bounded by the piston's rms, so the errors of scans a correlation time apart cancel and the variance of their mean falls faster than 1/n (as 1/n^2 over many correlation times)"
    } else {
        "at or above 1 here: consecutive scans share the piston's slow wander, so their errors persist from scan to scan and average out more slowly than 1/n"
    };
    format!("{what}; {why}")
}
