//! The photometric bands a magnitude is given in (their names, zero points,
//! wavelengths and widths) and the magnitudes accepted: what a target
//! list's `band` and `magnitude` cells are read as ([`crate::target_list`]),
//! and what the planner's photometry converts to photons.

use crate::error::{Error, Result};
use serde::Serialize;

/// A photometric band: the 2MASS infrared bands (Cohen, Wheaton & Megeath
/// 2003, AJ 126, 1090, Table 2) and the Johnson–Cousins visible bands
/// (Bessell, Castelli & Plez 1998, A&A 333, 231, Table A2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[non_exhaustive]
pub enum Band2Mass {
    /// J, 1.235 µm.
    J,
    /// H, 1.662 µm.
    H,
    /// Ks, 2.159 µm.
    Ks,
    /// Johnson V, 0.545 µm.
    V,
    /// Cousins R, 0.641 µm.
    R,
    /// Cousins I, 0.798 µm.
    I,
}

impl crate::words::Words for Band2Mass {
    const WORDS: &'static [crate::words::Word<Self>] = &[
        crate::words::Word {
            word: "J",
            value: Band2Mass::J,
            help: "J, 1.235 µm",
        },
        crate::words::Word {
            word: "H",
            value: Band2Mass::H,
            help: "H, 1.662 µm",
        },
        crate::words::Word {
            word: "Ks",
            value: Band2Mass::Ks,
            help: "Ks, 2.159 µm",
        },
        crate::words::Word {
            word: "V",
            value: Band2Mass::V,
            help: "Johnson V, 0.545 µm",
        },
        crate::words::Word {
            word: "R",
            value: Band2Mass::R,
            help: "Cousins R, 0.641 µm",
        },
        crate::words::Word {
            word: "I",
            value: Band2Mass::I,
            help: "Cousins I, 0.798 µm",
        },
    ];
}

/// [`Band2Mass`] under the name that says what it is now.
pub type PhotometricBand = Band2Mass;

impl Band2Mass {
    /// Zero-magnitude flux density F_ν,0, Jy (2MASS: Cohen et al. 2003,
    /// Table 2; V, R, I: Bessell et al. 1998, Table A2).
    pub fn zero_point_jy(self) -> f64 {
        match self {
            Band2Mass::J => 1594.0,
            Band2Mass::H => 1024.0,
            Band2Mass::Ks => 666.7,
            Band2Mass::V => 3640.0,
            Band2Mass::R => 3080.0,
            Band2Mass::I => 2550.0,
        }
    }

    /// Where [`Band2Mass::zero_point_jy`] comes from.
    pub fn zero_point_reference(self) -> &'static str {
        match self {
            Band2Mass::J | Band2Mass::H | Band2Mass::Ks => {
                "Cohen, Wheaton & Megeath (2003), AJ 126, 1090, Table 2"
            }
            Band2Mass::V | Band2Mass::R | Band2Mass::I => {
                "Bessell, Castelli & Plez (1998), A&A 333, 231, Table A2"
            }
        }
    }

    /// Isophotal (2MASS) or effective (V, R, I) wavelength, µm.
    pub fn isophotal_wavelength_um(self) -> f64 {
        match self {
            Band2Mass::J => 1.235,
            Band2Mass::H => 1.662,
            Band2Mass::Ks => 2.159,
            Band2Mass::V => 0.545,
            Band2Mass::R => 0.641,
            Band2Mass::I => 0.798,
        }
    }

    /// Full width at half maximum of the passband, µm (same sources).
    pub fn width_um(self) -> f64 {
        match self {
            Band2Mass::J => 0.162,
            Band2Mass::H => 0.251,
            Band2Mass::Ks => 0.262,
            Band2Mass::V => 0.085,
            Band2Mass::R => 0.15,
            Band2Mass::I => 0.15,
        }
    }

    /// Refuses a magnitude band whose passband (its centre ± one FWHM, a
    /// generous reach) does not hold the observing band's centre `centre_um`:
    /// the source's flux there is not what the magnitude measures.
    pub fn check_covers(self, centre_um: f64) -> Result<()> {
        let (c, w) = (self.isophotal_wavelength_um(), self.width_um());
        if (centre_um - c).abs() > w {
            return Err(Error::Invalid {
                param: "magnitude_band",
                reason: format!(
                    "the {self:?} band ({:.3}-{:.3} um) does not cover the observing band centred on {centre_um} um: give the magnitude in a band that does (J, H, Ks; V, R, I)",
                    c - w,
                    c + w
                ),
            });
        }
        Ok(())
    }
}

/// Brightest and faintest magnitudes accepted: beyond, the rate leaves the
/// range where the planner's photon counts are meaningful.
pub const MAGNITUDE_RANGE: (f64, f64) = (-10.0, 30.0);
