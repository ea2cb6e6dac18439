//! Instrument presets: the band, apertures, baselines, throughput and
//! detector of interferometers a user would name, as data. `plan
//! --instrument NAME` (Python `plan(instrument=...)`) starts from a preset
//! and any flag given overrides its value.
//!
//! Every value is cited, or stated as an assumption, in
//! `docs/instruments.md`; the test `every_preset_is_inside_the_accepted_ranges`
//! (`tests/plan_presets.rs`) checks each against the parameters' ranges.
//!
//! The plan models a combiner that scans the optical path temporally (one
//! interferogram per scan, [`crate::plan`]). For a combiner that codes the
//! fringe spatially or by ABCD (MIRC-X, GRAVITY, PIONIER in its ABCD mode)
//! the preset supplies the site, band, apertures and detector; the scan's
//! fringe frequency is then the model's choice, bounded by the detector's
//! frame rate ([`Instrument::fringe_hz_max`]).

use crate::error::{Error, Result};
use serde::Serialize;

/// One instrument's preset.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[non_exhaustive]
pub struct Instrument {
    /// The name `--instrument` takes (`facility-instrument`, lower case).
    pub name: &'static str,
    /// What it is, in a few words.
    pub description: &'static str,
    /// Centre wavelength λ0 of its band, µm.
    pub wavelength_um: f64,
    /// Full width of its band, nm.
    pub bandwidth_nm: f64,
    /// Telescope aperture, m.
    pub aperture_m: f64,
    /// The shortest baseline of the array, m.
    pub baseline_min_m: f64,
    /// The longest baseline of the array, m.
    pub baseline_max_m: f64,
    /// The baseline a plan uses unless `--baseline-m` is given, m.
    pub baseline_m: f64,
    /// Fraction of the source's photons counted (atmosphere, optics,
    /// combiner outputs sampled, detector quantum efficiency).
    pub throughput: f64,
    /// Detector frames (samples) per second, Hz.
    pub frame_rate_hz: f64,
    /// Read noise per frame, electrons (photons counted) RMS.
    pub read_noise: f64,
    /// Dead time between scans, s.
    pub dead_time_s: f64,
}

impl Instrument {
    /// The highest fringe frequency its detector samples at
    /// `samples_per_fringe` samples per fringe: frame rate / samples per
    /// fringe, Hz.
    pub fn fringe_hz_max(&self, samples_per_fringe: f64) -> f64 {
        self.frame_rate_hz / samples_per_fringe
    }
}

/// The presets, in the order `--instrument list` prints them. The values
/// and their sources: `docs/instruments.md`.
pub const INSTRUMENTS: [Instrument; 6] = [
    Instrument {
        name: "chara-mirc-x",
        description: "CHARA Array, MIRC-X, H band, six 1 m telescopes",
        wavelength_um: 1.65,
        bandwidth_nm: 300.0,
        aperture_m: 1.0,
        baseline_min_m: 34.0,
        baseline_max_m: 331.0,
        baseline_m: 150.0,
        throughput: 0.02,
        frame_rate_hz: 1000.0,
        read_noise: 0.7,
        dead_time_s: 0.0,
    },
    Instrument {
        name: "chara-fluor",
        description: "CHARA Array, FLUOR (JouFLU), K' band, scanned two-telescope fibre combiner",
        wavelength_um: 2.14,
        bandwidth_nm: 400.0,
        aperture_m: 1.0,
        baseline_min_m: 34.0,
        baseline_max_m: 331.0,
        baseline_m: 200.0,
        throughput: 0.01,
        frame_rate_hz: 2000.0,
        read_noise: 15.0,
        dead_time_s: 0.01,
    },
    Instrument {
        name: "vlti-pionier",
        description: "VLTI, PIONIER, H band broadband, 1.8 m Auxiliary Telescopes",
        wavelength_um: 1.65,
        bandwidth_nm: 300.0,
        aperture_m: 1.8,
        baseline_min_m: 8.0,
        baseline_max_m: 200.0,
        baseline_m: 60.0,
        throughput: 0.01,
        frame_rate_hz: 2000.0,
        read_noise: 1.0,
        dead_time_s: 0.005,
    },
    Instrument {
        name: "vlti-gravity-ft",
        description: "VLTI, GRAVITY fringe tracker (FT), K band, 8.2 m Unit Telescopes",
        wavelength_um: 2.2,
        bandwidth_nm: 500.0,
        aperture_m: 8.2,
        baseline_min_m: 47.0,
        baseline_max_m: 130.0,
        baseline_m: 100.0,
        throughput: 0.01,
        frame_rate_hz: 909.0,
        read_noise: 1.0,
        dead_time_s: 0.0,
    },
    Instrument {
        name: "npoi",
        description: "NPOI, visible (450-850 nm), 12 cm apertures, photon-counting detectors",
        wavelength_um: 0.65,
        bandwidth_nm: 400.0,
        aperture_m: 0.12,
        baseline_min_m: 16.0,
        baseline_max_m: 79.0,
        baseline_m: 40.0,
        throughput: 0.02,
        frame_rate_hz: 4000.0,
        read_noise: 0.0,
        dead_time_s: 0.0,
    },
    Instrument {
        name: "mroi",
        description: "MROI, H band fringe tracking, 1.4 m telescopes (design values)",
        wavelength_um: 1.65,
        bandwidth_nm: 300.0,
        aperture_m: 1.4,
        baseline_min_m: 7.8,
        baseline_max_m: 347.0,
        baseline_m: 100.0,
        throughput: 0.05,
        frame_rate_hz: 1000.0,
        read_noise: 1.0,
        dead_time_s: 0.0,
    },
];

/// The preset named `name` (case-insensitive), refused under the parameter
/// `instrument` with the list of names otherwise.
pub fn instrument(name: &str) -> Result<&'static Instrument> {
    let wanted = name.trim().to_ascii_lowercase();
    INSTRUMENTS
        .iter()
        .find(|i| i.name == wanted)
        .ok_or_else(|| Error::Invalid {
            param: "instrument",
            reason: format!("{name:?} is not one of: {}", names().join(", ")),
        })
}

/// The presets' names.
pub fn names() -> Vec<&'static str> {
    INSTRUMENTS.iter().map(|i| i.name).collect()
}

/// Fringe frequencies of a preset's grid when none is given: 20 from
/// `fringe_hz_max / 20` to `fringe_hz_max`, evenly in log (as many as the
/// default grid, 20 to 2000 Hz, but ending at the detector's edge and
/// denser near it, where bright sources land; slower fringes: `--fringe-hz`).
pub fn fringe_grid_hz(fringe_hz_max: f64) -> Vec<f64> {
    super::log_grid(fringe_hz_max / 20.0, fringe_hz_max, 20)
}

/// The inputs a preset sets, by the name of the parameter that overrides
/// each (the library's and Python's keyword; the CLI's flag with `-`).
pub const PRESET_KEYS: [&str; 9] = [
    "wavelength_um",
    "bandwidth_nm",
    "aperture_m",
    "baseline_m",
    "read_noise",
    "dead_time_s",
    "throughput",
    "fringe_hz",
    "frame_rate_hz",
];

impl Instrument {
    /// Sets in `p` and `req` every value of this preset whose parameter
    /// `given` says the caller did not give ([`PRESET_KEYS`]; a baseline
    /// given as `spatial_freq_cpas` counts as given): the band, aperture,
    /// baseline and read noise; the dead time and the detector's frame rate; the throughput of a
    /// magnitude's photon rate (and its apertures, those of `p`); and,
    /// without a fringe-frequency grid, one whose top is the fastest
    /// fringe the detector in use samples: the frame rate given, else the
    /// preset's ([`Instrument::fringe_hz_max`]).
    pub fn apply(
        &self,
        p: &mut crate::parameters::Physical,
        req: &mut crate::commands::plan::PlanRequest,
        given: &dyn Fn(&str) -> bool,
    ) {
        let set = |key: &str| !given(key);
        if set("wavelength_um") {
            p.wavelength_um = self.wavelength_um;
        }
        if set("bandwidth_nm") {
            p.bandwidth_nm = self.bandwidth_nm;
        }
        if set("aperture_m") {
            p.aperture_m = self.aperture_m;
        }
        if set("baseline_m") && set("spatial_freq_cpas") {
            p.baseline_m = Some(self.baseline_m);
            p.spatial_freq_cpas = None;
        }
        if set("read_noise") {
            p.read_noise = self.read_noise;
        }
        if set("dead_time_s") {
            req.dead_time_s = self.dead_time_s;
        }
        // The detector's edge bounds the grid (given or the preset's).
        if set("frame_rate_hz") {
            req.frame_rate_hz = Some(self.frame_rate_hz);
        }
        if let Some(m) = req.magnitude.as_mut() {
            m.aperture_m = p.aperture_m;
            if set("throughput") {
                m.throughput = self.throughput;
            }
        }
        // The grid's edge is the frame rate in use: the one given, which
        // overrides the preset's (a faster detector searches faster fringes).
        if set("fringe_hz") && req.fringe_hz.is_empty() {
            let frame_rate_hz = req.frame_rate_hz.unwrap_or(self.frame_rate_hz);
            req.fringe_hz = fringe_grid_hz(frame_rate_hz / req.samples_per_fringe);
        }
    }
}
