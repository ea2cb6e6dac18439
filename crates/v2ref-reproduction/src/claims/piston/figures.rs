//! Claims read from the Fig. 4 and Fig. 5 tables (the cached figures of
//! [`crate::figures::piston`]).

use super::sensitivity::{self, Sensitivity, BIASED_LEVEL, V2_UNBIASED_LEVEL};
use super::*;
use crate::figures::piston::{FIG4_HIGH_HZ, FIG4_LOW_HZ};

/// The claims read from the Fig. 4 tables.
pub(super) const FIG4_IDS: [&str; 4] = [
    "piston.fig4_v1_bias_300hz",
    "piston.fig4_v2_biased_300hz",
    "piston.fig4_v2_1000hz",
    "piston.fig4_v2_scatter_smaller",
];

/// The Fig. 4 columns the claims read, both disks concatenated.
pub(super) struct Fig4Columns {
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
    pub(super) fn read(f4: &Figure) -> Result<Self> {
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

pub(super) fn fig4_claims(c: &Fig4Columns) -> Vec<Computed> {
    vec![
        fig4_v1_bias_300(c),
        fig4_v2_biased_300(c),
        fig4_v2_1000(c),
        fig4_v2_scatter_smaller(c),
    ]
}

/// The paper's bounds: V1's piston bias at 300 Hz "below 0.1%", V2's at
/// 1000 Hz "mostly below 0.01%".
const V1_BIAS_300HZ_BOUND: f64 = 1e-3;
const V2_BIAS_1000HZ_BOUND: f64 = 1e-4;

fn fig4_v1_bias_300(c: &Fig4Columns) -> Computed {
    let n300 = c.bias_v1_300.len();
    let v1_300 = max_abs(&c.bias_v1_300);
    let sig_v1 = significant(&c.bias_v1_300, &c.bias_v1_300_se);
    // "Below 0.1%": every point consistent with |bias| < the bound at 3 standard errors.
    let below = c
        .bias_v1_300
        .iter()
        .zip(&c.bias_v1_300_se)
        .filter(|(b, se)| b.abs() - SIGNIFICANCE_SIGMAS * **se < V1_BIAS_300HZ_BOUND)
        .count();
    Computed::statement(
        "piston.fig4_v1_bias_300hz",
        Some(v1_300),
        below == n300 && 2 * sig_v1 <= n300,
        format!("at {FIG4_LOW_HZ} Hz over both disks and all {n300} spatial frequencies: largest |bias V1| {v1_300:.2e}; {below} points consistent with |bias| < {V1_BIAS_300HZ_BOUND:e} at {SIGNIFICANCE_SIGMAS} standard errors; {sig_v1} points differ from zero by more than {SIGNIFICANCE_SIGMAS} standard errors (zero-mean noise otherwise)"),
    )
}

fn fig4_v2_biased_300(c: &Fig4Columns) -> Computed {
    let n300 = c.bias_v2_300.len();
    let v1_300 = max_abs(&c.bias_v1_300);
    let v2_300 = max_abs(&c.bias_v2_300);
    let sig_v1 = significant(&c.bias_v1_300, &c.bias_v1_300_se);
    let sig_v2 = significant(&c.bias_v2_300, &c.bias_v2_300_se);
    Computed::statement(
        "piston.fig4_v2_biased_300hz",
        Some(v2_300),
        sig_v2 > sig_v1 && 2 * sig_v2 >= n300 - 2,
        format!("at {FIG4_LOW_HZ} Hz {sig_v2} of {n300} points have |bias V2| > {SIGNIFICANCE_SIGMAS} standard errors (V1: {sig_v1}); largest |bias V2| = {v2_300:.2e}, largest |bias V1| = {v1_300:.2e}"),
    )
}

fn fig4_v2_1000(c: &Fig4Columns) -> Computed {
    let b1000 = &c.bias_v2_1000;
    let under = b1000
        .iter()
        .filter(|b| b.abs() < V2_BIAS_1000HZ_BOUND)
        .count();
    Computed::statement(
        "piston.fig4_v2_1000hz",
        Some(under as f64 / b1000.len().max(1) as f64),
        2 * under > b1000.len(),
        format!(
            "at {FIG4_HIGH_HZ} Hz {under} of {} points have |bias V2| < {V2_BIAS_1000HZ_BOUND:e} (largest {:.2e})",
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
    Computed::statement(
        "piston.fig4_v2_scatter_smaller",
        Some(median_ratio),
        !pairs.is_empty() && smaller == pairs.len(),
        format!("scatter V2 < scatter V1 at {smaller} of {} points with piston; median ratio scatter V2 / scatter V1 = {median_ratio:.3}", pairs.len()),
    )
}

/// The claims read from the Fig. 5 tables.
pub(super) const FIG5_IDS: [&str; 6] = [
    "piston.fig5_v1_biased_below_hz",
    "piston.fig5_v2_biased_below_hz",
    "piston.fig5_v1_unbiased_above_hz",
    "piston.fig5_v2_1e-5_above_hz",
    "piston.fig5_integration_low_freq",
    "piston.scatter_1000_scans",
];

/// The model of the Fig. 5 claims, in words, with the scan of
/// [`ScanSetup::paper`].
fn model_note() -> String {
    let scan = ScanSetup::paper(FIG4_LOW_HZ);
    format!(
        "Model: two-aperture Kolmogorov piston PSD with wind along the baseline, packet centred on the scan-mean piston, positive-frequency bins, {} x {} um; the paper's Perrin (1997) sequences, its packet centring and bin window are not described.",
        scan.samples, scan.dx_um
    )
}

/// The level of |bias V1| the paper calls negligible above its
/// "unbiased from" frequency (0.1 %).
const V1_SMALL_BIAS_LEVEL: f64 = 1e-3;

/// `level` in percent, for the notes.
fn pct(level: f64) -> f64 {
    100.0 * level
}

/// The evidence of the sensitivity table for threshold `i` (in
/// [`sensitivity::THRESHOLD_NAMES`] order), or why it is missing.
fn sensitivity_note(sens: &Result<Sensitivity>, i: usize) -> String {
    let s = match sens {
        Ok(s) => s,
        Err(e) => return format!("Sensitivity table not computed: {e}"),
    };
    let values = s.rows.iter().map(|r| r.thresholds_hz[i]);
    let (lo, hi) = values.fold((f64::INFINITY, 0.0_f64), |(a, b), t| (a.min(t), b.max(t)));
    let (within, best) = s.closest(i);
    let inside = s.rows.iter().filter(|r| r.paper_inside(i)).count();
    let best_txt = best.map_or(String::new(), |b| {
        format!("; closest: {} at {:.0} Hz", b.label(), b.thresholds_hz[i])
    });
    let all = s.reproducing_all();
    let all_txt = if all.is_empty() {
        "no combination gives all four paper thresholds within a grid step".to_owned()
    } else {
        format!(
            "all four within a grid step: {}",
            all.iter().map(|r| r.label()).collect::<Vec<_>>().join("; ")
        )
    };
    format!(
        "Sensitivity (fig5_sensitivity, {} combinations of spectrum model x packet reference x bin window x sampling, {} scans per point): this threshold spans {lo:.0}-{hi:.0} Hz; the paper's {:.0} Hz lies inside the Monte Carlo interval of {inside} of them and within one grid step of {}{best_txt}; {all_txt}.",
        s.rows.len(),
        s.scans,
        sensitivity::PAPER_THRESHOLDS_HZ[i],
        within.len(),
    )
}

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
    pub(super) fn read(samp: &Table, integ: &Table) -> Result<Self> {
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

pub(super) fn fig5_claims<'a>(
    spec: &Spec<'a>,
    f5: &Figure,
    sens: &Result<Sensitivity>,
) -> Result<Vec<Computed>> {
    let samp = table(f5, "fig5_sampled")?;
    let c = Fig5Columns::read(samp, table(f5, "fig5_integrating")?)?;
    Ok(vec![
        fig5_v1_biased_below(spec, samp, &sensitivity_note(sens, 0))?,
        fig5_v2_biased_below(spec, samp, &sensitivity_note(sens, 1))?,
        fig5_v1_unbiased_above(spec, samp, &c, &sensitivity_note(sens, 2))?,
        fig5_v2_1e5_above(spec, samp, &c, &sensitivity_note(sens, 3))?,
        fig5_integration_low_freq(&c),
        scatter_1000_scans(&c),
    ])
}

fn fig5_v1_biased_below<'a>(spec: &Spec<'a>, samp: &Table, evidence: &str) -> Result<Computed> {
    let id = "piston.fig5_v1_biased_below_hz";
    let l = locate(samp, "bias_v1", BIASED_LEVEL)?;
    Ok(threshold_claim(
        id,
        spec(id).paper,
        &l,
        &format!("|bias V1| > {}% below", pct(BIASED_LEVEL)),
        &format!("{} {evidence}", model_note()),
    ))
}

fn fig5_v2_biased_below<'a>(spec: &Spec<'a>, samp: &Table, evidence: &str) -> Result<Computed> {
    let id = "piston.fig5_v2_biased_below_hz";
    let l2 = locate(samp, "bias_v2", BIASED_LEVEL)?;
    let band = locate(samp, "bias_v2_band", BIASED_LEVEL)?;
    let all = locate(samp, "bias_v2_all", BIASED_LEVEL)?;
    Ok(threshold_claim(
        id,
        spec(id).paper,
        &l2,
        &format!("|bias V2| > {}% below", pct(BIASED_LEVEL)),
        &format!(
            "With the in-band window the same crossing is {}, with all bins {}. {} {evidence}",
            crossing_text(band.crossing),
            crossing_text(all.crossing),
            model_note()
        ),
    ))
}

/// V1 unbiased: lowest frequency above which every |bias| < 3 standard errors.
fn fig5_v1_unbiased_above<'a>(
    spec: &Spec<'a>,
    samp: &Table,
    c: &Fig5Columns,
    evidence: &str,
) -> Result<Computed> {
    let id = "piston.fig5_v1_unbiased_above_hz";
    let freqs = &c.freqs;
    let (unb, unb_lo) = unbiased_from(freqs, &c.b1, &c.se1);
    let l_1e3 = locate(samp, "bias_v1", V1_SMALL_BIAS_LEVEL)?;
    // The interval: from the last significant point up to the first
    // unbiased one, widened by one frequency step either way.
    let step = freqs[1] / freqs[0];
    let paper = spec(id)
        .paper
        .map_or_else(String::new, |p| format!("; paper {p} Hz"));
    Ok(Computed {
        id,
        finding: Finding::Interval {
            value: unb,
            lo: unb_lo.min(unb / step),
            hi: unb * step,
            resolved: unb.is_finite(),
        },
        note: format!(
            "every |bias V1| is within {SIGNIFICANCE_SIGMAS} standard errors of zero from {unb:.0} Hz up (last significant point {unb_lo:.0} Hz); |bias V1| < {}% above {}{paper}. {} {evidence}",
            pct(V1_SMALL_BIAS_LEVEL),
            crossing_text(l_1e3.crossing),
            model_note()
        ),
    })
}

fn fig5_v2_1e5_above<'a>(
    spec: &Spec<'a>,
    samp: &Table,
    c: &Fig5Columns,
    evidence: &str,
) -> Result<Computed> {
    let id = "piston.fig5_v2_1e-5_above_hz";
    let l5 = locate(samp, "bias_v2", V2_UNBIASED_LEVEL)?;
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
        &format!("|bias V2| < {V2_UNBIASED_LEVEL:e} above"),
        &format!(
            "At {:.0} Hz: bias V2 {:.2e}, bias V1 {:.2e}, scatter V2 {:.2e} vs scatter V1 {:.2e}; V2 is more accurate than V1 (smaller |bias| and scatter) at {better} of {} frequencies. {} {evidence}",
            c.freqs[top], c.b2[top], c.b1[top], c.s2[top], c.s1[top],
            c.freqs.len(),
            model_note()
        ),
    ))
}

/// The lowest frequency from which every |bias| is within 3 standard errors
/// of zero (NaN when the last point is significant; the lowest frequency
/// when none is), and the last significant frequency (the lowest when none).
pub(super) fn unbiased_from(freqs: &[f64], bias: &[f64], se: &[f64]) -> (f64, f64) {
    let last_sig = (0..bias.len())
        .rev()
        .find(|&i| bias[i].abs() > SIGNIFICANCE_SIGMAS * se[i]);
    let unb = match last_sig {
        None => freqs[0],
        Some(i) if i + 1 < freqs.len() => freqs[i + 1],
        Some(_) => f64::NAN,
    };
    (unb, last_sig.map_or(freqs[0], |i| freqs[i]))
}

/// The paper's "below 200 Hz" of the integrating detector (Hz).
const INTEGRATION_LOW_HZ: f64 = 200.0;

/// Integration: below 200 Hz, compare |bias| integrating vs sampled.
fn fig5_integration_low_freq(c: &Fig5Columns) -> Computed {
    let low: Vec<usize> = (0..c.freqs.len())
        .filter(|&i| c.freqs[i] < INTEGRATION_LOW_HZ)
        .collect();
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
    Computed::statement(
        "piston.fig5_integration_low_freq",
        Some(d1),
        grow1 * 2 > low.len() && d1 > d2,
        format!(
            "below {INTEGRATION_LOW_HZ} Hz ({} frequencies): |bias| larger with integration at {grow1} (V1) and {grow2} (V2); mean increase of |bias| {d1:.2e} (V1), {d2:.2e} (V2); at {:.0} Hz scatter V1 {:.3e} integrating vs {:.3e} sampled",
            low.len(), c.freqs[0], c.s1_i[0], c.s1[0]
        ),
    )
}

/// Statistical error with 1000 scans at 300 Hz: scatter / sqrt(1000).
/// The paper's "0.1% or more with fewer than 1000 scans" at 300 Hz: the
/// frequency, the scans, and 0.1% at one significant digit (from 0.05%).
const SCATTER_HZ: f64 = 300.0;
const SCATTER_SCANS: u32 = 1000;
const PAPER_SCATTER_ERROR: f64 = 1e-3;
const SCATTER_ERROR_AT_LEAST: f64 = 0.5 * PAPER_SCATTER_ERROR;

fn scatter_1000_scans(c: &Fig5Columns) -> Computed {
    let freqs = &c.freqs;
    let dist = |i: usize| (freqs[i] / SCATTER_HZ).ln().abs();
    let i300 = (0..freqs.len())
        .min_by(|&a, &b| dist(a).total_cmp(&dist(b)))
        .unwrap_or(0); // freqs is not empty (checked on reading)
    let scans = SCATTER_SCANS as f64;
    let err1000 = c.s1[i300] / scans.sqrt();
    Computed::statement(
        "piston.scatter_1000_scans",
        Some(err1000),
        err1000 >= SCATTER_ERROR_AT_LEAST,
        format!(
            "scatter of V1 at {:.0} Hz on {FIG5_BASELINE_M} m: {:.3e}; over {SCATTER_SCANS} scans the standard error is {err1000:.2e} (V2: {:.2e}), at least {SCATTER_ERROR_AT_LEAST:e} (the paper's {}% at one digit): {}; the paper's figure is V1's",
            freqs[i300],
            c.s1[i300],
            c.s2[i300] / scans.sqrt(),
            pct(PAPER_SCATTER_ERROR),
            err1000 >= SCATTER_ERROR_AT_LEAST
        ),
    )
}
