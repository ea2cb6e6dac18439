//! The paths of `benches/floors.rs`: for each, the data, the floor and
//! v2ref's code on the same data.

use super::estimate_floor::{estimate_floor, positive_sums};
use super::Case;
use rayon::prelude::*;
use realfft::RealFftPlanner;
use v2ref_core::formalism::estimator::{positive_bins, BinWindow};
use v2ref_core::montecarlo::{in_pool_capped as in_pool, unit_rng, Rng};
use v2ref_core::noise::simulation::{simulate_noisy, NoisySpec, PoissonSampler, TRIALS_PER_UNIT};
use v2ref_core::noise::{example_interferogram, NoiseModel};
use v2ref_core::simulator::{Inputs, Model};
use v2ref_reproduction::cases::appendix_setup;

/// The paths, in the order they run.
pub const NAMES: [&str; 6] = [
    "estimate",
    "simulate-poisson",
    "simulate-gaussian",
    "synth",
    "piston-sequence",
    "piston",
];

/// The case of path `name`.
pub fn case(name: &str) -> Option<Case> {
    match name {
        "estimate" => Some(estimate(200_000, 64)),
        "simulate-poisson" => Some(simulate(NoiseModel::photon(), "Poisson")),
        "simulate-gaussian" => Some(simulate(
            NoiseModel::detector(2.0).expect("valid"),
            "Gaussian",
        )),
        "synth" => Some(synth_rows(1 << 17)),
        "piston-sequence" => Some(piston_series()),
        "piston" => Some(piston_run(16_000)),
        _ => None,
    }
}

/// The rows of a noisy set of the default configuration at N = `n`.
fn noisy_rows(rows: u64, n: usize) -> (Model, Vec<f64>) {
    let model = Model::new(&Inputs {
        samples: n,
        ..Inputs::default()
    })
    .expect("the default inputs");
    let mut data = Vec::with_capacity(rows as usize * n);
    let set = model.rows(rows, 1, 0).expect("rows");
    set.stream(0, 8, |block| {
        data.extend_from_slice(block);
        Ok(())
    })
    .expect("no sink error");
    drop(set);
    (model, data)
}

/// `estimate` on rows in memory. Floor: per row a real-input FFT (one
/// plan, buffers reused per thread) and the two sums over the positive
/// bins, written to a preallocated output; rows split in blocks over the
/// threads.
fn estimate(rows: u64, n: usize) -> Case {
    let (model, data) = noisy_rows(rows, n);
    let data = std::sync::Arc::new(data);
    let d = data.clone();
    let floor = move |threads: usize| {
        let out = in_pool(threads, || estimate_floor(&d, n));
        out.iter().map(|&(a, b)| a + b).sum()
    };
    let inputs = model.inputs.clone();
    let v2ref = move |threads: usize| {
        use v2ref_commands::commands::estimate::{estimate_rows, estimator, RowsName};
        use v2ref_core::conformance::estimate::BiasConvention;
        let name = RowsName {
            param: "interferograms",
            path: None,
        };
        let options = (BinWindow::Positive, BiasConvention::Model);
        let est = estimator(&inputs, options, true, None, threads).expect("estimator");
        let rows = estimate_rows(&est, name, (&data, 0), threads).expect("rows");
        rows.iter().map(|e| e.v1_sq_raw + e.v2_sq_raw).sum()
    };
    Case {
        name: format!("estimate, {rows} rows of N = {n}"),
        floor: Box::new(floor),
        v2ref: Box::new(v2ref),
    }
}

/// The noise Monte Carlo of the Appendix interferogram (N = 128, positive
/// bins). Floor: per trial the same draws from the same generators (one
/// per unit of TRIALS_PER_UNIT), a real-input FFT, the two sums and their
/// running sums and sums of squares; units over the threads.
fn simulate(noise: NoiseModel, label: &str) -> Case {
    const TRIALS: u64 = 1 << 17;
    let ifg = example_interferogram(&appendix_setup()).expect("the Appendix case");
    let n = ifg.modulated.len();
    let spec = NoisySpec {
        bins: positive_bins(n).unwrap(),
        modulated: ifg.modulated,
        continuum: ifg.continuum,
        noise,
    };
    let s = spec.clone();
    let floor = move |threads: usize| {
        let plan = RealFftPlanner::<f64>::new().plan_fft_forward(n);
        let poisson: Vec<PoissonSampler> = if s.noise.photon {
            s.modulated
                .iter()
                .zip(&s.continuum)
                .map(|(m, c)| PoissonSampler::new(m + c, true).expect("mean >= 0"))
                .collect()
        } else {
            Vec::new()
        };
        let draw = |rng: &mut Rng, row: &mut [f64]| {
            if poisson.is_empty() {
                for (x, &m) in row.iter_mut().zip(&s.modulated) {
                    let z: f64 = rng.standard_normal();
                    *x = m + s.noise.read_noise * z;
                }
            } else {
                for ((x, p), &c) in row.iter_mut().zip(&poisson).zip(&s.continuum) {
                    *x = p.sample(rng) - c;
                }
            }
        };
        let units = TRIALS.div_ceil(TRIALS_PER_UNIT);
        let parts: Vec<[f64; 4]> = in_pool(threads, || {
            (0..units)
                .into_par_iter()
                .map(|u| {
                    let mut rng = unit_rng(1, u);
                    let mut input = plan.make_input_vec();
                    let mut half = plan.make_output_vec();
                    let mut scratch = plan.make_scratch_vec();
                    let mut acc = [0.0; 4];
                    for _ in 0..TRIALS_PER_UNIT {
                        draw(&mut rng, &mut input);
                        plan.process_with_scratch(&mut input, &mut half, &mut scratch)
                            .expect("lengths from the plan");
                        let (v1, v2) = positive_sums(&half, n);
                        acc[0] += v1;
                        acc[1] += v1 * v1;
                        acc[2] += v2;
                        acc[3] += v2 * v2;
                    }
                    acc
                })
                .collect()
        });
        parts.iter().map(|a| a[0] + a[2]).sum::<f64>() / TRIALS as f64
    };
    let v2ref = move |threads: usize| {
        let run = simulate_noisy(&spec, TRIALS, 1, threads, &|_| {}).expect("runs");
        run.v1_sq.mean + run.v2_sq.mean
    };
    Case {
        name: format!("simulate, {label}, 2^17 trials of N = {n}"),
        floor: Box::new(floor),
        v2ref: Box::new(v2ref),
    }
}

/// The rows of a set (`synth` without piston: N = 128, the default
/// photon noise) collected in memory, as Python's `synthesize` holds
/// them. Floor: the same draws from the same generators (one per unit of
/// ROWS_PER_UNIT rows), each row written once into a preallocated array,
/// units over the threads.
fn synth_rows(rows: u64) -> Case {
    use v2ref_core::simulator::ROWS_PER_UNIT;
    let model = Model::new(&Inputs::default()).expect("the default inputs");
    let n = model.samples();
    let (m, c) = (
        model.signal.modulated.clone(),
        model.signal.continuum.clone(),
    );
    let floor = move |threads: usize| {
        let poisson: Vec<PoissonSampler> = m
            .iter()
            .zip(&c)
            .map(|(m, c)| PoissonSampler::new(m + c, true).expect("mean >= 0"))
            .collect();
        let mut out = vec![0.0; rows as usize * n];
        in_pool(threads, || {
            out.par_chunks_mut(ROWS_PER_UNIT as usize * n)
                .enumerate()
                .for_each(|(u, unit)| {
                    let mut rng = unit_rng(1, u as u64);
                    for row in unit.chunks_exact_mut(n) {
                        for ((x, p), &c) in row.iter_mut().zip(&poisson).zip(&c) {
                            *x = p.sample(&mut rng) - c;
                        }
                    }
                })
        });
        out.iter().sum()
    };
    let v2ref = move |threads: usize| {
        let set = model.rows(rows, 1, threads).expect("rows");
        let mut out = Vec::with_capacity(rows as usize * n);
        set.stream(threads, 8, |block| {
            out.extend_from_slice(block);
            Ok(())
        })
        .expect("no sink error");
        out.iter().sum()
    };
    Case {
        name: format!("synth rows, {rows} rows of N = {n}"),
        floor: Box::new(floor),
        v2ref: Box::new(v2ref),
    }
}

/// One piston sequence of 2^20 samples (K band, 1" seeing, 18 m, 1 ms
/// steps). Floor: the same draws (two normals per Fourier mode, one
/// generator per block of 2^15 modes) times √(P Δν), then one real-output
/// inverse FFT of M points (realfft, on one thread: the 2-thread ratio is
/// against a floor whose transform does not scale).
fn piston_series() -> Case {
    use v2ref_core::piston::synthesize_series;
    use v2ref_core::piston::{spectrum::PistonSpectrum, turbulence::Turbulence};
    const LEN: usize = 1 << 20;
    const DT_S: f64 = 1e-3;
    let turb = Turbulence::from_seeing(1.0, 2.2, 10.0, None).expect("valid");
    let spectrum = std::sync::Arc::new(PistonSpectrum::new(turb, 0.45, 18.0).expect("valid"));
    spectrum.tabulate();
    let sp = spectrum.clone();
    let floor = move |threads: usize| {
        let psd = |nu: f64| sp.psd_um2_per_hz(nu);
        let series = in_pool(threads, || floor_series(&psd, DT_S, LEN, 1));
        series[..LEN].iter().map(|p| p * p).sum()
    };
    let v2ref = move |threads: usize| {
        let psd = |nu: f64| spectrum.psd_um2_per_hz(nu);
        let series = synthesize_series(&psd, DT_S, LEN, 1, threads).expect("valid");
        series[..LEN].iter().map(|p| p * p).sum()
    };
    Case {
        name: "piston sequence, 2^20 samples".into(),
        floor: Box::new(floor),
        v2ref: Box::new(v2ref),
    }
}

/// The floor of a piston sequence of `len` samples at step `dt_s` from
/// `seed` (what `synthesize_series` computes): two normal draws per
/// Fourier mode (one generator per block of 2^15 modes) times √(P Δν),
/// then one real-output inverse FFT of M points (realfft, one thread).
fn floor_series(psd: &(dyn Fn(f64) -> f64 + Sync), dt_s: f64, len: usize, seed: u64) -> Vec<f64> {
    use realfft::num_complex::Complex;
    const BLOCK: usize = 1 << 15;
    let m = v2ref_core::piston::sequence_length(len);
    let (half, dnu) = (m / 2, 1.0 / (m as f64 * dt_s));
    let mut spectrum_half = vec![Complex::new(0.0, 0.0); half + 1];
    spectrum_half[1..half]
        .par_chunks_mut(BLOCK)
        .enumerate()
        .for_each(|(u, block)| {
            let mut rng = unit_rng(seed, u as u64);
            for (j, w) in block.iter_mut().enumerate() {
                let nu = (1 + u * BLOCK + j) as f64 * dnu;
                // √2 Re Σ W_k e^{…}: the real-output transform adds each
                // mode and its conjugate, so each carries W_k / √2.
                let s = std::f64::consts::FRAC_1_SQRT_2 * (psd(nu) * dnu).sqrt();
                let g: f64 = rng.standard_normal();
                let h: f64 = rng.standard_normal();
                *w = Complex::new(s * g, s * h);
            }
        });
    let plan = RealFftPlanner::<f64>::new().plan_fft_inverse(m);
    let mut series = plan.make_output_vec();
    plan.process(&mut spectrum_half, &mut series)
        .expect("lengths from the plan");
    series
}

/// A piston Monte Carlo (`v2ref piston` at one frequency: 16 000 scans of
/// N = 128, 300 Hz, K band, 18 m, point source, sampled detector). Floor:
/// the same sequences' floors ([`floor_series`], same layout and seeds),
/// then per scan its reference (the mean piston), the fringe read from the
/// same fringe table at each sample, a real-input FFT and, per window, the
/// two sums and V1, V2 accumulated; one unit per sequence over the threads.
fn piston_run(scans: usize) -> Case {
    use v2ref_core::formalism::estimator::BIN_WINDOWS;
    use v2ref_core::formalism::observation::{Frequency, Observation};
    use v2ref_core::formalism::phase::SpectralPhase;
    use v2ref_core::formalism::source::Source;
    use v2ref_core::formalism::spectrum::{Band, Spectrum};
    use v2ref_core::piston::{
        scan_stride, sequence_seed, sequence_split, simulate_piston, Detector, FringeTable,
        RunSize, ScanSetup,
    };
    use v2ref_core::piston::{spectrum::PistonSpectrum, turbulence::Turbulence};
    let turb = Turbulence::from_seeing(1.0, 2.2, 10.0, None).expect("valid");
    let spectrum = std::sync::Arc::new(PistonSpectrum::new(turb, 0.45, 18.0).expect("valid"));
    spectrum.tabulate();
    let obs = Observation::new(
        Spectrum::flat(Band::k()),
        Source::Point,
        Frequency::BaselineM(18.0),
        SpectralPhase::zero(),
    )
    .expect("valid");
    let setup = ScanSetup::paper(300.0);
    let (sp, o) = (spectrum.clone(), obs.clone());
    let floor = move |threads: usize| {
        let n = setup.samples;
        let (k, stride) = (sequence_split(scans).0, scan_stride(&sp, &setup, scans));
        let psd = |nu: f64| sp.psd_um2_per_hz(nu);
        let bins: Vec<Vec<usize>> = BIN_WINDOWS
            .iter()
            .map(|w| w.bins(n, setup.dx_um, &o.spectrum).unwrap())
            .collect();
        let plan = RealFftPlanner::<f64>::new().plan_fft_forward(n);
        let per_sequence = |j: usize| scans / k + usize::from(j < scans % k);
        let parts: Vec<f64> = in_pool(threads, || {
            let sequences: Vec<Vec<f64>> = (0..k)
                .map(|j| {
                    let len = (per_sequence(j) - 1) * stride + n + 4;
                    floor_series(&psd, setup.sample_time_s(), len, sequence_seed(1, j))
                })
                .collect();
            let excursion = sequences
                .iter()
                .flatten()
                .fold(0.0_f64, |a, p| a.max(p.abs()));
            let half_scan = n as f64 * setup.dx_um / 2.0;
            let table = FringeTable::new(&o, half_scan + 2.0 * excursion + 1.0).expect("table");
            (0..k)
                .into_par_iter()
                .map(|j| {
                    let series = &sequences[j];
                    let mut input = plan.make_input_vec();
                    let mut spectrum_half = plan.make_output_vec();
                    let mut scratch = plan.make_scratch_vec();
                    let mut acc = 0.0;
                    for l in 0..per_sequence(j) {
                        let scan = &series[l * stride..l * stride + n];
                        let reference = scan.iter().sum::<f64>() / n as f64;
                        for (i, &p) in scan.iter().enumerate() {
                            let x = (i as f64 - (n / 2) as f64) * setup.dx_um + p - reference;
                            input[(i + n - n / 2) % n] = table.fringe(x);
                        }
                        plan.process_with_scratch(&mut input, &mut spectrum_half, &mut scratch)
                            .expect("lengths from the plan");
                        for window in &bins {
                            let (mut power, mut re, mut im) = (0.0, 0.0, 0.0);
                            for &b in window {
                                // A real row: B_{N−k} is the conjugate of B_k.
                                let z = match b <= n / 2 {
                                    true => spectrum_half[b],
                                    false => spectrum_half[n - b].conj(),
                                };
                                power += z.norm_sqr();
                                re += z.re;
                                im += z.im;
                            }
                            acc += power.sqrt() + (re * re + im * im).sqrt();
                        }
                    }
                    acc
                })
                .collect()
        });
        parts.iter().sum::<f64>() / scans as f64
    };
    let v2ref = move |threads: usize| {
        let size = RunSize {
            scans,
            seed: 1,
            threads,
        };
        let run = simulate_piston(&obs, &spectrum, &setup, &[Detector::Sampled], &size, None)
            .expect("runs");
        run[0].windows.iter().map(|w| w.v1.mean + w.v2.mean).sum()
    };
    Case {
        name: format!("piston run, {scans} scans of N = 128"),
        floor: Box::new(floor),
        v2ref: Box::new(v2ref),
    }
}
