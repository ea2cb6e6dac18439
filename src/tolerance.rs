//! The one home for the crate's numerical tolerances.
//!
//! Every tolerance the library iterates to, and every tolerance a test, a
//! doc test or the golden check compares against, is a named constant
//! here, with the reason for its size (in the manner of statrs's
//! `src/prec.rs`). A change of policy is one edit.
//!
//! Deterministic code is held to machine epsilon [`EPS`] times a stated
//! condition number or operation count; quadratures to their convergence
//! target; truncated series and discretizations to their known rate of
//! convergence; Monte Carlo code to `k` standard errors with `k` at least
//! [`MC_SIGMAS`].
//!
//! The constants fall in four groups:
//!
//! * deterministic identities (rounding only): [`EPS`], [`ULPS`],
//!   [`ROUNDING_REL`], [`VISIBILITY_SQ_FLOOR`], [`DEFAULT_REL`],
//!   [`DEFAULT_ABS`], [`DFT_REL_PER_LOG2N`], [`DIRECT_SUM_REL`],
//!   [`NAIVE_DFT_ABS`], [`FFT_SUM_REL`], [`BIN_SUM_REL`],
//!   [`PATHS_AGREE_ABS`], [`BIN_ORACLE_ABS`], [`GAMMA_REL`],
//!   [`IDENTITY_REL`], [`IDENTITY_ABS`], [`CANCELLATION_ABS`],
//!   [`STREAMING_M3_REL`], [`STREAMING_M3_FLOOR`], [`NONNEGATIVE_REL`],
//!   [`GOLDEN_REL`], [`GOLDEN_ABS`], [`EXAMPLE_GOLDEN_ABS`],
//!   [`VISIBILITY_SCALING_REL`], [`VISIBILITY_SCALING_ABS`];
//! * quadrature and special functions (convergence targets, finite
//!   differences, iteration stops): [`QUADRATURE_REL`], [`QUADRATURE_ABS`],
//!   [`QUADRATURE_CHECK_REL`], [`NODES_REL`], [`TURBULENCE_QUADRATURE_REL`],
//!   [`TURBULENCE_CHECK_REL`], [`TURBULENCE_SPECTRAL_REL`],
//!   [`TURBULENCE_TAIL_REL`], [`CORNER_REL`], [`FRINGE_TABLE_REL`],
//!   [`FRINGE_TABLE_CHECK_ABS`], [`FRINGE_ORACLE_ABS`], [`BESSEL_ABS`],
//!   [`BESSEL_ZERO_REL`], [`FRESNEL_ABS`], [`CLOSED_FORM_VS_NUMERICAL`],
//!   [`FINITE_DIFFERENCE_REL`], [`SECOND_DIFFERENCE_ABS`],
//!   [`RESIDUAL_PHASE_REL`], [`KERNEL_ZERO_REL`], [`MINIMIZE_BRACKET_REL`],
//!   [`ARGMAX_ABS`];
//! * convergence studies (truncated series, discretizations, asymptotic
//!   regimes, printed precision): [`SAMPLED_VS_SPECTRAL_ABS`],
//!   [`SCALING_LAW_REL`], [`SQUARE_LAW_REL`], [`PSD_TABLE_REL`],
//!   [`PSD_TABLE_CORNER_REL`], [`PSD_TABLE_WIGGLE_REL`],
//!   [`ASYMPTOTIC_LIMIT_REL`], [`ASYMPTOTIC_CORRECTION_REL`],
//!   [`LOW_FREQ_VALUE_COEFF`], [`LOW_FREQ_SLOPE_COEFF`],
//!   [`MID_FREQ_VALUE_COEFF`], [`MID_FREQ_SLOPE_COEFF`],
//!   [`DECADE_SLOPE_ABS`], [`ROUGH_SCALING_REL`], [`LINEAR_RESPONSE_REL`],
//!   [`LEADING_TERM_REL`], [`SMALL_P_EXPANSION_ABS`],
//!   [`GRID_INTERPOLATION_REL`], [`DIRICHLET_VS_SINC_ABS`],
//!   [`SAMPLING_LIMIT_ABS`], [`NARROW_BAND_LIMIT_ABS`],
//!   [`CONVERGENCE_GROWTH_REL`], [`RIEMANN_SUM_ABS`], [`SINC_TAIL_ABS`],
//!   [`INTEGRATION_LOSS_ABS`], [`PRINTED_5_DECIMALS_ABS`],
//!   [`PRINTED_3_DECIMALS_ABS`], [`PRINTED_2_DECIMALS_ABS`];
//! * Monte Carlo: [`MC_SIGMAS`], [`SIGNIFICANCE_SIGMAS`], [`POWER_FACTOR`],
//!   [`MC_POWER_SIGMAS`].
//!
//! The assertion macros [`assert_rel_eq!`](crate::assert_rel_eq),
//! [`assert_abs_eq!`](crate::assert_abs_eq) and
//! [`assert_within_sigmas!`](crate::assert_within_sigmas) compare through
//! these constants (with [`DEFAULT_REL`], [`DEFAULT_ABS`] and [`MC_SIGMAS`]
//! when none is named) and print both values, their difference and the
//! tolerance on failure.

// ---------------------------------------------------------------------------
// Deterministic identities
// ---------------------------------------------------------------------------

/// Machine epsilon for `f64` (2.2e-16), the unit every deterministic
/// tolerance below is measured in.
pub const EPS: f64 = f64::EPSILON;

/// A handful of roundings of numbers of order one: 1e-15 ≈ 4.5 [`EPS`].
/// For a closed form evaluated with at most ~4 correctly rounded operations
/// (a reciprocal, `sin(x)/x`, a product of two rounded constants), the
/// error is at most 4 half-ulps. Used as a relative tolerance, or as an
/// absolute one for quantities of order one.
pub const ULPS: f64 = 1e-15;

/// Tens of roundings: 1e-14 ≈ 45 [`EPS`]. A short sum or a fixed
/// quadrature rule of up to ~20 terms of one sign (each term rounded once,
/// the sum once per addition: error ≤ n ε for n ≤ 20, with a margin of ~2),
/// or a library special function that is itself good to a few ulps
/// composed with a few operations. Relative, or absolute for quantities of
/// order one.
pub const ROUNDING_REL: f64 = 1e-14;

/// Scale floor of relative comparisons of V² (a relative tolerance is
/// applied to max(V², 1e-3)): near a null V² is a difference of O(1)
/// spectral integrals, so its absolute rounding does not fall with it;
/// below 1e-3 the comparison becomes absolute at tolerance × 1e-3. This
/// is a floor of the scale, not a tolerance of its own.
pub const VISIBILITY_SQ_FLOOR: f64 = 1e-3;

/// Default relative tolerance of [`assert_rel_eq!`](crate::assert_rel_eq):
/// [`ROUNDING_REL`], the tightest bound that holds for any short
/// deterministic computation in the crate.
pub const DEFAULT_REL: f64 = ROUNDING_REL;

/// Default absolute tolerance of [`assert_abs_eq!`](crate::assert_abs_eq):
/// [`ROUNDING_REL`], meant for quantities of order one.
pub const DEFAULT_ABS: f64 = ROUNDING_REL;

/// The DFT identities (Parseval, Σ B_k = N M_0) hold to rounding: the
/// relative error of an N-point FFT grows like ε log2 N; we allow
/// `DFT_REL_PER_LOG2N * log2 N` with a safety factor of 10.
pub const DFT_REL_PER_LOG2N: f64 = 10.0 * EPS;

/// A direct sum of N unit phasors against its closed form (the Dirichlet
/// kernel at u ≤ 3.5 for N ≤ 116), relative to N: each phase 2π j u is up
/// to ~10³ rad and is rounded to ~10³ ε ≈ 2e-13, so the N-term sum carries
/// at most ~2e-13 N of absolute error even when the errors add coherently;
/// 1e-12 N leaves a margin of 5, while an off-by-one in the kernel moves
/// it by O(1). Also the relative tolerance of the other phasor-sum closed
/// forms: the noise-bias kernel |Σ_k e^{−2πi ik/N}|² (N = 16) and
/// Σ_k B_k = N m_0 over N = 100 bins, each of relative error ~ε log2 N.
pub const DIRECT_SUM_REL: f64 = 1e-12;

/// A naive O(N²) DFT against the FFT, absolute, for N = 100 inputs of
/// magnitude ≤ 3: the naive phases 2π jk/N are reduced modulo N exactly, so
/// each term is good to a few ε and the N-term sum to ~N · 3 · few ε ≈
/// 1e-13 (the FFT to ε log2 N of the bin scale); 1e-11 leaves a wide
/// margin, while a wrong twiddle factor moves a bin by O(1).
pub const NAIVE_DFT_ABS: f64 = 1e-11;

/// A sum over all N bins of an FFT against its closed form (Parseval:
/// Σ|B_k|² = N Σ m_j²), relative, for N ≤ 10³: each bin carries ~ε log2 N
/// of relative error and the N-term sum of positive terms adds ≲ N ε of
/// its own, errors of random sign: ~√N ε log2 N + √N ε ≈ 2e-14 for
/// N = 100; 1e-13 leaves a margin of ~5.
pub const FFT_SUM_REL: f64 = 1e-13;

/// The sum of all N FFT bins against N m_0 (the normalization's
/// baseline), relative to N, for N ≤ 233: the bins have magnitudes up to
/// ~N/2 and relative errors ~ε log2 N, so their sum carries up to
/// ~N ε log2 N ≈ 4e-13 N of absolute rounding in the worst (coherent) case;
/// 1e-11 N covers that with a margin of ~25.
pub const BIN_SUM_REL: f64 = 1e-11;

/// Two routes to the same finite-scan bias or bin (the bin convolution and
/// the DFT of the synthesized interferogram): both sit on the same
/// spectral nodes, converged to ~1e-15 of the band integral, and the
/// biases are differences of O(1) numbers, so they agree to rounding
/// amplified by the sums over nodes and samples (≲ 10³ terms): 1e-12
/// absolute.
pub const PATHS_AGREE_ABS: f64 = 1e-12;

/// A DFT bin from the convolution path against the same bin by adaptive
/// quadrature (the oracle), absolute: bins are of size up to N/2 ≈ 30 for
/// N = 58 samples, and each route is converged to [`QUADRATURE_REL`] of
/// the band integral times that scale (~3e-12); 1e-11 leaves a margin of
/// ~3 for the oracle's Kronrod estimate.
pub const BIN_ORACLE_ABS: f64 = 1e-11;

/// Closed forms built of Gamma functions and non-integer powers against
/// mpmath or against each other (the turbulence constants C_D, C_Φ, the
/// profile integrals; the OPD spectrum at two wavelengths with r0 ∝
/// λ^{6/5}): the Lanczos Γ is good to ~1e-15 relative, and each constant
/// is a product of up to ~6 Gammas and powers with exponents up to 11/3
/// (a relative error δ in the base becomes 11/3 δ in the power): ~30 ε ≈
/// 7e-15, so 1e-13 leaves a margin of ~15.
pub const GAMMA_REL: f64 = 1e-13;

/// Agreement between two routes to the same closed form (cumulant recursion
/// vs the printed polynomial, quadratic form vs the Appendix sum, the O(N⁴)
/// moment oracle vs the quadratic form): sums of up to ~10⁴ terms of mixed
/// sign and magnitude up to (n N)⁴ ~ 10¹⁶, so a few hundred ulps of the
/// largest term; 1e-10 relative leaves a margin of ~10³ and still catches
/// any wrong coefficient (which moves the result by ≥ 1e-3 relative).
pub const IDENTITY_REL: f64 = 1e-10;

/// Absolute floor of an [`IDENTITY_REL`] comparison for a quantity that
/// vanishes exactly (an odd raw moment of a symmetric count distribution):
/// the two routes cancel terms up to ~c⁴ ≈ 10⁴ (c ≤ 10 counts), leaving
/// ~10⁴ ε × a few ≈ 1e-12 of rounding.
pub const IDENTITY_ABS: f64 = 1e-12;

/// Absolute floor for quantities that vanish through heavier cancellation:
/// a third central moment from the raw ones (E M³ − 3m E M² + 2m³, terms
/// up to ~10⁵ for means and spreads up to 10 with read noise), or the V2²
/// signal of a window from bins of size up to N² ≈ 10⁴: ~10⁵–10⁶ ε ≈
/// 2e-11–2e-10; 1e-9 leaves a margin of ~5.
pub const CANCELLATION_ABS: f64 = 1e-9;

/// The streaming (one-pass, merged) third central moment against the
/// two-pass sum, relative, on data offset by ~10⁴ standard deviations (a
/// mean of 10⁶, a spread of ~10²): each update subtracts terms ~(offset/σ)
/// times larger than its result, so a condition number up to ~10⁸ on the
/// relative error of the mean; 1e-7 leaves a margin, while a wrong update
/// coefficient misses by O(1).
pub const STREAMING_M3_REL: f64 = 1e-7;

/// Absolute floor of the [`STREAMING_M3_REL`] comparison, in units of
/// m2^{3/2} (the sum Σ(x − x̄)² to the power 3/2, the natural scale of the
/// sum Σ(x − x̄)³): for nearly symmetric data the third moment is ≪ its
/// scale and only the floor applies; 1e-3 of the scale corresponds to a
/// skewness error of 1e-3·√n ≈ 0.03 for n = 1000, still far below that of
/// a wrong formula.
pub const STREAMING_M3_FLOOR: f64 = 1e-3;

/// How negative a variance that is a difference of nearly equal sums (a
/// window variance of a nearly flat spectrum) may come out, relative to
/// max(|variance|, 1): the same cancellation as [`IDENTITY_REL`] (terms
/// ~10⁶ times the result), so 1e-9 of the scale, ten times
/// [`IDENTITY_REL`] for the extra subtraction.
pub const NONNEGATIVE_REL: f64 = 1e-9;

/// Golden-data comparison: relative tolerance for deterministic curves
/// (the issue's 1e-12; the computations are reproducible to a few ulps, the
/// margin covers a change of libm or of FMA contraction).
pub const GOLDEN_REL: f64 = 1e-12;

/// Absolute floor of the golden comparison, for values that cross zero
/// (a difference of two O(1) numbers is only known to ~1e-15).
pub const GOLDEN_ABS: f64 = 1e-14;

/// Agreement asked of an independent implementation checked against the
/// golden Fig. 1 curves (`examples/check_against_golden.rs`): a user's
/// fixed-grid quadrature of the band converges like h², and 1e-6 absolute
/// on V² (a tenth of the 1e-5 visibility accuracy the paper targets) is
/// reached by a few hundred nodes, while a wrong estimator definition
/// misses by ≥ 1e-3.
pub const EXAMPLE_GOLDEN_ABS: f64 = 1e-6;

/// The piston fringe is linear in the source visibility: run on the same
/// piston sequence, the mean and scatter of V1 and V2 of a grey source of
/// visibility V are V times those of a point source, to rounding (the grey
/// fringe is V times the table's values, not the same floating-point
/// numbers). Over ~10³ scans the statistics carry ~10³ ε of relative
/// rounding, amplified up to ~10² where a mean is small against the
/// scatter it is compared with: ~2e-11 of the scatter; 1e-9 leaves a margin
/// of ~50 and still sees any additive term (which breaks the scaling at
/// O(1)). Also the tolerance of the V2 bias ratio reported in the claims
/// table (0.5 for V = 0.5).
pub const VISIBILITY_SCALING_REL: f64 = 1e-9;

/// The same scaling as [`VISIBILITY_SCALING_REL`], checked in the claims
/// table on ratios of biases and scatters (ratios of numbers that can be as
/// small as ~1e-4, so the rounding above is amplified up to 10⁴ times):
/// 1e-6 absolute on a ratio of 0.5.
pub const VISIBILITY_SCALING_ABS: f64 = 1e-6;

// ---------------------------------------------------------------------------
// Quadrature and special functions
// ---------------------------------------------------------------------------

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

/// The piston spectrum's corner frequencies are closed forms, and the two
/// asymptotes that cross there are power laws with exponents up to 17/3:
/// a relative error δ of ν becomes 17/3 δ, and the prefactors combine a few
/// Gamma functions ([`GAMMA_REL`]); ~10× [`GAMMA_REL`]: 1e-12.
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
/// ≈ 9 [`EPS`] absolute. mpmath's 17-digit reference values are exact to
/// 1e-17 (`tests/data/fresnel_reference.csv`).
pub const FRESNEL_ABS: f64 = 2e-15;

/// The dispersion closed form (Fresnel integrals) against the numerical
/// spectral path, absolute on V²: the issue's requirement. The numerical
/// path is converged to [`QUADRATURE_REL`] on a band integral whose
/// integrand turns through at most P ≤ 4 rad of phase, so 1e-10 is met
/// with a wide margin, while a 1% error in P moves V² by ~1e-3 at P = 1,
/// more than [`POWER_FACTOR`] tolerances.
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

// ---------------------------------------------------------------------------
// Convergence studies
// ---------------------------------------------------------------------------

/// Agreement between the spectral (continuous) estimators and those from a
/// long, finely sampled interferogram: limited by the finite-scan
/// convolution, which falls as 1/(stroke · Δσ); see
/// `long_finely_sampled_scans_converge_to_the_spectral_estimators` in
/// `tests/foundation.rs` and the sampling property in
/// `tests/properties.rs`.
pub const SAMPLED_VS_SPECTRAL_ABS: f64 = 2e-3;

/// A leading-order scaling law (bandwidth bias ∝ Δλ at a null, ∝ Δλ² at a
/// lobe top) checked on bands of 100 and 200 nm at 2.2 µm, relative to the
/// predicted ratio: the next term of the expansion is smaller by
/// (Δλ/λ)² ≈ 1%, plus the motion of the null with the band (~1%); 5%
/// allows both, while the wrong power moves the ratio by 50–100%.
pub const SCALING_LAW_REL: f64 = 0.05;

/// The Δσ² law of the bandwidth bias away from a null, checked by halving
/// bands of 100, 50 and 25 nm, relative to the predicted ratio 4: the
/// correction is O(Δσ²/σ²·(πθBσ)²) ≲ 1% for these bands, so 2.5% (0.1 on
/// 4) is ample and a Δσ¹ or Δσ⁴ law (ratio 2 or 16) fails.
pub const SQUARE_LAW_REL: f64 = 0.025;

/// The tabulated piston PSD (Catmull–Rom in ln G on 80 points per decade
/// of frequency, step h = ln 10/80 ≈ 0.029) against the direct quadrature,
/// relative, where f D ≤ 1: the cubic's error ~h⁴ |d⁴ ln G/d(ln f)⁴|/384
/// is ≲ 1e-6 on the power laws and grows to ~1e-5 at the bends; integrals
/// of the table over frequency inherit the same relative error.
pub const PSD_TABLE_REL: f64 = 1e-5;

/// The tabulated piston PSD over the whole range that carries power (up to
/// 3 v/D), relative: the error of [`PSD_TABLE_REL`] peaks at ~3e-5 near
/// the high-frequency corner, where ln G bends fastest (h⁴ times a larger
/// fourth derivative); 1e-4.
pub const PSD_TABLE_CORNER_REL: f64 = 1e-4;

/// The tabulated piston PSD beyond f D ~ 1, relative: there the table
/// under-resolves the surviving Bessel wiggle (period 1/D, relative
/// amplitude ~(f D)^{−1/2}), sampled only a few times per period, but P is
/// below 1e-6 of its peak; 1e-2 bounds the interpolation of the wiggle.
pub const PSD_TABLE_WIGGLE_REL: f64 = 1e-2;

/// A limit approached as a power of a small parameter, checked well inside
/// its regime, relative: the piston variance for B ≫ D against the point
/// structure function (D/B = 1e-5), the mid-frequency asymptote as the
/// period average of the cosine factor at f D = 9e-4 (with 64 points per
/// period), the outer-scale correction at L0 = 10¹² m ((B/L0)^{1/3} ≈
/// 3e-4). Each correction is ≲ 3e-4; 1e-3 is loose enough for all three
/// and still sees a wrong limit (which differs at O(1)).
pub const ASYMPTOTIC_LIMIT_REL: f64 = 1e-3;

/// A finite sum corrected to leading order by an asymptotic form: the
/// variance of a synthesized piston sequence plus the power below its
/// lowest frequency, taken from the ν^{−2/3} law, against the continuous
/// variance. The missing piece is only approximately on that law (the
/// spectrum starts to bend within a factor ~10 of the corner), so the
/// correction itself is good to ~10–20% of a term that is ~20% of the
/// total; 5%, while omitting the correction fails.
pub const ASYMPTOTIC_CORRECTION_REL: f64 = 0.05;

/// Below the low-frequency corner, P/asymptote − 1 falls linearly in
/// r = ν/corner (the next term of the expansion in Bν/v): the test allows
/// 2r, a coefficient of order one with a margin, at r = 1e-4 … 1e-2.
pub const LOW_FREQ_VALUE_COEFF: f64 = 2.0;

/// The log-slope of P below the low-frequency corner approaches −2/3 with
/// an error linear in r = ν/corner; the log-derivative of a correction
/// c r^p carries the extra factor p (up to ~4 for the terms of the
/// expansion): 10 r.
pub const LOW_FREQ_SLOPE_COEFF: f64 = 10.0;

/// Between the corners, G against its f^{−8/3} asymptote: the aperture
/// filter's expansion in (f D)² gives a relative error falling as (f D)²
/// with a coefficient of order one; 10 (f D)² allows it with a margin and
/// still fails for an error of first order in f D.
pub const MID_FREQ_VALUE_COEFF: f64 = 10.0;

/// The log-slope of G between the corners approaches −8/3 with an error
/// in (f D)²: the log-derivative doubles the coefficient of
/// [`MID_FREQ_VALUE_COEFF`]: 20 (f D)².
pub const MID_FREQ_SLOPE_COEFF: f64 = 20.0;

/// Decade-averaged log-log slope of G above the high-frequency corner,
/// absolute: the residual Bessel oscillation enters the log ratio of two
/// points a decade apart at both ends and shrinks as (f D)^{−1/2}; 0.05
/// (1% of 17/3) resolves the −17/3 law while −8/3 or −11/3 miss by ≥ 2.
pub const DECADE_SLOPE_ABS: f64 = 0.05;

/// The finite-scan bias falls roughly as 1/stroke: each doubling of the
/// stroke halves it, up to the modulation by the sidelobes of the scan's
/// sinc response, which moves individual points of the curve by tens of
/// per cent at most. 30% on the ratio 2 (1.4 to 2.6) allows that, while a
/// bias that does not fall (ratio 1) or falls as 1/stroke² (ratio 4)
/// fails.
pub const ROUGH_SCALING_REL: f64 = 0.3;

/// The line bias is linear in the line width for narrow lines: between
/// widths of 1e-3 and 2e-3 resolution elements the ratio of biases is 2 up
/// to the next order, relative O(width) ≲ 1e-3 · O(1); 1e-3 on the ratio
/// (2e-3 absolute).
pub const LINEAR_RESPONSE_REL: f64 = 1e-3;

/// A small-argument limit checked at the first order of its series, at
/// x = 1e-3: the first neglected terms are π²x⁴/40 ≈ 2.5e-13 (Fresnel C)
/// and π²x⁴/56 ≈ 1.8e-13 (S) relative; 1e-12 relative bounds both with a
/// margin of ~4 and would see a wrong leading coefficient at once.
pub const LEADING_TERM_REL: f64 = 1e-12;

/// The small-P expansion V2² ≈ 1 − 4P²/45 of a point source under
/// quadratic dispersion, at P = 0.01 rad, absolute: the remainder is
/// O(P⁴) with a coefficient of order (4/45)²/2 ≈ 4e-3, i.e. ~4e-11; 1e-9
/// leaves a margin of ~20 while the P² term itself is 9e-6.
pub const SMALL_P_EXPANSION_ABS: f64 = 1e-9;

/// Between two points of the golden 0.1 cycles/arcsec grid, linear
/// interpolation misses the bandwidth-bias curves by h² f''/8 relative to
/// their size, with features on scales of ≳ 3 cycles/arcsec (the lobes of
/// the 43 mas disk): (0.1/3)²/8 ≈ 1.4e-4 of the effect; 1e-3 of the
/// largest effect (away from the kinks at the nulls) leaves a margin.
pub const GRID_INTERPOLATION_REL: f64 = 1e-3;

/// The Dirichlet kernel |sin(πNu)/(N sin πu)| against |sinc(Nu)| at small
/// u, absolute: they differ by the factor πu/sin(πu) − 1 ≈ (πu)²/6 ≈ 8e-7
/// at u = 7e-4; 1e-5 leaves a margin of ~12 while a kernel off by one
/// sample (N − 1) misses by ~1e-3.
pub const DIRICHLET_VS_SINC_ABS: f64 = 1e-5;

/// The integrating-detector normalization factor 1/sinc²(1/p) tends to 1
/// as the samples per fringe p grow, exceeding it by (π/p)²/3 ≈ 3.3e-12
/// at p = 10⁶: 1e-11 absolute is three times that.
pub const SAMPLING_LIMIT_ABS: f64 = 1e-11;

/// A narrow band (Δλ = 1e-4 µm at 2.2 µm) against the monochromatic limit,
/// absolute: the loss factors are even in the band width and depart from
/// their limit at order (Δλ/λ)² ≈ 2e-9 times O(1) coefficients; 1e-8.
pub const NARROW_BAND_LIMIT_ABS: f64 = 1e-8;

/// A convergence sequence may stall at its floor: a step is allowed to
/// increase the error by 5% (the finite-scan bias oscillates with the
/// sinc sidelobes as the scan grows, by a few per cent at the strokes
/// used), on top of an absolute floor of [`QUADRATURE_CHECK_REL`].
pub const CONVERGENCE_GROWTH_REL: f64 = 0.05;

/// A Riemann sum on a grid of step h against the integral it discretizes,
/// absolute for normalized integrals of a flat band: the end cells of a
/// top-hat give an error of at most h / width; with h = 1e-5 µm⁻¹ over the
/// 0.083 µm⁻¹ K band that is 1.2e-4, and 2e-4 allows for the grid's
/// offset.
pub const RIEMANN_SUM_ABS: f64 = 2e-4;

/// The sinc channel response truncated at ±200 resolution elements
/// against the infinite top-hat closed form, absolute on a visibility: the
/// discarded tails carry ~1/(π² · 200) ≈ 5e-4 of the response's area, but
/// the visibility is a ratio in which that area enters only through the
/// line's own share of the channel (the line moves V by ~4e-4 from 0.5):
/// ~5e-4 × 4e-4 × O(1) ≲ 1e-6; 2e-6.
pub const SINC_TAIL_ABS: f64 = 2e-6;

/// The integrating-detector loss of V1² measured on a synthesized
/// interferogram against the spectral formula, absolute: the measurement
/// comes from a finite scan, whose convolution bias is of the order of
/// [`SAMPLED_VS_SPECTRAL_ABS`]; the V2² loss, a single-bin quantity, agrees
/// to [`QUADRATURE_CHECK_REL`].
pub const INTEGRATION_LOSS_ABS: f64 = 2e-3;

/// A number the paper prints to five decimals (e.g. 0.50042): it is
/// reproduced to half a unit in its last place.
pub const PRINTED_5_DECIMALS_ABS: f64 = 5e-6;

/// A number the paper prints to three decimals (e.g. 599.585): reproduced
/// to one unit in its last place (the printed value may be truncated rather
/// than rounded).
pub const PRINTED_3_DECIMALS_ABS: f64 = 1e-3;

/// A value quoted to two decimals (e.g. the corrected OPD per coherence
/// time, 29.95 µm, in the claims table; the paper's 18 m baseline, which
/// 40 cycles/arcsec gives at 2.2 µm as 18.0013 m): reproduced to one unit
/// in its last place.
pub const PRINTED_2_DECIMALS_ABS: f64 = 1e-2;

// ---------------------------------------------------------------------------
// Monte Carlo
// ---------------------------------------------------------------------------

/// Number of standard errors a Monte Carlo test allows (≥ 5 by policy:
/// a 5σ two-sided excursion has probability 5.7e-7 per test).
pub const MC_SIGMAS: f64 = 5.0;

/// Standard errors at which the claims table calls a Monte Carlo bias
/// "significant" or "consistent with" a bound. This is a reporting
/// convention for the reproduction (3σ: 0.27% two-sided per point, so over
/// ~100 points a few chance excursions are expected and counted), not a
/// pass/fail tolerance; tests use [`MC_SIGMAS`].
pub const SIGNIFICANCE_SIGMAS: f64 = 3.0;

/// A check has power when the wrong answer it must reject lies at least
/// this many tolerances (or standard errors) away: 100, so that the
/// rejection cannot be an accident of the tolerance's margin or of a 5σ
/// fluctuation.
pub const POWER_FACTOR: f64 = 100.0;

/// Standard errors by which a Monte Carlo must reject a known-wrong
/// formula whose error is itself a smaller effect (the published variance
/// against the exact one): 50σ, ten times [`MC_SIGMAS`], so neither a
/// fluctuation nor the error of the standard error (a few % at the sample
/// sizes used) can fake the rejection.
pub const MC_POWER_SIGMAS: f64 = 50.0;

// ---------------------------------------------------------------------------
// Assertion helpers
// ---------------------------------------------------------------------------

/// Checks `|actual − expected| ≤ tol · |expected|` (exact equality always
/// passes, so infinities and zeros compare); on failure, the message the
/// macros print. Used by [`assert_rel_eq!`](crate::assert_rel_eq).
pub fn check_rel(actual: f64, expected: f64, tol: f64) -> Result<(), String> {
    let diff = (actual - expected).abs();
    let allowed = tol * expected.abs();
    if actual == expected || diff <= allowed {
        Ok(())
    } else {
        Err(format!(
            "actual {actual:e}, expected {expected:e}: |difference| {diff:e} (relative {:e}) exceeds the relative tolerance {tol:e} (allowed {allowed:e})",
            diff / expected.abs()
        ))
    }
}

/// Checks `|actual − expected| ≤ tol`; on failure, the message the macros
/// print. Used by [`assert_abs_eq!`](crate::assert_abs_eq).
pub fn check_abs(actual: f64, expected: f64, tol: f64) -> Result<(), String> {
    let diff = (actual - expected).abs();
    if actual == expected || diff <= tol {
        Ok(())
    } else {
        Err(format!(
            "actual {actual:e}, expected {expected:e}: |difference| {diff:e} exceeds the absolute tolerance {tol:e}"
        ))
    }
}

/// Checks `|value − expected| ≤ k · stderr`; on failure, the message the
/// macros print. Used by [`assert_within_sigmas!`](crate::assert_within_sigmas).
pub fn check_sigmas(value: f64, expected: f64, stderr: f64, k: f64) -> Result<(), String> {
    let diff = (value - expected).abs();
    let allowed = k * stderr;
    if diff <= allowed {
        Ok(())
    } else {
        Err(format!(
            "value {value:e}, expected {expected:e}: |difference| {diff:e} = {:.2} standard errors of {stderr:e} exceeds {k} (allowed {allowed:e})",
            diff / stderr
        ))
    }
}

/// Asserts that `actual` equals `expected` to a relative tolerance:
/// `|actual − expected| ≤ tol · |expected|`, with `tol` =
/// [`DEFAULT_REL`](crate::tolerance::DEFAULT_REL) unless given. An optional
/// format string and arguments follow the tolerance. On failure the message
/// prints both values, the difference and the tolerance.
///
/// ```
/// use v2ref::{assert_rel_eq, tolerance::ULPS};
/// assert_rel_eq!(0.1 + 0.2, 0.3);
/// assert_rel_eq!(2f64.sqrt().powi(2), 2.0, ULPS);
/// ```
#[macro_export]
macro_rules! assert_rel_eq {
    ($actual:expr, $expected:expr $(,)?) => {
        $crate::assert_rel_eq!($actual, $expected, $crate::tolerance::DEFAULT_REL)
    };
    ($actual:expr, $expected:expr, $tol:expr $(,)?) => {
        if let Err(msg) = $crate::tolerance::check_rel($actual, $expected, $tol) {
            panic!(
                "assert_rel_eq!({}, {}) failed: {}",
                stringify!($actual),
                stringify!($expected),
                msg
            );
        }
    };
    ($actual:expr, $expected:expr, $tol:expr, $($arg:tt)+) => {
        if let Err(msg) = $crate::tolerance::check_rel($actual, $expected, $tol) {
            panic!(
                "assert_rel_eq!({}, {}) failed: {}: {}",
                stringify!($actual),
                stringify!($expected),
                msg,
                format_args!($($arg)+)
            );
        }
    };
}

/// Asserts that `actual` equals `expected` to an absolute tolerance:
/// `|actual − expected| ≤ tol`, with `tol` =
/// [`DEFAULT_ABS`](crate::tolerance::DEFAULT_ABS) unless given. An optional
/// format string and arguments follow the tolerance. On failure the message
/// prints both values, the difference and the tolerance.
///
/// ```
/// use v2ref::{assert_abs_eq, tolerance::ULPS};
/// assert_abs_eq!(0.1 + 0.2, 0.3);
/// assert_abs_eq!((0.5f64).sin().asin(), 0.5, ULPS);
/// ```
#[macro_export]
macro_rules! assert_abs_eq {
    ($actual:expr, $expected:expr $(,)?) => {
        $crate::assert_abs_eq!($actual, $expected, $crate::tolerance::DEFAULT_ABS)
    };
    ($actual:expr, $expected:expr, $tol:expr $(,)?) => {
        if let Err(msg) = $crate::tolerance::check_abs($actual, $expected, $tol) {
            panic!(
                "assert_abs_eq!({}, {}) failed: {}",
                stringify!($actual),
                stringify!($expected),
                msg
            );
        }
    };
    ($actual:expr, $expected:expr, $tol:expr, $($arg:tt)+) => {
        if let Err(msg) = $crate::tolerance::check_abs($actual, $expected, $tol) {
            panic!(
                "assert_abs_eq!({}, {}) failed: {}: {}",
                stringify!($actual),
                stringify!($expected),
                msg,
                format_args!($($arg)+)
            );
        }
    };
}

/// Asserts that a Monte Carlo estimate `value` with standard error `stderr`
/// is within `k` standard errors of `expected`: `|value − expected| ≤ k ·
/// stderr`, with `k` = [`MC_SIGMAS`](crate::tolerance::MC_SIGMAS) unless
/// given. An optional format string and arguments follow `k`. On failure
/// the message prints both values, the difference, the number of standard
/// errors and the bound.
///
/// ```
/// use v2ref::assert_within_sigmas;
/// assert_within_sigmas!(1.02, 1.0, 0.01); // 2σ of 5
/// ```
#[macro_export]
macro_rules! assert_within_sigmas {
    ($value:expr, $expected:expr, $stderr:expr $(,)?) => {
        $crate::assert_within_sigmas!($value, $expected, $stderr, $crate::tolerance::MC_SIGMAS)
    };
    ($value:expr, $expected:expr, $stderr:expr, $k:expr $(,)?) => {
        if let Err(msg) = $crate::tolerance::check_sigmas($value, $expected, $stderr, $k) {
            panic!(
                "assert_within_sigmas!({}, {}) failed: {}",
                stringify!($value),
                stringify!($expected),
                msg
            );
        }
    };
    ($value:expr, $expected:expr, $stderr:expr, $k:expr, $($arg:tt)+) => {
        if let Err(msg) = $crate::tolerance::check_sigmas($value, $expected, $stderr, $k) {
            panic!(
                "assert_within_sigmas!({}, {}) failed: {}: {}",
                stringify!($value),
                stringify!($expected),
                msg,
                format_args!($($arg)+)
            );
        }
    };
}
