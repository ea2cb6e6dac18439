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
//! - [`RowLayout::Observation`]: every row through *one* contiguous
//!   sequence in time order, each scan starting where the previous one
//!   ended (stride N samples, one scan period). It is the observation a
//!   plan recommends: the mean of its n rows scatters as the mean of n
//!   consecutive scans through one atmosphere does — more than σ²/n when
//!   the atmosphere is slow against the scans, less when it is fast.
//!
//! The piston sequence of a set is held in memory whole: at most
//! [`MAX_SERIES`](crate::piston::MAX_SERIES) samples (2^24, 128 MiB of
//! f64, about 0.8 GB at the peak of its synthesis), shared by all the
//! sequences of a set; in the observation layout they all go to the one
//! sequence (164 000 rows at N = 102, where each of the 16 sequences of the
//! default layout holds at most about 10 000).

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
}

impl SetLayout {
    /// Row `row`'s sequence and its start, s from the start of that
    /// sequence (None past the last row).
    ///
    /// ```
    /// use v2ref::simulator::{RowLayout, SetLayout};
    /// let layout = SetLayout {
    ///     layout: RowLayout::Sequences,
    ///     sequences: 2,
    ///     rows_per_sequence: vec![3, 2],
    ///     stride_samples: 200,
    ///     stride_s: 0.02,
    ///     scan_time_s: 0.0064,
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
