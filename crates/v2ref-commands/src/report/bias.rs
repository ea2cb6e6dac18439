//! The answer of `v2ref bias` (its JSON document) and of Python's
//! `v2ref.bias`: built here, once, so that the command line and the Python
//! package cannot drift apart.

use crate::error::Result;
use crate::formalism::estimator::{sampled_wide_band, wide_band, BinWindow, Pair, WideBand};
use crate::formalism::interferogram::Sampling;
use crate::formalism::observation::Observation;
use crate::record::{InputsRecord, ObservationRecord, SamplingRecord};
use serde::Serialize;

/// The estimators of a finite, sampled scan.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FiniteScanReport {
    /// Δx = N δx, µm.
    pub stroke_um: f64,
    /// N.
    pub samples: usize,
    /// δx, µm.
    pub dx_um: f64,
    /// Whether each sample integrates the fringe over δx.
    pub integrating: bool,
    /// The bins the estimators sum (`positive`, `band`, `all`).
    pub bins: String,
    /// V1² of the scan (calibrated on an unresolved source).
    pub v1_sq: f64,
    /// V2² of the scan.
    pub v2_sq: f64,
    /// √V1².
    pub v1: f64,
    /// √V2².
    pub v2: f64,
}

/// The noise-free wide-band estimators of one observation: the infinite
/// scan, and a finite scan when one is asked for.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BiasReport {
    /// What was computed, as given and as used.
    pub inputs: InputsRecord,
    /// The infinite-scan estimators (spectral form).
    #[serde(flatten)]
    pub infinite_scan: WideBand,
    /// The finite-scan estimators, when a scan was given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub finite_scan: Option<FiniteScanReport>,
    /// One line per spectral channel, when channels are given
    /// ([`crate::commands::channels::bias_lines`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub channels: Option<Vec<crate::report::channels::ChannelBiasLine>>,
}

impl BiasReport {
    /// The report for `obs` (echoed as `observation`), with the finite scan
    /// `scan` (its sampling and bin window) when given. The finite scan
    /// costs O(N²) (docs/conventions.md).
    pub fn new(
        obs: &Observation,
        observation: ObservationRecord,
        scan: Option<(&Sampling, BinWindow)>,
    ) -> Result<BiasReport> {
        let finite_scan = match scan {
            Some((sampling, window)) => {
                let Pair { v1_sq, v2_sq } = sampled_wide_band(obs, sampling, window)?;
                Some(FiniteScanReport {
                    stroke_um: sampling.stroke_um(),
                    samples: sampling.samples(),
                    dx_um: sampling.dx_um(),
                    integrating: sampling.integrating(),
                    bins: window.name().to_owned(),
                    v1_sq,
                    v2_sq,
                    v1: v1_sq.sqrt(),
                    v2: v2_sq.sqrt(),
                })
            }
            None => None,
        };
        Ok(BiasReport {
            inputs: InputsRecord {
                observation,
                sampling: scan.map(|(sampling, window)| SamplingRecord::new(sampling, window)),
                atmosphere: None,
            },
            infinite_scan: wide_band(obs),
            finite_scan,
            channels: None,
        })
    }
}
