//! Issue 54, spectral channels in the library: the channels' refusals, the
//! wide band as one channel (bit for bit), the photons shared by the
//! channels, and the per-channel bandwidth bias against its scaling law.

use v2ref_core::bias::channels::{channel_biases, second_order_bandwidth_bias};
use v2ref_core::bias::finite_scan::{finite_scan_bias, Method};
use v2ref_core::bias::integration::calibrated_bias;
use v2ref_core::formalism::channels::Channels;
use v2ref_core::formalism::estimator::wide_band;
use v2ref_core::formalism::interferogram::Sampling;
use v2ref_core::formalism::observation::{Frequency, Observation};
use v2ref_core::formalism::phase::SpectralPhase;
use v2ref_core::formalism::source::Source;
use v2ref_core::formalism::spectrum::{Band, Spectrum};
use v2ref_core::simulator::channels::channel_models;
use v2ref_core::simulator::{Inputs, Model};
use v2ref_core::tolerance::{
    CHANNEL_FRINGE_SUM_REL, CHANNEL_SECOND_ORDER_REL, EPS, QUADRATURE_CHECK_REL,
};
use v2ref_core::{assert_abs_eq, assert_rel_eq};

fn k_flat() -> Spectrum {
    Spectrum::flat(Band::k())
}

/// The parameter and the message of a refusal.
fn refusal(result: v2ref_core::Result<Channels>) -> (String, String) {
    let e = result.expect_err("refused");
    (e.param().unwrap_or("").to_string(), e.to_string())
}

#[test]
fn bad_channels_are_refused_naming_what_to_fix() {
    let k = k_flat();
    let (lo, hi) = k.support();
    let mid = 0.5 * (lo + hi);
    let cases: Vec<(Vec<(f64, f64)>, &str)> = vec![
        (vec![(lo, mid + 0.01), (mid, hi)], "overlap"),
        (vec![(lo, mid), (mid, mid)], "is empty"),
        (vec![(mid, hi), (lo, mid)], "out of order"),
        (vec![(lo - 0.05, mid), (mid, hi)], "outside the band"),
        (vec![(lo, mid), (mid, hi + 0.05)], "outside the band"),
    ];
    for (edges, words) in cases {
        let (param, message) = refusal(Channels::new(&k, edges, vec![1.0, 1.0]));
        assert_eq!(param, "channels");
        assert!(message.contains(words), "{message}");
    }
    let (_, message) = refusal(Channels::new(&k, vec![(lo, hi)], vec![1.0, 1.0]));
    assert!(message.contains("one response per channel"), "{message}");
    let (_, message) = refusal(Channels::new(&k, vec![(lo, hi)], vec![0.0]));
    assert!(message.contains("must be > 0"), "{message}");
    assert_eq!(refusal(Channels::equal(&k, 0)).0, "channels");
    assert_eq!(refusal(Channels::from_resolution(&k, -3.0)).0, "resolution");
    assert_eq!(
        refusal(Channels::from_resolution(&k, f64::NAN)).0,
        "resolution"
    );
    // A power law cannot be cut exactly into tables.
    let slope = Spectrum::power_law(Band::k(), 2.0).unwrap();
    let (_, message) = refusal(Channels::equal(&slope, 3));
    assert!(message.contains("flat or tabulated"), "{message}");
    // A spectrum with no light in a channel.
    let table = Spectrum::tabulated(vec![0.4, 0.45, 0.5], vec![1.0, 0.0, 0.0]).unwrap();
    let (_, message) = refusal(Channels::new(
        &table,
        vec![(0.4, 0.45), (0.45, 0.5)],
        vec![1.0; 2],
    ));
    assert!(
        message.contains("channel 2") && message.contains("empty"),
        "{message}"
    );
    // Channels of one spectrum cannot split another configuration's.
    let h = Channels::equal(&Spectrum::flat(Band::new(1.65, 0.3).unwrap()), 2).unwrap();
    let e = channel_models(&Inputs::default(), &h).unwrap_err();
    assert_eq!(e.param(), Some("channels"));
    assert!(e.to_string().contains("another spectrum"), "{e}");
    let no_models = v2ref_core::simulator::channels::simulate_channels(
        &[],
        v2ref_core::formalism::estimator::BinWindow::Band,
        v2ref_core::conformance::estimate::BiasConvention::Model,
        v2ref_core::noise::calibrated::Trials {
            trials: 10,
            seed: 1,
            threads: 1,
        },
    );
    assert_eq!(no_models.unwrap_err().param(), Some("models"));
}

#[test]
fn channels_a_scan_cannot_resolve_are_refused() {
    let k = k_flat();
    // N δx = 32 µm: bins 1/32 µm⁻¹ apart, 2.67 of them across K.
    let sampling = Sampling::new(64, 0.5, false).unwrap();
    Channels::equal(&k, 2)
        .unwrap()
        .check_sampling(&sampling)
        .unwrap();
    let e = Channels::equal(&k, 8)
        .unwrap()
        .check_sampling(&sampling)
        .unwrap_err();
    assert_eq!(e.param(), Some("channels"));
    assert!(e.to_string().contains("holds no DFT bin"), "{e}");
}

#[test]
fn channel_csv_reads_wavenumbers_and_wavelengths_and_refuses_bad_tables() {
    let k = k_flat();
    let by_wavelength =
        "# two channels\nwavelength_lo_um,wavelength_hi_um,response\n2.0,2.2,1\n2.2,2.4,0.5\n";
    let c = Channels::from_csv_str(&k, by_wavelength).unwrap();
    assert_eq!(c.count(), 2);
    // Increasing wavenumber: the 2.2–2.4 µm channel first, its response with it.
    assert_eq!(c.responses(), &[0.5, 1.0]);
    assert_rel_eq!(c.edges_per_um()[0].1, 1.0 / 2.2, EPS);
    let by_wavenumber =
        "wavenumber_lo_per_um,wavenumber_hi_per_um,response\n0.42,0.45,1\n0.45,0.5,1\n";
    assert_eq!(
        Channels::from_csv_str(&k, by_wavenumber).unwrap().count(),
        2
    );
    for (text, words) in [
        (
            "wavelength_um,weight\n2.0,1\n",
            "line 1: 2 columns; expected 3",
        ),
        ("lo,hi,response\n", "header 'lo,hi,response'"),
        (
            "wavelength_lo_um,wavelength_hi_um,response\n2.0,x,1\n",
            "line 2",
        ),
        ("", "no header"),
        (
            "wavelength_lo_um,wavelength_hi_um,response\n2.0,2.3,1\n2.2,2.4,1\n",
            "overlap",
        ),
    ] {
        let e = Channels::from_csv_str(&k, text).unwrap_err();
        assert_eq!(e.param(), Some("channels"));
        assert!(e.to_string().contains(words), "{text:?}: {e}");
    }
}

fn disk_obs(spectrum: Spectrum, pp_rad: f64) -> Observation {
    let phase = SpectralPhase::dispersion_peak_to_peak(&spectrum, pp_rad).unwrap();
    Observation::new(
        spectrum,
        Source::uniform_disk(43.0).unwrap(),
        Frequency::SpatialFreqCpas(40.0),
        phase,
    )
    .unwrap()
}

/// C = 1 is the wide band: the same numbers, compared bit for bit.
#[test]
fn one_channel_is_the_wide_band_bit_for_bit() {
    let obs = disk_obs(k_flat(), 1.5);
    let sampling = Sampling::new(128, 0.5, true).unwrap();
    for one in [
        Channels::equal(&obs.spectrum, 1).unwrap(),
        Channels::from_resolution(&obs.spectrum, 2.0).unwrap(),
        Channels::new(&obs.spectrum, vec![obs.spectrum.support()], vec![0.3]).unwrap(),
    ] {
        assert_eq!(one.photon_shares(), &[1.0]);
        let b = channel_biases(&obs, &one, &sampling).unwrap();
        assert_eq!(b[0].wide_band, wide_band(&obs));
        let fin = finite_scan_bias(&obs, &sampling, Method::Dft, None).unwrap();
        assert_eq!(b[0].finite_scan, fin);
        assert_eq!(b[0].integrating, calibrated_bias(&obs, 0.5).unwrap());
        let models = channel_models(&Inputs::default(), &one).unwrap();
        let alone = Model::new(&Inputs::default()).unwrap();
        assert_eq!(models[0].signal, alone.signal);
        assert_eq!(models[0].observation, alone.observation);
    }
}

/// The photons are shared in proportion to the spectrum times the
/// response, and the channels' interferograms add up to the wide band's.
#[test]
fn channels_share_the_photons_and_add_up_to_the_wide_band() {
    // S F rising linearly from 1 to 3 across K: ∫ over [a, b] is exact.
    let (lo, hi) = k_flat().support();
    let line = |s: f64| 1.0 + 2.0 * (s - lo) / (hi - lo);
    let spectrum = Spectrum::tabulated(vec![lo, hi], vec![1.0, 3.0]).unwrap();
    let c = Channels::new(
        &spectrum,
        vec![(lo, 0.44), (0.44, 0.47), (0.47, hi)],
        vec![1.0, 0.5, 2.0],
    )
    .unwrap();
    let light: Vec<f64> = c
        .edges_per_um()
        .iter()
        .zip(c.responses())
        .map(|(&(a, b), r)| r * 0.5 * (line(a) + line(b)) * (b - a))
        .collect();
    let total: f64 = light.iter().sum();
    for (q, l) in c.photon_shares().iter().zip(&light) {
        // tol: shares integrated by the spectrum's quadrature against the trapezoid, exact for a line.
        assert_rel_eq!(*q, l / total, QUADRATURE_CHECK_REL);
    }
    // tol: a sum of C shares each rounded once: a few units of EPS.
    assert_abs_eq!(c.photon_shares().iter().sum::<f64>(), 1.0, 4.0 * EPS);

    // Equal responses: Σ_j q_j W_j = W, so the channels' fringes add up to the band's.
    let inputs = Inputs {
        spectrum: v2ref_core::simulator::SpectrumInput::Table {
            wavenumber_per_um: vec![lo, hi],
            weight: vec![1.0, 3.0],
        },
        samples: 64,
        ..Inputs::default()
    };
    let tiled = Channels::equal(&spectrum, 2).unwrap();
    let models = channel_models(&inputs, &tiled).unwrap();
    let band = Model::new(&inputs).unwrap();
    let photons: f64 = models.iter().map(|m| m.signal.continuum[0]).sum();
    // tol: the channels' photons add the band's integral in C pieces: a few roundings.
    assert_rel_eq!(photons, band.signal.continuum[0], 4.0 * EPS);
    for i in 0..64 {
        let sum: f64 = models.iter().map(|m| m.signal.modulated[i]).sum();
        // tol: each fringe integrated on its own nodes; agreement to the nodes' accuracy, absolute in photons.
        assert_abs_eq!(
            sum,
            band.signal.modulated[i],
            CHANNEL_FRINGE_SUM_REL * band.signal.continuum[0]
        );
    }
}

/// A channel's bandwidth bias falls as Δσ², with the second-order
/// coefficients g''/24 (V1²) and V V''/12 (V2²) of the flat channel.
#[test]
fn bandwidth_bias_per_channel_falls_as_the_square_of_its_width() {
    let obs = disk_obs(k_flat(), 0.0);
    let v = |s: f64| obs.source.visibility(s, obs.baseline_m).re;
    let centre = 0.46;
    let mut previous: Option<(f64, f64)> = None;
    for width in [0.064, 0.032, 0.016, 0.008] {
        let (lo, hi) = (centre - 0.5 * width, centre + 0.5 * width);
        let c = Channels::new(&obs.spectrum, vec![(lo, hi)], vec![1.0]).unwrap();
        let sampling = Sampling::new(4096, 0.5, false).unwrap();
        let b = channel_biases(&obs, &c, &sampling).unwrap()[0];
        let mono2 = b.wide_band.v_mono.powi(2);
        let (d1, d2) = (b.wide_band.v1_sq - mono2, b.wide_band.v2_sq - mono2);
        let (p1, p2) = second_order_bandwidth_bias(v, lo, hi);
        // tol: the neglected fourth-order term is (Δσ/λ-scale)² of the second: below 3 % at Δσ = 0.064 µm⁻¹.
        assert_rel_eq!(d1, p1, CHANNEL_SECOND_ORDER_REL);
        assert_rel_eq!(d2, p2, CHANNEL_SECOND_ORDER_REL);
        if let Some((q1, q2)) = previous {
            // Halving the width divides the bias by 4 (to the same fourth-order term).
            assert_rel_eq!(q1 / d1, 4.0, CHANNEL_SECOND_ORDER_REL);
            assert_rel_eq!(q2 / d2, 4.0, CHANNEL_SECOND_ORDER_REL);
        }
        previous = Some((d1, d2));
    }
}
