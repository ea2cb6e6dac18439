//! Source models: complex visibility as a function of wavenumber and
//! baseline (paper, Section "Effect of spectral bandwidth": the uniform
//! disk; the continuum-plus-line example).
//!
//! A simple source's visibility depends on the spatial frequency
//! `S = B σ` only (cycles/arcsec; see [`crate::formalism::spectrum::CPAS_PER_M_PER_INV_UM`]).
//! A composite source is the flux-weighted sum of its components' complex
//! visibilities at each wavenumber:
//! `V(σ) = Σ_j F_j(σ) V_j(σ) / Σ_j F_j(σ)`.

use crate::error::{self, Error, Result};
use crate::formalism::spectrum::CPAS_PER_M_PER_INV_UM;
use crate::math::special::jinc;
use num_complex::Complex64;

/// Milliarcseconds per arcsecond.
const MAS_PER_ARCSEC: f64 = 1000.0;

/// Arcseconds per milliarcsecond (unit conversion; multiply by it).
pub const ARCSEC_PER_MAS: f64 = 1e-3;

/// How a component's flux depends on wavenumber.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum FluxProfile {
    /// The same flux at every wavenumber.
    Flat {
        /// Flux, any unit shared by the components.
        flux: f64,
    },
    /// A Gaussian emission line, flux per unit wavenumber
    /// `peak · exp(−4 ln2 (σ − σ_c)² / fwhm²)`.
    GaussianLine {
        /// Line centre σ_c, µm⁻¹.
        centre_per_um: f64,
        /// Full width at half maximum, µm⁻¹.
        fwhm_per_um: f64,
        /// Peak flux per unit wavenumber, in the unit of the Flat components.
        peak: f64,
    },
}

impl FluxProfile {
    /// Flux at wavenumber `sigma` (µm⁻¹).
    pub fn at(&self, sigma: f64) -> f64 {
        match *self {
            FluxProfile::Flat { flux } => flux,
            FluxProfile::GaussianLine {
                centre_per_um,
                fwhm_per_um,
                peak,
            } => {
                let u = (sigma - centre_per_um) / fwhm_per_um;
                peak * (-4.0 * std::f64::consts::LN_2 * u * u).exp()
            }
        }
    }

    /// A Gaussian line of velocity width `fwhm_km_s` at `wavelength_um`
    /// carrying `flux` in total (integrated over wavenumber):
    /// `fwhm_σ = σ_c v/c`, `peak = flux / (fwhm_σ √(π / 4 ln 2))`.
    pub fn gaussian_line_velocity(wavelength_um: f64, fwhm_km_s: f64, flux: f64) -> Result<Self> {
        error::positive("wavelength_um", wavelength_um)?;
        error::positive("fwhm_km_s", fwhm_km_s)?;
        error::non_negative("flux", flux)?;
        let centre = 1.0 / wavelength_um;
        let fwhm = centre * fwhm_km_s / SPEED_OF_LIGHT_KM_S;
        let area_per_peak = fwhm * (std::f64::consts::PI / (4.0 * std::f64::consts::LN_2)).sqrt();
        if !(flux / area_per_peak).is_finite() || flux > f64::MAX / 4.0 {
            return Err(Error::Invalid {
                param: "flux",
                reason: format!("{flux} over a line {fwhm_km_s} km/s wide: its peak overflows"),
            });
        }
        Ok(FluxProfile::GaussianLine {
            centre_per_um: centre,
            fwhm_per_um: fwhm,
            peak: flux / area_per_peak,
        })
    }
}

/// Speed of light, km/s (exact, SI).
pub const SPEED_OF_LIGHT_KM_S: f64 = 299_792.458;

/// One component of a composite source.
#[derive(Debug, Clone, PartialEq)]
pub struct Component {
    /// Its morphology.
    pub source: Source,
    /// Its flux against wavenumber.
    pub flux: FluxProfile,
}

/// A source's brightness distribution, through its complex visibility.
///
/// # Example
///
/// ```
/// use v2ref_core::prelude::*;
/// use v2ref_core::formalism::estimator::{all_bins, positive_bins};
/// // A 43 mas uniform disk vanishes at its first null, πθS = 3.8317…
/// let disk = Source::uniform_disk(43.0)?;
/// let s_null_cpas = 3.831_705_970_207_512 / (std::f64::consts::PI * 43.0e-3);
/// let sigma = 0.5; // µm⁻¹: B = S/σ in m for S in cycles/arcsec (see CPAS_PER_M_PER_INV_UM)
/// let b = s_null_cpas / (sigma * v2ref_core::formalism::spectrum::CPAS_PER_M_PER_INV_UM);
/// assert!(disk.visibility(sigma, b).norm() < 1e-9);
/// assert_eq!(Source::Point.visibility(sigma, b).norm(), 1.0);
/// # Ok::<(), v2ref_core::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Source {
    /// Unresolved: V = 1 at every spatial frequency.
    Point,
    /// Uniform disk of angular diameter θ (mas):
    /// `V(S) = 2 J1(π θ S)/(π θ S)`, signed.
    UniformDisk {
        /// θ, mas.
        diameter_mas: f64,
    },
    /// A visibility that does not depend on spatial frequency (a model for
    /// a resolved component whose visibility is flat over the band, like
    /// the 50% continuum of the paper's line example).
    Constant {
        /// The complex visibility.
        visibility: Complex64,
    },
    /// Flux-weighted sum of components.
    Composite(Vec<Component>),
}

impl Source {
    /// A uniform disk of diameter `diameter_mas` (> 0, at most
    /// [`crate::bounds::DIAMETER_MAX_MAS`]).
    pub fn uniform_disk(diameter_mas: f64) -> Result<Source> {
        use crate::bounds::{positive_at_most, DIAMETER_MAX_MAS};
        positive_at_most("diameter_mas", diameter_mas, DIAMETER_MAX_MAS)?;
        Ok(Source::UniformDisk { diameter_mas })
    }

    /// A composite source; at least one component, fluxes ≥ 0 and finite,
    /// and no composite nested inside.
    pub fn composite(components: Vec<Component>) -> Result<Source> {
        if components.is_empty() {
            return Err(Error::Invalid {
                param: "components",
                reason: "a composite source needs at least one component".into(),
            });
        }
        for c in &components {
            if let Source::Composite(_) = c.source {
                return Err(Error::Invalid {
                    param: "components",
                    reason: "composite sources cannot be nested".into(),
                });
            }
            if let Source::UniformDisk { diameter_mas } = c.source {
                error::positive("diameter_mas", diameter_mas)?;
            }
            match c.flux {
                FluxProfile::Flat { flux } => {
                    error::non_negative("flux", flux)?;
                }
                FluxProfile::GaussianLine {
                    centre_per_um,
                    fwhm_per_um,
                    peak,
                } => {
                    error::positive("centre_per_um", centre_per_um)?;
                    error::positive("fwhm_per_um", fwhm_per_um)?;
                    error::non_negative("peak", peak)?;
                }
            }
        }
        Ok(Source::Composite(components))
    }

    /// Complex visibility of a single (non-composite) morphology at
    /// spatial frequency `s_cpas` (cycles/arcsec). Composite sources need a
    /// wavenumber for their flux weights: use [`Source::visibility`]; here
    /// they return 0 (nesting is refused by [`Source::composite`]).
    fn morphology_visibility(&self, s_cpas: f64) -> Complex64 {
        match self {
            Source::Point => Complex64::new(1.0, 0.0),
            Source::UniformDisk { diameter_mas } => {
                Complex64::new(uniform_disk_visibility(*diameter_mas, s_cpas), 0.0)
            }
            Source::Constant { visibility } => *visibility,
            Source::Composite(_) => Complex64::new(0.0, 0.0),
        }
    }

    /// Wavenumbers (µm⁻¹) around which the visibility has features narrower
    /// than the band (the lines of a composite source: centre ± 1, 2, 4, 8
    /// FWHM), for the quadrature to split at.
    pub fn features_per_um(&self) -> Vec<f64> {
        let mut out = Vec::new();
        if let Source::Composite(parts) = self {
            for p in parts {
                if let FluxProfile::GaussianLine {
                    centre_per_um,
                    fwhm_per_um,
                    ..
                } = p.flux
                {
                    out.push(centre_per_um);
                    for k in [1.0, 2.0, 4.0, 8.0] {
                        out.push(centre_per_um - k * fwhm_per_um);
                        out.push(centre_per_um + k * fwhm_per_um);
                    }
                }
            }
        }
        out
    }

    /// Complex visibility at wavenumber `sigma_per_um` on a baseline of
    /// `baseline_m` metres: `V(σ) = Σ_j F_j(σ) V_j(B σ) / Σ_j F_j(σ)`.
    pub fn visibility(&self, sigma_per_um: f64, baseline_m: f64) -> Complex64 {
        let s_cpas = baseline_m * sigma_per_um * CPAS_PER_M_PER_INV_UM;
        match self {
            Source::Composite(parts) => {
                let (mut num, mut den) = (Complex64::new(0.0, 0.0), 0.0);
                for p in parts {
                    let f = p.flux.at(sigma_per_um);
                    num += p.source.morphology_visibility(s_cpas) * f;
                    den += f;
                }
                if den > 0.0 {
                    num / den
                } else {
                    Complex64::new(0.0, 0.0)
                }
            }
            simple => simple.morphology_visibility(s_cpas),
        }
    }
}

/// Signed visibility of a uniform disk of diameter `diameter_mas` at spatial
/// frequency `s_cpas`: `2 J1(z)/z` with `z = π θ S` (θ in arcsec, S in
/// cycles/arcsec).
pub fn uniform_disk_visibility(diameter_mas: f64, s_cpas: f64) -> f64 {
    jinc(std::f64::consts::PI * diameter_mas / MAS_PER_ARCSEC * s_cpas)
}
