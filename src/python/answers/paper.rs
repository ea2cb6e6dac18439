//! The paper's effects one at a time: `bias`, `snr`, `piston`, `claims`.

use super::{formula, json, window};
use crate::bias::report::BiasReport;
use crate::error::Error;
use crate::noise::report::{Light, SnrReport};
use crate::piston::report::{PistonReport, PistonSetting};
use crate::piston::spectrum::PistonPsdModel;
use crate::piston::turbulence::{PistonSpectrum, Turbulence};
use crate::piston::{sweep, Detector, PistonRun, RunSize, ScanSetup};
use crate::python::inputs::Physical;
use crate::python::{interruptible, ok, parse_enum, Fail};
use crate::reproduction::cases::Effort;
use crate::simulator::record::{InputsRecord, SamplingRecord};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// `bias`: `v2ref bias --json`.
#[pyfunction]
#[pyo3(signature = (physical, bins, finite_scan))]
pub(super) fn bias(
    physical: &Bound<'_, PyDict>,
    bins: &str,
    finite_scan: bool,
) -> PyResult<String> {
    let p = Physical::from_dict(physical)?;
    let window = ok(window(bins))?;
    let obs = ok(p.observation())?;
    let sampling = if finite_scan || p.stroke_um.is_some() {
        Some(ok(p.sampling())?)
    } else {
        None
    };
    let scan = sampling.as_ref().map(|s| (s, window));
    json(&ok(BiasReport::new(&obs, p.record(&obs), scan))?)
}

/// `snr`: `v2ref snr --json`.
#[pyfunction]
#[pyo3(signature = (physical, bins, formula))]
pub(super) fn snr(physical: &Bound<'_, PyDict>, bins: &str, formula: &str) -> PyResult<String> {
    let p = Physical::from_dict(physical)?;
    let window = ok(window(bins))?;
    let formula = ok(self::formula(formula))?;
    let noise = ok(p.noise())?;
    let obs = ok(p.observation())?;
    let sampling = ok(p.sampling())?;
    let light = Light {
        photons: p.photons,
        visibility: p.visibility,
        noise,
    };
    json(&ok(SnrReport::new(
        &obs,
        p.record(&obs),
        &sampling,
        window,
        light,
        formula,
    ))?)
}

/// `piston`: `v2ref piston --json` (`physical` without `fringe_hz`; `psd`
/// and `wind_angle_deg` as `--psd`, `--wind-angle-deg`).
#[pyfunction]
#[pyo3(signature = (physical, fringe_hz, bins, scans, seed, threads, psd, wind_angle_deg))]
#[allow(clippy::too_many_arguments)]
pub(super) fn piston(
    py: Python<'_>,
    physical: &Bound<'_, PyDict>,
    fringe_hz: Vec<f64>,
    bins: &str,
    scans: usize,
    seed: u64,
    threads: usize,
    psd: &str,
    wind_angle_deg: f64,
) -> PyResult<String> {
    let psd: PistonPsdModel = ok(parse_enum("psd", psd, &["two-aperture", "three-slope"]))?;
    let p = Physical::from_dict(physical)?;
    let window = ok(window(bins))?;
    let reference = p.reference;
    let obs = ok(p.observation())?;
    let sampling = ok(p.sampling())?;
    ok(sampling.check_aliasing(&obs))?;
    let freqs = fringe_frequencies(fringe_hz, scans)?;
    let spectrum = piston_spectrum(&p, obs.baseline_m, wind_angle_deg, psd)?;
    let detector = if sampling.integrating() {
        Detector::Integrating {
            sub_samples: p.sub_samples,
        }
    } else {
        Detector::Sampled
    };
    let setup = ScanSetup {
        samples: sampling.samples(),
        dx_um: sampling.dx_um(),
        wavelength_um: p.wavelength_um,
        fringe_hz: freqs[0],
        reference,
    };
    let size = RunSize {
        scans,
        seed,
        threads,
    };
    let runs = interruptible(py, |tick| {
        sweep(
            &obs,
            &spectrum,
            &freqs,
            &setup,
            &[detector],
            &size,
            Some(tick),
        )
    })?;
    let runs: Vec<PistonRun> = runs.into_iter().flatten().collect();
    let inputs = InputsRecord {
        observation: p.record(&obs),
        sampling: Some(SamplingRecord::new(&sampling, window)),
        atmosphere: Some(ok(p.atmosphere_record())?),
    };
    let setting = PistonSetting {
        obs: &obs,
        spectrum: &spectrum,
        sampling: &sampling,
        detector,
        window,
        reference,
    };
    json(&PistonReport::new(inputs, setting, &runs))
}

/// The fringe frequencies of `piston` (300 and 1000 Hz when none is
/// given), each checked, and the scans checked (at least two).
fn fringe_frequencies(fringe_hz: Vec<f64>, scans: usize) -> PyResult<Vec<f64>> {
    let freqs = if fringe_hz.is_empty() {
        vec![300.0, 1000.0]
    } else {
        fringe_hz
    };
    for &f in &freqs {
        ok(crate::error::in_range("fringe_hz", f, 1e-3, 1e7))?;
    }
    if scans < 2 {
        return Err(Error::OutOfRange {
            param: "scans",
            value: scans as f64,
            accepted: ">= 2".into(),
        }
        .into_py_err());
    }
    Ok(freqs)
}

/// The differential-piston spectrum of `piston`: the turbulence of the
/// seeing, on the baseline `baseline_m`, the wind at `wind_angle_deg` to
/// it, under the model `psd`.
fn piston_spectrum(
    p: &Physical,
    baseline_m: f64,
    wind_angle_deg: f64,
    psd: PistonPsdModel,
) -> PyResult<PistonSpectrum> {
    ok(crate::error::positive("aperture_m", p.aperture_m))?;
    let turb = ok(Turbulence::from_seeing(
        ok(p.seeing_at_observing_arcsec())?,
        p.wavelength_um,
        p.wind_mps,
        p.outer_scale_m,
    ))?;
    ok(PistonSpectrum::new(turb, p.aperture_m, baseline_m)
        .and_then(|s| s.with_wind_angle_deg(wind_angle_deg))
        .and_then(|s| s.with_model(psd)))
}

/// `claims`: `v2ref claims --json` (`quick`: `--quick`).
#[pyfunction]
#[pyo3(signature = (quick))]
pub(super) fn claims(py: Python<'_>, quick: bool) -> PyResult<String> {
    let effort = if quick { Effort::Quick } else { Effort::Full };
    let results = interruptible(py, |_| Ok(crate::reproduction::claims::evaluate(effort)))?;
    json(&results)
}
