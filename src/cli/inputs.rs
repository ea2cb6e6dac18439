//! The flags of the end-to-end simulator (`simulate`, `synth`, `estimate`):
//! every physical input, gathered into [`v2ref::simulator::Inputs`].

use super::common::{LightArgs, ObservationArgs, ScanArgs, TurbulenceArgs};
use super::finite_f64;
use v2ref::simulator::{Inputs, Model, PistonInputs, SpectrumInput};
use v2ref::Result;

/// The differential piston: on when `--fringe-hz` is given.
#[derive(Debug, Clone, clap::Args)]
pub struct PistonArgs {
    /// Fringe frequency f = v/λ0, Hz: adds the differential piston of §6
    /// (consecutive scans through one piston sequence); none without it.
    #[arg(long, value_parser = finite_f64, allow_negative_numbers = true)]
    pub fringe_hz: Option<f64>,
    #[command(flatten)]
    pub turbulence: TurbulenceArgs,
}

/// Every physical input of one configuration.
#[derive(Debug, Clone, clap::Args)]
pub struct InputsArgs {
    #[command(flatten)]
    pub obs: ObservationArgs,
    #[command(flatten)]
    pub scan: ScanArgs,
    #[command(flatten)]
    pub light: LightArgs,
    #[command(flatten)]
    pub piston: PistonArgs,
}

impl InputsArgs {
    /// The inputs these flags describe, checked.
    pub fn inputs(&self) -> Result<Inputs> {
        let inputs = self.inputs_unchecked()?;
        inputs.validate()?;
        Ok(inputs)
    }

    /// Warns on stderr about the model's piston (see
    /// [`TurbulenceArgs::warn_if_outer_scale_infinite`]).
    pub fn warn_about(&self, model: &Model) {
        if let Some(s) = &model.piston_spectrum {
            self.piston
                .turbulence
                .warn_if_outer_scale_infinite(s.baseline_m(), s.rms_um());
        }
    }

    /// The inputs, before the checks that involve N (a file's width may
    /// still set it).
    pub fn inputs_unchecked(&self) -> Result<Inputs> {
        let obs = self.obs.observation()?;
        let sampling = self.scan.sampling()?;
        let t = &self.piston.turbulence;
        let seeing_arcsec = t.seeing_at_arcsec(self.obs.wavelength_um)?;
        let inputs = Inputs {
            spectrum: SpectrumInput::from_spectrum(
                &obs.spectrum,
                (self.obs.wavelength_um, self.obs.bandwidth_nm),
            ),
            source: self.obs.source_input(),
            baseline_m: obs.baseline_m,
            dispersion_pp_rad: self.obs.dispersion_pp_rad,
            samples: sampling.samples(),
            dx_um: sampling.dx_um(),
            integrating: sampling.integrating(),
            photons: self.light.photons,
            visibility: self.light.visibility,
            read_noise: self.light.read_noise,
            photon_noise: !self.light.no_photon_noise,
            piston: self.piston.fringe_hz.map(|f| PistonInputs {
                fringe_hz: f,
                wavelength_um: self.obs.wavelength_um,
                seeing_arcsec,
                wind_mps: t.wind_mps,
                aperture_m: t.aperture_m,
                outer_scale_m: t.outer_scale_m,
                reference: t.reference,
                sub_samples: t.sub_samples,
            }),
        };
        Ok(inputs)
    }
}
