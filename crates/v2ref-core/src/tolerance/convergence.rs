//! Tolerances of convergence studies: truncated series, discretizations,
//! asymptotic regimes, printed precision.

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
/// used), on top of an absolute floor of [`QUADRATURE_CHECK_REL`](super::QUADRATURE_CHECK_REL).
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
/// to [`QUADRATURE_CHECK_REL`](super::QUADRATURE_CHECK_REL).
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
