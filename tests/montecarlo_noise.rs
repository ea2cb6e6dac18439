//! The noisy Monte Carlo engine: moment accumulator, fast windowed
//! estimators against the FFT, Poisson samplers against the Poisson law.

use v2ref_core::formalism::estimator::{all_bins, band_bins, dft, positive_bins, raw_estimates};
use v2ref_core::formalism::oracle::naive_dft;
use v2ref_core::montecarlo::{unit_rng, RunningStats};
use v2ref_core::noise::simulation::{PoissonSampler, WindowedEstimators};
use v2ref_core::noise::{raw_moments_from_cumulants, NoiseModel};
use v2ref_core::tolerance::{IDENTITY_REL, MC_SIGMAS, STREAMING_M3_FLOOR, STREAMING_M3_REL};
use v2ref_core::{assert_abs_eq, assert_rel_eq};

#[test]
fn moments4_matches_two_pass_and_merges() {
    let xs: Vec<f64> = (0..1000)
        .map(|i| ((i * 7919) % 1013) as f64 * 0.37 + 1e6)
        .collect();
    let n = xs.len() as f64;
    let mean = xs.iter().sum::<f64>() / n;
    let c = |p: i32| xs.iter().map(|x| (x - mean).powi(p)).sum::<f64>();
    let mut acc = RunningStats::default();
    xs.iter().for_each(|&x| acc.push(x));
    assert_rel_eq!(acc.mean, mean, IDENTITY_REL);
    assert_rel_eq!(acc.m2, c(2), IDENTITY_REL);
    assert_abs_eq!(
        acc.m3,
        c(3),
        // tol: 1.5 is an exponent: the floor is in the unit of a third cumulant, c2^(3/2).
        STREAMING_M3_FLOOR * c(2).powf(1.5) + STREAMING_M3_REL * (c(3)).abs()
    );
    assert_rel_eq!(acc.m4, c(4), IDENTITY_REL);
    // merging two halves equals one pass
    let (mut a, mut b) = (RunningStats::default(), RunningStats::default());
    xs[..337].iter().for_each(|&x| a.push(x));
    xs[337..].iter().for_each(|&x| b.push(x));
    a.merge(&b);
    assert_eq!(a.count, acc.count);
    assert_rel_eq!(a.mean, acc.mean, IDENTITY_REL);
    assert_rel_eq!(a.m2, acc.m2, IDENTITY_REL);
    assert_rel_eq!(a.m4, acc.m4, IDENTITY_REL);
    // affine transform
    let t = acc.affine(2.0, -3.0);
    assert_rel_eq!(t.variance(), 4.0 * acc.variance(), IDENTITY_REL);
    assert_rel_eq!(t.mean, 2.0 * acc.mean - 3.0, IDENTITY_REL);
}

#[test]
fn fast_windowed_estimators_match_the_fft() {
    for &n in &[16usize, 17, 64, 128, 200] {
        let x: Vec<f64> = (0..n)
            .map(|i| ((i * 31 + 7) % 13) as f64 - 6.0 + 0.1 * i as f64)
            .collect();
        let spec = dft(&x);
        let windows = vec![
            all_bins(n).unwrap(),
            positive_bins(n).unwrap(),
            band_bins(n, 0.5, 0.4167, 0.5).unwrap(),
            vec![0, 1, n - 1],
            vec![3],
            (2..n - 2).collect(),
            (0..n).step_by(3).collect(),
            // A comb offset from 0: u = Σ_K e^{2πi ik/N} is sparse (nonzero
            // at multiples of N/4) and complex, the sparse path's other half.
            (1..n).step_by(4).collect(),
        ];
        for bins in windows {
            let fast = WindowedEstimators::new(n, &bins);
            assert_eq!(fast.samples(), n);
            let mut scratch = Vec::new();
            let got = fast.raw(&x, &mut scratch);
            let want = raw_estimates(&spec, &bins).unwrap();
            let naive = raw_estimates(&naive_dft(&x), &bins).unwrap();
            let scale = x.iter().map(|v| v * v).sum::<f64>() * (n * n) as f64;
            assert!(
                (got.v1_sq - want.v1_sq).abs() < IDENTITY_REL * scale,
                "n {n} bins {bins:?}"
            );
            assert!(
                (got.v2_sq - want.v2_sq).abs() < IDENTITY_REL * scale,
                "n {n} bins {bins:?}"
            );
            assert!((want.v1_sq - naive.v1_sq).abs() < IDENTITY_REL * scale);
        }
    }
}

/// Raw moments 1..4 of counts from `sampler` against the Poisson law
/// (moments from cumulants all equal to λ), closed-form standard errors,
/// with power against 1.02×.
fn check_poisson(sampler: &PoissonSampler, lambda: f64, seed: u64) {
    let t = 2_000_000u64;
    let mut rng = unit_rng(seed, 0);
    let mut acc = [0.0f64; 4];
    for _ in 0..t {
        let k = sampler.sample(&mut rng);
        let mut p = 1.0;
        for a in acc.iter_mut() {
            p *= k;
            *a += p;
        }
    }
    let mu = raw_moments_from_cumulants(&[lambda; 8]);
    for r in 1..=4 {
        let mc = acc[r - 1] / t as f64;
        let se = ((mu[2 * r] - mu[r] * mu[r]) / t as f64).sqrt();
        assert!(
            ((mc - mu[r]) / se).abs() < MC_SIGMAS,
            "lambda {lambda} r {r}: {mc} vs {}",
            mu[r]
        );
        assert!(
            ((mc - 1.02 * mu[r]) / se).abs() > MC_SIGMAS,
            "no power at r {r}"
        );
    }
}

#[test]
fn poisson_samplers_follow_the_poisson_law() {
    for (i, &lambda) in [3.5, 12.0, 20.0].iter().enumerate() {
        check_poisson(
            &PoissonSampler::new(lambda, true).unwrap(),
            lambda,
            40 + i as u64,
        );
        check_poisson(
            &PoissonSampler::new(lambda, false).unwrap(),
            lambda,
            50 + i as u64,
        );
    }
    let mut rng = unit_rng(1, 1);
    assert_eq!(
        PoissonSampler::new(0.0, true).unwrap().sample(&mut rng),
        0.0
    );
    assert!(PoissonSampler::new(-1.0, true).is_err());
    assert!(PoissonSampler::new(f64::NAN, false).is_err());
}

#[test]
fn noisy_spec_rejects_bad_input() {
    use v2ref_core::noise::simulation::{simulate_noisy, NoisySpec};
    let spec = NoisySpec {
        modulated: vec![-20.0, 1.0],
        continuum: vec![10.0, 10.0],
        noise: NoiseModel::photon(),
        bins: vec![0, 1],
    };
    assert!(simulate_noisy(&spec, 10, 1, 1, &|_| {}).is_err());
    let spec = NoisySpec {
        modulated: vec![1.0, 1.0],
        continuum: vec![10.0, 10.0],
        noise: NoiseModel::photon(),
        bins: vec![2],
    };
    assert!(simulate_noisy(&spec, 10, 1, 1, &|_| {}).is_err());
}

#[test]
fn the_alias_table_leaves_out_less_than_1e_minus_30_of_the_poisson_mass() {
    // The Poisson mass outside lo ..= hi, summed term by term from the pmf
    // in log space (ln p(k) = k ln λ − λ − ln k!, statrs's ln Γ) until the
    // terms fall below 1e-40 of it: the documented bound is 1e-32.
    use statrs::function::gamma::ln_gamma;
    let pmf = |k: f64, lambda: f64| (k * lambda.ln() - lambda - ln_gamma(k + 1.0)).exp();
    for lambda in [1e-4, 0.05, 0.5, 3.0, 20.0, 1e3, 1e6] {
        let (lo, hi) = PoissonSampler::support(lambda);
        assert!(
            lo >= 0.0 && lo <= lambda.floor() && hi >= lambda.ceil(),
            "λ = {lambda}"
        );
        let mut out = 0.0;
        let mut k = hi + 1.0;
        loop {
            let p = pmf(k, lambda);
            out += p;
            if p < 1e-45 {
                break;
            }
            k += 1.0;
        }
        let mut k = lo - 1.0;
        while k >= 0.0 {
            let p = pmf(k, lambda);
            out += p;
            if p < 1e-45 {
                break;
            }
            k -= 1.0;
        }
        assert!(
            // tol: the Poisson mass outside the range must be negligible: 1e-30 is far below the rounding of a probability of order one and far above the 1e-45 at which the sums stop.
            out < 1e-30,
            "λ = {lambda}: {out:e} of the mass outside {lo} ..= {hi}"
        );
    }
}

// ---- seeding (crates/v2ref-core/src/montecarlo/mod.rs) ----------------------------------------

#[test]
fn the_seed_mixer_is_splitmix64() {
    // derive_seed with no label and no key is SplitMix64's output function
    // of its argument: the state after k steps from seed 0 is k times the
    // golden gamma, and the published outputs for seed 0 (Vigna,
    // https://prng.di.unimi.it/splitmix64.c) are these three.
    use v2ref_core::montecarlo::derive_seed;
    let gamma = 0x9E37_79B9_7F4A_7C15u64;
    let published = [
        0xE220_A839_7B1D_CDAF,
        0x6E78_9E6A_A1B9_65F4,
        0x06C4_5D18_8009_454F,
    ];
    for (k, want) in published.into_iter().enumerate() {
        assert_eq!(
            derive_seed(gamma.wrapping_mul(k as u64), "", &[]),
            want,
            "output {k}"
        );
    }
    // Keyed by label and key, each seed distinct: neighbouring keys, labels
    // one letter apart, and the order of the words.
    let mut seeds: Vec<u64> = (0..512)
        .map(|i| derive_seed(7, "fig5", &[i as f64]))
        .collect();
    seeds.extend(["fig4", "fig6", "gig5", "fig"].map(|l| derive_seed(7, l, &[300.0])));
    seeds.push(derive_seed(7, "fig5", &[300.0, 1.0]));
    seeds.push(derive_seed(7, "fig5", &[1.0, 300.0]));
    let n = seeds.len();
    seeds.sort_unstable();
    seeds.dedup();
    assert_eq!(seeds.len(), n, "two keys share a seed");
}

#[test]
fn every_unit_has_its_own_stream() {
    // Distinct units of one seed, and one unit of distinct seeds, start
    // their streams differently (extreme seeds included, where a weak mix
    // of seed and unit would give every unit the same state); the same
    // (seed, unit) gives the same stream.
    let first = |seed: u64, unit: u64| unit_rng(seed, unit).next_u64();
    for seed in [0, 1, 7, u64::MAX] {
        let mut draws: Vec<u64> = (0..256).map(|u| first(seed, u)).collect();
        draws.sort_unstable();
        draws.dedup();
        assert_eq!(draws.len(), 256, "seed {seed}: units share a stream");
    }
    let mut by_seed: Vec<u64> = (0..256).map(|s| first(s, 3)).collect();
    by_seed.sort_unstable();
    by_seed.dedup();
    assert_eq!(by_seed.len(), 256);
    assert_eq!(first(42, 9), first(42, 9));
}

#[test]
fn the_generator_draws_what_rand_draws_from_the_same_state() {
    // v2ref's Rng against rand 0.8 itself on a Pcg64Mcg of the same seed:
    // the same 64-bit words, rand's `Standard` f64 ([0, 1), 53 bits) and
    // rand_distr's StandardNormal, draw for draw (the golden files hold
    // these streams). A uniform from 52 or 54 bits, or another normal
    // sampler, differs at the first draws.
    use rand::{Rng as _, RngCore, SeedableRng};
    use rand_distr::{Distribution, StandardNormal};
    for seed in [[0u8; 16], [7; 16], core::array::from_fn(|i| i as u8 * 17)] {
        let mut ours = v2ref_core::montecarlo::Rng::from_seed(seed);
        let mut theirs = rand_pcg::Pcg64Mcg::from_seed(seed);
        for _ in 0..1000 {
            assert_eq!(ours.next_u64(), theirs.next_u64());
            assert_eq!(ours.uniform_f64(), theirs.gen::<f64>());
            let z: f64 = StandardNormal.sample(&mut theirs);
            assert_eq!(ours.standard_normal(), z);
        }
    }
    let u = v2ref_core::montecarlo::Rng::from_seed([3; 16]).uniform_f64();
    assert!((0.0..1.0).contains(&u));
}

#[test]
fn units_run_in_unit_order_with_their_own_generators() {
    // run_units and run_unit_range return one result per unit, in unit
    // order, each from unit_rng(seed, unit), whatever the thread count.
    use v2ref_core::montecarlo::{run_unit_range, run_units};
    let draw = |u: u64, rng: &mut v2ref_core::montecarlo::Rng| (u, rng.next_u64());
    for threads in [1, 3] {
        let all = run_units(11, 5, threads, draw).unwrap();
        let want: Vec<(u64, u64)> = (0..5).map(|u| (u, unit_rng(11, u).next_u64())).collect();
        assert_eq!(all, want);
        let part = run_unit_range(11, 3..7, threads, draw).unwrap();
        let want: Vec<(u64, u64)> = (3..7).map(|u| (u, unit_rng(11, u).next_u64())).collect();
        assert_eq!(part, want);
    }
}

#[test]
fn thread_counts_are_checked_against_four_per_core_at_least_sixteen() {
    use v2ref_core::montecarlo::{
        check_threads, max_threads, MAX_THREADS_FLOOR, MAX_THREADS_PER_CORE,
    };
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let max = max_threads();
    assert_eq!(max, (MAX_THREADS_PER_CORE * cores).max(MAX_THREADS_FLOOR));
    assert_eq!((MAX_THREADS_PER_CORE, MAX_THREADS_FLOOR), (4, 16));
    for ok in [0, 1, max] {
        assert_eq!(check_threads(ok).unwrap(), ok);
    }
    assert!(matches!(
        check_threads(max + 1),
        Err(v2ref_core::Error::OutOfRange {
            param: "threads",
            ..
        })
    ));
}
