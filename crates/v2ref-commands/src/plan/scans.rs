//! The per-scan values an observation Monte Carlo keeps, and its size:
//! what the observation's solve (`observation.rs`) fills and the scans'
//! correlation (`correlation.rs`) reads, both above this module.

/// Independent piston sequences of an observation Monte Carlo: its
/// standard errors have `SEQUENCES − 1` degrees of freedom.
pub const SEQUENCES: usize = 16;

/// Most samples (scans × N) one observation Monte Carlo of the plan
/// simulates: 2^24, about 1.5 core-seconds (at 9e-8 core-s per scanned
/// sample, measured 2026-11-25); beyond, fewer blocks
/// per sequence (wider intervals), but always at least n scans.
pub const MAX_OBSERVATION_SAMPLES: usize = 1 << 24;

/// Scans of N samples each of one of the K sequences that
/// [`MAX_OBSERVATION_SAMPLES`] affords: L N + 4 ≤ a K-th of it (a
/// sequence of contiguous scans is L N samples and the 4 every sequence
/// has beyond its last scan), so that without dead time every setting at
/// one fringe frequency draws sequences of one FFT length (2^20), drawn
/// once for all of them (`candidates`).
pub(crate) fn affordable_scans(samples: usize) -> usize {
    (MAX_OBSERVATION_SAMPLES / SEQUENCES - 4) / samples.max(1)
}

/// The per-scan values of K contiguous sequences, for the block means of
/// any observation length up to the scans of one sequence.
pub(crate) struct ContiguousScans {
    /// Per sequence, per scan: V1², V2² and the offsets of the `model`
    /// convention's photon bias ([`ScanValues`]).
    pub(crate) sequences: Vec<Vec<ScanValues>>,
    /// One scan and its dead time, s.
    pub(crate) scan_period_s: f64,
}

/// One scan's values.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct ScanValues {
    /// The estimates V1², V2².
    pub(crate) v_sq: [f64; 2],
    /// Noise-free scans: what the `model` convention adds to the mean of
    /// V1², V2² over the `counts` one (the photon bias of the piston-free
    /// counts minus that of the scan's own); 0 for noisy scans.
    pub(crate) model_offset: [f64; 2],
}
