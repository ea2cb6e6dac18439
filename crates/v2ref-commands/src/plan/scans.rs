//! The per-scan values an observation Monte Carlo keeps: what the
//! observation's solve (`observation.rs`) fills and the scans'
//! correlation (`correlation.rs`) reads.

/// Independent piston sequences of an observation Monte Carlo: its
/// standard errors have `SEQUENCES − 1` degrees of freedom.
pub const SEQUENCES: usize = 16;

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
