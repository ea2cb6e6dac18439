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
//! ## Quick start
//!
//! ```
//! use v2ref::formalism::phase::SpectralPhase;
//! use v2ref::formalism::estimator::wide_band;
//! use v2ref::formalism::observation::{Frequency, Observation};
//! use v2ref::formalism::source::Source;
//! use v2ref::formalism::spectrum::{Band, Spectrum};
//!
//! // A 43 mas uniform disk in the full K band (2.0–2.4 µm), at its first null.
//! let k = Spectrum::flat(Band::new(2.2, 0.4)?);
//! let obs = Observation::new(
//!     k,
//!     Source::uniform_disk(43.0)?,
//!     Frequency::SpatialFreqCpas(28.36),
//!     SpectralPhase::zero(),
//! )?;
//! let wb = wide_band(&obs);
//! assert!(wb.v_mono < 1e-3);            // the monochromatic visibility vanishes…
//! assert!(wb.v1 - wb.v_mono > 0.04);    // …but the wide band fills the null for V1
//! assert!(wb.v2 < wb.v1);               // and much less for V2
//! # Ok::<(), v2ref::Error>(())
//! ```
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
//! | §2.1 eq. `eq:interferogramme`, weighting function W, σ_eff | [`spectrum::Spectrum`] ([`spectrum::Spectrum::mean_w`], [`spectrum::Spectrum::mean_w2`], [`spectrum::Spectrum::sigma_eff_per_um`]), [`quadrature`] | `tests/foundation.rs`, `tests/spectrum_csv.rs` |
//! | §2.2.1 continuous signals; extended visibility | [`observation::Observation::fringe_amplitude`] | `tests/foundation.rs` |
//! | §2.2.2 sampled signals, sample 0 on the white-light fringe | [`interferogram::Sampling`], [`interferogram::Interferogram::synthesize`], [`interferogram::SpectralNodes`] (slow oracle: [`oracle`]) | `tests/foundation.rs` |
//! | §2.2.2 integrating detector, sinc(σδx), 2/π at Nyquist | [`interferogram::sinc`], [`integration::wide_band_loss`], [`integration::calibrated_bias`] | `tests/foundation.rs`, `tests/bias_normalization.rs` |
//! | §2.2.2 eq. `eq:sampled_V`, FTS resolution R = σΔx | [`interferogram::Sampling::delta_sigma_per_um`], [`finite_scan::convolution_bins`] | `tests/bias_finite_scan.rs` |
//! | §3 eq. `eq:estimateurs` (spectral form) | [`estimator::v1_sq`], [`estimator::v2_sq`], [`estimator::wide_band`] | `tests/foundation.rs`, `tests/properties.rs` |
//! | §3 uniform disk $V(S) = 2J_1(\pi\theta S)/(\pi\theta S)$ | [`source::Source::UniformDisk`], [`special::jinc`], [`special::bessel_j1_zero`] | `tests/special.rs` |
//! | §3 continuum plus line example (0.50042) | [`source::Source::Composite`], [`source::FluxProfile`], [`line::channel_visibility`], [`line::top_hat_closed_form`] | `tests/bias_line.rs`, `tests/foundation.rs` |
//! | §3 Fig. 0, V2 normalization factor against stroke | [`normalization::deviation_curve`], [`normalization::threshold_stroke`] | `tests/bias_normalization.rs` |
//! | §3 Fig. 1, bandwidth bias | [`bandwidth::curve`], [`bandwidth::locate_max`] | `tests/bias_bandwidth.rs` |
//! | §4 dispersion phase $\phi = \tfrac12 D(\sigma-\sigma_0)^2$ | [`dispersion::SpectralPhase`] | `tests/properties.rs` |
//! | §4 Fig. 2, V2 of a point source under dispersion (Fresnel closed form) | [`special::fresnel::point_source_v2_sq`], [`special::fresnel::fresnel_cs`] | `tests/bias_dispersion.rs` |
//! | §4 fluoride-fibre example (ZBLAN, Gan 1995) | [`dispersion::zblan_peak_to_peak_rad`] | `tests/bias_dispersion.rs` |
//! | §5 Fig. 3, finite scan: DFT path and eq. `eq:sampled_V` convolution path | [`finite_scan::bias`], [`finite_scan::Kernel`] | `tests/bias_finite_scan.rs` |
//! | §6 Kolmogorov/von Kármán turbulence, r0 from seeing, differential-piston PSD | [`turbulence::Turbulence`], [`turbulence::PistonSpectrum`], [`turbulence::differential_piston_variance_from_structure_um2`] | `tests/turbulence.rs` |
//! | §6 piston sequences, scans with piston, bias and scatter of V1, V2 | [`piston::synthesize_series`], [`piston::simulate`], [`piston::FringeTable`] | `tests/piston.rs`, `tests/cli_piston.rs` |
//! | §6 Figs. 4 and 5 | [`figures::all`] (ids `fig4`, `fig5`) | `tests/piston_claims.rs`, `tests/golden.rs` |
//! | Appendix, $B_k$ and the estimators from the DFT | [`estimator::dft`], [`estimator::raw_estimates`], [`estimator::noise_bias`], [`estimator::BinWindow`] (slow oracle: [`oracle::naive_dft`]) | `tests/foundation.rs`, `tests/properties.rs` |
//! | Appendix, noise moments, bias terms, var V1², var V2², SNR (`published` / `exact`) | [`noise::moments`], [`noise::appendix_stats`], [`noise::worked_example`] | `tests/noise.rs`, `tests/noise_mc.rs` |
//! | Appendix, filtered samples (window factor) — exact quadratic form | [`window_variance::window_stats`] | `tests/noise.rs`, `tests/noise_mc.rs` |
//! | Monte Carlo: deterministic parallel driver, noisy interferograms | [`montecarlo::run_units`], [`montecarlo::simulate_noisy`], [`montecarlo::WindowedEstimators`] | `tests/montecarlo_noise.rs`, `tests/cli_noise.rs` |
//! | Figs. 0–5 as data, golden files | [`figure`], [`figures::all`], [`golden::check`], [`golden::update`] | `tests/golden.rs`, `tests/bias_snapshots.rs` |
//! | the claims ledger | [`claims::evaluate`], [`claims::to_markdown`] | `tests/claims.rs` |
//! | tolerances (one home) | [`tolerance`] | every test |
//!
//! ## Conventions
//!
//! The physics conventions (band edges, W, σ_eff, the dispersion's
//! peak-to-peak definition, sample 0 on the white-light fringe) are those of
//! the project's `CONVENTIONS.md`; the module docs state each one where it is
//! used. Where the paper is ambiguous, the choice and its effect are written
//! in the module docs and in `paper/reproduction.md`.

#![warn(missing_docs)]

pub mod bias;
pub mod error;
pub mod formalism;
pub mod math;
pub mod montecarlo;
pub mod noise;
pub mod piston;
pub mod reproduction;
pub mod tolerance;

pub use error::{Error, Result};
