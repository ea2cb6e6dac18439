//! The cost of spectral channels (issue 54): a C-channel `simulate_channels`
//! against C times the one-channel run, and the per-channel estimate
//! (`RowEstimator::estimate`, channel by channel) against its real-FFT
//! floor (`benches/floors/estimate_floor.rs`: per row a realfft forward of
//! N samples and the two sums over the positive bins).
//!
//! The set: H band (1.65 µm, 300 nm, flat), N = 256 samples of 0.5 µm,
//! 100 photons per sample shared between the channels, photon noise and 2
//! e⁻ of read noise, with and without the paper's piston at 300 Hz; C ∈
//! {1, 3, 6, 12} equal channels (`Channels::equal`, C = 1 is the whole
//! band), band window, `model` bias.
//!
//! ```sh
//! cargo bench --bench channels                  # criterion: times, one thread
//! benches/channels_callgrind.sh                 # instruction counts and ratios
//! # one side of one case, once (what the script counts):
//! target/release/deps/channels-* --count simulate-6-piston run
//! ```
//!
//! `--count CASE SIDE` runs SIDE of CASE once on one thread and exits:
//! `setup` builds the models (and, for an estimate case, draws the rows;
//! the piston spectrum's tables are computed there too), `run` is setup
//! then v2ref's work, `one` setup then the run of the first channel
//! alone, `each` setup then the run of each channel alone in turn (the
//! C lone runs a split costs at least), `floor` setup then the floor's, `cold` the models
//! and one run with nothing computed beforehand (the wall time of the
//! whole call is printed). `--list` prints the cases.

#[path = "floors/estimate_floor.rs"]
mod estimate_floor;

use criterion::{BenchmarkId, Criterion, Throughput};
use std::hint::black_box;
use std::time::Instant;
use v2ref_core::conformance::estimate::{BiasConvention, RowEstimator};
use v2ref_core::formalism::channels::Channels;
use v2ref_core::formalism::estimator::BinWindow;
use v2ref_core::montecarlo::in_pool_capped;
use v2ref_core::noise::calibrated::Trials;
use v2ref_core::simulator::channels::{channel_models, simulate_channels};
use v2ref_core::simulator::{Inputs, Model, PistonInputs, SpectrumInput};

/// The channel counts measured.
const COUNTS: [usize; 4] = [1, 3, 6, 12];
/// N, samples per row.
const SAMPLES: usize = 256;
/// Rows per channel of a `simulate` case.
const SIMULATE_ROWS: u64 = 4096;
/// Rows per channel of an `estimate` case.
const ESTIMATE_ROWS: u64 = 2048;

/// The H-band configuration, with the paper's piston at 300 Hz or none.
fn h_band(piston: bool) -> Inputs {
    Inputs {
        spectrum: SpectrumInput::Flat {
            wavelength_um: 1.65,
            bandwidth_nm: 300.0,
        },
        samples: SAMPLES,
        dx_um: 0.5,
        photons: 100.0,
        read_noise: 2.0,
        photon_noise: true,
        piston: piston.then(|| PistonInputs::paper(300.0)),
        ..Inputs::default()
    }
}

/// The models of `count` equal channels of the H band.
fn models(count: usize, piston: bool) -> Vec<Model> {
    let inputs = h_band(piston);
    let spectrum = inputs.spectrum.spectrum().expect("the H band");
    let channels = Channels::equal(&spectrum, count).expect("channels the scan resolves");
    channel_models(&inputs, &channels).expect("the channels' models")
}

/// The models with their piston spectrum's tables computed (a one-time
/// cost per spectrum, left out of the per-row cost).
fn tabulated_models(count: usize, piston: bool) -> Vec<Model> {
    let models = models(count, piston);
    for spectrum in models.iter().filter_map(|m| m.piston_spectrum.as_ref()) {
        spectrum.tabulate();
    }
    models
}

/// One `simulate_channels` of SIMULATE_ROWS rows per channel on `threads`
/// threads; the sum of the channels' means (kept: nothing optimized away).
fn simulate(models: &[Model], threads: usize) -> f64 {
    let size = Trials {
        trials: SIMULATE_ROWS,
        seed: 1,
        threads,
    };
    let run = simulate_channels(models, BinWindow::Band, BiasConvention::Model, size)
        .expect("the channels' run");
    run.v1_sq.iter().chain(&run.v2_sq).map(|s| s.mean).sum()
}

/// The rows of each channel (ESTIMATE_ROWS noisy rows without piston,
/// `M_i`) and its estimator over `window`.
struct EstimateSet {
    estimators: Vec<RowEstimator>,
    rows: Vec<Vec<f64>>,
}

fn estimate_set(count: usize, window: BinWindow) -> EstimateSet {
    let models = models(count, false);
    let rows = models
        .iter()
        .map(|m| {
            let mut data = Vec::with_capacity(ESTIMATE_ROWS as usize * SAMPLES);
            let set = m.rows(ESTIMATE_ROWS, 1, 1).expect("rows");
            set.stream(1, 8, |block| {
                data.extend_from_slice(block);
                Ok(())
            })
            .expect("no sink error");
            data
        })
        .collect();
    let estimators = models
        .iter()
        .map(|m| RowEstimator::new(m, window, BiasConvention::Model, true).expect("estimator"))
        .collect();
    EstimateSet { estimators, rows }
}

/// v2ref: each channel's rows through its `RowEstimator::estimate`, row
/// by row, channel by channel.
fn estimate_v2ref(set: &EstimateSet) -> f64 {
    let mut sum = 0.0;
    for (est, rows) in set.estimators.iter().zip(&set.rows) {
        for row in rows.chunks_exact(SAMPLES) {
            let e = est.estimate(row).expect("a row of N samples");
            sum += e.v1_sq_raw + e.v2_sq_raw;
        }
    }
    sum
}

/// The floor: per row a real-input FFT and the two sums, one thread.
fn estimate_floor(set: &EstimateSet) -> f64 {
    let sums = |rows: &Vec<f64>| {
        let out = in_pool_capped(1, || estimate_floor::estimate_floor(rows, SAMPLES));
        out.iter().map(|&(a, b)| a + b).sum::<f64>()
    };
    set.rows.iter().map(sums).sum()
}

/// The cases of `--count`: `simulate-C-{none,piston}`, `estimate-C-{band,positive}`.
fn case_names() -> Vec<String> {
    let mut names = Vec::new();
    for piston in ["none", "piston"] {
        names.extend(COUNTS.iter().map(|c| format!("simulate-{c}-{piston}")));
    }
    for window in ["band", "positive"] {
        names.extend(COUNTS.iter().map(|c| format!("estimate-{c}-{window}")));
    }
    names
}

/// Runs `side` of case `name` once on one thread; the checksum.
fn count(name: &str, side: &str) -> Result<f64, String> {
    let parts: Vec<&str> = name.split('-').collect();
    let (kind, c, variant) = match parts.as_slice() {
        [k, c, v] => (*k, c.parse::<usize>().map_err(|_| name.to_owned())?, *v),
        _ => return Err(format!("unknown case {name}")),
    };
    match (kind, variant, side) {
        ("simulate", v, "cold") => {
            let t = Instant::now();
            let sum = simulate(&models(c, v == "piston"), 1);
            println!(
                "{name}: {:.3} s (models and one run)",
                t.elapsed().as_secs_f64()
            );
            Ok(sum)
        }
        ("simulate", v, "setup" | "run" | "one" | "each") => {
            let models = tabulated_models(c, v == "piston");
            Ok(match side {
                "run" => simulate(&models, 1),
                "one" => simulate(&models[..1], 1),
                "each" => (0..c).map(|j| simulate(&models[j..=j], 1)).sum(),
                _ => 0.0,
            })
        }
        ("estimate", v, "setup" | "run" | "floor") => {
            let window = if v == "band" {
                BinWindow::Band
            } else {
                BinWindow::Positive
            };
            let set = estimate_set(c, window);
            Ok(match side {
                "run" => estimate_v2ref(&set),
                "floor" => estimate_floor(&set),
                _ => 0.0,
            })
        }
        _ => Err(format!("unknown case or side: {name} {side}")),
    }
}

fn bench_simulate(cr: &mut Criterion) {
    let mut g = cr.benchmark_group("channels_simulate");
    g.sample_size(10);
    g.warm_up_time(std::time::Duration::from_secs(1));
    g.measurement_time(std::time::Duration::from_secs(3));
    for piston in [false, true] {
        for c in COUNTS {
            let models = tabulated_models(c, piston);
            g.throughput(Throughput::Elements(c as u64 * SIMULATE_ROWS));
            let id = format!("{}/C{c}", if piston { "piston" } else { "none" });
            g.bench_function(BenchmarkId::new("simulate_channels", id), |b| {
                b.iter(|| black_box(simulate(&models, 1)))
            });
        }
    }
}

fn bench_estimate(cr: &mut Criterion) {
    let mut g = cr.benchmark_group("channels_estimate");
    g.sample_size(10);
    g.warm_up_time(std::time::Duration::from_secs(1));
    g.measurement_time(std::time::Duration::from_secs(2));
    for (wname, window) in [("band", BinWindow::Band), ("positive", BinWindow::Positive)] {
        for c in COUNTS {
            let set = estimate_set(c, window);
            g.throughput(Throughput::Elements(c as u64 * ESTIMATE_ROWS));
            let id = format!("{wname}/C{c}");
            g.bench_function(BenchmarkId::new("floor", &id), |b| {
                b.iter(|| black_box(estimate_floor(&set)))
            });
            g.bench_function(BenchmarkId::new("estimate", &id), |b| {
                b.iter(|| black_box(estimate_v2ref(&set)))
            });
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args
        .iter()
        .map(String::as_str)
        .collect::<Vec<_>>()
        .as_slice()
    {
        ["--list", ..] => println!("{}", case_names().join(" ")),
        ["--count", name, side, ..] => match count(name, side) {
            Ok(sum) => println!("checksum {sum:.6e}"),
            Err(e) => {
                eprintln!("channels: {e} (cases: {})", case_names().join(" "));
                std::process::exit(2);
            }
        },
        _ => {
            let mut cr = Criterion::default().configure_from_args();
            bench_simulate(&mut cr);
            bench_estimate(&mut cr);
            cr.final_summary();
        }
    }
}
