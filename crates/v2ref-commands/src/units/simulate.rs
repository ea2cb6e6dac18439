//! `simulate` as ranges of work units ([`super::UnitJob`]): each unit's
//! accumulators ([`UnitStats`], one per piston sequence) travel as words,
//! and the reduction merges them in unit order as
//! [`simulate`](crate::simulator::simulate) does.

use super::{check_range, key_of, unit_words, Partial, UnitJob};
use crate::error::{Error, Result};
use crate::noise::calibrated::Trials;
use crate::report::simulator::{check_trials, Estimation};
use crate::simulator::run::{merge, SimulationUnits, UnitStats};
use crate::simulator::{Inputs, Model, SimulationRun};
use std::ops::Range;

/// The request of `v2ref simulate`.
#[derive(Debug, Clone)]
pub struct SimulateJob {
    /// The physical inputs.
    pub inputs: Inputs,
    /// Bins, bias convention, formula.
    pub estimation: Estimation,
    /// Rows, seed, threads (per range).
    pub size: Trials,
}

/// Words per [`UnitStats`].
const UNIT_STATS_WORDS: usize = 4 * super::STATS_WORDS;

impl SimulateJob {
    /// The library's units of this request (the model built here).
    fn with_units<T>(&self, f: impl FnOnce(&SimulationUnits) -> Result<T>) -> Result<T> {
        check_trials(self.size.trials)?;
        let model = Model::new(&self.inputs)?;
        let e = &self.estimation;
        let units = SimulationUnits::new(&model, e.window, e.bias, e.formula, self.size)?;
        f(&units)
    }
}

impl UnitJob for SimulateJob {
    type Answer = SimulationRun;

    fn key(&self) -> u64 {
        let inputs = serde_json::to_string(&self.inputs).unwrap_or_default();
        let Trials { trials, seed, .. } = self.size;
        key_of(format!("simulate {inputs} {:?} {trials} {seed}", self.estimation).as_bytes())
    }

    fn unit_count(&self) -> Result<u64> {
        self.with_units(|u| Ok(u.units()))
    }

    fn words_per_unit(&self) -> Result<usize> {
        Ok(self.shape()?.1)
    }

    fn shape(&self) -> Result<(u64, usize)> {
        self.with_units(|u| Ok((u.units(), u.empty().len() * UNIT_STATS_WORDS)))
    }

    fn run_range(&self, range: Range<u64>, progress: &(dyn Fn(u64) + Sync)) -> Result<Partial> {
        self.with_units(|units| {
            check_range(&range, units.units())?;
            let mut words = Vec::new();
            units.fold(range.clone(), progress, |part| {
                part.iter().for_each(|s| put_unit_stats(s, &mut words))
            })?;
            Ok(Partial {
                key: self.key(),
                range,
                words,
            })
        })
    }

    fn reduce(&self, partials: &[Partial]) -> Result<SimulationRun> {
        self.with_units(|units| {
            let mut total = units.empty();
            let per_unit = total.len() * UNIT_STATS_WORDS;
            for words in unit_words(partials, self.key(), units.units(), per_unit)? {
                let part: Vec<UnitStats> = words
                    .chunks_exact(UNIT_STATS_WORDS)
                    .map(take_unit_stats)
                    .collect::<Result<_>>()?;
                merge(&mut total, &part);
            }
            Ok(units.finish(&total))
        })
    }
}

fn put_unit_stats(s: &UnitStats, out: &mut Vec<u64>) {
    for r in [&s.v1_sq, &s.v2_sq, &s.v1, &s.v2] {
        super::put_stats(r, out);
    }
}

fn take_unit_stats(words: &[u64]) -> Result<UnitStats> {
    let stats = super::take_stats(words);
    match stats[..] {
        [v1_sq, v2_sq, v1, v2] => Ok(UnitStats {
            v1_sq,
            v2_sq,
            v1,
            v2,
        }),
        _ => Err(Error::Invalid {
            param: "partial",
            reason: "a unit's result of the wrong length".into(),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::conformance::estimate::BiasConvention;
    use crate::formalism::estimator::BinWindow;
    use crate::noise::Formula;
    use crate::simulator::{simulate, PistonInputs};

    /// Splits `0..units` into `parts` ranges as evenly as can be.
    fn split(units: u64, parts: u64) -> Vec<Range<u64>> {
        let cuts: Vec<u64> = (0..=parts).map(|i| units * i / parts).collect();
        cuts.windows(2)
            .filter(|w| w[0] < w[1])
            .map(|w| w[0]..w[1])
            .collect()
    }

    fn same_bits_split(job: &SimulateJob) {
        let e = &job.estimation;
        let model = Model::new(&job.inputs).unwrap();
        let whole = simulate(&model, e.window, e.bias, e.formula, job.size, &|_| {}).unwrap();
        let units = job.unit_count().unwrap();
        assert!(units >= 7, "{units} units: too few to split in 7");
        for parts in [1, 2, 7] {
            let partials: Vec<Partial> = split(units, parts)
                .into_iter()
                .map(|r| job.run_range(r, &|_| {}).unwrap())
                .map(|p| Partial::from_bytes(&p.to_bytes(), job.key()).unwrap())
                .collect();
            let reduced = job.reduce(&partials).unwrap();
            // Debug prints each float's shortest exact form: equal text,
            // equal bits (and -0 differs from 0).
            assert_eq!(
                format!("{reduced:?}"),
                format!("{whole:?}"),
                "{parts} ranges"
            );
        }
    }

    fn job(inputs: Inputs, bias: BiasConvention, trials: u64) -> SimulateJob {
        SimulateJob {
            inputs,
            estimation: Estimation {
                window: BinWindow::Positive,
                bias,
                formula: Formula::Exact,
            },
            size: Trials {
                trials,
                seed: 11,
                threads: 2,
            },
        }
    }

    #[test]
    fn fast_path_split_in_1_2_7_ranges_gives_the_same_bits() {
        let inputs = Inputs {
            samples: 32,
            ..Inputs::default()
        };
        same_bits_split(&job(inputs, BiasConvention::Model, 7 * 8192 + 100));
    }

    #[test]
    fn row_path_with_piston_split_gives_the_same_bits() {
        let inputs = Inputs {
            samples: 32,
            piston: Some(PistonInputs::paper(300.0)),
            ..Inputs::default()
        };
        same_bits_split(&job(inputs, BiasConvention::Counts, 7 * 8192 + 3));
    }

    #[test]
    fn refuses_partials_of_another_request_or_an_incomplete_set() {
        let inputs = Inputs {
            samples: 16,
            ..Inputs::default()
        };
        let a = job(inputs, BiasConvention::Model, 3 * 8192);
        let b = SimulateJob {
            size: Trials { seed: 12, ..a.size },
            ..a.clone()
        };
        assert_ne!(a.key(), b.key());
        let threads = SimulateJob {
            size: Trials {
                threads: 1,
                ..a.size
            },
            ..a.clone()
        };
        assert_eq!(a.key(), threads.key());
        let p0 = a.run_range(0..1, &|_| {}).unwrap();
        let p1 = a.run_range(1..3, &|_| {}).unwrap();
        assert!(b.reduce(&[p0.clone(), p1.clone()]).is_err());
        assert!(a.reduce(std::slice::from_ref(&p1)).is_err());
        assert!(a.reduce(&[p1, p0]).is_err());
        assert!(a.run_range(2..4, &|_| {}).is_err());
    }
}
