//! Claims of the differential-piston study (Section "Effect of differential
//! piston", Figs. 4 and 5). Every Monte Carlo number here comes from the same
//! code path as `v2ref piston` and the figure data (`figures::piston`).

use super::{Computed, Find, Status};
use crate::error::{Error, Result};
use crate::formalism::estimator::BinWindow;
use crate::formalism::observation::{Frequency, Observation};
use crate::formalism::phase::SpectralPhase;
use crate::formalism::source::Source;
use crate::formalism::spectrum::{Band, Spectrum, CPAS_PER_M_PER_INV_UM};
use crate::montecarlo::derive_seed;
use crate::piston::turbulence::{
    differential_piston_variance_from_structure_um2, r0_from_seeing_m, PistonSpectrum,
};
use crate::piston::{simulate, Detector, PistonRun, RunSize, ScanSetup};
use crate::reproduction::cases::Effort;
use crate::reproduction::cases::{paper_turbulence, APERTURE_M, FIG5_BASELINE_M, FIGURE_SEED};
use crate::reproduction::figures::piston::{fig4, fig5};
use crate::reproduction::table::{Figure, Table};
use crate::tolerance::{MC_SIGMAS, SIGNIFICANCE_SIGMAS};
use num_complex::Complex64;

/// Where a curve |y(f)| falls below a level for good (f increasing).
#[derive(Debug, Clone, Copy, PartialEq)]
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
/// crossing of |bias| with `level`, and of |bias| ∓ 2 standard errors
/// (widened by half a grid step for the frequency sampling).
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
        .map(|(v, s)| (v.abs() - 2.0 * s).max(0.0))
        .collect();
    let high: Vec<f64> = y.iter().zip(&se).map(|(v, s)| v.abs() + 2.0 * s).collect();
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

fn threshold_claim(
    id: &'static str,
    paper: Option<f64>,
    loc: &Located,
    what: &str,
    extra: &str,
) -> Computed {
    let status = match (paper, loc.crossing) {
        (Some(p), Crossing::At(_)) if p >= loc.lo && p <= loc.hi => Status::Reproduced,
        _ => Status::Differs,
    };
    let paper_txt = paper.map_or(String::new(), |p| format!("; paper {p} Hz"));
    Computed::with_status(
        id,
        Some(loc.value),
        status,
        format!(
            "{what}: {} (interval {:.0}-{:.0} Hz from |bias| -/+ 2 standard errors and half a frequency step){paper_txt}. {extra}",
            crossing_text(loc.crossing),
            loc.lo,
            loc.hi
        ),
    )
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
        Ok(f5) => fig5_claims(&spec, &f5).unwrap_or_else(|e| failed_all(&FIG5_IDS, &e)),
        Err(e) => failed_all(&FIG5_IDS, &e),
    });
    out.extend(scaling_claims(effort));
    out
}

type Spec<'a> = dyn Fn(&str) -> &'a super::ClaimSpec + 'a;

/// The closed forms: the 18 m spatial frequency, r0, the coherence time,
/// the OPD scanned per coherence time and the RMS differential piston.
fn closed_form_claims<'a>(spec: &Spec<'a>) -> Vec<Computed> {
    let sigma_eff = Spectrum::flat(Band::k()).sigma_eff_per_um();
    let s = 18.0 * sigma_eff * CPAS_PER_M_PER_INV_UM;
    let mut out = vec![Computed::numeric(
        spec("piston.baseline_18m_cpas"),
        "piston.baseline_18m_cpas",
        s,
        format!("S = B sigma_eff = 18 m x {sigma_eff:.6} per um = {s:.3} cycles/arcsec (flat 2.0-2.4 um band)"),
    )];
    let turb = paper_turbulence();
    let r0_cm = 100.0 * turb.r0_m();
    out.push(match r0_from_seeing_m(1.0, 2.2) {
        Ok(r) => Computed::numeric(
            spec("piston.r0_k_cm"),
            "piston.r0_k_cm",
            100.0 * r,
            format!(
                "r0 = lambda / seeing = 2.2 um / 1 arcsec = {:.2} cm",
                100.0 * r
            ),
        ),
        Err(e) => Computed::failed("piston.r0_k_cm", &e),
    });
    let tau_ms = 1e3 * turb.coherence_time_s();
    out.push(Computed::numeric(
        spec("piston.coherence_time_ms"),
        "piston.coherence_time_ms",
        tau_ms,
        format!(
            "tau = r0 / v = {:.4} m / 10 m/s = {tau_ms:.2} ms",
            r0_cm / 100.0
        ),
    ));
    for (id, f, other) in [
        ("piston.opd_per_tau_300hz_um", 300.0, 1000.0),
        ("piston.opd_per_tau_1000hz_um", 1000.0, 300.0),
    ] {
        out.push(opd_per_tau_claim(spec(id), id, f, other, tau_ms));
    }
    out.push(rms_claim(r0_cm));
    out
}

/// The OPD scanned in one coherence time at `f` (the paper swapped the two
/// printed values).
fn opd_per_tau_claim(
    sp: &super::ClaimSpec,
    id: &'static str,
    f: f64,
    other: f64,
    tau_ms: f64,
) -> Computed {
    let opd = f * 2.2 * tau_ms * 1e-3;
    let opd_rounded = f * 2.2 * 0.045;
    let printed_matches_other = other * 2.2 * 0.045;
    let mut c = Computed::with_status(
        id,
        Some(opd),
        Status::Erratum,
        format!(
            "OPD scanned in one coherence time = f x lambda0 x tau = {f} Hz x 2.2 um x {tau_ms:.2} ms = {opd:.2} um ({opd_rounded:.1} um with tau rounded to 45 ms). The printed {} um is the value for {other} Hz ({printed_matches_other:.1} um): the paper swapped the two numbers. The physical argument that follows (piston mostly frozen at the higher frequency, where ~100 um > 64 um stroke are scanned per coherence time) needs the swapped reading.",
            sp.paper.unwrap_or(f64::NAN)
        ),
    );
    c.published = sp.paper;
    c.exact = Some(opd);
    c
}

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
    Computed::with_status(
        id,
        Some(rms),
        Status::Qualitative,
        format!(
            "sigma_p = {rms:.3} um from the spectral integral, {rms_sf:.3} um from the aperture-averaged structure function (45 cm apertures, r0 = {:.1} cm at 2.2 um, infinite outer scale); consistent with the paper's remark that the saturated piston stays near or below 20 um",
            r0_cm
        ),
    )
}

fn holds(ok: bool) -> Status {
    if ok {
        Status::Qualitative
    } else {
        Status::Differs
    }
}

/// The claims read from the Fig. 4 tables.
const FIG4_IDS: [&str; 4] = [
    "piston.fig4_v1_bias_300hz",
    "piston.fig4_v2_biased_300hz",
    "piston.fig4_v2_1000hz",
    "piston.fig4_v2_scatter_smaller",
];

/// The Fig. 4 columns the claims read, both disks concatenated.
struct Fig4Columns {
    bias_v1_300: Vec<f64>,
    bias_v1_300_se: Vec<f64>,
    bias_v2_300: Vec<f64>,
    bias_v2_300_se: Vec<f64>,
    bias_v2_1000: Vec<f64>,
    /// Scatter of V1 and V2 at both frequencies.
    scatter_v1: Vec<f64>,
    scatter_v2: Vec<f64>,
}

impl Fig4Columns {
    fn read(f4: &Figure) -> Result<Self> {
        let t300 = [
            table(f4, "fig4_43mas_300hz")?,
            table(f4, "fig4_10mas_300hz")?,
        ];
        let t1000 = [
            table(f4, "fig4_43mas_1000hz")?,
            table(f4, "fig4_10mas_1000hz")?,
        ];
        let all = [t300[0], t300[1], t1000[0], t1000[1]];
        Ok(Fig4Columns {
            bias_v1_300: columns(&t300, "bias_v1")?,
            bias_v1_300_se: columns(&t300, "bias_v1_stderr")?,
            bias_v2_300: columns(&t300, "bias_v2")?,
            bias_v2_300_se: columns(&t300, "bias_v2_stderr")?,
            bias_v2_1000: columns(&t1000, "bias_v2")?,
            scatter_v1: columns(&all, "scatter_v1")?,
            scatter_v2: columns(&all, "scatter_v2")?,
        })
    }
}

/// Points whose |bias| exceeds 3 standard errors.
fn significant(bias: &[f64], se: &[f64]) -> usize {
    bias.iter()
        .zip(se)
        .filter(|(b, s)| b.abs() > SIGNIFICANCE_SIGMAS * **s && **s > 0.0)
        .count()
}

fn fig4_claims(c: &Fig4Columns) -> Vec<Computed> {
    vec![
        fig4_v1_bias_300(c),
        fig4_v2_biased_300(c),
        fig4_v2_1000(c),
        fig4_v2_scatter_smaller(c),
    ]
}

fn fig4_v1_bias_300(c: &Fig4Columns) -> Computed {
    let n300 = c.bias_v1_300.len();
    let v1_300 = max_abs(&c.bias_v1_300);
    let sig_v1 = significant(&c.bias_v1_300, &c.bias_v1_300_se);
    // "Below 0.1%": every point consistent with |bias| < 1e-3 at 3 standard errors.
    let below = c
        .bias_v1_300
        .iter()
        .zip(&c.bias_v1_300_se)
        .filter(|(b, se)| b.abs() - SIGNIFICANCE_SIGMAS * **se < 1e-3)
        .count();
    Computed::with_status(
        "piston.fig4_v1_bias_300hz",
        Some(v1_300),
        holds(below == n300 && 2 * sig_v1 <= n300),
        format!("at 300 Hz over both disks and all {n300} spatial frequencies: largest |bias V1| {v1_300:.2e} (paper: below 0.1%); {below} points consistent with |bias| < 1e-3 at 3 standard errors; {sig_v1} points differ from zero by more than 3 standard errors (zero-mean noise otherwise)"),
    )
}

fn fig4_v2_biased_300(c: &Fig4Columns) -> Computed {
    let n300 = c.bias_v2_300.len();
    let v1_300 = max_abs(&c.bias_v1_300);
    let v2_300 = max_abs(&c.bias_v2_300);
    let sig_v1 = significant(&c.bias_v1_300, &c.bias_v1_300_se);
    let sig_v2 = significant(&c.bias_v2_300, &c.bias_v2_300_se);
    Computed::with_status(
        "piston.fig4_v2_biased_300hz",
        Some(v2_300),
        holds(sig_v2 > sig_v1 && 2 * sig_v2 >= n300 - 2),
        format!("at 300 Hz {sig_v2} of {n300} points have |bias V2| > 3 standard errors (V1: {sig_v1}); largest |bias V2| = {v2_300:.2e}, largest |bias V1| = {v1_300:.2e}"),
    )
}

fn fig4_v2_1000(c: &Fig4Columns) -> Computed {
    let b1000 = &c.bias_v2_1000;
    let under = b1000.iter().filter(|b| b.abs() < 1e-4).count();
    Computed::with_status(
        "piston.fig4_v2_1000hz",
        Some(under as f64 / b1000.len().max(1) as f64),
        holds(2 * under > b1000.len()),
        format!(
            "at 1000 Hz {under} of {} points have |bias V2| < 1e-4 (largest {:.2e})",
            b1000.len(),
            max_abs(b1000)
        ),
    )
}

fn fig4_v2_scatter_smaller(c: &Fig4Columns) -> Computed {
    let pairs: Vec<(f64, f64)> = c
        .scatter_v1
        .iter()
        .zip(&c.scatter_v2)
        .filter(|(a, _)| **a > 0.0)
        .map(|(a, b)| (*a, *b))
        .collect();
    let smaller = pairs.iter().filter(|(a, b)| b < a).count();
    let mut r: Vec<f64> = pairs.iter().map(|(a, b)| b / a).collect();
    r.sort_by(f64::total_cmp);
    // NaN when no point has piston: the claim then differs, visibly.
    let median_ratio = r.get(r.len() / 2).copied().unwrap_or(f64::NAN);
    Computed::with_status(
        "piston.fig4_v2_scatter_smaller",
        Some(median_ratio),
        holds(!pairs.is_empty() && smaller == pairs.len()),
        format!("scatter V2 < scatter V1 at {smaller} of {} points with piston; median ratio scatter V2 / scatter V1 = {median_ratio:.3}", pairs.len()),
    )
}

/// The claims read from the Fig. 5 tables.
const FIG5_IDS: [&str; 6] = [
    "piston.fig5_v1_biased_below_hz",
    "piston.fig5_v2_biased_below_hz",
    "piston.fig5_v1_unbiased_above_hz",
    "piston.fig5_v2_1e-5_above_hz",
    "piston.fig5_integration_low_freq",
    "piston.scatter_1000_scans",
];

const MODEL_NOTE: &str = "Model: Kolmogorov piston PSD with wind along the baseline, packet centred on the scan-mean piston, positive-frequency bins; the paper's Perrin (1997) sequences, its packet centring and bin window are not described, and the V2 thresholds move by large factors with the window (columns _band, _all).";

/// The Fig. 5 columns the claims read (sampled detector unless `_i`).
struct Fig5Columns {
    freqs: Vec<f64>,
    b1: Vec<f64>,
    se1: Vec<f64>,
    b2: Vec<f64>,
    s1: Vec<f64>,
    s2: Vec<f64>,
    b1_i: Vec<f64>,
    b2_i: Vec<f64>,
    s1_i: Vec<f64>,
}

impl Fig5Columns {
    fn read(samp: &Table, integ: &Table) -> Result<Self> {
        let c = Fig5Columns {
            freqs: column(samp, "fringe_hz")?,
            b1: column(samp, "bias_v1")?,
            se1: column(samp, "bias_v1_stderr")?,
            b2: column(samp, "bias_v2")?,
            s1: column(samp, "scatter_v1")?,
            s2: column(samp, "scatter_v2")?,
            b1_i: column(integ, "bias_v1")?,
            b2_i: column(integ, "bias_v2")?,
            s1_i: column(integ, "scatter_v1")?,
        };
        if c.freqs.len() < 2 || c.b1_i.len() != c.freqs.len() {
            return Err(Error::Invalid {
                param: "figure",
                reason: format!(
                    "fig5 needs two tables of the same frequencies, at least two ({} and {})",
                    c.freqs.len(),
                    c.b1_i.len()
                ),
            });
        }
        Ok(c)
    }
}

fn fig5_claims<'a>(spec: &Spec<'a>, f5: &Figure) -> Result<Vec<Computed>> {
    let samp = table(f5, "fig5_sampled")?;
    let c = Fig5Columns::read(samp, table(f5, "fig5_integrating")?)?;
    Ok(vec![
        fig5_v1_biased_below(spec, samp)?,
        fig5_v2_biased_below(spec, samp)?,
        fig5_v1_unbiased_above(spec, samp, &c)?,
        fig5_v2_1e5_above(spec, samp, &c)?,
        fig5_integration_low_freq(&c),
        scatter_1000_scans(&c),
    ])
}

fn fig5_v1_biased_below<'a>(spec: &Spec<'a>, samp: &Table) -> Result<Computed> {
    let id = "piston.fig5_v1_biased_below_hz";
    let l = locate(samp, "bias_v1", 0.01)?;
    Ok(threshold_claim(
        id,
        spec(id).paper,
        &l,
        "|bias V1| > 1% below",
        MODEL_NOTE,
    ))
}

fn fig5_v2_biased_below<'a>(spec: &Spec<'a>, samp: &Table) -> Result<Computed> {
    let id = "piston.fig5_v2_biased_below_hz";
    let l2 = locate(samp, "bias_v2", 0.01)?;
    let band = locate(samp, "bias_v2_band", 0.01)?;
    let all = locate(samp, "bias_v2_all", 0.01)?;
    Ok(threshold_claim(
        id,
        spec(id).paper,
        &l2,
        "|bias V2| > 1% below",
        &format!(
            "With the in-band window the same crossing is {}, with all bins {}. {MODEL_NOTE}",
            crossing_text(band.crossing),
            crossing_text(all.crossing)
        ),
    ))
}

/// V1 unbiased: lowest frequency above which every |bias| < 3 standard errors.
fn fig5_v1_unbiased_above<'a>(spec: &Spec<'a>, samp: &Table, c: &Fig5Columns) -> Result<Computed> {
    let id = "piston.fig5_v1_unbiased_above_hz";
    let freqs = &c.freqs;
    let last_sig = (0..c.b1.len())
        .rev()
        .find(|&i| c.b1[i].abs() > SIGNIFICANCE_SIGMAS * c.se1[i]);
    let unb = match last_sig {
        None => freqs[0],
        Some(i) if i + 1 < freqs.len() => freqs[i + 1],
        Some(_) => f64::NAN,
    };
    let unb_lo = last_sig.map_or(freqs[0], |i| freqs[i]);
    let l_1e3 = locate(samp, "bias_v1", 1e-3)?;
    let status = match spec(id).paper {
        Some(p) if unb.is_finite() && p >= unb_lo && p <= unb => Status::Reproduced,
        Some(p) if unb.is_finite() && (unb / p).ln().abs() < (freqs[1] / freqs[0]).ln() => {
            Status::Reproduced
        }
        _ => Status::Differs,
    };
    Ok(Computed::with_status(
        id,
        Some(unb),
        status,
        format!(
            "every |bias V1| is within 3 standard errors of zero from {unb:.0} Hz up (last significant point {unb_lo:.0} Hz); |bias V1| < 0.1% above {} ; paper 300 Hz. {MODEL_NOTE}",
            crossing_text(l_1e3.crossing)
        ),
    ))
}

fn fig5_v2_1e5_above<'a>(spec: &Spec<'a>, samp: &Table, c: &Fig5Columns) -> Result<Computed> {
    let id = "piston.fig5_v2_1e-5_above_hz";
    let l5 = locate(samp, "bias_v2", 1e-5)?;
    let top = c.freqs.len() - 1;
    let better = (0..c.freqs.len())
        .filter(|&i| {
            c.s2[i] < c.s1[i] && c.b2[i].abs() < c.b1[i].abs().max(SIGNIFICANCE_SIGMAS * c.se1[i])
        })
        .count();
    Ok(threshold_claim(
        id,
        spec(id).paper,
        &l5,
        "|bias V2| < 1e-5 above",
        &format!(
            "At {:.0} Hz: bias V2 {:.2e}, bias V1 {:.2e}, scatter V2 {:.2e} vs scatter V1 {:.2e}; V2 is more accurate than V1 (smaller |bias| and scatter) at {better} of {} frequencies. {MODEL_NOTE}",
            c.freqs[top], c.b2[top], c.b1[top], c.s2[top], c.s1[top],
            c.freqs.len()
        ),
    ))
}

/// Integration: below 200 Hz, compare |bias| integrating vs sampled.
fn fig5_integration_low_freq(c: &Fig5Columns) -> Computed {
    let low: Vec<usize> = (0..c.freqs.len()).filter(|&i| c.freqs[i] < 200.0).collect();
    let grow1 = low
        .iter()
        .filter(|&&i| c.b1_i[i].abs() > c.b1[i].abs())
        .count();
    let grow2 = low
        .iter()
        .filter(|&&i| c.b2_i[i].abs() > c.b2[i].abs())
        .count();
    let mean_growth = |bi: &[f64], b: &[f64]| {
        low.iter().map(|&i| bi[i].abs() - b[i].abs()).sum::<f64>() / low.len().max(1) as f64
    };
    let d1 = mean_growth(&c.b1_i, &c.b1);
    let d2 = mean_growth(&c.b2_i, &c.b2);
    Computed::with_status(
        "piston.fig5_integration_low_freq",
        Some(d1),
        holds(grow1 * 2 > low.len() && d1 > d2),
        format!(
            "below 200 Hz ({} frequencies): |bias| larger with integration at {grow1} (V1) and {grow2} (V2); mean increase of |bias| {d1:.2e} (V1), {d2:.2e} (V2); at {:.0} Hz scatter V1 {:.3e} integrating vs {:.3e} sampled",
            low.len(), c.freqs[0], c.s1_i[0], c.s1[0]
        ),
    )
}

/// Statistical error with 1000 scans at 300 Hz: scatter / sqrt(1000).
fn scatter_1000_scans(c: &Fig5Columns) -> Computed {
    let freqs = &c.freqs;
    let dist = |i: usize| (freqs[i] / 300.0).ln().abs();
    let i300 = (0..freqs.len())
        .min_by(|&a, &b| dist(a).total_cmp(&dist(b)))
        .unwrap_or(0); // freqs is not empty (checked on reading)
    let err1000 = c.s1[i300] / 1000f64.sqrt();
    Computed::with_status(
        "piston.scatter_1000_scans",
        Some(err1000),
        holds(err1000 >= 0.5e-3),
        format!(
            "scatter of V1 at {:.0} Hz on 18 m: {:.3e}; over 1000 scans the standard error is {err1000:.2e} (V2: {:.2e}) — the paper's 0.1% is the V1 figure",
            freqs[i300],
            c.s1[i300],
            c.s2[i300] / 1000f64.sqrt()
        ),
    )
}

/// Scans per run of the scaling checks.
fn scaling_scans(effort: Effort) -> usize {
    match effort {
        Effort::Full => 5000,
        Effort::Quick => 600,
    }
}

/// One scaling-check run on 18 m: wind `wind_mps`, fringe frequency `f`,
/// `source`, sampled detector; the seed is keyed by the claim `case`, the
/// wind and the frequency (not the source: the multiplicative check runs
/// two sources on one sequence on purpose).
fn scaling_run(
    case: &str,
    wind_mps: f64,
    f: f64,
    source: Source,
    scans: usize,
) -> Result<PistonRun> {
    let spectrum = PistonSpectrum::new(paper_turbulence(), APERTURE_M, FIG5_BASELINE_M)?
        .with_wind(wind_mps)?;
    let obs = Observation::new(
        Spectrum::flat(Band::k()),
        source,
        Frequency::BaselineM(FIG5_BASELINE_M),
        SpectralPhase::zero(),
    )?;
    let size = RunSize {
        scans,
        seed: derive_seed(FIGURE_SEED, case, &[wind_mps, f]),
        threads: 0,
    };
    let setup = ScanSetup::paper(f);
    let mut runs = simulate(&obs, &spectrum, &setup, &[Detector::Sampled], &size, None)?;
    runs.pop().ok_or_else(|| Error::Invalid {
        param: "detector",
        reason: "no run returned".into(),
    })
}

fn scaling_claims(effort: Effort) -> Vec<Computed> {
    let scans = scaling_scans(effort);
    vec![
        wind_rescaling_claim(scans)
            .unwrap_or_else(|e| Computed::failed("piston.wind_rescaling", &e)),
        multiplicative_claim(scans)
            .unwrap_or_else(|e| Computed::failed("piston.multiplicative", &e)),
    ]
}

/// z of the difference of the scatter (or bias) of two runs, positive bins.
fn z_between(x: &PistonRun, y: &PistonRun, v2: bool, bias: bool) -> f64 {
    let (wx, wy) = (x.window(BinWindow::Positive), y.window(BinWindow::Positive));
    let (ex, ey) = if v2 { (wx.v2, wy.v2) } else { (wx.v1, wy.v1) };
    if bias {
        (ex.mean - ey.mean) / ex.stderr_mean.hypot(ey.stderr_mean)
    } else {
        (ex.std - ey.std) / ex.stderr_std.hypot(ey.stderr_std)
    }
}

/// Wind rescaling: (f, v) = (100 Hz, 10 m/s) against (200 Hz, 20 m/s),
/// independent seeds; the unscaled (100 Hz, 20 m/s) shows the test's power.
fn wind_rescaling_claim(scans: usize) -> Result<Computed> {
    let case = "claim:piston.wind_rescaling";
    let a = scaling_run(case, 10.0, 100.0, Source::Point, scans)?;
    let b = scaling_run(case, 20.0, 200.0, Source::Point, scans)?;
    let c = scaling_run(case, 20.0, 100.0, Source::Point, scans)?;
    let (z1, z2, zb2) = (
        z_between(&a, &b, false, false),
        z_between(&a, &b, true, false),
        z_between(&a, &b, true, true),
    );
    let (n1, n2) = (
        z_between(&a, &c, false, false),
        z_between(&a, &c, true, false),
    );
    let ok = z1.abs() < MC_SIGMAS
        && z2.abs() < MC_SIGMAS
        && zb2.abs() < MC_SIGMAS
        && n1.abs() > MC_SIGMAS;
    Ok(Computed::with_status(
        "piston.wind_rescaling",
        Some(z1),
        holds(ok),
        format!(
            "{scans} scans each, independent seeds: (100 Hz, 10 m/s) vs (200 Hz, 20 m/s) differ by z = {z1:+.2} (scatter V1), {z2:+.2} (scatter V2), {zb2:+.2} (bias V2) standard errors; without rescaling (100 Hz, 20 m/s) the scatter differs by z = {n1:+.1} (V1), {n2:+.1} (V2). In this model the rescaling is exact in distribution: v P(nu) depends on nu and v only through nu/v, and the sample times scale as 1/f, so in units of the fringe period the scans see statistically identical piston sequences"
        ),
    ))
}

/// Multiplicative: a grey source of visibility 0.5 against the point
/// source, on the same piston sequence (the same seed key on purpose).
fn multiplicative_claim(scans: usize) -> Result<Computed> {
    let case = "claim:piston.multiplicative";
    let p = scaling_run(case, 10.0, 150.0, Source::Point, scans)?;
    let grey = Source::Constant {
        visibility: Complex64::new(0.5, 0.0),
    };
    let g = scaling_run(case, 10.0, 150.0, grey, scans)?;
    let (wp, wg) = (p.window(BinWindow::Positive), g.window(BinWindow::Positive));
    let r = [
        wg.v1.mean / wp.v1.mean,
        wg.v2.mean / wp.v2.mean,
        wg.v1.std / wp.v1.std,
        wg.v2.std / wp.v2.std,
    ];
    let worst = r.iter().fold(0.0_f64, |m, x| m.max((x - 0.5).abs()));
    Ok(Computed::with_status(
        "piston.multiplicative",
        Some(r[1]),
        holds(worst < crate::tolerance::VISIBILITY_SCALING_ABS),
        format!(
            "V = 0.5 (grey) against V = 1, same piston sequences at 150 Hz, {scans} scans: ratios bias V1 {:.9}, bias V2 {:.9}, scatter V1 {:.9}, scatter V2 {:.9} (0.5 expected; the fringe scales with V, so bias and scatter of V do too). For a resolved disk the visibility varies across the band and the scaling holds only approximately (see Fig. 4 tables)",
            r[0], r[1], r[2], r[3]
        ),
    ))
}
