//! The ranges of the physical inputs, in one place.
//!
//! Each bound is where the model stops describing an observation, or where
//! the computation would leave the floating-point range or its own
//! accuracy, whichever comes first; the reason is given with each. The
//! constructors that take these inputs check them and return
//! [`Error::OutOfRange`](crate::Error::OutOfRange) naming the parameter, so
//! that no input inside the ranges gives a non-finite answer and none
//! outside them gives a silent one. The CLI's `--help` states them.

use crate::error::{self, Result};

/// Shortest centre wavelength λ0, µm (1 nm): below it the band is X-rays,
/// where no fringe-scanning interferometer works.
pub const WAVELENGTH_MIN_UM: f64 = 1e-3;

/// Longest centre wavelength λ0, µm (10 cm, radio).
pub const WAVELENGTH_MAX_UM: f64 = 1e5;

/// Largest peak-to-peak quadratic dispersion phase over the band, rad.
/// Up to it the V2 quadrature resolves the phase's oscillation across the
/// band (V2 follows the Fresnel law 1/√P of a flat band); at 3e4 rad it is
/// already 20 % off. V2 there is below 1e-3 of V.
pub const DISPERSION_PP_MAX_RAD: f64 = 1e4;

/// Largest uniform-disk diameter, mas (1°): the visibility formula is that
/// of a small source (a plane sky); a source of a degree is no longer one.
pub const DIAMETER_MAX_MAS: f64 = 3.6e6;

/// Longest projected baseline, m (a million km, beyond any planned space
/// interferometer).
pub const BASELINE_MAX_M: f64 = 1e9;

/// Highest spatial frequency, cycles/arcsec: that of [`BASELINE_MAX_M`] at
/// [`WAVELENGTH_MIN_UM`] (B/λ = 1e18 rad⁻¹ ≈ 4.8e12 cycles/arcsec), rounded
/// up.
pub const SPATIAL_FREQ_MAX_CPAS: f64 = 1e13;

/// Most photons per sample (continuum), and the largest detector noise in
/// photons per sample: beyond the full well of any detector. The
/// variances hold fourth powers of the counts times N²; 1e12 keeps them
/// below 1e70, far inside the floating-point range.
pub const PHOTONS_MAX: f64 = 1e12;

/// Largest mean total count `c + m` of one sample: a continuum within
/// [`PHOTONS_MAX`] plus a fringe of |visibility| ≤ 1.
pub const MEAN_COUNT_MAX: f64 = 2.0 * PHOTONS_MAX;

/// Fastest wind of the frozen-flow turbulence, m/s (the speed of sound at
/// ground level: no layer of the atmosphere moves faster).
pub const WIND_MAX_MPS: f64 = 343.0;

/// Most samples per fringe of the planner: a finer sampling only adds
/// samples (N grows with it, and the finite scan costs N²). The fewest is
/// 2, Nyquist at the centre wavelength (fewer aliases any band).
pub const PLAN_SAMPLES_PER_FRINGE_MAX: f64 = 1e3;

/// Highest photon rate at the detector, photons/s (a zeroth-magnitude star
/// through a 100 m² aperture gives about 1e12 in K; 1e15 leaves room, and
/// keeps photons per sample within [`PHOTONS_MAX`] at any fringe frequency
/// the planner scans).
pub const PHOTON_RATE_MAX_PER_S: f64 = 1e15;

/// Longest dead time or time budget of the planner, s (a year).
pub const PLAN_TIME_MAX_S: f64 = 3.2e7;

/// Smallest target σ(V²) of the planner: far below any calibration error
/// (the scans needed grow as 1/σ², and overflow a count below 1e-150).
pub const PLAN_SIGMA_V2_MIN: f64 = 1e-9;

/// Worst seeing λ/r0, arcsec: r0 of 4.5 mm in K. Beyond, no fringe can be
/// tracked (ground-level seeing at the worst sites stays below 5″), and the
/// piston variance ∝ r0^(−5/3) heads for the floating-point limit.
pub const SEEING_MAX_ARCSEC: f64 = 100.0;

/// Shortest and longest wavelength at which a seeing may be quoted, µm:
/// site monitors measure it in the visible (0.5 µm) or the near infrared,
/// where the λ^(−1/5) law that converts it holds; a seeing "at" 1 nm or
/// 10 cm describes no measurement.
pub const SEEING_WAVELENGTH_MIN_UM: f64 = 0.3;
/// See [`SEEING_WAVELENGTH_MIN_UM`] (the N band's long end, rounded up).
pub const SEEING_WAVELENGTH_MAX_UM: f64 = 30.0;

/// Checks the wavelength at which a seeing is quoted (µm):
/// [`SEEING_WAVELENGTH_MIN_UM`] to [`SEEING_WAVELENGTH_MAX_UM`].
pub fn check_seeing_wavelength_um(wavelength_um: f64) -> Result<f64> {
    error::finite("seeing_wavelength_um", wavelength_um)?;
    check(
        "seeing_wavelength_um",
        wavelength_um,
        SEEING_WAVELENGTH_MIN_UM,
        SEEING_WAVELENGTH_MAX_UM,
    )
}

/// Checks a seeing (arcsec): `0 <= seeing <=` [`SEEING_MAX_ARCSEC`]
/// (0: no turbulence).
pub fn check_seeing_arcsec(seeing_arcsec: f64) -> Result<f64> {
    error::non_negative("seeing_arcsec", seeing_arcsec)?;
    check("seeing_arcsec", seeing_arcsec, 0.0, SEEING_MAX_ARCSEC)
}

/// Checks a centre wavelength λ0 (µm) against [`WAVELENGTH_MIN_UM`] …
/// [`WAVELENGTH_MAX_UM`].
pub fn check_wavelength_um(wavelength_um: f64) -> Result<f64> {
    error::finite("wavelength_um", wavelength_um)?;
    check(
        "wavelength_um",
        wavelength_um,
        WAVELENGTH_MIN_UM,
        WAVELENGTH_MAX_UM,
    )
}

/// Slowest wind, m/s: a millimetre a second. Below, the piston's time
/// scales D/v and B/v leave the range where its spectrum is finite (at
/// 5e-324 m/s every bias and scatter was undefined).
pub const WIND_MIN_MPS: f64 = 1e-3;

/// Checks a wind speed (m/s): [`WIND_MIN_MPS`] `<= v <=` [`WIND_MAX_MPS`].
pub fn check_wind_mps(wind_mps: f64) -> Result<f64> {
    positive_at_most("wind_mps", wind_mps, WIND_MAX_MPS)?;
    check("wind_mps", wind_mps, WIND_MIN_MPS, WIND_MAX_MPS)
}

/// Smallest telescope aperture D, m (a millimetre).
pub const APERTURE_MIN_M: f64 = 1e-3;

/// Largest telescope aperture D, m (a kilometre: beyond any telescope;
/// at 1e300 m the aperture filter of the piston spectrum underflows).
pub const APERTURE_MAX_M: f64 = 1e3;

/// Checks a telescope aperture (m): [`APERTURE_MIN_M`] to [`APERTURE_MAX_M`].
pub fn check_aperture_m(aperture_m: f64) -> Result<f64> {
    error::positive("aperture_m", aperture_m)?;
    check("aperture_m", aperture_m, APERTURE_MIN_M, APERTURE_MAX_M)
}

/// Narrowest band relative to its centre, Δλ/λ0: a narrower width is lost
/// in the rounding of λ0 (f64 keeps 16 digits) and the band's moments
/// become 0/0; such a band is monochromatic (`Spectrum::monochromatic`).
pub const BANDWIDTH_MIN_FRACTION: f64 = 1e-12;

/// Checks a band's full width Δλ against its centre λ0 (µm):
/// `BANDWIDTH_MIN_FRACTION · λ0 <= Δλ < 2 λ0` (the band must not reach zero
/// wavelength). `param` and `unit_per_um` say how the width `bandwidth` was
/// given (`bandwidth_um` and 1, or `bandwidth_nm` and 1000), so that a
/// refusal quotes the user's number in the user's unit.
pub fn check_bandwidth(
    param: &'static str,
    unit_per_um: f64,
    wavelength_um: f64,
    bandwidth: f64,
) -> Result<()> {
    check_wavelength_um(wavelength_um)?;
    error::positive(param, bandwidth)?;
    let min = BANDWIDTH_MIN_FRACTION * wavelength_um * unit_per_um;
    let max = 2.0 * wavelength_um * unit_per_um;
    if (min..max).contains(&bandwidth) {
        return Ok(());
    }
    let unit = if unit_per_um == 1.0 { "um" } else { "nm" };
    Err(crate::Error::OutOfRange {
        param,
        value: bandwidth,
        accepted: format!(
            "{} <= bandwidth < {} {unit} (from 1e-12 of the centre wavelength, below which the band is a line, to twice it, where the band would reach zero wavelength)",
            error::number(min),
            error::number(max)
        ),
    })
}

/// Checks that `value` lies in `lo ..= hi`, naming `param` otherwise.
pub fn check(param: &'static str, value: f64, lo: f64, hi: f64) -> Result<f64> {
    error::in_range(param, value, lo, hi)
}

/// Checks that `0 < value <= hi`.
pub fn positive_at_most(param: &'static str, value: f64, hi: f64) -> Result<f64> {
    error::positive(param, value)?;
    if value <= hi {
        Ok(value)
    } else {
        Err(crate::Error::OutOfRange {
            param,
            value,
            accepted: format!("> 0 and <= {}", error::number(hi)),
        })
    }
}

/// Checks that `0 <= value <= hi`.
pub fn non_negative_at_most(param: &'static str, value: f64, hi: f64) -> Result<f64> {
    error::in_range(param, value, 0.0, hi)
}

/// Most rows of a synthesized test set (`v2ref synth`, Python `synthesize`).
pub const SET_MAX_ROWS: u64 = 1 << 32;
/// Most values (rows × samples) of a set: 2^31 float64, 16 GiB.
pub const SET_MAX_VALUES: u64 = 1 << 31;
/// Most blocks in a set's reference run.
pub const SET_MAX_REFERENCE_BLOCKS: u64 = 1000;
/// Fewest blocks in a set's reference run (other than 0, none). With
/// piston the set's spread is measured over the blocks, and the score's
/// ratio is Student-t with `blocks − 1` degrees of freedom: valid at any
/// count, but its threshold at the default alpha (10⁻³, 4 tests) is 20.6
/// with 4 blocks and 2546 with 2 (the test sees nothing), 6.8 with 8.
/// 8 is the least that still tells a pipeline something
/// (`conformance::truth`).
pub const SET_MIN_REFERENCE_BLOCKS: u64 = 8;

/// Refuses an empty or oversized test set: `rows` of `samples` (≥ 1)
/// samples, and `blocks` reference blocks (0 for none, else
/// [`SET_MIN_REFERENCE_BLOCKS`] to [`SET_MAX_REFERENCE_BLOCKS`]).
pub fn check_set_size(rows: u64, samples: usize, blocks: u64) -> crate::Result<()> {
    let max_rows = SET_MAX_ROWS.min(SET_MAX_VALUES / samples.max(1) as u64);
    if !(2..=max_rows).contains(&rows) {
        return Err(crate::Error::OutOfRange {
            param: "rows",
            value: rows as f64,
            accepted: format!("2 to {max_rows} with {samples} samples per row"),
        });
    }
    if blocks != 0 && !(SET_MIN_REFERENCE_BLOCKS..=SET_MAX_REFERENCE_BLOCKS).contains(&blocks) {
        return Err(crate::Error::OutOfRange {
            param: "reference_blocks",
            value: blocks as f64,
            accepted: format!(
                "0 (none) or {SET_MIN_REFERENCE_BLOCKS} to {SET_MAX_REFERENCE_BLOCKS} \
                 (fewer leave too few degrees of freedom for the score's test)"
            ),
        });
    }
    Ok(())
}

/// Reserves room for exactly `count` more values in `values`, refusing
/// (naming `param`) what the system cannot give — a request past the
/// address-space limit of the process, or beyond its memory — instead of
/// letting the allocation abort the process. `what` says what the values
/// are, for the message (`"values of 2000 rows of 32 samples"`).
pub fn reserve<T>(
    values: &mut Vec<T>,
    count: usize,
    param: &'static str,
    what: &dyn Fn() -> String,
) -> crate::Result<()> {
    values.try_reserve_exact(count).map_err(|_| {
        let gib = count as f64 * std::mem::size_of::<T>() as f64 / (1u64 << 30) as f64;
        crate::Error::Invalid {
            param,
            reason: format!(
                "the {} take {gib:.2} GiB, which this process cannot allocate; make the set smaller",
                what()
            ),
        }
    })
}

/// Refuses (naming `param`) an `index` not below `count`, the number of
/// `what` of the set.
pub(crate) fn check_index(
    param: &'static str,
    index: u64,
    count: u64,
    what: &str,
) -> crate::Result<()> {
    if index < count {
        return Ok(());
    }
    Err(crate::Error::OutOfRange {
        param,
        value: index as f64,
        accepted: format!(
            "0 to {} (the set's {count} {what})",
            count.saturating_sub(1)
        ),
    })
}
