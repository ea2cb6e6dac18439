//! Which `OI_VIS2` tables hold which estimator, and their rows matched to
//! a set's: one broadband channel per row, in order, the counts and the
//! wavelength checked, flagged rows left out and counted.

use super::integrity::ReadOptions;
use super::order::{insnames_of, tables_of_insname};
use super::read::{read_oifits_file, Vis2Table};
use super::scored::BAND_SLACK;
use super::scored::{Expected, OifitsEstimates};
use super::{estimator_key, KEY_BIAS, KEY_BINS, KEY_ESTIMATOR};
use crate::conformance::score::Estimator;
use crate::formats::Estimates;
use crate::{Error, Result};
use std::path::Path;

/// Which tables and rows of a file are read, and how damage is treated.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Choice<'a> {
    /// Read only the tables of this `INSNAME`; needed when the tables of
    /// one estimator have several (parameter `insname`).
    pub insname: Option<&'a str>,
    /// The estimator of tables without a `V2R_EST` keyword (a pipeline's
    /// own file); tables whose `V2R_EST` says otherwise are left aside.
    /// Needed when a table does not say (parameter `estimator`).
    pub estimator: Option<Estimator>,
    /// Read only the rows of this target (its `TARGET` in `OI_TARGET`, or
    /// its `TARGET_ID`); needed when the rows are of several (parameter
    /// `target`).
    pub target: Option<&'a str>,
    /// How checksums are treated.
    pub read: ReadOptions,
}

/// Reads a pipeline's estimates from the OIFITS file `path` (parameter
/// `estimates`), the tables and rows of `choice`.
///
/// Tables of the same estimator are read one after the other, in file
/// order. Refused: no table, more than one channel per row, an
/// `EFF_WAVE` outside the set's band, a `V2R_BINS` or `V2R_BIAS` other
/// than the window and convention scored, rows of several targets when
/// none is chosen, rows out of time order (`MJD`), a row count other than
/// the set's, a non-finite unflagged value. A row flagged in any table
/// read is left out of every estimator.
///
/// **Channels.** Given the set's channels ([`Expected::channels_m`]),
/// every table holds `NWAVE` = C values per row, and the answer is per
/// channel ([`OifitsEstimates::channels`], in the set's order). Each
/// `EFF_WAVE` must lie in exactly one channel's wavelength range (with a
/// slack of 1e-4 of the channel's width, and no less than `EFF_WAVE`'s
/// float32 rounding), one `EFF_WAVE` per channel, in either order
/// (increasing or decreasing wavelength; each table matched on its own).
/// `FLAG` is per channel: a flagged (row, channel) leaves that row out of
/// that channel only, for every estimator read. Refused besides: `NWAVE`
/// ≠ C, an `EFF_WAVE` in no channel or on the edge of two, two `EFF_WAVE`
/// in one channel, a channel with fewer unflagged rows than
/// [`min_unflagged_rows`](crate::min_unflagged_rows).
pub fn read_oifits_estimates(
    path: &Path,
    choice: &Choice,
    expected: &Expected,
) -> Result<OifitsEstimates> {
    const P: &str = "estimates";
    let err = |loc: String, reason: String| Error::data(P, path, loc, reason);
    let file = read_oifits_file(path, P, choice.read)?;
    let all = &file.tables;
    if all.is_empty() {
        return Err(err(String::new(), "no OI_VIS2 table".into()));
    }
    let names = || insnames_of(all);
    let chosen = tables_of_insname(all, choice.insname)?;
    let mut by_est: [Vec<&Vis2Table>; 2] = [Vec::new(), Vec::new()];
    for t in chosen {
        if let Some(e) = assign(t, choice.estimator, path)? {
            check_convention(t, expected)?;
            by_est[(e == Estimator::V2Sq) as usize].push(t);
        }
    }
    if by_est.iter().all(Vec::is_empty) {
        return Err(err(
            String::new(),
            format!(
                "no OI_VIS2 table of the estimator asked for; the file has {}",
                names()
            ),
        ));
    }
    for group in &by_est {
        let mut n: Vec<&str> = group.iter().map(|t| t.insname.as_str()).collect();
        n.dedup();
        if n.len() > 1 {
            return Err(Error::Invalid {
                param: "insname",
                reason: format!(
                    "several OI_VIS2 tables of one estimator (INSNAME {}); choose one",
                    n.join(", ")
                ),
            });
        }
    }
    let target = super::order::target_of(&file, &by_est, choice.target, path)?;
    let insnames = all.iter().map(|t| t.insname.clone()).collect();
    if let Some(ranges_m) = expected.channels_m.as_deref() {
        let set = (ranges_m, expected.rows);
        let mut read = super::select_channels::read_channels(&by_est, target, set, path)?;
        (read.insnames, read.notes) = (insnames, file.notes);
        read.insnames.dedup();
        return Ok(read);
    }
    let columns = by_est
        .iter()
        .map(|g| {
            (!g.is_empty())
                .then(|| concat(g, target, expected, path))
                .transpose()
        })
        .collect::<Result<Vec<_>>>()?;
    let mut read = unflagged(columns, path, insnames)?;
    read.notes = file.notes;
    Ok(read)
}

/// Refuses a table whose `V2R_BINS` or `V2R_BIAS` names another window or
/// convention than the one scored: its values would be compared with
/// another truth.
fn check_convention(t: &Vis2Table, expected: &Expected) -> Result<()> {
    let checks = [
        ("bins", KEY_BINS, &t.bins, expected.bins.name()),
        ("bias", KEY_BIAS, &t.bias, expected.bias.name()),
    ];
    for (param, key, written, asked) in checks {
        if let Some(w) = written.as_deref().filter(|w| *w != asked) {
            return Err(Error::Invalid {
                param,
                reason: format!(
                    "{asked} is scored, but {} says {key} = '{w}': \
                     its estimates are of another {}; score with {param} {w}",
                    t.at(),
                    if param == "bins" {
                        "window of bins"
                    } else {
                        "bias convention"
                    }
                ),
            });
        }
    }
    Ok(())
}

/// The estimator of table `t`: its `V2R_EST`, else `estimator`; None when
/// its `V2R_EST` differs from `estimator`.
fn assign(t: &Vis2Table, estimator: Option<Estimator>, path: &Path) -> Result<Option<Estimator>> {
    let own = match t.estimator.as_deref() {
        None => None,
        Some(k) if k == estimator_key(Estimator::V1Sq) => Some(Estimator::V1Sq),
        Some(k) if k == estimator_key(Estimator::V2Sq) => Some(Estimator::V2Sq),
        Some(k) => {
            return Err(Error::data(
                "estimates",
                path,
                format!("{}, keyword {KEY_ESTIMATOR}", t.at()),
                format!("{k:?}; V1SQ or V2SQ is accepted"),
            ))
        }
    };
    match (own, estimator) {
        (Some(o), Some(e)) => Ok((o == e).then_some(o)),
        (Some(o), None) => Ok(Some(o)),
        (None, Some(e)) => Ok(Some(e)),
        (None, None) => Err(Error::Invalid {
            param: "estimator",
            reason: format!(
                "OI_VIS2 INSNAME {} does not say which estimator it holds (no {KEY_ESTIMATOR} keyword); \
                 give v1_sq or v2_sq",
                t.insname
            ),
        }),
    }
}

/// The tables' values and flags, one channel per row, checked against
/// the set.
fn concat(
    tables: &[&Vis2Table],
    target: Option<i64>,
    expected: &Expected,
    path: &Path,
) -> Result<(Vec<f64>, Vec<bool>)> {
    let (lo, hi) = expected.band_m;
    let mut values = Vec::new();
    let mut flags = Vec::new();
    for t in tables {
        let at = t.at();
        if t.nwave != 1 {
            return Err(Error::data("estimates", path, at, format!(
                "{} channels per row; one broadband estimate per interferogram is needed (NWAVE = 1), \
                 or, to score each channel, a set with the same {} spectral channels",
                t.nwave, t.nwave
            )));
        }
        let w = t.eff_wave_m[0];
        if !(w >= lo * (1.0 - BAND_SLACK) && w <= hi * (1.0 + BAND_SLACK)) {
            return Err(Error::data("estimates", path, at, format!(
                "EFF_WAVE {w:e} m lies outside the set's band [{lo:e}, {hi:e}] m: not this set's wavelength"
            )));
        }
        super::order::check_time_order(t, target, path)?;
        let of_target = |r: &usize| target.is_none_or(|id| t.target_id[*r] == id);
        for r in (0..t.rows).filter(of_target) {
            values.push(t.vis2data[r]);
            flags.push(t.flag[r]);
        }
    }
    if values.len() as u64 != expected.rows {
        return Err(Error::data(
            "estimates",
            path,
            format!("OI_VIS2 INSNAME {}", tables[0].insname),
            format!(
                "{} rows; the set (its sidecar) has {}: one row per interferogram, in order",
                values.len(),
                expected.rows
            ),
        ));
    }
    Ok((values, flags))
}

/// Leaves out every row flagged in any column; refuses a non-finite
/// unflagged value.
fn unflagged(
    columns: Vec<Option<(Vec<f64>, Vec<bool>)>>,
    path: &Path,
    insnames: Vec<String>,
) -> Result<OifitsEstimates> {
    let rows = columns
        .iter()
        .flatten()
        .map(|(v, _)| v.len())
        .next()
        .unwrap_or(0);
    let bad: Vec<bool> = (0..rows)
        .map(|r| columns.iter().flatten().any(|(_, f)| f[r]))
        .collect();
    let mut out = columns.into_iter().map(|c| {
        c.map(|(v, _)| {
            v.into_iter()
                .zip(&bad)
                .filter(|(_, &b)| !b)
                .map(|(x, _)| x)
                .collect::<Vec<f64>>()
        })
    });
    let (v1_sq, v2_sq) = (out.next().flatten(), out.next().flatten());
    for (name, col) in [("V1SQ", &v1_sq), ("V2SQ", &v2_sq)] {
        if let Some(r) = col
            .as_ref()
            .and_then(|x| x.iter().position(|v| !v.is_finite()))
        {
            return Err(Error::data(
                "estimates",
                path,
                format!("{name}, unflagged value {} (1-based)", r + 1),
                "not a finite number; flag it (FLAG = T) or give a value",
            ));
        }
    }
    let mut insnames = insnames;
    insnames.dedup();
    Ok(OifitsEstimates {
        estimates: Estimates { v1_sq, v2_sq },
        rows,
        flagged: bad.iter().filter(|&&b| b).count(),
        insnames,
        notes: Vec::new(),
        channels: Vec::new(),
    })
}
