//! The table of `plan --targets`: one row per target, written as CSV
//! ([`table_csv`]) and returned to Python under the same names.
//!
//! Its first columns are named as the OI_TARGET table of OIFITS v2 names
//! them (`TARGET`, `RAEP0`, `DECEP0`, in degrees as there), so that a
//! pipeline fills OI_TARGET from them; the rest are the plan's own,
//! lower-case (OI_TARGET has no field for them).

use super::plan::PlanAnswer;
use crate::plan::photometry::Band2Mass;
use crate::plan::Estimator;
use serde::Serialize;
use v2ref_core::target_list::{RowFault, Target};

/// What became of a row.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
pub enum Status {
    /// Planned: a setting reaches the target.
    Ok,
    /// Planned, but no setting of the grid reaches the target (`reason`).
    Unreachable,
    /// Not planned: the row could not be read or its plan was refused
    /// (`reason`).
    Error,
}

/// One target's recommendation (every field after `reason` is None for a
/// row in error; the plan's fields are None when nothing is recommended).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TargetRow {
    /// The target's name (OI_TARGET `TARGET`).
    #[serde(rename = "TARGET")]
    pub target: String,
    /// Right ascension, degrees (OI_TARGET `RAEP0`).
    #[serde(rename = "RAEP0")]
    pub ra_deg: Option<f64>,
    /// Declination, degrees (OI_TARGET `DECEP0`).
    #[serde(rename = "DECEP0")]
    pub dec_deg: Option<f64>,
    /// Line of the list the row is on (1-based).
    pub line: u64,
    /// ok, unreachable or error.
    pub status: Status,
    /// Why a row is in error or unreachable, in one line.
    pub reason: Option<String>,
    /// The magnitude used (the row's or the shared one).
    pub magnitude: Option<f64>,
    /// Its band.
    pub band: Option<Band2Mass>,
    /// The uniform disk's diameter used, mas.
    pub diameter_mas: Option<f64>,
    /// The photon rate at the detector used, photons/s.
    pub photon_rate_per_s: Option<f64>,
    /// The seed of this target's plan (keyed by the row's content).
    pub seed: Option<u64>,
    /// The estimator recommended.
    pub estimator: Option<Estimator>,
    /// Its fringe frequency, Hz.
    pub fringe_hz: Option<f64>,
    /// Its true stroke, µm (samples × step).
    pub stroke_um: Option<f64>,
    /// Samples per scan.
    pub samples: Option<usize>,
    /// Scans needed.
    pub scans: Option<f64>,
    /// Time for them, s.
    pub time_s: Option<f64>,
    /// The time with the piston terms at the lower ends of their intervals, s.
    pub time_lower_s: Option<f64>,
    /// The promise: σ(V²) of the observation's mean (the target, or the
    /// σ reached in a time budget), piston term at its interval's upper end.
    pub sigma_v2: Option<f64>,
    /// The same with the piston term at its interval's lower end: the
    /// promise's interval is [`sigma_v2_lower`, `sigma_v2`].
    pub sigma_v2_lower: Option<f64>,
    /// Whether the recommendation is the detector's fastest fringe.
    pub at_detector_edge: Option<bool>,
    /// The note when the recommendation sits on an edge of the grid.
    pub grid_edge: Option<String>,
    /// `--verify`: achieved σ / promised σ.
    pub verify_sigma_ratio: Option<f64>,
    /// Its interval's lower end.
    pub verify_sigma_ratio_lower: Option<f64>,
    /// Its interval's upper end.
    pub verify_sigma_ratio_upper: Option<f64>,
    /// Whether the achieved σ's interval reaches down to the promise.
    pub verify_sigma_kept: Option<bool>,
    /// Whether the achieved and predicted means agree.
    pub verify_mean_kept: Option<bool>,
}

/// The table's columns, in order (the CSV header; the Python dicts' keys).
pub const COLUMNS: [&str; 27] = [
    "TARGET",
    "RAEP0",
    "DECEP0",
    "line",
    "status",
    "reason",
    "magnitude",
    "band",
    "diameter_mas",
    "photon_rate_per_s",
    "seed",
    "estimator",
    "fringe_hz",
    "stroke_um",
    "samples",
    "scans",
    "time_s",
    "time_lower_s",
    "sigma_v2",
    "sigma_v2_lower",
    "at_detector_edge",
    "grid_edge",
    "verify_sigma_ratio",
    "verify_sigma_ratio_lower",
    "verify_sigma_ratio_upper",
    "verify_sigma_kept",
    "verify_mean_kept",
];

impl TargetRow {
    /// A row with only its name, line, status and reason.
    fn bare(line: u64, name: &str, status: Status, reason: Option<String>) -> TargetRow {
        TargetRow {
            target: name.to_owned(),
            ra_deg: None,
            dec_deg: None,
            line,
            status,
            reason,
            magnitude: None,
            band: None,
            diameter_mas: None,
            photon_rate_per_s: None,
            seed: None,
            estimator: None,
            fringe_hz: None,
            stroke_um: None,
            samples: None,
            scans: None,
            time_s: None,
            time_lower_s: None,
            sigma_v2: None,
            sigma_v2_lower: None,
            at_detector_edge: None,
            grid_edge: None,
            verify_sigma_ratio: None,
            verify_sigma_ratio_lower: None,
            verify_sigma_ratio_upper: None,
            verify_sigma_kept: None,
            verify_mean_kept: None,
        }
    }

    /// The row of a target that was not planned.
    pub fn fault(f: &RowFault) -> TargetRow {
        TargetRow::bare(f.line, &f.name, Status::Error, Some(f.reason.clone()))
    }

    /// The row of target `t`, planned with `seed` into `answer`, whose
    /// source had `diameter_mas`.
    pub fn planned(t: &Target, seed: u64, diameter_mas: f64, answer: &PlanAnswer) -> TargetRow {
        let plan = &answer.plan;
        let reason = plan.recommended.is_none().then(|| {
            let why = plan
                .no_v1_reason
                .as_deref()
                .or(plan.no_v2_reason.as_deref());
            why.unwrap_or("no setting of the grid reaches the target")
                .to_owned()
        });
        let status = if reason.is_some() {
            Status::Unreachable
        } else {
            Status::Ok
        };
        let mut row = TargetRow::bare(t.line, &t.name, status, reason);
        row.ra_deg = t.ra_deg;
        row.dec_deg = t.dec_deg;
        row.magnitude = answer.photometry.map(|m| m.magnitude.magnitude);
        row.band = answer.photometry.map(|m| m.magnitude.band);
        row.diameter_mas = Some(diameter_mas);
        row.photon_rate_per_s = Some(answer.inputs.photon_rate_per_s);
        row.seed = Some(seed);
        if let Some(p) = &plan.recommended {
            row.estimator = Some(p.estimator);
            row.fringe_hz = Some(p.fringe_hz);
            row.stroke_um = Some(p.stroke_um);
            row.samples = Some(p.samples);
            row.scans = p.scans_needed;
            row.time_s = p.time_s;
            row.time_lower_s = p.time_lower_s;
            row.sigma_v2 = p.observation.map(|o| o.sigma).or(p.sigma_reached);
            row.sigma_v2_lower = p.observation.map(|o| {
                let lower = (2.0 * o.sigma_piston - o.sigma_piston_upper).max(0.0);
                o.sigma_noise.hypot(lower)
            });
            row.at_detector_edge = Some(plan.at_detector_edge);
            row.grid_edge = plan.grid_edge.clone();
        }
        if let Some(v) = &answer.verification {
            row.verify_sigma_ratio = Some(v.sigma_ratio);
            row.verify_sigma_ratio_lower = Some(v.sigma_ratio_interval[0]);
            row.verify_sigma_ratio_upper = Some(v.sigma_ratio_interval[1]);
            row.verify_sigma_kept = Some(v.sigma_kept);
            row.verify_mean_kept = Some(v.mean_kept);
        }
        row
    }
}

/// One CSV cell: empty for None; quoted when it holds a comma, a quote or
/// a line break.
fn cell(v: &serde_json::Value) -> String {
    use serde_json::Value;
    let text = match v {
        Value::Null => return String::new(),
        Value::String(s) => s.clone(),
        other => other.to_string(),
    };
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text
    }
}

/// The table as CSV text: the header [`COLUMNS`], then one line per row.
/// Numbers are written in the shortest form that reads back to the same
/// bits.
pub fn table_csv(rows: &[TargetRow]) -> String {
    let mut out = COLUMNS.join(",");
    out.push('\n');
    for row in rows {
        let value = serde_json::to_value(row).unwrap_or_default();
        let line: Vec<String> = COLUMNS
            .iter()
            .map(|c| cell(value.get(c).unwrap_or(&serde_json::Value::Null)))
            .collect();
        out.push_str(&line.join(","));
        out.push('\n');
    }
    out
}
