//! The noise-free, piston-free model of a configuration: the source's and
//! the calibrator's interferograms, from which the rows are drawn and the
//! estimators normalized.

use crate::error::Result;
use crate::formalism::estimator::BinWindow;
use crate::formalism::interferogram::{Interferogram, Sampling};
use crate::formalism::observation::Observation;
use crate::noise::calibrated::CalibratedSetup;
use crate::noise::{scaled_interferogram, NoiseModel};
use crate::piston::fringe_table::{FringeTable, FringeTables};
use crate::piston::sequences::SharedSequences;
use crate::piston::spectrum::PistonSpectrum;
use crate::simulator::inputs::Inputs;
use std::sync::Arc;

/// A configuration built from its [`Inputs`].
#[derive(Debug, Clone)]
pub struct Model {
    /// The inputs it was built from.
    pub inputs: Inputs,
    /// The observation.
    pub observation: Observation,
    /// The sampling.
    pub sampling: Sampling,
    /// The noise.
    pub noise: NoiseModel,
    /// The source: c_i and the modulated m_i scaled by the visibility,
    /// photons, without piston.
    pub signal: Interferogram,
    /// The calibrator: an unresolved, phase-free source with the same
    /// photons (V = 1).
    pub calibrator: Interferogram,
    /// The differential-piston spectrum on the baseline, with piston.
    pub piston_spectrum: Option<PistonSpectrum>,
    /// Fringe tables shared with other models ([`Model::sharing_fringe_tables`]);
    /// none: each set builds the exact table its piston needs.
    fringe_tables: Option<FringeTables>,
    /// Piston sequences shared with other models
    /// ([`Model::sharing_piston_sequences`]); none: each set draws its own.
    piston_sequences: Option<SharedSequences>,
}

impl Model {
    /// Checks `inputs` and builds the model.
    ///
    /// # Example
    ///
    /// ```
    /// use v2ref_core::simulator::{Inputs, Model};
    /// let model = Model::new(&Inputs::default())?;
    /// // The calibrator's fringe peaks at zero OPD with m_0 = c.
    /// assert!((model.calibrator.modulated[0] - 10.0).abs() < 1e-9);
    /// # Ok::<(), v2ref_core::Error>(())
    /// ```
    pub fn new(inputs: &Inputs) -> Result<Model> {
        Self::build(inputs, None, None)
    }

    /// [`Model::new`] with the differential-piston spectrum given (it is
    /// the costly part of a model with piston, and depends only on the
    /// atmosphere, the apertures and the baseline: a caller that builds
    /// many models under one sky builds it once). It must be the spectrum of
    /// `inputs.piston` on `inputs.baseline_m`.
    pub fn with_piston_spectrum(inputs: &Inputs, spectrum: PistonSpectrum) -> Result<Model> {
        Self::build(inputs, Some(spectrum), None)
    }

    /// [`Model::with_piston_spectrum`] for `inputs` that differ from this
    /// model's in their noise and piston only: the interferograms (the
    /// costly part after the piston spectrum: a planner builds each
    /// setting's noise model and piston model from one) are this model's
    /// when `inputs` has the same observation, sampling, photons and
    /// visibility, and built anew otherwise; the same model either way.
    pub fn sibling_with_piston_spectrum(
        &self,
        inputs: &Inputs,
        spectrum: PistonSpectrum,
    ) -> Result<Model> {
        Self::build(inputs, Some(spectrum), Some(self))
    }

    /// This model, its sets reading their piston's fringe table from
    /// `tables` (shared with the other models given them: a planner's
    /// settings under one sky), a table of a slightly wider range than the
    /// exact one the set would build alone ([`FringeTables`]: the same
    /// numbers within the table's interpolation error, far less time for
    /// many settings).
    pub fn sharing_fringe_tables(mut self, tables: &FringeTables) -> Model {
        self.fringe_tables = Some(tables.clone());
        self
    }

    /// This model, its sets reading their piston sequences from `shared`
    /// when another model given it drew the same ones (same spectrum,
    /// seed, length and step: [`SharedSequences`]): the same bits as drawn
    /// alone, drawn once.
    pub fn sharing_piston_sequences(mut self, shared: &SharedSequences) -> Model {
        self.piston_sequences = Some(shared.clone());
        self
    }

    /// The shared piston sequences, if any.
    pub(crate) fn shared_sequences(&self) -> Option<&SharedSequences> {
        self.piston_sequences.as_ref()
    }

    /// The fringe table of a set whose piston needs |x| ≤ `max_opd_um`.
    pub(crate) fn fringe_table(&self, max_opd_um: f64) -> Result<Arc<FringeTable>> {
        match &self.fringe_tables {
            Some(tables) => tables.get(&self.observation, max_opd_um),
            None => Ok(Arc::new(FringeTable::new(&self.observation, max_opd_um)?)),
        }
    }

    fn build(
        inputs: &Inputs,
        given: Option<PistonSpectrum>,
        like: Option<&Model>,
    ) -> Result<Model> {
        inputs.validate()?;
        let observation = inputs.observation()?;
        let sampling = inputs.sampling()?;
        let same_signal = like.filter(|m| {
            m.observation == observation
                && m.sampling == sampling
                && m.inputs.photons == inputs.photons
                && m.inputs.visibility == inputs.visibility
        });
        let (signal, calibrator) = match same_signal {
            Some(m) => (m.signal.clone(), m.calibrator.clone()),
            None => (
                scaled_interferogram(&observation, &sampling, inputs.photons, inputs.visibility)?,
                scaled_interferogram(&observation.calibrator(), &sampling, inputs.photons, 1.0)?,
            ),
        };
        let piston_spectrum = match (&inputs.piston, given) {
            (Some(_), Some(s)) => Some(s),
            (Some(p), None) => Some(p.spectrum(observation.baseline_m)?),
            (None, _) => None,
        };
        Ok(Model {
            piston_spectrum,
            fringe_tables: None,
            piston_sequences: None,
            inputs: inputs.clone(),
            noise: inputs.noise()?,
            observation,
            sampling,
            signal,
            calibrator,
        })
    }

    /// N.
    pub fn samples(&self) -> usize {
        self.sampling.samples()
    }

    /// The bins of `window`.
    pub fn bins(&self, window: BinWindow) -> Vec<usize> {
        window.bins_within_bound(
            self.sampling.samples(),
            self.sampling.dx_um(),
            &self.observation.spectrum,
        )
    }

    /// The source, its calibrator and the bins of `window`, for the closed
    /// forms of [`crate::noise::calibrated`].
    pub fn calibrated_setup(&self, window: BinWindow) -> CalibratedSetup {
        CalibratedSetup {
            signal: self.signal.clone(),
            calibrator: self.calibrator.clone(),
            bins: self.bins(window),
        }
    }

    /// The model of the calibrator as a source of its own (for a
    /// calibrator's interferograms): same instrument, point source, V = 1.
    pub fn calibrator_model(&self) -> Result<Model> {
        let inputs = Inputs {
            source: crate::simulator::inputs::SourceInput::Point,
            dispersion_pp_rad: 0.0,
            visibility: 1.0,
            ..self.inputs.clone()
        };
        Model::new(&inputs)
    }

    /// x_i of each column at zero piston, µm.
    pub fn sample_opd_um(&self) -> Vec<f64> {
        (0..self.samples())
            .map(|i| self.sampling.opd_um(i))
            .collect()
    }

    /// The noise variance of each sample of the source without piston:
    /// `σ_det² + n_i` with photon noise, `σ_det²` without.
    pub fn sample_variance(&self) -> Vec<f64> {
        let read = self.noise.read_noise * self.noise.read_noise;
        self.signal
            .mean_counts()
            .iter()
            .map(|&n| read + if self.noise.photon { n } else { 0.0 })
            .collect()
    }
}
