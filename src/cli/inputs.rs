//! The flags of the end-to-end simulator (`simulate`, `synth`, `estimate`):
//! every physical input, gathered into [`v2ref_core::simulator::Inputs`].

use super::common::{
    warn_if_outer_scale_infinite, LightArgs, ObservationArgs, ScanArgs, TurbulenceArgs,
};
use super::flags::{augment, Given, Hyphen};
use v2ref_commands::parameters::{Parameter, Physical};
use v2ref_core::simulator::{Inputs, Model};
use v2ref_core::Result;

/// The differential piston: on when `--fringe-hz` is given.
#[derive(Debug, Clone)]
pub struct PistonArgs {
    fringe: Given,
    /// The turbulence the piston is made of.
    pub turbulence: TurbulenceArgs,
}

impl PistonArgs {
    /// The inputs of these flags, but the turbulence's.
    const KEYS: &'static [&'static Parameter] = &[&Parameter::FRINGE_HZ];

    /// Sets the inputs these flags hold in `p`.
    pub fn apply_to(&self, p: &mut Physical) -> Result<()> {
        self.fringe.apply_to(p)?;
        self.turbulence.apply_to(p)
    }
}

impl clap::FromArgMatches for PistonArgs {
    fn from_arg_matches(m: &clap::ArgMatches) -> std::result::Result<Self, clap::Error> {
        Ok(PistonArgs {
            fringe: Given::read(m, Self::KEYS),
            turbulence: TurbulenceArgs::from_arg_matches(m)?,
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

impl clap::Args for PistonArgs {
    fn group_id() -> Option<clap::Id> {
        Some(clap::Id::from("PistonArgs"))
    }
    /// Its flag, then the turbulence's. Its group holds its flag (clap's
    /// derive leaves the group of a struct with flattened flags empty: then
    /// `estimate --sidecar` took `--fringe-hz` and ignored it).
    fn augment_args(cmd: clap::Command) -> clap::Command {
        let cmd = augment(cmd, "PistonArgs", Self::KEYS, Hyphen::NegativeNumbers);
        TurbulenceArgs::augment_args(cmd)
    }
    fn augment_args_for_update(cmd: clap::Command) -> clap::Command {
        Self::augment_args(cmd)
    }
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
    /// [`warn_if_outer_scale_infinite`]).
    pub fn warn_about(&self, model: &Model) {
        let mut turbulence = Physical::default();
        let set = self.piston.turbulence.apply_to(&mut turbulence);
        if let (Some(s), Ok(())) = (&model.piston_spectrum, set) {
            warn_if_outer_scale_infinite(&turbulence, s.baseline_m(), s.rms_um());
        }
    }

    /// Every physical input these flags hold (the spectrum's file read).
    pub fn physical(&self) -> Result<Physical> {
        let mut p = self.obs.physical()?;
        self.scan.apply_to(&mut p)?;
        self.light.apply_to(&mut p)?;
        self.piston.apply_to(&mut p)?;
        Ok(p)
    }

    /// The inputs, before the checks that involve N (a file's width may
    /// still set it).
    pub fn inputs_unchecked(&self) -> Result<Inputs> {
        self.physical()?.inputs_unchecked()
    }
}

#[cfg(test)]
mod tests {
    use super::InputsArgs;
    use crate::cli::flag_of;
    use clap::{CommandFactory, Parser};
    use serde_json::Value as Json;
    use std::collections::BTreeSet;
    use v2ref_commands::parameters::{Kind, Parameter, Physical, Value, PARAMETERS};

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        inputs: InputsArgs,
    }

    /// The flags' defaults are the library's one declaration of them.
    #[test]
    fn flag_defaults_are_the_declared_defaults() {
        let cli = Cli::try_parse_from(["v2ref"]).unwrap();
        assert_eq!(cli.inputs.physical().unwrap(), Physical::default());
    }

    /// Each flag reaches its own field: a non-default value of every
    /// declared input's flag moves exactly that field (a flag copied into
    /// the wrong field, or not at all, fails). The spectrum's file is read.
    #[test]
    fn each_flag_sets_its_field() {
        let dir = tempfile::tempdir().unwrap();
        let csv = dir.path().join("band.csv");
        std::fs::write(&csv, "wavelength_um,weight\n2.0,1\n2.4,2\n").unwrap();
        let d = Physical::default();
        for p in &PARAMETERS {
            let name = p.name.replace('_', "-");
            let (flags, want) = match d.get(p) {
                Value::Flag(true) => (vec![format!("--no-{name}")], Value::Flag(false)),
                Value::Flag(false) => (vec![format!("--{name}")], Value::Flag(true)),
                Value::Number(x) => (
                    vec![format!("--{name}"), format!("{}", x + 0.5)],
                    Value::Number(x + 0.5),
                ),
                Value::Count(n) => (
                    vec![format!("--{name}"), format!("{}", n + 1)],
                    Value::Count(n + 1),
                ),
                Value::Word(w) => {
                    let words = Physical::words(p);
                    let other = words.iter().find(|(o, _)| *o != w).unwrap().0;
                    (
                        vec![format!("--{name}"), other.to_owned()],
                        Value::Word(other.to_owned()),
                    )
                }
                Value::Unset if p.kind == Kind::File => {
                    let table =
                        v2ref_files::formats::spectrum_csv::read_spectrum_file(&csv).unwrap();
                    (
                        vec![format!("--{name}"), csv.display().to_string()],
                        Value::Spectrum(table),
                    )
                }
                Value::Unset => (vec![format!("--{name}"), "1.5".into()], Value::Number(1.5)),
                v => panic!("{}: {v:?}", p.name),
            };
            let args = std::iter::once("v2ref".to_owned()).chain(flags.iter().cloned());
            let got = Cli::try_parse_from(args)
                .unwrap()
                .inputs
                .physical()
                .unwrap();
            assert_eq!(got.get(p), want, "{flags:?}");
            for o in PARAMETERS.iter().filter(|o| o.name != p.name) {
                assert_eq!(got.get(o), d.get(o), "{flags:?} moved {}", o.name);
            }
        }
    }

    /// Flags named as a physical input that take something else: the
    /// grids of `plan` and the list of `piston`.
    const NOT_PHYSICAL: [(&str, &str); 3] = [
        ("plan", "fringe-hz"),
        ("plan", "stroke-um"),
        ("piston", "fringe-hz"),
    ];

    /// Every flag of every command that sets a physical input: (`command
    /// --flag`, the flag, its declaration, whether it turns the input off).
    fn physical_flags() -> Vec<(String, clap::Arg, &'static Parameter, bool)> {
        let mut out = Vec::new();
        for sub in crate::Cli::command().get_subcommands() {
            for arg in sub.get_arguments() {
                let Some(long) = arg.get_long() else { continue };
                let (name, off) = match long.strip_prefix("no-") {
                    Some(n) => (n.replace('-', "_"), true),
                    None => (long.replace('-', "_"), false),
                };
                let Some(p) = PARAMETERS.iter().find(|p| p.name == name) else {
                    continue;
                };
                if !NOT_PHYSICAL.contains(&(sub.get_name(), long)) {
                    out.push((format!("{} --{long}", sub.get_name()), arg.clone(), p, off));
                }
            }
        }
        out
    }

    /// Every physical flag of every command states its one declaration:
    /// its help starts with the declared text, unit and accepted range
    /// (what leaving it unset means at its end), and every declared input
    /// has a flag somewhere.
    #[test]
    fn every_physical_flag_states_its_declaration() {
        let mut seen = BTreeSet::new();
        let flags = |n: &str| flag_of(n);
        for (at, arg, p, off) in physical_flags() {
            let help = arg.get_help().expect("a help").to_string();
            let mut head = Parameter { note: "", ..*p }.describe(&flags);
            head.pop(); // the full stop
            if off {
                head = format!("Turns off: {head}");
            }
            assert!(help.starts_with(&head), "{at}: {help:?} for {head:?}");
            if !p.unset.is_empty() {
                let unset = format!("[default: {}]", p.unset(&flags));
                assert!(help.ends_with(&unset), "{at}: {help:?}");
            }
            seen.insert(p.name);
        }
        let declared: BTreeSet<_> = PARAMETERS.iter().map(|p| p.name).collect();
        assert_eq!(seen, declared);
    }

    /// Every physical flag's default is the declared one (none where the
    /// input may be unset), and a choice offers the declared words.
    #[test]
    fn every_physical_flag_has_the_declared_default() {
        let defaults = serde_json::to_value(Physical::default()).unwrap();
        for (at, arg, p, off) in physical_flags() {
            let shown: Vec<String> = arg
                .get_default_values()
                .iter()
                .map(|v| v.to_string_lossy().into_owned())
                .collect();
            match &defaults[p.name] {
                Json::Null => assert!(shown.is_empty(), "{at}: {shown:?}"),
                Json::Bool(b) => assert_eq!(*b, off, "{at}"),
                Json::Number(x) => assert_eq!(shown[0].parse().ok(), x.as_f64(), "{at}"),
                Json::String(w) => {
                    assert_eq!(shown, [w.as_str()], "{at}");
                    let words: Vec<String> = arg
                        .get_possible_values()
                        .iter()
                        .map(|v| v.get_name().to_owned())
                        .collect();
                    let listed = p.accepted.replace(" or ", ", ");
                    assert_eq!(listed.split(", ").collect::<Vec<_>>(), words, "{at}");
                }
                v => panic!("{at}: {v}"),
            }
        }
    }
}
