//! What is scored of a pipeline's file: what it must match
//! ([`Expected`]), the estimates read ([`OifitsEstimates`], per channel
//! [`ChannelEstimates`]), the fewest unflagged rows a verdict needs, the
//! truth of the rows kept and the slack on a band's or channel's ends;
//! shared by the broadband reading (`select`) and the reading per channel
//! (`select_channels`), below both.

use crate::conformance::sidecar::ConventionTruth;
use crate::formalism::channels::Channels;
use crate::formats::Estimates;

/// Fewest unflagged rows scored, as a fraction of the set's rows. FLAG is
/// a selection: the truth scored against assumes the rows kept are a
/// random half or more of the set; with more flagged, the verdict would
/// say more about the flags than about the estimator (398 rows flagged of
/// 400 left a test of no power that still said PASS).
pub const MIN_UNFLAGGED_FRACTION: f64 = 0.5;

/// The fewest unflagged rows of a set of `rows` rows that are scored.
pub fn min_unflagged_rows(rows: u64) -> u64 {
    (rows as f64 * MIN_UNFLAGGED_FRACTION).ceil() as u64
}

/// Relative slack on the band's ends (`EFF_WAVE` is stored as float32);
/// on a channel's ends, the slack relative to the channel's width.
pub(crate) const BAND_SLACK: f64 = 1e-4;

/// The truth of a set of `rows` rows for the `kept` rows left after
/// flagged ones are left out: the set's scatter (`set_stderr_mean`,
/// `set_stderr_var`) grows as `sqrt(rows / kept)` (independent rows; the
/// truth's own uncertainty does not change).
pub fn truth_for_kept_rows(truth: &ConventionTruth, rows: u64, kept: u64) -> ConventionTruth {
    let mut t = truth.clone();
    if kept > 0 && kept < rows {
        let s = (rows as f64 / kept as f64).sqrt();
        for e in [&mut t.v1_sq, &mut t.v2_sq] {
            e.set_stderr_mean *= s;
            e.set_stderr_var = e.set_stderr_var.map(|v| v * s);
        }
    }
    t
}

/// A pipeline's estimates read from OIFITS, flagged rows left out.
#[derive(Debug, Clone, PartialEq)]
pub struct OifitsEstimates {
    /// The unflagged rows' estimates, in order (one broadband channel);
    /// empty (both None) when the set's channels were given: the
    /// estimates are then in `channels`.
    pub estimates: Estimates,
    /// Rows in the file (per estimator).
    pub rows: usize,
    /// Rows left out: flagged in any table read (with channels: in any
    /// channel; each channel's own count is its [`ChannelEstimates`]'s).
    pub flagged: usize,
    /// Per channel of the set, in its order, when [`Expected::channels_m`]
    /// was given; empty otherwise.
    pub channels: Vec<ChannelEstimates>,
    /// `INSNAME` of the tables read.
    pub insnames: Vec<String>,
    /// The file's notes ([`OifitsFile::notes`](crate::OifitsFile::notes)).
    pub notes: Vec<String>,
}

/// What the file must match: the set's rows, band and channels, and the
/// window and convention scored.
#[derive(Debug, Clone, PartialEq)]
pub struct Expected {
    /// Rows of the set.
    pub rows: u64,
    /// The band's wavelengths (shortest, longest), m.
    pub band_m: (f64, f64),
    /// The set's spectral channels, each its wavelengths (shortest,
    /// longest), m, in the set's order ([`wavelength_ranges_m`] of its
    /// [`Channels`](crate::formalism::channels::Channels)): each table then
    /// holds `NWAVE` = C values per row, matched to the channels by
    /// `EFF_WAVE`. None: one broadband channel per row (`NWAVE` = 1).
    pub channels_m: Option<Vec<(f64, f64)>>,
    /// The window of bins scored (a table's `V2R_BINS` must agree).
    pub bins: crate::formalism::estimator::BinWindow,
    /// The bias convention scored (a table's `V2R_BIAS` must agree).
    pub bias: crate::conformance::estimate::BiasConvention,
}

/// One channel of the set as read from an OIFITS file.
#[derive(Debug, Clone, PartialEq)]
pub struct ChannelEstimates {
    /// The set's channel, 0-based, in the set's order (increasing
    /// wavenumber).
    pub channel: usize,
    /// Its wavelengths (shortest, longest), m, as the set gives them.
    pub range_m: (f64, f64),
    /// The `EFF_WAVE` matched to it, m (of the first table read).
    pub eff_wave_m: f64,
    /// The estimates of the rows unflagged in this channel, in order.
    pub estimates: Estimates,
    /// Rows left out of this channel: flagged in it in any table read.
    pub flagged: usize,
}

impl ChannelEstimates {
    /// The truth this channel is scored against: `truth`, the channel's
    /// own truth for a set of `rows` rows, for the rows kept in this
    /// channel ([`truth_for_kept_rows`]: the set's scatter grows as
    /// `sqrt(rows / kept)`).
    pub fn truth_for_kept_rows(&self, truth: &ConventionTruth, rows: u64) -> ConventionTruth {
        let kept = rows.saturating_sub(self.flagged as u64);
        truth_for_kept_rows(truth, rows, kept)
    }
}

/// Each channel's wavelengths (shortest, longest), m, in the channels'
/// order: `(1/σ⁺, 1/σ⁻)` of [`Channels::edges_per_um`]. What
/// [`Expected::channels_m`](Expected::channels_m) takes.
pub fn wavelength_ranges_m(channels: &Channels) -> Vec<(f64, f64)> {
    channels
        .edges_per_um()
        .iter()
        .map(|&(lo, hi)| (1e-6 / hi, 1e-6 / lo))
        .collect()
}
