//! The observation an OIFITS file describes, from a configuration: the
//! effective wavelength and width of the band, the baseline, the time of
//! each scan.

use super::observing::{mjd_of_date, ObservingContext, Site};
use crate::formalism::channels::Channels;
use crate::formalism::spectrum::Spectrum;
use crate::simulator::Inputs;
use crate::Result;

/// Row spacing, s, where the configuration has no scan speed (no piston).
pub const NOMINAL_ROW_S: f64 = 1.0;

/// What an OIFITS file says of the observation.
#[derive(Debug, Clone, PartialEq)]
pub struct Setting {
    /// `TARGET` of `OI_TARGET`.
    pub target: String,
    /// The target's right ascension and declination (J2000), degrees.
    pub target_radec_deg: (f64, f64),
    /// `DATE-OBS`: when the first row starts (UTC), `YYYY-MM-DD` (at
    /// 00:00) or `YYYY-MM-DDThh:mm:ss[.s]`.
    pub date_obs: String,
    /// The array's site; its two stations stand on the baseline, east–west.
    pub site: Site,
    /// Telescope diameter, m (`DIAMETER`): the piston's aperture; None
    /// where the configuration has none (no piston: the aperture plays no
    /// part in the set), written as NaN, FITS's undefined value.
    pub diameter_m: Option<f64>,
    /// Projected baseline, m: `UCOORD` (east), `VCOORD = 0`, and the
    /// second station's position.
    pub baseline_m: f64,
    /// `EFF_WAVE`, m: `1/σ_eff`, the wavelength of the effective wavenumber
    /// the estimators measure at.
    pub eff_wave_m: f64,
    /// `EFF_BAND`, m: the width in wavelength of the band's support.
    pub eff_band_m: f64,
    /// `EFF_WAVE` and `EFF_BAND`, m, of each spectral channel, in the
    /// set's channel order (increasing wavenumber, so decreasing
    /// wavelength: column j of `VIS2DATA` is channel j). Empty: one
    /// broadband channel, (`eff_wave_m`, `eff_band_m`).
    pub channels_m: Vec<(f64, f64)>,
    /// Duration of one scan, s (`INT_TIME`); None where the configuration
    /// has no scan speed (then `INT_TIME = 0` and rows `NOMINAL_ROW_S`
    /// apart).
    pub scan_s: Option<f64>,
}

impl Setting {
    /// The setting of a configuration, where and when `observing` says.
    pub fn from_inputs(inputs: &Inputs, observing: &ObservingContext) -> Result<Setting> {
        let spectrum = inputs.spectrum.spectrum()?;
        let (eff_wave_m, eff_band_m) = wavelengths(&spectrum);
        // The scan runs N δx of OPD at v = f λ0 (µm/s).
        let scan_s = inputs
            .piston
            .as_ref()
            .map(|p| inputs.samples as f64 * inputs.dx_um / (p.fringe_hz * p.wavelength_um));
        Ok(Setting {
            target: observing.target_name.clone(),
            target_radec_deg: observing.radec_deg,
            date_obs: observing.date.clone(),
            site: observing.site.clone(),
            diameter_m: inputs.piston.as_ref().map(|p| p.aperture_m),
            baseline_m: inputs.baseline_m,
            eff_wave_m,
            eff_band_m,
            channels_m: Vec::new(),
            scan_s: scan_s.filter(|s| s.is_finite() && *s > 0.0),
        })
    }

    /// This setting read in the spectral channels `channels` (of the
    /// configuration the setting is of): channel j's `EFF_WAVE` is
    /// `1/σ_eff,j` and its `EFF_BAND` the width in wavelength of its
    /// support, `1/σ_j⁻ − 1/σ_j⁺`, both of its own spectrum
    /// ([`Channels::spectrum`]). The whole band's `eff_wave_m` and
    /// `eff_band_m` stay (the field of view is the band's). One channel
    /// over the whole band writes the broadband file, byte for byte.
    pub fn with_channels(mut self, channels: &Channels) -> Setting {
        self.channels_m = channels.spectra().iter().map(wavelengths).collect();
        self
    }

    /// (`EFF_WAVE`, `EFF_BAND`), m, of each channel written: the
    /// channels', else the one broadband channel.
    pub fn wavelengths_m(&self) -> Vec<(f64, f64)> {
        if self.channels_m.is_empty() {
            vec![(self.eff_wave_m, self.eff_band_m)]
        } else {
            self.channels_m.clone()
        }
    }

    /// Seconds between rows, and the integration time of each.
    pub fn row_s(&self) -> f64 {
        self.scan_s.unwrap_or(NOMINAL_ROW_S)
    }

    /// The MJD of the middle of row `r` (0-based): rows follow one
    /// another from [`Setting::date_obs`] (checked when it was given: a
    /// date that is none counts from MJD 0).
    pub fn mjd(&self, r: usize) -> f64 {
        mjd_of_date(&self.date_obs).unwrap_or(0.0) + (r as f64 + 0.5) * self.row_s() / 86_400.0
    }
}

/// `EFF_WAVE` and `EFF_BAND` of a spectrum, m.
pub fn wavelengths(spectrum: &Spectrum) -> (f64, f64) {
    let (lo, hi) = spectrum.support();
    let eff = 1e-6 / spectrum.sigma_eff_per_um();
    let band = if lo > 0.0 { 1e-6 / lo - 1e-6 / hi } else { 0.0 };
    (eff, band)
}
