//! The planner: `plan`, `photon_rate`.

use crate::commands::{self, plan::PlanRequest};
use crate::conformance::estimate::BiasConvention;
use crate::values::to_py;
use crate::words::Words;
use crate::{interruptible, ok};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;
use v2ref_commands::units::verify::VerifyJob;
use v2ref_commands::units::{Partial, UnitJob};

/// `plan`: `v2ref plan --json` (`physical` without `fringe_hz`; exactly one
/// of `target_sigma_v2` and `time_budget_s`, or neither for σ(V²) = 1e-3);
/// `oifits`: `--oifits`; `observing`: its target, date and site (the
/// wrapper's keywords, as `--target-name` ... `--site-height-m`);
/// `verify_units`: a callable that computes the verification's units
/// elsewhere ([`verify_in_units`]; None: here).
#[pyfunction]
#[pyo3(signature = (physical, samples_per_fringe, photon_rate_per_s, dead_time_s, fringe_hz, stroke_um, target_sigma_v2, time_budget_s, scans, seed, threads, diameter_err_mas=0.0, oifits=None, bias="counts", verify_observations=None, observing=None, force=false, magnitude=None, frame_rate_hz=None, instrument=None, verify_units=None))]
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
    oifits: Option<PathBuf>,
    bias: &str,
    verify_observations: Option<u64>,
    observing: Option<crate::oifits::ObservingKeywords>,
    force: bool,
    magnitude: Magnitude3,
    frame_rate_hz: Option<f64>,
    instrument: Option<(String, Vec<String>)>,
    verify_units: Option<PyObject>,
) -> PyResult<PyObject> {
    if let Some(path) = &oifits {
        ok(v2ref_oifits::check_fits_extension(path, "oifits"))?;
    }
    // Checked and locked before any computing, as `v2ref plan --oifits`.
    let set = match &oifits {
        Some(path) => Some(ok(crate::formats::OutputSet::begin(
            &[(path, "oifits")],
            force,
        ))?),
        None => None,
    };
    let observing = crate::oifits::observing_of(observing, oifits.is_some(), "oifits")?;
    let (mut p, mut req) = request(
        physical,
        (samples_per_fringe, photon_rate_per_s, dead_time_s),
        (fringe_hz, stroke_um),
        (target_sigma_v2, time_budget_s, scans, seed),
        (diameter_err_mas, bias, magnitude, frame_rate_hz),
    )?;
    preset(instrument, &mut p, &mut req)?;
    let prepared = ok(commands::plan::prepare(&p, &req))?;
    let mut answer = interruptible(py, |tick| commands::plan::run(prepared, threads, tick))?;
    if let Some(observations) = verify_observations {
        let size = ok(commands::plan::verification(&answer, observations))?;
        match &verify_units {
            None => interruptible(py, |tick| {
                commands::plan::verify(&mut answer, &size, threads, tick)
            })?,
            Some(units) => verify_in_units(py, &mut answer, &size, observations, units)?,
        }
    }
    if let (Some(path), Some(set)) = (&oifits, set) {
        // Nothing is written when no setting reaches the target: the
        // answer's `recommended` is then null, as the CLI says in a note.
        ok(set.write(|| {
            v2ref_oifits::write_plan(path, "oifits", (&answer.inputs, &answer.plan), &observing)
        }))?;
    }
    to_py(py, &answer)
}

/// `plan`'s verification from the partial results of its units
/// ([`VerifyJob`]), which `units(f, Δx, n, observations)` (`v2ref.dask`)
/// computes, in unit order, from the plan's own keywords.
fn verify_in_units(
    py: Python<'_>,
    answer: &mut commands::plan::PlanAnswer,
    size: &v2ref_commands::plan::verify::VerificationSize,
    observations: u64,
    units: &PyObject,
) -> PyResult<()> {
    let (f, s, n) = (
        answer.plan.recommended.map_or(0.0, |p| p.fringe_hz),
        answer.plan.recommended.map_or(0.0, |p| p.stroke_um),
        size.scans_per_observation,
    );
    let job = ok(VerifyJob::new(
        answer.inputs.clone(),
        (f, s, n),
        observations,
        0,
    ))?;
    let bytes: Vec<Vec<u8>> = units.call1(py, (f, s, n, observations))?.extract(py)?;
    let partials: Vec<Partial> = bytes
        .iter()
        .map(|b| ok(Partial::from_bytes(b, job.key())))
        .collect::<PyResult<_>>()?;
    let means = interruptible(py, |_| job.reduce(&partials))?;
    ok(commands::plan::record_verification(answer, size, means))
}

/// The plan's inputs from `plan`'s keywords (those of [`request`], and
/// `instrument`), as a worker of `v2ref.dask` rebuilds them.
pub(crate) fn plan_inputs(kw: &Bound<'_, PyDict>) -> PyResult<v2ref_commands::plan::PlanInputs> {
    fn get<'py, T: FromPyObject<'py>>(kw: &Bound<'py, PyDict>, key: &str) -> PyResult<T> {
        match kw.get_item(key)? {
            Some(v) => v.extract(),
            None => Err(pyo3::exceptions::PyValueError::new_err(format!(
                "{key}: missing"
            ))),
        }
    }
    let physical: Bound<'_, PyDict> = get(kw, "physical")?;
    let bias: String = get(kw, "bias")?;
    let (mut p, mut req) = request(
        &physical,
        (
            get(kw, "samples_per_fringe")?,
            get(kw, "photon_rate_per_s")?,
            get(kw, "dead_time_s")?,
        ),
        (get(kw, "fringe_hz")?, get(kw, "stroke_um")?),
        (
            get(kw, "target_sigma_v2")?,
            get(kw, "time_budget_s")?,
            get(kw, "scans")?,
            get(kw, "seed")?,
        ),
        (
            get(kw, "diameter_err_mas")?,
            &bias,
            get(kw, "magnitude")?,
            get(kw, "frame_rate_hz")?,
        ),
    )?;
    let instrument = match kw.get_item("instrument")? {
        Some(v) => v.extract()?,
        None => None,
    };
    preset(instrument, &mut p, &mut req)?;
    Ok(ok(commands::plan::prepare(&p, &req))?.inputs)
}

/// The keywords of `plan` as the library's inputs (shared by
/// `plan_targets`, whose rows replace some of them), grouped as they are
/// listed: the sampling and rate, the grid, the target and Monte Carlo, the
/// source's details.
pub(super) fn request(
    physical: &Bound<'_, PyDict>,
    (samples_per_fringe, photon_rate_per_s, dead_time_s): (f64, f64, f64),
    (fringe_hz, stroke_um): (Vec<f64>, Vec<f64>),
    (target_sigma_v2, time_budget_s, scans, seed): (Option<f64>, Option<f64>, u64, u64),
    (diameter_err_mas, bias, magnitude, frame_rate_hz): (f64, &str, Magnitude3, Option<f64>),
) -> PyResult<(crate::parameters::Physical, PlanRequest)> {
    let p = crate::inputs::physical_from_dict(physical)?;
    let magnitude = match magnitude {
        Some((magnitude, band, throughput)) => Some(crate::plan::photometry::Magnitude {
            magnitude,
            band: ok(crate::plan::photometry::Band2Mass::from_word(
                "magnitude_band",
                &band,
            ))?,
            aperture_m: p.aperture_m,
            throughput,
        }),
        None => None,
    };
    let req = PlanRequest {
        samples_per_fringe,
        photon_rate_per_s,
        magnitude,
        dead_time_s,
        frame_rate_hz,
        fringe_hz,
        stroke_um,
        target_sigma_v2,
        time_budget_s,
        scans,
        seed,
        diameter_err_mas,
        bias: ok(BiasConvention::from_word("bias", bias))?,
    };
    Ok((p, req))
}

/// `instrument`: (the preset's name, the keywords the caller gave) applied
/// as `v2ref plan --instrument` applies it, filling only what was not given
/// ([`crate::plan::instrument::Instrument::apply`]); then a magnitude needs
/// a throughput (NaN: none given), the caller's or the preset's.
fn preset(
    instrument: Option<(String, Vec<String>)>,
    p: &mut crate::parameters::Physical,
    req: &mut PlanRequest,
) -> PyResult<()> {
    if let Some((name, given)) = instrument {
        let preset = ok(crate::plan::instrument::instrument(&name))?;
        preset.apply(p, req, &|key| given.iter().any(|g| g == key));
    }
    match req.magnitude {
        Some(m) if m.throughput.is_nan() => Err(pyo3::exceptions::PyValueError::new_err(
            "throughput: needed with magnitude: give throughput, or an instrument whose \
             preset has one",
        )),
        _ => Ok(()),
    }
}

/// `plan`'s `magnitude`: (magnitude, band, throughput).
pub(super) type Magnitude3 = Option<(f64, String, f64)>;

/// `photon_rate`: the photon rate at the detector from a magnitude (2MASS
/// or Johnson–Cousins; `v2ref plan --magnitude`).
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
    let band = ok(Band2Mass::from_word("band", band))?;
    let m = Magnitude {
        magnitude,
        band,
        aperture_m,
        throughput,
    };
    ok(m.photon_rate_per_s(wavelength_um, bandwidth_nm * 1e-3))
}
