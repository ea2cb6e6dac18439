//! Spectral channels: a dispersed instrument records its scan in C narrow
//! bands at once, each a detector of its own behind the same optical path
//! difference.
//!
//! A [`Channels`] splits a spectrum S(σ)F(σ) into C channels, channel j
//! covering `[σ_j⁻, σ_j⁺]` (µm⁻¹) with a response r_j (the relative
//! throughput of its pixel, any positive scale). What each channel sees is
//! the parent's S F cut to its own interval (the response is flat across a
//! channel, so it scales the channel's photons, never its weight W_j):
//!
//! - `W_j(σ) = S F(σ) 1[σ_j⁻ ≤ σ ≤ σ_j⁺] / ∫_j S F dσ`, the channel's own
//!   spectrum ([`Channels::spectrum`]), from which every wide-band formula
//!   gives the channel's number;
//! - `q_j = r_j ∫_j S F dσ / Σ_l r_l ∫_l S F dσ`, the channel's share of the
//!   source's photons ([`Channels::photon_shares`], Σ q_j = 1).
//!
//! One channel over the whole support is the wide band itself: its spectrum
//! is the parent (the same value, not a copy rebuilt from a table), its
//! share exactly 1, so every per-channel number with C = 1 is today's
//! wide-band number bit for bit.
//!
//! A cut spectrum is exact as a table only where S F is linear between its
//! kinks, so channels split a flat or tabulated spectrum
//! ([`Spectrum::is_piecewise_linear`]); another shape is refused unless
//! it is kept whole (C = 1).

use crate::error::{Error, Result};
use crate::formalism::estimator::band_bins;
use crate::formalism::interferogram::Sampling;
use crate::formalism::spectrum::Spectrum;
use crate::tolerance::BAND_EDGE_REL;

/// Most channels of one instrument: far more than the spectrographs of
/// the field record (a few hundred at most), few enough that a list of
/// per-channel answers stays readable.
pub const MAX_CHANNELS: usize = 4096;

/// A spectrum split into spectral channels (see the module docs).
///
/// # Example
///
/// ```
/// use v2ref_core::formalism::channels::Channels;
/// use v2ref_core::formalism::spectrum::{Band, Spectrum};
/// let h = Spectrum::flat(Band::new(1.65, 0.3)?);
/// let six = Channels::equal(&h, 6)?;
/// assert_eq!(six.count(), 6);
/// // A flat band shares its photons equally between equal channels.
/// assert!(six.photon_shares().iter().all(|q| (q - 1.0 / 6.0).abs() < 1e-12));
/// // Overlapping channels are refused, naming the parameter.
/// let (lo, hi) = h.support();
/// let overlap = Channels::new(&h, vec![(lo, 0.62), (0.61, hi)], vec![1.0, 1.0]);
/// assert_eq!(overlap.unwrap_err().param(), Some("channels"));
/// # Ok::<(), v2ref_core::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Channels {
    parent: Spectrum,
    edges_per_um: Vec<(f64, f64)>,
    responses: Vec<f64>,
    spectra: Vec<Spectrum>,
    shares: Vec<f64>,
}

/// A refusal of the channels, saying what to fix.
fn refuse(reason: String) -> Error {
    Error::Invalid {
        param: "channels",
        reason,
    }
}

impl Channels {
    /// Channel j over `edges_per_um[j] = (σ_j⁻, σ_j⁺)` µm⁻¹ with response
    /// `responses[j]` (finite, > 0), in increasing wavenumber. Refused:
    /// no channel or more than [`MAX_CHANNELS`]; an empty channel (σ⁻ ≥ σ⁺,
    /// or no light of the spectrum in it); channels out of order or
    /// overlapping; a channel outside the spectrum's support (with the band
    /// window's slack [`BAND_EDGE_REL`]); a spectrum that cannot be cut
    /// exactly (see the module docs).
    pub fn new(
        spectrum: &Spectrum,
        edges_per_um: Vec<(f64, f64)>,
        responses: Vec<f64>,
    ) -> Result<Channels> {
        check_layout(spectrum, &edges_per_um, &responses)?;
        let (band_lo, band_hi) = spectrum.support();
        let whole = edges_per_um.len() == 1
            && edges_per_um[0].0 <= band_lo * (1.0 + BAND_EDGE_REL)
            && edges_per_um[0].1 >= band_hi * (1.0 - BAND_EDGE_REL);
        if !whole && !spectrum.is_piecewise_linear() {
            return Err(refuse(
                "only a flat or tabulated spectrum can be split into channels; give this spectrum as a table".into(),
            ));
        }
        let spectra = match whole {
            true => vec![spectrum.clone()],
            false => edges_per_um
                .iter()
                .enumerate()
                .map(|(j, &(lo, hi))| cut(spectrum, j, lo, hi))
                .collect::<Result<Vec<_>>>()?,
        };
        let light: Vec<f64> = edges_per_um
            .iter()
            .zip(&responses)
            .map(|(&(lo, hi), r)| r * fraction_in(spectrum, lo, hi))
            .collect();
        let total: f64 = light.iter().sum();
        Ok(Channels {
            parent: spectrum.clone(),
            shares: light.iter().map(|l| l / total).collect(),
            edges_per_um,
            responses,
            spectra,
        })
    }

    /// The wide band as one channel over the spectrum's whole support.
    pub fn whole(spectrum: &Spectrum) -> Channels {
        let edges = vec![spectrum.support()];
        Channels {
            parent: spectrum.clone(),
            edges_per_um: edges,
            responses: vec![1.0],
            spectra: vec![spectrum.clone()],
            shares: vec![1.0],
        }
    }

    /// `count` channels of equal width in wavenumber over the spectrum's
    /// support, each of response 1 (1 ≤ count ≤ [`MAX_CHANNELS`]).
    pub fn equal(spectrum: &Spectrum, count: usize) -> Result<Channels> {
        check_count(count)?;
        if count == 1 {
            return Ok(Channels::whole(spectrum));
        }
        let (lo, hi) = spectrum.support();
        let edge = |j: usize| match j {
            0 => lo,
            j if j == count => hi,
            j => lo + (hi - lo) * j as f64 / count as f64,
        };
        let edges = (0..count).map(|j| (edge(j), edge(j + 1))).collect();
        Channels::new(spectrum, edges, vec![1.0; count])
    }

    /// Channels of constant spectral resolution `resolution` (R = σ/Δσ of
    /// each channel, at its centre) over the spectrum's support: the
    /// edges are geometric, `σ_j = σ_min (σ_max/σ_min)^{j/C}`, with C the
    /// whole number of channels of resolution nearest R (at least 1; a
    /// resolution below the band's own gives the band as one channel).
    /// `resolution` finite and > 0.
    pub fn from_resolution(spectrum: &Spectrum, resolution: f64) -> Result<Channels> {
        if !resolution.is_finite() || resolution <= 0.0 {
            return Err(Error::OutOfRange {
                param: "resolution",
                value: resolution,
                accepted: "a finite spectral resolution R = λ/Δλ > 0".into(),
            });
        }
        let (lo, hi) = spectrum.support();
        // A channel of ratio ρ = σ⁺/σ⁻ has R = (ρ + 1)/(2(ρ − 1)).
        let per_channel = ((2.0 * resolution + 1.0) / (2.0 * resolution - 1.0)).ln();
        let wanted = match resolution > 0.5 {
            true => ((hi / lo).ln() / per_channel).round(),
            false => 1.0,
        };
        let count = wanted.max(1.0).min(MAX_CHANNELS as f64 + 1.0) as usize;
        check_count(count).map_err(|_| Error::OutOfRange {
            param: "resolution",
            value: resolution,
            accepted: format!("at most {MAX_CHANNELS} channels over the band"),
        })?;
        if count == 1 {
            return Ok(Channels::whole(spectrum));
        }
        let ratio = hi / lo;
        let edge = |j: usize| match j {
            0 => lo,
            j if j == count => hi,
            j => lo * ratio.powf(j as f64 / count as f64),
        };
        let edges = (0..count).map(|j| (edge(j), edge(j + 1))).collect();
        Channels::new(spectrum, edges, vec![1.0; count])
    }

    /// Channels from CSV text: `#` comments and blank lines skipped, the
    /// header `wavenumber_lo_per_um,wavenumber_hi_per_um,response` or
    /// `wavelength_lo_um,wavelength_hi_um,response`, then one row per
    /// channel (its two edges and its response), by increasing axis value.
    /// A wavelength table is converted to wavenumber and reversed. Each
    /// refusal names the line and what to fix; then the checks of
    /// [`Channels::new`].
    pub fn from_csv_str(spectrum: &Spectrum, text: &str) -> Result<Channels> {
        let mut wavelength: Option<bool> = None;
        let (mut edges, mut responses) = (Vec::new(), Vec::new());
        let mut lines = crate::csv_lines::CsvLines::new(text.as_bytes(), u64::MAX);
        while let Some((n, cells)) = lines
            .next_record()
            .map_err(|e| refuse(format!("line {}: cannot be read ({:?})", e.line, e.fault)))?
        {
            let at = |reason: String| refuse(format!("line {n}: {reason}"));
            if cells.len() != 3 {
                return Err(at(format!("{} columns; expected 3", cells.len())));
            }
            if wavelength.is_none() {
                wavelength = Some(csv_header(&cells).map_err(at)?);
                continue;
            }
            if edges.len() == MAX_CHANNELS {
                return Err(at(format!("more than {MAX_CHANNELS} channels")));
            }
            let number = |s: &str| s.parse::<f64>().ok().filter(|v| v.is_finite());
            let parsed: Option<Vec<f64>> = cells.iter().map(|c| number(c)).collect();
            let Some(v) = parsed else {
                return Err(at("every cell must be a finite number".into()));
            };
            if v[0] <= 0.0 || v[1] <= 0.0 {
                return Err(at("the edges must be > 0".into()));
            }
            edges.push((v[0], v[1]));
            responses.push(v[2]);
        }
        let Some(is_wavelength) = wavelength else {
            return Err(refuse(format!(
                "no header: expected '{}' or '{}'",
                CSV_HEADERS[0], CSV_HEADERS[1]
            )));
        };
        if is_wavelength {
            // Increasing wavelength is decreasing wavenumber; a channel
            // whose edges do not increase keeps them crossed, and is refused.
            edges = edges
                .iter()
                .rev()
                .map(|&(a, b)| (1.0 / b, 1.0 / a))
                .collect();
            responses.reverse();
        }
        Channels::new(spectrum, edges, responses)
    }

    /// The spectrum the channels were cut from.
    pub fn parent(&self) -> &Spectrum {
        &self.parent
    }

    /// Refuses `spectrum` unless the channels were cut from it: a
    /// configuration's channels must split that configuration's spectrum.
    pub fn check_parent(&self, spectrum: &Spectrum) -> Result<()> {
        if &self.parent == spectrum {
            return Ok(());
        }
        Err(refuse(
            "the channels were cut from another spectrum than the configuration's; build them from its spectrum".into(),
        ))
    }

    /// Number of channels C.
    pub fn count(&self) -> usize {
        self.edges_per_um.len()
    }

    /// `(σ_j⁻, σ_j⁺)` of each channel, µm⁻¹, in increasing wavenumber.
    pub fn edges_per_um(&self) -> &[(f64, f64)] {
        &self.edges_per_um
    }

    /// r_j of each channel.
    pub fn responses(&self) -> &[f64] {
        &self.responses
    }

    /// Channel j's own spectrum: the parent's S F on its interval.
    ///
    /// # Panics
    ///
    /// When `j ≥ count()`, as indexing does.
    pub fn spectrum(&self, j: usize) -> &Spectrum {
        &self.spectra[j]
    }

    /// The channels' spectra, in channel order.
    pub fn spectra(&self) -> &[Spectrum] {
        &self.spectra
    }

    /// q_j, each channel's share of the source's photons (Σ q_j = 1).
    pub fn photon_shares(&self) -> &[f64] {
        &self.shares
    }

    /// Refuses a scan that cannot resolve every channel: each channel must
    /// hold at least one positive-frequency bin of the scan's DFT (bins
    /// `1/(N δx)` µm⁻¹ apart), or its estimator sums nothing.
    pub fn check_sampling(&self, sampling: &Sampling) -> Result<()> {
        let (n, dx) = (sampling.samples(), sampling.dx_um());
        let bin_per_um = sampling.delta_sigma_per_um();
        let empty = self
            .edges_per_um
            .iter()
            .map(|&(lo, hi)| band_bins(n, dx, lo, hi).map(|bins| bins.is_empty()))
            .collect::<Result<Vec<bool>>>()?
            .into_iter()
            .position(|is_empty| is_empty);
        let Some(j) = empty else { return Ok(()) };
        let (lo, hi) = self.edges_per_um[j];
        let (band_lo, band_hi) = (
            self.edges_per_um[0].0,
            self.edges_per_um[self.count() - 1].1,
        );
        let most = ((band_hi - band_lo) / bin_per_um).floor().max(1.0);
        Err(Error::OutOfRange {
            param: "channels",
            value: self.count() as f64,
            accepted: format!(
                "channels the scan resolves: channel {} ({lo}-{hi} per um) holds no DFT bin of \
                 {bin_per_um} per um (N = {n}, dx = {dx} um); use at most about {most} channels \
                 or a longer scan",
                j + 1
            ),
        })
    }
}

/// The channel CSV's headers: by wavenumber, by wavelength.
pub const CSV_HEADERS: [&str; 2] = [
    "wavenumber_lo_per_um,wavenumber_hi_per_um,response",
    "wavelength_lo_um,wavelength_hi_um,response",
];

/// Whether the header names a wavelength table.
fn csv_header(cells: &[&str]) -> std::result::Result<bool, String> {
    let header = cells.join(",");
    match CSV_HEADERS.iter().position(|h| *h == header) {
        Some(i) => Ok(i == 1),
        None => Err(format!(
            "header '{header}': expected '{}' or '{}'",
            CSV_HEADERS[0], CSV_HEADERS[1]
        )),
    }
}

/// 1 ≤ count ≤ [`MAX_CHANNELS`].
fn check_count(count: usize) -> Result<()> {
    if (1..=MAX_CHANNELS).contains(&count) {
        return Ok(());
    }
    Err(Error::OutOfRange {
        param: "channels",
        value: count as f64,
        accepted: format!("1 to {MAX_CHANNELS} channels"),
    })
}

/// The checks of [`Channels::new`] on the edges and responses.
fn check_layout(spectrum: &Spectrum, edges: &[(f64, f64)], responses: &[f64]) -> Result<()> {
    check_count(edges.len())?;
    if responses.len() != edges.len() {
        return Err(refuse(format!(
            "{} responses for {} channels; give one response per channel",
            responses.len(),
            edges.len()
        )));
    }
    let (band_lo, band_hi) = spectrum.support();
    for (j, (&(lo, hi), &r)) in edges.iter().zip(responses).enumerate() {
        let c = j + 1;
        if !(lo.is_finite() && hi.is_finite() && r.is_finite()) {
            return Err(refuse(format!(
                "channel {c}: edges and response must be finite numbers"
            )));
        }
        if lo >= hi {
            return Err(refuse(format!(
                "channel {c} is empty: its edges {lo} and {hi} per um must increase"
            )));
        }
        if r <= 0.0 {
            return Err(refuse(format!("channel {c}: response {r} must be > 0")));
        }
        if lo < band_lo * (1.0 - BAND_EDGE_REL) || hi > band_hi * (1.0 + BAND_EDGE_REL) {
            return Err(refuse(format!(
                "channel {c} ({lo}-{hi} per um) lies outside the band ({band_lo}-{band_hi} per um)"
            )));
        }
        if let Some(&(next_lo, next_hi)) = edges.get(j + 1) {
            if next_lo < lo || next_hi < hi {
                return Err(refuse(format!(
                    "channels {c} and {} are out of order; list them by increasing wavenumber",
                    c + 1
                )));
            }
            if next_lo < hi {
                return Err(refuse(format!(
                    "channels {c} and {} overlap ({hi} > {next_lo} per um)",
                    c + 1
                )));
            }
        }
    }
    Ok(())
}

/// `∫_lo^hi W dσ`: the fraction of the spectrum's light in [lo, hi].
fn fraction_in(spectrum: &Spectrum, lo: f64, hi: f64) -> f64 {
    let inside = |s: f64| f64::from(u8::from(s >= lo && s <= hi));
    spectrum.mean_w_split(inside, &[lo, hi])
}

/// Channel j's spectrum: S F on [lo, hi] as a table through the
/// spectrum's kinks inside it (exact for a piecewise-linear S F).
fn cut(spectrum: &Spectrum, j: usize, lo: f64, hi: f64) -> Result<Spectrum> {
    let (band_lo, band_hi) = spectrum.support();
    let (lo, hi) = (lo.max(band_lo), hi.min(band_hi));
    let mut sigma = vec![lo];
    sigma.extend(
        spectrum
            .pieces(&[])
            .into_iter()
            .filter(|&s| s > lo && s < hi),
    );
    sigma.push(hi);
    let weight = sigma.iter().map(|&s| spectrum.raw_weight(s)).collect();
    Spectrum::tabulated(sigma, weight).map_err(|e| {
        refuse(format!(
            "channel {} ({lo}-{hi} per um) is empty or unusable: {}",
            j + 1,
            e.detail()
        ))
    })
}
