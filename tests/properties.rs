//! Property tests over random bands, diameters, spatial frequencies and
//! spectral phases.

use num_complex::Complex64;
use proptest::prelude::*;
use v2ref_core::formalism::estimator::{
    all_bins, dft, raw_estimates, sampled_wide_band, v1_sq, v2_sq, BinWindow,
};
use v2ref_core::formalism::interferogram::Sampling;
use v2ref_core::formalism::observation::{Frequency, Observation};
use v2ref_core::formalism::phase::SpectralPhase;
use v2ref_core::formalism::source::Source;
use v2ref_core::formalism::spectrum::{Band, Spectrum};
use v2ref_core::tolerance::{DFT_REL_PER_LOG2N, QUADRATURE_REL, ROUNDING_REL, VISIBILITY_SQ_FLOOR};

fn band() -> impl Strategy<Value = Band> {
    (1.0f64..4.0, 0.01f64..0.3).prop_map(|(l, frac)| Band::new(l, l * frac).unwrap())
}

fn phase(sp: &Spectrum, coeffs: &[f64]) -> SpectralPhase {
    // Coefficients scaled so each term reaches at most a few radians over the band.
    let half = 0.5 * sp.width_per_um();
    SpectralPhase {
        sigma0_per_um: sp.sigma_centre_per_um(),
        coefficients: coeffs
            .iter()
            .enumerate()
            .map(|(k, c)| c / half.powi(k as i32))
            .collect(),
    }
}

fn obs(sp: Spectrum, diameter: f64, s: f64, ph: SpectralPhase) -> Observation {
    Observation::new(
        sp,
        Source::uniform_disk(diameter).unwrap(),
        Frequency::SpatialFreqCpas(s),
        ph,
    )
    .unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, .. ProptestConfig::default() })]

    #[test]
    fn v1_is_blind_to_any_spectral_phase(
        b in band(), d in 1.0f64..100.0, s in 0.0f64..100.0,
        coeffs in prop::collection::vec(-3.0f64..3.0, 0..5),
    ) {
        let sp = Spectrum::flat(b);
        let with = v1_sq(&obs(sp.clone(), d, s, phase(&sp, &coeffs)));
        let without = v1_sq(&obs(sp, d, s, SpectralPhase::zero()));
        prop_assert!((with - without).abs() <= ROUNDING_REL * without.max(VISIBILITY_SQ_FLOOR));
    }

    #[test]
    fn scaling_w_by_a_constant_changes_nothing(
        b in band(), d in 1.0f64..100.0, s in 0.0f64..100.0, k in 1e-6f64..1e6,
        slope in prop::collection::vec(0.1f64..2.0, 2..8),
    ) {
        let (lo, hi) = (b.sigma_min_per_um(), b.sigma_max_per_um());
        let n = slope.len();
        let sig: Vec<f64> = (0..n).map(|j| lo + (hi - lo) * j as f64 / (n - 1) as f64).collect();
        let scaled: Vec<f64> = slope.iter().map(|w| w * k).collect();
        let a = Spectrum::tabulated(sig.clone(), slope).unwrap();
        let bb = Spectrum::tabulated(sig, scaled).unwrap();
        let ph = phase(&a, &[0.0, 0.0, 1.0]);
        let (oa, ob) = (obs(a, d, s, ph.clone()), obs(bb, d, s, ph));
        prop_assert!((v1_sq(&oa) - v1_sq(&ob)).abs() <= QUADRATURE_REL * v1_sq(&oa).max(VISIBILITY_SQ_FLOOR));
        prop_assert!((v2_sq(&oa) - v2_sq(&ob)).abs() <= QUADRATURE_REL * v2_sq(&oa).max(VISIBILITY_SQ_FLOOR));
        prop_assert!((oa.baseline_m - ob.baseline_m).abs() <= ROUNDING_REL * oa.baseline_m.max(1e-9));
    }

    #[test]
    fn flat_spectrum_orders_the_estimators(
        b in band(), d in 1.0f64..100.0, s in 0.0f64..100.0,
        coeffs in prop::collection::vec(-3.0f64..3.0, 0..4),
    ) {
        // V2² = |mean V e^{iφ}|² ≤ mean |V|² = V1² ≤ 1 (Cauchy–Schwarz, |V| ≤ 1).
        let sp = Spectrum::flat(b);
        let o = obs(sp.clone(), d, s, phase(&sp, &coeffs));
        let (v1, v2) = (v1_sq(&o), v2_sq(&o));
        let slack = QUADRATURE_REL;
        prop_assert!(v2 >= 0.0);
        prop_assert!(v2 <= v1 + slack, "V2² {} > V1² {}", v2, v1);
        // tol: 1.0 is V1²'s bound, not a tolerance; slack is the quadrature's.
        prop_assert!(v1 <= 1.0 + slack);
    }

    #[test]
    fn dft_identities_hold_to_rounding(m in prop::collection::vec(-1e3f64..1e3, 2..600)) {
        let n = m.len() as f64;
        let b = dft(&m);
        let tol = DFT_REL_PER_LOG2N * n.log2().max(1.0);
        let energy: f64 = m.iter().map(|x| x * x).sum();
        let parseval: f64 = b.iter().map(Complex64::norm_sqr).sum();
        prop_assert!((parseval - n * energy).abs() <= tol * n * energy + 1e-300);
        let sum: Complex64 = b.iter().sum();
        let scale: f64 = n * m.iter().map(|x| x.abs()).sum::<f64>();
        prop_assert!((sum - Complex64::new(n * m[0], 0.0)).norm() <= tol * scale);
        let raw = raw_estimates(&b, &all_bins(m.len()).unwrap()).unwrap();
        prop_assert!((raw.v1_sq - n * energy).abs() <= tol * n * energy + 1e-300);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, .. ProptestConfig::default() })]

    #[test]
    #[ignore = "slow tier: long sampled scans against the spectral form (6 s)"]
    fn long_sampled_scans_agree_with_the_spectral_form(
        d in 5.0f64..60.0, s in 0.0f64..60.0, pp in -2.0f64..2.0,
    ) {
        let sp = Spectrum::flat(Band::k());
        let ph = SpectralPhase::dispersion_peak_to_peak(&sp, pp).unwrap();
        let o = obs(sp, d, s, ph);
        let sampled = sampled_wide_band(&o, &Sampling::new(4096, 0.25, false).unwrap(), BinWindow::Positive).unwrap();
        prop_assert!((sampled.v1_sq - v1_sq(&o)).abs() < v2ref_core::tolerance::SAMPLED_VS_SPECTRAL_ABS);
        prop_assert!((sampled.v2_sq - v2_sq(&o)).abs() < v2ref_core::tolerance::SAMPLED_VS_SPECTRAL_ABS);
    }
}
