//! Claims of the Appendix (estimator SNR under detector and photon noise):
//! `appendix.*`, `snr.*`, `sensitivity.*`. Closed forms from
//! [`crate::noise`] and [`crate::noise::window_variance`], checked by the Monte
//! Carlo of [`crate::noise::simulation::simulate_noisy`] /
//! [`crate::noise::simulation::sample_moments`] (seeds fixed below).
//!
//! One step per group of claims: the all-bins estimators of the Appendix
//! case (one Monte Carlo run per noise, read by five claims), the moments of
//! one sample, the windowed variance, the worked examples' SNRs, the
//! crossover, and the ABCD variance. A step whose computation fails yields
//! [`Computed::failed`] for each of its claims.

use super::{settle, Check, Computed, Find};
use crate::cases::{appendix_setup, Effort, APPENDIX_READ_NOISE_PER_PHOTON, APPENDIX_SEED};
use crate::formalism::interferogram::Interferogram;
use crate::montecarlo::RunningStats;
use crate::noise::simulation::{sample_moments, simulate_noisy, NoisySpec};
use crate::noise::window_variance::{two_sided_band_bins, window_stats};
use crate::noise::{
    self, abcd_detector_variance, appendix_stats, colavita_detector_variance, crossover_samples,
    example_interferogram, moments, published, var_m2, worked_example, ExampleSetup, Formula,
    NoiseModel,
};
use crate::tolerance::IDENTITY_REL;
use crate::Result;

/// The seed of the Monte Carlo that computes `what` (a claim id or group):
/// derived from the Appendix base seed by the crate's one rule.
fn seed(what: &str) -> u64 {
    crate::montecarlo::derive_seed(APPENDIX_SEED, what, &[])
}

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

/// A Monte Carlo check: `estimate ± stderr`.
fn mc(estimate: f64, stderr: f64) -> Check {
    Check::MonteCarlo { estimate, stderr }
}

/// "holds" or "does not hold", for the notes' conclusions.
fn holds_text(holds: bool) -> &'static str {
    if holds {
        "holds"
    } else {
        "does not hold"
    }
}

/// V1² and V2² of `trials` noisy interferograms of `spec`.
fn mc_estimators(spec: &NoisySpec, trials: u64, seed: u64) -> Result<(RunningStats, RunningStats)> {
    simulate_noisy(spec, trials, seed, 0, &|_| {}).map(|r| (r.v1_sq, r.v2_sq))
}

/// The claims of the all-bins estimators (one Monte Carlo per noise).
const ALL_BINS_IDS: [&str; 5] = [
    "appendix.expectation_v1",
    "appendix.expectation_v2",
    "appendix.photon_bias_terms",
    "appendix.detector_variances",
    "appendix.photon_variances",
];
/// The claims of the moments of one sample.
const SAMPLE_IDS: [&str; 3] = [
    "appendix.gaussian_moments",
    "appendix.photon_moments",
    "snr.combined_noise_variance",
];
/// The claim of the windowed variance.
const WINDOW_IDS: [&str; 1] = ["appendix.window_variance_factor"];
/// The claims of the worked examples' SNRs.
const WORKED_IDS: [&str; 5] = [
    "snr.detector_v1",
    "snr.detector_v2",
    "snr.photon_v1",
    "snr.photon_v2",
    "sensitivity.v1_over_v2",
];
/// The claim of the crossover of SNR_1 and SNR_2.
const CROSSOVER_IDS: [&str; 1] = ["snr.crossover_samples"];
/// The claim of the ABCD variance.
const ABCD_IDS: [&str; 1] = ["snr.colavita_correction"];

/// The Appendix case every step reads: the setup, its noise-free
/// interferogram and the two noises of the worked examples.
struct Case {
    setup: ExampleSetup,
    ifg: Interferogram,
    /// Detector noise σ_det = 0.2 n.
    detector: NoiseModel,
    /// Photon noise alone.
    photon: NoiseModel,
}

impl Case {
    fn new(setup: ExampleSetup) -> Result<Case> {
        Ok(Case {
            setup,
            ifg: example_interferogram(&setup)?,
            detector: NoiseModel {
                read_noise: APPENDIX_READ_NOISE_PER_PHOTON * setup.photons,
                photon: false,
            },
            photon: NoiseModel::photon(),
        })
    }

    /// All N bins.
    fn all_bins(&self) -> Vec<usize> {
        (0..self.setup.samples).collect()
    }

    /// The noisy-interferogram spec of the case with `noise` over all bins.
    fn spec(&self, noise: NoiseModel) -> NoisySpec {
        NoisySpec {
            modulated: self.ifg.modulated.clone(),
            continuum: self.ifg.continuum.clone(),
            noise,
            bins: self.all_bins(),
        }
    }
}

/// The claims this area computes.
pub(super) fn claims(find: &Find<'_>, effort: Effort) -> Vec<Computed> {
    claims_for(find, effort, appendix_setup())
}

/// One step: the claims of one group, computed from the case.
type Step = fn(&Find<'_>, &Case, &Sizes) -> Result<Vec<Computed>>;

/// The claims for the Appendix case `setup` (the paper's in [`claims`]);
/// if the case itself cannot be built, every claim that reads it fails.
fn claims_for(find: &Find<'_>, effort: Effort, setup: ExampleSetup) -> Vec<Computed> {
    let sz = sizes(effort);
    let case = Case::new(setup);
    let steps: [(&[&'static str], Step); 5] = [
        (&ALL_BINS_IDS, all_bins_claims),
        (&SAMPLE_IDS, sample_moment_claims),
        (&WINDOW_IDS, window_claims),
        (&WORKED_IDS, worked_example_claims),
        (&CROSSOVER_IDS, crossover_claims),
    ];
    let mut out = Vec::new();
    for (ids, step) in steps {
        let computed = case.as_ref().map_err(Clone::clone);
        out.extend(settle(ids, computed.and_then(|c| step(find, c, &sz))));
    }
    out.extend(settle(&ABCD_IDS, abcd_claims(&sz)));
    out
}

/// The all-bins Monte Carlo of the Appendix case (one run per noise) and
/// the closed forms its five claims compare it with.
struct AllBins {
    /// V1², V2² under detector noise.
    det: (RunningStats, RunningStats),
    /// V1², V2² under photon noise.
    phot: (RunningStats, RunningStats),
    /// Exact photon-noise closed forms.
    ep: noise::AppendixStats,
    /// Printed photon-noise closed forms.
    pp: noise::AppendixStats,
    /// Exact detector-noise closed forms.
    ed: noise::AppendixStats,
    /// Printed detector-noise closed forms.
    pd: noise::AppendixStats,
    /// N Σ m_i² and N² m_0².
    sig: (f64, f64),
    /// N.
    big_n: f64,
    /// Interferograms per run.
    trials: u64,
}

impl AllBins {
    fn run(case: &Case, sz: &Sizes) -> Result<AllBins> {
        let ifg = &case.ifg;
        let det = mc_estimators(
            &case.spec(case.detector),
            sz.interferograms,
            seed("appendix.all_bins.detector"),
        )?;
        let phot = mc_estimators(
            &case.spec(case.photon),
            sz.interferograms,
            seed("appendix.all_bins.photon"),
        )?;
        let stats = |noise: &NoiseModel, f: Formula| {
            appendix_stats(&ifg.modulated, &ifg.continuum, noise, f)
        };
        let big_n = case.setup.samples as f64;
        let sum_m2: f64 = ifg.modulated.iter().map(|m| m * m).sum();
        let m0 = ifg.modulated[0];
        Ok(AllBins {
            det,
            phot,
            ep: stats(&case.photon, Formula::Exact)?,
            pp: stats(&case.photon, Formula::Published)?,
            ed: stats(&case.detector, Formula::Exact)?,
            pd: stats(&case.detector, Formula::Published)?,
            sig: (big_n * sum_m2, big_n * big_n * m0 * m0),
            big_n,
            trials: sz.interferograms,
        })
    }
}

/// Expectations, photon bias terms and variances of V1² and V2² over all
/// bins: `appendix.expectation_*`, `appendix.photon_bias_terms`,
/// `appendix.*_variances`.
fn all_bins_claims(_find: &Find<'_>, case: &Case, sz: &Sizes) -> Result<Vec<Computed>> {
    let a = AllBins::run(case, sz)?;
    Ok(vec![
        expectation_v1_claim(&a),
        expectation_v2_claim(&a, case),
        photon_bias_claim(&a),
        detector_variance_claim(&a),
        photon_variance_claim(&a, case),
    ])
}

fn expectation_v1_claim(a: &AllBins) -> Computed {
    let ((d1, _), (p1, _)) = (&a.det, &a.phot);
    let (ed, ep, pp, sig1) = (&a.ed, &a.ep, &a.pp, a.sig.0);
    let r_det1 = (d1.mean - ed.bias_v1_sq) / sig1;
    let r_phot1 = (p1.mean - ep.bias_v1_sq) / sig1;
    // The predicate: both means, exact bias removed, are N Σ m_i².
    let holds = mc(r_det1, d1.stderr_mean() / sig1).confirms(1.0)
        && mc(r_phot1, p1.stderr_mean() / sig1).confirms(1.0);
    Computed::statement(
        "appendix.expectation_v1",
        Some(r_phot1),
        holds,
        format!(
                    "{n}-sample Appendix interferogram, {t} trials each: (mean V1^2_raw - exact bias) / (N sum m_i^2) = {} (detector noise, bias N^2 s^2) and {} (photon noise, bias N sum n_i); with the printed photon bias N sum m_i the mean exceeds N sum m_i^2 by N sum c_i = {:.4e}, i.e. ratio {:.4}. <V1^2> = N sum m_i^2 once the right bias is removed {}",
                    versus(r_det1, d1.stderr_mean() / sig1, 1.0),
                    versus(r_phot1, p1.stderr_mean() / sig1, 1.0),
                    pp.expectation_v1_sq - sig1,
                    (p1.mean - pp.bias_v1_sq) / sig1,
                    holds_text(holds),
                    n = a.big_n,
                    t = a.trials
                ),
    )
}

fn expectation_v2_claim(a: &AllBins, case: &Case) -> Computed {
    let ((_, d2), (_, p2)) = (&a.det, &a.phot);
    let (ed, ep, pp, sig2) = (&a.ed, &a.ep, &a.pp, a.sig.1);
    // V2 needs sample 0 on the white-light fringe: the same
    // interferogram read half a sample off the fringe.
    let shifted = half_sample_m0(&case.setup);
    let r_phot2 = (p2.mean - ep.bias_v2_sq) / sig2;
    let r_det2 = (d2.mean - ed.bias_v2_sq) / sig2;
    // The predicate: both means, exact bias removed, are N² m_0², and
    // half a sample off the fringe loses V2² (m_0 < n).
    let holds = mc(r_det2, d2.stderr_mean() / sig2).confirms(1.0)
        && mc(r_phot2, p2.stderr_mean() / sig2).confirms(1.0)
        && shifted < 1.0;
    Computed::statement(
        "appendix.expectation_v2",
        Some(r_phot2),
        holds,
        format!(
                    "(mean V2^2_raw - exact bias) / (N^2 m_0^2) = {} (detector) and {} (photon, bias N^2 n_0; the printed N^2 m_0 leaves N^2 c_0 = {:.4e}). Sample 0 half a sample ({} um) off the white-light fringe gives m_0/n = {:.4}, so V2^2 reads {:.4} of its value: V2 needs sample 0 on the fringe",
                    versus(r_det2, d2.stderr_mean() / sig2, 1.0),
                    versus(r_phot2, p2.stderr_mean() / sig2, 1.0),
                    pp.expectation_v2_sq - sig2,
                    0.5 * case.setup.dx_um,
                    shifted,
                    shifted * shifted
                ),
    )
}

fn photon_bias_claim(a: &AllBins) -> Computed {
    let (p1, p2) = &a.phot;
    let (ep, pp, big_n) = (&a.ep, &a.pp, a.big_n);
    let (sig1, sig2) = a.sig;
    let rel_pub = (p1.mean - pp.bias_v1_sq - sig1) / p1.stderr_mean();
    // In the claim's unit (mean count per sample): bias / N².
    let per_sample = big_n * big_n;
    Computed::formula(
        "appendix.photon_bias_terms",
        ep.bias_v1_sq / per_sample,
        pp.bias_v1_sq / per_sample,
        format!(
                    "the photon-noise power in V1^2_raw is N sum n_i (n_i = c_i + m_i, the mean total count), not N sum m_i; in V2^2_raw N^2 n_0, not N^2 m_0. Monte Carlo ({} interferograms, photon noise, Appendix case): mean V1^2_raw - N sum m_i^2 = {} vs exact N sum n_i; the printed N sum m_i = {:.4e} misses by {:.0} se. V2: mean - N^2 m_0^2 = {} vs exact N^2 n_0. value = sum n_i / N (mean count per sample) = {:.4}; published sum m_i / N = {:.4}",
            a.trials,
                    versus(p1.mean - sig1, p1.stderr_mean(), ep.bias_v1_sq),
                    pp.bias_v1_sq,
                    rel_pub,
                    versus(p2.mean - sig2, p2.stderr_mean(), ep.bias_v2_sq),
                    ep.bias_v1_sq / (big_n * big_n),
                    pp.bias_v1_sq / (big_n * big_n),
                ),
    )
    .checked(mc((p1.mean - sig1) / per_sample, p1.stderr_mean() / per_sample))
}

fn detector_variance_claim(a: &AllBins) -> Computed {
    let ((d1, d2), ed) = (&a.det, &a.ed);
    let rv1 = d1.variance() / ed.var_v1_sq;
    let rv2 = d2.variance() / ed.var_v2_sq;
    let (pd, same) = (&a.pd, |x: f64, y: f64| {
        (x - y).abs() <= IDENTITY_REL * y.abs()
    });
    // The predicate: the printed forms are the exact ones, and the Monte
    // Carlo confirms them.
    let printed_exact = same(pd.var_v1_sq, ed.var_v1_sq) && same(pd.var_v2_sq, ed.var_v2_sq);
    let holds = printed_exact
        && mc(rv1, d1.stderr_variance() / ed.var_v1_sq).confirms(1.0)
        && mc(rv2, d2.stderr_variance() / ed.var_v2_sq).confirms(1.0);
    Computed::statement(
        "appendix.detector_variances",
        Some(rv1),
        holds,
        format!(
                    "printed forms equal to the exact ones: {printed_exact}; Monte Carlo ({} interferograms, s = {APPENDIX_READ_NOISE_PER_PHOTON} n): var V1^2 / (2 N^2 s^2 [2 sum m^2 + N s^2]) = {}, var V2^2 / (2 N^4 s^2 [2 m_0^2 + s^2]) = {}",
            a.trials,
                    versus(rv1, d1.stderr_variance() / ed.var_v1_sq, 1.0),
                    versus(rv2, d2.stderr_variance() / ed.var_v2_sq, 1.0),
                ),
    )
}

fn photon_variance_claim(a: &AllBins, case: &Case) -> Computed {
    let ((p1, p2), ep, pp) = (&a.phot, &a.ep, &a.pp);
    let pv1 = p1.variance();
    let pv2 = p2.variance();
    Computed::formula(
        "appendix.photon_variances",
        ep.var_v1_sq,
        pp.var_v1_sq,
        format!(
                    "printed N^2 sum n_i(4n_i^2+6n_i+1) is N^2 sum var(I_i^2) of the total count; the estimator uses M = I - c: var V1^2 = N^2 sum (4 m_i^2 n_i + 4 m_i n_i + 2 n_i^2 + n_i), var V2^2 = N^4 (4 m_0^2 n_0 + 4 m_0 n_0 + 2 n_0^2 + n_0). Monte Carlo ({} interferograms, Appendix case, n = {}): var V1^2 = {} (exact), printed {:.4e} ({:.0} se away); var V2^2 = {} (exact), printed {:.4e} ({:.0} se away)",
            a.trials,
            case.setup.photons,
                    versus(pv1, p1.stderr_variance(), ep.var_v1_sq),
                    pp.var_v1_sq,
                    (pv1 - pp.var_v1_sq) / p1.stderr_variance(),
                    versus(pv2, p2.stderr_variance(), ep.var_v2_sq),
                    pp.var_v2_sq,
                    (pv2 - pp.var_v2_sq) / p2.stderr_variance(),
                ),
    )
    .checked(mc(pv1, p1.stderr_variance()))
}

/// The windowed variance against the paper's window factor, detector
/// noise: `appendix.window_variance_factor` (closed form and Monte Carlo of
/// the two-sided band window).
fn window_claims(_find: &Find<'_>, case: &Case, sz: &Sizes) -> Result<Vec<Computed>> {
    let (setup, ifg, detector) = (&case.setup, &case.ifg, &case.detector);
    let counts = ifg.mean_counts();
    let all = case.all_bins();
    let obs = noise::example_observation();
    let (lo, hi) = obs.spectrum.support();
    let factor = noise::paper_window_factor(setup.dx_um, hi - lo);
    let window2 = two_sided_band_bins(setup.samples, setup.dx_um, lo, hi);
    let window1 = crate::formalism::estimator::band_bins(setup.samples, setup.dx_um, lo, hi)?;
    let w_all = window_stats(&ifg.modulated, &counts, detector, &all)?;
    let w2 = window_stats(&ifg.modulated, &counts, detector, &window2)?;
    let w1 = window_stats(&ifg.modulated, &counts, detector, &window1)?;
    let ratio1 = w_all.var_v1_sq / w2.var_v1_sq;
    let ratio2 = w_all.var_v2_sq / w2.var_v2_sq;
    let spec_w = NoisySpec {
        bins: window2.clone(),
        ..case.spec(*detector)
    };
    let (a, b) = mc_estimators(
        &spec_w,
        sz.interferograms,
        seed("appendix.window_variance_factor"),
    )?;
    let mc_note = format!(
        "; Monte Carlo of the two-sided window ({} interferograms): var V1^2 = {}, var V2^2 = {}",
        sz.interferograms,
        versus(a.variance(), a.stderr_variance(), w2.var_v1_sq),
        versus(b.variance(), b.stderr_variance(), w2.var_v2_sq)
    );
    // The Monte Carlo of the windowed variance, as a ratio to the all-bins
    // closed form (the claim's unit).
    let mc_ratio = w_all.var_v1_sq / a.variance();
    let mc_ratio_se = mc_ratio * a.stderr_variance() / a.variance();
    Ok(vec![Computed::formula(
        "appendix.window_variance_factor",
        ratio1,
        factor * factor,
        format!(
                "exact quadratic-form variances, detector case (s = {APPENDIX_READ_NOISE_PER_PHOTON} n), {} samples: the band covers {} positive bins ({} with their mirror images, which a window must keep to keep the whole fringe of a real signal). Paper factor (1/dx)/delta-sigma_0 = {:.2}. Exact var(all bins)/var(two-sided band window): V1^2 {ratio1:.3}, V2^2 {ratio2:.3} (the white-noise argument divides only the noise x noise term; the signal x noise term of V1^2 lies inside the window and stays). SNR gain: V1 {:.3}, V2 {:.3} vs the paper's sqrt = {factor:.3}; positive-band-only window: SNR1 {:.3}, SNR2 {:.3} (all bins: {:.3}, {:.3}){mc_note}",
                setup.samples,
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
    )
    .checked(mc(mc_ratio, mc_ratio_se))])
}

/// m_0/n when sample 0 sits half a sample (δx/2) off the white-light fringe.
fn half_sample_m0(setup: &ExampleSetup) -> f64 {
    let obs = noise::example_observation();
    crate::formalism::interferogram::SpectralNodes::new(&obs, setup.dx_um, None)
        .expect("the example's nodes")
        .fringe(0.5 * setup.dx_um)
}

mod moments;
mod snr;
use moments::sample_moment_claims;
use snr::{abcd_claims, crossover_claims, worked_example_claims};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::claims::{ledger, Finding};

    /// A case whose interferogram cannot be built (no samples): every claim
    /// that reads it is `failed` with the error in its note, none is
    /// missing (which would leave it `pending`).
    #[test]
    fn a_failed_case_yields_failed_claims() {
        let specs = ledger();
        let find = |id: &str| specs.iter().find(|s| s.id == id);
        let bad = ExampleSetup {
            samples: 0,
            ..appendix_setup()
        };
        let out = claims_for(&find, Effort::Quick, bad);
        let case_ids = [
            &ALL_BINS_IDS[..],
            &SAMPLE_IDS,
            &WINDOW_IDS,
            &WORKED_IDS,
            &CROSSOVER_IDS,
        ]
        .concat();
        for id in &case_ids {
            let c = out
                .iter()
                .find(|c| c.id == *id)
                .expect("every claim answered");
            assert_eq!(c.finding, Finding::Failed, "{id}");
            assert!(c.note.starts_with("computation failed: "), "{}", c.note);
            assert_eq!(c.finding.value(), None);
        }
        let abcd = out.iter().find(|c| c.id == ABCD_IDS[0]).expect("answered");
        assert_ne!(abcd.finding, Finding::Failed, "ABCD does not read the case");
    }

    /// A step that fails yields `failed` for each of its ids.
    #[test]
    fn settle_reports_a_failed_step() {
        let err = crate::Error::Invalid {
            param: "samples",
            reason: "none".into(),
        };
        let out = settle(&WORKED_IDS, Err(err.clone()));
        assert_eq!(out.len(), WORKED_IDS.len());
        for (c, id) in out.iter().zip(WORKED_IDS) {
            assert_eq!(c.id, id);
            assert_eq!(c.finding, Finding::Failed);
            assert_eq!(c.note, format!("computation failed: {err}"));
        }
    }
}
