//! The conformance vectors: a handful of small synth sets, each isolating
//! one effect (or two), that a pipeline runs its estimator on and scores
//! (`golden/vectors/`, regenerated and compared by `v2ref golden --check`).

use crate::piston::PistonReference;
use crate::simulator::{Inputs, PistonInputs, SourceInput, SpectrumInput};

/// Rows of every vector: enough for the score to catch a 1–3 % error of
/// the mean (its `min_detectable_rel_bias` is printed per vector), few
/// enough that all vectors weigh a few MB.
pub const VECTOR_ROWS: u64 = 1000;
/// Samples per row of the vectors (except the odd-N one).
pub const VECTOR_SAMPLES: usize = 64;
/// Replicates in each vector's reference run.
pub const VECTOR_REFERENCE_BLOCKS: u64 = 32;

/// One conformance vector.
#[derive(Debug, Clone, PartialEq)]
pub struct Vector {
    /// File stem under `golden/vectors/`.
    pub name: &'static str,
    /// What it tests, in one line.
    pub tests: &'static str,
    /// The configuration.
    pub inputs: Inputs,
    /// Its seed.
    pub seed: u64,
}

fn base() -> Inputs {
    Inputs {
        samples: VECTOR_SAMPLES,
        source: SourceInput::Point,
        visibility: 0.6,
        photons: 50.0,
        read_noise: 0.0,
        photon_noise: true,
        ..Inputs::default()
    }
}

fn photon(inputs: Inputs) -> Inputs {
    Inputs {
        photon_noise: true,
        ..inputs
    }
}

fn piston(fringe_hz: f64) -> Inputs {
    Inputs {
        piston: Some(PistonInputs {
            reference: PistonReference::Mean,
            ..PistonInputs::paper(fringe_hz)
        }),
        ..base()
    }
}

/// Every vector, in the order of the README table.
pub fn catalogue() -> Vec<Vector> {
    let k_band = SpectrumInput::Flat {
        wavelength_um: 2.2,
        bandwidth_nm: 400.0,
    };
    vec![
        Vector {
            name: "noise_gaussian",
            tests: "detector noise only (σ_det = 3 photons): the V1², V2² bias |K|Σσ² and Σ|u_i|²σ², normalization",
            inputs: Inputs {
                read_noise: 3.0,
                photon_noise: false,
                ..base()
            },
            seed: 101,
        },
        Vector {
            name: "noise_poisson",
            tests: "photon noise only: the bias from n_i = c_i + m_i (not m_i), Poisson scatter",
            inputs: base(),
            seed: 102,
        },
        Vector {
            name: "noise_both",
            tests: "photon and detector noise together (cross term of the variance)",
            inputs: Inputs {
                read_noise: 2.0,
                ..base()
            },
            seed: 103,
        },
        Vector {
            name: "bandwidth_disk",
            tests: "full K band, 43 mas uniform disk at 20 cycles/arcsec (V ≈ 0.33): bandwidth smearing of V1² against V2²",
            inputs: photon(Inputs {
                spectrum: k_band,
                source: SourceInput::Ud { diameter_mas: 43.0 },
                baseline_m: 20.0 / 40.0 * Inputs::default().baseline_m,
                visibility: 1.0,
                photons: 50.0,
                ..base()
            }),
            seed: 104,
        },
        Vector {
            name: "dispersion",
            tests: "3 rad peak-to-peak quadratic dispersion over K: V2² loses contrast, V1² does not",
            inputs: Inputs {
                dispersion_pp_rad: 3.0,
                ..base()
            },
            seed: 105,
        },
        Vector {
            name: "short_scan_odd",
            tests: "odd N = 25 (12.5 µm stroke): sample positions and bins 1 … (N−1)/2 for odd N, a scan shorter than the coherence length",
            inputs: Inputs {
                samples: 25,
                ..base()
            },
            seed: 106,
        },
        Vector {
            name: "integrating",
            tests: "integrating detector at 0.7 µm per sample: the sinc(σδx) loss of the calibrator and the source",
            inputs: Inputs {
                integrating: true,
                dx_um: 0.7,
                ..base()
            },
            seed: 107,
        },
        Vector {
            name: "piston_low",
            tests: "differential piston at 100 Hz (1″ seeing, 10 m/s, 18 m): piston bias and correlated scans, with photon noise",
            inputs: piston(100.0),
            seed: 108,
        },
        Vector {
            name: "piston_high",
            tests: "differential piston at 1000 Hz: piston nearly frozen in each scan, with photon noise",
            inputs: piston(1000.0),
            seed: 109,
        },
    ]
}
