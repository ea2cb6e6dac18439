//! `v2ref snr`: closed-form expectations, variances and SNRs of V1² and V2²
//! (paper, Appendix), in the `published` or `exact` formula, with the
//! paper's window factor kept apart and the exact variance of the chosen
//! bin window beside it.

use super::common::{ObservationArgs, SamplingArgs};
use super::{finite_f64, print_json, print_rows};
use serde::Serialize;
use std::process::ExitCode;
use v2ref::formalism::interferogram::Interferogram;
use v2ref::noise::window_variance::{window_stats, WindowStats};
use v2ref::noise::{
    appendix_stats, paper_window_factor, scaled_interferogram, Formula, NoiseModel,
};
use v2ref::Result;

/// Largest N for which the exact windowed variance (N × N matrices) is computed.
pub const MAX_WINDOW_SAMPLES: usize = 4096;

/// Signal and noise flags shared by `snr` and `simulate`.
#[derive(Debug, Clone, clap::Args)]
pub struct NoiseArgs {
    /// Visibility V scaling the fringe (m_0 = n V for a point source), 0 to 1.
    #[arg(long, default_value = "1", value_parser = finite_f64, allow_hyphen_values = true)]
    pub visibility: f64,
    /// Continuum photons per sample n (c = n), >= 0.
    #[arg(long, default_value = "10", value_parser = finite_f64, allow_hyphen_values = true)]
    pub photons: f64,
    /// Detector noise standard deviation σ_det, photons per sample, >= 0.
    #[arg(long, default_value = "0", value_parser = finite_f64, allow_hyphen_values = true)]
    pub read_noise: f64,
    /// No Poisson photon noise (detector noise only).
    #[arg(long)]
    pub no_photon_noise: bool,
    /// Formula: as printed in the paper, or exact.
    #[arg(long, value_enum, default_value = "exact")]
    pub formula: Formula,
}

impl NoiseArgs {
    /// The noise model these flags describe.
    pub fn noise(&self) -> Result<NoiseModel> {
        NoiseModel::new(self.read_noise, !self.no_photon_noise)
    }

    /// The noise-free interferogram and the calibrator's (point source,
    /// V = 1, same photons).
    pub fn interferograms(
        &self,
        obs: &ObservationArgs,
        sampling: &SamplingArgs,
    ) -> Result<(
        Interferogram,
        Interferogram,
        v2ref::formalism::interferogram::Sampling,
        Vec<usize>,
        f64,
    )> {
        let o = obs.observation()?;
        let s = sampling.sampling()?;
        v2ref::error::non_negative("photons", self.photons)?;
        let ifg = scaled_interferogram(&o, &s, self.photons, self.visibility)?;
        let cal = scaled_interferogram(&o.calibrator(), &s, self.photons, 1.0)?;
        let bins = sampling.bins.bins(s.samples(), s.dx_um(), &o.spectrum);
        Ok((ifg, cal, s, bins, o.spectrum.width_per_um()))
    }
}

/// Flags of `snr`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    obs: ObservationArgs,
    #[command(flatten)]
    sampling: SamplingArgs,
    #[command(flatten)]
    noise: NoiseArgs,
    /// One JSON document instead of the table.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct Window {
    window: String,
    #[serde(flatten)]
    stats: WindowStats,
}

#[derive(Serialize)]
struct Answer {
    formula: Formula,
    samples: usize,
    photons: f64,
    visibility: f64,
    read_noise: f64,
    photon_noise: bool,
    sum_m2: f64,
    m0: f64,
    bias_v1_sq: f64,
    bias_v2_sq: f64,
    var_v1_sq: f64,
    var_v2_sq: f64,
    snr1: f64,
    snr2: f64,
    window_factor: f64,
    snr1_with_window_factor: f64,
    snr2_with_window_factor: f64,
    /// Exact statistics of the --bins window (null above MAX_WINDOW_SAMPLES).
    window_exact: Option<Window>,
}

/// Runs `snr`.
pub fn run(args: Args) -> Result<ExitCode> {
    let noise = args.noise.noise()?;
    let (ifg, _cal, sampling, bins, band_width) =
        args.noise.interferograms(&args.obs, &args.sampling)?;
    let formula = args.noise.formula;
    let st = appendix_stats(&ifg.modulated, &ifg.continuum, &noise, formula)?;
    let factor = paper_window_factor(sampling.dx_um(), band_width);
    let window_exact = if sampling.samples() <= MAX_WINDOW_SAMPLES {
        Some(Window {
            window: format!("{:?}", args.sampling.bins).to_lowercase(),
            stats: window_stats(&ifg.modulated, &ifg.mean_counts(), &noise, &bins)?,
        })
    } else {
        None
    };
    let answer = Answer {
        formula,
        samples: st.samples,
        photons: args.noise.photons,
        visibility: args.noise.visibility,
        read_noise: noise.read_noise,
        photon_noise: noise.photon,
        sum_m2: st.sum_m2,
        m0: st.m0,
        bias_v1_sq: st.bias_v1_sq,
        bias_v2_sq: st.bias_v2_sq,
        var_v1_sq: st.var_v1_sq,
        var_v2_sq: st.var_v2_sq,
        snr1: st.snr1,
        snr2: st.snr2,
        window_factor: factor,
        snr1_with_window_factor: factor * st.snr1,
        snr2_with_window_factor: factor * st.snr2,
        window_exact,
    };
    if args.json {
        print_json(&answer);
    } else {
        let mut rows = vec![
            ("formula", format!("{:?}", formula).to_lowercase()),
            ("samples N", st.samples.to_string()),
            ("sum m_i^2 [photons^2]", format!("{:.6}", st.sum_m2)),
            ("m_0 [photons]", format!("{:.6}", st.m0)),
            ("bias V1^2 (all bins)", format!("{:.6e}", st.bias_v1_sq)),
            ("bias V2^2 (all bins)", format!("{:.6e}", st.bias_v2_sq)),
            ("var V1^2 (all bins)", format!("{:.6e}", st.var_v1_sq)),
            ("var V2^2 (all bins)", format!("{:.6e}", st.var_v2_sq)),
            ("SNR1 (all bins)", format!("{:.4}", st.snr1)),
            ("SNR2 (all bins)", format!("{:.4}", st.snr2)),
            (
                "paper window factor sqrt(dsigma/dsigma0)",
                format!("{factor:.4}"),
            ),
        ];
        if let Some(w) = &answer.window_exact {
            rows.push((
                "window (exact)",
                format!("{} ({} bins)", w.window, w.stats.bins),
            ));
            rows.push(("SNR1 (window, exact)", format!("{:.4}", w.stats.snr1)));
            rows.push(("SNR2 (window, exact)", format!("{:.4}", w.stats.snr2)));
        }
        print_rows(&rows);
    }
    Ok(ExitCode::SUCCESS)
}
