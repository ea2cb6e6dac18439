//! # v2ref — squared-visibility estimators, reference implementation
//!
//! v2ref implements the two wide-band squared-visibility estimators of
//! G. Perrin & S. T. Ridgway, *Squared visibility estimators: calibrating
//! biases to reach very high dynamic range*: $V_1^2$, the sum of the squared
//! moduli of the Fourier components of the interferogram, and $V_2^2$, the
//! squared modulus of their complex sum. It computes their biases from
//! spectral bandwidth, chromatic dispersion, finite scan length, integrating
//! detectors and differential piston, and their variances and SNR under
//! detector and photon noise, each checked against a closed form, a Monte
//! Carlo and a golden file.
//!
//! ## Quick start
//!
//! ```
//! use v2ref::prelude::*;
//!
//! // A 43 mas uniform disk in the full K band (2.0–2.4 µm), at its first null.
//! let k = Spectrum::flat(Band::new(2.2, 0.4)?);
//! let obs = Observation::new(
//!     k,
//!     Source::uniform_disk(43.0)?,
//!     Frequency::SpatialFreqCpas(28.36),
//!     SpectralPhase::zero(),
//! )?;
//! let wb = wide_band(&obs);
//! assert!(wb.v_mono < 1e-3);            // the monochromatic visibility vanishes…
//! assert!(wb.v1 - wb.v_mono > 0.04);    // …but the wide band fills the null for V1
//! assert!(wb.v2 < wb.v1);               // and much less for V2
//! # Ok::<(), v2ref::Error>(())
//! ```
//!
//! ## A pipeline's `cargo test`: the oracle route
//!
//! A pipeline with its own V1²/V2² estimator holds it to v2ref from its
//! own tests through [`oracle`], in memory (a dev-dependency with no file
//! format and no C compiler): a set of
//! noisy rows and its truth, the closed forms, the score of the pipeline's
//! per-row estimates with the test's power, and the golden vectors
//! regenerated bit for bit.
//!
//! ```
//! use v2ref::oracle::{BiasConvention, BinWindow, Estimates, Set};
//!
//! let set = Set::golden("noise_gaussian")?;       // golden/vectors/noise_gaussian, in memory
//! let (window, bias) = (BinWindow::Positive, BiasConvention::Model);
//! let mine: Vec<f64> = set                       // the pipeline's V1² of each row
//!     .reference_estimates(window, bias)?
//!     .iter()
//!     .map(|r| r.v1_sq)
//!     .collect();
//! let report = set.score(window, bias, Estimates::default().v1_sq(&mine))?;
//! assert!(report.pass, "{report}");
//! # Ok::<(), v2ref::Error>(())
//! ```
//!
//! [`prelude`] gathers the dozen items a user calls first; the folders below
//! follow the paper's table of contents.
//!
//! ## What is public, and what is stable
//!
//! This crate is the stable surface — what a pipeline's `cargo test` and a
//! reader of the paper need, about 150 items: [`prelude`], [`oracle`], the
//! paper's parts ([`formalism`], [`bias`], [`noise`], [`piston`],
//! [`simulator`], [`conformance`]), [`math`], [`montecarlo`], and [`Error`]
//! with [`Result`]. Its listing is committed
//! (`crates/v2ref/public-api/default.txt`) and CI fails when the crate's
//! differs from it; its enums and its error are `#[non_exhaustive]`, so a
//! new variant is not a breaking change. Bad input is a typed [`Error`]
//! naming the parameter and its accepted range, never a silently wrong
//! number. A function's name says what it runs or returns:
//! [`simulator::simulate`] (a set of noisy rows with every effect),
//! [`piston::simulate_piston`] (scans through piston sequences),
//! [`noise::simulation::simulate_noisy`] (noisy scans without piston), and
//! [`bias::finite_scan::finite_scan_bias`] (the finite scan's bias).
//!
//! The items are those of the crate `v2ref-core`, re-exported: the numerics
//! with every helper public for the workspace's own crates (the command
//! line, Python, OIFITS, the reproduction of the paper) and test suite, and
//! not stable. A pipeline needs only this crate.
//!
//! ## Types from other crates
//!
//! The stable surface names few types it does not define, each kept for a
//! reason:
//!
//! - [`montecarlo::Rng`] is v2ref's own type (its generator, PCG-64 MCG,
//!   sits inside it): its methods are inherent, so a pipeline on any rand
//!   release draws from it without rand's traits, and a rand release on
//!   either side changes nothing in the other's build.
//! - `num_complex::Complex64` (the DFT's bins: [`formalism::estimator::dft`],
//!   [`formalism::estimator::raw_estimates`], [`formalism::oracle::naive_dft`],
//!   [`bias::finite_scan::convolution_bins`]; a
//!   [`formalism::interferogram::SpectralNodes`]' amplitudes, an observation's
//!   fringe amplitude, a source's visibility, a finite-scan kernel's value):
//!   kept, as the complex number of Rust's numerics — rustfft's, ndarray's
//!   and nalgebra's, so a pipeline's own FFT output is passed as it is —
//!   and a plain `#[repr(C)]` pair `{ re, im }` on the semver line 0.4
//!   since 2021.
//! - `serde`'s `Serialize` and `Deserialize`, implemented by the reports and
//!   inputs (never a type in a signature): kept, so that a pipeline writes
//!   a report or reads a request in any serde format; serde 1 has been
//!   stable since 2017.
//!
//! No other crate's type or trait is part of the surface (rustdoc also
//! shows the blanket impls that some dependencies' traits give every type;
//! no signature names them): the statistics
//! (statrs), the FFTs (rustfft), the thread pool (rayon) and the random
//! distributions (rand_distr) are used inside only, and may change release
//! without a pipeline noticing.
//!
//! ## The crate, as the paper
//!
//! | paper | module |
//! |---|---|
//! | §1 Introduction (dynamic range) and §2 *General formalism*: spectrum and W(σ), source, the interferometric equation, sampled and integrated signals, the estimators | [`formalism`] |
//! | §3 *Effect of spectral bandwidth* (with the line example and the normalization of V2, Fig. 0), §4 *chromatic dispersion*, §5 *finite scan length*, the integrating detector | [`bias`] |
//! | §6 *Effect of differential piston*: turbulence, piston spectrum and sequences, scans through them | [`piston`] |
//! | Appendix, *Estimator signal-to-noise ratio*: noise moments, closed forms, windowed variance, noisy Monte Carlo | [`noise`] |
//! | all of the above at once: noisy interferograms with every effect, for any instrument | [`simulator`] |
//! | the conformance kit: per-row estimates, the truth of a synth set, the score of a pipeline | [`conformance`] |
//! | the paper's cases, figures, claims, golden files and plots | the crate `v2ref-reproduction` |
//! | special functions and quadrature | [`math`] |
//! | the deterministic parallel Monte Carlo driver, seeds, running statistics | [`montecarlo`] |
//! | errors: each names the parameter and its accepted range | [`Error`] |
//!
//! ## Units and conventions
//!
//! Wavelength λ and OPD x in µm, wavenumber σ in µm⁻¹, angular diameter θ in
//! mas, spatial frequency S in cycles/arcsec ($S = B\sigma_\mathrm{eff}$),
//! baseline B in m, fringe frequency in Hz, phases in rad, counts in photons
//! per sample. Names carry their unit where it is not obvious.
//!
//! The conventions a pipeline must match to agree with v2ref bit for bit —
//! where sample 0 sits, which bins each window sums for even and odd N, how
//! the estimators are normalized, which noise bias is subtracted, the random
//! streams — are written out in the repository's `docs/conventions.md`;
//! every equation of the paper, re-typeset, is in `docs/equations.md`.
//! Where the paper is ambiguous, the choice and its effect are stated in the
//! module docs and in `paper/reproduction.md`.
//!
//! ## Paper → code
//!
//! The paper's labelled equations, written out (W is the normalized weight
//! $S F/\int S F\,d\sigma$, $V_e$ the extended visibility $W V e^{i\phi}/2$
//! on positive σ, $\delta\sigma = 1/\Delta x$):
//!
//! | label | equation | implemented by | tests |
//! |---|---|---|---|
//! | `eq:dynamique` (§1) | $\mathrm{DR} = \sqrt{N_\mathrm{vis}\,/\,\big((\delta V/V)^2 + \delta\phi^2\big)}$ | [`formalism::dynamic_range::dynamic_range`] | `tests/claims.rs` |
//! | `eq:interferogramme` (§2.1) | $I(x) = \int_0^\infty S F\,d\sigma + \int_0^\infty S F\,V \cos\!\big(2\pi\sigma x + \phi(\sigma) + 2\pi\sigma p(x)\big)\,d\sigma$ | [`formalism::interferogram::Interferogram::synthesize`], [`formalism::observation::Observation::fringe_amplitude`] | `tests/foundation.rs` |
//! | `eq:sampled_V` (§2.2.2) | $V_s(k\,\delta\sigma) = \big[V_e \ast \widetilde\Pi(\sigma\Delta x)\big](k\,\delta\sigma),\; k = 0,\dots,N-1$ | [`bias::finite_scan::convolution_bins`] | `tests/bias_finite_scan.rs` |
//! | `eq:estimateurs` (§3) | $V_1^2 = \dfrac{4\sum_k \lvert V_e(k\delta\sigma)\rvert^2\,\delta\sigma}{\sum_k W^2(k\delta\sigma)\,\delta\sigma}$, $\;V_2^2 = \dfrac{4\,\lvert\sum_k V_e(k\delta\sigma)\,\delta\sigma\rvert^2}{\big(\sum_k W(k\delta\sigma)\,\delta\sigma\big)^2}$ | spectral form: [`formalism::estimator::v1_sq`], [`formalism::estimator::v2_sq`]; sampled form: [`formalism::estimator::sampled_wide_band`] | `tests/foundation.rs`, `tests/properties.rs` |
//!
//! And the rest of the paper, in order:
//!
//! | paper | formula | implemented by | tests |
//! |---|---|---|---|
//! | §2.1 weight, effective wavenumber | $W = SF/\int SF$, $\sigma_\mathrm{eff} = \int \sigma W\,d\sigma$ | [`formalism::spectrum::Spectrum`] (`mean_w`, `mean_w2`, `sigma_eff_per_um`), [`math::quadrature`] | `tests/foundation.rs`, `tests/spectrum_csv.rs` |
//! | §2.2.2 sampling, sample 0 on the white-light fringe | $x_i = i\,\delta x$ for $i < \lceil N/2\rceil$, $(i - N)\,\delta x$ beyond (centred scan, DFT order) | [`formalism::interferogram::Sampling`], [`formalism::interferogram::SpectralNodes`] (slow oracle: [`formalism::oracle`]) | `tests/foundation.rs` |
//! | §2.2.2 integrating detector | spectrum filtered by $\mathrm{sinc}(\sigma\delta x)$, $2/\pi$ at Nyquist | [`formalism::interferogram::sinc`], [`bias::integration`] | `tests/foundation.rs`, `tests/bias_normalization.rs` |
//! | §3 uniform disk | $V(S) = 2J_1(\pi\theta S)/(\pi\theta S)$ | [`formalism::source::Source`], [`math::special::jinc`], [`math::special::bessel_j1_zero`] | `tests/special.rs` |
//! | §3 continuum plus line (0.50042) | channel visibility, flux-weighted over one spectral element | [`bias::line::channel_visibility`], [`bias::line::top_hat_closed_form`] | `tests/bias_line.rs` |
//! | §3 Fig. 0, normalization of V2 | $\big(\sum_k W\delta\sigma\big)^2$ against the stroke | [`bias::normalization::deviation_curve`] | `tests/bias_normalization.rs` |
//! | §3 Fig. 1, bandwidth bias | $V_1 - V_\mathrm{mono}$, $V_2 - V_\mathrm{mono}$ against S | [`bias::bandwidth::curve`] | `tests/bias_bandwidth.rs` |
//! | §4 dispersion | $\phi = \tfrac12 D(\sigma-\sigma_0)^2$, peak to peak $P = \tfrac12 D(\Delta\sigma/2)^2$ | [`formalism::phase::SpectralPhase`], [`bias::dispersion`] | `tests/bias_dispersion.rs` |
//! | §4 Fig. 2, point source under dispersion | $V_2^2$ from the Fresnel integrals $C$, $S$ | [`math::special::point_source_v2_sq`] | `tests/bias_dispersion.rs` |
//! | §5 Fig. 3, finite scan | the DFT of the sampled scan and the convolution of `eq:sampled_V` | [`bias::finite_scan::finite_scan_bias`] | `tests/bias_finite_scan.rs` |
//! | §6 turbulence and the differential-piston spectrum | Kolmogorov / von Kármán, $r_0$ from seeing, two-aperture filter | [`piston::turbulence`] | `tests/turbulence.rs` |
//! | §6 piston sequences and scans, Figs. 4–5 | bias and scatter of V1, V2 | [`piston::synthesize_series`], [`piston::simulate_piston`] | `tests/piston.rs`, `tests/piston_claims.rs` |
//! | Appendix, the DFT and the raw estimators | $B_k = \sum_i M_i e^{-2\pi i\,ik/N}$, $V_1^2 = \sum_{K}\lvert B_k\rvert^2$, $V_2^2 = \lvert\sum_{K} B_k\rvert^2$ | [`formalism::estimator::dft`], [`formalism::estimator::raw_estimates`], [`formalism::estimator::BinWindow`] (slow oracle: [`formalism::oracle::naive_dft`]) | `tests/foundation.rs`, `tests/properties.rs` |
//! | Appendix, additive-noise bias | $\lvert K\rvert \sum_i v_i$ and $\sum_i v_i \lvert\sum_K e^{-2\pi i\,ik/N}\rvert^2$ | [`formalism::estimator::noise_bias`] | `tests/noise.rs` |
//! | Appendix, noise moments, var $V_1^2$, var $V_2^2$, SNR (printed and exact) | $\mathrm{SNR} = \langle V^2\rangle/\sqrt{\operatorname{var} V^2}$ | [`noise::moments()`](noise::moments()), [`noise::appendix_stats`], [`noise::worked_example`] | `tests/noise.rs`, `tests/noise_mc.rs` |
//! | Appendix, filtered samples — exact quadratic form | $\operatorname{var}(M^\mathsf{T} A M)$ | [`noise::window_variance::window_stats`] | `tests/noise.rs`, `tests/noise_mc.rs` |
//! | Monte Carlo of noisy scans | | [`noise::simulation::simulate_noisy`], [`montecarlo::run_units`] | `tests/montecarlo_noise.rs`, `tests/cli_noise.rs` |
//! | standard errors of correlated scans (independent piston sequences) | $\mathrm{se}^2(\bar x) = \tfrac{K}{K-1}\sum_j w_j^2 (m_j - \bar m)^2$, $w_j = n_j/N$ | [`montecarlo::replicated_summary`], [`piston::sequence_split`], [`piston::scan_stride`] | `tests/piston_errors.rs` |
//! | the planner's decision | reach the target with the piston terms at the upper ends of their 90 % intervals | `v2ref_commands::plan::plan` | `tests/plan.rs`, `tests/plan_cases.rs` |
//! | all effects at once: rows of one synth set | $I_i \sim \mathrm{Poisson}(c_i + m_i(\text{piston}_s)) + \sigma_\mathrm{det}\,\mathcal N(0,1)$, $M_i = I_i - c_i$ | [`simulator::Model::rows`], [`simulator::simulate`] | `tests/simulator.rs` |
//! | per-row estimates, bias conventions | $(V^2_\mathrm{raw} - b)/C$, $v_i = \sigma_\mathrm{det}^2 + n_i$ with $n_i$ from the model or the row | [`conformance::estimate::RowEstimator`] (slow oracle: [`conformance::estimate::estimate_row_oracle`]) | `tests/simulator.rs`, `tests/conformance_cli.rs` |
//! | the truth of a set and the score of a pipeline | $z = (\bar x - \mu)/\sigma_\mathrm{set}$, $\lvert z\rvert \le \Phi^{-1}(1-\alpha/2m)$ | [`conformance::truth::truth`], [`conformance::score`] | `tests/conformance_score.rs`, `tests/conformance_cli.rs` |
//! | spectral channels (issue 54; in `v2ref-core`, not yet re-exported here) | $W_j = S F\,\mathbf 1[\sigma_j^-\le\sigma\le\sigma_j^+]/\int_j S F\,d\sigma$, photon share $q_j = r_j\int_j SF/\sum_l r_l\int_l SF$ | `v2ref_core::formalism::channels::Channels` | `tests/channels.rs` |
//! | each channel's biases | $V_{1,j}^2 = \int W_j^2\lvert V\rvert^2/\int W_j^2$, $V_{2,j}^2 = \lvert\int W_j V e^{i\phi}\rvert^2$; flat channel: $V_{1,j}^2 - V_\mathrm{mono}^2 \approx (\lvert V\rvert^2)''\,\Delta\sigma_j^2/24$, $V_{2,j}^2 - V_\mathrm{mono}^2 \approx V V''\,\Delta\sigma_j^2/12$ | `v2ref_core::bias::channels::channel_biases`, `v2ref_core::bias::channels::second_order_bandwidth_bias` | `tests/channels.rs` |
//! | each channel's noise; the piston shared by the channels | rows of $q_j c$ photons per sample through one OPD sequence for all channels; $\operatorname{var}\big(\sum_j w_j x_j\big) = w^\mathsf T\Sigma w$, not $\sum_j w_j^2\Sigma_{jj}$ | `v2ref_core::simulator::channels::channel_models`, `v2ref_core::simulator::channels::channel_expectations` (closed forms, SNR = mean/σ), `v2ref_core::simulator::channels::simulate_channels`, `v2ref_core::simulator::channel_moments::ChannelMoments` | `tests/channels_mc.rs` |
//! | a dispersed set in the conformance kit | rows of $C\times N$ values, channel after channel; a truth per channel; one threshold $z_\mathrm{crit} = \Phi^{-1}\big(1-\alpha/(2\sum_j 2E_j)\big)$ over every test of every channel | [`oracle::Set::synthesize_channels`], [`oracle::Set::score_channels`], `v2ref_core::conformance::channel_score::score_channels` | `tests/conformance_channels.rs` |
//! | Figs. 0–5 as data, golden files, claims | | `v2ref_reproduction::figures::all`, `v2ref_reproduction::golden::check`, `v2ref_reproduction::claims::evaluate` | `tests/golden.rs`, `tests/claims.rs` |

#![warn(missing_docs)]
#![forbid(unsafe_code)]

pub use v2ref_core::{Error, Result};

/// The dozen items a user calls first.
pub mod prelude {
    pub use v2ref_core::prelude::*;
}

/// A pipeline's `cargo test`: a set of noisy rows and its truth in memory,
/// the closed forms, the score of the pipeline's per-row estimates with the
/// test's power, the golden vectors regenerated bit for bit.
pub mod oracle {
    pub use v2ref_core::oracle::*;
}

/// §§1–2, the general formalism: the spectrum and its weight, the source,
/// the observation, the spectral phase, the sampled interferogram and the
/// estimators.
pub mod formalism {
    /// §1, the dynamic range a visibility's accuracy allows.
    pub mod dynamic_range {
        pub use v2ref_core::formalism::dynamic_range::dynamic_range;
    }
    /// §3 and the appendix: the estimators V1² and V2², spectral and
    /// sampled, the DFT, the windows of bins and the noise bias.
    pub mod estimator {
        pub use v2ref_core::formalism::estimator::{
            all_bins, band_bins, dft, noise_bias, positive_bins, raw_estimates, sampled_wide_band,
            v1_sq, v2_sq, wide_band, BinWindow, Pair, WideBand, BIN_WINDOWS,
        };
    }
    /// §2.2: the sampled (and integrated) interferogram.
    pub mod interferogram {
        pub use v2ref_core::formalism::interferogram::{
            sinc, Interferogram, Sampling, SpectralNodes,
        };
    }
    /// §2.1: a spectrum, a source and where in the (u, v) plane.
    pub mod observation {
        pub use v2ref_core::formalism::observation::{Frequency, Observation};
    }
    /// The slow, obviously correct DFT beside the fast one.
    pub mod oracle {
        pub use v2ref_core::formalism::oracle::naive_dft;
    }
    /// §4: the spectral phase of dispersion.
    pub mod phase {
        pub use v2ref_core::formalism::phase::SpectralPhase;
    }
    /// §3: the source and its visibility.
    pub mod source {
        pub use v2ref_core::formalism::source::{Component, FluxProfile, Source};
    }
    /// §2.1: the band, a tabulated spectrum, the weight W(σ).
    pub mod spectrum {
        pub use v2ref_core::formalism::spectrum::{Band, Spectrum};
    }
}

/// §§3–5: the biases of spectral bandwidth, dispersion, finite scan length
/// and the integrating detector.
pub mod bias {
    /// §3, Fig. 1: the bandwidth bias against spatial frequency.
    pub mod bandwidth {
        pub use v2ref_core::bias::bandwidth::curve;
    }
    /// §4: chromatic dispersion (the ZBLAN fibre's index).
    pub mod dispersion {
        pub use v2ref_core::bias::dispersion::{
            dispersion_coefficient, residual_peak_to_peak, zblan_index, zblan_peak_to_peak_rad,
            ZBLAN_B1, ZBLAN_B2, ZBLAN_C1_UM, ZBLAN_C2_UM,
        };
    }
    /// §5, Fig. 3: the finite scan's bias.
    pub mod finite_scan {
        pub use v2ref_core::bias::finite_scan::{
            convolution_bins, finite_scan_bias, Bias, Kernel, Method,
        };
    }
    /// §2.2.2: the integrating detector.
    pub mod integration {
        pub use v2ref_core::bias::integration::{
            calibrated, calibrated_bias, monochromatic_contrast, monochromatic_norm_factor,
            wide_band_loss,
        };
    }
    /// §3: a continuum with a spectral line.
    pub mod line {
        pub use v2ref_core::bias::line::{
            channel_visibility, top_hat_closed_form, Channel, ChannelVisibility, LineCase,
            LineProfile,
        };
    }
    /// §3, Fig. 0: the normalization of V2² against the stroke.
    pub mod normalization {
        pub use v2ref_core::bias::normalization::deviation_curve;
    }
}

/// The appendix: the estimators' noise moments, variances and SNR under
/// detector and photon noise, closed forms and Monte Carlo.
pub mod noise {
    pub use v2ref_core::noise::{
        appendix_stats, moments, worked_example, AppendixStats, Cumulants, ExampleSetup, Formula,
        Moments, NoiseModel, WorkedExample,
    };
    /// The exact mean and variance of the normalized, bias-subtracted
    /// estimators.
    pub mod calibrated {
        pub use v2ref_core::noise::calibrated::{
            expectation, CalibratedExpectation, CalibratedSetup, Trials,
        };
    }
    /// The Monte Carlo of noisy scans (no piston).
    pub mod simulation {
        pub use v2ref_core::noise::simulation::{simulate_noisy, NoisyRun, NoisySpec};
    }
    /// Filtered samples: the exact variance of the quadratic form.
    pub mod window_variance {
        pub use v2ref_core::noise::window_variance::{window_stats, WindowStats};
    }
}

/// §6: differential piston — turbulence, its spectrum, sequences and scans.
pub mod piston {
    pub use v2ref_core::piston::{
        scan_stride, sequence_split, simulate_piston, synthesize_series, Detector, PistonReference,
        PistonRun, RunSize, ScanSetup, WindowResult,
    };
    /// The differential-piston spectrum of two apertures.
    pub mod spectrum {
        pub use v2ref_core::piston::spectrum::{PistonPsdModel, PistonSpectrum, TransverseTable};
    }
    /// The three-slope spectrum of earlier simulations, for comparison.
    pub mod three_slope {
        pub use v2ref_core::piston::three_slope::ThreeSlope;
    }
    /// The atmosphere: seeing, r0, wind, outer scale.
    pub mod turbulence {
        pub use v2ref_core::piston::turbulence::Turbulence;
    }
}

/// All effects at once: noisy interferograms of any instrument, row by row.
pub mod simulator {
    pub use v2ref_core::piston::{FringeTables, SharedSequences};
    pub use v2ref_core::record::{SourceInput, SpectrumInput};
    pub use v2ref_core::simulator::{
        simulate, Inputs, Model, PistonEffect, PistonFacts, PistonInputs, RowLayout, RowTiming,
        Rows, SetLayout, SimulationRun,
    };
}

/// The conformance kit: per-row estimates, the truth of a set, the score of
/// a pipeline.
pub mod conformance {
    /// Per-row estimates under a window and a bias convention, and their
    /// slow oracle.
    pub mod estimate {
        pub use v2ref_core::conformance::estimate::{
            estimate_row_oracle, BiasConvention, RowEstimate, RowEstimator, RowFault,
            BIAS_CONVENTIONS,
        };
    }
    /// The score of a pipeline's estimates against a set's truth.
    pub mod score {
        pub use v2ref_core::conformance::score::{
            score, score_report, Estimator, EstimatorScore, NamedScore, ScoreReport,
            VarStderrSource, DEFAULT_ALPHA, POWER,
        };
    }
    /// What a set states of itself: its data, its truth, its members.
    pub mod sidecar {
        pub use v2ref_core::conformance::sidecar::{
            ConventionTruth, DataFiles, EstimatorTruth, ReferenceRun, Sidecar, Truth, TruthSource,
            WindowTruth,
        };
        pub use v2ref_core::manifest::Member;
    }
    /// The truth of a set: the reference run beside the closed forms.
    pub mod truth {
        pub use v2ref_core::conformance::truth::{truth, TruthSize};
    }
    /// The golden vectors' catalogue.
    pub mod vectors {
        pub use v2ref_core::conformance::vectors::{catalogue, Vector};
    }
}

/// Special functions and quadrature.
pub mod math {
    /// Gauss–Legendre and adaptive Gauss–Kronrod quadrature.
    pub mod quadrature {
        pub use v2ref_core::math::quadrature::{gauss_legendre, integrate, Tolerance};
    }
    /// Bessel J1 and its zeros, jinc, the Fresnel integrals' point source.
    pub mod special {
        pub use v2ref_core::math::special::{bessel_j1_zero, jinc, point_source_v2_sq};
    }
}

/// The deterministic parallel Monte Carlo: work units keyed by what they
/// compute, one generator per unit, reduced in unit order; running
/// statistics and standard errors of correlated samples.
pub mod montecarlo {
    pub use v2ref_core::montecarlo::{replicated_summary, run_units, Rng, RunningStats, Summary};
}
