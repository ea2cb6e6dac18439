//! The per-channel tables of `bias`, `snr` and `simulate` (the answers are
//! built in `v2ref_commands::commands::channels`; printed here).

use v2ref_commands::commands::channels_simulate::{ChannelSimulateReport, Combined};
use v2ref_commands::report::channels::{ChannelBiasLine, ChannelPlace, MeanSigma, SnrChannels};
use v2ref_core::noise::snr_value::snr_text;

/// A channel's first columns: number, wavelength range, photon share.
fn place(p: &ChannelPlace) -> String {
    format!(
        "{:>3}  {:.4}-{:.4}  {:.4}",
        p.channel, p.wavelength_lo_um, p.wavelength_hi_um, p.photon_share
    )
}

/// The header of [`place`]'s columns.
const PLACE_HEADER: &str = "  #  lambda [um]      share";

/// `bias`'s table: one line per channel, each bias on V1 and V2 (not
/// squared).
pub fn print_bias(lines: &[ChannelBiasLine]) {
    outln!();
    outln!(
        "{PLACE_HEADER}  {:>10} {:>10}  {:>10} {:>10}  {:>10} {:>10}  {:>10} {:>10}  {:>10} {:>10}",
        "V1",
        "V2",
        "bw V1",
        "bw V2",
        "disp V1",
        "disp V2",
        "scan V1",
        "scan V2",
        "integ V1",
        "integ V2"
    );
    for l in lines {
        let b = &l.biases;
        outln!(
            "{}  {:>10.7} {:>10.7}  {:>+10.3e} {:>+10.3e}  {:>+10.3e} {:>+10.3e}  {:>+10.3e} {:>+10.3e}  {:>+10.3e} {:>+10.3e}",
            place(&l.place),
            b.wide_band.v1,
            b.wide_band.v2,
            b.bandwidth.v1,
            b.bandwidth.v2,
            b.dispersion.v1,
            b.dispersion.v2,
            b.finite_scan.v1,
            b.finite_scan.v2,
            b.integrating.v1,
            b.integrating.v2
        );
    }
}

/// One estimator's mean, σ and SNR, as columns.
fn mean_sigma(m: &MeanSigma) -> String {
    let sigma = m.sigma.map_or("-".to_owned(), |s| format!("{s:.4e}"));
    format!("{:>10.6} {:>11} {:>8}", m.mean, sigma, snr_text(m.snr, 4))
}

/// `snr`'s table: per channel and combined.
pub fn print_snr(c: &SnrChannels) {
    outln!();
    outln!(
        "{PLACE_HEADER}  {:>10} {:>11} {:>8}  {:>10} {:>11} {:>8}",
        "V1^2",
        "sigma",
        "SNR1",
        "V2^2",
        "sigma",
        "SNR2"
    );
    for l in &c.channels {
        outln!(
            "{}  {}  {}",
            place(&l.place),
            mean_sigma(&l.v1_sq),
            mean_sigma(&l.v2_sq)
        );
    }
    outln!(
        "{:<26}  {}  {}",
        "combined",
        mean_sigma(&c.combined.v1_sq),
        mean_sigma(&c.combined.v2_sq)
    );
    outln!("combined: {}; {}", c.combined.weights, c.combined.note);
}

/// One estimator's combination across channels, as a row's value.
fn combined(c: &Combined) -> String {
    format!(
        "mean {:.6}, sigma {:.4e} +- {:.1e} (measured), {:.4e} if independent, ratio {:.3}",
        c.mean,
        c.sigma,
        c.stderr_variance / (2.0 * c.sigma),
        c.independent_sigma,
        c.sigma_ratio
    )
}

/// The correlation matrix, one line per channel.
fn print_correlation(name: &str, c: &Combined) {
    outln!("correlation of {name} across channels:");
    for row in &c.correlation {
        let cells: Vec<String> = row.iter().map(|x| format!("{x:>6.3}")).collect();
        outln!("  {}", cells.join(" "));
    }
}

/// `simulate`'s table with channels.
pub fn print_simulate(a: &ChannelSimulateReport) {
    let rows = vec![
        ("bins", a.bins.clone()),
        ("bias", a.bias.name().to_owned()),
        ("trials (per channel)", a.trials.to_string()),
        ("seed", a.seed.to_string()),
        ("channels", a.channels.len().to_string()),
        ("combined V1^2", combined(&a.combined_v1_sq)),
        ("combined V2^2", combined(&a.combined_v2_sq)),
    ];
    super::print_rows(&rows);
    outln!("combined: {}; {}", a.weights, a.note);
    outln!();
    outln!(
        "{PLACE_HEADER}  {:>10} {:>10} {:>10}  {:>10} {:>10} {:>10}",
        "mean V1^2",
        "+-",
        "std",
        "mean V2^2",
        "+-",
        "std"
    );
    for l in &a.channels {
        outln!(
            "{}  {:>10.6} {:>10.2e} {:>10.4e}  {:>10.6} {:>10.2e} {:>10.4e}",
            place(&l.place),
            l.v1_sq.mean,
            l.v1_sq.stderr_mean,
            l.v1_sq.std,
            l.v2_sq.mean,
            l.v2_sq.stderr_mean,
            l.v2_sq.std
        );
    }
    print_correlation("V1^2", &a.combined_v1_sq);
    print_correlation("V2^2", &a.combined_v2_sq);
}
