//! Slow, obviously correct versions of the fast paths, kept for tests (as
//! RustFFT keeps its naive DFT beside the FFT algorithms).

use crate::formalism::estimator::dft_phase;
use crate::formalism::interferogram::{sinc, Sampling};
use crate::formalism::observation::Observation;
use num_complex::Complex64;

/// `B_k = Σ_i M_i e^{−2πi ik/N}` by the definition, O(N²).
pub fn naive_dft(samples: &[f64]) -> Vec<Complex64> {
    let n = samples.len();
    (0..n)
        .map(|k| {
            samples
                .iter()
                .enumerate()
                .map(|(i, &m)| {
                    let phase = dft_phase(i, k, n);
                    Complex64::from_polar(m, phase)
                })
                .sum()
        })
        .collect()
}

/// The modulated signal per unit continuum at OPD `x_um`, by adaptive
/// quadrature of `Re ∫ W V e^{iφ} e^{2πiσx} s(σ) dσ` (one integral per call).
pub fn fringe_adaptive(obs: &Observation, x_um: f64, integrating_dx_um: Option<f64>) -> f64 {
    obs.spectrum
        .mean_w_split(
            |s| {
                let filter = integrating_dx_um.map_or(1.0, |dx| sinc(s * dx));
                let carrier = Complex64::from_polar(filter, 2.0 * std::f64::consts::PI * s * x_um);
                obs.fringe_amplitude(s) * carrier
            },
            &obs.source.features_per_um(),
        )
        .re
}

/// The modulated samples m_i per unit continuum, each by adaptive quadrature.
pub fn interferogram_adaptive(obs: &Observation, sampling: &Sampling) -> Vec<f64> {
    let dx = sampling.integrating().then_some(sampling.dx_um());
    (0..sampling.samples())
        .map(|i| fringe_adaptive(obs, sampling.opd_um(i), dx))
        .collect()
}
