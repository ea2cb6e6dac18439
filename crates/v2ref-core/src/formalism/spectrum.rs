//! The band and the weighting function W(σ) (paper, Section "General
//! formalism": `W = S F / ∫ S F dσ`).
//!
//! A [`Spectrum`] is the product S(σ)F(σ) of the source spectrum and the
//! transmission as a function of wavenumber σ (µm⁻¹), up to a constant. It
//! offers the two averages every estimator is built from:
//!
//! - [`Spectrum::mean_w`]: `∫ W(σ) f(σ) dσ` (W as a probability density);
//! - [`Spectrum::mean_w2`]: `∫ W²(σ) f(σ) dσ / ∫ W² dσ`;
//!
//! computed by adaptive Gauss–Kronrod quadrature split at every kink of the
//! spectrum, converged to `tolerance::QUADRATURE_REL` (1e-13). A
//! monochromatic spectrum (a Dirac line) is the limit where both averages
//! are `f(σ0)`.
//!
//! Conventions (`docs/conventions.md`): a band of centre λ0 and width Δλ covers
//! `[λ0 − Δλ/2, λ0 + Δλ/2]`, i.e. `σ ∈ [1/(λ0 + Δλ/2), 1/(λ0 − Δλ/2)]`; a
//! flat spectrum is constant in σ over that interval.

use crate::error::{self, Error, Result};
use crate::math::quadrature::{integrate_pieces, QuadValue, Tolerance};

/// Spatial frequency (cycles/arcsec) per metre of baseline per µm⁻¹ of
/// wavenumber: `S = B σ · 10⁶ · π / 648000`.
pub const CPAS_PER_M_PER_INV_UM: f64 = 1e6 * std::f64::consts::PI / 648_000.0;

/// Micrometres per nanometre (unit conversion of bandwidths given in nm).
pub const UM_PER_NM: f64 = 1e-3;

/// A spectral band given by its centre wavelength and full width.
///
/// # Example
///
/// ```
/// use v2ref_core::prelude::*;
/// use v2ref_core::formalism::estimator::{all_bins, positive_bins};
/// let k = Band::k(); // 2.0–2.4 µm
/// assert_eq!(k, Band::new(2.2, 0.4)?);
/// assert!((k.sigma_min_per_um() - 1.0 / 2.4).abs() < 1e-15);
/// // A band reaching zero wavelength is refused, naming the parameter.
/// assert_eq!(Band::new(1.0, 2.5).unwrap_err().param(), Some("bandwidth_um"));
/// # Ok::<(), v2ref_core::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Band {
    centre_um: f64,
    width_um: f64,
}

/// Most data rows of a tabulated spectrum: far more than a filter curve
/// or a measured spectrum needs for the bias integrals (the cost of the
/// table grows with its rows), few enough to read in a second.
pub const MAX_SPECTRUM_ROWS: usize = 100_000;

/// Largest spectrum CSV file read, bytes (room for [`MAX_SPECTRUM_ROWS`]
/// rows with comments).
pub const MAX_SPECTRUM_CSV_BYTES: u64 = 16 << 20;

impl Band {
    /// Band of centre `wavelength_um` (λ0, µm) and full width `bandwidth_um`
    /// (Δλ, µm). Requires λ0 within [`crate::bounds::WAVELENGTH_MIN_UM`] …
    /// [`crate::bounds::WAVELENGTH_MAX_UM`] and Δλ within
    /// [`crate::bounds::check_bandwidth`]'s range (up to 2 λ0, where the band
    /// would reach zero wavelength).
    pub fn new(wavelength_um: f64, bandwidth_um: f64) -> Result<Band> {
        crate::bounds::check_bandwidth("bandwidth_um", 1.0, wavelength_um, bandwidth_um)?;
        Ok(Band {
            centre_um: wavelength_um,
            width_um: bandwidth_um,
        })
    }

    /// The paper's K band: 2.2 µm centre, 0.4 µm wide (2.0–2.4 µm).
    pub fn k() -> Band {
        Band {
            centre_um: 2.2,
            width_um: 0.4,
        }
    }

    /// Centre wavelength λ0, µm.
    pub fn centre_um(&self) -> f64 {
        self.centre_um
    }
    /// Full width Δλ, µm.
    pub fn width_um(&self) -> f64 {
        self.width_um
    }
    /// Lowest wavenumber `1/(λ0 + Δλ/2)`, µm⁻¹.
    pub fn sigma_min_per_um(&self) -> f64 {
        1.0 / (self.centre_um + 0.5 * self.width_um)
    }
    /// Highest wavenumber `1/(λ0 − Δλ/2)`, µm⁻¹.
    pub fn sigma_max_per_um(&self) -> f64 {
        1.0 / (self.centre_um - 0.5 * self.width_um)
    }
}

/// The shape of S(σ)F(σ), unnormalized.
#[derive(Debug, Clone, PartialEq)]
enum Shape {
    /// Dirac line at σ.
    Line { sigma: f64 },
    /// Constant on [lo, hi].
    Flat { lo: f64, hi: f64 },
    /// `(σ/σ_mid)^index` on [lo, hi].
    PowerLaw { lo: f64, hi: f64, index: f64 },
    /// Top-hat [lo, hi] whose edges are raised-cosine ramps of full width
    /// `edge`, centred on lo and hi (half power at lo and hi).
    SmoothEdges { lo: f64, hi: f64, edge: f64 },
    /// Piecewise linear through (σ_j, w_j), zero outside.
    Table { sigma: Vec<f64>, weight: Vec<f64> },
}

/// S(σ)F(σ) over a band, with its normalization and effective wavenumber.
///
/// # Example
///
/// ```
/// use v2ref_core::prelude::*;
/// use v2ref_core::formalism::estimator::{all_bins, positive_bins};
/// // A flat band in wavenumber: σ_eff is the centre of [1/2.4, 1/2.0] µm⁻¹.
/// let k = Spectrum::flat(Band::k());
/// assert!((k.sigma_eff_per_um() - 0.5 * (1.0 / 2.4 + 0.5)).abs() < 1e-12);
/// // A source spectrum ∝ σ² (Rayleigh–Jeans) moves σ_eff blueward.
/// let rj = Spectrum::power_law(Band::k(), 2.0)?;
/// assert!(rj.sigma_eff_per_um() > k.sigma_eff_per_um());
/// # Ok::<(), v2ref_core::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Spectrum {
    shape: Shape,
    /// ∫ S F dσ.
    norm: f64,
    /// ∫ W² dσ (µm).
    w2_integral: f64,
    /// σ_eff = ∫ σ W dσ.
    sigma_eff: f64,
}

impl Spectrum {
    /// Flat S F over the band (the paper's default: flat spectrum and flat
    /// transmission).
    pub fn flat(band: Band) -> Spectrum {
        Self::build(Shape::Flat {
            lo: band.sigma_min_per_um(),
            hi: band.sigma_max_per_um(),
        })
    }

    /// A monochromatic spectrum at `wavelength_um`: the zero-bandwidth limit.
    pub fn monochromatic(wavelength_um: f64) -> Result<Spectrum> {
        crate::bounds::check_wavelength_um(wavelength_um)?;
        Ok(Self::build(Shape::Line {
            sigma: 1.0 / wavelength_um,
        }))
    }

    /// S F ∝ (σ/σ_c)^index over the band, σ_c the band centre in
    /// wavenumber: a smooth model of a spectral slope (index 0 is flat).
    pub fn power_law(band: Band, index: f64) -> Result<Spectrum> {
        error::in_range("index", index, -20.0, 20.0)?;
        Ok(Self::build(Shape::PowerLaw {
            lo: band.sigma_min_per_um(),
            hi: band.sigma_max_per_um(),
            index,
        }))
    }

    /// A top-hat over the band with raised-cosine edges of full width
    /// `edge_per_um` (µm⁻¹) centred on each band edge, so that the
    /// equivalent width stays the band's. Requires
    /// `0 < edge_per_um ≤ σ_max − σ_min`.
    pub fn smooth_top_hat(band: Band, edge_per_um: f64) -> Result<Spectrum> {
        let (lo, hi) = (band.sigma_min_per_um(), band.sigma_max_per_um());
        error::positive("edge_per_um", edge_per_um)?;
        if edge_per_um > hi - lo {
            return Err(Error::OutOfRange {
                param: "edge_per_um",
                value: edge_per_um,
                accepted: format!("0 < edge <= {} per um (the band width)", hi - lo),
            });
        }
        Ok(Self::build(Shape::SmoothEdges {
            lo,
            hi,
            edge: edge_per_um,
        }))
    }

    /// A tabulated S F, piecewise linear between the nodes and zero outside.
    /// `sigma_per_um` strictly increasing and positive, `weight` ≥ 0 and not
    /// all zero, at least two nodes.
    pub fn tabulated(sigma_per_um: Vec<f64>, weight: Vec<f64>) -> Result<Spectrum> {
        let bad = |reason: String| Err(Error::SpectrumTable { reason });
        if sigma_per_um.len() != weight.len() {
            return bad("wavenumber and weight columns differ in length".into());
        }
        if sigma_per_um.len() < 2 {
            return bad(format!(
                "{} data row(s); at least 2 are needed",
                sigma_per_um.len()
            ));
        }
        for (j, (&s, &w)) in sigma_per_um.iter().zip(&weight).enumerate() {
            if !s.is_finite() || s <= 0.0 {
                return bad(format!(
                    "node {}: wavenumber {s} is not a finite number > 0",
                    j + 1
                ));
            }
            if !w.is_finite() || w < 0.0 {
                return bad(format!(
                    "node {}: weight {w} is not a finite number >= 0",
                    j + 1
                ));
            }
        }
        if let Some(j) = sigma_per_um.windows(2).position(|p| p[1] <= p[0]) {
            return bad(format!(
                "nodes {} and {}: the axis must be strictly increasing (no duplicates)",
                j + 1,
                j + 2
            ));
        }
        if weight.iter().all(|&w| w == 0.0) {
            return bad("every weight is zero".into());
        }
        let sp = Self::build(Shape::Table {
            sigma: sigma_per_um,
            weight,
        });
        // Extreme magnitudes (weights whose squares overflow, an axis over
        // hundreds of decades) leave no usable weighting function.
        let usable = |x: f64| x.is_finite() && x > 0.0;
        if !(usable(sp.norm) && usable(sp.w2_integral) && usable(sp.sigma_eff)) {
            return bad(
                "the table's magnitudes overflow (weights or axis values too large or too spread); rescale the weights"
                    .into(),
            );
        }
        Ok(sp)
    }

    /// Reads a tabulated spectrum from CSV text: `#` comments, then the
    /// header `wavelength_um,weight` or `wavenumber_per_um,weight`, then rows
    /// with the axis strictly increasing. `weight` (also spelled
    /// `weight_per_wavenumber`) is S(σ)F(σ) at that point (the photon
    /// spectrum per unit wavenumber times the transmission, any scale);
    /// `weight_per_um` is the same per unit wavelength, converted by the
    /// Jacobian λ² (W_σ = λ² W_λ). It is interpolated linearly in
    /// wavenumber. A leading UTF-8 byte-order mark is skipped. At most
    /// [`MAX_SPECTRUM_ROWS`] rows. The file of the same text is read by the
    /// edges (`spectrum_from_csv_path` of the crate `v2ref-files`): the core reads no
    /// file.
    pub fn from_csv_str(text: &str) -> Result<Spectrum> {
        // Some((wavelength axis, weight per unit wavelength)).
        let mut axis: Option<(bool, bool)> = None;
        let (mut xs, mut ws) = (Vec::new(), Vec::new());
        // Text in memory: every line can be read (no limit, no I/O).
        let mut lines = crate::csv_lines::CsvLines::new(text.as_bytes(), u64::MAX);
        while let Some((n, cells)) = lines.next_record().map_err(|e| Error::SpectrumTable {
            reason: format!("line {}: cannot be read ({:?})", e.line, e.fault),
        })? {
            let at = |reason: String| Error::SpectrumTable {
                reason: format!("line {n}: {reason}"),
            };
            if cells.len() != 2 {
                return Err(at(format!("{} columns; expected 2", cells.len())));
            }
            if axis.is_none() {
                axis = Some(csv_header(&cells).map_err(at)?);
            } else if xs.len() == MAX_SPECTRUM_ROWS {
                return Err(at(format!(
                    "more than {MAX_SPECTRUM_ROWS} rows; resample the spectrum (the bias integrals need far fewer)"
                )));
            } else {
                let (x, w) = csv_row(&cells, xs.last().copied()).map_err(at)?;
                xs.push(x);
                ws.push(w);
            }
        }
        let Some((is_wavelength, per_wavelength)) = axis else {
            return Err(Error::SpectrumTable {
                reason: "no header: expected 'wavelength_um,weight' or 'wavenumber_per_um,weight'"
                    .into(),
            });
        };
        if per_wavelength {
            // W_σ dσ = W_λ dλ with |dλ/dσ| = λ² = 1/σ².
            for (w, &x) in ws.iter_mut().zip(&xs) {
                *w *= if is_wavelength { x * x } else { 1.0 / (x * x) };
            }
        }
        if is_wavelength {
            // Increasing wavelength is decreasing wavenumber.
            xs = xs.iter().rev().map(|l| 1.0 / l).collect();
            ws.reverse();
        }
        Self::tabulated(xs, ws)
    }

    fn build(shape: Shape) -> Spectrum {
        let mut s = Spectrum {
            shape,
            norm: 1.0,
            w2_integral: 1.0,
            sigma_eff: 0.0,
        };
        if let Shape::Line { sigma } = s.shape {
            s.sigma_eff = sigma;
            s.w2_integral = f64::INFINITY;
            return s;
        }
        let [n, n2, m] = s.integrate_raw(|sig, w| [w, w * w, sig * w]);
        s.norm = n;
        s.w2_integral = n2 / (n * n);
        s.sigma_eff = m / n;
        s
    }

    /// The nodes (σ_j µm⁻¹, w_j) of a tabulated spectrum; None for the
    /// analytic shapes.
    pub fn table(&self) -> Option<(&[f64], &[f64])> {
        match &self.shape {
            Shape::Table { sigma, weight } => Some((sigma, weight)),
            _ => None,
        }
    }

    /// Whether S F is linear between its kinks (flat or tabulated): then its
    /// restriction to a sub-interval is exactly a table (the channels of
    /// `formalism::channels`).
    pub fn is_piecewise_linear(&self) -> bool {
        matches!(self.shape, Shape::Flat { .. } | Shape::Table { .. })
    }

    /// Whether this is a Dirac line.
    pub fn is_monochromatic(&self) -> bool {
        matches!(self.shape, Shape::Line { .. })
    }

    /// The interval outside which W is zero, µm⁻¹.
    pub fn support(&self) -> (f64, f64) {
        match &self.shape {
            Shape::Line { sigma } => (*sigma, *sigma),
            Shape::Flat { lo, hi } | Shape::PowerLaw { lo, hi, .. } => (*lo, *hi),
            Shape::SmoothEdges { lo, hi, edge } => (lo - 0.5 * edge, hi + 0.5 * edge),
            Shape::Table { sigma, .. } => (sigma[0], sigma[sigma.len() - 1]),
        }
    }

    /// σ0, the centre of the band in wavenumber (the expansion point of the
    /// dispersion phase). For the parametric shapes it is the centre of the
    /// nominal band; for a table, the centre of its support.
    pub fn sigma_centre_per_um(&self) -> f64 {
        match &self.shape {
            Shape::SmoothEdges { lo, hi, .. } => 0.5 * (lo + hi),
            _ => {
                let (lo, hi) = self.support();
                0.5 * (lo + hi)
            }
        }
    }

    /// Δσ, the nominal width of the band in wavenumber, µm⁻¹ (zero for a line).
    pub fn width_per_um(&self) -> f64 {
        match &self.shape {
            Shape::SmoothEdges { lo, hi, .. } => hi - lo,
            _ => {
                let (lo, hi) = self.support();
                hi - lo
            }
        }
    }

    /// The effective wavenumber σ_eff = ∫ σ W dσ, µm⁻¹.
    pub fn sigma_eff_per_um(&self) -> f64 {
        self.sigma_eff
    }

    /// ∫ W² dσ, µm (infinite for a line).
    pub fn w2_integral_um(&self) -> f64 {
        self.w2_integral
    }

    /// S F at σ, unnormalized (zero outside the support; 0 for a line).
    pub fn raw_weight(&self, sigma: f64) -> f64 {
        match &self.shape {
            Shape::Line { .. } => 0.0,
            Shape::Flat { lo, hi } => f64::from(u8::from(sigma >= *lo && sigma <= *hi)),
            Shape::PowerLaw { lo, hi, index } => {
                if sigma >= *lo && sigma <= *hi {
                    (sigma / (0.5 * (lo + hi))).powf(*index)
                } else {
                    0.0
                }
            }
            Shape::SmoothEdges { lo, hi, edge } => {
                let d = (sigma - lo).min(hi - sigma); // distance inside the nearer edge
                if d >= 0.5 * edge {
                    1.0
                } else if d <= -0.5 * edge {
                    0.0
                } else {
                    0.5 * (1.0 + (std::f64::consts::PI * d / edge).sin())
                }
            }
            Shape::Table {
                sigma: s,
                weight: w,
            } => {
                if sigma < s[0] || sigma > s[s.len() - 1] {
                    return 0.0;
                }
                let j = s.partition_point(|&x| x <= sigma).clamp(1, s.len() - 1);
                let t = (sigma - s[j - 1]) / (s[j] - s[j - 1]);
                w[j - 1] + t * (w[j] - w[j - 1])
            }
        }
    }

    /// W(σ) = S F / ∫ S F dσ, µm (zero outside the support; a line has no
    /// density and returns 0).
    pub fn weight(&self, sigma: f64) -> f64 {
        self.raw_weight(sigma) / self.norm
    }

    /// The points where W or its derivative jumps, in increasing order.
    fn breaks(&self) -> Vec<f64> {
        match &self.shape {
            Shape::Line { sigma } => vec![*sigma],
            Shape::Flat { lo, hi } | Shape::PowerLaw { lo, hi, .. } => vec![*lo, *hi],
            Shape::SmoothEdges { lo, hi, edge } => {
                let h = 0.5 * edge;
                let mut b = vec![lo - h, lo + h, hi - h, hi + h];
                b.dedup();
                b
            }
            Shape::Table { sigma, .. } => sigma.clone(),
        }
    }

    /// The spectrum's kinks plus the `extra` points that fall inside its
    /// support, sorted: the pieces over which integrands are smooth.
    pub fn pieces(&self, extra: &[f64]) -> Vec<f64> {
        let mut b = self.breaks();
        let (lo, hi) = self.support();
        b.extend(extra.iter().copied().filter(|&x| x > lo && x < hi));
        b.sort_by(f64::total_cmp);
        b.dedup();
        b
    }

    /// ∫ g(σ, S F(σ)) dσ over the support, piece by piece.
    fn integrate_raw<T: QuadValue>(&self, g: impl Fn(f64, f64) -> T) -> T {
        self.integrate_raw_split(g, &[])
    }

    fn integrate_raw_split<T: QuadValue>(&self, g: impl Fn(f64, f64) -> T, extra: &[f64]) -> T {
        let f = |s: f64| g(s, self.raw_weight(s));
        integrate_pieces(&f, &self.pieces(extra), Tolerance::default())
    }

    /// `∫ W(σ) f(σ) dσ`: the W-weighted mean of f (W is a unit-area density).
    /// For a line, `f(σ0)`.
    pub fn mean_w<T: QuadValue>(&self, f: impl Fn(f64) -> T) -> T {
        self.mean_w_split(f, &[])
    }

    /// [`Spectrum::mean_w`] with extra break points where f has narrow
    /// features (a spectral line), so the quadrature cannot step over them.
    pub fn mean_w_split<T: QuadValue>(&self, f: impl Fn(f64) -> T, extra: &[f64]) -> T {
        if let Shape::Line { sigma } = self.shape {
            return f(sigma);
        }
        let inv = 1.0 / self.norm;
        self.integrate_raw_split(
            |s, w| {
                if w == 0.0 {
                    T::zero()
                } else {
                    f(s).scale(w * inv)
                }
            },
            extra,
        )
    }

    /// `∫ W²(σ) f(σ) dσ / ∫ W² dσ`: the W²-weighted mean of f. For a line, `f(σ0)`.
    pub fn mean_w2<T: QuadValue>(&self, f: impl Fn(f64) -> T) -> T {
        self.mean_w2_split(f, &[])
    }

    /// [`Spectrum::mean_w2`] with extra break points (see [`Spectrum::mean_w_split`]).
    pub fn mean_w2_split<T: QuadValue>(&self, f: impl Fn(f64) -> T, extra: &[f64]) -> T {
        if let Shape::Line { sigma } = self.shape {
            return f(sigma);
        }
        let inv = 1.0 / (self.norm * self.norm * self.w2_integral);
        self.integrate_raw_split(
            |s, w| {
                if w == 0.0 {
                    T::zero()
                } else {
                    f(s).scale(w * w * inv)
                }
            },
            extra,
        )
    }

    /// The Riemann sums `(Σ_k W(k δσ) δσ, Σ_k W²(k δσ) δσ)` over all integers
    /// k: the normalization sums of the paper's eq. `eq:estimateurs` on the
    /// grid of a scan of length `1/δσ`. `delta_sigma_per_um` must be > 0.
    pub fn grid_sums(&self, delta_sigma_per_um: f64) -> Result<(f64, f64)> {
        error::positive("delta_sigma_per_um", delta_sigma_per_um)?;
        let (lo, hi) = self.support();
        // A scan's bins in the band are fewer than its samples (2^24 at
        // most) unless it is undersampled many times over: refuse a grid
        // of more than 2^30 points before summing it.
        let max_points = (1u64 << 30) as f64;
        if (hi - lo) / delta_sigma_per_um > max_points {
            return Err(Error::OutOfRange {
                param: "delta_sigma_per_um",
                value: delta_sigma_per_um,
                accepted: format!(
                    "a grid of at most {max_points} points over the support ({} µm⁻¹ wide)",
                    hi - lo
                ),
            });
        }
        let k0 = (lo / delta_sigma_per_um).ceil() as i64;
        let k1 = (hi / delta_sigma_per_um).floor() as i64;
        let (mut s1, mut s2) = (0.0, 0.0);
        for k in k0..=k1 {
            let w = self.weight(k as f64 * delta_sigma_per_um);
            s1 += w;
            s2 += w * w;
        }
        Ok((s1 * delta_sigma_per_um, s2 * delta_sigma_per_um))
    }
}

/// The CSV header's two cells: (wavelength axis, weight per unit
/// wavelength): `wavelength_um` or `wavenumber_per_um`, then `weight` or
/// `weight_per_wavenumber` (per unit wavenumber) or `weight_per_um` (per
/// unit wavelength).
fn csv_header(cells: &[&str]) -> std::result::Result<(bool, bool), String> {
    let is_wavelength = match cells[0] {
        "wavelength_um" => true,
        "wavenumber_per_um" => false,
        other => {
            return Err(format!(
                "header '{other}': the first column must be wavelength_um or wavenumber_per_um"
            ))
        }
    };
    let per_wavelength = match cells[1] {
        "weight" | "weight_per_wavenumber" => false,
        "weight_per_um" => true,
        other => {
            return Err(format!(
                "header '{other}': the second column must be weight (per unit wavenumber), weight_per_wavenumber or weight_per_um (per unit wavelength)"
            ))
        }
    };
    Ok((is_wavelength, per_wavelength))
}

/// One CSV data row: the axis value (> 0, above `prev`) and the weight (≥ 0).
fn csv_row(cells: &[&str], prev: Option<f64>) -> std::result::Result<(f64, f64), String> {
    let parse = |s: &str, what: &str| match s.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(format!("{what} '{s}' is not a finite number")),
    };
    let x = parse(cells[0], "axis value")?;
    let w = parse(cells[1], "weight")?;
    if x <= 0.0 {
        return Err(format!("axis value {x} must be > 0"));
    }
    if w < 0.0 {
        return Err(format!("weight {w} must be >= 0"));
    }
    if let Some(prev) = prev.filter(|&p| x <= p) {
        return Err(format!(
            "axis value {x} after {prev}: values must be strictly increasing (no duplicates)"
        ));
    }
    Ok((x, w))
}
