//! Claims of the differential-piston study (Section "Effect of differential
//! piston", Figs. 4 and 5). Every Monte Carlo number here comes from the same
//! code path as `v2ref piston` and the figure data (`figures::piston`).

use super::{Computed, Find, Status};
use crate::formalism::estimator::BinWindow;
use crate::formalism::observation::{Frequency, Observation};
use crate::formalism::phase::SpectralPhase;
use crate::formalism::source::Source;
use crate::formalism::spectrum::{Band, Spectrum, CPAS_PER_M_PER_INV_UM};
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
/// below `level` for good.
pub fn locate(table: &Table, col: &str, level: f64) -> Located {
    let f = table.column("fringe_hz").unwrap_or_default();
    let y = table.column(col).unwrap_or_default();
    let se = table
        .column(&format!("{col}_stderr"))
        .unwrap_or_else(|| vec![0.0; y.len()]);
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
    Located {
        value: crossing_value(best, &f),
        lo: a.min(b),
        hi: a.max(b),
        crossing: best,
    }
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

fn table<'a>(fig: &'a Figure, name: &str) -> Option<&'a Table> {
    fig.tables.iter().find(|t| t.name == name)
}

fn max_abs(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// The claims this area computes.
pub(super) fn claims(find: &Find<'_>, effort: Effort) -> Vec<Computed> {
    let spec = |id: &str| find(id).expect("id in ledger");
    let mut out = Vec::new();
    let sigma_eff = Spectrum::flat(Band::k()).sigma_eff_per_um();
    let s = 18.0 * sigma_eff * CPAS_PER_M_PER_INV_UM;
    out.push(Computed::numeric(
        spec("piston.baseline_18m_cpas"),
        "piston.baseline_18m_cpas",
        s,
        format!("S = B sigma_eff = 18 m x {sigma_eff:.6} per um = {s:.3} cycles/arcsec (flat 2.0-2.4 um band)"),
    ));

    // Closed forms: r0, coherence time, OPD scanned per coherence time.
    let turb = paper_turbulence();
    let r0_cm = r0_from_seeing_m(1.0, 2.2).map_or(f64::NAN, |r| 100.0 * r);
    out.push(Computed::numeric(
        spec("piston.r0_k_cm"),
        "piston.r0_k_cm",
        r0_cm,
        format!("r0 = lambda / seeing = 2.2 um / 1 arcsec = {r0_cm:.2} cm"),
    ));
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
        let sp = spec(id);
        let opd = f * 2.2 * turb.coherence_time_s();
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
        out.push(c);
    }

    // RMS differential piston at 18 m.
    let rms = PistonSpectrum::new(turb, APERTURE_M, FIG5_BASELINE_M)
        .map(|p| p.rms_um())
        .unwrap_or(f64::NAN);
    let rms_sf =
        differential_piston_variance_from_structure_um2(&turb, APERTURE_M, FIG5_BASELINE_M).sqrt();
    out.push(Computed::with_status(
        "piston.rms_18m_um",
        Some(rms),
        Status::Qualitative,
        format!(
            "sigma_p = {rms:.3} um from the spectral integral, {rms_sf:.3} um from the aperture-averaged structure function (45 cm apertures, r0 = {:.1} cm at 2.2 um, infinite outer scale); consistent with the paper's remark that the saturated piston stays near or below 20 um",
            r0_cm
        ),
    ));

    match fig4(effort) {
        Ok(f4) => out.extend(fig4_claims(&f4)),
        Err(e) => out.push(Computed::with_status(
            "piston.fig4_v1_bias_300hz",
            None,
            Status::Pending,
            format!("Fig. 4 failed: {e}"),
        )),
    }
    match fig5(effort) {
        Ok(f5) => out.extend(fig5_claims(spec, &f5)),
        Err(e) => out.push(Computed::with_status(
            "piston.fig5_v1_biased_below_hz",
            None,
            Status::Pending,
            format!("Fig. 5 failed: {e}"),
        )),
    }
    out.extend(scaling_claims(effort));
    out
}

fn holds(ok: bool) -> Status {
    if ok {
        Status::Qualitative
    } else {
        Status::Differs
    }
}

fn fig4_claims(f4: &Figure) -> Vec<Computed> {
    let mut out = Vec::new();
    let get = |name: &str| table(f4, name);
    let tabs300: Vec<&Table> = ["fig4_43mas_300hz", "fig4_10mas_300hz"]
        .iter()
        .filter_map(|n| get(n))
        .collect();
    let tabs1000: Vec<&Table> = ["fig4_43mas_1000hz", "fig4_10mas_1000hz"]
        .iter()
        .filter_map(|n| get(n))
        .collect();
    let col = |ts: &[&Table], c: &str| -> Vec<f64> {
        ts.iter()
            .flat_map(|t| t.column(c).unwrap_or_default())
            .collect()
    };
    let significant = |ts: &[&Table], c: &str| -> usize {
        let b = col(ts, &format!("bias_{c}"));
        let se = col(ts, &format!("bias_{c}_stderr"));
        b.iter()
            .zip(&se)
            .filter(|(b, s)| b.abs() > SIGNIFICANCE_SIGMAS * **s && **s > 0.0)
            .count()
    };
    let n300 = col(&tabs300, "bias_v1").len();
    let v1_300 = max_abs(&col(&tabs300, "bias_v1"));
    let sig_v1 = significant(&tabs300, "v1");
    // "Below 0.1%": every point consistent with |bias| < 1e-3 at 3 standard errors.
    let below = col(&tabs300, "bias_v1")
        .iter()
        .zip(col(&tabs300, "bias_v1_stderr"))
        .filter(|(b, se)| b.abs() - SIGNIFICANCE_SIGMAS * se < 1e-3)
        .count();
    out.push(Computed::with_status(
        "piston.fig4_v1_bias_300hz",
        Some(v1_300),
        holds(below == n300 && 2 * sig_v1 <= n300),
        format!("at 300 Hz over both disks and all {n300} spatial frequencies: largest |bias V1| {v1_300:.2e} (paper: below 0.1%); {below} points consistent with |bias| < 1e-3 at 3 standard errors; {sig_v1} points differ from zero by more than 3 standard errors (zero-mean noise otherwise)"),
    ));
    let v2_300 = max_abs(&col(&tabs300, "bias_v2"));
    let sig_v2 = significant(&tabs300, "v2");
    out.push(Computed::with_status(
        "piston.fig4_v2_biased_300hz",
        Some(v2_300),
        holds(sig_v2 > sig_v1 && 2 * sig_v2 >= n300 - 2),
        format!("at 300 Hz {sig_v2} of {n300} points have |bias V2| > 3 standard errors (V1: {sig_v1}); largest |bias V2| = {v2_300:.2e}, largest |bias V1| = {v1_300:.2e}"),
    ));
    let b1000 = col(&tabs1000, "bias_v2");
    let under = b1000.iter().filter(|b| b.abs() < 1e-4).count();
    out.push(Computed::with_status(
        "piston.fig4_v2_1000hz",
        Some(under as f64 / b1000.len().max(1) as f64),
        holds(2 * under > b1000.len()),
        format!(
            "at 1000 Hz {under} of {} points have |bias V2| < 1e-4 (largest {:.2e})",
            b1000.len(),
            max_abs(&b1000)
        ),
    ));
    let all: Vec<&Table> = tabs300.iter().chain(&tabs1000).copied().collect();
    let s1 = col(&all, "scatter_v1");
    let s2 = col(&all, "scatter_v2");
    let pairs: Vec<(f64, f64)> = s1
        .iter()
        .zip(&s2)
        .filter(|(a, _)| **a > 0.0)
        .map(|(a, b)| (*a, *b))
        .collect();
    let smaller = pairs.iter().filter(|(a, b)| b < a).count();
    let median_ratio = {
        let mut r: Vec<f64> = pairs.iter().map(|(a, b)| b / a).collect();
        r.sort_by(f64::total_cmp);
        r.get(r.len() / 2).copied().unwrap_or(f64::NAN)
    };
    out.push(Computed::with_status(
        "piston.fig4_v2_scatter_smaller",
        Some(median_ratio),
        holds(smaller == pairs.len()),
        format!("scatter V2 < scatter V1 at {smaller} of {} points with piston; median ratio scatter V2 / scatter V1 = {median_ratio:.3}", pairs.len()),
    ));
    out
}

fn fig5_claims<'a>(spec: impl Fn(&str) -> &'a super::ClaimSpec, f5: &Figure) -> Vec<Computed> {
    let mut out = Vec::new();
    let (Some(samp), Some(integ)) = (table(f5, "fig5_sampled"), table(f5, "fig5_integrating"))
    else {
        return out;
    };
    let freqs = samp.column("fringe_hz").unwrap_or_default();
    let model_note = "Model: Kolmogorov piston PSD with wind along the baseline, packet centred on the scan-mean piston, positive-frequency bins; the paper's Perrin (1997) sequences, its packet centring and bin window are not described, and the V2 thresholds move by large factors with the window (columns _band, _all).";

    let l = locate(samp, "bias_v1", 0.01);
    out.push(threshold_claim(
        "piston.fig5_v1_biased_below_hz",
        spec("piston.fig5_v1_biased_below_hz").paper,
        &l,
        "|bias V1| > 1% below",
        model_note,
    ));
    let l2 = locate(samp, "bias_v2", 0.01);
    let band = locate(samp, "bias_v2_band", 0.01);
    let all = locate(samp, "bias_v2_all", 0.01);
    out.push(threshold_claim(
        "piston.fig5_v2_biased_below_hz",
        spec("piston.fig5_v2_biased_below_hz").paper,
        &l2,
        "|bias V2| > 1% below",
        &format!(
            "With the in-band window the same crossing is {}, with all bins {}. {model_note}",
            crossing_text(band.crossing),
            crossing_text(all.crossing)
        ),
    ));
    // V1 unbiased: lowest frequency above which every |bias| < 3 standard errors.
    let b1 = samp.column("bias_v1").unwrap_or_default();
    let se1 = samp.column("bias_v1_stderr").unwrap_or_default();
    let last_sig = (0..b1.len())
        .rev()
        .find(|&i| b1[i].abs() > SIGNIFICANCE_SIGMAS * se1[i]);
    let unb = match last_sig {
        None => freqs[0],
        Some(i) if i + 1 < freqs.len() => freqs[i + 1],
        Some(_) => f64::NAN,
    };
    let unb_lo = last_sig.map_or(freqs[0], |i| freqs[i]);
    let l_1e3 = locate(samp, "bias_v1", 1e-3);
    let p = spec("piston.fig5_v1_unbiased_above_hz").paper;
    let status = match p {
        Some(p) if unb.is_finite() && p >= unb_lo && p <= unb => Status::Reproduced,
        Some(p) if unb.is_finite() && (unb / p).ln().abs() < (freqs[1] / freqs[0]).ln() => {
            Status::Reproduced
        }
        _ => Status::Differs,
    };
    out.push(Computed::with_status(
        "piston.fig5_v1_unbiased_above_hz",
        Some(unb),
        status,
        format!(
            "every |bias V1| is within 3 standard errors of zero from {unb:.0} Hz up (last significant point {unb_lo:.0} Hz); |bias V1| < 0.1% above {} ; paper 300 Hz. {model_note}",
            crossing_text(l_1e3.crossing)
        ),
    ));
    let l5 = locate(samp, "bias_v2", 1e-5);
    let s1 = samp.column("scatter_v1").unwrap_or_default();
    let s2 = samp.column("scatter_v2").unwrap_or_default();
    let b2 = samp.column("bias_v2").unwrap_or_default();
    let top = freqs.len() - 1;
    out.push(threshold_claim(
        "piston.fig5_v2_1e-5_above_hz",
        spec("piston.fig5_v2_1e-5_above_hz").paper,
        &l5,
        "|bias V2| < 1e-5 above",
        &format!(
            "At {:.0} Hz: bias V2 {:.2e}, bias V1 {:.2e}, scatter V2 {:.2e} vs scatter V1 {:.2e}; V2 is more accurate than V1 (smaller |bias| and scatter) at {} of {} frequencies. {model_note}",
            freqs[top], b2[top], b1[top], s2[top], s1[top],
            (0..freqs.len()).filter(|&i| s2[i] < s1[i] && b2[i].abs() < b1[i].abs().max(3.0 * se1[i])).count(),
            freqs.len()
        ),
    ));
    // Integration: below 200 Hz, compare |bias| integrating vs sampled.
    let bi1 = integ.column("bias_v1").unwrap_or_default();
    let bi2 = integ.column("bias_v2").unwrap_or_default();
    let low: Vec<usize> = (0..freqs.len()).filter(|&i| freqs[i] < 200.0).collect();
    let grow1 = low.iter().filter(|&&i| bi1[i].abs() > b1[i].abs()).count();
    let grow2 = low.iter().filter(|&&i| bi2[i].abs() > b2[i].abs()).count();
    let d1: f64 =
        low.iter().map(|&i| bi1[i].abs() - b1[i].abs()).sum::<f64>() / low.len().max(1) as f64;
    let d2: f64 =
        low.iter().map(|&i| bi2[i].abs() - b2[i].abs()).sum::<f64>() / low.len().max(1) as f64;
    let si1 = integ.column("scatter_v1").unwrap_or_default();
    out.push(Computed::with_status(
        "piston.fig5_integration_low_freq",
        Some(d1),
        holds(grow1 * 2 > low.len() && d1 > d2),
        format!(
            "below 200 Hz ({} frequencies): |bias| larger with integration at {grow1} (V1) and {grow2} (V2); mean increase of |bias| {d1:.2e} (V1), {d2:.2e} (V2); at {:.0} Hz scatter V1 {:.3e} integrating vs {:.3e} sampled",
            low.len(), freqs[0], si1[0], s1[0]
        ),
    ));
    // Statistical error with 1000 scans at 300 Hz: scatter / sqrt(1000).
    let i300 = (0..freqs.len())
        .min_by(|&a, &b| {
            (freqs[a] / 300.0)
                .ln()
                .abs()
                .total_cmp(&(freqs[b] / 300.0).ln().abs())
        })
        .unwrap_or(0);
    let err1000 = s1[i300] / 1000f64.sqrt();
    out.push(Computed::with_status(
        "piston.scatter_1000_scans",
        Some(err1000),
        holds(err1000 >= 0.5e-3),
        format!(
            "scatter of V1 at {:.0} Hz on 18 m: {:.3e}; over 1000 scans the standard error is {err1000:.2e} (V2: {:.2e}) — the paper's 0.1% is the V1 figure",
            freqs[i300],
            s1[i300],
            s2[i300] / 1000f64.sqrt()
        ),
    ));
    out
}

fn scaling_claims(effort: Effort) -> Vec<Computed> {
    let mut out = Vec::new();
    let scans = match effort {
        Effort::Full => 5000,
        Effort::Quick => 600,
    };
    let base = PistonSpectrum::new(paper_turbulence(), APERTURE_M, FIG5_BASELINE_M).ok();
    let run = |turb_wind: f64, f: f64, source: Source, seed: u64| -> Option<PistonRun> {
        let spectrum = base.as_ref()?.with_wind(turb_wind).ok()?;
        let obs = Observation::new(
            Spectrum::flat(Band::k()),
            source,
            Frequency::BaselineM(FIG5_BASELINE_M),
            SpectralPhase::zero(),
        )
        .ok()?;
        simulate(
            &obs,
            &spectrum,
            &ScanSetup::paper(f),
            &[Detector::Sampled],
            &RunSize {
                scans,
                seed,
                threads: 0,
            },
            None,
        )
        .ok()?
        .pop()
    };
    // Wind rescaling: (f, v) = (100 Hz, 10 m/s) against (200 Hz, 20 m/s),
    // independent seeds; the unscaled (100 Hz, 20 m/s) shows the test's power.
    let a = run(10.0, 100.0, Source::Point, FIGURE_SEED ^ 0xA1);
    let b = run(20.0, 200.0, Source::Point, FIGURE_SEED ^ 0xB2);
    let c = run(20.0, 100.0, Source::Point, FIGURE_SEED ^ 0xC3);
    if let (Some(a), Some(b), Some(c)) = (a, b, c) {
        let z = |x: &PistonRun, y: &PistonRun, v2: bool| {
            let (ex, ey) = if v2 {
                (
                    x.window(BinWindow::Positive).v2,
                    y.window(BinWindow::Positive).v2,
                )
            } else {
                (
                    x.window(BinWindow::Positive).v1,
                    y.window(BinWindow::Positive).v1,
                )
            };
            (ex.std - ey.std) / (ex.std_stderr.hypot(ey.std_stderr))
        };
        let zb = |x: &PistonRun, y: &PistonRun| {
            let (ex, ey) = (
                x.window(BinWindow::Positive).v2,
                y.window(BinWindow::Positive).v2,
            );
            (ex.mean - ey.mean) / ex.mean_stderr.hypot(ey.mean_stderr)
        };
        let (z1, z2, zb2) = (z(&a, &b, false), z(&a, &b, true), zb(&a, &b));
        let (n1, n2) = (z(&a, &c, false), z(&a, &c, true));
        let ok = z1.abs() < MC_SIGMAS
            && z2.abs() < MC_SIGMAS
            && zb2.abs() < MC_SIGMAS
            && n1.abs() > MC_SIGMAS;
        out.push(Computed::with_status(
            "piston.wind_rescaling",
            Some(z1),
            holds(ok),
            format!(
                "{scans} scans each, independent seeds: (100 Hz, 10 m/s) vs (200 Hz, 20 m/s) differ by z = {z1:+.2} (scatter V1), {z2:+.2} (scatter V2), {zb2:+.2} (bias V2) standard errors; without rescaling (100 Hz, 20 m/s) the scatter differs by z = {n1:+.1} (V1), {n2:+.1} (V2). In this model the rescaling is exact in distribution: v P(nu) depends on nu and v only through nu/v, and the sample times scale as 1/f, so in units of the fringe period the scans see statistically identical piston sequences"
            ),
        ));
    }
    // Multiplicative: a grey source of visibility 0.5 against the point source,
    // same piston sequence (same seed).
    let p = run(10.0, 150.0, Source::Point, FIGURE_SEED ^ 0xD4);
    let g = run(
        10.0,
        150.0,
        Source::Constant {
            visibility: Complex64::new(0.5, 0.0),
        },
        FIGURE_SEED ^ 0xD4,
    );
    if let (Some(p), Some(g)) = (p, g) {
        let (wp, wg) = (p.window(BinWindow::Positive), g.window(BinWindow::Positive));
        let r = [
            wg.v1.mean / wp.v1.mean,
            wg.v2.mean / wp.v2.mean,
            wg.v1.std / wp.v1.std,
            wg.v2.std / wp.v2.std,
        ];
        let worst = r.iter().fold(0.0_f64, |m, x| m.max((x - 0.5).abs()));
        out.push(Computed::with_status(
            "piston.multiplicative",
            Some(r[1]),
            holds(worst < crate::tolerance::VISIBILITY_SCALING_ABS),
            format!(
                "V = 0.5 (grey) against V = 1, same piston sequences at 150 Hz, {scans} scans: ratios bias V1 {:.9}, bias V2 {:.9}, scatter V1 {:.9}, scatter V2 {:.9} (0.5 expected; the fringe scales with V, so bias and scatter of V do too). For a resolved disk the visibility varies across the band and the scaling holds only approximately (see Fig. 4 tables)",
                r[0], r[1], r[2], r[3]
            ),
        ));
    }
    out
}
