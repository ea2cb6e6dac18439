//! `--instrument NAME` of `plan`: start from an instrument's preset
//! (`v2ref_commands::plan::instrument`), every flag given on the command line
//! overriding its value; `--instrument list` prints the presets.

use std::collections::BTreeSet;
use v2ref_commands::commands::plan::PlanRequest;
use v2ref_commands::parameters::Physical;
use v2ref_commands::plan::instrument::{instrument, Instrument, INSTRUMENTS};
use v2ref_core::{Error, Result};

/// The flag, and which flags the command line gave (they override the
/// preset; a default does not).
#[derive(Debug, Clone, Default)]
pub struct InstrumentArgs {
    name: Option<String>,
    given: BTreeSet<String>,
}

/// The flag's id.
const ID: &str = "instrument";

impl clap::FromArgMatches for InstrumentArgs {
    fn from_arg_matches(m: &clap::ArgMatches) -> std::result::Result<Self, clap::Error> {
        let given = m
            .ids()
            .filter(|id| {
                m.value_source(id.as_str()) == Some(clap::parser::ValueSource::CommandLine)
            })
            .map(|id| id.as_str().to_owned())
            .collect();
        Ok(InstrumentArgs {
            name: m.get_one::<String>(ID).cloned(),
            given,
        })
    }
    fn update_from_arg_matches(
        &mut self,
        m: &clap::ArgMatches,
    ) -> std::result::Result<(), clap::Error> {
        *self = Self::from_arg_matches(m)?;
        Ok(())
    }
}

impl clap::Args for InstrumentArgs {
    fn augment_args(cmd: clap::Command) -> clap::Command {
        let names = v2ref_commands::plan::instrument::names().join(", ");
        cmd.arg(
            clap::Arg::new(ID)
                .long("instrument")
                .value_name("NAME")
                .action(clap::ArgAction::Set)
                .help(format!(
                    "Start from an instrument's preset (band, apertures, baseline, \
                     throughput, detector frame rate, read noise, dead time; sources in \
                     docs/instruments.md); any flag given overrides its value. One of: \
                     {names}; `list` prints them"
                )),
        )
    }
    fn augment_args_for_update(cmd: clap::Command) -> clap::Command {
        Self::augment_args(cmd)
    }
}

impl InstrumentArgs {
    /// With `--instrument list`: prints the presets (as a JSON array of
    /// their fields with `json`, else a table) and says so.
    pub fn print_list(&self, json: bool) -> bool {
        if self.name.as_deref().map(str::trim) != Some("list") {
            return false;
        }
        if json {
            super::print_json(&INSTRUMENTS);
            return true;
        }
        outln!(
            "{:<16} {:>7} {:>6} {:>5} {:>13} {:>6} {:>7} {:>6} {:>7}  description",
            "name",
            "λ0 um",
            "Δλ nm",
            "D m",
            "B m (default)",
            "T",
            "frame/s",
            "σ e-",
            "dead s"
        );
        for i in &INSTRUMENTS {
            outln!(
                "{:<16} {:>7} {:>6} {:>5} {:>13} {:>6} {:>7} {:>6} {:>7}  {}",
                i.name,
                i.wavelength_um,
                i.bandwidth_nm,
                i.aperture_m,
                format!(
                    "{}-{} ({})",
                    i.baseline_min_m, i.baseline_max_m, i.baseline_m
                ),
                i.throughput,
                i.frame_rate_hz,
                i.read_noise,
                i.dead_time_s,
                i.description
            );
        }
        true
    }

    /// The preset named, if any.
    pub fn preset(&self) -> Result<Option<&'static Instrument>> {
        self.name.as_deref().map(instrument).transpose()
    }

    /// Applies the preset to `p` and `req` where the command line gave no
    /// flag ([`Instrument::apply`]); then a magnitude needs a throughput,
    /// the flag's or the preset's.
    pub fn apply(&self, p: &mut Physical, req: &mut PlanRequest) -> Result<()> {
        if let Some(preset) = self.preset()? {
            preset.apply(p, req, &|key| self.given.contains(key));
        }
        match req.magnitude {
            Some(m) if m.throughput.is_nan() => Err(Error::Invalid {
                param: "throughput",
                reason: "needed with --magnitude: give --throughput, or an --instrument whose \
                         preset has one"
                    .into(),
            }),
            _ => Ok(()),
        }
    }
}
