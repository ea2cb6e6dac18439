//! The fourth cumulant of a Gaussian quadratic form (the closed-form
//! standard error of a Monte Carlo sample variance) against an independent
//! route: the eigen-decomposition of the whitened form, by Jacobi rotations
//! written here (no linear-algebra crate).

use v2ref_core::assert_rel_eq;
use v2ref_core::noise::window_variance::{gaussian_cumulant4, quadratic_forms};
use v2ref_core::tolerance::IDENTITY_REL;

/// The eigenvalues and unit eigenvectors of the symmetric matrix `a`
/// (cyclic Jacobi rotations until the off-diagonal part is below 1e-12 of
/// the matrix's norm).
fn symmetric_eigen(mut a: Vec<Vec<f64>>) -> (Vec<f64>, Vec<Vec<f64>>) {
    let n = a.len();
    let mut v: Vec<Vec<f64>> = (0..n)
        .map(|i| (0..n).map(|j| f64::from(u8::from(i == j))).collect())
        .collect();
    let norm: f64 = a.iter().flatten().map(|x| x * x).sum::<f64>().sqrt();
    let off = |a: &Vec<Vec<f64>>| -> f64 {
        (0..n)
            .flat_map(|i| (0..n).filter(move |&j| j != i).map(move |j| (i, j)))
            .map(|(i, j)| a[i][j] * a[i][j])
            .sum::<f64>()
            .sqrt()
    };
    // tol: an off-diagonal part 1e-12 of the norm moves the eigenvalues by
    // about its square (1e-24), far below the test's IDENTITY_REL.
    for _sweep in 0..50 {
        if off(&a) <= 1e-12 * norm {
            break;
        }
        for p in 0..n {
            for q in p + 1..n {
                if a[p][q] == 0.0 {
                    continue;
                }
                // The rotation that zeroes a[p][q] (Golub & Van Loan, Alg. 8.5.1).
                let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                let t = theta.signum() / (theta.abs() + theta.hypot(1.0));
                let c = 1.0 / t.hypot(1.0);
                let s = t * c;
                // Columns p and q of A and V, then rows p and q of A.
                for row in a.iter_mut().chain(v.iter_mut()) {
                    let (xp, xq) = (row[p], row[q]);
                    row[p] = c * xp - s * xq;
                    row[q] = s * xp + c * xq;
                }
                let (above, from_q) = a.split_at_mut(q);
                for (xp, xq) in above[p].iter_mut().zip(from_q[0].iter_mut()) {
                    let (apk, aqk) = (*xp, *xq);
                    *xp = c * apk - s * aqk;
                    *xq = s * apk + c * aqk;
                }
            }
        }
    }
    // Column j of v is the eigenvector of a[j][j].
    let vectors = (0..n)
        .map(|j| v.iter().map(|row| row[j]).collect())
        .collect();
    ((0..n).map(|j| a[j][j]).collect(), vectors)
}

#[test]
fn gaussian_cumulant4_is_a_sum_of_noncentral_chi_squares() {
    // Q = Mᵀ A M with M ~ N(m, Σ), Σ diagonal: with Σ^{1/2} A Σ^{1/2} =
    // P Λ Pᵀ and δ = Pᵀ Σ^{-1/2} m, Q = Σ_j λ_j (Z_j + δ_j)², a sum of
    // independent scaled noncentral χ²₁, each of fourth cumulant
    // 48 λ_j⁴ (1 + 4 δ_j²). An eigen-decomposition route, independent of the
    // trace formula; unequal variances and partial windows.
    let m = [1.0, -2.0, 0.5, 3.0, 0.0, -1.5];
    let var = [1.7, 0.4, 2.2, 1.0, 0.9, 3.1];
    let sd: Vec<f64> = var.iter().map(|v: &f64| v.sqrt()).collect();
    let whitened_mean: Vec<f64> = m.iter().zip(&sd).map(|(mi, s)| mi / s).collect();
    for bins in [vec![1, 2], vec![0, 3, 5], (0..6).collect()] {
        let (a1, a2) = quadratic_forms(6, &bins);
        for a in [a1, a2] {
            let b: Vec<Vec<f64>> = (0..6)
                .map(|i| (0..6).map(|j| sd[i] * a[(i, j)] * sd[j]).collect())
                .collect();
            let (eigenvalues, eigenvectors) = symmetric_eigen(b);
            let want: f64 = eigenvalues
                .iter()
                .zip(&eigenvectors)
                .map(|(l, p)| {
                    let d: f64 = p.iter().zip(&whitened_mean).map(|(x, y)| x * y).sum();
                    48.0 * l.powi(4) * (1.0 + 4.0 * d * d)
                })
                .sum();
            assert_rel_eq!(gaussian_cumulant4(&a, &m, &var), want, IDENTITY_REL);
        }
    }
}
