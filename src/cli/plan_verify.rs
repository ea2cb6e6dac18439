//! The lines `plan --verify` prints: the simulated observations beside the
//! promise.

use v2ref::plan::verify::Verification;

/// Prints the verification `v` (V² throughout).
pub fn print(v: &Verification) {
    let pct = v.confidence * 100.0;
    let verdict = |kept: bool| if kept { "kept" } else { "NOT kept" };
    outln!("");
    outln!(
        "verified: {} observations of {} consecutive scans through one atmosphere ({} independent piston sequences, photon and detector noise, --bias {}, seed {}):",
        v.observations,
        v.scans_per_observation,
        v.sequences,
        v.bias.name(),
        v.seed
    );
    outln!(
        "  sigma(V^2) achieved {:.3e} ({pct:.0}% interval {:.3e} to {:.3e}); promised {:.3e}: {} (independent scans would promise {:.3e})",
        v.achieved_sigma,
        v.achieved_sigma_interval[0],
        v.achieved_sigma_interval[1],
        v.promised_sigma,
        verdict(v.sigma_kept),
        v.sigma_if_independent
    );
    outln!(
        "  mean V^2 achieved {:.5e} ({pct:.0}% interval {:.5e} to {:.5e}); predicted {:.5e}: {}; bias (uncorrectable) achieved {:+.2e}, predicted {:+.2e}",
        v.achieved_mean,
        v.achieved_mean_interval[0],
        v.achieved_mean_interval[1],
        v.predicted_mean,
        verdict(v.mean_kept),
        v.achieved_bias,
        v.predicted_bias
    );
}
