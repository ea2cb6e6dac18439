//! Exact mean and variance of the estimators summed over any window K of
//! Fourier bins, for any independent per-sample noise (paper, Appendix
//! "Variance of estimators with filtered samples", which approximates the
//! gain of a window by the white-noise factor Δσ/Δσ_0).
//!
//! Both raw estimators are quadratic forms in the samples `M = m + e`:
//!
//! - `V1²_K = Σ_{k∈K} |B_k|² = Mᵀ A₁ M` with
//!   `A₁[i][j] = Σ_{k∈K} cos(2π (i − j) k / N)`;
//! - `V2²_K = |Σ_{k∈K} B_k|² = |Σ_i u_i M_i|² = Mᵀ A₂ M` with
//!   `u_i = Σ_{k∈K} e^{−2πi ik/N}` and `A₂[i][j] = Re(u_i ū_j)`.
//!
//! For independent e_i of variance v_i = κ2_i, third and fourth cumulants
//! κ3_i, κ4_i (Poisson photon noise has κ3 = κ4 = n_i), a symmetric A gives
//!
//! - `⟨MᵀAM⟩ = mᵀAm + Σ_i A_ii v_i` (the second term is the noise bias);
//! - `var(MᵀAM) = 4 Σ_i (Am)_i² v_i + 2 Σ_{ij} A_ij² v_i v_j
//!   + 4 Σ_i (Am)_i A_ii κ3_i + Σ_i A_ii² κ4_i`.
//!
//! (Expand `mᵀAm + 2mᵀAe + eᵀAe`: the linear term, the quadratic term, and
//! their covariance `2 Σ_i (Am)_i A_ii κ3_i`; the κ4 term is the non-Gaussian
//! part of `var(eᵀAe)`.) With all N bins `A₁ = N·I` and `A₂ = N²·e₀e₀ᵀ`,
//! which gives back [`crate::noise::appendix_stats`].
//!
//! The white-noise argument of the paper reduces only the noise × noise term
//! `2 Σ A_ij² v_i v_j`; the signal × noise term `4 Σ (Am)_i² v_i` is the
//! noise projected on the fringe, which a window that keeps the fringe
//! keeps too. [`window_stats`] gives the exact numbers;
//! [`variance_by_moments`] is the slow, obvious oracle (the paper's
//! four-index sum over samples).

use crate::error::{Error, Result};
use crate::formalism::estimator::{band_bins_within_bound, dft_phase};
use crate::noise::{Cumulants, NoiseModel};
use serde::Serialize;

/// A dense n × n matrix of f64, row-major: the matrix of a quadratic form
/// `MᵀAM` (`a[(i, j)]` is A_ij).
#[derive(Debug, Clone, PartialEq)]
pub struct SquareMatrix {
    n: usize,
    entries: Vec<f64>,
}

impl SquareMatrix {
    /// The n × n matrix of entries `f(i, j)`.
    pub fn from_fn(n: usize, mut f: impl FnMut(usize, usize) -> f64) -> SquareMatrix {
        let entries = (0..n * n).map(|at| f(at / n, at % n)).collect();
        SquareMatrix { n, entries }
    }

    /// The number of rows (and columns), n.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// Row `i`: A_i0 … A_i(n−1).
    pub fn row(&self, i: usize) -> &[f64] {
        &self.entries[i * self.n..(i + 1) * self.n]
    }

    /// The product `A x` (each entry summed over j in order).
    pub fn times(&self, x: &[f64]) -> Vec<f64> {
        (0..self.n)
            .map(|i| {
                self.row(i)
                    .iter()
                    .zip(x)
                    .fold(0.0, |acc, (a, x)| acc + a * x)
            })
            .collect()
    }
}

impl std::ops::Index<(usize, usize)> for SquareMatrix {
    type Output = f64;

    fn index(&self, (i, j): (usize, usize)) -> &f64 {
        &self.entries[i * self.n + j]
    }
}

/// `Σ_i x_i y_i` summed as nalgebra 0.33's `dot` sums a dynamic vector (eight
/// partial sums over blocks of eight, combined (0+4), (1+5), (2+6), (3+7),
/// then the tail in order): the order the exact statistics were computed
/// in before this crate wrote its own, kept so that their bits are.
fn dot(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len().min(y.len());
    let blocks = n / 8 * 8;
    let mut acc = [0.0; 8];
    for i in (0..blocks).step_by(8) {
        for (l, a) in acc.iter_mut().enumerate() {
            *a += x[i + l] * y[i + l];
        }
    }
    let mut sum = 0.0;
    for l in 0..4 {
        sum += acc[l] + acc[l + 4];
    }
    for i in blocks..n {
        sum += x[i] * y[i];
    }
    sum
}

/// The matrices A₁ (V1²) and A₂ (V2²) of the window `bins` for N = `n`.
pub fn quadratic_forms(n: usize, bins: &[usize]) -> (SquareMatrix, SquareMatrix) {
    // cos(2π d k/N) for every lag d, summed over the window.
    let lag: Vec<f64> = (0..n)
        .map(|d| bins.iter().map(|&k| dft_phase(d, k, n).cos()).sum())
        .collect();
    let a1 = SquareMatrix::from_fn(n, |i, j| lag[(i + n - j) % n]);
    let (ure, uim): (Vec<f64>, Vec<f64>) = (0..n)
        .map(|i| {
            bins.iter().fold((0.0, 0.0), |(re, im), &k| {
                let ph = dft_phase(i, k, n);
                (re + ph.cos(), im + ph.sin())
            })
        })
        .unzip();
    let a2 = SquareMatrix::from_fn(n, |i, j| ure[i] * ure[j] + uim[i] * uim[j]);
    (a1, a2)
}

/// `(mᵀAm, Σ A_ii v_i, var(MᵀAM))` for a symmetric A.
pub fn quadratic_form_moments(a: &SquareMatrix, m: &[f64], cum: &[Cumulants]) -> (f64, f64, f64) {
    let n = m.len();
    let am = a.times(m);
    let signal = dot(m, &am);
    let mut bias = 0.0;
    let mut var = 0.0;
    for i in 0..n {
        let aii = a[(i, i)];
        bias += aii * cum[i].k2;
        var +=
            4.0 * am[i] * am[i] * cum[i].k2 + 4.0 * am[i] * aii * cum[i].k3 + aii * aii * cum[i].k4;
        for j in 0..n {
            var += 2.0 * a[(i, j)] * a[(i, j)] * cum[i].k2 * cum[j].k2;
        }
    }
    (signal, bias, var)
}

/// Fourth cumulant of `MᵀAM` for Gaussian noise of variances `var[i]`:
/// `48 [tr((AΣ)⁴) + 4 (Am)ᵀ Σ (AΣ)² (Am)]` (the Gaussian quadratic-form
/// cumulants `κ_r = 2^{r−1}(r−1)! [tr((AΣ)^r) + (r/4) bᵀΣ(AΣ)^{r−2}b]`,
/// b = 2Am; Mathai & Provost 1992, Thm 3.2b.2). Gives the closed-form
/// standard error of a Monte Carlo sample variance.
pub fn gaussian_cumulant4(a: &SquareMatrix, m: &[f64], var: &[f64]) -> f64 {
    let n = a.dim();
    // AΣ: column j of A times var[j]; (AΣ)² by rows.
    let a_sigma = SquareMatrix::from_fn(n, |i, j| a[(i, j)] * var[j]);
    let a_sigma_sq = SquareMatrix::from_fn(n, |i, j| {
        (0..n).map(|k| a_sigma[(i, k)] * a_sigma[(k, j)]).sum()
    });
    // tr((AΣ)⁴) = Σ_ij [(AΣ)²]_ij [(AΣ)²]_ji.
    let tr4: f64 = (0..n)
        .flat_map(|i| (0..n).map(move |j| (i, j)))
        .map(|(i, j)| a_sigma_sq[(i, j)] * a_sigma_sq[(j, i)])
        .sum();
    let am = a.times(m);
    let sigma_am: Vec<f64> = am.iter().zip(var).map(|(x, v)| x * v).collect();
    let quad: f64 = sigma_am
        .iter()
        .zip(a_sigma_sq.times(&am))
        .map(|(x, y)| x * y)
        .sum();
    48.0 * (tr4 + 4.0 * quad)
}

/// Exact statistics of both estimators over one window.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WindowStats {
    /// Number of bins in the window.
    pub bins: usize,
    /// Noise-free V1²_K (signal).
    pub signal_v1_sq: f64,
    /// Noise-free V2²_K (signal).
    pub signal_v2_sq: f64,
    /// Noise bias of V1²_K: `Σ A₁_ii v_i`.
    pub bias_v1_sq: f64,
    /// Noise bias of V2²_K: `Σ A₂_ii v_i`.
    pub bias_v2_sq: f64,
    /// var V1²_K.
    pub var_v1_sq: f64,
    /// var V2²_K.
    pub var_v2_sq: f64,
    /// signal / √var for V1² (`"infinite"`/`"undefined"` in JSON without
    /// noise, [`crate::noise::snr_value`]).
    #[serde(serialize_with = "crate::noise::snr_value::serialize_snr")]
    pub snr1: f64,
    /// signal / √var for V2² (same).
    #[serde(serialize_with = "crate::noise::snr_value::serialize_snr")]
    pub snr2: f64,
}

fn sample_cumulants(noise: &NoiseModel, m: &[f64], counts: &[f64]) -> Result<Vec<Cumulants>> {
    if m.len() != counts.len() || m.is_empty() {
        return Err(Error::Invalid {
            param: "samples",
            reason: format!("{} modulated values and {} counts", m.len(), counts.len()),
        });
    }
    counts
        .iter()
        .map(|&n| {
            // A photon count beyond the library's bound squares past f64.
            crate::bounds::non_negative_at_most("counts", n, crate::bounds::MEAN_COUNT_MAX)?;
            noise.cumulants(n)
        })
        .collect()
}

/// Exact mean, bias and variance of V1²_K and V2²_K for samples of mean
/// `m[i]` and mean total count `counts[i]` (photons), noise `noise`, window
/// `bins` (indices 0 … N−1).
pub fn window_stats(
    m: &[f64],
    counts: &[f64],
    noise: &NoiseModel,
    bins: &[usize],
) -> Result<WindowStats> {
    let cum = sample_cumulants(noise, m, counts)?;
    let n = m.len();
    if let Some(&k) = bins.iter().find(|&&k| k >= n) {
        return Err(Error::OutOfRange {
            param: "bins",
            value: k as f64,
            accepted: format!("0 to {}", n - 1),
        });
    }
    let (a1, a2) = quadratic_forms(n, bins);
    let (s1, b1, v1) = quadratic_form_moments(&a1, m, &cum);
    let (s2, b2, v2) = quadratic_form_moments(&a2, m, &cum);
    Ok(WindowStats {
        bins: bins.len(),
        signal_v1_sq: s1,
        signal_v2_sq: s2,
        bias_v1_sq: b1,
        bias_v2_sq: b2,
        var_v1_sq: v1,
        var_v2_sq: v2,
        snr1: s1 / v1.sqrt(),
        snr2: s2 / v2.sqrt(),
    })
}

/// The positive-frequency bins of the band [lo, hi] µm⁻¹ and their mirror
/// images N − k: the window that keeps the whole fringe peak of a real
/// interferogram.
pub fn two_sided_band_bins(n: usize, dx_um: f64, lo_per_um: f64, hi_per_um: f64) -> Vec<usize> {
    let pos = band_bins_within_bound(n, dx_um, lo_per_um, hi_per_um);
    let mut all: Vec<usize> = pos.iter().flat_map(|&k| [k, n - k]).collect();
    all.sort_unstable();
    all.dedup();
    all
}

/// Slow oracle: `var(MᵀAM) = Σ_{jlpq} A_jl A_pq (⟨M_j M_l M_p M_q⟩ −
/// ⟨M_j M_l⟩⟨M_p M_q⟩)`, each expectation a product of per-sample raw
/// moments over the distinct indices (the paper's four-index sum). O(N⁴):
/// for tests with small N.
pub fn variance_by_moments(a: &SquareMatrix, m: &[f64], counts: &[f64], noise: &NoiseModel) -> f64 {
    let n = m.len();
    let raw: Vec<[f64; 5]> = (0..n)
        .map(|i| crate::noise::model::moments_of(m[i], noise.cumulants_at(counts[i])).raw)
        .collect();
    let expect = |idx: &[usize]| -> f64 {
        let mut sorted = idx.to_vec();
        sorted.sort_unstable();
        let mut prod = 1.0;
        let mut i = 0;
        while i < sorted.len() {
            let mut j = i;
            while j < sorted.len() && sorted[j] == sorted[i] {
                j += 1;
            }
            prod *= raw[sorted[i]][j - i];
            i = j;
        }
        prod
    };
    let mut var = 0.0;
    for j in 0..n {
        for l in 0..n {
            let ajl = a[(j, l)];
            if ajl == 0.0 {
                continue;
            }
            let e2 = expect(&[j, l]);
            for p in 0..n {
                for q in 0..n {
                    let apq = a[(p, q)];
                    if apq == 0.0 {
                        continue;
                    }
                    var += ajl * apq * (expect(&[j, l, p, q]) - e2 * expect(&[p, q]));
                }
            }
        }
    }
    var
}
