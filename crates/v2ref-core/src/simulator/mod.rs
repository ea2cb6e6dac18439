//! The end-to-end simulator: raw interferograms with every effect of the
//! paper at once and in any combination — the source and its spectrum
//! (flat band or tabulated, §§2–3), dispersion (§4), finite scan and
//! sampling (§5), the integrating detector, a differential-piston sequence
//! (§6), photon and detector noise (Appendix).
//!
//! [`Inputs`] holds every physical input as plain numbers; [`Model`] is
//! the configuration built from them (the noise-free, piston-free source
//! and calibrator); [`Model::rows`] draws a set of noisy rows
//! (`rows`); `estimate` computes each row's V1² and V2² (raw,
//! bias-subtracted, normalized: the conformance kit's reference,
//! re-exported at [`crate::conformance::estimate`]); [`run::simulate`]
//! reduces them to the running statistics of the normalized estimators,
//! beside their closed forms.

pub mod channel_moments;
pub mod channels;
pub mod estimate;
pub(crate) mod inputs;
pub(crate) mod layout;
pub(crate) mod model;
pub mod rows;
pub mod run;

pub use inputs::{Inputs, PistonInputs, SourceInput, SpectrumInput};
pub use layout::{RowLayout, RowTiming, SetLayout, MAX_DEAD_TIME_S, MAX_OBSERVATIONS};
pub use model::Model;
pub use rows::{PistonFacts, Rows, ROWS_PER_UNIT};
pub use run::{simulate, PistonEffect, SimulationRun};
