//! The planner: `plan`, `photon_rate`.

use super::json;
use crate::error::Error;
use crate::plan::{default_grid, Plan, PlanInputs, SeeingGiven, Target};
use crate::python::inputs::Physical;
use crate::python::{interruptible, ok, parse_enum, Fail};
use crate::simulator::PistonInputs;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// `plan`: `v2ref plan --json` (`physical` without `fringe_hz`; exactly one
/// of `target_sigma_v2` and `time_budget_s`, or neither for σ(V²) = 1e-3).
#[pyfunction]
#[pyo3(signature = (physical, samples_per_fringe, photon_rate_per_s, dead_time_s, fringe_hz, stroke_um, target_sigma_v2, time_budget_s, scans, seed, threads, diameter_err_mas=0.0))]
#[allow(clippy::too_many_arguments)]
pub(super) fn plan(
    py: Python<'_>,
    physical: &Bound<'_, PyDict>,
    samples_per_fringe: f64,
    photon_rate_per_s: f64,
    dead_time_s: f64,
    fringe_hz: Vec<f64>,
    stroke_um: Vec<f64>,
    target_sigma_v2: Option<f64>,
    time_budget_s: Option<f64>,
    scans: u64,
    seed: u64,
    threads: usize,
    diameter_err_mas: f64,
) -> PyResult<String> {
    let p = Physical::from_dict(physical)?;
    let instrument = ok(p.inputs_unchecked())?;
    let target = target(target_sigma_v2, time_budget_s)?;
    let (default_f, default_s) = default_grid();
    let inputs = PlanInputs {
        atmosphere: atmosphere(&p)?,
        instrument,
        samples_per_fringe,
        photon_rate_per_s,
        dead_time_s,
        fringe_hz: if fringe_hz.is_empty() {
            default_f
        } else {
            fringe_hz
        },
        stroke_um: if stroke_um.is_empty() {
            default_s
        } else {
            stroke_um
        },
        target,
        scans,
        seed,
        diameter_err_mas,
    };
    let result = interruptible(py, |tick| crate::plan::plan(&inputs, threads, tick))?;
    json(&Answer {
        inputs: &inputs,
        seeing_as_given: SeeingGiven {
            arcsec: p.seeing_arcsec,
            wavelength_um: p.seeing_wavelength_um.unwrap_or(p.wavelength_um),
        },
        plan: &result,
    })
}

/// The answer of `plan`: the inputs, the seeing as given and the plan.
#[derive(serde::Serialize)]
struct Answer<'a> {
    inputs: &'a PlanInputs,
    seeing_as_given: SeeingGiven,
    #[serde(flatten)]
    plan: &'a Plan,
}

/// What the plan aims at: σ(V²) or a time budget (not both; σ(V²) = 1e-3
/// when neither is given).
fn target(target_sigma_v2: Option<f64>, time_budget_s: Option<f64>) -> PyResult<Target> {
    match (target_sigma_v2, time_budget_s) {
        (Some(_), Some(_)) => Err(Error::Invalid {
            param: "time_budget_s",
            reason: "give target_sigma_v2 or time_budget_s, not both".into(),
        }
        .into_py_err()),
        (_, Some(b)) => Ok(Target::TimeBudgetS(b)),
        (Some(s), None) => Ok(Target::SigmaV2(s)),
        (None, None) => Ok(Target::SigmaV2(1e-3)),
    }
}

/// The atmosphere of the plan (its fringe frequency a placeholder: the
/// plan sweeps its own), the seeing at the observing wavelength.
fn atmosphere(p: &Physical) -> PyResult<PistonInputs> {
    Ok(PistonInputs {
        fringe_hz: 1.0,
        wavelength_um: p.wavelength_um,
        seeing_arcsec: ok(p.seeing_at_observing_arcsec())?,
        wind_mps: p.wind_mps,
        aperture_m: p.aperture_m,
        outer_scale_m: p.outer_scale_m,
        reference: p.reference,
        sub_samples: p.sub_samples,
    })
}

/// `photon_rate`: the photon rate at the detector from a 2MASS magnitude
/// (`v2ref plan --magnitude`).
#[pyfunction]
#[pyo3(signature = (magnitude, band, aperture_m, throughput, wavelength_um, bandwidth_nm))]
pub(super) fn photon_rate(
    magnitude: f64,
    band: &str,
    aperture_m: f64,
    throughput: f64,
    wavelength_um: f64,
    bandwidth_nm: f64,
) -> PyResult<f64> {
    use crate::plan::photometry::{Band2Mass, Magnitude};
    let band: Band2Mass = ok(parse_enum("band", band, &["J", "H", "Ks", "V", "R", "I"]))?;
    let m = Magnitude {
        magnitude,
        band,
        aperture_m,
        throughput,
    };
    ok(m.photon_rate_per_s(wavelength_um, bandwidth_nm * 1e-3))
}
