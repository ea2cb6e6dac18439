//! §6 of the paper, *Effect of differential piston*: the turbulence and the
//! differential-piston spectrum, piston sequences, scans through them, and
//! the Monte Carlo of the bias and scatter they give V1 and V2.
//!
//! - [`turbulence`]: Kolmogorov turbulence, r0 and seeing.
//! - [`spectrum`]: the temporal spectrum of the differential piston
//!   ([`spectrum::PistonSpectrum`]).
//! - [`transverse`]: the transverse integrals G and S under that spectrum,
//!   by quadrature and tabulated ([`transverse::TransverseTable`]).
//! - [`three_slope`]: the three-slope model of that spectrum (Conan et al.
//!   1995 asymptotes, as in Perrin 1997), [`spectrum::PistonPsdModel`].
//! - `model_comparison` (internal): why the three-slope model gives less piston
//!   than the two-aperture spectrum of the same site with an outer scale.
//! - `series`: piston sequences synthesised from that spectrum.
//! - `fringe_table`: the fringe tabulated against OPD.
//! - `scan`: the detectors, the packet reference and one scan's samples.
//! - `calibration` ([`Calibration`]): the piston-free calibration of each detector.
//! - `simulation`: the Monte Carlo over consecutive scans (Figs. 4, 5).
//! - `report` (internal): a run's answer (the CLI's JSON, the Python dict).
//!
//! The items of `series`, `fringe_table`, `scan`, `sequences` and
//! `simulation` are public here, as `v2ref_core::piston::simulate_piston` etc. (their
//! one path).

pub(crate) mod calibration;
pub(crate) mod fringe_table;
pub mod scan;
pub mod sequences;
pub mod series;
pub mod simulation;
pub mod spectrum;
pub mod three_slope;
pub mod transverse;
pub mod turbulence;

pub use calibration::Calibration;
pub use fringe_table::*;
pub use scan::*;
pub use sequences::*;
pub use series::*;
pub use simulation::*;
