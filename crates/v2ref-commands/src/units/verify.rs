//! `plan --verify`'s simulated observations as ranges of work units
//! ([`super::UnitJob`]). The verification scans [`SEQUENCES`] independent
//! piston sequences, drawn in batches of as many sequences as fit the
//! piston's memory limit together (one generator per batch: the batch is
//! what one seed computes, so it is the unit; a verification long enough
//! to need the cluster has one sequence per batch, 16 units). A unit's
//! result is, for each of its sequences and for V1² and V2², the running
//! statistics of its observations' means (the blocks of n consecutive
//! scans); the reduction pools them in sequence order as
//! [`verify`](crate::plan::verify::verify) does.

use super::STATS_WORDS;
use super::{check_range, key_of, put_stats, take_stats, unit_words, Partial, UnitJob};
use crate::conformance::estimate::RowEstimator;
use crate::error::Result;
use crate::formalism::estimator::BinWindow;
use crate::montecarlo::{in_pool, replicated_summary, RunningStats, Steps, Summary};
use crate::plan::observation::{batch_rows, sequences_per_batch};
use crate::plan::verify::{size_at, verify_model, verify_seed, VerificationSize, SEQUENCES};
use crate::plan::PlanInputs;
use crate::simulator::Model;
use std::ops::Range;

/// The verification of a plan's point.
#[derive(Debug, Clone)]
pub struct VerifyJob {
    /// The plan's inputs.
    pub inputs: PlanInputs,
    /// f, Hz, of the point verified.
    pub fringe_hz: f64,
    /// Δx, µm.
    pub stroke_um: f64,
    /// The simulation's shape.
    pub size: VerificationSize,
    /// Threads per range (0: all).
    pub threads: usize,
}

impl VerifyJob {
    /// The verification at `(f, Δx, n)` ([`size_at`]) with `observations`
    /// observations.
    pub fn new(
        inputs: PlanInputs,
        point: (f64, f64, u64),
        observations: u64,
        threads: usize,
    ) -> Result<VerifyJob> {
        let sky = inputs.atmosphere.spectrum(inputs.instrument.baseline_m)?;
        let size = size_at(&inputs, &sky, point, observations)?;
        Ok(VerifyJob {
            inputs,
            fringe_hz: point.0,
            stroke_um: point.1,
            size,
            threads,
        })
    }

    /// The model scanned and the sequences per batch (as
    /// `ContiguousScans::simulate` batches them).
    fn setup(&self) -> Result<(Model, usize)> {
        let sky = self
            .inputs
            .atmosphere
            .spectrum(self.inputs.instrument.baseline_m)?;
        let model = verify_model(&self.inputs, &sky, self.fringe_hz, self.stroke_um)?;
        let per_batch = sequences_per_batch(
            model.samples(),
            self.size.scans_per_sequence,
            self.size.stride,
        );
        Ok((model, per_batch))
    }

    /// Words of a unit: per sequence of a batch, V1² and V2²'s statistics.
    fn words(per_batch: usize) -> usize {
        per_batch * 2 * STATS_WORDS
    }

    /// Appends the words of batch `b`: each sequence's statistics of its
    /// observations' means (a batch short of `per_batch` sequences, the
    /// last, padded with empty statistics).
    fn batch(
        &self,
        (model, per_batch): (&Model, usize),
        b: u64,
        progress: &(dyn Fn(u64) + Sync),
        words: &mut Vec<u64>,
    ) -> Result<()> {
        let est = RowEstimator::new(model, BinWindow::Positive, self.inputs.bias, true)?;
        let first = b as usize * per_batch;
        let k = per_batch.min(SEQUENCES - first);
        let per_sequence = self.size.scans_per_sequence;
        let seed = verify_seed(&self.inputs, self.fringe_hz, self.stroke_um);
        let rows = (k * per_sequence) as u64;
        let set = batch_rows(model, seed, first, (k, per_sequence, self.size.stride))?;
        let n = model.samples();
        let mut values: Vec<[f64; 2]> = Vec::with_capacity(rows as usize);
        set.fold_units(
            0,
            |_, block| {
                let mut steps = Steps::new(progress, n);
                let out = block
                    .chunks_exact(n)
                    .map(|row| {
                        steps.step()?;
                        let e = est.estimate(row)?;
                        Ok([e.v1_sq, e.v2_sq])
                    })
                    .collect::<Result<Vec<_>>>()?;
                steps.finish()?;
                Ok(out)
            },
            |block: Vec<[f64; 2]>| values.extend(block),
        )?;
        let obs = (self.size.scans_per_observation as usize).clamp(1, per_sequence.max(1));
        let mut sequences = values.chunks(per_sequence);
        for _ in 0..per_batch {
            let seq = sequences.next().unwrap_or(&[]);
            for e in 0..2 {
                let mut g = RunningStats::default();
                for block in seq.chunks_exact(obs) {
                    // `+ 0.0` as `block_means` adds the `model` offset it
                    // leaves out here: the same sums to the bit.
                    let sum: f64 = block.iter().map(|s| s[e] + 0.0).sum();
                    g.push(sum / obs as f64);
                }
                put_stats(&g, words);
            }
        }
        Ok(())
    }
}

impl UnitJob for VerifyJob {
    /// The observations' means of V1² and V2² (`block_means`).
    type Answer = [Summary; 2];

    fn key(&self) -> u64 {
        let inputs = serde_json::to_string(&self.inputs).unwrap_or_default();
        let (f, s, size) = (self.fringe_hz, self.stroke_um, &self.size);
        key_of(format!("plan-verify {inputs} {f:?} {s:?} {size:?}").as_bytes())
    }

    fn unit_count(&self) -> Result<u64> {
        Ok(SEQUENCES.div_ceil(self.setup()?.1) as u64)
    }

    fn words_per_unit(&self) -> Result<usize> {
        Ok(Self::words(self.setup()?.1))
    }

    fn shape(&self) -> Result<(u64, usize)> {
        let per_batch = self.setup()?.1;
        Ok((SEQUENCES.div_ceil(per_batch) as u64, Self::words(per_batch)))
    }

    fn run_range(&self, range: Range<u64>, progress: &(dyn Fn(u64) + Sync)) -> Result<Partial> {
        let (model, per_batch) = self.setup()?;
        check_range(&range, SEQUENCES.div_ceil(per_batch) as u64)?;
        let mut words =
            Vec::with_capacity((range.end - range.start) as usize * Self::words(per_batch));
        in_pool(self.threads, || {
            for b in range.clone() {
                self.batch((&model, per_batch), b, progress, &mut words)?;
            }
            Ok(())
        })?;
        Ok(Partial {
            key: self.key(),
            range,
            words,
        })
    }

    fn reduce(&self, partials: &[Partial]) -> Result<[Summary; 2]> {
        let (units, per_unit) = self.shape()?;
        let words: Vec<u64> = unit_words(partials, self.key(), units, per_unit)?.concat();
        // Per sequence [V1², V2²], the padding of the last batch dropped.
        let stats = take_stats(&words);
        let groups: Vec<&[RunningStats]> = stats.chunks_exact(2).take(SEQUENCES).collect();
        Ok([0, 1].map(|e| {
            let of_e: Vec<RunningStats> = groups.iter().map(|g| g[e]).collect();
            replicated_summary(&of_e)
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::commands::plan::{prepare, PlanRequest};
    use crate::conformance::estimate::BiasConvention;
    use crate::parameters::Physical;
    use crate::plan::observation::ContiguousScans;

    /// A K-band point source on 50 m with long dead times (sequences long
    /// in samples, few scans to estimate).
    fn inputs() -> PlanInputs {
        let p = Physical {
            baseline_m: Some(50.0),
            read_noise: 2.0,
            ..Physical::default()
        };
        let req = PlanRequest {
            samples_per_fringe: 4.0,
            photon_rate_per_s: 2e6,
            magnitude: None,
            dead_time_s: 0.1,
            frame_rate_hz: None,
            fringe_hz: vec![800.0],
            stroke_um: vec![32.0],
            target_sigma_v2: Some(3e-3),
            time_budget_s: None,
            scans: 400,
            seed: 3,
            diameter_err_mas: 0.0,
            bias: BiasConvention::Counts,
        };
        prepare(&p, &req).unwrap().inputs
    }

    /// The one process's means: `verify`'s own simulation.
    fn one_process(job: &VerifyJob) -> [Summary; 2] {
        let (model, _) = job.setup().unwrap();
        let size = &job.size;
        let seed = verify_seed(&job.inputs, job.fringe_hz, job.stroke_um);
        let layout = (size.scans_per_sequence, size.stride, size.sample_time_s);
        let bias = job.inputs.bias;
        let scans = ContiguousScans::simulate(&model, None, bias, layout, seed, &|_| {}).unwrap();
        scans.block_means(size.scans_per_observation as usize, false)
    }

    #[test]
    fn a_verification_split_in_batches_gives_the_one_process_bits() {
        // Sequences of just over 2^24 / 16 samples: batches of 15 and 1
        // (padded), two units.
        let job = VerifyJob::new(inputs(), (800.0, 32.0, 8), 16 * 350, 1).unwrap();
        assert_eq!(job.shape().unwrap().0, 2, "{:?}", job.size);
        let whole = one_process(&job);
        let partials: Vec<Partial> = [0..1, 1..2]
            .into_iter()
            .map(|r| job.run_range(r, &|_| {}).unwrap())
            .map(|p| Partial::from_bytes(&p.to_bytes(), job.key()).unwrap())
            .collect();
        let reduced = job.reduce(&partials).unwrap();
        assert_eq!(format!("{reduced:?}"), format!("{whole:?}"));
        assert_eq!(reduced[0].count, 16 * 350);
        // Power: another seed's units are refused, another point differs.
        let mut other = job.clone();
        other.inputs.seed = 4;
        assert!(job
            .reduce(&[partials[0].clone(), other.run_range(1..2, &|_| {}).unwrap()])
            .is_err());
        assert!(job.reduce(&partials[..1]).is_err(), "a unit missing");
    }
}
