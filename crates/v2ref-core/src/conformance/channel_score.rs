//! Scoring a dispersed set: each channel's estimates against its own
//! truth, under one family-wise threshold for the whole set.
//!
//! Channel j's estimators are scored as a wide-band set's are
//! ([`score_with_threshold`]: `z_mean`, `z_var`, their normal equivalents
//! with the truth's degrees of freedom), but the threshold is shared by
//! every test of every channel. With `E_j` estimators given in channel j
//! (1 or 2), the set makes `m = Σ_j 2 E_j` tests (`2·C·E` when every
//! channel gives the same E), and the Bonferroni threshold
//!
//! `z_crit = Φ⁻¹(1 − α/(2m))`
//!
//! holds the probability that a correct pipeline fails any test of any
//! channel at or below α, **whatever the correlation between channels**
//! (the union bound needs none; the shared piston correlates them). A
//! channel passes when each of its `|z| ≤ z_crit`; the set passes when
//! every channel does.
//!
//! **Power**, per channel: each [`NamedScore`] states the smallest relative
//! error of its mean and of its variance caught with probability 0.9 at
//! this `z_crit` (`(z_crit + Φ⁻¹(0.9))·se/|T|`, see [`crate::conformance::score`]):
//! a test over more channels has a higher threshold, so each channel's
//! power is a little less than it would be scored alone.

use crate::conformance::score::{
    critical_z, score_with_threshold, Estimates, NamedScore, TESTS_PER_ESTIMATOR,
};
use crate::conformance::sidecar::ConventionTruth;
use crate::error::{Error, Result};
use serde::Serialize;

/// The score of one channel.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChannelScore {
    /// One entry per estimator given, V1² first, each at the set's
    /// threshold (its power stated at that threshold).
    pub estimators: Vec<NamedScore>,
    /// Every |z| of the channel ≤ the set's z_crit.
    pub pass: bool,
}

/// The scores of every channel of a dispersed set under one Bonferroni
/// threshold (module docs).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChannelScoreReport {
    /// The family-wise false-alarm rate over every channel.
    pub alpha: f64,
    /// m, the tests made: 2 per estimator given, summed over the channels.
    pub tests: usize,
    /// `Φ⁻¹(1 − alpha/(2m))`, the threshold of every test.
    pub z_crit: f64,
    /// One entry per channel, in increasing wavenumber.
    pub channels: Vec<ChannelScore>,
    /// Every channel passes.
    pub pass: bool,
}

/// Scores each channel's `estimates[j]` against `truths[j]` (the set's
/// truth of one window and bias convention, per channel), for a set of
/// `expected_rows` rows, with the family-wise rate `alpha` shared among
/// every test of every channel (module docs).
///
/// Refuses (parameter `estimates`) a number of channels other than the
/// truths' C, naming C; a channel with no estimator; and, naming the
/// channel, whatever [`score_with_threshold`] refuses (a length other
/// than `expected_rows`, a non-finite estimate); `alpha` outside
/// [`MIN_ALPHA`](crate::conformance::score::MIN_ALPHA)..1.
pub fn score_channels(
    estimates: &[Estimates<'_>],
    truths: &[&ConventionTruth],
    expected_rows: u64,
    alpha: f64,
) -> Result<ChannelScoreReport> {
    if truths.is_empty() {
        return Err(Error::Invalid {
            param: "truth",
            reason: "no channel: give the truth of each channel of the set".into(),
        });
    }
    if estimates.len() != truths.len() {
        return Err(Error::Invalid {
            param: "estimates",
            reason: format!(
                "{} channels of estimates, but the set has {} channels; give one per channel, in increasing wavenumber",
                estimates.len(),
                truths.len()
            ),
        });
    }
    let given: Vec<_> = estimates
        .iter()
        .zip(truths)
        .map(|(e, t)| e.given(t))
        .collect();
    if let Some(j) = given.iter().position(Vec::is_empty) {
        return Err(Error::Invalid {
            param: "estimates",
            reason: format!(
                "channel {} has no estimator; give its v1_sq, v2_sq or both",
                j + 1
            ),
        });
    }
    let tests = TESTS_PER_ESTIMATOR * given.iter().map(Vec::len).sum::<usize>();
    let z_crit = critical_z(alpha, tests)?;
    let mut channels = Vec::with_capacity(given.len());
    for (j, channel) in given.into_iter().enumerate() {
        let estimators = channel
            .into_iter()
            .map(|(estimator, x, t)| {
                let score = score_with_threshold(x, t, expected_rows, z_crit)
                    .map_err(|e| in_channel(j, e))?;
                Ok(NamedScore { estimator, score })
            })
            .collect::<Result<Vec<_>>>()?;
        let pass = estimators.iter().all(|s| s.score.pass);
        channels.push(ChannelScore { estimators, pass });
    }
    Ok(ChannelScoreReport {
        alpha,
        tests,
        z_crit,
        pass: channels.iter().all(|c| c.pass),
        channels,
    })
}

/// `e` naming channel `j` (0-based) in its reason.
fn in_channel(j: usize, e: Error) -> Error {
    match e {
        Error::Invalid { param, reason } => Error::Invalid {
            param,
            reason: format!("channel {}: {reason}", j + 1),
        },
        e => e,
    }
}

/// One screen: the verdict, then a line per channel and estimator with its
/// z-scores, the mean against the truth, and the smallest relative error
/// of the mean and of the variance the set catches in it.
impl std::fmt::Display for ChannelScoreReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let verdict = if self.pass { "pass" } else { "FAIL" };
        writeln!(
            f,
            "{verdict}: alpha {:e} over {} tests in {} channels, every |z| <= {:.3} needed",
            self.alpha,
            self.tests,
            self.channels.len(),
            self.z_crit
        )?;
        for (j, c) in self.channels.iter().enumerate() {
            for e in &c.estimators {
                let s = &e.score;
                let mark = if s.pass { "" } else { "  <- out" };
                writeln!(
                    f,
                    "  channel {:>2} {}: mean {:.5e} expected {:.5e}, z_mean {:+.2}, z_var {:+.2}; catches {:.2} % / {:.2} %{mark}",
                    j + 1,
                    e.estimator.name(),
                    s.mean,
                    s.expected_mean,
                    s.z_mean,
                    s.z_var,
                    100.0 * s.min_detectable_rel_bias_mean,
                    100.0 * s.min_detectable_rel_bias_var
                )?;
            }
        }
        Ok(())
    }
}
