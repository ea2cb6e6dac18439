//! §6: the fringe of a source per unit continuum, m(x) (x the OPD in µm),
//! tabulated so that the piston Monte Carlo can read it at any OPD the
//! piston pushes a sample to.
//!
//! # Tabulated fringe
//!
//! The fringe `m(x) = Re Σ_j a_j e^{2πiσ_j x}` ([`SpectralNodes`]) is written
//! `Re[e^{2πiσ_c x} a(x)]` with the slowly varying complex envelope
//! `a(x) = Σ_j a_j e^{2πi(σ_j − σ_c)x}`, tabulated with its derivative and
//! interpolated by cubic Hermite polynomials ([`FringeTable`]); the grid step
//! bounds the interpolation error below 1e-12 of the fringe amplitude.

use crate::error::{self, Result};
use crate::formalism::interferogram::SpectralNodes;
use crate::formalism::observation::Observation;
use num_complex::Complex64;
use rayon::prelude::*;
use std::f64::consts::PI;
use std::sync::{Arc, Mutex};

/// Largest OPD (µm) a scan may reach with its piston: beyond, the fringe
/// table would cost more memory and time than any realistic case needs.
pub const MAX_OPD_UM: f64 = 5000.0;

/// The fringe per unit continuum, `m(x) = Re Σ_j a_j e^{2πiσ_j x}`, tabulated
/// for fast evaluation on |x| ≤ `max_opd_um` (see the module docs).
#[derive(Debug, Clone)]
pub struct FringeTable {
    nodes: SpectralNodes,
    sigma_c: f64,
    x0: f64,
    h: f64,
    value: Vec<Complex64>,
    slope: Vec<Complex64>,
    carrier: Vec<Complex64>,
}

/// Largest carrier phase 2πσ_c h across one grid step, rad: the step's
/// carrier rotation is evaluated by its Taylor series to θ⁷, whose error
/// θ⁸/8! stays below 1e-15 there.
const MAX_STEP_PHASE: f64 = 0.06;

/// Per node, e^{2πiδ_j x} is marched along the grid by complex
/// multiplication, re-anchored exactly every `RESYNC` steps.
const RESYNC: usize = 128;

/// Grid points summed over all the nodes at a time: their values and
/// slopes (32 KiB) stay in the L1 cache while the nodes stream past, where
/// a whole table (megabytes) would be read and written once per node. A
/// multiple of `RESYNC`, so that each block starts on an exact anchor and
/// every sum has the same terms in the same order as node by node.
const BLOCK: usize = 8 * RESYNC;

/// A node's term: 2πδ_j, the phase step e^{2πiδ_j h}, a_j and a_j·2πiδ_j.
type NodeTerm = (f64, Complex64, Complex64, Complex64);

/// Nodes marched together: their phase recurrences are independent, so
/// the processor runs them side by side instead of waiting on one chain of
/// complex products (each sum still takes the nodes in order).
const LANES: usize = 4;

/// Adds every node's term to the grid points `start..start + value.len()`
/// of the grid `(x0, h)`, node after node (the order of the sums).
fn add_nodes(
    terms: &[NodeTerm],
    grid: (f64, f64),
    start: usize,
    value: &mut [Complex64],
    slope: &mut [Complex64],
) {
    let mut lanes = terms.chunks_exact(LANES);
    for group in &mut lanes {
        let group: &[NodeTerm; LANES] = group.try_into().expect("chunks_exact");
        add_lanes(group, grid, start, value, slope);
    }
    for term in lanes.remainder() {
        add_lanes(std::array::from_ref(term), grid, start, value, slope);
    }
}

/// [`add_nodes`] for `L` nodes at a time.
fn add_lanes<const L: usize>(
    terms: &[NodeTerm; L],
    (x0, h): (f64, f64),
    start: usize,
    value: &mut [Complex64],
    slope: &mut [Complex64],
) {
    let mut phase = [Complex64::new(0.0, 0.0); L];
    for (k, (v, s)) in value.iter_mut().zip(slope.iter_mut()).enumerate() {
        let i = start + k;
        for (p, &(w, step, a, da)) in phase.iter_mut().zip(terms) {
            if i % RESYNC == 0 {
                *p = Complex64::from_polar(1.0, w * (x0 + i as f64 * h));
            } else {
                *p *= step;
            }
            *v += a * *p;
            *s += da * *p;
        }
    }
}

/// Interpolation error target of [`FringeTable`], relative to Σ|a_j|.
const TABLE_REL: f64 = crate::tolerance::FRINGE_TABLE_REL;

impl FringeTable {
    /// The table of the (unfiltered) fringe of `obs` over |x| ≤ `max_opd_um`.
    pub fn new(obs: &Observation, max_opd_um: f64) -> Result<FringeTable> {
        error::positive("max_opd", max_opd_um)?;
        // SpectralNodes sizes its Gauss–Legendre panels (16 points) to a
        // quarter fringe at the largest OPD it is given; a whole fringe per
        // panel already integrates e^{2πiσx} to ~1e-20 (the error of the
        // 16-point rule on one cycle is ~π³²/32!), so ask for a quarter of
        // the range: four times fewer nodes (checked against the full set
        // and the adaptive oracle in tests/piston.rs).
        let nodes = SpectralNodes::new(obs, 0.25 * max_opd_um, None)?;
        let (lo, hi) = nodes
            .sigma_per_um
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &s| {
                (a.min(s), b.max(s))
            });
        let sigma_c = if lo.is_finite() { 0.5 * (lo + hi) } else { 0.0 };
        let dmax = if lo.is_finite() { 0.5 * (hi - lo) } else { 0.0 };
        // Cubic Hermite error ≤ h⁴/384 · max|a''''| ≤ h⁴/384 · (2π dmax)⁴ Σ|a_j|.
        let h = if dmax > 0.0 {
            ((384.0 * TABLE_REL).powf(0.25) / (2.0 * PI * dmax)).min(0.5)
        } else {
            0.5
        };
        let h = if sigma_c > 0.0 {
            h.min(MAX_STEP_PHASE / (2.0 * PI * sigma_c))
        } else {
            h
        };
        let n = (2.0 * max_opd_um / h).ceil() as usize + 1;
        let h = 2.0 * max_opd_um / (n - 1) as f64;
        let x0 = -max_opd_um;
        let mut value = vec![Complex64::new(0.0, 0.0); n];
        let mut slope = vec![Complex64::new(0.0, 0.0); n];
        let terms: Vec<NodeTerm> = nodes
            .sigma_per_um
            .iter()
            .zip(&nodes.amplitude)
            .map(|(&s, &a)| {
                let w = 2.0 * PI * (s - sigma_c);
                (
                    w,
                    Complex64::from_polar(1.0, w * h),
                    a,
                    a * Complex64::new(0.0, w),
                )
            })
            .collect();
        value
            .par_chunks_mut(BLOCK)
            .zip(slope.par_chunks_mut(BLOCK))
            .enumerate()
            .try_for_each(|(b, (value, slope))| {
                crate::montecarlo::cancel::check()?;
                add_nodes(&terms, (x0, h), b * BLOCK, value, slope);
                Ok::<(), crate::Error>(())
            })?;
        let carrier = (0..n)
            .map(|i| Complex64::from_polar(1.0, 2.0 * PI * sigma_c * (x0 + i as f64 * h)))
            .collect();
        Ok(FringeTable {
            nodes,
            sigma_c,
            x0,
            h,
            value,
            slope,
            carrier,
        })
    }

    /// The nodes the table was built from.
    pub fn nodes(&self) -> &SpectralNodes {
        &self.nodes
    }

    /// Half-width of the tabulated OPD range, µm.
    pub fn max_opd_um(&self) -> f64 {
        -self.x0
    }

    /// m(x) per unit continuum at OPD `x_um` (beyond the table, the direct
    /// node sum).
    #[inline]
    pub fn fringe(&self, x_um: f64) -> f64 {
        let t = (x_um - self.x0) / self.h;
        let n = self.value.len();
        if !(t >= 0.0 && t < (n - 1) as f64) {
            return self.nodes.fringe(x_um);
        }
        let i = t as usize;
        let u = t - i as f64;
        let u2 = u * u;
        let u3 = u2 * u;
        let h00 = 2.0 * u3 - 3.0 * u2 + 1.0;
        let h10 = (u3 - 2.0 * u2 + u) * self.h;
        let h01 = 3.0 * u2 - 2.0 * u3;
        let h11 = (u3 - u2) * self.h;
        let a = self.value[i] * h00
            + self.slope[i] * h10
            + self.value[i + 1] * h01
            + self.slope[i + 1] * h11;
        // e^{2πiσ_c x} = carrier_i · e^{iθ}, θ = 2πσ_c u h ≤ MAX_STEP_PHASE.
        let th = 2.0 * PI * self.sigma_c * u * self.h;
        let t2 = th * th;
        let cos = 1.0 - t2 / 2.0 * (1.0 - t2 / 12.0 * (1.0 - t2 / 30.0 * (1.0 - t2 / 56.0)));
        let sin = th * (1.0 - t2 / 6.0 * (1.0 - t2 / 20.0 * (1.0 - t2 / 42.0)));
        let c = self.carrier[i];
        let (zr, zi) = (c.re * cos - c.im * sin, c.re * sin + c.im * cos);
        a.re * zr - a.im * zi
    }

    /// [`fringe`](Self::fringe) at each of `x_um` (at most [`BATCH`]),
    /// into `out`: the same bits, in two passes. The first is arithmetic
    /// alone (the grid position, the Hermite weights, the step's carrier
    /// rotation: seven divisions a point), which the compiler runs on two
    /// points at a time; the second reads the table. A point off the table
    /// is evaluated as `fringe` evaluates it.
    pub(crate) fn fringes(&self, x_um: &[f64], out: &mut [f64]) {
        assert!(x_um.len() <= BATCH && out.len() == x_um.len());
        let len = x_um.len();
        let last = (self.value.len() - 1) as f64;
        let (mut t, mut cell) = ([0.0; BATCH], [0i32; BATCH]);
        let mut weight = [[0.0; 4]; BATCH];
        let (mut cos, mut sin) = ([0.0; BATCH], [0.0; BATCH]);
        for j in 0..len {
            t[j] = (x_um[j] - self.x0) / self.h;
            // On the table 0 <= t < len - 1 < 2^31: the truncation to i32
            // is the one `fringe` takes to usize (and is vectorized).
            cell[j] = t[j] as i32;
            let u = t[j] - cell[j] as f64;
            let u2 = u * u;
            let u3 = u2 * u;
            weight[j] = [
                2.0 * u3 - 3.0 * u2 + 1.0,
                (u3 - 2.0 * u2 + u) * self.h,
                3.0 * u2 - 2.0 * u3,
                (u3 - u2) * self.h,
            ];
            let th = 2.0 * PI * self.sigma_c * u * self.h;
            let t2 = th * th;
            cos[j] = 1.0 - t2 / 2.0 * (1.0 - t2 / 12.0 * (1.0 - t2 / 30.0 * (1.0 - t2 / 56.0)));
            sin[j] = th * (1.0 - t2 / 6.0 * (1.0 - t2 / 20.0 * (1.0 - t2 / 42.0)));
        }
        for j in 0..len {
            if !(t[j] >= 0.0 && t[j] < last) {
                out[j] = self.nodes.fringe(x_um[j]);
                continue;
            }
            let i = cell[j] as usize;
            let [h00, h10, h01, h11] = weight[j];
            let a = self.value[i] * h00
                + self.slope[i] * h10
                + self.value[i + 1] * h01
                + self.slope[i + 1] * h11;
            let c = self.carrier[i];
            let (zr, zi) = (c.re * cos[j] - c.im * sin[j], c.re * sin[j] + c.im * cos[j]);
            out[j] = a.re * zr - a.im * zi;
        }
    }
}

/// Points [`FringeTable::fringes`] takes at a time (its scratch lives on
/// the stack).
pub(crate) const BATCH: usize = 64;

/// Rungs per octave of [`FringeTables`]' ranges: a table is at most 2^¼
/// (19 %) wider than the range asked, so at most ~1.4 times the cost of the
/// exact one (its cost grows as the range squared), and a grid's settings
/// share a few rungs instead of building one table each.
const RUNGS_PER_OCTAVE: f64 = 4.0;

/// The fringe tables of the settings of one plan, shared: a table is built
/// once per observation and rung of range (the range asked rounded up to
/// the next 2^(k/4) µm) and read by every setting whose range falls on
/// that rung.
///
/// The table a setting reads depends only on its observation and the range
/// it needs, not on which settings ran before or on how many threads, so
/// the answer has the same bits whatever the order. It differs from the
/// exact-range table of [`FringeTable::new`] by the interpolation error
/// only (below [`crate::tolerance::FRINGE_TABLE_REL`] of the fringe's
/// amplitude), so the conformance vectors, which build their own exact
/// tables, do not move. No lock is held while a table is built (it is
/// built on the thread pool, whose waiting workers take up other work, a
/// setting asking for the same table among it: waiting on a lock there
/// could deadlock): two settings asking at once may both build it, and
/// the first kept is read by both. Clones share the tables.
#[derive(Debug, Clone, Default)]
pub struct FringeTables {
    #[allow(clippy::type_complexity)]
    built: Arc<Mutex<Vec<(Observation, i32, Arc<FringeTable>)>>>,
}

impl FringeTables {
    /// No table yet.
    pub fn new() -> FringeTables {
        FringeTables::default()
    }

    /// The table of `obs` over at least |x| ≤ `max_opd_um` (≤ [`MAX_OPD_UM`]).
    pub fn get(&self, obs: &Observation, max_opd_um: f64) -> Result<Arc<FringeTable>> {
        error::positive("max_opd", max_opd_um)?;
        let rung = (RUNGS_PER_OCTAVE * max_opd_um.log2()).ceil();
        let range = (rung / RUNGS_PER_OCTAVE)
            .exp2()
            .min(MAX_OPD_UM)
            .max(max_opd_um);
        let find = |built: &[(Observation, i32, Arc<FringeTable>)]| {
            built
                .iter()
                .find(|(o, r, _)| *r == rung as i32 && o == obs)
                .map(|(_, _, table)| table.clone())
        };
        if let Some(table) = find(&self.built.lock().unwrap_or_else(|e| e.into_inner())) {
            return Ok(table);
        }
        let made = Arc::new(FringeTable::new(obs, range)?);
        let mut built = self.built.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(first) = find(&built) {
            return Ok(first);
        }
        built.push((obs.clone(), rung as i32, made.clone()));
        Ok(made)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::formalism::observation::Frequency;
    use crate::formalism::phase::SpectralPhase;
    use crate::formalism::source::Source;
    use crate::formalism::spectrum::{Band, Spectrum};
    use crate::tolerance::FRINGE_TABLE_CHECK_ABS;

    fn obs(diameter_mas: f64) -> Observation {
        Observation::new(
            Spectrum::flat(Band::k()),
            Source::uniform_disk(diameter_mas).unwrap(),
            Frequency::BaselineM(18.0),
            SpectralPhase::zero(),
        )
        .unwrap()
    }

    /// The table summed block by block, four nodes at a time, has the bits
    /// of the plain sum node after node over the whole grid (the oracle
    /// below: the same terms in the same order).
    #[test]
    fn blocked_sums_have_the_bits_of_the_node_by_node_sums() {
        let table = FringeTable::new(&obs(43.0), 37.3).unwrap();
        let n = table.value.len();
        // A last block shorter than the others.
        assert!(n % BLOCK != 0);
        let (mut value, mut slope) = (
            vec![Complex64::new(0.0, 0.0); n],
            vec![Complex64::new(0.0, 0.0); n],
        );
        for (&s, &a) in table.nodes.sigma_per_um.iter().zip(&table.nodes.amplitude) {
            let w = 2.0 * PI * (s - table.sigma_c);
            let step = Complex64::from_polar(1.0, w * table.h);
            let mut phase = Complex64::new(0.0, 0.0);
            for i in 0..n {
                phase = if i % RESYNC == 0 {
                    Complex64::from_polar(1.0, w * (table.x0 + i as f64 * table.h))
                } else {
                    phase * step
                };
                value[i] += a * phase;
                slope[i] += a * Complex64::new(0.0, w) * phase;
            }
        }
        assert!(value == table.value && slope == table.slope);
    }

    /// Settings on one rung read one table, the table of that rung's range
    /// whoever asked first; another observation has its own; every table
    /// covers the range asked and agrees with the exact one.
    #[test]
    fn shared_tables_are_one_per_observation_and_rung() {
        let tables = FringeTables::new();
        let (a, b) = (obs(43.0), obs(20.0));
        let first = tables.get(&a, 45.5).unwrap();
        let same = tables.get(&a, 46.0).unwrap();
        assert!(Arc::ptr_eq(&first, &same));
        assert!(first.max_opd_um() >= 45.5 && first.max_opd_um() <= 45.5 * 2f64.powf(0.25));
        assert!(!Arc::ptr_eq(&first, &tables.get(&b, 45.5).unwrap()));
        let alone = FringeTable::new(&a, first.max_opd_um()).unwrap();
        assert!(alone.value == first.value);
        let exact = FringeTable::new(&a, 45.5).unwrap();
        let worst = (0..2000)
            .map(|i| -45.0 + i as f64 * 0.045)
            .map(|x| (first.fringe(x) - exact.fringe(x)).abs())
            .fold(0.0, f64::max);
        assert!(worst < FRINGE_TABLE_CHECK_ABS, "{worst:e}");
    }
}
