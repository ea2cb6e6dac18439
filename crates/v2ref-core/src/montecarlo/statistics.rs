//! Running statistics of Monte Carlo output.

/// Running mean and central moments up to order 4 (Pébay 2008, "Formulas
/// for robust, one-pass parallel computation of covariances and
/// arbitrary-order statistical moments", eqs. 1.5 and 3.1), numerically
/// stable and mergeable; gives the standard error of the variance as well as
/// of the mean.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct RunningStats {
    /// Number of values.
    pub count: u64,
    /// Their mean.
    pub mean: f64,
    /// Σ (x − mean)².
    pub m2: f64,
    /// Σ (x − mean)³.
    pub m3: f64,
    /// Σ (x − mean)⁴.
    pub m4: f64,
}

impl RunningStats {
    /// Adds one value.
    #[inline]
    pub fn push(&mut self, x: f64) {
        let n1 = self.count as f64;
        self.count += 1;
        let n = self.count as f64;
        let delta = x - self.mean;
        let dn = delta / n;
        let dn2 = dn * dn;
        let term1 = delta * dn * n1;
        self.mean += dn;
        self.m4 += term1 * dn2 * (n * n - 3.0 * n + 3.0) + 6.0 * dn2 * self.m2 - 4.0 * dn * self.m3;
        self.m3 += term1 * dn * (n - 2.0) - 3.0 * dn * self.m2;
        self.m2 += term1;
    }

    /// Merges another accumulator (merge in a fixed order for reproducible
    /// last bits).
    pub fn merge(&mut self, o: &RunningStats) {
        if o.count == 0 {
            return;
        }
        if self.count == 0 {
            *self = *o;
            return;
        }
        let (na, nb) = (self.count as f64, o.count as f64);
        let n = na + nb;
        let d = o.mean - self.mean;
        let d2 = d * d;
        let m2 = self.m2 + o.m2 + d2 * na * nb / n;
        let m3 = self.m3
            + o.m3
            + d * d2 * na * nb * (na - nb) / (n * n)
            + 3.0 * d * (na * o.m2 - nb * self.m2) / n;
        let m4 = self.m4
            + o.m4
            + d2 * d2 * na * nb * (na * na - na * nb + nb * nb) / (n * n * n)
            + 6.0 * d2 * (na * na * o.m2 + nb * nb * self.m2) / (n * n)
            + 4.0 * d * (na * o.m3 - nb * self.m3) / n;
        self.mean += d * nb / n;
        self.m2 = m2;
        self.m3 = m3;
        self.m4 = m4;
        self.count += o.count;
    }

    /// Unbiased sample variance (n − 1 denominator); NaN below two values.
    pub fn variance(&self) -> f64 {
        if self.count < 2 {
            f64::NAN
        } else {
            self.m2 / (self.count - 1) as f64
        }
    }

    /// Standard error of the mean, √(var/n).
    pub fn stderr_mean(&self) -> f64 {
        (self.variance() / self.count as f64).sqrt()
    }

    /// Standard error of the sample variance,
    /// `√((μ4 − (n−3)/(n−1) s⁴)/n)` with the sample fourth central moment.
    pub fn stderr_variance(&self) -> f64 {
        if self.count < 4 {
            return f64::NAN;
        }
        let n = self.count as f64;
        variance_stderr(self.m4 / n, self.variance(), self.count)
    }

    /// The statistics of `a·x + b` (exact for the mean and central moments).
    pub fn affine(&self, a: f64, b: f64) -> RunningStats {
        RunningStats {
            count: self.count,
            mean: a * self.mean + b,
            m2: a * a * self.m2,
            m3: a * a * a * self.m3,
            m4: a.powi(4) * self.m4,
        }
    }
}

impl RunningStats {
    /// The statistics of `values`, pushed in order.
    pub fn from_values(values: &[f64]) -> RunningStats {
        let mut s = RunningStats::default();
        for &x in values {
            s.push(x);
        }
        s
    }

    /// Sample standard deviation `s = √var` (n − 1 denominator).
    pub fn std(&self) -> f64 {
        self.variance().sqrt()
    }

    /// Standard error of [`std`](Self::std) by the delta method,
    /// `se(s²)/(2s)`; zero when `s = 0`; NaN below four values, as
    /// [`stderr_variance`](Self::stderr_variance) (undefined, never a
    /// finite number that would claim a precision).
    pub fn stderr_std(&self) -> f64 {
        let s = self.std();
        if self.count < 4 {
            f64::NAN
        } else if s > 0.0 {
            self.stderr_variance() / (2.0 * s)
        } else {
            0.0
        }
    }

    /// The summary a user reads.
    pub fn summary(&self) -> Summary {
        Summary {
            count: self.count,
            mean: self.mean,
            stderr_mean: self.stderr_mean(),
            var: self.variance(),
            stderr_var: self.stderr_variance(),
            std: self.std(),
            stderr_std: self.stderr_std(),
        }
    }
}

/// The standard error of the unbiased sample variance of `n` independent
/// values whose variance is `var` (σ²) and fourth central moment `mu4`
/// (μ4): `√((μ4 − (n−3)/(n−1) σ⁴)/n)`, exact for any distribution
/// (clamped at 0 where a sample's moments make it negative).
///
/// The one formula for both of its uses: a sample's own error
/// ([`RunningStats::stderr_variance`], with its own μ4 and s²) and the
/// scatter a conformance set of `n` rows is stated to have
/// ([`crate::conformance::truth`], with μ4 from the reference run's pool
/// and the truth's σ²).
pub fn variance_stderr(mu4: f64, var: f64, n: u64) -> f64 {
    let n = n as f64;
    ((mu4 - (n - 3.0) / (n - 1.0) * var * var) / n)
        .max(0.0)
        .sqrt()
}

/// What a Monte Carlo reports of one quantity: its mean, variance and
/// standard deviation over the trials, each with its standard error (from
/// the sample fourth moment, no normality assumed).
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct Summary {
    /// Number of trials.
    pub count: u64,
    /// Mean.
    pub mean: f64,
    /// Standard error of the mean, √(var/n).
    pub stderr_mean: f64,
    /// Unbiased sample variance (n − 1 denominator).
    pub var: f64,
    /// Standard error of the variance.
    pub stderr_var: f64,
    /// Standard deviation √var.
    pub std: f64,
    /// Standard error of the standard deviation, se(var)/(2 std).
    pub stderr_std: f64,
}

/// The [`Summary`] of values that come in `groups`, independent of each
/// other but correlated within (the scans cut from one piston sequence):
/// the mean, variance and standard deviation of all the values pooled, with
/// standard errors from the spread between the groups (independent
/// replications; the cluster-robust estimator of a ratio of sums), valid
/// whatever the correlation inside a group.
///
/// With group sizes n_j, N = Σ n_j, weights w_j = n_j/N, group means m_j and
/// the pooled mean m̄, the mean's squared error is
/// `K/(K−1) Σ w_j² (m_j − m̄)²`; the variance's is the same form applied to
/// q_j, the mean square deviation of group j about m̄; the standard
/// deviation's is the variance's over 2s (delta method).
///
/// Fewer than two groups give NaN errors (there is no spread to measure);
/// `count` is N. The error has K − 1 degrees of freedom: see
/// [`replicated_t_quantile`] for intervals.
pub fn replicated_summary(groups: &[RunningStats]) -> Summary {
    let mut pooled = RunningStats::default();
    for g in groups {
        pooled.merge(g);
    }
    let mut summary = pooled.summary();
    let k = groups.iter().filter(|g| g.count > 0).count();
    let total = pooled.count as f64;
    let (mut se2_mean, mut se2_var) = (f64::NAN, f64::NAN);
    if k >= 2 {
        let weight = |g: &RunningStats| g.count as f64 / total;
        let square_dev = |g: &RunningStats| {
            let d = g.mean - pooled.mean;
            if g.count == 0 {
                0.0
            } else {
                g.m2 / g.count as f64 + d * d
            }
        };
        let q_bar: f64 = groups.iter().map(|g| weight(g) * square_dev(g)).sum();
        let spread = |f: &dyn Fn(&RunningStats) -> f64| {
            groups
                .iter()
                .map(|g| (weight(g) * f(g)).powi(2))
                .sum::<f64>()
                * k as f64
                / (k as f64 - 1.0)
        };
        se2_mean = spread(&|g| g.mean - pooled.mean);
        se2_var = spread(&|g| square_dev(g) - q_bar) * (total / (total - 1.0)).powi(2);
    }
    summary.stderr_mean = se2_mean.sqrt();
    summary.stderr_var = se2_var.sqrt();
    summary.stderr_std = if summary.std > 0.0 {
        summary.stderr_var / (2.0 * summary.std)
    } else {
        0.0
    };
    summary
}

/// The effective number of independent values behind a mean: var/se², the
/// count that independent values of the same spread would need for the
/// same standard error (NaN when the error is unknown, +∞ when it is 0).
pub fn effective_count(summary: &Summary) -> f64 {
    summary.var / (summary.stderr_mean * summary.stderr_mean)
}

/// The two-sided Student-t quantile for a confidence `level` (0.5 to
/// 0.999 999) with `groups − 1` degrees of freedom: the factor that turns a
/// [`replicated_summary`] error into a confidence half-width. NaN below two
/// groups.
pub fn replicated_t_quantile(level: f64, groups: usize) -> f64 {
    use statrs::distribution::{ContinuousCDF, StudentsT};
    if groups < 2 || !(0.5..1.0).contains(&level) {
        return f64::NAN;
    }
    StudentsT::new(0.0, 1.0, (groups - 1) as f64)
        .map(|t| t.inverse_cdf(0.5 + level / 2.0))
        .unwrap_or(f64::NAN)
}
