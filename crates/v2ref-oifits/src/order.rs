//! Which rows of an OIFITS file stand for a set's rows: those of one
//! target (`TARGET_ID`, chosen by name or number when there are several),
//! in time order (`MJD` never decreasing), since a set's rows are matched
//! to the file's in order.

use super::read::{OifitsFile, Vis2Table};
use crate::{Error, Result};
use std::path::Path;

/// The `TARGET_ID` whose rows are read: None when every row is of one
/// target and none is chosen; `chosen` (a `TARGET` name or a number)
/// resolved otherwise. Refused: rows of several targets and none chosen,
/// a chosen target with no rows, a number that names one target and is
/// the `TARGET_ID` of another's rows (ambiguous: neither is preferred).
pub fn target_of(
    file: &OifitsFile,
    groups: &[Vec<&Vis2Table>],
    chosen: Option<&str>,
    path: &Path,
) -> Result<Option<i64>> {
    let mut ids: Vec<i64> = groups
        .iter()
        .flatten()
        .flat_map(|t| t.target_id.iter().copied())
        .collect();
    ids.sort_unstable();
    ids.dedup();
    let listed = || {
        ids.iter()
            .map(|id| match file.targets.iter().find(|(i, _)| i == id) {
                Some((_, name)) => format!("{id} ({name})"),
                None => id.to_string(),
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    let Some(name) = chosen else {
        if ids.len() > 1 {
            return Err(Error::Invalid {
                param: "target",
                reason: format!(
                    "the rows are of several targets, TARGET_ID {}; choose one (its TARGET name or TARGET_ID)",
                    listed()
                ),
            });
        }
        return Ok(None);
    };
    let by_name = file
        .targets
        .iter()
        // As OIFITS compares names, leading and trailing blanks are not
        // significant (the MIRC-X pipeline writes `' bet Ari'`); nor,
        // here, is case.
        .find(|(_, n)| n.trim().eq_ignore_ascii_case(name.trim()))
        .map(|(i, _)| *i);
    let by_id = name.trim().parse::<i64>().ok();
    if let (Some(named), Some(numbered)) = (by_name, by_id) {
        if named != numbered && ids.contains(&numbered) {
            return Err(Error::Invalid {
                param: "target",
                reason: format!(
                    "{name} is ambiguous: the TARGET named {name:?} has TARGET_ID {named}, \
                     and rows have TARGET_ID {numbered}; the rows are of TARGET_ID {}: \
                     choose by a TARGET name that is not a number",
                    listed()
                ),
            });
        }
    }
    match by_name.or(by_id).filter(|id| ids.contains(id)) {
        Some(id) => Ok(Some(id)),
        None => Err(Error::Invalid {
            param: "target",
            reason: format!(
                "{name}: no OI_VIS2 row of this target in {}; its rows are of TARGET_ID {}",
                path.display(),
                listed()
            ),
        }),
    }
}

/// The `OI_VIS2` tables of `file` (read from `path`) of `insname`
/// (every table when None), each with only the rows of `target` (a
/// `TARGET` name or `TARGET_ID`, chosen as `score` chooses; every row when
/// None); a table with no row of the target is left out. Refused
/// (parameters `insname`, `target`): no table of the `INSNAME`, no row of
/// the target, a number that names one target and is another's
/// `TARGET_ID`.
pub fn choose_tables(
    file: &OifitsFile,
    insname: Option<&str>,
    target: Option<&str>,
    path: &Path,
) -> Result<Vec<Vis2Table>> {
    let chosen = tables_of_insname(&file.tables, insname)?;
    let id = match target {
        Some(_) => target_of(file, std::slice::from_ref(&chosen), target, path)?,
        None => None,
    };
    let Some(id) = id else {
        return Ok(chosen.into_iter().cloned().collect());
    };
    Ok(chosen
        .into_iter()
        .filter(|t| t.target_id.contains(&id))
        .map(|t| rows_of_target(t, id))
        .collect())
}

/// Table `t` with only the rows of `TARGET_ID` `id`.
fn rows_of_target(t: &Vis2Table, id: i64) -> Vis2Table {
    let keep: Vec<usize> = (0..t.rows).filter(|&r| t.target_id[r] == id).collect();
    Vis2Table {
        rows: keep.len(),
        target_id: pick(&t.target_id, &keep, 1),
        mjd: pick(&t.mjd, &keep, 1),
        ucoord_m: pick(&t.ucoord_m, &keep, 1),
        vcoord_m: pick(&t.vcoord_m, &keep, 1),
        vis2data: pick(&t.vis2data, &keep, t.nwave),
        vis2err: pick(&t.vis2err, &keep, t.nwave),
        flag: pick(&t.flag, &keep, t.nwave),
        ..t.clone()
    }
}

/// The rows `keep` of `values`, `width` values a row.
fn pick<T: Clone>(values: &[T], keep: &[usize], width: usize) -> Vec<T> {
    keep.iter()
        .flat_map(|&r| values[r * width..(r + 1) * width].iter().cloned())
        .collect()
}

/// Refuses rows of table `t` (those of `target`, or all) whose `MJD` is
/// not a number or is earlier than the row before: the rows would not
/// be the set's, in order.
pub fn check_time_order(t: &Vis2Table, target: Option<i64>, path: &Path) -> Result<()> {
    let mut last: Option<(usize, f64)> = None;
    for r in 0..t.rows {
        if target.is_some_and(|id| t.target_id[r] != id) {
            continue;
        }
        let mjd = t.mjd[r];
        let at = || format!("{}, row {}", t.at(), r + 1);
        if !mjd.is_finite() {
            return Err(Error::data(
                "estimates",
                path,
                at(),
                format!("MJD {mjd}; a date (days) is needed"),
            ));
        }
        if let Some((q, before)) = last.filter(|(_, before)| mjd < *before) {
            return Err(Error::data(
                "estimates",
                path,
                at(),
                format!(
                    "MJD {mjd} is earlier than row {}'s {before}: the rows are matched to the \
                     set's in order, so they must be in time order",
                    q + 1
                ),
            ));
        }
        last = Some((r, mjd));
    }
    Ok(())
}

/// The `INSNAME`s of `tables`, in file order, each once in a run.
pub(crate) fn insnames_of(tables: &[Vis2Table]) -> String {
    let mut v: Vec<&str> = tables.iter().map(|t| t.insname.as_str()).collect();
    v.dedup();
    v.join(", ")
}

/// The tables of `insname` (every table when None), refused (parameter
/// `insname`) when there is none.
pub(crate) fn tables_of_insname<'a>(
    all: &'a [Vis2Table],
    insname: Option<&str>,
) -> Result<Vec<&'a Vis2Table>> {
    let chosen: Vec<&Vis2Table> = match insname {
        Some(n) => all.iter().filter(|t| same_name(&t.insname, n)).collect(),
        None => all.iter().collect(),
    };
    match insname {
        Some(n) if chosen.is_empty() => Err(Error::Invalid {
            param: "insname",
            reason: format!(
                "{n}: no OI_VIS2 table of this INSNAME; the file has {}",
                insnames_of(all)
            ),
        }),
        _ => Ok(chosen),
    }
}

/// True when an `INSNAME` written is the one asked for, as OIFITS
/// compares names: leading and trailing blanks are not significant.
fn same_name(written: &str, asked: &str) -> bool {
    written.trim() == asked.trim()
}
