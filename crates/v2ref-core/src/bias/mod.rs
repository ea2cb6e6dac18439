//! §§3–5 of the paper: the deterministic biases of the two estimators —
//! spectral bandwidth (§3, with the continuum-plus-line example and the
//! normalization of V2, Fig. 0), chromatic dispersion (§4), finite scan
//! length (§5) and the integrating detector (§2.2.2); `report` (internal) is the
//! answer of `v2ref bias` and Python's `v2ref.bias`.

pub mod bandwidth;
pub mod channels;
pub mod dispersion;
pub mod finite_scan;
pub mod integration;
pub mod line;
pub mod normalization;
