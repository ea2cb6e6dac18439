//! A pipeline's estimates in spectral channels (`NWAVE` = C values per
//! row): each table's `EFF_WAVE`s matched to the set's channels by
//! wavelength, the values read per channel, `FLAG` per (row, channel).
//!
//! A pipeline writes its channels in its own order (PIONIER, GRAVITY and
//! MIRC-X often in decreasing wavelength) and `EFF_WAVE` as float32, so a
//! column is matched to the channel its `EFF_WAVE` lies in, never by
//! position.

use super::read::Vis2Table;
use super::scored::{min_unflagged_rows, ChannelEstimates, OifitsEstimates, BAND_SLACK};
use crate::formats::Estimates;
use crate::{Error, Result};
use std::path::Path;

/// One estimator's tables read per channel of the set.
struct PerChannel {
    /// `values[j][r]`: row r of channel j.
    values: Vec<Vec<f64>>,
    /// `flags[j][r]`, the same shape.
    flags: Vec<Vec<bool>>,
    /// The `EFF_WAVE` of each channel, m (the first table's).
    eff_wave_m: Vec<f64>,
}

/// The estimates of `groups` (the V1² tables, the V2² tables; one group
/// at least not empty) per channel of the set, `set` its channels'
/// wavelength ranges (m) and rows; `target` the `TARGET_ID` read.
pub(crate) fn read_channels(
    groups: &[Vec<&Vis2Table>],
    target: Option<i64>,
    set: (&[(f64, f64)], u64),
    path: &Path,
) -> Result<OifitsEstimates> {
    let columns = groups
        .iter()
        .map(|g| {
            (!g.is_empty())
                .then(|| per_channel(g, target, set, path))
                .transpose()
        })
        .collect::<Result<Vec<_>>>()?;
    let read: Vec<&PerChannel> = columns.iter().flatten().collect();
    let rows = read.first().map_or(0, |p| p.values[0].len());
    let tables: Vec<String> = groups.iter().flatten().map(|t| t.at()).collect();
    let mut any_bad = vec![false; rows];
    let mut channels = Vec::with_capacity(set.0.len());
    for (j, &range_m) in set.0.iter().enumerate() {
        let bad: Vec<bool> = (0..rows)
            .map(|r| read.iter().any(|p| p.flags[j][r]))
            .collect();
        let flagged = bad.iter().filter(|&&b| b).count();
        let eff_wave_m = read[0].eff_wave_m[j];
        let floor = min_unflagged_rows(rows as u64);
        if ((rows - flagged) as u64) < floor {
            return Err(Error::data(
                "estimates",
                path,
                format!("{}, channel {} of {}", tables.join(" and "), j + 1, set.0.len()),
                format!(
                    "{} of {rows} rows unflagged at EFF_WAVE {:.6} µm (channel {}); at least {floor} \
                     are scored per channel: unflag rows or leave the channel out of the set",
                    rows - flagged,
                    eff_wave_m * 1e6,
                    range_um(range_m)
                ),
            ));
        }
        let mut kept = columns.iter().enumerate().map(|(e, c)| {
            c.as_ref()
                .map(|p| kept_values(&p.values[j], &bad, (e, j), path))
                .transpose()
        });
        let (v1_sq, v2_sq) = (kept.next().transpose()?, kept.next().transpose()?);
        for (r, b) in bad.iter().enumerate() {
            any_bad[r] |= b;
        }
        channels.push(ChannelEstimates {
            channel: j,
            range_m,
            eff_wave_m,
            estimates: Estimates {
                v1_sq: v1_sq.flatten(),
                v2_sq: v2_sq.flatten(),
            },
            flagged,
        });
    }
    Ok(OifitsEstimates {
        estimates: Estimates {
            v1_sq: None,
            v2_sq: None,
        },
        rows,
        flagged: any_bad.iter().filter(|&&b| b).count(),
        insnames: Vec::new(),
        notes: Vec::new(),
        channels,
    })
}

/// The values of the rows not `bad`; refuses a non-finite one (estimator
/// `e`, 0 for V1², channel `j`).
fn kept_values(
    values: &[f64],
    bad: &[bool],
    (e, j): (usize, usize),
    path: &Path,
) -> Result<Vec<f64>> {
    let kept: Vec<f64> = values
        .iter()
        .zip(bad)
        .filter(|(_, &b)| !b)
        .map(|(v, _)| *v)
        .collect();
    match kept.iter().position(|v| !v.is_finite()) {
        None => Ok(kept),
        Some(r) => Err(Error::data(
            "estimates",
            path,
            format!(
                "{}, channel {}, unflagged value {} (1-based)",
                ["V1SQ", "V2SQ"][e],
                j + 1,
                r + 1
            ),
            "not a finite number; flag it (FLAG = T in that channel) or give a value",
        )),
    }
}

/// One estimator's `tables`, read one after the other, per channel.
fn per_channel(
    tables: &[&Vis2Table],
    target: Option<i64>,
    (ranges_m, rows): (&[(f64, f64)], u64),
    path: &Path,
) -> Result<PerChannel> {
    let c = ranges_m.len();
    let mut out = PerChannel {
        values: vec![Vec::new(); c],
        flags: vec![Vec::new(); c],
        eff_wave_m: vec![f64::NAN; c],
    };
    for (i, t) in tables.iter().enumerate() {
        let map = match_channels(t, ranges_m, path)?;
        super::order::check_time_order(t, target, path)?;
        if i == 0 {
            for (k, &j) in map.iter().enumerate() {
                out.eff_wave_m[j] = t.eff_wave_m[k];
            }
        }
        let of_target = |r: &usize| target.is_none_or(|id| t.target_id[*r] == id);
        for r in (0..t.rows).filter(of_target) {
            for (k, &j) in map.iter().enumerate() {
                out.values[j].push(t.vis2data[r * c + k]);
                out.flags[j].push(t.flag[r * c + k]);
            }
        }
    }
    let read = out.values[0].len();
    if read as u64 != rows {
        return Err(Error::data(
            "estimates",
            path,
            format!("OI_VIS2 INSNAME {}", tables[0].insname),
            format!(
                "{read} rows; the set (its sidecar) has {rows}: one row per interferogram, in order"
            ),
        ));
    }
    Ok(out)
}

/// The set's channel of each column of table `t` (column k holds channel
/// `map[k]`): one `EFF_WAVE` in each channel.
fn match_channels(t: &Vis2Table, ranges_m: &[(f64, f64)], path: &Path) -> Result<Vec<usize>> {
    let refuse = |reason: String| Error::data("estimates", path, t.at(), reason);
    let c = ranges_m.len();
    if t.nwave != c {
        return Err(refuse(format!(
            "NWAVE = {}, but the set has {c} spectral channels ({}); one value per channel \
             and row is needed, each EFF_WAVE in its channel",
            t.nwave,
            ranges_list(ranges_m)
        )));
    }
    let mut taken: Vec<Option<usize>> = vec![None; c];
    let mut map = Vec::with_capacity(c);
    for (k, &w) in t.eff_wave_m.iter().enumerate() {
        let j = channel_of(w, ranges_m).map_err(|why| {
            refuse(format!(
                "EFF_WAVE {} of {c} ({:.6} µm) {why}; the set's channels: {}",
                k + 1,
                w * 1e6,
                ranges_list(ranges_m)
            ))
        })?;
        if let Some(first) = taken[j] {
            return Err(refuse(format!(
                "EFF_WAVE {} and {} ({:.6} and {:.6} µm) both lie in the set's channel {} of {c} \
                 ({}); one EFF_WAVE per channel is needed",
                first + 1,
                k + 1,
                t.eff_wave_m[first] * 1e6,
                w * 1e6,
                j + 1,
                range_um(ranges_m[j])
            )));
        }
        taken[j] = Some(k);
        map.push(j);
    }
    Ok(map)
}

/// The channel whose wavelength range holds `w` (m): the one that holds
/// it exactly, else the one that holds it within [`edge_slack_m`];
/// refused (the reason) when none does, or two do (`w` on their edge).
fn channel_of(w: f64, ranges_m: &[(f64, f64)]) -> std::result::Result<usize, String> {
    let holding = |slack: bool| -> Vec<usize> {
        let within = |&(lo, hi): &(f64, f64)| {
            let s = if slack { edge_slack_m(lo, hi, w) } else { 0.0 };
            w >= lo - s && w <= hi + s
        };
        (0..ranges_m.len())
            .filter(|&j| within(&ranges_m[j]))
            .collect()
    };
    let exact = holding(false);
    let found = if exact.is_empty() {
        holding(true)
    } else {
        exact
    };
    match found[..] {
        [j] => Ok(j),
        [] => Err("lies in none of the set's channels".into()),
        [a, b, ..] => Err(format!(
            "lies on the edge of the set's channels {} and {}: which one it is is not known",
            a + 1,
            b + 1
        )),
    }
}

/// The slack on a channel's ends, m: [`BAND_SLACK`] of its width, and no
/// less than the float32 rounding of a wavelength `w` (half a float32
/// unit is `2⁻²⁴ w`; `f32::EPSILON w` is twice that).
fn edge_slack_m(lo: f64, hi: f64, w: f64) -> f64 {
    (BAND_SLACK * (hi - lo)).max(w.abs() * f64::from(f32::EPSILON))
}

/// A channel's range, µm: `[1.600000, 1.650000] µm`.
fn range_um((lo, hi): (f64, f64)) -> String {
    format!("[{:.6}, {:.6}] µm", lo * 1e6, hi * 1e6)
}

/// The channels' ranges, µm, in order, for a one-line message: every one
/// up to ten, else the first and last three.
fn ranges_list(ranges_m: &[(f64, f64)]) -> String {
    let shown = |r: &[(f64, f64)]| -> Vec<String> { r.iter().map(|&x| range_um(x)).collect() };
    let c = ranges_m.len();
    if c <= 10 {
        return shown(ranges_m).join(", ");
    }
    format!(
        "{}, … {} more …, {}",
        shown(&ranges_m[..3]).join(", "),
        c - 6,
        shown(&ranges_m[c - 3..]).join(", ")
    )
}
