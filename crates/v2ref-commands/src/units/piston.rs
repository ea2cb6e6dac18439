//! `piston` as ranges of work units ([`super::UnitJob`]): a unit is one
//! fringe frequency (its run is keyed by its value and independent of the
//! others), its result the numbers of its [`PistonRun`]; the reduction
//! puts the runs in order and builds the command's report.

use super::{check_range, key_of, unit_words, Partial, UnitJob};
use crate::commands::piston::{prepare, report, run_frequencies, PistonRequest};
use crate::error::{Error, Result};
use crate::formalism::estimator::BIN_WINDOWS;
use crate::montecarlo::Summary;
use crate::parameters::Physical;
use crate::piston::{PistonRun, WindowResult};
use crate::report::piston::PistonReport;
use std::ops::Range;

/// The request of `v2ref piston` (without an observation length).
#[derive(Debug, Clone)]
pub struct PistonJob {
    /// The physical inputs.
    pub physical: Physical,
    /// Frequencies, scans, seed, threads (per range), …
    pub request: PistonRequest,
}

/// Words of a [`Summary`], of a window's result, of a run.
const SUMMARY_WORDS: usize = 7;
const WINDOW_WORDS: usize = 4 + 2 * SUMMARY_WORDS;
const RUN_WORDS: usize = 7 + WINDOW_WORDS * BIN_WINDOWS.len();

impl UnitJob for PistonJob {
    type Answer = PistonReport;

    fn key(&self) -> u64 {
        let physical = serde_json::to_string(&self.physical).unwrap_or_default();
        let request = PistonRequest {
            threads: 0,
            ..self.request.clone()
        };
        // The physical inputs name a spectrum CSV by its path: its table
        // keys the request too.
        let table = super::spectrum_key_text(&self.physical);
        key_of(format!("piston {physical} {table} {request:?}").as_bytes())
    }

    fn unit_count(&self) -> Result<u64> {
        Ok(prepare(&self.physical, &self.request)?.fringe_hz.len() as u64)
    }

    fn words_per_unit(&self) -> Result<usize> {
        Ok(RUN_WORDS)
    }

    fn run_range(&self, range: Range<u64>, progress: &(dyn Fn(u64) + Sync)) -> Result<Partial> {
        let prepared = prepare(&self.physical, &self.request)?;
        check_range(&range, prepared.fringe_hz.len() as u64)?;
        let freqs = &prepared.fringe_hz[range.start as usize..range.end as usize];
        let runs = run_frequencies(
            &prepared,
            &self.physical,
            &self.request,
            freqs,
            Some(progress),
        )?;
        let mut words = Vec::with_capacity(runs.len() * RUN_WORDS);
        runs.iter().for_each(|r| put_run(r, &mut words));
        Ok(Partial {
            key: self.key(),
            range,
            words,
        })
    }

    fn reduce(&self, partials: &[Partial]) -> Result<PistonReport> {
        let prepared = prepare(&self.physical, &self.request)?;
        let units = prepared.fringe_hz.len() as u64;
        let runs: Vec<PistonRun> = unit_words(partials, self.key(), units, RUN_WORDS)?
            .into_iter()
            .map(|w| take_run(w, &prepared.detector, self.request.scans))
            .collect::<Result<_>>()?;
        report(&prepared, &self.physical, &self.request, &runs)
    }
}

fn put_summary(s: &Summary, out: &mut Vec<u64>) {
    out.push(s.count);
    let floats = [
        s.mean,
        s.stderr_mean,
        s.var,
        s.stderr_var,
        s.std,
        s.stderr_std,
    ];
    out.extend(floats.map(f64::to_bits));
}

fn take_summary(w: &[u64]) -> Summary {
    let f = |i: usize| f64::from_bits(w[i]);
    Summary {
        count: w[0],
        mean: f(1),
        stderr_mean: f(2),
        var: f(3),
        stderr_var: f(4),
        std: f(5),
        stderr_std: f(6),
    }
}

/// The numbers of a run (its detector and windows are the request's).
fn put_run(r: &PistonRun, out: &mut Vec<u64>) {
    out.extend([r.sequences as u64, r.seed]);
    let floats = [
        r.fringe_hz,
        r.scan_time_s,
        r.piston_rms_um,
        r.residual_rms_um,
        r.span_correlation_times,
    ];
    out.extend(floats.map(f64::to_bits));
    for w in &r.windows {
        let floats = [
            w.v1_no_piston,
            w.v2_no_piston,
            w.v1_effective_scans,
            w.v2_effective_scans,
        ];
        out.extend(floats.map(f64::to_bits));
        put_summary(&w.v1, out);
        put_summary(&w.v2, out);
    }
}

fn take_run(w: &[u64], detector: &crate::piston::Detector, scans: usize) -> Result<PistonRun> {
    if w.len() != RUN_WORDS {
        return Err(Error::Invalid {
            param: "partial",
            reason: "a unit's result of the wrong length".into(),
        });
    }
    let f = |i: usize| f64::from_bits(w[i]);
    let windows = BIN_WINDOWS
        .iter()
        .zip(w[7..].chunks_exact(WINDOW_WORDS))
        .map(|(&window, w)| WindowResult {
            window,
            v1_no_piston: f64::from_bits(w[0]),
            v2_no_piston: f64::from_bits(w[1]),
            v1_effective_scans: f64::from_bits(w[2]),
            v2_effective_scans: f64::from_bits(w[3]),
            v1: take_summary(&w[4..4 + SUMMARY_WORDS]),
            v2: take_summary(&w[4 + SUMMARY_WORDS..]),
        })
        .collect();
    Ok(PistonRun {
        fringe_hz: f(2),
        detector: *detector,
        scans,
        sequences: w[0] as usize,
        seed: w[1],
        scan_time_s: f(3),
        piston_rms_um: f(4),
        residual_rms_um: f(5),
        span_correlation_times: f(6),
        windows,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::commands::piston::run;
    use crate::piston::spectrum::PistonPsdModel;

    #[test]
    fn three_frequencies_split_in_1_2_3_ranges_give_the_report_bits() {
        let physical = Physical {
            samples: 32,
            ..Physical::DEFAULT
        };
        let request = PistonRequest {
            fringe_hz: vec![300.0, 700.0, 1000.0],
            bins: crate::formalism::estimator::BinWindow::Positive,
            scans: 40,
            seed: 3,
            threads: 2,
            psd: PistonPsdModel::TwoAperture,
            wind_angle_deg: 0.0,
            observation: None,
        };
        let job = PistonJob { physical, request };
        let prepared = prepare(&job.physical, &job.request).unwrap();
        let whole = run(&prepared, &job.physical, &job.request, None).unwrap();
        for cuts in [[0, 3].as_slice(), &[0, 1, 3], &[0, 1, 2, 3]] {
            let partials: Vec<Partial> = cuts
                .windows(2)
                .map(|w| job.run_range(w[0]..w[1], &|_| {}).unwrap())
                .collect();
            let reduced = job.reduce(&partials).unwrap();
            assert_eq!(format!("{reduced:?}"), format!("{whole:?}"));
        }
        let other = PistonJob {
            request: PistonRequest {
                seed: 4,
                ..job.request.clone()
            },
            ..job.clone()
        };
        assert!(other
            .reduce(&[job.run_range(0..3, &|_| {}).unwrap()])
            .is_err());
    }

    #[test]
    fn the_key_hashes_the_spectrum_table_not_the_file_name() {
        use crate::formalism::spectrum::Spectrum;
        use crate::parameters::SpectrumFile;
        let job = |weight: f64| {
            let table = Spectrum::tabulated(vec![0.4, 0.45, 0.5], vec![1.0, weight, 1.0]).unwrap();
            let physical = Physical {
                spectrum_csv: Some(SpectrumFile::new(std::path::Path::new("s.csv"), table)),
                ..Physical::DEFAULT
            };
            let request = PistonRequest {
                fringe_hz: vec![300.0],
                bins: crate::formalism::estimator::BinWindow::Positive,
                scans: 40,
                seed: 3,
                threads: 1,
                psd: PistonPsdModel::TwoAperture,
                wind_angle_deg: 0.0,
                observation: None,
            };
            PistonJob { physical, request }
        };
        // One file name, its table edited: another request.
        assert_eq!(job(2.0).key(), job(2.0).key());
        assert_ne!(job(2.0).key(), job(3.0).key());
    }
}
