//! The truth of a conformance set (`synth`'s sidecar) as ranges of work
//! units ([`super::UnitJob`]): a unit is one unit of a block of the
//! reference run, its result the running statistics of every window,
//! convention and estimator; the reduction merges them in unit order as
//! [`truth`](crate::conformance::truth::truth) does.

use super::{check_range, key_of, unit_words, Partial, UnitJob};
use crate::conformance::estimate::BIAS_CONVENTIONS;
use crate::conformance::sidecar::Truth;
use crate::conformance::truth::{
    truth_from_units, truth_unit_count, truth_units, usable_windows, TruthSize, UnitStats,
};
use crate::error::Result;
use crate::simulator::{Inputs, Model, RowTiming};
use std::ops::Range;

/// The truth of a set of `size.rows` rows of `inputs` laid out as `layout`.
#[derive(Debug, Clone)]
pub struct TruthJob {
    /// The physical inputs.
    pub inputs: Inputs,
    /// Rows, seed, reference blocks, threads (per range).
    pub size: TruthSize,
    /// How the rows lie in time through the piston.
    pub layout: RowTiming,
}

impl TruthJob {
    /// Words of a unit's result for `windows` usable windows.
    fn unit_words(windows: usize) -> usize {
        windows * BIAS_CONVENTIONS.len() * 2 * super::STATS_WORDS
    }
}

impl UnitJob for TruthJob {
    type Answer = Truth;

    fn key(&self) -> u64 {
        let inputs = serde_json::to_string(&self.inputs).unwrap_or_default();
        let TruthSize {
            rows,
            seed,
            reference_blocks,
            ..
        } = self.size;
        let layout = &self.layout;
        key_of(format!("truth {inputs} {rows} {seed} {reference_blocks} {layout:?}").as_bytes())
    }

    fn unit_count(&self) -> Result<u64> {
        truth_unit_count(&Model::new(&self.inputs)?, self.size)
    }

    fn words_per_unit(&self) -> Result<usize> {
        Ok(Self::unit_words(
            usable_windows(&Model::new(&self.inputs)?).len(),
        ))
    }

    fn shape(&self) -> Result<(u64, usize)> {
        let model = Model::new(&self.inputs)?;
        let words = Self::unit_words(usable_windows(&model).len());
        Ok((truth_unit_count(&model, self.size)?, words))
    }

    fn run_range(&self, range: Range<u64>, progress: &(dyn Fn(u64) + Sync)) -> Result<Partial> {
        let model = Model::new(&self.inputs)?;
        check_range(&range, truth_unit_count(&model, self.size)?)?;
        let units = truth_units(&model, self.size, self.layout, range.clone(), progress)?;
        let mut words = Vec::new();
        for stats in units.iter().flatten().flatten().flatten() {
            super::put_stats(stats, &mut words);
        }
        Ok(Partial {
            key: self.key(),
            range,
            words,
        })
    }

    fn reduce(&self, partials: &[Partial]) -> Result<Truth> {
        let model = Model::new(&self.inputs)?;
        let windows = usable_windows(&model).len();
        let count = truth_unit_count(&model, self.size)?;
        let per_unit = Self::unit_words(windows);
        let units: Vec<UnitStats> = unit_words(partials, self.key(), count, per_unit)?
            .into_iter()
            .map(|w| take_unit(w, windows))
            .collect();
        truth_from_units(&model, self.size, &units)
    }
}

/// A unit's statistics from its words (of the length checked by the caller).
fn take_unit(words: &[u64], windows: usize) -> UnitStats {
    let stats = super::take_stats(words);
    let per_window = BIAS_CONVENTIONS.len() * 2;
    (0..windows)
        .map(|w| {
            (0..BIAS_CONVENTIONS.len())
                .map(|c| {
                    let at = w * per_window + 2 * c;
                    [stats[at], stats[at + 1]]
                })
                .collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::conformance::truth::truth;
    use crate::simulator::RowLayout;

    #[test]
    fn a_truth_split_in_ranges_gives_the_one_process_bits() {
        let inputs = Inputs {
            samples: 32,
            ..Inputs::default()
        };
        let size = TruthSize {
            rows: 2 * crate::simulator::ROWS_PER_UNIT + 5,
            seed: 11,
            reference_blocks: 8,
            threads: 1,
        };
        let job = TruthJob {
            inputs: inputs.clone(),
            size,
            layout: RowLayout::Sequences.into(),
        };
        let whole = truth(&Model::new(&inputs).unwrap(), size, &|_| {}).unwrap();
        assert_eq!(job.unit_count().unwrap(), 24);
        for cuts in [[0, 24].as_slice(), &[0, 1, 5, 24], &[0, 23, 24]] {
            let partials: Vec<Partial> = cuts
                .windows(2)
                .map(|w| job.run_range(w[0]..w[1], &|_| {}).unwrap())
                .collect();
            let bytes: Vec<Partial> = partials
                .iter()
                .map(|p| Partial::from_bytes(&p.to_bytes(), job.key()).unwrap())
                .collect();
            let reduced = job.reduce(&bytes).unwrap();
            assert_eq!(format!("{reduced:?}"), format!("{whole:?}"));
        }
        let other = TruthJob {
            size: TruthSize { seed: 12, ..size },
            ..job.clone()
        };
        let p = other.run_range(0..24, &|_| {}).unwrap();
        assert!(job.reduce(&[p]).is_err(), "another request's partial");
    }
}
