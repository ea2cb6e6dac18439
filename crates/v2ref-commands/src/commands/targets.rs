//! `plan --targets`: a list of targets planned with one instrument's
//! settings, one row of recommendations per target.
//!
//! The list is a CSV text ([`parse_targets`]): a header naming its columns,
//! then one target a line. Each row overrides the shared request's
//! magnitude (and band), the source's diameter and the seed; everything
//! else is shared. A row that cannot be planned (a number that does not
//! parse, a band that is not one, a magnitude out of range, a missing or
//! repeated name, a plan refused) keeps its line number and its reason, and
//! the other rows are planned all the same ([`TargetRow`] with status
//! `error`).
//!
//! A row's seed is keyed by its content (name and values) and the shared
//! seed, never by its position: reordering the list or adding rows leaves
//! every other row's plan bit for bit the same.

use crate::commands::plan::{self, PlanAnswer, PlanRequest};
use crate::error::{Error, Result};
use crate::montecarlo::derive_seed;
use crate::parameters::Physical;
use crate::plan::photometry::{Band2Mass, Magnitude};
use crate::words::Words;

pub use super::targets_table::{table_csv, Status, TargetRow, COLUMNS};
pub use v2ref_core::target_list::{parse_targets, RowFault, Target, INPUT_COLUMNS, MAX_TARGETS};

/// What is shared by every target: the physical inputs, the plan's
/// options, the throughput a row's magnitude is collected with (when the
/// shared request has no magnitude of its own), and whether to verify.
#[derive(Debug, Clone)]
pub struct SharedPlan {
    /// The physical inputs (a row replaces `diameter_mas`).
    pub physical: Physical,
    /// The plan's options (a row replaces `magnitude` and `seed`).
    pub request: PlanRequest,
    /// Throughput for rows with a magnitude, when `request.magnitude` is
    /// None (else its throughput is used).
    pub throughput: Option<f64>,
    /// Observations simulated to verify each recommendation (None: no
    /// verification).
    pub verify_observations: Option<u64>,
}

/// The seed of `t`'s plan: the shared seed hashed with the row's name and
/// values ([`derive_seed`]), so that it does not depend on where the row is.
pub fn target_seed(shared_seed: u64, t: &Target) -> u64 {
    let band = t.band.map_or(f64::NAN, |b| {
        Band2Mass::WORDS
            .iter()
            .position(|w| w.value == b)
            .unwrap_or(0) as f64
    });
    let or_nan = |v: Option<f64>| v.unwrap_or(f64::NAN);
    derive_seed(
        shared_seed,
        &format!("target\u{0}{}", t.name),
        &[
            or_nan(t.magnitude),
            band,
            or_nan(t.diameter_mas),
            or_nan(t.ra_deg),
            or_nan(t.dec_deg),
        ],
    )
}

/// The shared inputs with `t`'s values in place.
fn inputs_of(shared: &SharedPlan, t: &Target) -> Result<(Physical, PlanRequest)> {
    let mut p = shared.physical.clone();
    let mut req = shared.request.clone();
    if let Some(d) = t.diameter_mas {
        p.diameter_mas = d;
    }
    req.seed = target_seed(shared.request.seed, t);
    if let (Some(magnitude), Some(band)) = (t.magnitude, t.band) {
        if p.spectrum_csv.is_some() {
            return Err(Error::Invalid {
                param: "magnitude",
                reason: "a magnitude is converted over the flat band, not with a spectrum CSV"
                    .into(),
            });
        }
        let throughput = shared
            .request
            .magnitude
            .map(|m| m.throughput)
            .or(shared.throughput)
            .ok_or_else(|| Error::Invalid {
                param: "throughput",
                reason: "needed with a row's magnitude: give a throughput (or an instrument \
                         whose preset has one)"
                    .into(),
            })?;
        req.magnitude = Some(Magnitude {
            magnitude,
            band,
            aperture_m: p.aperture_m,
            throughput,
        });
    }
    Ok((p, req))
}

/// The plan of one target, alone (`threads` as `plan`'s): its answer, or
/// the error that refused it. Cancellation is the only error that stops
/// the caller rather than marking the row ([`plan_targets`]).
pub fn plan_target(shared: &SharedPlan, t: &Target, threads: usize) -> Result<PlanAnswer> {
    let (p, req) = inputs_of(shared, t)?;
    let prepared = plan::prepare(&p, &req)?;
    let mut answer = plan::run(prepared, threads, &|_| {})?;
    // Nothing to verify when nothing reaches the target: the row says why.
    let recommended = answer.plan.recommended.is_some();
    if let Some(observations) = shared.verify_observations.filter(|_| recommended) {
        let size = plan::verification(&answer, observations)?;
        plan::verify(&mut answer, &size, threads, &|_| {})?;
    }
    Ok(answer)
}

/// The table row of one read row: planned, or marked `error` with the
/// reason (a cancellation is returned as the error).
pub fn target_row(
    shared: &SharedPlan,
    row: &std::result::Result<Target, RowFault>,
    threads: usize,
) -> Result<TargetRow> {
    match row {
        Err(fault) => Ok(TargetRow::fault(fault)),
        Ok(t) => match plan_target(shared, t, threads) {
            Err(Error::Cancelled) => Err(Error::Cancelled),
            Err(e) => Ok(TargetRow::fault(&RowFault {
                line: t.line,
                name: t.name.clone(),
                reason: e.to_string().replace('\n', " "),
            })),
            Ok(answer) => {
                let seed = target_seed(shared.request.seed, t);
                let diameter_mas = t.diameter_mas.unwrap_or(shared.physical.diameter_mas);
                Ok(TargetRow::planned(t, seed, diameter_mas, &answer))
            }
        },
    }
}

/// Every row planned in order, one after the other (each plan uses
/// `threads`); `progress` counts targets.
pub fn plan_targets(
    shared: &SharedPlan,
    rows: &[std::result::Result<Target, RowFault>],
    threads: usize,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Vec<TargetRow>> {
    let mut table = Vec::with_capacity(rows.len());
    for row in rows {
        table.push(target_row(shared, row, threads)?);
        progress(1);
    }
    Ok(table)
}
