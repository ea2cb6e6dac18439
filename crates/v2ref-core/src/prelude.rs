//! The items a user calls first, in one import:
//!
//! ```
//! use v2ref_core::prelude::*;
//!
//! // A 2 mas disk in H (1.5–1.8 µm) on a 100 m baseline, scanned over 64 µm.
//! let h = Spectrum::flat(Band::new(1.65, 0.3)?);
//! let obs = Observation::new(h, Source::uniform_disk(2.0)?, Frequency::BaselineM(100.0), SpectralPhase::zero())?;
//! let infinite_scan = wide_band(&obs);
//! let scan = sampled_wide_band(&obs, &Sampling::from_stroke(64.0, 0.4, false)?, BinWindow::Positive)?;
//! assert!((scan.v1_sq - infinite_scan.v1 * infinite_scan.v1).abs() < 1e-2);
//! # Ok::<(), v2ref_core::Error>(())
//! ```
//!
//! | what | item |
//! |---|---|
//! | the band and the source spectrum | [`Band`], [`Spectrum`] |
//! | the source | [`Source`] |
//! | an observation: spectrum, source, baseline, spectral phase | [`Observation`], [`Frequency`], [`SpectralPhase`] |
//! | a scan and its samples | [`Sampling`], [`Interferogram`] |
//! | the estimators, infinite scan | [`wide_band`] ([`WideBand`]) |
//! | the estimators from the DFT of a sampled scan | [`sampled_wide_band`], [`dft`], [`raw_estimates`], [`BinWindow`] |
//! | the additive-noise bias of the raw estimators | [`noise_bias`] |
//! | noise closed forms (Appendix) | [`NoiseModel`], [`appendix_stats`], [`Formula`] |
//! | Monte Carlo of noisy scans | [`simulate_noisy`], [`NoisySpec`] |
//! | finite-scan bias | [`finite_scan_bias`] |
//! | differential piston | [`Turbulence`], [`PistonSpectrum`], [`ScanSetup`], [`simulate_piston`] |
//! | errors | [`Error`], [`Result`] |

pub use crate::bias::finite_scan::finite_scan_bias;
pub use crate::error::{Error, Result};
pub use crate::formalism::estimator::{
    dft, noise_bias, raw_estimates, sampled_wide_band, wide_band, BinWindow, WideBand,
};
pub use crate::formalism::interferogram::{Interferogram, Sampling};
pub use crate::formalism::observation::{Frequency, Observation};
pub use crate::formalism::phase::SpectralPhase;
pub use crate::formalism::source::Source;
pub use crate::formalism::spectrum::{Band, Spectrum};
pub use crate::noise::simulation::{simulate_noisy, NoisySpec};
pub use crate::noise::{appendix_stats, Formula, NoiseModel};
pub use crate::piston::simulate_piston;
pub use crate::piston::spectrum::PistonSpectrum;
pub use crate::piston::turbulence::Turbulence;
pub use crate::piston::ScanSetup;
