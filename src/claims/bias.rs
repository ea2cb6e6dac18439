//! Claims of the bias studies: bandwidth, dispersion, finite scan,
//! normalization, integration, spectral line, resolution.

use super::{Computed, Effort, Find, Status};
use crate::bandwidth::locate_max;
use crate::dispersion::SpectralPhase;
use crate::estimator::{dft, raw_estimates, v1_sq, v2_sq, wide_band, BinWindow};
use crate::interferogram::{sinc, Interferogram, Sampling};
use crate::observation::{Frequency, Observation};
use crate::source::{FluxProfile, Source};
use crate::spectrum::{Band, Spectrum};

/// The claims this area computes.
pub(super) fn claims(find: &Find<'_>, _effort: Effort) -> Vec<Computed> {
    let mut out = Vec::new();
    let spec = |id: &str| find(id).expect("id in ledger");

    // Integrating detector: the sinc filter and the monochromatic
    // normalization, both measured on synthesized interferograms.
    let nyquist = sinc(0.5);
    out.push(Computed::numeric(
        spec("integration.sinc_min_nyquist"),
        "integration.sinc_min_nyquist",
        nyquist,
        format!("sinc(sigma dx) at sigma dx = 1/2 is 2/pi = {nyquist:.6}"),
    ));
    let norm_4spf = integrating_contrast_loss(4.0);
    out.push(Computed::numeric(
        spec("integration.norm_factor_4spf"),
        "integration.norm_factor_4spf",
        norm_4spf,
        format!(
            "ratio of V1^2 from a sampled and an integrating detector on a monochromatic 2.2 um interferogram, 4 samples per fringe: {norm_4spf:.6} (pi^2/8 = {:.6})",
            std::f64::consts::PI.powi(2) / 8.0
        ),
    ));

    // Resolution and the line example.
    let stroke = Sampling::from_stroke(100.0, 0.5, false).expect("valid sampling");
    let sigma = 1.0 / 2.0;
    let r = sigma * stroke.stroke_um();
    out.push(Computed::numeric(
        spec("resolution.fts_100um_2um"),
        "resolution.fts_100um_2um",
        r,
        format!("R = sigma * stroke = {r} for a 100 um stroke at 2 um"),
    ));
    if let Ok(FluxProfile::GaussianLine { fwhm_per_um, .. }) =
        FluxProfile::gaussian_line_velocity(2.0, 10.0, 1.0)
    {
        let width = fwhm_per_um * stroke.stroke_um();
        out.push(Computed::numeric(
            spec("line.width_in_elements"),
            "line.width_in_elements",
            width,
            format!("10 km/s at 2 um is {fwhm_per_um:.4e} per um; one spectral element is 1/stroke = 0.01 per um: 1/{:.1} of an element (c = 299792.458 km/s; the paper's 1/600 takes c = 3e5)", 1.0 / width),
        ));
    }

    // Bandwidth (Fig. 1): largest |V - V_mono| over 0-80 cycles/arcsec.
    let k_band = Spectrum::flat(Band::k());
    let disk = Source::UniformDisk { diameter_mas: 43.0 };
    let deviation = |which: fn(&crate::estimator::WideBand) -> f64| {
        let k_band = k_band.clone();
        let disk = disk.clone();
        move |s: f64| {
            let obs = Observation::new(
                k_band.clone(),
                disk.clone(),
                Frequency::SpatialFreqCpas(s),
                SpectralPhase::zero(),
            )
            .expect("valid observation");
            let wb = wide_band(&obs);
            (which(&wb) - wb.v_mono).abs()
        }
    };
    let (s1, d1) = locate_max(deviation(|w| w.v1), 0.0, 80.0, 1601);
    out.push(Computed::numeric(
        spec("bandwidth.v1_max_diff_400nm"),
        "bandwidth.v1_max_diff_400nm",
        d1,
        format!("max |V1 - V_mono| = {d1:.5} at S = {s1:.3} cycles/arcsec (first null of the 43 mas disk at sigma_eff: {:.3})", first_null_cpas(43.0)),
    ));
    let (s2, d2) = locate_max(deviation(|w| w.v2), 0.0, 80.0, 1601);
    out.push(Computed::numeric(
        spec("bandwidth.v2_max_diff_400nm"),
        "bandwidth.v2_max_diff_400nm",
        d2,
        format!("max |V2 - V_mono| = {d2:.5} at S = {s2:.3} cycles/arcsec"),
    ));

    // Dispersion: V1 is blind to the spectral phase; V2 of a point source.
    let mut worst_v1 = 0.0_f64;
    for k in 0..=80 {
        let s = k as f64;
        let make = |pp: f64| {
            Observation::new(
                k_band.clone(),
                disk.clone(),
                Frequency::SpatialFreqCpas(s),
                SpectralPhase::dispersion_peak_to_peak(&k_band, pp).expect("finite"),
            )
            .expect("valid observation")
        };
        worst_v1 = worst_v1.max((v1_sq(&make(2.0)) - v1_sq(&make(0.0))).abs());
    }
    out.push(Computed::with_status(
        "dispersion.v1_invariant",
        Some(worst_v1),
        Status::Qualitative,
        format!("max |V1^2(2 rad) - V1^2(0)| over 0-80 cycles/arcsec, 43 mas disk, infinite scan: {worst_v1:.1e}"),
    ));
    for (id, pp) in [
        ("dispersion.v2_point_1rad", 1.0),
        ("dispersion.v2_point_1p5rad", 1.5),
        ("dispersion.v2_point_2rad", 2.0),
    ] {
        let obs = Observation::new(
            k_band.clone(),
            Source::Point,
            Frequency::SpatialFreqCpas(0.0),
            SpectralPhase::dispersion_peak_to_peak(&k_band, pp).expect("finite"),
        )
        .expect("valid observation");
        let v2 = v2_sq(&obs).sqrt();
        out.push(Computed::with_status(
            id,
            Some(v2),
            Status::Qualitative,
            format!("V2 of a point source, 400 nm flat band at 2.2 um, {pp} rad peak-to-peak: {v2:.6} (a bias of {:.4})", 1.0 - v2),
        ));
    }
    out
}

/// The spatial frequency (cycles/arcsec) of the first null of a uniform
/// disk of `diameter_mas`: `S = j_{1,1} / (π θ)`.
fn first_null_cpas(diameter_mas: f64) -> f64 {
    crate::special::bessel_j1_zero(1) / (std::f64::consts::PI * diameter_mas * 1e-3)
}

/// `V1²(sampling detector) / V1²(integrating detector)` for a monochromatic
/// interferogram at `samples_per_fringe`: the contrast-loss normalization.
fn integrating_contrast_loss(samples_per_fringe: f64) -> f64 {
    let wavelength = 2.2;
    let dx = wavelength / samples_per_fringe;
    let obs = Observation::new(
        Spectrum::monochromatic(wavelength).expect("valid"),
        Source::Point,
        Frequency::BaselineM(0.0),
        SpectralPhase::zero(),
    )
    .expect("valid observation");
    let v1 = |integrating: bool| {
        let sampling = Sampling::new(128, dx, integrating).expect("valid sampling");
        let ifg = Interferogram::synthesize(&obs, &sampling, 1.0, None).expect("valid");
        let bins = BinWindow::All.bins(128, dx);
        raw_estimates(&dft(&ifg.modulated), &bins).v1_sq
    };
    v1(false) / v1(true)
}
