//! Tolerances of deterministic identities: rounding only, in units of
//! [`EPS`] times a stated condition number or operation count.

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

/// A value worked out by hand (Python float64) and written in the test with
/// ten significant digits: its last digit is rounded, 5e-10 relative, so
/// 1e-9 (the computation itself is good to [`ROUNDING_REL`]).
pub const HAND_10_DIGITS_REL: f64 = 1e-9;

/// The slack of a band window's edges ([`band_bins`](crate::formalism::estimator::band_bins)),
/// relative to the edge in units of bins (`N δx σ`): a bin within 1e-9 of
/// an edge is on it and kept. An edge and a bin's wavenumber computed from
/// decimal inputs (λ0 ± Δλ/2, N δx) carry a few roundings, ~1e-15
/// relative: the slack is a million times that, so no rounding decides a
/// tie. A bin that misses an edge by less than 1e-9 of it in exact
/// arithmetic is counted on it too: inputs stated to fewer than nine
/// significant digits cannot put a bin that close without putting it on
/// the edge.
pub const BAND_EDGE_REL: f64 = 1e-9;

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

/// The four-step inverse DFT (`math::fft::inverse_dft`) against a single
/// rustfft transform or the naive DFT, as the largest difference relative
/// to the largest output magnitude, for M ≤ 1.3·10⁶: each route carries
/// ~ε log2 M ≈ 5e-15 of relative rounding per output, and the two-table
/// twiddles add ~2ε; the error of an output relative to the largest is at
/// most a few ×1e-14 even when errors add coherently; 1e-12 leaves a margin
/// of ~30, while a wrong twiddle or index moves outputs by O(1).
pub const FOUR_STEP_REL: f64 = 1e-12;

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
/// N = 58 samples, and each route is converged to [`QUADRATURE_REL`](super::QUADRATURE_REL) of
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
/// (the 1e-12; the computations are reproducible to a few ulps, the
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

/// The one-pass and merged running statistics against an exact two-pass
/// computation on data whose mean (10⁹) dwarfs their spread (σ ≈ 0.6):
/// every update rounds the running mean to half an ulp of 10⁹ (6e-8), i.e.
/// r ≈ 1e-7 of σ. The mean's error is a weighted walk of these roundings,
/// ~√(n/3) r ≈ 2e-6 σ for n = 10³; the central sums Σ(x − x̄)^p see the
/// mean's error only at second order, but each deviation carries r, so p r
/// ≲ 4e-7 relative even when the roundings add coherently. 1e-5 (the mean
/// in units of σ, m2 and m4 relative, m3 relative to m2^{3/2}) covers both,
/// while an n instead of an n − 1 in the variance moves it by 1/n = 1e-3 and
/// a wrong merge coefficient by O(1).
pub const STREAMING_LARGE_MEAN_REL: f64 = 1e-5;

/// A flat channel's bandwidth bias against its second-order law
/// (`g'' Δσ²/24`, `V V'' Δσ²/12`, `bias::channels`): the neglected term is
/// of relative order (Δσ/ℓ)², ℓ the wavenumber scale over which V bends; for
/// a 43 mas disk at 40 cycles/arcsec and Δσ ≤ 0.064 µm⁻¹ (a sixth of the
/// K band or less) 3 % holds, while a law off by a factor 2 (a Δσ²/12 for a
/// Δσ²/24) is off by 100 %.
pub const CHANNEL_SECOND_ORDER_REL: f64 = 0.03;

/// The channels' fringes summed against the band's, in units of the band's
/// photons per sample: each is integrated on its own Gauss–Legendre nodes
/// (`SpectralNodes`, converged far below 1e-12 of the continuum), so they
/// agree to rounding; 1e-9 leaves room for the sum of a few channels while
/// a channel's share off by one part in 10⁶ moves the sum 10³ times more.
pub const CHANNEL_FRINGE_SUM_REL: f64 = 1e-9;
