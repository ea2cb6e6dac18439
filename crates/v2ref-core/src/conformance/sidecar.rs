//! The JSON sidecar of a synth set: what makes a file of interferograms
//! self-describing — every physical input, the sample positions, the
//! continuum, the seed and version, and the truth each estimate is scored
//! against.

use crate::conformance::estimate::BiasConvention;
use crate::error::{Error, Result};
use crate::formalism::channels::Channels;
use crate::formalism::estimator::{BinWindow, Pair};
use crate::simulator::{Inputs, SetLayout};
use serde::{Deserialize, Serialize};

/// The value of [`Sidecar::format`] this version writes and reads.
pub const FORMAT: &str = "v2ref-synth-1";

/// The sidecar of one synth set.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Sidecar {
    /// [`FORMAT`].
    pub format: String,
    /// The v2ref version that wrote the set.
    pub version: String,
    /// The data files.
    pub data: DataFiles,
    /// The seed of the set's random draws.
    pub seed: u64,
    /// With piston, where the rows lie in time: the independent sequences,
    /// the rows of each and the stride between them, from which each row's
    /// start follows ([`SetLayout::row_start`]). Absent without piston
    /// (the rows are independent) and in sidecars written before it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub layout: Option<SetLayout>,
    /// Every physical input.
    pub inputs: Inputs,
    /// Whether the continuum c_i was subtracted from each row (rows hold
    /// `M_i = I_i − c_i`) or not (rows hold the counts `I_i`).
    pub continuum_subtracted: bool,
    /// x_i, the OPD of each column at zero piston, µm (DFT order: column 0
    /// at the white-light fringe).
    pub sample_opd_um: Vec<f64>,
    /// c_i, the continuum of each column, photons.
    pub continuum_photons: Vec<f64>,
    /// n_i = c_i + m_i, the noise-free mean count of each column without
    /// piston, photons (what the `model` bias convention uses).
    pub mean_counts_photons: Vec<f64>,
    /// What the estimators should give.
    pub truth: Truth,
    /// The other files of the set, each with its size and checksum,
    /// written by `synth --out` (and Python's `synthesize(out=...)`), whose
    /// sidecar is placed last: a reader checks the files it reads against
    /// them, so that a set a stopped run left half placed is refused.
    /// Absent in sidecars written before it and in the conformance
    /// vectors.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub members: Option<Vec<Member>>,
    /// The spectral channels of a dispersed set, in increasing wavenumber:
    /// each row then holds C × N values, channel after channel (the `.npy`
    /// shape is (rows, C, N)), and each channel has its own continuum,
    /// mean counts and truth ([`ChannelSidecar`]). Absent for a wide-band
    /// set (one channel: the rows, continuum and truth above), which
    /// serializes as before.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub channels: Option<Vec<ChannelSidecar>>,
}

/// The files a set is stored in, relative to the sidecar's folder.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DataFiles {
    /// The `.npy` file: float64, C order, shape (rows, samples), or
    /// (rows, channels, samples) for a dispersed set.
    pub npy: String,
    /// The same rows as CSV (one row per line, no header), if written.
    pub csv: Option<String>,
    /// Number of rows (scans).
    pub rows: u64,
    /// N, samples per row (per channel in a dispersed set).
    pub samples: usize,
    /// C, the spectral channels of a dispersed set (each row holds C × N
    /// values, channel-major); absent for a wide-band set.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub channels: Option<usize>,
}

/// The truth of a set.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Truth {
    /// σ_eff, µm⁻¹.
    pub sigma_eff_per_um: f64,
    /// S = B σ_eff, cycles/arcsec.
    pub spatial_freq_cpas: f64,
    /// |V(σ_eff)| times the `visibility` scale: the monochromatic
    /// visibility at the effective wavenumber.
    pub v_sigma_eff: f64,
    /// V1² of the configuration in its spectral form (infinite scan, no
    /// noise, no piston), times visibility².
    pub v1_sq_spectral: f64,
    /// V2² likewise.
    pub v2_sq_spectral: f64,
    /// Per window of bins.
    pub windows: Vec<WindowTruth>,
    /// The independent run the truth's statistics come from where there is
    /// no closed form.
    pub reference_run: ReferenceRun,
}

/// The truth of one window of bins.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WindowTruth {
    /// The window.
    pub bins: BinWindow,
    /// The bins k it sums.
    pub bin_indices: Vec<usize>,
    /// The model calibrator's noise-free raw estimates (point source, same
    /// photons and sampling, no piston): the divisors of the normalized
    /// estimates.
    pub calibration: Pair,
    /// The noise-free normalized estimates of this set's configuration
    /// without piston (what a noiseless, piston-free row reads).
    pub noise_free: Pair,
    /// The noise bias the `model` convention subtracts (raw units).
    pub model_bias: Pair,
    /// The expected statistics of the normalized estimates, per bias
    /// convention.
    pub conventions: Vec<ConventionTruth>,
}

/// Expected statistics of both normalized estimators under one bias
/// convention.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ConventionTruth {
    /// The bias convention.
    pub bias: BiasConvention,
    /// Normalized V1².
    pub v1_sq: EstimatorTruth,
    /// Normalized V2².
    pub v2_sq: EstimatorTruth,
}

/// Where a truth value comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum TruthSource {
    /// An exact closed form (no uncertainty).
    ClosedForm,
    /// The independent reference run of [`Truth::reference_run`].
    ReferenceRun,
}

/// The expected mean and variance over rows of one normalized estimator,
/// and how much a set of this many rows is expected to scatter.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct EstimatorTruth {
    /// Expected mean over rows.
    pub mean: f64,
    /// Expected variance over rows.
    pub var: f64,
    /// Where `mean` comes from.
    pub mean_source: TruthSource,
    /// Where `var` comes from.
    pub var_source: TruthSource,
    /// Standard error of `mean` itself (0 for a closed form).
    pub stderr_mean: f64,
    /// Standard error of `var` itself (0 for a closed form).
    pub stderr_var: f64,
    /// The standard deviation of the mean of a set of [`DataFiles::rows`]
    /// rows (from the reference run's blocks of that size: it includes the
    /// correlation of consecutive piston scans).
    pub set_stderr_mean: f64,
    /// The standard deviation of the variance of such a set (from the
    /// reference run; None when it was not run).
    pub set_stderr_var: Option<f64>,
    /// Degrees of freedom of the standard errors above when they were
    /// measured as a spread over the reference run's B blocks (B − 1, with
    /// piston): the score's ratios are then Student-t, not normal. None
    /// when they are exact or come from a pool of independent rows large
    /// enough to be taken as exact (and in sidecars written before it).
    #[serde(default)]
    pub stderr_dof: Option<u64>,
}

/// The size and seed of the reference run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct ReferenceRun {
    /// Its seed (derived from the set's, never equal to it).
    pub seed: u64,
    /// Blocks, each with its own seed (0: no reference run). With piston
    /// each is an independent replicate of the set; without, their rows
    /// are pooled.
    pub blocks: u64,
    /// Rows per block: the set's size with piston, else at least the set's
    /// size and enough for a pool of
    /// [`POOLED_MIN_ROWS`](crate::conformance::truth::POOLED_MIN_ROWS) rows.
    pub rows_per_block: u64,
}

impl Sidecar {
    /// A sidecar from its JSON text, read from `path` (named in every
    /// refusal, under the parameter `sidecar`): JSON, of [`FORMAT`], with
    /// every field a v2ref sidecar has. An error of the JSON gives its
    /// line and column.
    pub fn from_json(text: &str, path: &std::path::Path) -> crate::Result<Sidecar> {
        use crate::error::Error;
        const P: &str = "sidecar";
        let value: serde_json::Value = serde_json::from_str(text).map_err(|e| {
            Error::data(
                P,
                path,
                format!("line {}, column {}", e.line(), e.column()),
                format!("not JSON ({e}); the sidecar written by v2ref synth is needed"),
            )
        })?;
        let format = match value.get("format") {
            Some(serde_json::Value::String(f)) if f == FORMAT => return Self::fields(text, path),
            Some(f) => f.to_string(),
            None => "missing".to_owned(),
        };
        Err(Error::data(
            P,
            path,
            "field format",
            format!("{format}; \"{FORMAT}\" is needed"),
        ))
    }

    /// The fields of a sidecar's text, parsed again from the text so that
    /// an error carries its line.
    fn fields(text: &str, path: &std::path::Path) -> crate::Result<Sidecar> {
        serde_json::from_str::<Sidecar>(text).map_err(|e| {
            crate::error::Error::data(
                "sidecar",
                path,
                format!("line {}, column {}", e.line(), e.column()),
                format!("not a v2ref sidecar: {e}"),
            )
        })
    }

    /// The truth of `window` under `bias`, if the sidecar has it.
    pub fn truth(&self, window: BinWindow, bias: BiasConvention) -> Option<&ConventionTruth> {
        self.truth
            .windows
            .iter()
            .find(|w| w.bins == window)?
            .conventions
            .iter()
            .find(|c| c.bias == bias)
    }
}

// A dispersed set's channels (crate::conformance::channels writes them):
// here beside the sidecar that holds them, so that the sidecar's module
// needs no module that uses it.

/// One spectral channel of a dispersed set.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ChannelSidecar {
    /// `[σ⁻, σ⁺]`, the channel's wavenumber edges, µm⁻¹.
    pub wavenumber_edges_per_um: [f64; 2],
    /// r, the channel's response (relative throughput, any positive scale).
    pub response: f64,
    /// `1/σ_eff`, the wavelength of the channel's effective wavenumber, µm
    /// (informative: OIFITS's `EFF_WAVE`).
    pub wavelength_eff_um: f64,
    /// `1/σ⁻ − 1/σ⁺`, the channel's width in wavelength, µm (informative:
    /// OIFITS's `EFF_BAND`).
    pub bandwidth_um: f64,
    /// q, the channel's share of the source's photons (Σ q = 1).
    pub photon_share: f64,
    /// c_i of the channel, photons (`q` times the whole band's).
    pub continuum_photons: Vec<f64>,
    /// n_i = c_i + m_i of the channel without piston, photons (what the
    /// `model` bias convention uses on this channel's samples).
    pub mean_counts_photons: Vec<f64>,
    /// What the estimators of this channel's samples should give.
    pub truth: Truth,
}

/// A refusal of a sidecar's channels, saying what to fix.
fn refuse(reason: String) -> Error {
    Error::Invalid {
        param: "channels",
        reason: format!("in the sidecar: {reason}"),
    }
}

impl Sidecar {
    /// C, the channels of the set's rows: 1 for a wide-band set.
    pub fn channel_count(&self) -> usize {
        self.channels.as_ref().map_or(1, Vec::len)
    }

    /// The [`Channels`] of a dispersed set, rebuilt from the inputs'
    /// spectrum and each channel's edges and response, and checked
    /// (parameter `channels`): every check of [`Channels::new`] (channels
    /// in order, not overlapping, in the band), `data.channels` equal to
    /// the channels listed, each channel's continuum and mean counts of N
    /// values, and the stated photon shares those of the rebuilt channels
    /// (to 10⁻¹⁰). None for a wide-band set (no `channels`).
    pub fn channels(&self) -> Result<Option<Channels>> {
        let Some(list) = &self.channels else {
            return match self.data.channels {
                None | Some(1) => Ok(None),
                Some(c) => Err(refuse(format!(
                    "data.channels is {c} but no channel is listed; list each channel under channels"
                ))),
            };
        };
        if self.data.channels != Some(list.len()) {
            return Err(refuse(format!(
                "{} channels listed but data.channels is {:?}; they must agree",
                list.len(),
                self.data.channels
            )));
        }
        let spectrum = self.inputs.spectrum.spectrum()?;
        let edges = list
            .iter()
            .map(|c| (c.wavenumber_edges_per_um[0], c.wavenumber_edges_per_um[1]))
            .collect();
        let responses = list.iter().map(|c| c.response).collect();
        let channels =
            Channels::new(&spectrum, edges, responses).map_err(|e| refuse(e.detail()))?;
        let n = self.data.samples;
        for (j, (c, &q)) in list.iter().zip(channels.photon_shares()).enumerate() {
            if c.continuum_photons.len() != n || c.mean_counts_photons.len() != n {
                return Err(refuse(format!(
                    "channel {}: its continuum_photons and mean_counts_photons need {n} values (data.samples)",
                    j + 1
                )));
            }
            let off = (c.photon_share - q).abs();
            if off.is_nan() || off > crate::tolerance::IDENTITY_REL * q {
                return Err(refuse(format!(
                    "channel {}: photon_share {} is not the {q} its edges and response give",
                    j + 1,
                    c.photon_share
                )));
            }
        }
        Ok(Some(channels))
    }
}

pub use crate::manifest::Member;
