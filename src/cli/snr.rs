//! `v2ref snr`: closed-form expectations, variances and SNRs of V1² and V2²
//! (paper, Appendix), in the `published` or `exact` formula, with the
//! paper's window factor kept apart and the exact variance of the chosen
//! bin window beside it.

use super::common::{LightArgs, ObservationArgs, SamplingArgs};
use super::{print_json, print_rows};
use serde::Serialize;
use std::process::ExitCode;
use v2ref::formalism::estimator::BinWindow;
use v2ref::formalism::interferogram::Sampling;
use v2ref::formalism::observation::Observation;
use v2ref::noise::calibrated::{CalibratedSetup, MAX_WINDOW_SAMPLES};
use v2ref::noise::snr_value::{serialize_snr, snr_text};
use v2ref::noise::window_variance::{window_stats, WindowStats};
use v2ref::noise::{appendix_stats, paper_window_factor, Formula, NoiseModel};
use v2ref::simulator::record::{InputsRecord, SamplingRecord};
use v2ref::Result;

/// Signal and noise flags shared by `snr` and `simulate`.
#[derive(Debug, Clone, clap::Args)]
pub struct NoiseArgs {
    #[command(flatten)]
    pub light: LightArgs,
    /// Formula: as printed in the paper, or exact.
    #[arg(long, value_enum, default_value = "exact")]
    pub formula: Formula,
}

impl NoiseArgs {
    /// The noise model these flags describe.
    pub fn noise(&self) -> Result<NoiseModel> {
        self.light.noise()
    }

    /// The noise-free interferograms (source and calibrator) of `obs`
    /// sampled by `sampling`, and the bins of `window`.
    pub fn setup(
        &self,
        obs: &Observation,
        sampling: &Sampling,
        window: BinWindow,
    ) -> Result<CalibratedSetup> {
        let l = &self.light;
        CalibratedSetup::new(obs, sampling, l.photons, l.visibility, window)
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
    inputs: InputsRecord,
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
    #[serde(serialize_with = "serialize_snr")]
    snr1: f64,
    #[serde(serialize_with = "serialize_snr")]
    snr2: f64,
    window_factor: f64,
    #[serde(serialize_with = "serialize_snr")]
    snr1_with_window_factor: f64,
    #[serde(serialize_with = "serialize_snr")]
    snr2_with_window_factor: f64,
    /// Exact statistics of the --bins window (null above MAX_WINDOW_SAMPLES).
    window_exact: Option<Window>,
}

/// Runs `snr`.
pub fn run(args: Args) -> Result<ExitCode> {
    let noise = args.noise.noise()?;
    let obs = args.obs.observation()?;
    let sampling = args.sampling.sampling()?;
    let setup = args.noise.setup(&obs, &sampling, args.sampling.bins)?;
    let ifg = &setup.signal;
    let formula = args.noise.formula;
    let st = appendix_stats(&ifg.modulated, &ifg.continuum, &noise, formula)?;
    let factor = paper_window_factor(sampling.dx_um(), obs.spectrum.width_per_um());
    let window_exact = if sampling.samples() <= MAX_WINDOW_SAMPLES {
        Some(Window {
            window: args.sampling.bins.name().to_owned(),
            stats: window_stats(&ifg.modulated, &ifg.mean_counts(), &noise, &setup.bins)?,
        })
    } else {
        None
    };
    let answer = Answer {
        inputs: InputsRecord {
            observation: args.obs.record(&obs),
            sampling: Some(SamplingRecord::new(&sampling, args.sampling.bins)),
            atmosphere: None,
        },
        formula,
        samples: st.samples,
        photons: args.noise.light.photons,
        visibility: args.noise.light.visibility,
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
        print_table(&answer);
    }
    Ok(ExitCode::SUCCESS)
}

fn print_table(a: &Answer) {
    let obs = &a.inputs.observation;
    let mut rows = vec![
        (
            "baseline [m]",
            format!(
                "{:.3} ({:.2} cycles/arcsec)",
                obs.baseline_m, obs.spatial_freq_cpas
            ),
        ),
        ("formula", format!("{:?}", a.formula).to_lowercase()),
        ("samples N", a.samples.to_string()),
        ("sum m_i^2 [photons^2]", format!("{:.6}", a.sum_m2)),
        ("m_0 [photons]", format!("{:.6}", a.m0)),
        ("bias V1^2 (all bins)", format!("{:.6e}", a.bias_v1_sq)),
        ("bias V2^2 (all bins)", format!("{:.6e}", a.bias_v2_sq)),
        ("var V1^2 (all bins)", format!("{:.6e}", a.var_v1_sq)),
        ("var V2^2 (all bins)", format!("{:.6e}", a.var_v2_sq)),
        ("SNR1 (all bins)", snr_text(a.snr1, 4)),
        ("SNR2 (all bins)", snr_text(a.snr2, 4)),
        (
            "paper window factor sqrt(dsigma/dsigma0)",
            format!("{:.4}", a.window_factor),
        ),
    ];
    if let Some(w) = &a.window_exact {
        rows.push((
            "window (exact)",
            format!("{} ({} bins)", w.window, w.stats.bins),
        ));
        rows.push(("SNR1 (window, exact)", snr_text(w.stats.snr1, 4)));
        rows.push(("SNR2 (window, exact)", snr_text(w.stats.snr2, 4)));
    }
    print_rows(&rows);
}
