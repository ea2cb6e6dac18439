//! Claims of the Appendix (estimator SNR under detector and photon noise):
//! `appendix.*`, `snr.*`, `sensitivity.*`. Closed forms from
//! [`crate::noise`] and [`crate::noise::window_variance`], checked by the Monte
//! Carlo of [`crate::noise::simulation::simulate_noisy`] /
//! [`crate::noise::simulation::sample_moments`] (seeds fixed below).

use super::{Computed, Find, Status};
use crate::montecarlo::RunningStats;
use crate::noise::simulation::{sample_moments, simulate_noisy, NoisySpec};
use crate::noise::window_variance::{two_sided_band_bins, window_stats};
use crate::noise::{
    self, abcd_detector_variance, appendix_stats, colavita_detector_variance, crossover_samples,
    example_interferogram, moments, published, var_m2, worked_example, ExampleSetup, Formula,
    NoiseModel,
};
use crate::reproduction::cases::Effort;

/// Seed of every Monte Carlo of this provider.
const SEED: u64 = 20_040_712;

struct Sizes {
    scalar: u64,
    interferograms: u64,
}

fn sizes(effort: Effort) -> Sizes {
    match effort {
        Effort::Quick => Sizes {
            scalar: 400_000,
            interferograms: 40_000,
        },
        Effort::Full => Sizes {
            scalar: 4_000_000,
            interferograms: 400_000,
        },
    }
}

/// `x ± se` as "x (± se)" with the deviation from `reference` in standard errors.
fn versus(mc: f64, se: f64, reference: f64) -> String {
    format!(
        "{mc:.6} +- {se:.2e} vs {reference:.6} ({:+.1} se)",
        (mc - reference) / se
    )
}

fn mc_estimators(spec: &NoisySpec, trials: u64, seed: u64) -> Option<(RunningStats, RunningStats)> {
    simulate_noisy(spec, trials, seed, 0, &|_| {})
        .ok()
        .map(|r| (r.v1_sq, r.v2_sq))
}

/// The claims this area computes.
pub(super) fn claims(find: &Find<'_>, effort: Effort) -> Vec<Computed> {
    let sz = sizes(effort);
    let mut out = Vec::new();
    let setup = ExampleSetup::appendix();
    let Ok(ifg) = example_interferogram(&setup) else {
        return out;
    };
    let n = setup.photons;
    let big_n = setup.samples as f64;
    let all: Vec<usize> = (0..setup.samples).collect();
    let sum_m2: f64 = ifg.modulated.iter().map(|m| m * m).sum();
    let m0 = ifg.modulated[0];
    let counts = ifg.mean_counts();
    let detector = NoiseModel {
        read_noise: 0.2 * n,
        photon: false,
    };
    let photon = NoiseModel::photon();

    // --- Expectations (bias-subtracted), all bins, both noises. ---------
    let spec_det = NoisySpec {
        modulated: ifg.modulated.clone(),
        continuum: ifg.continuum.clone(),
        noise: detector,
        bins: all.clone(),
    };
    let spec_phot = NoisySpec {
        noise: photon,
        ..spec_det.clone()
    };
    let det_run = mc_estimators(&spec_det, sz.interferograms, SEED);
    let phot_run = mc_estimators(&spec_phot, sz.interferograms, SEED + 1);
    if let (Some((d1, d2)), Some((p1, p2))) = (det_run, phot_run) {
        let exact_phot = appendix_stats(&ifg.modulated, &ifg.continuum, &photon, Formula::Exact);
        let pub_phot = appendix_stats(&ifg.modulated, &ifg.continuum, &photon, Formula::Published);
        let exact_det = appendix_stats(&ifg.modulated, &ifg.continuum, &detector, Formula::Exact);
        if let (Ok(ep), Ok(pp), Ok(ed)) = (exact_phot, pub_phot, exact_det) {
            let sig1 = big_n * sum_m2;
            let sig2 = big_n * big_n * m0 * m0;
            let r_det1 = (d1.mean - ed.bias_v1_sq) / sig1;
            let r_phot1 = (p1.mean - ep.bias_v1_sq) / sig1;
            out.push(Computed::with_status(
                "appendix.expectation_v1",
                Some(r_phot1),
                Status::Qualitative,
                format!(
                    "128-sample Appendix interferogram, {t} trials each: (mean V1^2_raw - exact bias) / (N sum m_i^2) = {} (detector noise, bias N^2 s^2) and {} (photon noise, bias N sum n_i); with the printed photon bias N sum m_i the mean exceeds N sum m_i^2 by N sum c_i = {:.4e}, i.e. ratio {:.4}. Exact: N sum m_i^2 holds once the right bias is removed",
                    versus(r_det1, d1.stderr_mean() / sig1, 1.0),
                    versus(r_phot1, p1.stderr_mean() / sig1, 1.0),
                    pp.expectation_v1_sq - sig1,
                    (p1.mean - pp.bias_v1_sq) / sig1,
                    t = sz.interferograms
                ),
            ));
            // V2 needs sample 0 on the white-light fringe: the same
            // interferogram read half a sample off the fringe.
            let shifted = half_sample_m0();
            let r_phot2 = (p2.mean - ep.bias_v2_sq) / sig2;
            let r_det2 = (d2.mean - ed.bias_v2_sq) / sig2;
            out.push(Computed::with_status(
                "appendix.expectation_v2",
                Some(r_phot2),
                Status::Qualitative,
                format!(
                    "(mean V2^2_raw - exact bias) / (N^2 m_0^2) = {} (detector) and {} (photon, bias N^2 n_0; the printed N^2 m_0 leaves N^2 c_0 = {:.4e}). Sample 0 half a sample (0.25 um) off the white-light fringe gives m_0/n = {:.4}, so V2^2 reads {:.4} of its value: V2 needs sample 0 on the fringe",
                    versus(r_det2, d2.stderr_mean() / sig2, 1.0),
                    versus(r_phot2, p2.stderr_mean() / sig2, 1.0),
                    pp.expectation_v2_sq - sig2,
                    shifted,
                    shifted * shifted
                ),
            ));
            // Photon bias terms.
            let rel_pub = (p1.mean - pp.bias_v1_sq - sig1) / p1.stderr_mean();
            out.push(Computed {
                id: "appendix.photon_bias_terms",
                value: Some(ep.bias_v1_sq / (big_n * big_n)),
                status: Status::Erratum,
                note: format!(
                    "the photon-noise power in V1^2_raw is N sum n_i (n_i = c_i + m_i, the mean total count), not N sum m_i; in V2^2_raw N^2 n_0, not N^2 m_0. Monte Carlo ({} interferograms, photon noise, Appendix case): mean V1^2_raw - N sum m_i^2 = {} vs exact N sum n_i; the printed N sum m_i = {:.4e} misses by {:.0} se. V2: mean - N^2 m_0^2 = {} vs exact N^2 n_0. value = sum n_i / N (mean count per sample) = {:.4}; published sum m_i / N = {:.4}",
                    sz.interferograms,
                    versus(p1.mean - sig1, p1.stderr_mean(), ep.bias_v1_sq),
                    pp.bias_v1_sq,
                    rel_pub,
                    versus(p2.mean - sig2, p2.stderr_mean(), ep.bias_v2_sq),
                    ep.bias_v1_sq / (big_n * big_n),
                    pp.bias_v1_sq / (big_n * big_n),
                ),
                published: Some(pp.bias_v1_sq / (big_n * big_n)),
                exact: Some(ep.bias_v1_sq / (big_n * big_n)),
            });
            // Detector variances.
            let rv1 = d1.variance() / ed.var_v1_sq;
            let rv2 = d2.variance() / ed.var_v2_sq;
            out.push(Computed::with_status(
                "appendix.detector_variances",
                Some(rv1),
                Status::Qualitative,
                format!(
                    "printed and exact agree; Monte Carlo ({} interferograms, s = 0.2 n): var V1^2 / (2 N^2 s^2 [2 sum m^2 + N s^2]) = {}, var V2^2 / (2 N^4 s^2 [2 m_0^2 + s^2]) = {}",
                    sz.interferograms,
                    versus(rv1, d1.stderr_variance() / ed.var_v1_sq, 1.0),
                    versus(rv2, d2.stderr_variance() / ed.var_v2_sq, 1.0),
                ),
            ));
            // Photon variances.
            let pv1 = p1.variance();
            let pv2 = p2.variance();
            out.push(Computed {
                id: "appendix.photon_variances",
                value: Some(ep.var_v1_sq),
                status: Status::Erratum,
                note: format!(
                    "printed N^2 sum n_i(4n_i^2+6n_i+1) is N^2 sum var(I_i^2) of the total count; the estimator uses M = I - c: var V1^2 = N^2 sum (4 m_i^2 n_i + 4 m_i n_i + 2 n_i^2 + n_i), var V2^2 = N^4 (4 m_0^2 n_0 + 4 m_0 n_0 + 2 n_0^2 + n_0). Monte Carlo ({} interferograms, Appendix case, n = 10): var V1^2 = {} (exact), printed {:.4e} ({:.0} se away); var V2^2 = {} (exact), printed {:.4e} ({:.0} se away)",
                    sz.interferograms,
                    versus(pv1, p1.stderr_variance(), ep.var_v1_sq),
                    pp.var_v1_sq,
                    (pv1 - pp.var_v1_sq) / p1.stderr_variance(),
                    versus(pv2, p2.stderr_variance(), ep.var_v2_sq),
                    pp.var_v2_sq,
                    (pv2 - pp.var_v2_sq) / p2.stderr_variance(),
                ),
                published: Some(pp.var_v1_sq),
                exact: Some(ep.var_v1_sq),
            });
        }
    }

    // --- Per-sample moments. -------------------------------------------
    let (m, s) = (10.0, 2.0);
    let gauss = NoiseModel {
        read_noise: s,
        photon: false,
    };
    if let Ok(mc) = sample_moments(m, 0.0, &gauss, sz.scalar, SEED + 2, 0) {
        let p4 = published::gaussian_m4(m, s);
        let p2 = published::gaussian_m2(m, s);
        let e = moments(&gauss, m, 0.0);
        out.push(Computed::with_status(
            "appendix.gaussian_moments",
            Some(mc[3].mean / p4),
            Status::Qualitative,
            format!(
                "printed forms equal the exact cumulant forms ({p4} = {}, {p2} = {}); Monte Carlo m = {m}, s = {s}, {} draws: <M^4> = {}, <M^2> = {}",
                e.raw[4],
                e.raw[2],
                sz.scalar,
                versus(mc[3].mean, mc[3].stderr_mean(), p4),
                versus(mc[1].mean, mc[1].stderr_mean(), p2),
            ),
        ));
    }
    // Photon: c = 10, m = 10, n = 20 (sample 0 of the Appendix case).
    let (mp, cp) = (n, n);
    let nn = mp + cp;
    if let Ok(mc) = sample_moments(mp, cp, &photon, sz.scalar, SEED + 3, 0) {
        let e = moments(&photon, mp, nn);
        let p4 = published::photon_m4(nn);
        let p2 = published::photon_m2(nn);
        out.push(Computed {
            id: "appendix.photon_moments",
            value: Some(e.raw[4]),
            status: Status::Erratum,
            note: format!(
                "the printed n^4+6n^3+7n^2+n and n^2+n are the raw moments of the Poisson count I (mean n), not of M = I - c. Exact for M = m + e (cumulants of e all equal n): <M^2> = m^2 + n, <M^4> = m^4 + 6m^2 n + 4mn + n + 3n^2. At m = c = {mp} (n = {nn}), {} draws: <M^4> = {} (printed {p4}, {:.0} se away); <M^2> = {} (printed {p2})",
                sz.scalar,
                versus(mc[3].mean, mc[3].stderr_mean(), e.raw[4]),
                (mc[3].mean - p4) / mc[3].stderr_mean(),
                versus(mc[1].mean, mc[1].stderr_mean(), e.raw[2]),
            ),
            published: Some(p4),
            exact: Some(e.raw[4]),
        });
    }
    // Combined noise: var(M^2) with both vs the sum of each alone.
    let both = NoiseModel {
        read_noise: s,
        photon: true,
    };
    if let Ok(mc) = sample_moments(mp, cp, &both, sz.scalar, SEED + 4, 0) {
        let exact = var_m2(&both, mp, nn);
        let sum = var_m2(&gauss, mp, nn) + var_m2(&photon, mp, nn);
        // var(M^2) by Monte Carlo, from the moments of M^2 (sample 2 of mc).
        let v = mc[1].variance();
        let se = mc[1].stderr_variance();
        out.push(Computed {
            id: "snr.combined_noise_variance",
            value: Some(exact),
            status: Status::Erratum,
            note: format!(
                "var(M^2) with both noises is not the sum of the two: the 2 kappa2^2 term of var(M^2) = 4m^2 k2 + 4m k3 + k4 + 2 k2^2 with k2 = s^2 + n adds the cross term 4 s^2 n. At m = c = {mp}, n = {nn}, s = {s}: exact {exact}, sum of the parts {sum}; Monte Carlo ({} draws) var(M^2) = {} ({:.1} se from the sum). The paper's photon part is itself the erratum of appendix.photon_variances",
                sz.scalar,
                versus(v, se, exact),
                (v - sum) / se,
            ),
            published: Some(sum),
            exact: Some(exact),
        });
    }

    // --- Window factor. -------------------------------------------------
    let obs = noise::example_observation();
    let (lo, hi) = obs.spectrum.support();
    let factor = noise::paper_window_factor(setup.dx_um, hi - lo);
    let window2 = two_sided_band_bins(setup.samples, setup.dx_um, lo, hi);
    let window1 = crate::formalism::estimator::band_bins(setup.samples, setup.dx_um, lo, hi);
    if let (Ok(w_all), Ok(w2), Ok(w1)) = (
        window_stats(&ifg.modulated, &counts, &detector, &all),
        window_stats(&ifg.modulated, &counts, &detector, &window2),
        window_stats(&ifg.modulated, &counts, &detector, &window1),
    ) {
        let ratio1 = w_all.var_v1_sq / w2.var_v1_sq;
        let ratio2 = w_all.var_v2_sq / w2.var_v2_sq;
        let spec_w = NoisySpec {
            bins: window2.clone(),
            ..spec_det.clone()
        };
        let mc_note = match mc_estimators(&spec_w, sz.interferograms, SEED + 5) {
            Some((a, b)) => format!(
                "; Monte Carlo of the two-sided window ({} interferograms): var V1^2 = {}, var V2^2 = {}",
                sz.interferograms,
                versus(a.variance(), a.stderr_variance(), w2.var_v1_sq),
                versus(b.variance(), b.stderr_variance(), w2.var_v2_sq)
            ),
            None => String::new(),
        };
        out.push(Computed {
            id: "appendix.window_variance_factor",
            value: Some(ratio1),
            status: Status::Erratum,
            note: format!(
                "exact quadratic-form variances, detector case (s = 0.2 n), 128 samples: the band covers {} positive bins ({} with their mirror images, which a window must keep to keep the whole fringe of a real signal). Paper factor (1/dx)/delta-sigma_0 = {:.2}. Exact var(all bins)/var(two-sided band window): V1^2 {ratio1:.3}, V2^2 {ratio2:.3} (the white-noise argument divides only the noise x noise term; the signal x noise term of V1^2 lies inside the window and stays). SNR gain: V1 {:.3}, V2 {:.3} vs the paper's sqrt = {factor:.3}; positive-band-only window: SNR1 {:.3}, SNR2 {:.3} (all bins: {:.3}, {:.3}){mc_note}",
                window1.len(),
                window2.len(),
                factor * factor,
                w2.snr1 / w_all.snr1,
                w2.snr2 / w_all.snr2,
                w1.snr1,
                w1.snr2,
                w_all.snr1,
                w_all.snr2,
            ),
            published: Some(factor * factor),
            exact: Some(ratio1),
        });
    }

    // --- The worked examples. --------------------------------------------
    let variants = [
        ("centred scan, sampling detector", setup),
        (
            "centred, integrating",
            ExampleSetup {
                integrating: true,
                ..setup
            },
        ),
        (
            "zero-start scan, sampling",
            ExampleSetup {
                zero_start: true,
                ..setup
            },
        ),
        (
            "zero-start, integrating",
            ExampleSetup {
                zero_start: true,
                integrating: true,
                ..setup
            },
        ),
    ];
    let table: Vec<String> = variants
        .iter()
        .filter_map(|(name, v)| {
            worked_example(v, Formula::Published).ok().map(|w| {
                format!(
                    "{name}: sum m^2/n^2 = {:.3}, SNR {:.3}/{:.3} (detector), {:.3}/{:.3} (photon)",
                    w.sum_m2_over_n2, w.detector.0, w.detector.1, w.photon.0, w.photon.1
                )
            })
        })
        .collect();
    let table = table.join("; ");
    if let (Ok(p), Ok(e)) = (
        worked_example(&setup, Formula::Published),
        worked_example(&setup, Formula::Exact),
    ) {
        let spec = |id: &str| find(id);
        let why = format!(
            "project interferogram: 128 samples, dx = 0.5 um, flat 2.0-2.4 um band (flat in wavenumber), centred scan, sampling detector, c = n, m_0 = n (Interferogram::synthesize). Alternatives with the printed formulas: {table}. sum m^2/n^2 = 11.41 would give both 7.63 and 1.33: the paper's interferogram carried 1.4 % less fringe power than ours"
        );
        if let Some(sp) = spec("snr.detector_v1") {
            out.push(Computed::numeric(
                sp,
                "snr.detector_v1",
                p.detector.0,
                format!(
                    "SNR1 (all bins, without the window factor) = {:.4}; printed and exact formulas agree for detector noise. {why}",
                    p.detector.0
                ),
            ));
        }
        if let Some(sp) = spec("snr.detector_v2") {
            out.push(Computed::numeric(
                sp,
                "snr.detector_v2",
                p.detector.1,
                format!(
                    "SNR2 = m_0^2 / sqrt(2 s^2 (2 m_0^2 + s^2)) = 1/sqrt(0.08 * 2.04) = {:.4}, independent of the interferogram's shape",
                    p.detector.1
                ),
            ));
        }
        out.push(Computed {
            id: "snr.photon_v1",
            value: Some(e.photon.0),
            status: Status::Erratum,
            note: format!(
                "with the printed photon variance n_i(4n_i^2+6n_i+1) our interferogram gives {:.4} (paper 1.33; the 1.4 % fringe-power difference of snr.detector_v1); with the exact var(M_i^2) = 4m_i^2 n_i + 4 m_i n_i + 2n_i^2 + n_i (confirmed by Monte Carlo, appendix.photon_variances) SNR1 = {:.4}",
                p.photon.0, e.photon.0
            ),
            published: Some(p.photon.0),
            exact: Some(e.photon.0),
        });
        out.push(Computed {
            id: "snr.photon_v2",
            value: Some(e.photon.1),
            status: Status::Erratum,
            note: format!(
                "printed formula with m_0 = 10, n_0 = c + m_0 = 20: 100/sqrt(20*1721) = {:.4} (reproduces 0.54); exact var(M_0^2) = 4m_0^2 n_0 + 4m_0 n_0 + 2n_0^2 + n_0 = 9620 gives SNR2 = {:.4}",
                p.photon.1, e.photon.1
            ),
            published: Some(p.photon.1),
            exact: Some(e.photon.1),
        });
        // V1 vs V2.
        out.push(Computed::with_status(
            "sensitivity.v1_over_v2",
            Some(p.detector.0 / p.detector.1),
            Status::Qualitative,
            format!(
                "SNR1/SNR2 in the Appendix case, all bins: detector noise {:.2}; photon noise {:.2} with the printed variances, {:.2} with the exact ones. Within 2-3 for the printed formulas; exact photon noise gives 4.0",
                p.detector.0 / p.detector.1,
                p.photon.0 / p.photon.1,
                e.photon.0 / e.photon.1
            ),
        ));
        // Crossover.
        let cross = |noise: &NoiseModel, f: Formula| {
            crossover_samples(&ifg.modulated, &ifg.continuum, noise, f)
                .ok()
                .flatten()
        };
        let cd = cross(&detector, Formula::Exact);
        let cpp = cross(&photon, Formula::Published);
        let cpe = cross(&photon, Formula::Exact);
        let fmt = |c: Option<usize>| c.map_or("never".to_owned(), |v| v.to_string());
        out.push(Computed::with_status(
            "snr.crossover_samples",
            cd.map(|v| v as f64),
            Status::Qualitative,
            format!(
                "the Appendix fringe packet read with more samples (no fringe, continuum c = n) until SNR1 <= SNR2: detector noise s = 0.2 n at N = {}; photon noise n = 10 at N = {} (printed variances) or {} (exact). 'a few thousand' holds for detector noise and for the exact photon variances; the printed photon variances would put it below a thousand",
                fmt(cd),
                fmt(cpp),
                fmt(cpe)
            ),
        ));
    }

    // --- ABCD (Colavita). ---------------------------------------------------
    let (total, vis, sig) = (40.0, 1.0, 2.0);
    let abcd: Vec<f64> = (0..4)
        .map(|k| total / 4.0 * vis * (0.3 + k as f64 * std::f64::consts::FRAC_PI_2).cos())
        .collect();
    let spec_abcd = NoisySpec {
        modulated: abcd,
        continuum: vec![total / 4.0; 4],
        noise: NoiseModel {
            read_noise: sig,
            photon: false,
        },
        bins: vec![1],
    };
    if let Some((z, _)) = mc_estimators(&spec_abcd, sz.scalar, SEED + 6) {
        let exact = abcd_detector_variance(total, vis, sig);
        let colavita = colavita_detector_variance(sig);
        out.push(Computed::with_status(
            "snr.colavita_correction",
            Some(z.variance() / exact),
            Status::Qualitative,
            format!(
                "ABCD estimator (A-C)^2 + (B-D)^2 = |B_1|^2 of the 4-sample DFT, <N> = {total} photons, V = {vis}, s = {sig}, sampling detector: Monte Carlo ({} trials) variance {}; Colavita's 16 s^4 = {colavita} alone is {:.0} se away. The paper's extra term is right",
                sz.scalar,
                versus(z.variance(), z.stderr_variance(), exact),
                (z.variance() - colavita) / z.stderr_variance()
            ),
        ));
    }
    out
}

/// m_0/n when sample 0 sits half a sample (δx/2) off the white-light fringe.
fn half_sample_m0() -> f64 {
    let setup = ExampleSetup::appendix();
    let obs = noise::example_observation();
    crate::formalism::interferogram::SpectralNodes::new(&obs, setup.dx_um, None)
        .fringe(0.5 * setup.dx_um)
}
