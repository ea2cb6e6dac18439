//! The physical keyword arguments of the Python functions, read into the
//! library's [`Physical`] (its defaults, its builders: the same as the
//! CLI's flags).

use super::values::to_py;
use super::Fail;
use crate::parameters::{Parameter, PARAMETERS};
use crate::words::Words;
use pyo3::prelude::*;
use pyo3::types::PyDict;

pub use crate::parameters::Physical;

fn item<'py, T: FromPyObject<'py>>(d: &Bound<'py, PyDict>, key: &str, default: T) -> PyResult<T> {
    match d.get_item(key)? {
        Some(v) if !v.is_none() => v.extract().map_err(|e| {
            pyo3::exceptions::PyTypeError::new_err(format!(
                "{key}: {}",
                e.value(d.py())
                    .str()
                    .map(|s| s.to_string())
                    .unwrap_or_default()
            ))
        }),
        _ => Ok(default),
    }
}

/// The choice `key` of `d` (missing or None: `default`), one of its words
/// ([`Words::WORDS`]).
fn choice<T: Words>(d: &Bound<'_, PyDict>, key: &'static str, default: T) -> PyResult<T> {
    let word: Option<String> = item(d, key, None)?;
    match word {
        None => Ok(default),
        Some(word) => T::from_word(key, &word).map_err(|e| e.into_py_err()),
    }
}

impl Physical {
    /// The physical inputs in `d` (missing or None: [`Physical::default`]),
    /// checked ([`Physical::check`]).
    pub fn from_dict(d: &Bound<'_, PyDict>) -> PyResult<Physical> {
        for (k, _) in d.iter() {
            let k: String = k.extract()?;
            if !PARAMETERS.iter().any(|p| p.name == k) {
                let names: Vec<&str> = PARAMETERS.iter().map(|p| p.name).collect();
                return Err(pyo3::exceptions::PyTypeError::new_err(format!(
                    "{k}: not a keyword argument (accepted: {})",
                    names.join(", ")
                )));
            }
        }
        let d0 = Physical::default();
        let p = Physical {
            wavelength_um: item(d, Parameter::WAVELENGTH_UM.name, d0.wavelength_um)?,
            bandwidth_nm: item(d, Parameter::BANDWIDTH_NM.name, d0.bandwidth_nm)?,
            spectrum_csv: item(d, Parameter::SPECTRUM_CSV.name, d0.spectrum_csv)?,
            source: choice(d, Parameter::SOURCE.name, d0.source)?,
            diameter_mas: item(d, Parameter::DIAMETER_MAS.name, d0.diameter_mas)?,
            spatial_freq_cpas: item(d, Parameter::SPATIAL_FREQ_CPAS.name, d0.spatial_freq_cpas)?,
            baseline_m: item(d, Parameter::BASELINE_M.name, d0.baseline_m)?,
            dispersion_pp_rad: item(d, Parameter::DISPERSION_PP_RAD.name, d0.dispersion_pp_rad)?,
            stroke_um: item(d, Parameter::STROKE_UM.name, d0.stroke_um)?,
            dx_um: item(d, Parameter::DX_UM.name, d0.dx_um)?,
            samples: item(d, Parameter::SAMPLES.name, d0.samples)?,
            integrating: item(d, Parameter::INTEGRATING.name, d0.integrating)?,
            visibility: item(d, Parameter::VISIBILITY.name, d0.visibility)?,
            photons: item(d, Parameter::PHOTONS.name, d0.photons)?,
            read_noise: item(d, Parameter::READ_NOISE.name, d0.read_noise)?,
            photon_noise: item(d, Parameter::PHOTON_NOISE.name, d0.photon_noise)?,
            fringe_hz: item(d, Parameter::FRINGE_HZ.name, d0.fringe_hz)?,
            wind_mps: item(d, Parameter::WIND_MPS.name, d0.wind_mps)?,
            seeing_arcsec: item(d, Parameter::SEEING_ARCSEC.name, d0.seeing_arcsec)?,
            seeing_wavelength_um: item(
                d,
                Parameter::SEEING_WAVELENGTH_UM.name,
                d0.seeing_wavelength_um,
            )?,
            aperture_m: item(d, Parameter::APERTURE_M.name, d0.aperture_m)?,
            outer_scale_m: item(d, Parameter::OUTER_SCALE_M.name, d0.outer_scale_m)?,
            sub_samples: item(d, Parameter::SUB_SAMPLES.name, d0.sub_samples)?,
            reference: choice(d, Parameter::REFERENCE.name, d0.reference)?,
        };
        p.check().map_err(|e| e.into_py_err())?;
        Ok(p)
    }
}

/// Adds the one declaration of the physical inputs to the module:
/// `PHYSICAL_KEYWORDS` (their names, in order), `PHYSICAL_DEFAULTS` (a dict)
/// and `PHYSICAL_PARAMETERS` (a list of dicts: [`PARAMETERS`], each with its
/// help text `doc` and what leaving it unset means, `unset_doc`, other
/// inputs named ``` ``name`` ```). The package reads the same declaration
/// from `_declaration.py`, generated from it.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    let names: Vec<&str> = PARAMETERS.iter().map(|p| p.name).collect();
    m.add("PHYSICAL_KEYWORDS", names)?;
    m.add("PHYSICAL_DEFAULTS", to_py(py, &Physical::default())?)?;
    let keyword = |n: &str| format!("``{n}``");
    let table: Vec<serde_json::Value> = PARAMETERS
        .iter()
        .map(|p| {
            let mut v = serde_json::json!(p);
            v["doc"] = p.describe(&keyword).into();
            v["unset_doc"] = p.unset(&keyword).into();
            v
        })
        .collect();
    m.add("PHYSICAL_PARAMETERS", to_py(py, &table)?)
}
