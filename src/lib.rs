//! # v2ref — squared-visibility estimators, reference implementation
//!
//! v2ref implements the two wide-band squared-visibility estimators of
//! G. Perrin & S. T. Ridgway, *Squared visibility estimators: calibrating
//! biases to reach very high dynamic range*: $V_1^2$, the sum of the squared
//! moduli of the Fourier components of the interferogram, and $V_2^2$, the
//! squared modulus of their complex sum. It computes their biases from
//! spectral bandwidth, chromatic dispersion, finite scan length, integrating
//! detectors and differential piston, and their variances and SNR under
//! detector and photon noise, each checked against a closed form, a Monte
//! Carlo and a golden file.
//!
//! ## Units
//!
//! Wavelength λ and OPD x in µm, wavenumber σ in µm⁻¹, angular diameter θ in
//! mas, spatial frequency S in cycles/arcsec ($S = B\sigma_\mathrm{eff}$),
//! baseline B in m, fringe frequency in Hz, phases in rad, counts in photons
//! per sample. Names carry their unit where it is not obvious.
//!
//! ## Paper → code
//!
//! | paper | module / function | tests |
//! |---|---|---|
//! | Introduction, eq. `eq:dynamique` | [`dynamic_range::dynamic_range`] | `tests/claims.rs` |
//! | §2.1 eq. `eq:interferogramme`, weighting function W | [`spectrum::Spectrum`] ([`spectrum::Spectrum::mean_w`], [`spectrum::Spectrum::mean_w2`]) | `tests/spectrum.rs` |
//! | §2.2.2 sampled signals, integrating detector (sinc) | [`interferogram::Sampling`], [`interferogram::Interferogram::synthesize`], [`interferogram::sinc`] | `tests/interferogram.rs` |
//! | §2.2.2 eq. `eq:sampled_V`, FTS resolution R = σΔx | [`interferogram::Sampling::delta_sigma_per_um`] | `tests/interferogram.rs` |
//! | §3 eq. `eq:estimateurs` (spectral form) | [`estimator::v1_sq`], [`estimator::v2_sq`], [`estimator::wide_band`] | `tests/estimator.rs` |
//! | §3 uniform disk $V(S) = 2J_1(\pi\theta S)/(\pi\theta S)$ | [`source::Source::UniformDisk`], [`special::jinc`] | `tests/special.rs` |
//! | §3 continuum plus line example | [`source::Source::Composite`], [`source::FluxProfile`] | `tests/estimator.rs` |
//! | §3 Fig. 1, bandwidth bias | [`bandwidth::curve`], [`bandwidth::locate_max`] | `tests/claims.rs` |
//! | §4 dispersion phase $\phi = \tfrac12 D(\sigma-\sigma_0)^2$ | [`dispersion::SpectralPhase`] | `tests/estimator.rs` |
//! | Appendix, $B_k$ and the estimators from the DFT | [`estimator::dft`], [`estimator::raw_estimates`], [`estimator::noise_bias`], [`estimator::BinWindow`] | `tests/interferogram.rs` |
//! | §6 Kolmogorov/von Kármán turbulence, r0 from seeing, differential-piston PSD | [`turbulence::Turbulence`], [`turbulence::PistonSpectrum`], [`turbulence::differential_piston_variance_from_structure_um2`] | `tests/turbulence.rs` |
//! | §6 piston sequences, scans with piston, bias and scatter of V1, V2 | [`piston::synthesize_series`], [`piston::simulate`], [`piston::FringeTable`] | `tests/piston.rs`, `tests/cli_piston.rs` |
//! | §6 Figs. 4 and 5 | `figures::piston` (ids `fig4`, `fig5`) | `tests/piston_claims.rs` |
//! | the claims ledger | [`claims::evaluate`] | `tests/claims.rs` |
//! | figure data, golden files | [`figure`] | |
//!
//! ## Conventions
//!
//! The physics conventions (band edges, W, σ_eff, the dispersion's
//! peak-to-peak definition, sample 0 on the white-light fringe) are those of
//! the project's `CONVENTIONS.md`; the module docs state each one where it is
//! used. Where the paper is ambiguous, the choice and its effect are written
//! in the module docs and in `paper/reproduction.md`.

#![warn(missing_docs)]

pub mod bandwidth;
pub mod claims;
pub mod dispersion;
pub mod dynamic_range;
pub mod error;
pub mod estimator;
pub mod figure;
pub mod figures;
pub mod interferogram;
pub mod montecarlo;
pub mod observation;
pub mod oracle;
pub mod piston;
pub mod quadrature;
pub mod source;
pub mod special;
pub mod spectrum;
pub mod tolerance;
pub mod turbulence;

pub use error::{Error, Result};
