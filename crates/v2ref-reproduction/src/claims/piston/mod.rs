//! Claims of the differential-piston study (Section "Effect of differential
//! piston", Figs. 4 and 5). Every Monte Carlo number here comes from the same
//! code path as `v2ref piston` and the figure data (`figures::piston`).

use super::{Computed, Find, Finding};
use crate::cases::{paper_turbulence, APERTURE_M, FIG5_BASELINE_M, FIGURE_SEED};
use crate::cases::{Effort, SEEING_ARCSEC, WAVELENGTH_UM, WIND_MPS};
use crate::error::{Error, Result};
use crate::figures::piston::{fig4, fig5};
use crate::formalism::estimator::BinWindow;
use crate::formalism::observation::{Frequency, Observation};
use crate::formalism::phase::SpectralPhase;
use crate::formalism::source::Source;
use crate::formalism::spectrum::{Band, Spectrum, CPAS_PER_M_PER_INV_UM};
use crate::montecarlo::derive_seed;
use crate::piston::spectrum::{differential_piston_variance_from_structure_um2, PistonSpectrum};
use crate::piston::turbulence::r0_from_seeing_m;
use crate::piston::{simulate_piston, Detector, PistonRun, RunSize, ScanSetup};
use crate::table::{Figure, Table};
use crate::tolerance::{MC_SIGMAS, SIGNIFICANCE_SIGMAS, TURBULENCE_CHECK_REL};
use num_complex::Complex64;

mod figures;
mod scaling;
pub mod sensitivity;

use figures::{fig4_claims, fig5_claims, unbiased_from, Fig4Columns, FIG4_IDS, FIG5_IDS};
use scaling::scaling_claims;

/// Where a curve |y(f)| falls below a level for good (f increasing).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Crossing {
    /// Every point is below the level.
    BelowRange,
    /// Every point is above the level.
    AboveRange,
    /// The last downward crossing, interpolated linearly in log f, log |y|.
    At(f64),
}

/// Floor under |y| before taking its logarithm (a zero would give −∞ and a
/// NaN crossing); any positive value far below every level looked for.
const LOG_FLOOR: f64 = 1e-300;

/// The last frequency at which `|y|` goes from ≥ `level` to < `level`.
pub fn last_crossing(freqs: &[f64], y: &[f64], level: f64) -> Crossing {
    let n = freqs.len();
    let above = |i: usize| y[i].abs() >= level;
    match (0..n).rev().find(|&i| above(i)) {
        None => Crossing::BelowRange,
        Some(i) if i == n - 1 => Crossing::AboveRange,
        Some(i) => {
            let (a, b) = (
                y[i].abs().max(LOG_FLOOR).ln(),
                y[i + 1].abs().max(LOG_FLOOR).ln(),
            );
            let t = if a > b {
                (a - level.ln()) / (a - b)
            } else {
                0.5
            };
            let (fa, fb) = (freqs[i].ln(), freqs[i + 1].ln());
            Crossing::At((fa + t.clamp(0.0, 1.0) * (fb - fa)).exp())
        }
    }
}

fn crossing_value(c: Crossing, freqs: &[f64]) -> f64 {
    match c {
        Crossing::BelowRange => freqs[0],
        Crossing::AboveRange => freqs[freqs.len() - 1],
        Crossing::At(f) => f,
    }
}

fn crossing_text(c: Crossing) -> String {
    match c {
        Crossing::BelowRange => "below the lowest frequency simulated".into(),
        Crossing::AboveRange => "above the highest frequency simulated".into(),
        Crossing::At(f) => format!("{f:.0} Hz"),
    }
}

/// A threshold located on a Monte Carlo curve with its uncertainty: the
/// crossing of |bias| with `level`, and the interval between the crossings
/// of |bias| ∓ [`SIGNIFICANCE_SIGMAS`] standard errors — the frequencies at
/// which the Monte Carlo does not resolve |bias| from the level at the
/// significance the claims use elsewhere (3σ) — widened by half a grid
/// step on each side for the frequency sampling. A paper threshold inside
/// it is consistent with the curve.
pub struct Located {
    /// Best estimate, Hz.
    pub value: f64,
    /// Lower end of the interval, Hz.
    pub lo: f64,
    /// Upper end, Hz.
    pub hi: f64,
    /// The best estimate's kind.
    pub crossing: Crossing,
}

/// Locates where `|bias|` (column `col`, with `col_stderr`) of `table` falls
/// below `level` for good; a missing column is an error.
pub fn locate(table: &Table, col: &str, level: f64) -> Result<Located> {
    let f = column(table, "fringe_hz")?;
    let y = column(table, col)?;
    let se = column(table, &format!("{col}_stderr"))?;
    let best = last_crossing(&f, &y, level);
    let low: Vec<f64> = y
        .iter()
        .zip(&se)
        .map(|(v, s)| (v.abs() - SIGNIFICANCE_SIGMAS * s).max(0.0))
        .collect();
    let high: Vec<f64> = y
        .iter()
        .zip(&se)
        .map(|(v, s)| v.abs() + SIGNIFICANCE_SIGMAS * s)
        .collect();
    let half_step = if f.len() > 1 {
        ((f[f.len() - 1] / f[0]).ln() / (f.len() - 1) as f64 * 0.5).exp()
    } else {
        1.0
    };
    let a = crossing_value(last_crossing(&f, &low, level), &f) / half_step;
    let b = crossing_value(last_crossing(&f, &high, level), &f) * half_step;
    Ok(Located {
        value: crossing_value(best, &f),
        lo: a.min(b),
        hi: a.max(b),
        crossing: best,
    })
}

/// Whether the paper's threshold `p` lies inside the interval, in words.
fn inside_text(p: f64, loc: &Located) -> &'static str {
    match (loc.lo..=loc.hi).contains(&p) {
        false => "outside the interval",
        true if matches!(loc.crossing, Crossing::At(_)) => "inside the interval",
        true => "inside the interval, but the crossing itself is outside the simulated range",
    }
}

fn threshold_claim(
    id: &'static str,
    paper: Option<f64>,
    loc: &Located,
    what: &str,
    extra: &str,
) -> Computed {
    let paper_txt = paper.map_or(String::new(), |p| {
        format!("; paper {p} Hz, {}", inside_text(p, loc))
    });
    Computed {
        id,
        finding: Finding::Interval {
            value: loc.value,
            lo: loc.lo,
            hi: loc.hi,
            resolved: matches!(loc.crossing, Crossing::At(_)),
        },
        note: format!(
            "{what}: {} (interval {:.0}-{:.0} Hz from |bias| -/+ {SIGNIFICANCE_SIGMAS} standard errors and half a frequency step){paper_txt}. {extra}",
            crossing_text(loc.crossing),
            loc.lo,
            loc.hi
        ),
    }
}

/// The table `name` of `fig`; a missing table is an error.
fn table<'a>(fig: &'a Figure, name: &str) -> Result<&'a Table> {
    fig.tables
        .iter()
        .find(|t| t.name == name)
        .ok_or_else(|| Error::Invalid {
            param: "figure",
            reason: format!("{} has no table {name}", fig.id),
        })
}

/// The column `name` of `t`; a missing column is an error.
fn column(t: &Table, name: &str) -> Result<Vec<f64>> {
    t.column(name).ok_or_else(|| Error::Invalid {
        param: "figure",
        reason: format!("table {} has no column {name}", t.name),
    })
}

/// The column `name` of several tables, concatenated.
fn columns(ts: &[&Table], name: &str) -> Result<Vec<f64>> {
    let mut out = Vec::new();
    for t in ts {
        out.extend(column(t, name)?);
    }
    Ok(out)
}

fn max_abs(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// A failed claim for each of `ids`, with the error that stopped what they
/// are computed from.
fn failed_all(ids: &[&'static str], err: &Error) -> Vec<Computed> {
    ids.iter().map(|id| Computed::failed(id, err)).collect()
}

/// The claims this area computes.
pub(super) fn claims(find: &Find<'_>, effort: Effort) -> Vec<Computed> {
    let spec = |id: &str| find(id).expect("id in ledger");
    let mut out = closed_form_claims(&spec);
    out.extend(match fig4(effort).and_then(|f| Fig4Columns::read(&f)) {
        Ok(c) => fig4_claims(&c),
        Err(e) => failed_all(&FIG4_IDS, &e),
    });
    out.extend(match fig5(effort) {
        Ok(f5) => fig5_claims(&spec, &f5, &sensitivity::fig5_sensitivity(effort))
            .unwrap_or_else(|e| failed_all(&FIG5_IDS, &e)),
        Err(e) => failed_all(&FIG5_IDS, &e),
    });
    out.extend(scaling_claims(effort));
    out
}

type Spec<'a> = dyn Fn(&str) -> &'a super::ClaimSpec + 'a;

/// The closed forms: the 18 m spatial frequency, r0, the coherence time,
/// the OPD scanned per coherence time and the RMS differential piston.
fn closed_form_claims<'a>(spec: &Spec<'a>) -> Vec<Computed> {
    let band = Band::k();
    let sigma_eff = Spectrum::flat(band).sigma_eff_per_um();
    let s = FIG5_BASELINE_M * sigma_eff * CPAS_PER_M_PER_INV_UM;
    let mut out = vec![Computed::number(
        "piston.baseline_18m_cpas",
        s,
        format!(
            "S = B sigma_eff = {FIG5_BASELINE_M} m x {sigma_eff:.6} per um = {s:.3} cycles/arcsec (flat band, {} um wide at {} um)",
            band.width_um(),
            band.centre_um()
        ),
    )];
    let turb = paper_turbulence();
    let r0_cm = 100.0 * turb.r0_m();
    out.push(match r0_from_seeing_m(SEEING_ARCSEC, WAVELENGTH_UM) {
        Ok(r) => Computed::number(
            "piston.r0_k_cm",
            100.0 * r,
            format!(
                "r0 = lambda / seeing = {WAVELENGTH_UM} um / {SEEING_ARCSEC} arcsec = {:.2} cm",
                100.0 * r
            ),
        ),
        Err(e) => Computed::failed("piston.r0_k_cm", &e),
    });
    let tau_ms = 1e3 * turb.coherence_time_s();
    out.push(Computed::number(
        "piston.coherence_time_ms",
        tau_ms,
        format!(
            "tau = r0 / v = {:.4} m / {WIND_MPS} m/s = {tau_ms:.2} ms",
            r0_cm / 100.0
        ),
    ));
    for (id, f, other) in [
        ("piston.opd_per_tau_300hz_um", 300.0, 1000.0),
        ("piston.opd_per_tau_1000hz_um", 1000.0, 300.0),
    ] {
        let printed_tau_ms = spec("piston.coherence_time_ms").paper;
        out.push(opd_per_tau_claim(id, f, other, tau_ms, printed_tau_ms));
    }
    out.push(rms_claim(r0_cm));
    out
}

/// The OPD scanned in one coherence time at `f`, against the paper's
/// reading: the value at the `other` frequency with the printed,
/// rounded coherence time (the paper swapped the two printed values).
fn opd_per_tau_claim(
    id: &'static str,
    f: f64,
    other: f64,
    tau_ms: f64,
    printed_tau_ms: Option<f64>,
) -> Computed {
    let opd = f * WAVELENGTH_UM * tau_ms * 1e-3;
    let Some(printed_tau_ms) = printed_tau_ms else {
        return Computed::number(id, opd, "the ledger prints no coherence time");
    };
    let opd_rounded = f * WAVELENGTH_UM * printed_tau_ms * 1e-3;
    let swapped = other * WAVELENGTH_UM * printed_tau_ms * 1e-3;
    Computed::formula(
        id,
        opd,
        swapped,
        format!(
            "OPD scanned in one coherence time = f x lambda0 x tau = {f} Hz x {WAVELENGTH_UM} um x {tau_ms:.2} ms = {opd:.2} um ({opd_rounded:.1} um with tau rounded to {printed_tau_ms} ms). At {other} Hz with the rounded tau: {swapped:.1} um, the paper's reading with the two frequencies swapped. The physical argument that follows (piston mostly frozen at the higher frequency, where more OPD than the Fig. 5 scan's stroke is scanned per coherence time) needs the swapped reading.",
        ),
    )
}

/// The paper's bound on the saturated RMS differential piston (µm).
const SATURATED_PISTON_UM: f64 = 20.0;

/// The RMS differential piston on 18 m, two ways.
fn rms_claim(r0_cm: f64) -> Computed {
    let id = "piston.rms_18m_um";
    let turb = paper_turbulence();
    let rms = match PistonSpectrum::new(turb, APERTURE_M, FIG5_BASELINE_M) {
        Ok(p) => p.rms_um(),
        Err(e) => return Computed::failed(id, &e),
    };
    let rms_sf =
        differential_piston_variance_from_structure_um2(&turb, APERTURE_M, FIG5_BASELINE_M).sqrt();
    // The predicate: the two routes agree and the piston stays below the
    // paper's bound.
    let routes_agree = (rms - rms_sf).abs() <= TURBULENCE_CHECK_REL * rms;
    let holds = routes_agree && rms <= SATURATED_PISTON_UM;
    Computed::statement(
        id,
        Some(rms),
        holds,
        format!(
            "sigma_p = {rms:.3} um from the spectral integral, {rms_sf:.3} um from the aperture-averaged structure function ({:.0} cm apertures, r0 = {:.1} cm at {WAVELENGTH_UM} um, infinite outer scale); the paper's remark that the saturated piston stays near or below {SATURATED_PISTON_UM} um {}",
            100.0 * APERTURE_M,
            r0_cm,
            if holds { "holds" } else { "does not hold" }
        ),
    )
}
