//! How a set's rows lie in time through the differential piston, and how
//! the sidecar records it.
//!
//! Two layouts, for two questions:
//!
//! - [`RowLayout::Sequences`] (the default): the rows are cut from up to 16
//!   independent piston sequences ([`crate::piston::sequence_split`]), the
//!   scans of each spread over at least two piston correlation times
//!   ([`crate::piston::scan_stride`], so there are gaps between them). It
//!   samples the statistics of *one scan* over many atmospheres: the
//!   per-scan bias and scatter, with the spread between sequences as their
//!   error.
//! - [`RowLayout::Observation`]: the rows are [`RowTiming::observations`]
//!   observations of n consecutive scans each (stride: one scan period,
//!   the scan and [`RowTiming::dead_time_s`]), each through its own
//!   atmosphere: the observation a plan recommends, whose mean of n rows
//!   scatters as the mean of n consecutive scans through one atmosphere
//!   does — more than σ²/n when the atmosphere is slow against the scans,
//!   less when it is fast. Each observation reads the start of a sequence
//!   at least [`OBSERVATION_SPAN`](crate::piston::sequences::OBSERVATION_SPAN)
//!   times longer and two correlation times B/v, so its drift is kept; the
//!   sidecar's note says how long it was.
//!
//! The piston of a set is held in memory: in the default layout, all its
//! sequences within [`MAX_SERIES`](crate::piston::MAX_SERIES) samples
//! (2^24, 128 MiB of f64, about 0.8 GB at the peak of their synthesis);
//! in the observation layout, each observation's sequence is synthesized
//! within it in turn and only the stretches read are kept, together within
//! it.

use crate::error::Result;
use serde::{Deserialize, Serialize};

/// How the rows of a set with piston lie in time.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum RowLayout {
    /// Independent sequences, scans spread out in each: the statistics of
    /// one scan (the default; the rows of every earlier version).
    #[default]
    Sequences,
    /// One contiguous sequence, scan after scan: one observation of n
    /// consecutive scans through one atmosphere.
    Observation,
}

impl crate::words::Words for RowLayout {
    const WORDS: &'static [crate::words::Word<Self>] = &[
        crate::words::Word {
            word: "sequences",
            value: RowLayout::Sequences,
            help: "Independent sequences, scans spread out in each: the statistics of one scan (the default; the rows of every earlier version)",
        },
        crate::words::Word {
            word: "observation",
            value: RowLayout::Observation,
            help: "One contiguous sequence, scan after scan: one observation of n consecutive scans through one atmosphere",
        },
    ];
}

/// How the rows of a set lie in time: the [`RowLayout`] and, in the
/// observation layout, how many independent observations the rows are
/// cut into and the dead time between consecutive scans.
///
/// In the observation layout the rows are `observations` observations of
/// `rows / observations` consecutive scans each, one scan period (the scan
/// and `dead_time_s`) apart; observation j reads the start of its own
/// piston sequence (seed keyed by j), synthesized several times longer
/// than the observation and over at least two correlation times B/v, so
/// that the piston's drift over the observation is not forced to zero
/// (an FFT sequence only as long as the observation is periodic over it).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct RowTiming {
    /// The layout.
    pub layout: RowLayout,
    /// Independent observations (observation layout; 1 otherwise).
    pub observations: u64,
    /// Dead time between consecutive scans of an observation, s
    /// (observation layout; 0 otherwise).
    pub dead_time_s: f64,
}

impl Default for RowTiming {
    fn default() -> RowTiming {
        RowLayout::default().into()
    }
}

impl From<RowLayout> for RowTiming {
    fn from(layout: RowLayout) -> RowTiming {
        RowTiming {
            layout,
            observations: 1,
            dead_time_s: 0.0,
        }
    }
}

/// Most independent observations of one set.
pub const MAX_OBSERVATIONS: u64 = 1_000_000;

/// Longest dead time between scans, s (a year, as `plan --dead-time-s`).
pub const MAX_DEAD_TIME_S: f64 = 3.2e7;

impl RowTiming {
    /// The observation layout: `observations` independent observations
    /// (1 to [`MAX_OBSERVATIONS`]), scans `dead_time_s` apart (0 to
    /// [`MAX_DEAD_TIME_S`]); refused under the parameter named otherwise.
    pub fn observation(observations: u64, dead_time_s: f64) -> Result<RowTiming> {
        crate::error::in_range(
            "observations",
            observations as f64,
            1.0,
            MAX_OBSERVATIONS as f64,
        )?;
        crate::error::in_range("dead_time_s", dead_time_s, 0.0, MAX_DEAD_TIME_S)?;
        Ok(RowTiming {
            layout: RowLayout::Observation,
            observations,
            dead_time_s,
        })
    }

    /// `layout` with `observations` and `dead_time_s` as the flags give
    /// them: the observation layout takes both ([`RowTiming::observation`]);
    /// the others refuse anything but 1 observation and no dead time.
    pub fn new(layout: RowLayout, observations: u64, dead_time_s: f64) -> Result<RowTiming> {
        match layout {
            RowLayout::Observation => RowTiming::observation(observations, dead_time_s),
            RowLayout::Sequences if observations != 1 => Err(crate::Error::Invalid {
                param: "observations",
                reason: format!("{observations}: only with layout observation (1 otherwise)"),
            }),
            RowLayout::Sequences if dead_time_s != 0.0 => Err(crate::Error::Invalid {
                param: "dead_time_s",
                reason: format!(
                    "{dead_time_s}: only with layout observation (the sequences layout spreads its scans apart already)"
                ),
            }),
            RowLayout::Sequences => Ok(layout.into()),
        }
    }
}

impl RowLayout {
    /// The name `--layout` and Python's `layout=` take.
    pub fn name(&self) -> &'static str {
        crate::words::Words::word(*self)
    }

    /// The layout named `name` (`sequences` or `observation`), refused
    /// under the parameter `layout` otherwise.
    pub fn from_name(name: &str) -> Result<RowLayout> {
        crate::words::Words::from_word("layout", name)
    }
}

/// Where the rows of a set with piston lie in time, as the sidecar
/// records it. Row r belongs to sequence j when
/// `first_row(j) ≤ r < first_row(j + 1)` (the sequences in row order,
/// `first_row(j)` the sum of `rows_per_sequence` before j) and starts
/// `(r − first_row(j)) · stride_s` seconds after the start of sequence j;
/// the sequences are independent draws of the atmosphere, with no time in
/// common ([`SetLayout::row_start`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SetLayout {
    /// The layout asked for.
    pub layout: RowLayout,
    /// Independent piston sequences.
    pub sequences: usize,
    /// Rows read from each sequence, in row order.
    pub rows_per_sequence: Vec<u64>,
    /// Samples from the start of one row's scan to the start of the next
    /// row's in a sequence (N: the scans are back to back).
    pub stride_samples: usize,
    /// The same in seconds.
    pub stride_s: f64,
    /// Duration of one scan (N samples), s.
    pub scan_time_s: f64,
    /// Observation layout: samples of each periodic piston sequence the
    /// rows read (the longest when they differ); absent otherwise and in
    /// sidecars written before it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sequence_samples: Option<u64>,
    /// How long each sequence is against what its rows span, in words
    /// (the observation layout: whether an observation's drift is kept);
    /// absent in sidecars written before it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

impl SetLayout {
    /// Row `row`'s sequence and its start, s from the start of that
    /// sequence (None past the last row).
    ///
    /// ```
    /// use v2ref_core::simulator::{RowLayout, SetLayout};
    /// let layout = SetLayout {
    ///     layout: RowLayout::Sequences,
    ///     sequences: 2,
    ///     rows_per_sequence: vec![3, 2],
    ///     stride_samples: 200,
    ///     stride_s: 0.02,
    ///     scan_time_s: 0.0064,
    ///     sequence_samples: None,
    ///     note: None,
    /// };
    /// assert_eq!(layout.row_start(4), Some((1, 0.02)));
    /// assert_eq!(layout.row_start(5), None);
    /// ```
    pub fn row_start(&self, row: u64) -> Option<(usize, f64)> {
        let mut first = 0;
        for (j, &rows) in self.rows_per_sequence.iter().enumerate() {
            if row < first + rows {
                return Some((j, (row - first) as f64 * self.stride_s));
            }
            first += rows;
        }
        None
    }
}

/// The sidecar's words on an observation layout's sequences: how long each
/// observation's piston sequence is against the observation and the
/// correlation time `correlation_s` (B/v), and so whether the piston's
/// drift over an observation is kept.
pub(crate) fn observation_note(
    correlation_s: f64,
    setup: &crate::piston::scan::ScanSetup,
    (scans, stride): (usize, usize),
    period_samples: usize,
) -> String {
    let t_s = setup.sample_time_s();
    let observation_s = ((scans.max(1) - 1) * stride + setup.samples) as f64 * t_s;
    let sequence_s = period_samples as f64 * t_s;
    let times = sequence_s / observation_s;
    let kept = if times >= crate::piston::sequences::OBSERVATION_SPAN as f64 - 1e-9 {
        "its piston's drift over the observation is not forced to zero (the plan's observation model: sequences of at least 4 observations)"
    } else {
        "shorter than the plan's 4 observations (the memory limit, 2^24 samples per sequence): the piston's wander slower than one over the sequence is missing, and the nearer the sequence is to the observation the more its drift over the observation is forced toward zero; use fewer scans per observation"
    };
    let s = |x: f64| crate::error::number(format!("{x:.4e}").parse().unwrap_or(x));
    format!(
        "each observation ({scans} consecutive scans, {} s) reads the start of its own periodic piston sequence of {} s: {times:.2} times the observation and {:.2} correlation times B/v = {} s; {kept}",
        s(observation_s),
        s(sequence_s),
        sequence_s / correlation_s,
        s(correlation_s)
    )
}
