//! The functions of `v2ref._v2ref`: one per CLI command, each building the
//! same answer as the command (`src/cli/<command>.rs`) from the same
//! library calls.

use super::inputs::Physical;
use super::{interruptible, ok, parse_enum, Fail};
use crate::bias::report::BiasReport;
use crate::conformance::estimate::{BiasConvention, RowEstimate, RowEstimator};
use crate::conformance::score::score_report;
use crate::conformance::sidecar::{DataFiles, Sidecar, FORMAT};
use crate::conformance::truth::{truth, TruthSize};
use crate::error::{Error, Result};
use crate::formalism::estimator::{BinWindow, Pair};
use crate::noise::calibrated::Trials;
use crate::noise::report::{Light, SnrReport};
use crate::noise::Formula;
use crate::piston::report::{PistonReport, PistonSetting};
use crate::piston::spectrum::PistonPsdModel;
use crate::piston::turbulence::{PistonSpectrum, Turbulence};
use crate::piston::{sweep, Detector, PistonRun, RunSize, ScanSetup};
use crate::reproduction::cases::Effort;
use crate::simulator::record::{InputsRecord, SamplingRecord};
use crate::simulator::report::{check_trials, Estimation, SimulateReport};
use crate::simulator::{simulate as run_simulation, Model};
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde::Serialize;

/// Units generated at once while streaming.
const STREAM_BATCH_UNITS: u64 = 8;

fn window(s: &str) -> Result<BinWindow> {
    parse_enum("bins", s, &["positive", "band", "all"])
}

fn convention(s: &str) -> Result<BiasConvention> {
    parse_enum("bias", s, &["model", "counts"])
}

fn formula(s: &str) -> Result<Formula> {
    match s {
        "published" => Ok(Formula::Published),
        "exact" => Ok(Formula::Exact),
        _ => Err(Error::Invalid {
            param: "formula",
            reason: format!("'{s}' is not one of: published, exact"),
        }),
    }
}

fn json<T: Serialize>(value: &T) -> PyResult<String> {
    serde_json::to_string(value)
        .map_err(|e| PyValueError::new_err(format!("cannot serialize the answer: {e}")))
}

/// Unusable content of an array argument.
fn data_error(param: &str, location: &str, reason: &str) -> PyErr {
    if location.is_empty() {
        PyValueError::new_err(format!("{param}: {reason}"))
    } else {
        PyValueError::new_err(format!("{param}: {location}: {reason}"))
    }
}

/// The first non-finite value of a row-major matrix of `cols` columns.
fn check_finite(param: &str, data: &[f64], cols: usize) -> PyResult<()> {
    match data.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(i) => Err(data_error(
            param,
            &format!("row {}, column {} (1-based)", i / cols + 1, i % cols + 1),
            &format!(
                "{} is not a finite number; every value must be finite",
                data[i]
            ),
        )),
    }
}

/// A 2-D C-contiguous float64 array as (rows, cols, data).
fn matrix<'a>(
    param: &str,
    a: &'a PyReadonlyArray2<'_, f64>,
) -> PyResult<(usize, usize, &'a [f64])> {
    let shape = a.shape();
    let (rows, cols) = (shape[0], shape[1]);
    if rows == 0 || cols == 0 {
        return Err(data_error(
            param,
            "",
            &format!(
                "empty ({rows} rows, {cols} columns); at least one row and one column are needed"
            ),
        ));
    }
    let data = a.as_slice().map_err(|_| {
        pyo3::exceptions::PyTypeError::new_err(format!(
            "{param}: not a C-contiguous array (pass numpy.ascontiguousarray(x))"
        ))
    })?;
    Ok((rows, cols, data))
}

/// A sidecar from its JSON text (`name`: where it came from, for messages).
fn parse_sidecar(text: &str, name: &str) -> PyResult<Sidecar> {
    let value: serde_json::Value = serde_json::from_str(text).map_err(|e| {
        data_error(
            "sidecar",
            name,
            &format!("not JSON ({e}); the sidecar written by v2ref synth is needed"),
        )
    })?;
    match value.get("format") {
        Some(serde_json::Value::String(f)) if f == FORMAT => {}
        Some(f) => {
            return Err(data_error(
                "sidecar",
                &format!("{name}: field format"),
                &format!("{f}; \"{FORMAT}\" is needed"),
            ))
        }
        None => {
            return Err(data_error(
                "sidecar",
                &format!("{name}: field format"),
                &format!("missing; \"{FORMAT}\" is needed"),
            ))
        }
    }
    serde_json::from_value::<Sidecar>(value)
        .map_err(|e| data_error("sidecar", name, &format!("not a v2ref sidecar: {e}")))
}

/// The columns of `estimate`, in the order of `v2ref estimate`.
const ESTIMATE_COLUMNS: [&str; 6] = [
    "v1_sq_raw",
    "v2_sq_raw",
    "v1_sq_bias",
    "v2_sq_bias",
    "v1_sq",
    "v2_sq",
];

/// The first non-finite value of the interferograms, found without a
/// pass over all of them: a NaN or infinity in a row makes its raw
/// estimates non-finite (sums and products with unit-modulus twiddles
/// keep it), so only the rows whose raw estimates are not finite are
/// searched, in order.
fn check_rows_finite(data: &[f64], cols: usize, rows: &[RowEstimate]) -> PyResult<()> {
    for (r, e) in rows.iter().enumerate() {
        if e.v1_sq_raw.is_finite() && e.v2_sq_raw.is_finite() {
            continue;
        }
        let row = &data[r * cols..(r + 1) * cols];
        if let Some(c) = row.iter().position(|v| !v.is_finite()) {
            return Err(data_error(
                "interferograms",
                &format!("row {}, column {} (1-based)", r + 1, c + 1),
                &format!(
                    "{} is not a finite number; every value must be finite",
                    row[c]
                ),
            ));
        }
    }
    Ok(())
}

/// `estimate`: per-row V1², V2² (raw, bias, normalized), as `v2ref
/// estimate`. `physical` holds only the keyword arguments given;
/// `sidecar` is a sidecar's JSON text, `sidecar_name` where it came from.
#[pyfunction]
#[pyo3(signature = (interferograms, physical, sidecar, sidecar_name, continuum_subtracted, bins, bias, calibrator, threads))]
#[allow(clippy::too_many_arguments)]
fn estimate<'py>(
    py: Python<'py>,
    interferograms: PyReadonlyArray2<'py, f64>,
    physical: &Bound<'py, PyDict>,
    sidecar: Option<&str>,
    sidecar_name: &str,
    continuum_subtracted: Option<bool>,
    bins: &str,
    bias: &str,
    calibrator: Option<PyReadonlyArray2<'py, f64>>,
    threads: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let window = ok(window(bins))?;
    let bias = ok(convention(bias))?;
    let (rows, cols, data) = matrix("interferograms", &interferograms)?;
    let (mut inputs, continuum_subtracted, strict) = match sidecar {
        Some(text) => {
            if let Some((k, _)) = physical.iter().next() {
                return Err(PyValueError::new_err(format!(
                    "{k}: cannot be used with sidecar (the configuration comes from it)"
                )));
            }
            if continuum_subtracted.is_some() {
                return Err(PyValueError::new_err(
                    "continuum_subtracted: cannot be used with sidecar (the configuration comes from it)",
                ));
            }
            let sc = parse_sidecar(text, sidecar_name)?;
            if rows as u64 != sc.data.rows {
                return Err(data_error(
                    "interferograms",
                    "",
                    &format!("{rows} rows; its sidecar says {}", sc.data.rows),
                ));
            }
            (sc.inputs, sc.continuum_subtracted, true)
        }
        None => {
            let p = Physical::from_dict(physical)?;
            (
                ok(p.inputs_unchecked())?,
                continuum_subtracted.unwrap_or(true),
                false,
            )
        }
    };
    if inputs.samples != cols {
        if strict || inputs.piston.is_some() {
            return Err(data_error(
                "interferograms",
                "",
                &format!(
                    "{cols} columns; the configuration has {} samples per row",
                    inputs.samples
                ),
            ));
        }
        inputs.samples = cols;
    }
    ok(inputs.validate())?;
    let model = ok(Model::new(&inputs))?;
    let est = ok(RowEstimator::new(
        &model,
        window,
        bias,
        continuum_subtracted,
    ))?;
    let cal = match &calibrator {
        None => None,
        Some(c) => {
            let (_, ccols, cdata) = matrix("calibrator", c)?;
            check_finite("calibrator", cdata, ccols)?;
            if ccols != cols {
                return Err(data_error(
                    "calibrator",
                    "",
                    &format!("{ccols} columns; the interferograms have {cols}"),
                ));
            }
            Some(cdata)
        }
    };
    let rows = py.allow_threads(|| -> Result<Vec<RowEstimate>> {
        let est = match cal {
            None => est,
            Some(cdata) => {
                let cal_model = model.calibrator_model()?;
                let cal_est = RowEstimator::new(&cal_model, window, bias, continuum_subtracted)?;
                let c: Pair = cal_est.calibration_from_rows(cdata, threads)?;
                est.with_calibration(c)?
            }
        };
        est.estimate_rows(data, threads)
    });
    let rows = ok(rows)?;
    check_rows_finite(data, cols, &rows)?;
    let mut columns: [Vec<f64>; 6] = std::array::from_fn(|_| Vec::with_capacity(rows.len()));
    for e in &rows {
        for (c, v) in columns.iter_mut().zip([
            e.v1_sq_raw,
            e.v2_sq_raw,
            e.v1_sq_bias,
            e.v2_sq_bias,
            e.v1_sq,
            e.v2_sq,
        ]) {
            c.push(v);
        }
    }
    let out = PyDict::new(py);
    for (name, c) in ESTIMATE_COLUMNS.iter().zip(columns) {
        out.set_item(name, PyArray1::from_vec(py, c))?;
    }
    Ok(out)
}

/// `synthesize`: a set's rows (2-D array) and its sidecar (JSON text), as
/// `v2ref synth` writes them; `npy` is the data file name recorded.
#[pyfunction]
#[pyo3(signature = (physical, rows, seed, threads, reference_blocks, keep_continuum, npy))]
#[allow(clippy::too_many_arguments)]
fn synthesize<'py>(
    py: Python<'py>,
    physical: &Bound<'py, PyDict>,
    rows: u64,
    seed: u64,
    threads: usize,
    reference_blocks: Option<u64>,
    keep_continuum: bool,
    npy: String,
) -> PyResult<(Bound<'py, PyAny>, String)> {
    let inputs = ok(Physical::from_dict(physical)?.inputs())?;
    // None: sized by what the truth needs (`default_reference_blocks`).
    let reference_blocks = reference_blocks.unwrap_or_else(|| {
        crate::conformance::truth::default_reference_blocks(inputs.piston.is_some())
    });
    ok(crate::bounds::check_set_size(
        rows,
        inputs.samples,
        reference_blocks,
    ))?;
    let model = ok(Model::new(&inputs))?;
    let n = inputs.samples;
    let (data, sidecar) = interruptible(py, |tick| {
        let size = TruthSize {
            rows,
            seed,
            reference_blocks,
            threads,
        };
        let truth = truth(&model, size, tick)?;
        let set = model.rows(rows, seed, threads)?;
        let continuum = &model.signal.continuum;
        let mut data: Vec<f64> = Vec::with_capacity(rows as usize * n);
        set.stream(threads, STREAM_BATCH_UNITS, |block: &[f64]| {
            if keep_continuum {
                data.extend(
                    block
                        .iter()
                        .zip(continuum.iter().cycle())
                        .map(|(m, c)| m + c),
                );
            } else {
                data.extend_from_slice(block);
            }
            tick((block.len() / n) as u64);
            Ok::<(), Error>(())
        })?;
        let sidecar = Sidecar {
            format: FORMAT.to_owned(),
            version: env!("CARGO_PKG_VERSION").to_owned(),
            data: DataFiles {
                npy,
                csv: None,
                rows,
                samples: n,
            },
            seed,
            continuum_subtracted: !keep_continuum,
            sample_opd_um: model.sample_opd_um(),
            continuum_photons: continuum.clone(),
            mean_counts_photons: model.signal.mean_counts(),
            inputs: inputs.clone(),
            truth,
        };
        Ok((data, sidecar))
    })?;
    let array = PyArray1::from_vec(py, data).reshape([rows as usize, n])?;
    Ok((array.into_any(), json(&sidecar)?))
}

/// `simulate`: the running statistics of `v2ref simulate --json`.
#[pyfunction]
#[pyo3(signature = (physical, bins, bias, formula, trials, seed, threads))]
#[allow(clippy::too_many_arguments)]
fn simulate(
    py: Python<'_>,
    physical: &Bound<'_, PyDict>,
    bins: &str,
    bias: &str,
    formula: &str,
    trials: u64,
    seed: u64,
    threads: usize,
) -> PyResult<String> {
    let (window, bias, formula) = (
        ok(window(bins))?,
        ok(convention(bias))?,
        ok(self::formula(formula))?,
    );
    ok(check_trials(trials))?;
    let inputs = ok(Physical::from_dict(physical)?.inputs())?;
    let model = ok(Model::new(&inputs))?;
    let size = Trials {
        trials,
        seed,
        threads,
    };
    let run = interruptible(py, |tick| {
        run_simulation(&model, window, bias, formula, size, tick)
    })?;
    let estimation = Estimation {
        window,
        bias,
        formula,
    };
    json(&SimulateReport::new(inputs, estimation, size, &run))
}

/// `bias`: `v2ref bias --json`.
#[pyfunction]
#[pyo3(signature = (physical, bins, finite_scan))]
fn bias(physical: &Bound<'_, PyDict>, bins: &str, finite_scan: bool) -> PyResult<String> {
    let p = Physical::from_dict(physical)?;
    let window = ok(window(bins))?;
    let obs = ok(p.observation())?;
    let sampling = if finite_scan || p.stroke_um.is_some() {
        Some(ok(p.sampling())?)
    } else {
        None
    };
    let scan = sampling.as_ref().map(|s| (s, window));
    json(&ok(BiasReport::new(&obs, ok(p.record(&obs))?, scan))?)
}

/// `snr`: `v2ref snr --json`.
#[pyfunction]
#[pyo3(signature = (physical, bins, formula))]
fn snr(physical: &Bound<'_, PyDict>, bins: &str, formula: &str) -> PyResult<String> {
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
        ok(p.record(&obs))?,
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
fn piston(
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
    let reference = ok(p.reference())?;
    let obs = ok(p.observation())?;
    let sampling = ok(p.sampling())?;
    ok(sampling.check_aliasing(&obs))?;
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
    ok(crate::error::positive("aperture_m", p.aperture_m))?;
    let turb = ok(Turbulence::from_seeing(
        ok(p.seeing_at_observing_arcsec())?,
        p.wavelength_um,
        p.wind_mps,
        p.outer_scale_m,
    ))?;
    let spectrum = ok(PistonSpectrum::new(turb, p.aperture_m, obs.baseline_m)
        .and_then(|s| s.with_wind_angle_deg(wind_angle_deg))
        .and_then(|s| s.with_model(psd)))?;
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
        observation: ok(p.record(&obs))?,
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

/// `claims`: `v2ref claims --json` (`quick`: `--quick`).
#[pyfunction]
#[pyo3(signature = (quick))]
fn claims(py: Python<'_>, quick: bool) -> PyResult<String> {
    let effort = if quick { Effort::Quick } else { Effort::Full };
    let results = interruptible(py, |_| Ok(crate::reproduction::claims::evaluate(effort)))?;
    json(&results)
}

#[derive(Serialize)]
struct ScoreAnswer<'a> {
    sidecar: &'a str,
    estimates: &'a str,
    bins: BinWindow,
    bias: BiasConvention,
    rows: u64,
    #[serde(flatten)]
    report: &'a crate::conformance::score::ScoreReport,
}

/// `score`: `v2ref score --json`, the estimates as 1-D arrays (either may
/// be None, not both).
#[pyfunction]
#[pyo3(signature = (v1_sq, v2_sq, sidecar, sidecar_name, estimates_name, bins, bias, alpha))]
#[allow(clippy::too_many_arguments)]
fn score(
    v1_sq: Option<PyReadonlyArray1<'_, f64>>,
    v2_sq: Option<PyReadonlyArray1<'_, f64>>,
    sidecar: &str,
    sidecar_name: &str,
    estimates_name: &str,
    bins: &str,
    bias: &str,
    alpha: f64,
) -> PyResult<String> {
    let window = ok(window(bins))?;
    let bias = ok(convention(bias))?;
    let sc = parse_sidecar(sidecar, sidecar_name)?;
    let truth = sc.truth(window, bias).ok_or_else(|| {
        data_error(
            "sidecar",
            &format!("{sidecar_name}: field truth.windows"),
            &format!(
                "no truth for bins={} bias={}; pick a window and convention the set has",
                window.name(),
                bias.name()
            ),
        )
    })?;
    if v1_sq.is_none() && v2_sq.is_none() {
        return Err(PyValueError::new_err(
            "estimates: no column named v1_sq or v2_sq; one of them is needed",
        ));
    }
    let cols = [("v1_sq", &v1_sq), ("v2_sq", &v2_sq)];
    let mut slices: Vec<Option<&[f64]>> = Vec::new();
    for (name, col) in cols {
        match col {
            None => slices.push(None),
            Some(a) => {
                let x = a.as_slice().map_err(|_| {
                    pyo3::exceptions::PyTypeError::new_err(format!(
                        "estimates: column {name} is not contiguous"
                    ))
                })?;
                if x.is_empty() {
                    return Err(data_error(
                        "estimates",
                        "",
                        "no rows; one estimate per row is needed",
                    ));
                }
                if let Some(r) = x.iter().position(|v| !v.is_finite()) {
                    return Err(data_error(
                        "estimates",
                        &format!("row {} (1-based), column {name}", r + 1),
                        &format!(
                            "{} is not a finite number; every value must be finite",
                            x[r]
                        ),
                    ));
                }
                slices.push(Some(x));
            }
        }
    }
    let rows = sc.data.rows;
    let report = ok(score_report(slices[0], slices[1], truth, rows, alpha))?;
    json(&ScoreAnswer {
        sidecar: sidecar_name,
        estimates: estimates_name,
        bins: window,
        bias,
        rows,
        report: &report,
    })
}

/// Adds the functions to the module.
/// `plan`: `v2ref plan --json` (`physical` without `fringe_hz`; exactly one
/// of `target_sigma_v2` and `time_budget_s`, or neither for σ(V²) = 1e-3).
#[pyfunction]
#[pyo3(signature = (physical, samples_per_fringe, photon_rate_per_s, dead_time_s, fringe_hz, stroke_um, target_sigma_v2, time_budget_s, scans, seed, threads, diameter_err_mas=0.0))]
#[allow(clippy::too_many_arguments)]
fn plan(
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
    use crate::plan::{default_grid, PlanInputs, Target};
    let p = Physical::from_dict(physical)?;
    let instrument = ok(p.inputs_unchecked())?;
    let target = match (target_sigma_v2, time_budget_s) {
        (Some(_), Some(_)) => {
            return Err(Error::Invalid {
                param: "time_budget_s",
                reason: "give target_sigma_v2 or time_budget_s, not both".into(),
            }
            .into_py_err())
        }
        (_, Some(b)) => Target::TimeBudgetS(b),
        (Some(s), None) => Target::SigmaV2(s),
        (None, None) => Target::SigmaV2(1e-3),
    };
    let (default_f, default_s) = default_grid();
    let inputs = PlanInputs {
        atmosphere: crate::simulator::PistonInputs {
            fringe_hz: 1.0,
            wavelength_um: p.wavelength_um,
            seeing_arcsec: ok(p.seeing_at_observing_arcsec())?,
            wind_mps: p.wind_mps,
            aperture_m: p.aperture_m,
            outer_scale_m: p.outer_scale_m,
            reference: ok(p.reference())?,
            sub_samples: p.sub_samples,
        },
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
    #[derive(serde::Serialize)]
    struct Answer<'a> {
        inputs: &'a PlanInputs,
        seeing_as_given: crate::plan::SeeingGiven,
        #[serde(flatten)]
        plan: &'a crate::plan::Plan,
    }
    json(&Answer {
        inputs: &inputs,
        seeing_as_given: crate::plan::SeeingGiven {
            arcsec: p.seeing_arcsec,
            wavelength_um: p.seeing_wavelength_um.unwrap_or(p.wavelength_um),
        },
        plan: &result,
    })
}

/// `photon_rate`: the photon rate at the detector from a 2MASS magnitude
/// (`v2ref plan --magnitude`).
#[pyfunction]
#[pyo3(signature = (magnitude, band, aperture_m, throughput, wavelength_um, bandwidth_nm))]
fn photon_rate(
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

/// `check_threads`: a thread count checked as `--threads` is (0 to
/// `montecarlo::max_threads()`).
#[pyfunction]
fn check_threads(threads: usize) -> PyResult<usize> {
    ok(crate::montecarlo::check_threads(threads))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(check_threads, m)?)?;
    m.add_function(wrap_pyfunction!(photon_rate, m)?)?;
    m.add_function(wrap_pyfunction!(plan, m)?)?;
    m.add_function(wrap_pyfunction!(estimate, m)?)?;
    m.add_function(wrap_pyfunction!(synthesize, m)?)?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(bias, m)?)?;
    m.add_function(wrap_pyfunction!(snr, m)?)?;
    m.add_function(wrap_pyfunction!(piston, m)?)?;
    m.add_function(wrap_pyfunction!(claims, m)?)?;
    m.add_function(wrap_pyfunction!(score, m)?)?;
    Ok(())
}
