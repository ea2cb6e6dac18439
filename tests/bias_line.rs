//! The continuum-plus-line example (paper, Section "Effect of spectral
//! bandwidth"): closed forms, limits, and the crate's composite-source path.

use num_complex::Complex64;
use v2ref_core::bias::line::{
    channel_visibility, top_hat_closed_form, width_in_elements, Channel, LineCase, LineProfile,
};
use v2ref_core::formalism::estimator::v2_sq;
use v2ref_core::formalism::observation::{Frequency, Observation};
use v2ref_core::formalism::phase::SpectralPhase;
use v2ref_core::formalism::source::{Component, FluxProfile, Source};
use v2ref_core::formalism::spectrum::Spectrum;
use v2ref_core::tolerance::{
    EPS, LINEAR_RESPONSE_REL, PRINTED_3_DECIMALS_ABS, PRINTED_5_DECIMALS_ABS, QUADRATURE_CHECK_REL,
    ROUNDING_REL, SINC_TAIL_ABS,
};
use v2ref_core::{assert_abs_eq, assert_rel_eq};

#[test]
fn paper_case_numbers() {
    let case = LineCase::paper();
    assert_abs_eq!(1.0 / case.width_elements, 599.585, PRINTED_3_DECIMALS_ABS);
    let v = channel_visibility(&case).unwrap();
    let c = top_hat_closed_form(&case).unwrap();
    assert!(
        (v.unweighted - c.unweighted).abs() < ROUNDING_REL
            && (v.flux_weighted - c.flux_weighted).abs() < ROUNDING_REL
    );
    // The printed 0.50042 is the unweighted average; the flux-weighted
    // channel is about twice as far from 0.5.
    assert_abs_eq!(v.unweighted, 0.50042, PRINTED_5_DECIMALS_ABS, "{v:?}");
    assert_abs_eq!(v.flux_weighted, 0.50083, PRINTED_5_DECIMALS_ABS, "{v:?}");
}

#[test]
fn limits() {
    let base = LineCase::paper();
    for (case, want) in [
        (
            LineCase {
                flux_ratio: 0.0,
                ..base
            },
            0.5,
        ),
        (
            LineCase {
                line_visibility: 0.5,
                ..base
            },
            0.5,
        ),
    ] {
        let v = channel_visibility(&case).unwrap();
        assert!(
            (v.unweighted - want).abs() < ROUNDING_REL
                && (v.flux_weighted - want).abs() < ROUNDING_REL,
            "{v:?}"
        );
    }
    // A line filling the channel: every sample sees V_in.
    let full = LineCase {
        width_elements: 1.0,
        ..base
    };
    let v = channel_visibility(&full).unwrap();
    assert!(
        (v.unweighted - 0.75).abs() < ROUNDING_REL && (v.flux_weighted - 0.75).abs() < ROUNDING_REL
    );
    // The bias grows linearly with the line width for narrow lines.
    let b = |w: f64| {
        channel_visibility(&LineCase {
            width_elements: w,
            ..base
        })
        .unwrap()
        .flux_weighted
            - 0.5
    };
    assert_rel_eq!(b(2e-3) / b(1e-3), 2.0, LINEAR_RESPONSE_REL);
    assert!(channel_visibility(&LineCase {
        width_elements: -1.0,
        ..base
    })
    .is_err());
    assert_rel_eq!(
        width_in_elements(2.0, 10.0, 100.0),
        base.width_elements,
        EPS
    );
}

#[test]
fn the_sinc_channel_agrees_for_a_centred_line() {
    let case = LineCase {
        channel: Channel::Sinc,
        ..LineCase::paper()
    };
    let v = channel_visibility(&case).unwrap();
    let t = top_hat_closed_form(&LineCase::paper()).unwrap();
    // The sinc's tails beyond ±200 elements carry ~1/(π² 200) of its area.
    assert!(
        (v.unweighted - t.unweighted).abs() < SINC_TAIL_ABS
            && (v.flux_weighted - t.flux_weighted).abs() < SINC_TAIL_ABS,
        "{v:?} vs {t:?}"
    );
}

#[test]
fn the_crate_estimator_with_a_filter_only_spectrum_gives_the_unweighted_average() {
    // W from the channel alone (the line's flux not in W), V(σ) the
    // flux-weighted mix per wavenumber: the estimator path reproduces the
    // unweighted average — the paper's number — which is why W must
    // include the source's own spectrum to give what an instrument reads.
    let fwhm_elements = 0.05;
    let element = 0.01; // µm⁻¹ (100 µm scan)
    let channel = Spectrum::tabulated(
        vec![0.5 - element / 2.0, 0.5 + element / 2.0],
        vec![1.0, 1.0],
    )
    .unwrap();
    let source = Source::composite(vec![
        Component {
            source: Source::Constant {
                visibility: Complex64::new(0.5, 0.0),
            },
            flux: FluxProfile::Flat { flux: 1.0 },
        },
        Component {
            source: Source::Point,
            flux: FluxProfile::GaussianLine {
                centre_per_um: 0.5,
                fwhm_per_um: fwhm_elements * element,
                peak: 1.0,
            },
        },
    ])
    .unwrap();
    let obs = Observation::new(
        channel,
        source,
        Frequency::BaselineM(0.0),
        SpectralPhase::zero(),
    )
    .unwrap();
    let via_estimator = v2_sq(&obs).sqrt();
    let case = LineCase {
        width_elements: fwhm_elements,
        profile: LineProfile::Gaussian,
        ..LineCase::paper()
    };
    let v = channel_visibility(&case).unwrap();
    assert!(
        (via_estimator - v.unweighted).abs() < QUADRATURE_CHECK_REL,
        "{via_estimator} vs {v:?}"
    );
    assert!((via_estimator - v.flux_weighted).abs() > 1e-3);
}
