//! The lines `plan --verify` prints: the simulated observations beside the
//! promise.

use v2ref_commands::plan::verify::Verification;
use v2ref_core::conformance::estimate::BiasConvention;

/// Prints the verification `v` (V² throughout).
pub fn print(v: &Verification) {
    let pct = v.confidence * 100.0;
    let verdict = |agree: bool| {
        if agree {
            "within the interval of their difference"
        } else {
            "OUTSIDE the interval of their difference"
        }
    };
    outln!("");
    outln!(
        "verified: {} observations of {} consecutive scans through one atmosphere ({} independent piston sequences, photon and detector noise, {}, seed {}):",
        v.observations,
        v.scans_per_observation,
        v.sequences,
        convention_words(v.bias),
        v.seed
    );
    if let Some(why) = &v.fewer_observations_why {
        outln!("  fewer observations than asked: {why}");
    }
    outln!(
        "  sigma(V^2) achieved/promised {:.3} ({pct:.0}% interval {:.3} to {:.3}): achieved {:.3e}, promised {:.3e}{} (independent scans would promise {:.3e})",
        v.sigma_ratio,
        v.sigma_ratio_interval[0],
        v.sigma_ratio_interval[1],
        v.achieved_sigma,
        v.promised_sigma,
        if v.sigma_kept {
            ""
        } else {
            "; the promise is optimistic: the whole interval is above 1"
        },
        v.sigma_if_independent
    );
    outln!(
        "  mean V^2 achieved {:.5e} ({pct:.0}% interval {:.5e} to {:.5e}); predicted {:.5e}, achieved - predicted {:+.2e}, {}; bias (uncorrectable) achieved {:+.2e}, predicted {:+.2e}",
        v.achieved_mean,
        v.achieved_mean_interval[0],
        v.achieved_mean_interval[1],
        v.predicted_mean,
        v.achieved_mean - v.predicted_mean,
        verdict(v.mean_kept),
        v.achieved_bias,
        v.predicted_bias
    );
}

/// The bias convention in words, saying which command defaults to which
/// (`plan` to counts, `estimate` to model).
pub(super) fn convention_words(b: BiasConvention) -> String {
    let said = match b {
        BiasConvention::Counts => "plan's default; estimate defaults to model",
        BiasConvention::Model => "estimate's default; plan's is counts",
        _ => "",
    };
    format!("--bias {} ({said})", b.name())
}
