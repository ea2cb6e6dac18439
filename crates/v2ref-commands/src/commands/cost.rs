//! What a run will cost, predicted before it starts from cost laws
//! measured once: the edges say so when the prediction exceeds
//! [`NOTICE_S`] (the CLI on stderr, Python as a warning), before any work.
//!
//! Every constant below was measured on the project's build machine (two
//! cores of an x86-64 VM shared with other builds, release build,
//! 2026-11-25) as user CPU time, so core-seconds: the load of the machine
//! does not enter. A prediction divides the parallel parts by the cores a
//! run uses and adds the sequential parts. The laws are those of the
//! defaults (the K band, a 43 mas disk, 10 photons per sample); elsewhere
//! they hold to a factor of about 2, which is what a note of "about 19
//! days" needs.
//!
//! The parts of a run:
//! - the noise-free interferograms of the source and its calibrator, each
//!   N samples × a spectral grid that grows with the stroke
//!   ([`SpectralNodes::count`]): the N² cost of a long scan, sequential;
//! - the exact window statistics (only up to
//!   [`MAX_WINDOW_SAMPLES`] samples): N², sequential;
//! - the rows (trials, rows of a set, scans): linear, in parallel.

use crate::error::Result;
use crate::formalism::interferogram::{Sampling, SpectralNodes};
use crate::formalism::observation::Observation;
use crate::noise::calibrated::MAX_WINDOW_SAMPLES;
use crate::noise::simulation::PoissonSampler;
use crate::parameters::Physical;
use crate::simulator::Inputs;

/// Predicted durations beyond this are announced before the run, s.
pub const NOTICE_S: f64 = 60.0;

/// Core-seconds per sample × spectral node of one noise-free
/// interferogram: `Interferogram::synthesize` timed alone at N = 2048,
/// 4096, 8192, 16384 (2816 to 21920 nodes): 0.08, 0.32, 1.28, 5.09 s,
/// 1.39e-8 to 1.42e-8 each.
pub const SYNTHESIS_S_PER_SAMPLE_NODE: f64 = 1.42e-8;

/// Core-seconds per N² of the exact statistics of one window: `snr` less
/// its two interferograms, 0.12 s at N = 2048 and 0.51 s at 4096.
pub const WINDOW_STATS_S_PER_SAMPLE_SQ: f64 = 3.0e-8;

/// Core-seconds per sample of one noisy row drawn and estimated, when the
/// Poisson alias tables fit ([`ALIAS_TABLE_ENTRIES`]): `simulate` of 5e5
/// trials of 1024 samples, 4.53 s beyond its setup (the `--bias counts`
/// path: 1.1e-8).
pub const ROW_S_PER_SAMPLE: f64 = 9e-9;

/// The same when the alias tables do not fit (the counts drawn one by one
/// by `rand_distr::Poisson`): `simulate` of 8192 trials of 16384 samples,
/// 4.5 s beyond its setup (3.4e-8; the counts path 3.6e-8).
pub const ROW_DIRECT_S_PER_SAMPLE: f64 = 3.5e-8;

/// Entries of the Poisson alias tables a run may use (as
/// `noise::simulation` decides; the tables cover about λ ± 12√λ + 20).
pub const ALIAS_TABLE_ENTRIES: f64 = (1u64 << 20) as f64;

/// A row of a set's reference run against a row of the set (four
/// estimators each): 65536 rows of 1024 samples in 1.4 s, 2.1e-8 per
/// sample, 2.3 × [`ROW_S_PER_SAMPLE`].
pub const REFERENCE_ROW_FACTOR: f64 = 2.3;

/// Wall seconds per value written to a `.npy` file (the disk, not a
/// core): `synth` of 1e6 rows of 1024 samples, 39 s against 10.5 s of CPU.
pub const NPY_WRITE_S_PER_VALUE: f64 = 3.9e-8;

/// Core-seconds per value of the CSV copy (`synth --csv`): 1e5 rows of
/// 1024 samples, 6.3 s against 1.4 s without.
pub const CSV_WRITE_S_PER_VALUE: f64 = 5.6e-8;

/// Core-seconds per sample of a row estimated from a file (`estimate`):
/// 1e5 rows of 1024 samples from `.npy` to CSV in 0.49 s.
pub const ESTIMATE_S_PER_SAMPLE: f64 = 5e-9;

/// Core-seconds per sample of one scan through the piston (sequence,
/// scan, estimators): `piston` of 2000 scans at 4096 and 8192 samples
/// (2.79 s, 7.49 s) with the N² term below; `plan` of 16000 against 2000
/// scans on the default grid gives 8.1e-8.
pub const SCAN_S_PER_SAMPLE: f64 = 9e-8;

/// Core-seconds per N² of a piston run's tables (fringe table,
/// calibrations), from the same three `piston` runs.
pub const PISTON_TABLE_S_PER_SAMPLE_SQ: f64 = 7.7e-8;

/// Seconds of the piston spectrum's table, once per run (`piston` of 1000
/// scans of 128 samples: 0.70 s at 30, 300 and 3000 Hz).
pub const PISTON_SPECTRUM_S: f64 = 0.7;

/// Core-seconds of one grid point of `plan` beside its scans and
/// interferograms: the default grid (80 points) less its scans, 1.3 s.
pub const PLAN_POINT_S: f64 = 0.008;

/// A predicted duration and what it is of.
#[derive(Debug, Clone, PartialEq)]
pub struct Cost {
    /// Seconds, on the cores the run uses.
    pub seconds: f64,
    /// The run in words (for example "1e12 trials of 128 samples").
    pub what: String,
}

impl Cost {
    /// The note to print before the run when it is predicted to take more
    /// than [`NOTICE_S`].
    pub fn notice(&self) -> Option<String> {
        (self.seconds > NOTICE_S).then(|| {
            format!(
                "predicted to take about {} ({}, by the measured cost laws of v2ref_commands::commands::cost); Ctrl-C stops it and leaves no partial output",
                duration_words(self.seconds),
                self.what
            )
        })
    }
}

/// A duration in words: seconds, minutes, hours, days or years.
pub fn duration_words(s: f64) -> String {
    match s {
        s if s < 120.0 => format!("{s:.0} s"),
        s if s < 7200.0 => format!("{:.0} min", s / 60.0),
        s if s < 172_800.0 => format!("{:.1} h", s / 3600.0),
        s if s < 3.2e7 * 2.0 => format!("{:.0} days", s / 86400.0),
        s => format!("{:.0} years", s / 3.156e7),
    }
}

/// The cores a run of `threads` threads (0: all) uses.
fn cores(threads: usize) -> f64 {
    let all = std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get);
    (if threads == 0 { all } else { threads.min(all) }) as f64
}

/// Core-seconds of the noise-free interferograms of `obs` and of its
/// calibrator through `sampling`; refuses a sampling that aliases the
/// band, as the synthesis would (a cost is predicted for valid inputs
/// only, so that the error comes before any note).
pub fn interferograms_s(obs: &Observation, sampling: &Sampling) -> Result<f64> {
    sampling.check_aliasing(obs)?;
    let n = sampling.samples();
    let max_opd_um = (0..n).map(|i| sampling.opd_um(i).abs()).fold(0.0, f64::max);
    let nodes =
        SpectralNodes::count(obs, max_opd_um) + SpectralNodes::count(&obs.calibrator(), max_opd_um);
    Ok(SYNTHESIS_S_PER_SAMPLE_NODE * n as f64 * nodes as f64)
}

/// Core-seconds of `windows` exact window statistics at `n` samples (none
/// above `MAX_WINDOW_SAMPLES`).
fn window_stats_s(n: usize, windows: f64) -> f64 {
    if n <= MAX_WINDOW_SAMPLES {
        windows * WINDOW_STATS_S_PER_SAMPLE_SQ * (n as f64).powi(2)
    } else {
        0.0
    }
}

/// Core-seconds of one noisy row of `inputs` drawn and estimated.
fn row_s(inputs: &Inputs) -> f64 {
    let n = inputs.samples as f64;
    let (lo, hi) = PoissonSampler::support(inputs.photons);
    let tables_fit = !inputs.photon_noise || n * (hi - lo + 1.0) <= ALIAS_TABLE_ENTRIES;
    n * if tables_fit {
        ROW_S_PER_SAMPLE
    } else {
        ROW_DIRECT_S_PER_SAMPLE
    }
}

/// A count in words: `16384`, `1.678e7`, `1e12`.
fn count(n: f64) -> String {
    if n < 1e6 {
        return format!("{n:.0}");
    }
    let text = format!("{n:.3e}");
    match text.split_once('e') {
        Some((mantissa, exponent)) => {
            let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
            format!("{mantissa}e{exponent}")
        }
        None => text,
    }
}

/// `bias`: the finite scan, when asked (its two interferograms).
pub fn bias(p: &Physical, finite_scan: bool) -> Result<Cost> {
    let seconds = if crate::commands::bias::wants_finite_scan(p, finite_scan) {
        interferograms_s(&p.observation()?, &p.sampling()?)?
    } else {
        0.0
    };
    Ok(Cost {
        seconds,
        what: format!("a finite scan of {} samples", p.sampling()?.samples()),
    })
}

/// `snr`: the two interferograms and one window's statistics.
pub fn snr(p: &Physical) -> Result<Cost> {
    let sampling = p.sampling()?;
    let n = sampling.samples();
    Ok(Cost {
        seconds: interferograms_s(&p.observation()?, &sampling)? + window_stats_s(n, 1.0),
        what: format!("closed forms over {n} samples"),
    })
}

/// `simulate` of `trials` rows of `inputs` on `threads` threads: the
/// interferograms twice over (the model, the noise bias of the window)
/// and two windows' statistics, then the rows.
pub fn simulate(inputs: &Inputs, trials: u64, threads: usize) -> Result<Cost> {
    let setup = 2.0 * interferograms_s(&inputs.observation()?, &inputs.sampling()?)?
        + window_stats_s(inputs.samples, 2.0);
    Ok(Cost {
        seconds: setup + trials as f64 * row_s(inputs) / cores(threads),
        what: format!(
            "{} trials of {} samples",
            count(trials as f64),
            inputs.samples
        ),
    })
}

/// How a set is delivered: written to `.npy` (and CSV) or kept in memory.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum SetOutput {
    /// An array in memory (Python).
    Memory,
    /// A `.npy` file, and a CSV copy when `csv`.
    Files {
        /// Also CSV.
        csv: bool,
    },
}

/// `synth` of `rows` rows with `reference_rows` rows of reference run:
/// the truth's closed forms (6.5 times the interferograms: every window
/// and convention; measured 16.8 s at 8192 samples, 67 s at 16384), its
/// reference rows, the set's rows and their writing.
pub fn synth(
    inputs: &Inputs,
    (rows, reference_rows): (u64, u64),
    threads: usize,
    output: SetOutput,
) -> Result<Cost> {
    let n = inputs.samples as f64;
    let setup = 6.5 * interferograms_s(&inputs.observation()?, &inputs.sampling()?)?
        + window_stats_s(inputs.samples, 3.0);
    let row = row_s(inputs);
    let compute =
        (reference_rows as f64 * REFERENCE_ROW_FACTOR * row + rows as f64 * row) / cores(threads);
    let write = match output {
        SetOutput::Memory => 0.0,
        SetOutput::Files { csv } => {
            let per_value = NPY_WRITE_S_PER_VALUE + if csv { CSV_WRITE_S_PER_VALUE } else { 0.0 };
            rows as f64 * n * per_value
        }
    };
    Ok(Cost {
        seconds: setup + compute + write,
        what: format!("{} rows of {} samples", count(rows as f64), inputs.samples),
    })
}

/// `estimate` of `rows` rows of `inputs`: the model (1.6 times the
/// interferograms: 4.12 s at 8192 samples) and the rows.
pub fn estimate(inputs: &Inputs, rows: u64, threads: usize) -> Result<Cost> {
    let setup = 1.6 * interferograms_s(&inputs.observation()?, &inputs.sampling()?)?;
    let n = inputs.samples as f64;
    Ok(Cost {
        seconds: setup + rows as f64 * n * ESTIMATE_S_PER_SAMPLE / cores(threads),
        what: format!("{} rows of {} samples", count(rows as f64), inputs.samples),
    })
}

/// `piston` of `scans` scans of `samples` samples at each of `frequencies`
/// fringe frequencies.
pub fn piston(samples: usize, frequencies: usize, scans: usize, threads: usize) -> Cost {
    let n = samples as f64;
    let per_frequency = scans as f64 * n * SCAN_S_PER_SAMPLE + PISTON_TABLE_S_PER_SAMPLE_SQ * n * n;
    Cost {
        seconds: PISTON_SPECTRUM_S + frequencies as f64 * per_frequency / cores(threads),
        what: format!(
            "{} fringe frequencies x {} scans of {samples} samples",
            count(frequencies as f64),
            count(scans as f64)
        ),
    }
}

/// `plan` over a grid of `frequencies` fringe frequencies × the strokes
/// sampled as `strokes`, with `scans` scans per point (at most
/// [`crate::plan::POINT_SAMPLES`] samples): per point the
/// interferograms of two models and the noise bias (three times the
/// pair), its window's statistics and its piston Monte Carlo, the points
/// in parallel.
pub fn plan(
    obs: &Observation,
    (frequencies, strokes): (usize, &[Sampling]),
    scans: u64,
    threads: usize,
) -> Result<Cost> {
    let mut per_frequency = 0.0;
    for s in strokes {
        let n = s.samples();
        per_frequency += PLAN_POINT_S
            + 3.0 * interferograms_s(obs, s)?
            + window_stats_s(n, 1.0)
            + crate::plan::point_scans(scans, n) as f64 * n as f64 * SCAN_S_PER_SAMPLE;
    }
    let points = frequencies * strokes.len();
    Ok(Cost {
        seconds: PISTON_SPECTRUM_S + frequencies as f64 * per_frequency / cores(threads),
        what: format!(
            "{} grid points of {} scans",
            count(points as f64),
            count(scans as f64)
        ),
    })
}

/// `plan --verify`: the scans of the simulated observations through the
/// piston with noise (sequence, scan, noise, estimators), in parallel.
pub fn plan_verification(size: &crate::plan::verify::VerificationSize, threads: usize) -> Cost {
    let n = size.samples as f64;
    let scans = size.scans() as f64;
    let observations = scans / size.scans_per_observation.max(1) as f64;
    Cost {
        seconds: PISTON_SPECTRUM_S
            + n * n * PISTON_TABLE_S_PER_SAMPLE_SQ
            + scans * n * (SCAN_S_PER_SAMPLE + ROW_S_PER_SAMPLE) / cores(threads),
        what: format!(
            "{} observations of {} consecutive scans ({} scans of {} samples)",
            count(observations.floor()),
            size.scans_per_observation,
            count(scans),
            size.samples
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn inputs(samples: usize) -> Inputs {
        let p = Physical {
            samples,
            ..Physical::default()
        };
        p.inputs().expect("valid inputs")
    }

    #[test]
    fn only_a_run_of_more_than_a_minute_has_a_notice() {
        let cost = |seconds| Cost {
            seconds,
            what: "a run".into(),
        };
        assert_eq!(cost(59.0).notice(), None);
        let note = cost(7.0 * 86400.0).notice().expect("a week is announced");
        assert!(note.contains("about 7 days (a run"), "{note}");
        assert!(note.contains("Ctrl-C stops it"), "{note}");
    }

    #[test]
    fn counts_and_durations_read_as_words() {
        assert_eq!(count(16384.0), "16384");
        assert_eq!(count(16_777_216.0), "1.678e7");
        assert_eq!(count(1e12), "1e12");
        assert_eq!(duration_words(90.0), "90 s");
        assert_eq!(duration_words(600.0), "10 min");
        assert_eq!(duration_words(10_800.0), "3.0 h");
        assert_eq!(duration_words(1e9), "32 years");
    }

    #[test]
    fn the_defaults_are_quick_and_the_hostile_requests_are_announced() {
        let default = Physical::default();
        assert!(snr(&default).unwrap().seconds < 1.0);
        assert!(bias(&default, true).unwrap().seconds < 1.0);
        assert!(simulate(&inputs(128), 100_000, 0).unwrap().seconds < 10.0);
        let huge = Physical {
            samples: 1 << 24,
            ..Physical::default()
        };
        // N² synthesis: 2^24 samples take months, 1e5 minutes.
        assert!(snr(&huge).unwrap().seconds > 30.0 * 86400.0);
        let long_scan = Physical {
            samples: 100_000,
            ..Physical::default()
        };
        let finite = bias(&long_scan, true).unwrap().seconds;
        assert!((120.0..1200.0).contains(&finite), "{finite}");
        assert_eq!(bias(&long_scan, false).unwrap().seconds, 0.0);
        assert!(
            simulate(&inputs(128), 1_000_000_000_000, 0)
                .unwrap()
                .seconds
                > 86400.0
        );
        let rows = (1 << 24, 1 << 16);
        let memory = synth(&inputs(128), rows, 0, SetOutput::Memory).unwrap();
        let files = synth(&inputs(128), rows, 0, SetOutput::Files { csv: true }).unwrap();
        assert!(files.seconds > memory.seconds && files.seconds > NOTICE_S);
    }

    #[test]
    fn long_scans_cost_the_slower_poisson_draws() {
        // 10 photons a sample: the alias tables fit 8192 samples, not 16384.
        let per_sample = |n: usize| row_s(&inputs(n)) / n as f64;
        assert_eq!(per_sample(8192), ROW_S_PER_SAMPLE);
        assert_eq!(per_sample(16384), ROW_DIRECT_S_PER_SAMPLE);
    }
}
