//! Tolerances of quadratures and special functions: convergence targets,
//! finite differences, iteration stops.

/// Relative accuracy the band integrals are converged to (the adaptive
/// Gauss–Kronrod target). The integrands are smooth and bounded by one, so
/// the absolute error of a normalized integral is of the same order.
pub const QUADRATURE_REL: f64 = 1e-13;

/// Absolute floor of the adaptive quadrature target: the band integrals
/// are normalized and of order one, so a floor of ~5 ε stops the
/// subdivision where the Kronrod error estimate is itself only rounding
/// (a 15-point rule sums 15 products: ~15 ε of noise in the estimate).
pub const QUADRATURE_ABS: f64 = 1e-15;

/// A result converged to [`QUADRATURE_REL`], compared against a closed form
/// or against a second quadrature route: the target is met panel by panel
/// on the Kronrod estimate, which is conservative for smooth integrands
/// but not a bound; a sharply peaked integrand (a Lorentzian of width 1e-2
/// and height 10⁴) or a ratio of two converged integrals may carry a few
/// times the target. A factor 10: 1e-12.
pub const QUADRATURE_CHECK_REL: f64 = 1e-12;

/// Exactness of a fixed Gauss rule on polynomials it integrates exactly
/// (degree ≤ 2n − 1), relative: the nodes and weights are computed by
/// Newton's method to ~1 ulp, and x^p for p ≤ 2n − 2 ≤ 30 amplifies a
/// node error by p: ~30 ε ≈ 7e-15, so 1e-13 leaves a margin of ~15.
pub const NODES_REL: f64 = 1e-13;

/// Target of the turbulence spectral integrals (the piston PSD and the
/// structure function), relative. The integrands oscillate like Bessel
/// functions out to 100/D and are integrated over ~10² lobes, so the
/// per-panel Kronrod estimate cannot be driven to [`QUADRATURE_REL`]
/// without rounding noise dominating the estimate; 1e-11 is ~10²
/// [`QUADRATURE_REL`], and far below the 1e-4 accuracy any piston result
/// is quoted to.
pub const TURBULENCE_QUADRATURE_REL: f64 = 1e-11;

/// Two routes to a turbulence spectral quantity (the direct 2-D pupil
/// integral against the 1-D spectral integral, the structure function two
/// ways), relative: each is converged to [`TURBULENCE_QUADRATURE_REL`], but
/// the change of variables near f = 0 and the added asymptotic tail
/// (below 1e-12 of the total, see `F_MAX_TIMES_D` in `turbulence.rs`) differ
/// between routes; a factor 10 above the target: 1e-10.
pub const TURBULENCE_CHECK_REL: f64 = 1e-10;

/// The differential piston variance by the spectral route (the 1-D
/// integral of the piston PSD, itself an integral) against mpmath,
/// relative: two nested integrals at [`TURBULENCE_QUADRATURE_REL`] plus the
/// averaged asymptotic tail beyond 100/D, whose neglected oscillation is
/// ~1e-10 of the total at B = 18 m; 1e-9.
pub const TURBULENCE_SPECTRAL_REL: f64 = 1e-9;

/// A turbulence spectral integral whose tail beyond 100/D is taken from
/// the high-frequency asymptote with the Bessel oscillation averaged, at
/// points where that matters most: the transverse integral G at f D = 3
/// (the neglected oscillation leaves ~3e-9 of G), and the piston variance
/// of other geometries (overlapping apertures B < D, D from 0.1 to 8 m),
/// relative; 1e-8.
pub const TURBULENCE_TAIL_REL: f64 = 1e-8;

/// The crosswind integral S of the piston spectrum against its definition
/// integrated half period by half period of `sin²(π f_y b)` out to 100/D,
/// relative: beyond 64 half periods the crate replaces `2 sin²` by its mean
/// 1, which the module estimates at ~1e-6 of S; measured at most 2.5e-7
/// over 60 pairs (f_x D from 1e-5 to 5, b from 0.2 to 150 m); 1e-6.
pub const CROSSWIND_REL: f64 = 1e-6;

/// ln G of the piston spectrum's table read back at a node, or
/// interpolated where the cubic is exact (a line or a quadratic in ln f),
/// absolute in ln G (relative in G): the node's abscissa goes through exp
/// and ln (|ln f_x D| ≤ 17, so ~4e-15 in ln f and 1.5e-13 in grid units of
/// ln 10/80), times slopes of ln G up to a few per grid step; 1e-12.
pub const TABLE_LN_ABS: f64 = 1e-12;

/// The piston spectrum's corner frequencies are closed forms, and the two
/// asymptotes that cross there are power laws with exponents up to 17/3:
/// a relative error δ of ν becomes 17/3 δ, and the prefactors combine a few
/// Gamma functions ([`GAMMA_REL`](super::GAMMA_REL)); ~10× [`GAMMA_REL`](super::GAMMA_REL): 1e-12.
pub const CORNER_REL: f64 = 1e-12;

/// Interpolation error target of the piston fringe table, relative to
/// Σ|a_j| (the fringe amplitude): the table is built so that its cubic
/// interpolation error, which falls as h⁴, is below 1e-12; the synthesized
/// fringes then match the direct spectral sums to far better than the
/// 1e-4 at which any piston bias is quoted.
pub const FRINGE_TABLE_REL: f64 = 1e-12;

/// The fringe table against the direct spectral sum or against the full
/// node set, absolute for a fringe of amplitude ~1: [`FRINGE_TABLE_REL`]
/// plus the rounding of a sum over ~10³ Gauss–Legendre nodes (~10³ ε ≈
/// 2e-13), with a factor 10 for both: 1e-11.
pub const FRINGE_TABLE_CHECK_ABS: f64 = 1e-11;

/// The fringe table against the adaptive spectral oracle at single OPDs,
/// absolute for a fringe of amplitude ~1: the oracle integrates an
/// integrand with up to ~25 oscillations across the band (|x| ≤ 60 µm) to
/// [`QUADRATURE_REL`] of ∫|integrand| per panel, and its Kronrod estimate
/// on oscillatory panels is ~10× optimistic; 1e-10 allows both, ten
/// times [`FRINGE_TABLE_CHECK_ABS`].
pub const FRINGE_ORACLE_ABS: f64 = 1e-10;

/// Absolute accuracy of `2 J1(z)/z` and of J0, J1 over |z| ≤ 100, checked
/// against mpmath at 50 digits (`tests/data/bessel_reference.csv`). Miller's
/// backward recurrence loses a few ulps over ~100 steps.
pub const BESSEL_ABS: f64 = 1e-14;

/// Accuracy of a located zero of J1, relative: Newton's method is iterated
/// until its step is below one ulp, so the zero is limited by the accuracy
/// of J1 near it ([`BESSEL_ABS`]) divided by the slope |J1'| = |J0| ≈
/// √(2/πx) ≥ 0.1 for zeros below ~60, relative to zeros ≥ 3.8: ≲ 3e-15;
/// 1e-14 with a margin.
pub const BESSEL_ZERO_REL: f64 = 1e-14;

/// Fresnel integrals are O(1) and computed to a few ulps (a power series
/// of alternating terms up to x = 1.5, a continued fraction above); 2e-15
/// ≈ 9 [`EPS`](super::EPS) absolute. mpmath's 17-digit reference values are exact to
/// 1e-17 (`tests/data/fresnel_reference.csv`).
pub const FRESNEL_ABS: f64 = 2e-15;

/// The dispersion closed form (Fresnel integrals) against the numerical
/// spectral path, absolute on V²: the requirement. The numerical
/// path is converged to [`QUADRATURE_REL`] on a band integral whose
/// integrand turns through at most P ≤ 4 rad of phase, so 1e-10 is met
/// with a wide margin, while a 1% error in P moves V² by ~1e-3 at P = 1,
/// more than [`POWER_FACTOR`](super::POWER_FACTOR) tolerances.
pub const CLOSED_FORM_VS_NUMERICAL: f64 = 1e-10;

/// A central difference with step h against the exact derivative,
/// relative: truncation h² f'''/6 plus rounding ε |f| / h. For the
/// second derivative of the glass phase (five-point rule, h = 1e-3 µm⁻¹,
/// |φ| ~ 4e4 rad, D ~ 10³ rad µm²) the rounding term ε |φ| / h² / D ≈ 1e-8
/// sets the size; first derivatives with h = 1e-6 meet it with room.
pub const FINITE_DIFFERENCE_REL: f64 = 1e-8;

/// The five-point second difference of a phase that is exactly linear in
/// σ (constant index), absolute (rad µm²): the truncation vanishes and
/// only rounding remains, (1 + 16 + 30 + 16 + 1)/12 · ε|φ|/h² ≈ 5e-5 for
/// |φ| ≈ 4e4 rad and h = 1e-3 µm⁻¹; 1e-4 is twice that, and a real
/// dispersion of the test's glass (D ~ 10³) is 10⁷ times larger.
pub const SECOND_DIFFERENCE_ABS: f64 = 1e-4;

/// The glass residual phase (peak-to-peak beyond the linear term) is
/// proportional to the glass length; doubling the length reproduces it to
/// rounding, conditioned by |φ|/residual (the residual is a difference of
/// phases ~10³–10⁴ times larger) and by the first difference that removes
/// the slope: ~10⁴–10⁵ ε ≈ 2e-11; 1e-9 relative leaves a margin of ~50.
pub const RESIDUAL_PHASE_REL: f64 = 1e-9;

/// The glass residual phase of an index with a σ² term (a phase cubic in
/// σ) against its closed form, relative: the slope removed by the central
/// difference (h = 1e-4 µm⁻¹) is off by its truncation h² φ'''/6, which
/// tilts the residual by h² φ'''/6 · a over the half-band a. For
/// n = 1.4 + 0.1σ², L = 1 cm, a = 0.04 µm⁻¹ that is 2.5e-6 rad of 14 rad,
/// 1.8e-7 (measured); 1e-6 leaves a margin of 5, while a wrong operator in
/// the residual moves it by O(1).
pub const RESIDUAL_CUBIC_REL: f64 = 1e-6;

/// The quadratic dispersion of ZBLAN over the K band by the crate's
/// five-point second difference against mpmath's derivative of the
/// Sellmeier phase, relative: the rounding of the rule,
/// (1 + 16 + 30 + 16 + 1)/12 · ε|φ|/h² ≈ 5e-5 rad µm² per cm of glass
/// (|φ| ≈ 4.3e4 rad, h = 1e-3 µm⁻¹), against |D| ≈ 1.0e3 rad µm² per cm
/// (both scale with the length): up to 5e-8 when the errors add; 2.1e-8
/// measured at 2.5 cm. 2e-7 leaves a margin of 4, while the band centre
/// taken wrongly moves P by tens of percent.
pub const GLASS_DISPERSION_REL: f64 = 2e-7;

/// Entries of a Dirichlet-type window kernel smaller than this fraction of
/// the kernel's scale (the number of bins) are rounding residues of exact
/// zeros: each entry is a sum of up to ~10³ unit phasors with ~ε N of
/// phase rounding each, i.e. ≲ 1e-13 of the scale; real entries are ≥
/// 1/N ≥ 1e-6 of it. 1e-12 separates the two by six decades either way.
pub const KERNEL_ZERO_REL: f64 = 1e-12;

/// Width, relative to the search interval, to which the golden-section
/// search for the largest bandwidth bias shrinks its bracket. Near a smooth
/// maximum the value is flat to second order, so the located maximum is
/// accurate to ~(1e-9)² relative in value while the location itself is
/// limited by the ~√ε flatness of f (see [`ARGMAX_ABS`]); 1e-9 takes ~45
/// iterations.
pub const MINIMIZE_BRACKET_REL: f64 = 1e-9;

/// Location of a smooth maximum found on two different starting grids,
/// absolute (cycles/arcsec): near the top, f(x) − f(x*) ~ f''(x − x*)²/2
/// cannot be resolved below the ~1e-13 relative accuracy of f, so x* is
/// only known to ~√(2 · 1e-13 / f'') ≈ 1e-5 – 1e-6 for the curvatures of
/// the bias curves; 1e-4 (a 10⁻⁶ fraction of the 80 cycles/arcsec range)
/// has a margin of 10 and still separates distinct maxima (≥ 1 apart). The
/// value at the maximum, flat to second order, agrees to
/// [`MINIMIZE_BRACKET_REL`].
pub const ARGMAX_ABS: f64 = 1e-4;

/// The library's spectral estimators against the composite Simpson
/// reference written in `tests/spectral_estimators.rs` (≥ 4000 panels over
/// the band, 2 J1(z)/z from Bessel's integral), relative on V² (with the
/// floor [`VISIBILITY_SQ_FLOOR`](super::VISIBILITY_SQ_FLOOR)): Simpson's
/// truncation h⁴ L max|f⁗|/180 is ≲ 1e-15 for |V|² with z ≤ 20 and
/// power-law or piecewise-linear W (h ≤ Δσ/4000), its ~4000-term sums carry
/// up to ~4000 ε ≈ 1e-12 of rounding when the errors add coherently, and
/// the library's ratio of two integrals carries
/// [`QUADRATURE_CHECK_REL`]; 1e-11 allows both with a margin of ~5, while
/// V1² weighted by W instead of W² moves it by ≥ 1e-3 relative on any band
/// whose W changes by a few per cent across it.
pub const REFERENCE_QUADRATURE_REL: f64 = 1e-11;
