//! §6: one scan through the piston — the OPD of each sample, in µm, is the
//! nominal position plus the differential piston minus the reference that
//! locates the fringe packet; the detector reads the fringe at the sample
//! time or averages it over the sample interval.
//!
//! # Scans
//!
//! The OPD at time t of a scan is `v t + p(t) − p_ref`, v = f λ0 (f the
//! fringe frequency), sampled every δx/v; N samples (scan Δx = N δx). The
//! sampled detector reads the fringe at the sample time; the integrating
//! detector averages it over the sample's own interval, computed with K
//! Gauss–Legendre sub-samples in time (the piston interpolated between its
//! samples by a cubic), which converges to the exact average — with no
//! piston, to the sinc(σδx)-filtered fringe (`tests/piston.rs` shows it).
//!
//! `p_ref` is the paper's unstated choice of where the fringe packet sits in
//! the scan ([`PistonReference`]). By default it is the piston averaged over
//! the scan (a group-delay tracker, or the packet located on the scan
//! itself, centres the scan on the mean OPD error), so that a piston frozen
//! during the scan has no effect on either estimator — the paper's premise
//! that fast scanning freezes the piston. The alternatives are the piston at
//! the middle (zero-OPD) sample, which makes the all-bins V2 = N²M_0²
//! immune by construction, and no correction at all.

use crate::error::{self, Error, Result};
use crate::formalism::interferogram::Sampling;
use crate::math::quadrature::gauss_legendre;
use crate::piston::fringe_table::{FringeTable, BATCH};
use serde::Serialize;

pub use crate::record::PistonReference;

/// Most Gauss–Legendre sub-samples per integrating sample.
pub const MAX_SUB_SAMPLES: usize = 64;
/// Default sub-samples of the integrating detector: at 4 samples per 2 µm
/// fringe the Gauss–Legendre average is converged to ~2e-13 of the fringe
/// amplitude (errors 8e-2, 1e-3, 1e-8, 2e-13 for K = 1, 2, 4, 6; see
/// `tests/piston.rs`).
pub const DEFAULT_SUB_SAMPLES: usize = 6;

/// How each sample sees the fringe.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
pub enum Detector {
    /// The fringe at the sample time.
    Sampled,
    /// The fringe averaged over the sample's interval, with this many
    /// Gauss–Legendre sub-samples (1 … [`MAX_SUB_SAMPLES`]).
    Integrating {
        /// K.
        sub_samples: usize,
    },
}

impl Detector {
    /// Sub-sample offsets within a sample (units of the sample interval,
    /// centred on 0) and their weights (summing to 1).
    pub(crate) fn sub_samples(&self) -> Result<(Vec<f64>, Vec<f64>)> {
        match *self {
            Detector::Sampled => Ok((vec![0.0], vec![1.0])),
            Detector::Integrating { sub_samples } => {
                if !(1..=MAX_SUB_SAMPLES).contains(&sub_samples) {
                    return Err(Error::OutOfRange {
                        param: "sub_samples",
                        value: sub_samples as f64,
                        accepted: format!("1 to {MAX_SUB_SAMPLES}"),
                    });
                }
                let (x, w) = gauss_legendre(sub_samples)?;
                Ok((
                    x.iter().map(|u| 0.5 * u).collect(),
                    w.iter().map(|w| 0.5 * w).collect(),
                ))
            }
        }
    }

    /// `"sampled"` or `"integrating"`.
    pub fn name(&self) -> &'static str {
        match self {
            Detector::Sampled => "sampled",
            Detector::Integrating { .. } => "integrating",
        }
    }
}

/// One scan's acquisition parameters.
///
/// # Example
///
/// ```
/// use v2ref_core::prelude::*;
/// // The paper's scans: 128 samples of 0.5 µm, fringes at 2.2 µm.
/// let s = ScanSetup::paper(1000.0);
/// assert_eq!(s.opd_speed_um_per_s(), 2200.0);           // v = f λ0
/// assert!((s.scan_time_s() - 128.0 * 0.5 / 2200.0).abs() < 1e-15); // N δx / v
/// # Ok::<(), v2ref_core::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScanSetup {
    /// N.
    pub samples: usize,
    /// δx, µm.
    pub dx_um: f64,
    /// λ0 that defines the fringe frequency f = v/λ0, µm.
    pub wavelength_um: f64,
    /// f, Hz.
    pub fringe_hz: f64,
    /// Where the packet sits.
    pub reference: PistonReference,
}

impl ScanSetup {
    /// The paper's scans at fringe frequency `fringe_hz`: 128 samples of
    /// 0.5 µm (a 64 µm stroke, four samples per 2.0 µm fringe), λ0 = 2.2 µm,
    /// the packet centred on the scan-mean piston ([`PistonReference::Mean`]).
    pub fn paper(fringe_hz: f64) -> ScanSetup {
        ScanSetup {
            samples: 128,
            dx_um: 0.5,
            wavelength_um: 2.2,
            fringe_hz,
            reference: PistonReference::Mean,
        }
    }

    /// Checks the values.
    pub fn validate(&self) -> Result<()> {
        Sampling::new(self.samples, self.dx_um, false)?;
        error::positive("wavelength_um", self.wavelength_um)?;
        error::in_range("fringe_hz", self.fringe_hz, 1e-3, 1e7)?;
        Ok(())
    }

    /// OPD speed v = f λ0, µm/s.
    pub fn opd_speed_um_per_s(&self) -> f64 {
        self.fringe_hz * self.wavelength_um
    }
    /// Time per sample δx/v, s.
    pub fn sample_time_s(&self) -> f64 {
        self.dx_um / self.opd_speed_um_per_s()
    }
    /// Duration of one scan N δx / v, s.
    pub fn scan_time_s(&self) -> f64 {
        self.samples as f64 * self.sample_time_s()
    }
}

/// The modulated samples (per unit continuum, DFT order as
/// [`Sampling::opd_um`]) of one scan whose OPD error at time τ (in sample
/// intervals from the scan start, sample j centred on τ = j) is
/// `piston(τ)` µm; `reference_um` is subtracted from it.
pub fn scan_samples(
    table: &FringeTable,
    setup: &ScanSetup,
    detector: Detector,
    piston: impl Fn(f64) -> f64,
    reference_um: f64,
) -> Result<Vec<f64>> {
    let (u, w) = detector.sub_samples()?;
    let mut out = vec![0.0; setup.samples];
    fill_scan(table, setup, &u, &w, &piston, reference_um, &mut out);
    Ok(out)
}

#[inline]
pub(crate) fn fill_scan(
    table: &FringeTable,
    setup: &ScanSetup,
    u: &[f64],
    w: &[f64],
    piston: &impl Fn(f64) -> f64,
    reference_um: f64,
    out: &mut [f64],
) {
    let n = setup.samples;
    let half = n / 2;
    let (mut x, mut fringe) = ([0.0; BATCH], [0.0; BATCH]);
    // The samples in batches (the table reads a batch at a time); within a
    // sample, the sub-samples summed in order, as one by one.
    for first in (0..n).step_by(BATCH) {
        let batch = BATCH.min(n - first);
        let mut acc = [0.0; BATCH];
        for (&uk, &wk) in u.iter().zip(w) {
            for (b, x) in x[..batch].iter_mut().enumerate() {
                let j = first + b;
                let nominal = (j as f64 - half as f64) * setup.dx_um;
                *x = nominal + uk * setup.dx_um + piston(j as f64 + uk) - reference_um;
            }
            table.fringes(&x[..batch], &mut fringe[..batch]);
            for (acc, f) in acc[..batch].iter_mut().zip(&fringe[..batch]) {
                *acc += wk * f;
            }
        }
        for (b, acc) in acc[..batch].iter().enumerate() {
            out[(first + b + n - half) % n] = *acc;
        }
    }
}

/// Cubic (Catmull–Rom) interpolation of a periodic sequence at position t.
#[inline]
pub(crate) fn interp(series: &[f64], t: f64) -> f64 {
    let m = series.len();
    let fl = t.floor();
    let u = t - fl;
    if u == 0.0 {
        return series[(fl as i64).rem_euclid(m as i64) as usize];
    }
    let i = fl as i64;
    let (p0, p1, p2, p3) = if i >= 1 && (i as usize) + 2 < m {
        let i = i as usize;
        (series[i - 1], series[i], series[i + 1], series[i + 2])
    } else {
        let at = |k: i64| series[(i + k).rem_euclid(m as i64) as usize];
        (at(-1), at(0), at(1), at(2))
    };
    let u2 = u * u;
    let u3 = u2 * u;
    0.5 * ((2.0 * p1)
        + (-p0 + p2) * u
        + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * u2
        + (-p0 + 3.0 * p1 - 3.0 * p2 + p3) * u3)
}
