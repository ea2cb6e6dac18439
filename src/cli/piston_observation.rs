//! The lines `piston --observation-scans` prints: σ(V²) of the mean of an
//! observation's consecutive scans beside the independent-scan value.

use v2ref_commands::plan::ObservationPiston;

/// Prints one line per fringe frequency.
pub fn print(rows: &[ObservationPiston]) {
    outln!("");
    outln!("sigma(V^2) of the mean of an observation's n consecutive scans (piston alone, no noise), beside sigma_scan/sqrt(n) (independent scans); inflation = n sigma^2(mean) / sigma^2(scan)");
    outln!(
        "{:>10}  {:>9}  {:>9}  {:>22}  {:>10}  {:>9}  {:>22}  {:>10}  {:>9}",
        "f [Hz]",
        "n",
        "T [s]",
        "sigma V1^2 (mean)",
        "indep.",
        "inflation",
        "sigma V2^2 (mean)",
        "indep.",
        "inflation"
    );
    for r in rows {
        let root_n = (r.scans as f64).sqrt();
        outln!(
            "{:>10.2}  {:>9}  {:>9.3}  {:>11.3e} ±{:>9.1e}  {:>10.3e}  {:>9.2}  {:>11.3e} ±{:>9.1e}  {:>10.3e}  {:>9.2}",
            r.fringe_hz,
            r.scans,
            r.duration_s,
            r.sigma_v1_sq,
            r.sigma_v1_sq_stderr,
            r.sigma_v1_sq_per_scan / root_n,
            r.variance_inflation_v1,
            r.sigma_v2_sq,
            r.sigma_v2_sq_stderr,
            r.sigma_v2_sq_per_scan / root_n,
            r.variance_inflation_v2
        );
        if let Some(m) = r.extrapolated_from_scans {
            outln!("  (n scans do not fit one simulated sequence: measured at {m} scans and carried to n as 1/n, which assumes scans further apart are uncorrelated)");
        }
    }
    if let Some(r) = rows.first() {
        outln!(
            "  ({} simulated observations per frequency from {} independent piston sequences of {} consecutive scans; errors from the spread between sequences)",
            r.simulated_observations,
            r.sequences,
            r.scans_per_sequence
        );
    }
}
