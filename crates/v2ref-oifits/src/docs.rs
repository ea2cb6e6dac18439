//! The OIFITS documents v2ref writes: a pipeline-style file of per-row
//! estimates (`estimate`), a set's truth (`synth`), and a plan's predicted
//! observation (`plan`). The front ends only choose a path and call
//! [`super::write_oifits`].

use super::observing::ObservingContext;
use super::setting::Setting;
use super::write::{Key, KeyValue, OifitsDoc, Vis2Out};
use super::{default_insname, estimator_key, KEY_BIAS, KEY_BINS};
use crate::conformance::estimate::{BiasConvention, RowEstimate};

/// The columns of `which` estimators from per-row estimates.
pub fn columns_of(rows: &[RowEstimate], which: &[Estimator]) -> Vec<(Estimator, Vec<f64>)> {
    which
        .iter()
        .map(|&e| {
            let v = rows.iter().map(|r| e.pick(r.v1_sq, r.v2_sq)).collect();
            (e, v)
        })
        .collect()
}
use crate::conformance::score::Estimator;
use crate::conformance::sidecar::Sidecar;
use crate::formalism::channels::Channels;
use crate::formalism::estimator::BinWindow;
use crate::noise::calibrated::expectation;
use crate::noise::Formula;
use crate::plan::{PlanInputs, PlanPoint};
use crate::simulator::channels::channel_models;
use crate::simulator::{Inputs, Model};
use crate::{Error, Result};

/// Both estimators, in order.
pub const BOTH: [Estimator; 2] = [Estimator::V1Sq, Estimator::V2Sq];

fn window_keys(bins: BinWindow, bias: BiasConvention) -> Vec<Key> {
    vec![
        Key::str(KEY_BINS, bins.name(), "window of Fourier bins summed"),
        Key::str(KEY_BIAS, bias.name(), "bias convention subtracted"),
    ]
}

/// Per-row estimates of `model`'s interferograms as OIFITS: one table per
/// entry of `columns` (an estimator and its value for every row). `VIS2ERR` is the closed-form standard deviation
/// of the calibrated estimator at the configuration's conditions (the
/// exact variance of the `model` convention, piston-free, with the
/// model's calibration), the same for every row; NaN where it has no
/// closed form (more than 4096 samples). Nothing is flagged. Target,
/// date and site: `observing`'s.
pub fn estimates_doc(
    model: &Model,
    columns: &[(Estimator, Vec<f64>)],
    (bins, bias): (BinWindow, BiasConvention),
    observing: &ObservingContext,
) -> Result<OifitsDoc> {
    let sd = closed_form_sd(model, bins)?;
    Ok(OifitsDoc {
        setting: Setting::from_inputs(&model.inputs, observing)?,
        tables: estimate_tables(columns, &[sd], (bins, bias)),
        keywords: vec![estimates_kind()],
    })
}

/// Per-row estimates in spectral channels as OIFITS (`NWAVE` = C): the
/// configuration `inputs` split by `channels`, one table per entry of
/// `columns`, each an estimator and its rows × C values, row after row
/// (row r, channel j at `r·C + j`; channel j is `channels`' j-th, in
/// increasing wavenumber, so `EFF_WAVE` is written in decreasing order).
/// `OI_WAVELENGTH` holds each channel's `1/σ_eff,j` and width
/// ([`Setting::with_channels`]); `VIS2ERR` of channel j is the closed-form
/// standard deviation of channel j's calibrated estimator (its model from
/// [`channel_models`]: its spectrum, its share of the photons), the same
/// for every row. One channel over the whole band writes what
/// [`estimates_doc`] writes, byte for byte. Refused (parameter `columns`):
/// a column that is not whole rows of C values. Built for the `estimate`
/// command's channels (wired in the CLI in a later round).
pub fn estimates_doc_channels(
    (inputs, channels): (&Inputs, &Channels),
    columns: &[(Estimator, Vec<f64>)],
    (bins, bias): (BinWindow, BiasConvention),
    observing: &ObservingContext,
) -> Result<OifitsDoc> {
    let count = channels.count();
    if let Some((e, v)) = columns
        .iter()
        .find(|(_, v)| v.is_empty() || v.len() % count != 0)
    {
        return Err(Error::Invalid {
            param: "columns",
            reason: format!(
                "{}: {} values; one per row and channel, rows × {count}, row after row",
                estimator_key(*e),
                v.len()
            ),
        });
    }
    let sds = channel_models(inputs, channels)?
        .iter()
        .map(|m| closed_form_sd(m, bins))
        .collect::<Result<Vec<_>>>()?;
    Ok(OifitsDoc {
        setting: Setting::from_inputs(inputs, observing)?.with_channels(channels),
        tables: estimate_tables(columns, &sds, (bins, bias)),
        keywords: vec![estimates_kind()],
    })
}

/// The closed-form standard deviations (V1², V2²) of one row of
/// `model`'s calibrated estimators over `bins` (NaN without a closed form).
fn closed_form_sd(model: &Model, bins: BinWindow) -> Result<[f64; 2]> {
    let closed = expectation(&model.calibrated_setup(bins), &model.noise, Formula::Exact)?;
    let sd = |v: Option<f64>| v.map_or(f64::NAN, f64::sqrt);
    Ok([sd(closed.var_v1_sq), sd(closed.var_v2_sq)])
}

/// The primary header's `V2R_KIND` of per-row estimates.
fn estimates_kind() -> Key {
    Key::str(
        "V2R_KIND",
        "ESTIMATES",
        "per-row estimates of interferograms",
    )
}

/// One table per column, `VIS2ERR` of channel j `sds[j]` (V1², V2²) on
/// every row; nothing flagged.
fn estimate_tables(
    columns: &[(Estimator, Vec<f64>)],
    sds: &[[f64; 2]],
    (bins, bias): (BinWindow, BiasConvention),
) -> Vec<Vis2Out> {
    columns
        .iter()
        .map(|(e, vals)| {
            let e = *e;
            let per_channel: Vec<f64> = sds.iter().map(|sd| e.pick(sd[0], sd[1])).collect();
            let rows = vals.len() / per_channel.len();
            let mut keywords = window_keys(bins, bias);
            keywords.push(Key::str(
                "V2R_ERR",
                "closed form",
                "VIS2ERR: closed-form sd of one row, model conv.",
            ));
            Vis2Out {
                insname: default_insname(e).into(),
                estimator: Some(e),
                vis2err: per_channel.repeat(rows),
                flag: vec![false; vals.len()],
                vis2data: vals.clone(),
                keywords,
                vis2data_note: Some("normalized, bias-subtracted V^2 of one scan".into()),
            }
        })
        .collect()
}

/// A synth set's truth as OIFITS: per row, the expected V1² and V2² of
/// the window `bins` and convention `bias` (`VIS2DATA`) and their
/// standard deviation over rows (`VIS2ERR`), from the sidecar's truth.
/// Target, date and site: `observing`'s.
pub fn truth_doc(
    sidecar: &Sidecar,
    (bins, bias): (BinWindow, BiasConvention),
    observing: &ObservingContext,
) -> Result<OifitsDoc> {
    let truth = sidecar.truth(bins, bias).ok_or_else(|| Error::Invalid {
        param: "bins",
        reason: format!("the set has no truth for {} / {}", bins.name(), bias.name()),
    })?;
    let rows = usize::try_from(sidecar.data.rows).unwrap_or(usize::MAX);
    crate::bounds::check_set_size(sidecar.data.rows, 1, 0)?;
    let tables = BOTH
        .iter()
        .map(|&e| {
            let t = e.pick(&truth.v1_sq, &truth.v2_sq);
            let mut keywords = window_keys(bins, bias);
            keywords.push(Key::str(
                "V2R_ERR",
                "truth var",
                "VIS2ERR: sqrt of the truth's per-row variance",
            ));
            Vis2Out {
                insname: default_insname(e).into(),
                estimator: Some(e),
                vis2data: vec![t.mean; rows],
                vis2err: vec![t.var.max(0.0).sqrt(); rows],
                flag: vec![false; rows],
                keywords,
                vis2data_note: Some("truth: the expected estimate of every row".into()),
            }
        })
        .collect();
    Ok(OifitsDoc {
        setting: Setting::from_inputs(&sidecar.inputs, observing)?,
        tables,
        keywords: vec![
            Key::str(
                "V2R_KIND",
                "TRUTH",
                "a synth set's truth, not a measurement",
            ),
            Key {
                name: "V2R_SEED".into(),
                value: KeyValue::Str(sidecar.seed.to_string()),
                comment: "the set's seed".into(),
            },
        ],
    })
}

/// A plan's predicted observation at `point` (the recommended setting) as
/// OIFITS: one row, the V² a run of `scans_needed` scans measures
/// (`V²_sampled + piston bias`) and its predicted σ (`VIS2ERR`, the
/// target's). The deterministic biases left to correct are keywords
/// (`V2R_BBW` bandwidth and dispersion, `V2R_BSCN` scan and detector,
/// `V2R_BPST` piston and `V2R_EPST` its standard error), with the V² error
/// from the diameter's (`V2R_VDIA`), the window and the bias convention,
/// and a note on the `VIS2DATA` column. Target, date and site:
/// `observing`'s.
pub fn plan_doc(
    inputs: &PlanInputs,
    point: &PlanPoint,
    observing: &ObservingContext,
) -> Result<OifitsDoc> {
    let scans = point.scans_needed.unwrap_or(0.0).ceil().max(1.0);
    let sigma = point
        .sigma_reached
        .unwrap_or(point.sigma_per_scan / scans.sqrt());
    let e = Estimator::from(point.estimator);
    let mut setting = Setting::from_inputs(&inputs.instrument, observing)?;
    setting.scan_s = point.time_s.or(Some(point.scan_time_s * scans));
    // The instrument's piston is set per grid point: the telescopes are
    // the atmosphere's apertures.
    setting.diameter_m = Some(inputs.atmosphere.aperture_m);
    let keywords = vec![
        Key::f64(
            "V2R_VMON",
            point.v_mono_sq,
            "V_mono^2 at sigma_eff: what to fit",
        ),
        Key::f64(
            "V2R_BBW",
            point.bias_bandwidth_dispersion,
            "bias: bandwidth+dispersion (correct)",
        ),
        Key::f64(
            "V2R_BSCN",
            point.bias_scan_detector,
            "bias: finite scan+detector (correct)",
        ),
        Key::f64(
            "V2R_BPST",
            point.bias_piston,
            "bias: piston, Monte Carlo (correct)",
        ),
        Key::f64(
            "V2R_EPST",
            point.bias_piston_stderr,
            "standard error of V2R_BPST (Monte Carlo)",
        ),
        Key::f64(
            "V2R_VDIA",
            point.v_sq_error_from_diameter,
            "V^2 error from the diameter's error",
        ),
        Key::f64(
            "V2R_FHZ",
            point.fringe_hz,
            "[Hz] fringe frequency of the setting",
        ),
        Key::f64(
            "V2R_STRK",
            point.stroke_um,
            "[um] scan stroke of the setting",
        ),
        Key::f64("V2R_NSCN", scans, "scans averaged"),
        Key::str(
            "V2R_ERR",
            "predicted",
            "VIS2ERR: predicted sigma of the mean",
        ),
        Key::str(
            KEY_BINS,
            BinWindow::Positive.name(),
            "window of Fourier bins summed",
        ),
        Key::str(
            KEY_BIAS,
            BiasConvention::Model.name(),
            "bias convention subtracted",
        ),
    ];
    let vmeas = point.v_sq_sampled + point.bias_piston;
    Ok(OifitsDoc {
        setting,
        tables: vec![Vis2Out {
            insname: default_insname(e).into(),
            estimator: Some(e),
            vis2data: vec![vmeas],
            vis2err: vec![sigma],
            flag: vec![false],
            keywords,
            vis2data_note: Some("as measured: V2R_VMON+BBW+BSCN+BPST; correct".into()),
        }],
        keywords: vec![Key::str(
            "V2R_KIND",
            "PLAN",
            "a predicted observation, not a measurement",
        )],
    })
}
