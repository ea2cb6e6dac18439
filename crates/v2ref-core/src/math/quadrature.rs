//! Adaptive Gauss–Kronrod quadrature (7-point Gauss, 15-point Kronrod).
//!
//! The band integrals of the paper (W, W², W V e^{iφ}, σ W over the band)
//! are smooth on each piece of the spectrum, so a G7/K15 rule with
//! bisection converges geometrically. Node and weight values are those of
//! QUADPACK's `qk15` (Piessens et al. 1983); `tests/foundation.rs` checks
//! that K15 integrates polynomials of degree 22 and G7 of degree 13 exactly.
//!
//! Integrands may be vector-valued (several integrals share one set of
//! function evaluations): anything implementing [`QuadValue`].

use num_complex::Complex64;

/// A value that can be integrated: a vector space with a size measure.
pub trait QuadValue: Copy {
    /// The zero element.
    fn zero() -> Self;
    /// `self + other`.
    fn add(self, other: Self) -> Self;
    /// `self * k`.
    fn scale(self, k: f64) -> Self;
    /// Largest absolute component (for error control).
    fn max_abs(self) -> f64;
}

impl QuadValue for f64 {
    fn zero() -> Self {
        0.0
    }
    fn add(self, o: Self) -> Self {
        self + o
    }
    fn scale(self, k: f64) -> Self {
        self * k
    }
    fn max_abs(self) -> f64 {
        self.abs()
    }
}

impl QuadValue for Complex64 {
    fn zero() -> Self {
        Complex64::new(0.0, 0.0)
    }
    fn add(self, o: Self) -> Self {
        self + o
    }
    fn scale(self, k: f64) -> Self {
        self * k
    }
    fn max_abs(self) -> f64 {
        self.re.abs().max(self.im.abs())
    }
}

impl<const K: usize> QuadValue for [f64; K] {
    fn zero() -> Self {
        [0.0; K]
    }
    fn add(mut self, o: Self) -> Self {
        for (a, b) in self.iter_mut().zip(o) {
            *a += b;
        }
        self
    }
    fn scale(mut self, k: f64) -> Self {
        for a in &mut self {
            *a *= k;
        }
        self
    }
    fn max_abs(self) -> f64 {
        self.iter().fold(0.0, |m, a| m.max(a.abs()))
    }
}

/// Kronrod abscissae on [−1, 1] (positive half; index 7 is the centre).
/// Odd indices are also the 7-point Gauss abscissae.
const XGK: [f64; 8] = [
    0.991_455_371_120_812_6,
    0.949_107_912_342_758_5,
    0.864_864_423_359_769_1,
    0.741_531_185_599_394_4,
    0.586_087_235_467_691_1,
    0.405_845_151_377_397_2,
    0.207_784_955_007_898_5,
    0.0,
];
/// Kronrod weights.
const WGK: [f64; 8] = [
    0.022_935_322_010_529_22,
    0.063_092_092_629_978_55,
    0.104_790_010_322_250_18,
    0.140_653_259_715_525_92,
    0.169_004_726_639_267_9,
    0.190_350_578_064_785_4,
    0.204_432_940_075_298_9,
    0.209_482_141_084_727_83,
];
/// Gauss weights for the abscissae XGK[1], XGK[3], XGK[5], XGK[7].
const WG: [f64; 4] = [
    0.129_484_966_168_869_7,
    0.279_705_391_489_276_7,
    0.381_830_050_505_118_9,
    0.417_959_183_673_469_4,
];

/// One G7/K15 panel on [a, b]: (Kronrod estimate, |K15 − G7|).
pub fn gauss_kronrod_15<T: QuadValue>(f: &impl Fn(f64) -> T, a: f64, b: f64) -> (T, f64) {
    let centre = 0.5 * (a + b);
    let half = 0.5 * (b - a);
    let fc = f(centre);
    let mut kronrod = fc.scale(WGK[7]);
    let mut gauss = fc.scale(WG[3]);
    for j in 0..7 {
        let dx = half * XGK[j];
        let pair = f(centre - dx).add(f(centre + dx));
        kronrod = kronrod.add(pair.scale(WGK[j]));
        if j % 2 == 1 {
            gauss = gauss.add(pair.scale(WG[j / 2]));
        }
    }
    let err = kronrod.add(gauss.scale(-1.0)).max_abs() * half.abs();
    (kronrod.scale(half), err)
}

/// Tolerances of [`integrate`]: converged when the error estimate is below
/// `max(abs, rel · |I|)` (|I| the largest component).
#[derive(Debug, Clone, Copy)]
pub struct Tolerance {
    /// Absolute target.
    pub abs: f64,
    /// Relative target.
    pub rel: f64,
}

impl Default for Tolerance {
    fn default() -> Self {
        Tolerance {
            abs: crate::tolerance::QUADRATURE_ABS,
            rel: crate::tolerance::QUADRATURE_REL,
        }
    }
}

/// Maximum bisection depth: 2^-40 of the interval is below any physical scale.
const MAX_DEPTH: u32 = 40;

/// Most panels one integral may use (a guard against integrands that the
/// tolerance cannot be met for; the band integrals use a few dozen).
const MAX_PANELS: usize = 4000;

/// Rounding floor of the error target, in units of ε times the integral of
/// the absolute integrand: no rule can do better than rounding.
const ROUNDING_FLOOR: f64 = 50.0 * f64::EPSILON;

/// ∫_a^b f(x) dx by adaptive G7/K15 with global error control: the panel
/// with the largest error estimate is bisected until the sum of estimates
/// meets the tolerance (or panels reach a depth of 40 bisections, or 4000
/// panels in all).
pub fn integrate<T: QuadValue>(f: impl Fn(f64) -> T, a: f64, b: f64, tol: Tolerance) -> T {
    integrate_pieces(&f, &[a, b], tol)
}

/// Like [`integrate`] over `[breaks[0], breaks[last]]`, starting from the
/// given pieces (place a break at every kink of the integrand).
pub fn integrate_pieces<T: QuadValue>(f: &impl Fn(f64) -> T, breaks: &[f64], tol: Tolerance) -> T {
    struct Panel<T> {
        a: f64,
        b: f64,
        value: T,
        err: f64,
        depth: u32,
    }
    let mut panels: Vec<Panel<T>> = breaks
        .windows(2)
        .filter(|w| w[1] > w[0])
        .map(|w| {
            let (value, err) = gauss_kronrod_15(f, w[0], w[1]);
            Panel {
                a: w[0],
                b: w[1],
                value,
                err,
                depth: 0,
            }
        })
        .collect();
    loop {
        let total = panels.iter().fold(T::zero(), |s, p| s.add(p.value));
        let err: f64 = panels.iter().map(|p| p.err).sum();
        let scale: f64 = panels.iter().map(|p| p.value.max_abs()).sum();
        let target = tol
            .abs
            .max(tol.rel * total.max_abs())
            .max(ROUNDING_FLOOR * scale);
        let worst = panels
            .iter()
            .enumerate()
            .filter(|(_, p)| p.depth < MAX_DEPTH)
            .max_by(|x, y| x.1.err.total_cmp(&y.1.err))
            .map(|(i, _)| i);
        match worst {
            Some(i) if err > target && panels[i].err > 0.0 && panels.len() < MAX_PANELS => {
                let p = panels.swap_remove(i);
                let mid = 0.5 * (p.a + p.b);
                for (a, b) in [(p.a, mid), (mid, p.b)] {
                    let (value, err) = gauss_kronrod_15(f, a, b);
                    panels.push(Panel {
                        a,
                        b,
                        value,
                        err,
                        depth: p.depth + 1,
                    });
                }
            }
            _ => {
                // Sum in order of position so the result does not depend on
                // the order panels were refined in.
                panels.sort_by(|x, y| x.a.total_cmp(&y.a));
                return panels.iter().fold(T::zero(), |s, p| s.add(p.value));
            }
        }
    }
}

/// Newton's method for a Gauss–Legendre node stops when its step is below
/// this (half an ulp of a node in [−1, 1]): the node no longer moves.
const LEGENDRE_NEWTON_STOP: f64 = 1e-16;

/// Most nodes of [`gauss_legendre`]: its cost grows as n² (each node's
/// Newton steps evaluate P_n by an n-term recurrence), about 0.1 s here.
pub const GAUSS_LEGENDRE_MAX_NODES: usize = 4096;

/// Nodes and weights of the n-point Gauss–Legendre rule on [−1, 1]
/// (Newton's method on P_n from Tricomi's initial guesses; nodes accurate to
/// a few ulps). Exact for polynomials of degree 2n − 1. Refuses n = 0 (no
/// rule) and n above [`GAUSS_LEGENDRE_MAX_NODES`].
pub fn gauss_legendre(n: usize) -> crate::Result<(Vec<f64>, Vec<f64>)> {
    if !(1..=GAUSS_LEGENDRE_MAX_NODES).contains(&n) {
        return Err(crate::Error::OutOfRange {
            param: "nodes",
            value: n as f64,
            accepted: format!("1 to {GAUSS_LEGENDRE_MAX_NODES} Gauss-Legendre nodes"),
        });
    }
    let mut x = vec![0.0; n];
    let mut w = vec![0.0; n];
    let nf = n as f64;
    for i in 0..n.div_ceil(2) {
        let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (nf + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            // P_n(z) by the three-term recurrence, and its derivative.
            let (mut p0, mut p1) = (1.0, z);
            for k in 2..=n {
                let kf = k as f64;
                let p2 = ((2.0 * kf - 1.0) * z * p1 - (kf - 1.0) * p0) / kf;
                p0 = p1;
                p1 = p2;
            }
            let pn = if n == 1 { z } else { p1 };
            let pm = if n == 1 { 1.0 } else { p0 };
            dp = nf * (z * pn - pm) / (z * z - 1.0);
            let step = pn / dp;
            z -= step;
            if step.abs() < LEGENDRE_NEWTON_STOP {
                break;
            }
        }
        x[i] = -z;
        x[n - 1 - i] = z;
        let wi = 2.0 / ((1.0 - z * z) * dp * dp);
        w[i] = wi;
        w[n - 1 - i] = wi;
    }
    Ok((x, w))
}
