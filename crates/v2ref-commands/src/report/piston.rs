//! The answer of a piston run, as `v2ref piston --json` prints it and
//! `v2ref.piston()` returns it: one place, so that the CLI and the Python
//! package cannot drift apart.

use crate::formalism::estimator::BinWindow;
use crate::formalism::interferogram::Sampling;
use crate::formalism::observation::Observation;
use crate::piston::scan::{Detector, PistonReference};
use crate::piston::simulation::PistonRun;
use crate::piston::spectrum::PistonSpectrum;
use crate::record::InputsRecord;
use crate::report::model_comparison::PsdComparison;
use serde::Serialize;

/// One fringe frequency's bias and scatter of V1 and V2 (of V, not V²).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PistonRow {
    /// Fringe frequency f, Hz.
    pub fringe_hz: f64,
    /// ⟨V1 − V1(no piston)⟩.
    pub bias_v1: f64,
    /// ⟨V2 − V2(no piston)⟩.
    pub bias_v2: f64,
    /// Standard deviation of V1 over the scans.
    pub scatter_v1: f64,
    /// Standard deviation of V2 over the scans.
    pub scatter_v2: f64,
    /// Standard error of `bias_v1`.
    pub bias_v1_stderr: f64,
    /// Standard error of `bias_v2`.
    pub bias_v2_stderr: f64,
    /// Standard error of `scatter_v1`.
    pub scatter_v1_stderr: f64,
    /// Standard error of `scatter_v2`.
    pub scatter_v2_stderr: f64,
    /// V1 without piston.
    pub v1_no_piston: f64,
    /// V2 without piston.
    pub v2_no_piston: f64,
    /// Duration of one scan, s.
    pub scan_time_s: f64,
    /// RMS of the piston left in a scan after the packet reference, µm.
    pub residual_rms_um: f64,
    /// Scans simulated.
    pub scans: usize,
    /// Independent piston sequences the scans are cut from; the standard
    /// errors come from the spread between them (`sequences − 1` degrees of
    /// freedom), valid however correlated consecutive scans are.
    pub sequences: usize,
    /// Independent scans worth the bias of V1 (variance / stderr²): below
    /// `scans` when consecutive scans share their errors, above it when
    /// their errors alternate in sign; uncertain with the sequences'
    /// K − 1 degrees of freedom.
    pub effective_scans_v1: f64,
    /// Independent scans worth the bias of V2.
    pub effective_scans_v2: f64,
    /// Time spanned by each sequence in piston correlation times B/v.
    pub span_correlation_times: f64,
    /// Seed of this frequency's stream.
    pub seed: u64,
}

impl PistonRow {
    /// The row of `run` in the bins of `window`.
    pub fn new(run: &PistonRun, window: BinWindow) -> PistonRow {
        let w = run.window(window);
        PistonRow {
            fringe_hz: run.fringe_hz,
            bias_v1: w.v1.mean,
            bias_v2: w.v2.mean,
            scatter_v1: w.v1.std,
            scatter_v2: w.v2.std,
            bias_v1_stderr: w.v1.stderr_mean,
            bias_v2_stderr: w.v2.stderr_mean,
            scatter_v1_stderr: w.v1.stderr_std,
            scatter_v2_stderr: w.v2.stderr_std,
            v1_no_piston: w.v1_no_piston,
            v2_no_piston: w.v2_no_piston,
            scan_time_s: run.scan_time_s,
            residual_rms_um: run.residual_rms_um,
            scans: run.scans,
            sequences: run.sequences,
            effective_scans_v1: w.v1_effective_scans,
            effective_scans_v2: w.v2_effective_scans,
            span_correlation_times: run.span_correlation_times,
            seed: run.seed,
        }
    }
}

/// A piston run: its inputs, the turbulence it implies and one row per
/// fringe frequency.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PistonReport {
    /// What was asked, in its units.
    pub inputs: InputsRecord,
    /// |V| of the source at σ_eff on this baseline.
    pub visibility: f64,
    /// The spectrum model (`two-aperture` or `three-slope`).
    pub psd: &'static str,
    /// Wind direction from the baseline, degrees.
    pub wind_angle_deg: f64,
    /// The three-slope corners (ν1, ν2), Hz, when that model is used
    /// (absent otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub psd_corners_hz: Option<[f64; 2]>,
    /// `sampled` or `integrating`.
    pub detector: &'static str,
    /// The bins summed.
    pub bins: &'static str,
    /// Where the fringe packet sits in each scan.
    pub reference: &'static str,
    /// Projected baseline B, m.
    pub baseline_m: f64,
    /// S = B σ_eff, cycles/arcsec.
    pub spatial_freq_cpas: f64,
    /// r0 at λ0, m.
    pub r0_m: f64,
    /// r0/v, s (the paper's coherence time).
    pub r0_over_v_s: f64,
    /// The usual coherence time τ0 = 0.314 r0/v, s.
    pub tau0_s: f64,
    /// RMS differential piston, µm.
    pub piston_rms_um: f64,
    /// N.
    pub samples: usize,
    /// δx, µm.
    pub dx_um: f64,
    /// Δx, µm.
    pub stroke_um: f64,
    /// One row per fringe frequency, in the order asked.
    pub results: Vec<PistonRow>,
    /// With the three-slope spectrum, per fringe frequency: how far the
    /// piston moves within one scan under each model of the same site, and
    /// the note that says why they differ (absent otherwise).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub three_slope_comparison: Vec<ComparisonNote>,
}

/// The two spectra compared over the scans of one fringe frequency.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ComparisonNote {
    /// f, Hz.
    pub fringe_hz: f64,
    /// The numbers.
    #[serde(flatten)]
    pub comparison: PsdComparison,
    /// What they mean, in one line.
    pub note: String,
}

/// What a piston run was made of.
#[derive(Debug, Clone, Copy)]
pub struct PistonSetting<'a> {
    /// The observation.
    pub obs: &'a Observation,
    /// The piston spectrum (turbulence, model, wind).
    pub spectrum: &'a PistonSpectrum,
    /// The scan.
    pub sampling: &'a Sampling,
    /// The detector.
    pub detector: Detector,
    /// The bins summed.
    pub window: BinWindow,
    /// Where the fringe packet sits.
    pub reference: PistonReference,
}

impl PistonReport {
    /// The report of `runs` made with `setting`, whose inputs are `inputs`.
    pub fn new(inputs: InputsRecord, setting: PistonSetting<'_>, runs: &[PistonRun]) -> Self {
        let PistonSetting {
            obs,
            spectrum,
            sampling,
            detector,
            window,
            reference,
        } = setting;
        let turb = spectrum.turbulence();
        PistonReport {
            inputs,
            visibility: obs
                .source
                .visibility(obs.spectrum.sigma_eff_per_um(), obs.baseline_m)
                .norm(),
            psd: spectrum.model().name(),
            wind_angle_deg: spectrum.wind_angle_deg(),
            psd_corners_hz: spectrum
                .three_slope()
                .map(|m| [m.corner_low_hz(), m.corner_high_hz()]),
            detector: detector.name(),
            bins: window.name(),
            reference: reference.name(),
            baseline_m: obs.baseline_m,
            spatial_freq_cpas: obs.spatial_freq_cpas(),
            r0_m: turb.r0_m(),
            r0_over_v_s: turb.coherence_time_s(),
            tau0_s: turb.tau0_s(),
            piston_rms_um: spectrum.rms_um(),
            samples: sampling.samples(),
            dx_um: sampling.dx_um(),
            stroke_um: sampling.stroke_um(),
            results: runs.iter().map(|r| PistonRow::new(r, window)).collect(),
            three_slope_comparison: Vec::new(),
        }
    }
}
