//! A spectral line narrower than the resolution (paper, Section "Effect of
//! spectral bandwidth", the continuum-plus-line example): a resolved
//! continuum of visibility V_c plus an unresolved spot of visibility V_l
//! emitting only in a line, seen in one spectral channel.
//!
//! In the paper's formalism the visibility of a channel of response F(σ) is
//! `∫ W V dσ / ∫ W dσ` with `W ∝ S F` and S the source's total spectrum,
//! continuum plus line, and `V(σ) = (S_c V_c + S_l(σ) V_l)/(S_c + S_l(σ))`
//! (flux-weighted, [`crate::formalism::source`]). The line adds flux as well as
//! visibility, so the channel reads the **flux-weighted** average
//! ([`ChannelVisibility::flux_weighted`]). The paper's printed 0.50042 is
//! instead the **unweighted** linear average of V(σ) across the channel,
//! `∫ F V dσ / ∫ F dσ` ([`ChannelVisibility::unweighted`]), which ignores
//! the line's photons in the normalization. Both are computed here.
//!
//! Top-hat line and top-hat channel, line inside the channel, line width a
//! fraction w of the channel, line-to-continuum flux-density ratio r inside
//! the line: unweighted `V_c + w (V_in − V_c)` with
//! `V_in = (V_c + r V_l)/(1 + r)`; flux-weighted
//! `(V_c + w r V_l)/(1 + w r)`. [`channel_visibility`] integrates the
//! general case numerically (Gaussian line, sinc channel of a Fourier
//! transform spectrometer, line off centre).

use crate::error::{self, Error, Result};
use crate::formalism::source::SPEED_OF_LIGHT_KM_S;
use crate::math::quadrature::{integrate_pieces, Tolerance};

/// The line's spectral profile, normalized to a peak of 1.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum LineProfile {
    /// 1 within ±width/2 of the centre.
    TopHat,
    /// `exp(−4 ln2 (Δσ/width)²)`: width is the FWHM.
    Gaussian,
}

/// The channel's response F(σ), peak 1.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Channel {
    /// 1 over one spectral element δσ = 1/Δx centred on the channel.
    TopHat,
    /// The Fourier-transform spectrometer response `sinc((σ − σ_c) Δx)` (eq. `eq:sampled_V`),
    /// integrated over ±`SINC_HALF_SPAN` elements.
    Sinc,
}

/// Elements on each side of the channel centre the sinc channel is
/// integrated over (its tails beyond fall as 1/(π k) and alternate).
pub const SINC_HALF_SPAN: f64 = 200.0;

/// The example's parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineCase {
    /// Continuum visibility V_c.
    pub continuum_visibility: f64,
    /// Visibility of the line emitter V_l.
    pub line_visibility: f64,
    /// Line flux density over continuum flux density at the line peak, r.
    pub flux_ratio: f64,
    /// Line width (full width, or FWHM for a Gaussian) in spectral elements.
    pub width_elements: f64,
    /// Line centre minus channel centre, in spectral elements.
    pub offset_elements: f64,
    /// Line profile.
    pub profile: LineProfile,
    /// Channel response.
    pub channel: Channel,
}

impl LineCase {
    /// The paper's example: V_c = 0.5, V_l = 1, equal flux densities in
    /// the line (r = 1), a 10 km/s top-hat line at 2 µm observed with a
    /// 100 µm scan (R = σΔx = 50), top-hat channel, line centred.
    pub fn paper() -> LineCase {
        LineCase {
            continuum_visibility: 0.5,
            line_visibility: 1.0,
            flux_ratio: 1.0,
            width_elements: width_in_elements(2.0, 10.0, 100.0),
            offset_elements: 0.0,
            profile: LineProfile::TopHat,
            channel: Channel::TopHat,
        }
    }
}

/// Width of a line of velocity width `km_s` at `wavelength_um`, in spectral
/// elements of a scan of `stroke_um`: `(σ v/c) · Δx`.
pub fn width_in_elements(wavelength_um: f64, km_s: f64, stroke_um: f64) -> f64 {
    km_s / SPEED_OF_LIGHT_KM_S / wavelength_um * stroke_um
}

/// The two averages of V over the channel.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ChannelVisibility {
    /// `∫ F V / ∫ F`: the linear average the paper's number uses.
    pub unweighted: f64,
    /// `∫ F S V / ∫ F S`: what the instrument measures (W includes the line).
    pub flux_weighted: f64,
}

/// The channel visibility of `case` by adaptive quadrature (σ in units of
/// spectral elements from the channel centre).
pub fn channel_visibility(case: &LineCase) -> Result<ChannelVisibility> {
    check_case(case)?;
    let (vc, vl, r, w, c) = (
        case.continuum_visibility,
        case.line_visibility,
        case.flux_ratio,
        case.width_elements,
        case.offset_elements,
    );
    let line = |u: f64| -> f64 {
        let d = (u - c) / w;
        match case.profile {
            LineProfile::TopHat => f64::from(u8::from(d.abs() <= 0.5)),
            LineProfile::Gaussian => (-4.0 * std::f64::consts::LN_2 * d * d).exp(),
        }
    };
    let (lo, hi) = match case.channel {
        Channel::TopHat => (-0.5, 0.5),
        Channel::Sinc => (-SINC_HALF_SPAN, SINC_HALF_SPAN),
    };
    let response = |u: f64| match case.channel {
        Channel::TopHat => 1.0,
        Channel::Sinc => crate::formalism::interferogram::sinc(u),
    };
    // Break points: channel edges, the line's edges and its neighbourhood,
    // and every sinc zero, so that each panel is smooth.
    let mut breaks = vec![lo, hi];
    for k in [-8.0, -4.0, -2.0, -1.0, -0.5, 0.0, 0.5, 1.0, 2.0, 4.0, 8.0] {
        breaks.push(c + k * w);
    }
    if case.channel == Channel::Sinc {
        breaks.extend((-(SINC_HALF_SPAN as i64)..=SINC_HALF_SPAN as i64).map(|k| k as f64));
    }
    breaks.retain(|&b| (lo..=hi).contains(&b));
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();
    let tol = Tolerance {
        abs: crate::tolerance::QUADRATURE_ABS,
        rel: crate::tolerance::QUADRATURE_REL,
    };
    let [f, fv, fs, fsv] = integrate_pieces(
        &|u: f64| {
            let (f, l) = (response(u), r * line(u));
            let v = (vc + l * vl) / (1.0 + l);
            [f, f * v, f * (1.0 + l), f * (vc + l * vl)]
        },
        &breaks,
        tol,
    );
    Ok(ChannelVisibility {
        unweighted: fv / f,
        flux_weighted: fsv / fs,
    })
}

fn check_case(case: &LineCase) -> Result<()> {
    error::in_range("continuum_visibility", case.continuum_visibility, -1.0, 1.0)?;
    error::in_range("line_visibility", case.line_visibility, -1.0, 1.0)?;
    error::non_negative("flux_ratio", case.flux_ratio)?;
    error::positive("width_elements", case.width_elements)?;
    error::finite("offset_elements", case.offset_elements)?;
    Ok(())
}

/// The closed forms for a top-hat line inside a top-hat channel (module
/// docs): `(unweighted, flux_weighted)`. A line wider than the channel
/// (`width_elements` above 1) or reaching past its edge is refused: the
/// forms hold only inside.
pub fn top_hat_closed_form(case: &LineCase) -> Result<ChannelVisibility> {
    check_case(case)?;
    error::in_range("width_elements", case.width_elements, 0.0, 1.0)?;
    let room = 0.5 * (1.0 - case.width_elements);
    error::in_range("offset_elements", case.offset_elements, -room, room)?;
    if case.profile != LineProfile::TopHat || case.channel != Channel::TopHat {
        return Err(Error::Invalid {
            param: "case",
            reason: "the closed forms are for a top-hat line in a top-hat channel".into(),
        });
    }
    let (vc, vl, r, w) = (
        case.continuum_visibility,
        case.line_visibility,
        case.flux_ratio,
        case.width_elements,
    );
    let v_in = (vc + r * vl) / (1.0 + r);
    Ok(ChannelVisibility {
        unweighted: vc + w * (v_in - vc),
        flux_weighted: (vc + w * r * vl) / (1.0 + w * r),
    })
}
