//! The covariance across channels of one estimator's per-row values, and
//! the honest error of a weighted mean of the channels drawn from it.
//!
//! Each row gives one value x_c per channel c. The rows fall in independent
//! groups (the piston sequences they were cut from, or, without piston,
//! their work unit modulo [`NOISE_GROUPS`]); each group keeps its count and
//! the shifted sums `Σ (x_c − a_c)` and `Σ (x_c − a_c)(x_d − a_d)`, the
//! shift a_c being the channel's noise-free value (so the sums of small
//! deviations do not cancel). The covariance Σ is that of all the rows
//! pooled; the variance of a combination `Σ_c w_c x_c` is `wᵀ Σ w`, with a
//! standard error by the delete-one-group jackknife (valid however the rows
//! of a group correlate).

use serde::Serialize;

/// Groups of the rows of a run without piston (their rows are independent,
/// any grouping will do; 16 give the jackknife 15 degrees of freedom).
pub const NOISE_GROUPS: usize = 16;

/// One group's shifted sums.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GroupSums {
    /// Rows.
    pub count: u64,
    /// `Σ (x_c − a_c)` per channel.
    pub first: Vec<f64>,
    /// `Σ (x_c − a_c)(x_d − a_d)`, row-major C × C.
    pub second: Vec<f64>,
}

impl GroupSums {
    fn empty(channels: usize) -> GroupSums {
        GroupSums {
            count: 0,
            first: vec![0.0; channels],
            second: vec![0.0; channels * channels],
        }
    }

    fn add(&mut self, other: &GroupSums) {
        self.count += other.count;
        self.first
            .iter_mut()
            .zip(&other.first)
            .for_each(|(a, b)| *a += b);
        self.second
            .iter_mut()
            .zip(&other.second)
            .for_each(|(a, b)| *a += b);
    }
}

/// The per-group sums of one estimator over C channels.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChannelMoments {
    /// a_c, the shift of each channel.
    pub shift: Vec<f64>,
    /// The groups' sums.
    pub groups: Vec<GroupSums>,
}

impl ChannelMoments {
    /// Empty sums for `groups` groups of `shift.len()` channels.
    pub fn new(shift: Vec<f64>, groups: usize) -> ChannelMoments {
        let c = shift.len();
        ChannelMoments {
            shift,
            groups: vec![GroupSums::empty(c); groups],
        }
    }

    /// Adds one row's values `x` (one per channel) to group `g`.
    pub fn push(&mut self, g: usize, x: &[f64]) {
        let mut d = Vec::with_capacity(x.len());
        self.deviations_into(x.iter().copied(), &mut d);
        self.push_deviations(g, &d);
    }

    /// `d_c = x_c − a_c` of one row's values `x` into `d` (cleared first):
    /// what [`ChannelMoments::push_deviations`] takes. The hot loop keeps
    /// `d` from row to row instead of allocating it per row.
    pub(crate) fn deviations_into(&self, x: impl Iterator<Item = f64>, d: &mut Vec<f64>) {
        d.clear();
        d.extend(x.zip(&self.shift).map(|(x, a)| x - a));
    }

    /// Adds one row's deviations `d` (from [`ChannelMoments::deviations_into`])
    /// to group `g`: the same sums, in the same order, as
    /// [`ChannelMoments::push`] of the row's values.
    pub(crate) fn push_deviations(&mut self, g: usize, d: &[f64]) {
        let c = self.shift.len();
        let sums = &mut self.groups[g];
        sums.count += 1;
        for (i, di) in d.iter().enumerate() {
            sums.first[i] += di;
            let row = &mut sums.second[i * c..(i + 1) * c];
            row.iter_mut().zip(d).for_each(|(s, dj)| *s += di * dj);
        }
    }

    /// Adds another run's sums, group by group (merge in a fixed order for
    /// reproducible last bits).
    pub fn merge(&mut self, other: &ChannelMoments) {
        for (a, b) in self.groups.iter_mut().zip(&other.groups) {
            a.add(b);
        }
    }

    /// Number of channels C.
    pub fn channels(&self) -> usize {
        self.shift.len()
    }

    /// The covariance matrix Σ of the rows pooled (n − 1 denominator),
    /// row-major C × C; `skip` leaves one group out (the jackknife).
    fn covariance_without(&self, skip: Option<usize>) -> Vec<f64> {
        let c = self.channels();
        let mut total = GroupSums::empty(c);
        for (g, sums) in self.groups.iter().enumerate() {
            if Some(g) != skip {
                total.add(sums);
            }
        }
        let n = total.count as f64;
        (0..c * c)
            .map(|ij| {
                let (i, j) = (ij / c, ij % c);
                (total.second[ij] - total.first[i] * total.first[j] / n) / (n - 1.0)
            })
            .collect()
    }

    /// Σ, the covariance across channels of one row's values, C × C.
    pub fn covariance(&self) -> Vec<Vec<f64>> {
        let c = self.channels();
        self.covariance_without(None)
            .chunks(c)
            .map(<[f64]>::to_vec)
            .collect()
    }

    /// The correlation matrix `Σ_cd / √(Σ_cc Σ_dd)`.
    pub fn correlation(&self) -> Vec<Vec<f64>> {
        let cov = self.covariance();
        let c = self.channels();
        (0..c)
            .map(|i| {
                (0..c)
                    .map(|j| cov[i][j] / (cov[i][i] * cov[j][j]).sqrt())
                    .collect()
            })
            .collect()
    }

    /// The variance of one row's weighted combination `Σ_c w_c x_c`,
    /// `wᵀ Σ w`, with its jackknife standard error over the groups (NaN
    /// with fewer than two non-empty groups).
    pub fn combined_variance(&self, weights: &[f64]) -> (f64, f64) {
        let form = |cov: &[f64]| quadratic_form(cov, weights);
        let all = form(&self.covariance_without(None));
        let kept: Vec<usize> = (0..self.groups.len())
            .filter(|&g| self.groups[g].count > 0)
            .collect();
        let k = kept.len() as f64;
        if kept.len() < 2 {
            return (all, f64::NAN);
        }
        let leave_out: Vec<f64> = kept
            .iter()
            .map(|&g| form(&self.covariance_without(Some(g))))
            .collect();
        let mean = leave_out.iter().sum::<f64>() / k;
        let spread: f64 = leave_out.iter().map(|v| (v - mean).powi(2)).sum();
        (all, ((k - 1.0) / k * spread).sqrt())
    }

    /// The variance the combination would have if the channels were
    /// independent, `Σ_c w_c² Σ_cc` (σ²/C for equal weights 1/C and equal
    /// variances): what ignoring the shared piston claims.
    pub fn independent_variance(&self, weights: &[f64]) -> f64 {
        let c = self.channels();
        let cov = self.covariance_without(None);
        (0..c)
            .map(|i| weights[i] * weights[i] * cov[i * c + i])
            .sum()
    }
}

/// `wᵀ A w` for a row-major square `a`.
fn quadratic_form(a: &[f64], w: &[f64]) -> f64 {
    let c = w.len();
    (0..c)
        .map(|i| w[i] * (0..c).map(|j| a[i * c + j] * w[j]).sum::<f64>())
        .sum()
}
