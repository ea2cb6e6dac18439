//! The spectral estimators `v1_sq`, `v2_sq` and `wide_band` on NON-flat
//! spectra — sloped (`Spectrum::power_law`), with an absorption band
//! (`Spectrum::tabulated`), tabulated from CSV (`Spectrum::from_csv_str`) —
//! against two truths that share no code with them:
//!
//! - a composite Simpson quadrature written here, piece by piece between
//!   the kinks of W, with the uniform-disk visibility 2 J1(z)/z from
//!   Bessel's integral by the trapezoidal rule (itself checked against the
//!   mpmath table `tests/data/bessel_reference.csv` below), W evaluated by
//!   this file's own formulas and the cycles/arcsec conversion written out;
//! - the sampled DFT path (`sampled_wide_band`: a long, fine synthesized
//!   scan, |B_k|² summed over the positive bins and normalized by the
//!   calibrator), in which the W² of V1² arises from squaring the fringe
//!   spectrum rather than from any weighting in the code.
//!
//! On a flat band W² ∝ W, so the weighting of V1² (W², not W) is only
//! visible here: issue 16 found that no other test sees V1² weighted by W.

use proptest::prelude::*;
use std::f64::consts::PI;
use v2ref_core::assert_rel_eq;
use v2ref_core::formalism::estimator::{
    dft, positive_bins, raw_estimates, sampled_wide_band, v1_sq, v2_sq, v_mono, wide_band,
    BinWindow,
};
use v2ref_core::formalism::interferogram::{Interferogram, Sampling};
use v2ref_core::formalism::observation::{Frequency, Observation};
use v2ref_core::formalism::phase::SpectralPhase;
use v2ref_core::formalism::source::Source;
use v2ref_core::formalism::spectrum::{Band, Spectrum};
use v2ref_core::tolerance::{
    BESSEL_ABS, POWER_FACTOR, REFERENCE_QUADRATURE_REL, SAMPLED_VS_SPECTRAL_ABS,
    VISIBILITY_SQ_FLOOR,
};

// ---- the independent reference ------------------------------------------------

/// Cycles/arcsec per (metre of baseline × µm⁻¹ of wavenumber): B σ is in
/// cycles per radian ×10⁶, and one arcsec is π/648000 rad. Written out here
/// rather than imported.
const CPAS: f64 = 1e6 * PI / 648_000.0;

/// J1(z) by the trapezoidal rule on Bessel's integral
/// J1(z) = (1/π) ∫₀^π cos(τ − z sin τ) dτ (DLMF 10.9.1): the integrand is
/// even and 2π-periodic, so the rule converges geometrically (Trefethen &
/// Weideman 2014, SIAM Rev. 56, 385), to rounding once M ≳ |z| + 30.
fn bessel_j1_trapezoid(z: f64) -> f64 {
    const M: usize = 160;
    let h = PI / M as f64;
    let f = |t: f64| (t - z * t.sin()).cos();
    let inner: f64 = (1..M).map(|j| f(j as f64 * h)).sum();
    (0.5 * (f(0.0) + f(PI)) + inner) * h / PI
}

/// 2 J1(z)/z: its power series Σ (−1)^k (z/2)^{2k} / (k! (k+1)!) below
/// |z| = 1 (terms fall by ≥ 8 each, 14 terms reach rounding), Bessel's
/// integral above.
fn jinc_reference(z: f64) -> f64 {
    // tol: not a tolerance: the switch from the power series to Bessel's integral (doc above).
    if z.abs() < 1.0 {
        let q = 0.25 * z * z;
        let (mut term, mut sum) = (1.0, 1.0);
        for k in 1..14 {
            term *= -q / (k as f64 * (k + 1) as f64);
            sum += term;
        }
        sum
    } else {
        2.0 * bessel_j1_trapezoid(z) / z
    }
}

/// W(σ) up to scale, as the reference evaluates it.
type Weight = Box<dyn Fn(f64) -> f64>;

/// An observation as the reference sees it: W up to scale, its kinks, the
/// disk, the baseline and a quadratic phase a2 (σ − σ0)².
struct Model {
    breaks: Vec<f64>,
    weight: Weight,
    diameter_mas: f64,
    baseline_m: f64,
    sigma0: f64,
    a2: f64,
}

struct Reference {
    v1_sq: f64,
    v2_sq: f64,
    /// ∫ W |V|² dσ / ∫ W dσ: what V1² would read weighted by W (the
    /// mutation of issue 16), to show each comparison has power.
    v1_sq_w_weighted: f64,
    v_mono: f64,
}

impl Model {
    fn visibility(&self, sigma: f64) -> f64 {
        let z = PI * self.diameter_mas * 1e-3 * self.baseline_m * sigma * CPAS;
        jinc_reference(z)
    }

    /// ∫ f over the support: composite Simpson on each piece between kinks,
    /// with a step of at most 1/4000 of the support (at least 2 panels).
    fn integrate(&self, f: impl Fn(f64) -> f64) -> f64 {
        let span = self.breaks[self.breaks.len() - 1] - self.breaks[0];
        let h_max = span / 4000.0;
        self.breaks
            .windows(2)
            .map(|p| {
                let (a, b) = (p[0], p[1]);
                let mut n = ((b - a) / h_max).ceil().max(2.0) as usize;
                n += n % 2;
                let h = (b - a) / n as f64;
                let inner: f64 = (1..n)
                    .map(|j| {
                        let c = if j % 2 == 1 { 4.0 } else { 2.0 };
                        c * f(a + j as f64 * h)
                    })
                    .sum();
                (f(a) + f(b) + inner) * h / 3.0
            })
            .sum()
    }

    fn reference(&self) -> Reference {
        let w = &self.weight;
        let i1 = self.integrate(w);
        let i2 = self.integrate(|s| w(s) * w(s));
        let sigma_eff = self.integrate(|s| s * w(s)) / i1;
        let phase = |s: f64| self.a2 * (s - self.sigma0) * (s - self.sigma0);
        let re = self.integrate(|s| w(s) * self.visibility(s) * phase(s).cos()) / i1;
        let im = self.integrate(|s| w(s) * self.visibility(s) * phase(s).sin()) / i1;
        Reference {
            v1_sq: self.integrate(|s| w(s) * w(s) * self.visibility(s).powi(2)) / i2,
            v2_sq: re * re + im * im,
            v1_sq_w_weighted: self.integrate(|s| w(s) * self.visibility(s).powi(2)) / i1,
            v_mono: self.visibility(sigma_eff).abs(),
        }
    }

    fn observation(&self, spectrum: Spectrum) -> Observation {
        let phase = SpectralPhase {
            sigma0_per_um: self.sigma0,
            coefficients: vec![0.0, 0.0, self.a2],
        };
        Observation::new(
            spectrum,
            Source::uniform_disk(self.diameter_mas).unwrap(),
            Frequency::BaselineM(self.baseline_m),
            phase,
        )
        .unwrap()
    }
}

/// Piecewise-linear interpolation through (σ_j, w_j), zero outside.
fn linear(sig: &[f64], w: &[f64], s: f64) -> f64 {
    if s < sig[0] || s > sig[sig.len() - 1] {
        return 0.0;
    }
    let j = sig
        .windows(2)
        .position(|p| s <= p[1])
        .unwrap_or(sig.len() - 2);
    let t = (s - sig[j]) / (sig[j + 1] - sig[j]);
    w[j] + t * (w[j + 1] - w[j])
}

/// The three kinds of non-flat spectrum, each as the library builds it and
/// as the reference models it.
#[derive(Debug, Clone, Copy)]
enum Kind {
    /// S F ∝ (σ/σ_c)^index on the band.
    PowerLaw { index: f64 },
    /// A sloped continuum (σ/σ_c)^index times 1 − depth·exp(−u²/2),
    /// u = (σ − position)/width, tabulated on 61 nodes, built from vectors.
    Absorption {
        index: f64,
        depth: f64,
        position: f64,
        width: f64,
    },
    /// The same table written as CSV text in wavelength (decreasing
    /// wavenumber) and read back by `Spectrum::from_csv_str`.
    AbsorptionCsv {
        index: f64,
        depth: f64,
        position: f64,
        width: f64,
    },
}

/// The table of an absorption band: nodes in wavenumber and weights.
fn absorption_table(
    band: Band,
    index: f64,
    depth: f64,
    pos: f64,
    width: f64,
) -> (Vec<f64>, Vec<f64>) {
    let (lo, hi) = (band.sigma_min_per_um(), band.sigma_max_per_um());
    let c = 0.5 * (lo + hi);
    let (centre, sd) = (lo + pos * (hi - lo), width * (hi - lo));
    let sig: Vec<f64> = (0..=60).map(|j| lo + (hi - lo) * j as f64 / 60.0).collect();
    let w = sig
        .iter()
        .map(|&s| (s / c).powf(index) * (1.0 - depth * (-0.5 * ((s - centre) / sd).powi(2)).exp()))
        .collect();
    (sig, w)
}

/// The library's spectrum and the reference model of `kind` on `band`, for
/// a disk of `diameter_mas` at `s_cpas` (at the band centre) under a
/// quadratic phase of `pp_rad` at the band edges.
fn case(
    kind: Kind,
    band: Band,
    diameter_mas: f64,
    s_cpas: f64,
    pp_rad: f64,
) -> (Observation, Model) {
    let (lo, hi) = (band.sigma_min_per_um(), band.sigma_max_per_um());
    let c = 0.5 * (lo + hi);
    let half = 0.5 * (hi - lo);
    let (spectrum, breaks, weight): (Spectrum, Vec<f64>, Weight) = match kind {
        Kind::PowerLaw { index } => (
            Spectrum::power_law(band, index).unwrap(),
            vec![lo, hi],
            Box::new(move |s: f64| {
                if (lo..=hi).contains(&s) {
                    (s / c).powf(index)
                } else {
                    0.0
                }
            }),
        ),
        Kind::Absorption {
            index,
            depth,
            position,
            width,
        } => {
            let (sig, w) = absorption_table(band, index, depth, position, width);
            let sp = Spectrum::tabulated(sig.clone(), w.clone()).unwrap();
            (sp, sig.clone(), Box::new(move |s: f64| linear(&sig, &w, s)))
        }
        Kind::AbsorptionCsv {
            index,
            depth,
            position,
            width,
        } => {
            let (sig, w) = absorption_table(band, index, depth, position, width);
            // Increasing wavelength; Rust's `{}` round-trips every f64.
            let lambda: Vec<f64> = sig.iter().rev().map(|s| 1.0 / s).collect();
            let weights: Vec<f64> = w.iter().rev().copied().collect();
            let mut text =
                String::from("# a sloped band with an absorption feature\nwavelength_um,weight\n");
            for (l, x) in lambda.iter().zip(&weights) {
                text.push_str(&format!("{l},{x}\n"));
            }
            let sp = Spectrum::from_csv_str(&text).unwrap();
            // The reference reads the same numbers: σ = 1/λ, in increasing σ.
            let sig: Vec<f64> = lambda.iter().rev().map(|l| 1.0 / l).collect();
            let w: Vec<f64> = weights.iter().rev().copied().collect();
            (sp, sig.clone(), Box::new(move |s: f64| linear(&sig, &w, s)))
        }
    };
    let model = Model {
        breaks,
        weight,
        diameter_mas,
        baseline_m: s_cpas / (c * CPAS),
        sigma0: c,
        a2: pp_rad / (half * half),
    };
    (model.observation(spectrum), model)
}

/// |actual − expected| ≤ tol · max(expected, VISIBILITY_SQ_FLOOR) for a V².
fn close_sq(actual: f64, expected: f64, tol: f64) -> bool {
    (actual - expected).abs() <= tol * expected.abs().max(VISIBILITY_SQ_FLOOR)
}

// ---- the reference is right ---------------------------------------------------

#[test]
fn reference_jinc_matches_mpmath() {
    let mut count = 0;
    for line in include_str!("data/bessel_reference.csv").lines() {
        let row: Vec<&str> = line.split(',').collect();
        if row[0] != "value" {
            continue;
        }
        let x: f64 = row[1].parse().unwrap();
        let want: f64 = row[4].parse().unwrap();
        if x > 40.0 {
            continue; // beyond every z this file uses (≤ 20)
        }
        let got = jinc_reference(x);
        assert!(
            (got - want).abs() <= BESSEL_ABS,
            "jinc({x}) = {got}, mpmath {want}, error {:e}",
            (got - want).abs()
        );
        count += 1;
    }
    assert!(count > 100, "{count} rows");
}

#[test]
fn reference_quadrature_has_the_closed_form_moments_of_a_power_law() {
    // ∫ σ^p over [lo, hi] in closed form; a point source has V = 1, so
    // V1² = V2² = 1 exactly and σ_eff has the closed form
    // (p+1)/(p+2) (hi^{p+2} − lo^{p+2}) / (hi^{p+1} − lo^{p+1}).
    let band = Band::k();
    let (lo, hi) = (band.sigma_min_per_um(), band.sigma_max_per_um());
    for p in [-5.0f64, -1.5, 2.5, 3.8] {
        let (_, m) = case(Kind::PowerLaw { index: p }, band, 1e-6, 0.0, 0.0);
        let c = 0.5 * (lo + hi);
        let want = (hi.powf(p + 1.0) - lo.powf(p + 1.0)) / ((p + 1.0) * c.powf(p));
        assert_rel_eq!(
            m.integrate(|s| (m.weight)(s)),
            want,
            REFERENCE_QUADRATURE_REL
        );
        let r = m.reference();
        assert_rel_eq!(r.v1_sq, 1.0, REFERENCE_QUADRATURE_REL);
        assert_rel_eq!(r.v2_sq, 1.0, REFERENCE_QUADRATURE_REL);
    }
}

// ---- the case ------------------------------------------------------------

/// W doubling across K (index ln 2 / ln 1.2), the 43 mas disk at 20
/// cycles/arcsec: the case of issue 16, where V1² weighted by W instead of
/// W² is 5.6% off.
#[test]
fn v1_sq_of_a_band_whose_w_doubles_across_k_is_the_w2_weighted_mean() {
    let index = 2f64.ln() / 1.2f64.ln();
    let (obs, model) = case(Kind::PowerLaw { index }, Band::k(), 43.0, 20.0, 0.0);
    let r = model.reference();
    // The wrong weighting is ≥ POWER_FACTOR tolerances away: the check has power.
    let gap = (r.v1_sq_w_weighted - r.v1_sq).abs() / r.v1_sq;
    assert!(gap > 0.05, "W vs W² weighting differs by only {gap:e}");
    assert!(gap > POWER_FACTOR * REFERENCE_QUADRATURE_REL);
    assert_rel_eq!(v1_sq(&obs), r.v1_sq, REFERENCE_QUADRATURE_REL);
    assert_rel_eq!(v2_sq(&obs), r.v2_sq, REFERENCE_QUADRATURE_REL);
    let wb = wide_band(&obs);
    assert_rel_eq!(wb.v1_sq, r.v1_sq, REFERENCE_QUADRATURE_REL);
    assert_rel_eq!(wb.v2_sq, r.v2_sq, REFERENCE_QUADRATURE_REL);
    assert_rel_eq!(wb.v_mono, r.v_mono, REFERENCE_QUADRATURE_REL);
    assert_rel_eq!(v_mono(&obs), r.v_mono, REFERENCE_QUADRATURE_REL);
    // tol: a square against its computed square: two roundings, four ε.
    assert_rel_eq!(wb.v1 * wb.v1, wb.v1_sq, 4.0 * f64::EPSILON);

    // The sampled path, built by hand: a 1024 µm scan, the positive bins,
    // normalized by the calibrator's.
    let sampling = Sampling::new(2048, 0.5, false).unwrap();
    let bins = positive_bins(sampling.samples()).unwrap();
    let raw = |o: &Observation| {
        let ifg = Interferogram::synthesize(o, &sampling, 1.0, None).unwrap();
        raw_estimates(&dft(&ifg.modulated), &bins).unwrap()
    };
    let (src, cal) = (raw(&obs), raw(&obs.calibrator()));
    let (s1, s2) = (src.v1_sq / cal.v1_sq, src.v2_sq / cal.v2_sq);
    assert!(
        (s1 - r.v1_sq).abs() < SAMPLED_VS_SPECTRAL_ABS,
        "sampled V1² {s1} vs reference {} (W-weighted {})",
        r.v1_sq,
        r.v1_sq_w_weighted
    );
    assert!(
        (s2 - r.v2_sq).abs() < SAMPLED_VS_SPECTRAL_ABS,
        "sampled V2² {s2} vs {}",
        r.v2_sq
    );
    assert!((s1 - r.v1_sq_w_weighted).abs() > 2.0 * SAMPLED_VS_SPECTRAL_ABS);
    eprintln!(
        "V1² {} (W-weighted {}, gap {gap:.4}), library {:e} off, sampled {:e} off",
        r.v1_sq,
        r.v1_sq_w_weighted,
        (v1_sq(&obs) - r.v1_sq).abs(),
        (s1 - r.v1_sq).abs()
    );
}

#[test]
fn absorption_band_and_csv_spectra_match_the_reference() {
    let band = Band::k();
    for (d, s, pp) in [(43.0, 20.0, 0.0), (43.0, 35.0, 1.5), (20.0, 50.0, -2.0)] {
        for kind in [
            Kind::Absorption {
                index: 0.0,
                depth: 0.9,
                position: 0.3,
                width: 0.08,
            },
            Kind::AbsorptionCsv {
                index: -2.0,
                depth: 0.7,
                position: 0.7,
                width: 0.05,
            },
        ] {
            let (obs, m) = case(kind, band, d, s, pp);
            let r = m.reference();
            let wb = wide_band(&obs);
            assert!(
                close_sq(wb.v1_sq, r.v1_sq, REFERENCE_QUADRATURE_REL),
                "{kind:?} d {d} S {s}: V1² {} vs {}",
                wb.v1_sq,
                r.v1_sq
            );
            assert!(
                close_sq(wb.v2_sq, r.v2_sq, REFERENCE_QUADRATURE_REL),
                "{kind:?} d {d} S {s}: V2² {} vs {}",
                wb.v2_sq,
                r.v2_sq
            );
            assert_rel_eq!(wb.v_mono, r.v_mono, REFERENCE_QUADRATURE_REL);
        }
    }
}

// ---- properties over random non-flat spectra ---------------------------------------

fn band() -> impl Strategy<Value = Band> {
    (1.5f64..2.5, 0.1f64..0.3).prop_map(|(l, frac)| Band::new(l, l * frac).unwrap())
}

/// A spectral index at least 1 in size, either sign.
fn slope() -> impl Strategy<Value = f64> {
    (1.0f64..6.0, any::<bool>()).prop_map(|(p, neg)| if neg { -p } else { p })
}

fn kind() -> impl Strategy<Value = Kind> {
    let absorption = (-3.0f64..3.0, 0.3f64..0.95, 0.15f64..0.85, 0.03f64..0.15);
    prop_oneof![
        slope().prop_map(|index| Kind::PowerLaw { index }),
        absorption
            .clone()
            .prop_map(|(index, depth, position, width)| Kind::Absorption {
                index,
                depth,
                position,
                width
            }),
        absorption.prop_map(|(index, depth, position, width)| Kind::AbsorptionCsv {
            index,
            depth,
            position,
            width
        }),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, .. ProptestConfig::default() })]

    /// `v1_sq`, `v2_sq` and `wide_band` against the Simpson reference.
    #[test]
    fn spectral_estimators_match_an_independent_quadrature(
        kind in kind(), b in band(), d in 5.0f64..60.0, s in 1.0f64..60.0,
        pp in prop_oneof![Just(0.0), -3.0f64..3.0],
    ) {
        let (obs, m) = case(kind, b, d, s, pp);
        let r = m.reference();
        let wb = wide_band(&obs);
        prop_assert!(close_sq(v1_sq(&obs), r.v1_sq, REFERENCE_QUADRATURE_REL),
            "V1² {} vs reference {} (W-weighted {})", v1_sq(&obs), r.v1_sq, r.v1_sq_w_weighted);
        prop_assert!(close_sq(v2_sq(&obs), r.v2_sq, REFERENCE_QUADRATURE_REL),
            "V2² {} vs reference {}", v2_sq(&obs), r.v2_sq);
        prop_assert_eq!(wb.v1_sq, v1_sq(&obs));
        prop_assert_eq!(wb.v2_sq, v2_sq(&obs));
        prop_assert!(close_sq(wb.v_mono, r.v_mono, REFERENCE_QUADRATURE_REL),
            "V_mono {} vs reference {}", wb.v_mono, r.v_mono);
    }

    /// V1 is blind to the spectral phase on any spectrum, and V2² ≤ V1²
    /// does NOT hold in general off a flat band (W² vs W weighting), but
    /// V2² ≤ ∫W|V|² (Cauchy–Schwarz with the unit-area W) does.
    #[test]
    fn v2_sq_is_bounded_by_the_w_weighted_mean_of_v_sq(
        kind in kind(), b in band(), d in 5.0f64..60.0, s in 1.0f64..60.0, pp in -3.0f64..3.0,
    ) {
        let (obs, m) = case(kind, b, d, s, pp);
        let (without, _) = case(kind, b, d, s, 0.0);
        let r = m.reference();
        prop_assert!(v2_sq(&obs) <= r.v1_sq_w_weighted * (1.0 + REFERENCE_QUADRATURE_REL));
        prop_assert!(close_sq(v1_sq(&obs), v1_sq(&without), REFERENCE_QUADRATURE_REL));
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 10, .. ProptestConfig::default() })]

    /// The spectral form against a long, fine sampled scan (2048 samples of
    /// 0.5 µm, positive bins, calibrated), on non-flat spectra.
    #[test]
    fn long_sampled_scans_agree_with_the_spectral_form_on_non_flat_spectra(
        kind in kind(), d in 10.0f64..60.0, s in 5.0f64..50.0, pp in -2.0f64..2.0,
    ) {
        let (obs, _) = case(kind, Band::k(), d, s, pp);
        let sampled = sampled_wide_band(&obs, &Sampling::new(2048, 0.5, false).unwrap(), BinWindow::Positive).unwrap();
        prop_assert!((sampled.v1_sq - v1_sq(&obs)).abs() < SAMPLED_VS_SPECTRAL_ABS,
            "V1²: sampled {} spectral {}", sampled.v1_sq, v1_sq(&obs));
        prop_assert!((sampled.v2_sq - v2_sq(&obs)).abs() < SAMPLED_VS_SPECTRAL_ABS,
            "V2²: sampled {} spectral {}", sampled.v2_sq, v2_sq(&obs));
    }
}
