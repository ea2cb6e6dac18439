//! The observation an OIFITS file describes, from a configuration: the
//! effective wavelength and width of the band, the baseline, the time of
//! each scan.

use crate::formalism::spectrum::Spectrum;
use crate::simulator::Inputs;
use crate::Result;

/// MJD at the start of the rows: 2000-01-01T00:00 UTC (TIME counts from it). The rows are a
/// model's, not a night's: a fixed, recognisable epoch.
pub const MJD0: f64 = 51_544.0;
/// `DATE-OBS` of [`MJD0`].
pub const DATE_OBS: &str = "2000-01-01";
/// Row spacing, s, where the configuration has no scan speed (no piston).
pub const NOMINAL_ROW_S: f64 = 1.0;

/// What an OIFITS file says of the observation.
#[derive(Debug, Clone, PartialEq)]
pub struct Setting {
    /// `TARGET` of `OI_TARGET`.
    pub target: String,
    /// Projected baseline, m: `UCOORD` (east), `VCOORD = 0`, and the
    /// second station's position.
    pub baseline_m: f64,
    /// `EFF_WAVE`, m: `1/σ_eff`, the wavelength of the effective wavenumber
    /// the estimators measure at.
    pub eff_wave_m: f64,
    /// `EFF_BAND`, m: the width in wavelength of the band's support.
    pub eff_band_m: f64,
    /// Duration of one scan, s (`INT_TIME`); None where the configuration
    /// has no scan speed (then `INT_TIME = 0` and rows [`NOMINAL_ROW_S`]
    /// apart).
    pub scan_s: Option<f64>,
}

impl Setting {
    /// The setting of a configuration (`target` names the source).
    pub fn from_inputs(inputs: &Inputs, target: &str) -> Result<Setting> {
        let spectrum = inputs.spectrum.spectrum()?;
        let (eff_wave_m, eff_band_m) = wavelengths(&spectrum);
        // The scan runs N δx of OPD at v = f λ0 (µm/s).
        let scan_s = inputs
            .piston
            .as_ref()
            .map(|p| inputs.samples as f64 * inputs.dx_um / (p.fringe_hz * p.wavelength_um));
        Ok(Setting {
            target: target.to_owned(),
            baseline_m: inputs.baseline_m,
            eff_wave_m,
            eff_band_m,
            scan_s: scan_s.filter(|s| s.is_finite() && *s > 0.0),
        })
    }

    /// Seconds from [`MJD0`] to the middle of row `r` (0-based).
    pub fn time_s(&self, r: usize) -> f64 {
        let step = self.scan_s.unwrap_or(NOMINAL_ROW_S);
        (r as f64 + 0.5) * step
    }
}

/// `EFF_WAVE` and `EFF_BAND` of a spectrum, m.
pub fn wavelengths(spectrum: &Spectrum) -> (f64, f64) {
    let (lo, hi) = spectrum.support();
    let eff = 1e-6 / spectrum.sigma_eff_per_um();
    let band = if lo > 0.0 { 1e-6 / lo - 1e-6 / hi } else { 0.0 };
    (eff, band)
}
