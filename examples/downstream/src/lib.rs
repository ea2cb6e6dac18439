//! A pipeline's own squared-visibility estimator, written without v2ref
//! (it shares only the conventions of `docs/conventions.md`), with three
//! bugs that can be planted in it ([`Mistake`]) to show that the tests
//! (`tests/route.rs`) catch them through v2ref's oracle route.
//!
//! For a row of N continuum-subtracted samples `M_i`, bins K = 1 … ⌈N/2⌉ − 1,
//! `B_k = Σ_i M_i e^{−2πi ik/N}` and the noise variance `v_i = σ_det² + n_i`
//! of each sample (`n_i` its mean count when there is photon noise):
//! `V1² = (Σ_K |B_k|² − |K| Σ_i v_i)/C1` and
//! `V2² = (|Σ_K B_k|² − Σ_i |u_i|² v_i)/C2`, `u_i = Σ_K e^{−2πi ik/N}`.

use num_complex::Complex64;
use std::f64::consts::PI;

/// A bug the pipeline can be built with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mistake {
    /// None: the estimator as the conventions state it.
    None,
    /// The photon-noise bias forgotten: `v_i = σ_det²` only.
    ForgottenPhotonBias,
    /// A wrong bin set: 0 … N/2, DC and Nyquist included.
    DcAndNyquistBins,
    /// V2²'s noise bias weighted like V1²'s: `|K| Σ_i v_i` for both.
    V2BiasLikeV1,
}

/// What the pipeline knows of its instrument: its own calibration and
/// noise model.
#[derive(Debug, Clone)]
pub struct Instrument {
    /// N, samples per scan.
    pub samples: usize,
    /// σ_det, the detector noise, photons per sample.
    pub read_noise: f64,
    /// Whether the counts carry photon noise.
    pub photon_noise: bool,
    /// n_i, the mean count of each sample, photons.
    pub mean_counts: Vec<f64>,
    /// The calibrator's noise-free modulated samples (a point source of
    /// visibility 1 through the same instrument), photons: the pipeline
    /// normalizes by its raw V1², V2² over its own bins.
    pub calibrator_row: Vec<f64>,
}

/// The pipeline's estimator.
#[derive(Debug, Clone)]
pub struct Pipeline {
    bins: Vec<usize>,
    /// e^{−2πi ik/N} of each bin k (rows) and sample i (columns).
    twiddles: Vec<Vec<Complex64>>,
    bias: (f64, f64),
    calibration: (f64, f64),
}

impl Pipeline {
    /// The estimator of `instrument`, with `mistake` planted.
    pub fn new(instrument: &Instrument, mistake: Mistake) -> Pipeline {
        let n = instrument.samples;
        let bins: Vec<usize> = match mistake {
            Mistake::DcAndNyquistBins => (0..=n / 2).collect(),
            _ => (1..n.div_ceil(2)).collect(),
        };
        let twiddles: Vec<Vec<Complex64>> = bins
            .iter()
            .map(|&k| {
                (0..n)
                    .map(|i| {
                        Complex64::from_polar(1.0, -2.0 * PI * ((i * k) % n) as f64 / n as f64)
                    })
                    .collect()
            })
            .collect();
        let photons = instrument.photon_noise && mistake != Mistake::ForgottenPhotonBias;
        let variance: Vec<f64> = instrument
            .mean_counts
            .iter()
            .map(|&c| instrument.read_noise.powi(2) + if photons { c } else { 0.0 })
            .collect();
        let b1 = bins.len() as f64 * variance.iter().sum::<f64>();
        let b2 = match mistake {
            Mistake::V2BiasLikeV1 => b1,
            _ => (0..n)
                .map(|i| twiddles.iter().map(|t| t[i]).sum::<Complex64>().norm_sqr() * variance[i])
                .sum(),
        };
        let mut pipeline = Pipeline {
            bins,
            twiddles,
            bias: (0.0, 0.0),
            calibration: (1.0, 1.0),
        };
        // The noise-free calibrator row: its raw estimates are the divisors.
        pipeline.calibration = pipeline.estimate(&instrument.calibrator_row);
        pipeline.bias = (b1, b2);
        pipeline
    }

    /// The bins the pipeline sums.
    pub fn bins(&self) -> &[usize] {
        &self.bins
    }

    /// The normalized, bias-subtracted (V1², V2²) of one row.
    pub fn estimate(&self, row: &[f64]) -> (f64, f64) {
        let mut v1_raw = 0.0;
        let mut sum = Complex64::new(0.0, 0.0);
        for t in &self.twiddles {
            let b: Complex64 = row.iter().zip(t).map(|(&m, &w)| w * m).sum();
            v1_raw += b.norm_sqr();
            sum += b;
        }
        (
            (v1_raw - self.bias.0) / self.calibration.0,
            (sum.norm_sqr() - self.bias.1) / self.calibration.1,
        )
    }

    /// (V1², V2²) of every row, as two columns.
    pub fn estimate_rows<'a>(&self, rows: impl Iterator<Item = &'a [f64]>) -> (Vec<f64>, Vec<f64>) {
        rows.map(|r| self.estimate(r)).unzip()
    }
}
