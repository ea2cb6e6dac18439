//! The answer of `v2ref snr` (its JSON document) and of Python's
//! `v2ref.snr`: built here, once, so that the command line and the Python
//! package cannot drift apart.

use crate::error::Result;
use crate::formalism::estimator::BinWindow;
use crate::formalism::interferogram::Sampling;
use crate::formalism::observation::Observation;
use crate::noise::calibrated::{CalibratedSetup, MAX_WINDOW_SAMPLES};
use crate::noise::snr_value::serialize_snr;
use crate::noise::window_variance::{window_stats, WindowStats};
use crate::noise::{appendix_stats, paper_window_factor, Formula, NoiseModel};
use crate::record::{InputsRecord, ObservationRecord, SamplingRecord};
use serde::Serialize;

/// The exact statistics of one window of bins.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WindowReport {
    /// The window (`positive`, `band`, `all`).
    pub window: String,
    /// Its bias, variance and SNR of V1² and V2², exact.
    #[serde(flatten)]
    pub stats: WindowStats,
}

/// The light of one scan: what the closed forms are evaluated at.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light {
    /// Mean photons per scan.
    pub photons: f64,
    /// The source's visibility modulus.
    pub visibility: f64,
    /// Detector and photon noise.
    pub noise: NoiseModel,
}

/// Closed-form expectations, variances and SNRs of V1² and V2² (paper,
/// Appendix) over all bins, the paper's window factor kept apart, and the
/// exact statistics of the chosen window beside them. An SNR without noise
/// is written "infinite" (or "undefined" for 0/0).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SnrReport {
    /// What was computed, as given and as used.
    pub inputs: InputsRecord,
    /// The formula: as printed in the paper, or exact.
    pub formula: Formula,
    /// N.
    pub samples: usize,
    /// Mean photons per scan.
    pub photons: f64,
    /// Visibility modulus.
    pub visibility: f64,
    /// σ_det, photons per sample.
    pub read_noise: f64,
    /// Whether photon noise is included.
    pub photon_noise: bool,
    /// Σ m_i², photons².
    pub sum_m2: f64,
    /// m_0, photons.
    pub m0: f64,
    /// Bias of V1² over all bins.
    pub bias_v1_sq: f64,
    /// Bias of V2² over all bins.
    pub bias_v2_sq: f64,
    /// Variance of V1² over all bins.
    pub var_v1_sq: f64,
    /// Variance of V2² over all bins.
    pub var_v2_sq: f64,
    /// SNR of V1² over all bins.
    #[serde(serialize_with = "serialize_snr")]
    pub snr1: f64,
    /// SNR of V2² over all bins.
    #[serde(serialize_with = "serialize_snr")]
    pub snr2: f64,
    /// The paper's window factor √(Δσ/Δσ0).
    pub window_factor: f64,
    /// SNR1 times the window factor.
    #[serde(serialize_with = "serialize_snr")]
    pub snr1_with_window_factor: f64,
    /// SNR2 times the window factor.
    #[serde(serialize_with = "serialize_snr")]
    pub snr2_with_window_factor: f64,
    /// Exact statistics of the chosen window (None above
    /// [`MAX_WINDOW_SAMPLES`] samples).
    pub window_exact: Option<WindowReport>,
    /// Per spectral channel and combined, when channels are given
    /// ([`crate::commands::channels::snr_lines`]): `channels` and
    /// `combined`.
    #[serde(flatten)]
    pub channels: Option<crate::report::channels::SnrChannels>,
}

impl SnrReport {
    /// The report for `obs` (echoed as `observation`) sampled by `sampling`
    /// in `light`, by `formula`, with the exact statistics of `window`.
    pub fn new(
        obs: &Observation,
        observation: ObservationRecord,
        sampling: &Sampling,
        window: BinWindow,
        light: Light,
        formula: Formula,
    ) -> Result<SnrReport> {
        let noise = light.noise;
        let setup = CalibratedSetup::new(obs, sampling, light.photons, light.visibility, window)?;
        let ifg = &setup.signal;
        let st = appendix_stats(&ifg.modulated, &ifg.continuum, &noise, formula)?;
        let factor = paper_window_factor(sampling.dx_um(), obs.spectrum.width_per_um());
        let window_exact = if sampling.samples() <= MAX_WINDOW_SAMPLES {
            Some(WindowReport {
                window: window.name().to_owned(),
                stats: window_stats(&ifg.modulated, &ifg.mean_counts(), &noise, &setup.bins)?,
            })
        } else {
            None
        };
        Ok(SnrReport {
            inputs: InputsRecord {
                observation,
                sampling: Some(SamplingRecord::new(sampling, window)),
                atmosphere: None,
            },
            formula,
            samples: st.samples,
            photons: light.photons,
            visibility: light.visibility,
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
            channels: None,
        })
    }
}
