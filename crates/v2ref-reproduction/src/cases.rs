//! The paper's cases: every parameter of its figures and worked examples
//! that more than one part of the reproduction uses, the effort levels, and
//! the seeds. Claims and figures both take their setups from here, so that
//! neither depends on the other.
//!
//! # Seeds
//!
//! Every Monte Carlo of the reproduction starts from one of the named base
//! seeds below; each independent computation inside it derives its own seed
//! with [`crate::montecarlo::derive_seed`] from the base seed, a label naming
//! the computation and the parameters it computes (never its position in a
//! list), so that a point's result does not depend on what else is asked.

use crate::error::Result;
use crate::formalism::observation::{Frequency, Observation};
use crate::formalism::phase::SpectralPhase;
use crate::formalism::source::Source;
use crate::formalism::spectrum::{Band, Spectrum};
use crate::noise::ExampleSetup;
use crate::piston::turbulence::Turbulence;

/// How hard the Monte Carlo providers work.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Effort {
    /// Fewer trials and scans, same code paths (tests, `reproduce --quick`).
    Quick,
    /// The paper's sizes.
    Full,
}

// ---------------------------------------------------------------------------
// §3–§5: bandwidth, normalization and finite scan (Figs. 0–3)

/// The paper's uniform disk (Figs. 1–3), mas.
pub const DIAMETER_MAS: f64 = 43.0;
/// Centre wavelength of every band of Figs. 0–3, µm.
pub const WAVELENGTH_UM: f64 = 2.2;
/// The bandwidths of Fig. 1, nm.
pub const BANDWIDTHS_NM: [f64; 6] = [12.5, 25.0, 50.0, 100.0, 200.0, 400.0];
/// Smallest spatial frequency of Figs. 1–3 (zero baseline), cycles/arcsec.
pub const S_MIN_CPAS: f64 = 0.0;
/// Largest spatial frequency of Figs. 1–3, cycles/arcsec.
pub const S_MAX_CPAS: f64 = 80.0;

/// The grid [`S_MIN_CPAS`] = 0, step, 2 step, …, [`S_MAX_CPAS`]
/// (cycles/arcsec).
pub fn s_grid(step_cpas: f64) -> Vec<f64> {
    let n = ((S_MAX_CPAS - S_MIN_CPAS) / step_cpas).round() as usize;
    (0..=n).map(|i| S_MIN_CPAS + i as f64 * step_cpas).collect()
}

/// The paper's flat K band (2.0–2.4 µm, flat in wavenumber) of Figs. 0–3.
pub fn k_band() -> Spectrum {
    Spectrum::flat(Band::k())
}

/// `source` seen through `spectrum` at spatial frequency `s_cpas`
/// (cycles/arcsec) with spectral phase `phase`: the observation every
/// bias figure and claim sweeps over S.
pub fn observe_at(
    spectrum: &Spectrum,
    source: Source,
    s_cpas: f64,
    phase: &SpectralPhase,
) -> Result<Observation> {
    Observation::new(
        spectrum.clone(),
        source,
        Frequency::SpatialFreqCpas(s_cpas),
        phase.clone(),
    )
}

/// The paper's uniform disk of [`DIAMETER_MAS`].
pub fn disk() -> Source {
    Source::UniformDisk {
        diameter_mas: DIAMETER_MAS,
    }
}

/// Fig. 0: largest number of samples (a stroke of 511.5 µm).
pub const FIG0_MAX_SAMPLES: usize = 930;
/// Fig. 0: the smooth band edge shown, µm⁻¹ (raised-cosine ramp width).
pub const FIG0_EDGE_PER_UM: f64 = 0.02;
/// Fig. 0: spectral indices shown (S F ∝ σ^index).
pub const FIG0_INDICES: [f64; 3] = [-2.0, 2.0, 4.0];
/// Fig. 2 dispersions, peak-to-peak rad.
pub const DISPERSIONS_RAD: [f64; 3] = [1.0, 1.5, 2.0];

/// The strokes of the paper's Fig. 3, µm (nominal: N = round(stroke/δx)).
pub const STROKES_UM: [f64; 8] = [256.0, 128.0, 64.0, 32.0, 16.0, 8.0, 4.0, 2.0];
/// Sample spacing of Figs. 0 and 3: 4 samples per fringe at 2.2 µm.
pub const DX_UM: f64 = 2.2 / 4.0;
/// The ABCD case of Fig. 3: 4 samples per fringe at 2 µm, N = 4.
pub const ABCD_DX_UM: f64 = 0.5;
/// The accuracy the paper calls the best current one (0.2%).
pub const ACCURACY: f64 = 0.002;

/// The S grid step of Figs. 1 and 2: 0.1 cycles/arcsec (the nulls of the
/// 43 mas disk are 23.6 cycles/arcsec apart, their lobes several wide).
pub fn fig1_step(effort: Effort) -> f64 {
    match effort {
        Effort::Full => 0.1,
        Effort::Quick => 0.5,
    }
}

/// The S grid step of Fig. 3 (DFT path): 0.25 cycles/arcsec.
pub fn fig3_step(effort: Effort) -> f64 {
    match effort {
        Effort::Full => 0.25,
        Effort::Quick => 1.0,
    }
}

/// The S grid step of the convolution cross-check of Fig. 3.
pub fn fig3_check_step(effort: Effort) -> f64 {
    match effort {
        Effort::Full => 1.0,
        Effort::Quick => 4.0,
    }
}

// ---------------------------------------------------------------------------
// Appendix: estimator SNR (the worked examples)

/// The project's reading of the Appendix's worked examples: 128 samples,
/// δx = 0.5 µm, centred scan, sampling detector, n = 10 continuum photons per
/// sample, V = 1 (so `m_0 = n V`; `noise::example` explains the
/// choice).
pub fn appendix_setup() -> ExampleSetup {
    ExampleSetup {
        samples: 128,
        dx_um: 0.5,
        integrating: false,
        zero_start: false,
        photons: 10.0,
        visibility: 1.0,
    }
}

/// The detector noise of the worked examples, σ_det = 0.2 n (photons per
/// sample, n the continuum of [`appendix_setup`]).
pub const APPENDIX_READ_NOISE_PER_PHOTON: f64 = 0.2;

// ---------------------------------------------------------------------------
// §6: differential piston (Figs. 4 and 5)

/// The seed every piston figure derives its points' seeds from.
pub const FIGURE_SEED: u64 = 20_060_515;

/// The base seed of the Appendix's Monte Carlos (noise claims); each run
/// derives its own with [`crate::montecarlo::derive_seed`], labelled by the
/// claim it computes.
pub const APPENDIX_SEED: u64 = 20_040_712;
/// Seeing, arcsec at 2.2 µm.
pub const SEEING_ARCSEC: f64 = 1.0;
/// Wind speed, m/s.
pub const WIND_MPS: f64 = 10.0;
/// Aperture diameter, m.
pub const APERTURE_M: f64 = 0.45;
/// Fig. 5 baseline, m.
pub const FIG5_BASELINE_M: f64 = 18.0;

/// The paper's turbulence (1 arcsec at 2.2 µm, 10 m/s, Kolmogorov).
pub fn paper_turbulence() -> Turbulence {
    Turbulence::from_seeing(SEEING_ARCSEC, 2.2, WIND_MPS, None).expect("valid constants")
}

/// Fig. 5's fringe frequencies: `count` log-spaced values from 50 to 2000 Hz.
pub fn fig5_frequencies(count: usize) -> Vec<f64> {
    let (lo, hi) = (50f64.ln(), 2000f64.ln());
    (0..count)
        .map(|i| (lo + (hi - lo) * i as f64 / (count - 1) as f64).exp())
        .collect()
}

/// Fig. 5 sizes: (frequencies, scans per point).
pub fn fig5_size(effort: Effort) -> (usize, usize) {
    match effort {
        Effort::Full => (32, 10_000),
        Effort::Quick => (9, 1_000),
    }
}

/// Fig. 4 sizes: (spatial-frequency step in cycles/arcsec over 0–80, scans).
pub fn fig4_size(effort: Effort) -> (f64, usize) {
    match effort {
        Effort::Full => (2.0, 1_000),
        Effort::Quick => (10.0, 200),
    }
}
