//! The paths of `benches/floors.rs`: for each, the data, the floor and
//! v2ref's code on the same data.

use super::Case;
use rayon::prelude::*;
use realfft::RealFftPlanner;
use v2ref::formalism::estimator::{positive_bins, BinWindow};
use v2ref::montecarlo::{in_pool, unit_rng, Rng};
use v2ref::noise::simulation::{simulate_noisy, NoisySpec, PoissonSampler, TRIALS_PER_UNIT};
use v2ref::noise::{example_interferogram, NoiseModel};
use v2ref::reproduction::cases::appendix_setup;
use v2ref::simulator::{Inputs, Model};

/// The paths, in the order they run.
pub const NAMES: [&str; 5] = [
    "estimate",
    "simulate-poisson",
    "simulate-gaussian",
    "synth",
    "piston-sequence",
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
        _ => None,
    }
}

/// `(Σ_{k∈K} |B_k|², |Σ_{k∈K} B_k|²)` over the positive bins 1 … ⌈N/2⌉ − 1
/// of a real row's half spectrum.
fn positive_sums(half: &[realfft::num_complex::Complex<f64>], n: usize) -> (f64, f64) {
    let (mut power, mut re, mut im) = (0.0, 0.0, 0.0);
    for b in &half[1..n.div_ceil(2)] {
        power += b.norm_sqr();
        re += b.re;
        im += b.im;
    }
    (power, re * re + im * im)
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
        Ok::<(), ()>(())
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
        let plan = RealFftPlanner::<f64>::new().plan_fft_forward(n);
        let mut out = vec![(0.0, 0.0); d.len() / n];
        in_pool(threads, || {
            out.par_chunks_mut(256)
                .zip(d.par_chunks(n * 256))
                .for_each(|(out, block)| {
                    let mut input = plan.make_input_vec();
                    let mut half = plan.make_output_vec();
                    let mut scratch = plan.make_scratch_vec();
                    for (o, row) in out.iter_mut().zip(block.chunks_exact(n)) {
                        input.copy_from_slice(row);
                        plan.process_with_scratch(&mut input, &mut half, &mut scratch)
                            .expect("lengths from the plan");
                        *o = positive_sums(&half, n);
                    }
                })
        });
        out.iter().map(|&(a, b)| a + b).sum()
    };
    let inputs = model.inputs.clone();
    let v2ref = move |threads: usize| {
        use v2ref::commands::estimate::{estimate_rows, estimator, RowsName};
        use v2ref::conformance::estimate::BiasConvention;
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
        bins: positive_bins(n),
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
            use rand_distr::{Distribution, StandardNormal};
            if poisson.is_empty() {
                for (x, &m) in row.iter_mut().zip(&s.modulated) {
                    let z: f64 = StandardNormal.sample(rng);
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
    use v2ref::simulator::rows::ROWS_PER_UNIT;
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
            Ok::<(), ()>(())
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
    use v2ref::piston::series::{sequence_length, synthesize_series};
    use v2ref::piston::turbulence::{PistonSpectrum, Turbulence};
    const LEN: usize = 1 << 20;
    const DT_S: f64 = 1e-3;
    let turb = Turbulence::from_seeing(1.0, 2.2, 10.0, None).expect("valid");
    let spectrum = std::sync::Arc::new(PistonSpectrum::new(turb, 0.45, 18.0).expect("valid"));
    spectrum.tabulate();
    let sp = spectrum.clone();
    let floor = move |threads: usize| {
        use rand_distr::{Distribution, StandardNormal};
        const BLOCK: usize = 1 << 15;
        let m = sequence_length(LEN);
        let (half, dnu) = (m / 2, 1.0 / (m as f64 * DT_S));
        let mut spectrum_half = vec![realfft::num_complex::Complex::new(0.0, 0.0); half + 1];
        in_pool(threads, || {
            spectrum_half[1..half]
                .par_chunks_mut(BLOCK)
                .enumerate()
                .for_each(|(u, block)| {
                    let mut rng = unit_rng(1, u as u64);
                    for (j, w) in block.iter_mut().enumerate() {
                        let nu = (1 + u * BLOCK + j) as f64 * dnu;
                        // Half the coefficient: the real-output transform
                        // adds each mode and its conjugate.
                        let s = 0.5 * (sp.psd_um2_per_hz(nu) * dnu).sqrt();
                        let g: f64 = StandardNormal.sample(&mut rng);
                        let h: f64 = StandardNormal.sample(&mut rng);
                        *w = realfft::num_complex::Complex::new(s * g, s * h);
                    }
                })
        });
        let plan = RealFftPlanner::<f64>::new().plan_fft_inverse(m);
        let mut series = plan.make_output_vec();
        plan.process(&mut spectrum_half, &mut series)
            .expect("lengths from the plan");
        let root2 = std::f64::consts::SQRT_2;
        series[..LEN].iter().map(|p| (root2 * p).powi(2)).sum()
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
