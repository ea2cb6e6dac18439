//! The flags of the end-to-end simulator (`simulate`, `synth`, `estimate`):
//! every physical input, gathered into [`v2ref_core::simulator::Inputs`].

use super::common::{
    warn_if_outer_scale_infinite, LightArgs, ObservationArgs, ScanArgs, TurbulenceArgs,
};
use super::flags::{Flags, PistonArgs};
use v2ref_commands::parameters::Physical;
use v2ref_core::simulator::{Inputs, Model};
use v2ref_core::Result;

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
    /// The turbulence the piston is made of.
    #[command(flatten)]
    pub turbulence: TurbulenceArgs,
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
        let set = self.turbulence.apply_to(&mut turbulence);
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
        self.turbulence.apply_to(&mut p)?;
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
    use serde_json::{json, Value as Json};
    use std::collections::BTreeSet;
    use v2ref_commands::parameters::{Parameter, Physical, PARAMETERS};

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        inputs: InputsArgs,
    }

    /// No flag given: the library's defaults.
    #[test]
    fn flag_defaults_are_the_declared_defaults() {
        let cli = Cli::try_parse_from(["v2ref"]).unwrap();
        assert_eq!(cli.inputs.physical().unwrap(), Physical::default());
    }

    /// A word of the choice `--name` other than `now`.
    fn another_word(name: &str, now: &str) -> String {
        let cmd = Cli::command();
        let arg = cmd.get_arguments().find(|a| a.get_long() == Some(name));
        let values = arg.unwrap().get_possible_values();
        let other = values.iter().find(|v| v.get_name() != now).unwrap();
        other.get_name().to_owned()
    }

    /// Each flag reaches its own field: a non-default value of every
    /// input's flag moves exactly that field (a flag copied into the wrong
    /// field, or not at all, fails). The spectrum's and channels' files are read.
    #[test]
    fn each_flag_sets_its_field() {
        let dir = tempfile::tempdir().unwrap();
        let csv = dir.path().join("band.csv");
        std::fs::write(&csv, "wavelength_um,weight\n2.0,1\n2.4,2\n").unwrap();
        let csv = csv.display().to_string();
        let table = dir.path().join("channels.csv");
        let text = "wavelength_lo_um,wavelength_hi_um,response\n2.0,2.2,1\n2.2,2.4,1\n";
        std::fs::write(&table, text).unwrap();
        let table = table.display().to_string();
        let d = serde_json::to_value(Physical::default()).unwrap();
        for p in &PARAMETERS {
            let name = p.name.replace('_', "-");
            let (flags, want) = match &d[p.name] {
                Json::Bool(true) => (vec![format!("--no-{name}")], json!(false)),
                Json::Bool(false) => (vec![format!("--{name}")], json!(true)),
                Json::Number(n) if n.is_u64() => {
                    let n = n.as_u64().unwrap() + 1;
                    (vec![format!("--{name}"), n.to_string()], json!(n))
                }
                Json::Number(x) => {
                    let x = x.as_f64().unwrap() + 0.5;
                    (vec![format!("--{name}"), x.to_string()], json!(x))
                }
                Json::String(w) => {
                    let other = another_word(&name, w);
                    (vec![format!("--{name}"), other.clone()], json!(other))
                }
                Json::Null if p.name == "spectrum_csv" => {
                    (vec![format!("--{name}"), csv.clone()], json!(csv))
                }
                Json::Null if p.name == "channels_csv" => {
                    (vec![format!("--{name}"), table.clone()], json!(table))
                }
                Json::Null if p.name == "channels" => {
                    (vec![format!("--{name}"), "3".into()], json!(3))
                }
                Json::Null => (vec![format!("--{name}"), "1.5".into()], json!(1.5)),
                v => panic!("{}: {v:?}", p.name),
            };
            let args = std::iter::once("v2ref".to_owned()).chain(flags.iter().cloned());
            let got = Cli::try_parse_from(args)
                .unwrap()
                .inputs
                .physical()
                .unwrap();
            if p.name == "spectrum_csv" {
                assert!(got.spectrum_csv.is_some(), "the file is read");
            }
            if p.name == "channels_csv" {
                let file = got.channels_csv.as_ref().expect("the file is read");
                assert_eq!(file.text(), text);
            }
            let got = serde_json::to_value(got).unwrap();
            assert_eq!(got[p.name], want, "{flags:?}");
            for o in PARAMETERS.iter().filter(|o| o.name != p.name) {
                assert_eq!(got[o.name], d[o.name], "{flags:?} moved {}", o.name);
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
    /// --flag`, the flag, its entry, whether it turns the input off).
    fn physical_flags() -> Vec<(String, clap::Arg, &'static Parameter, bool)> {
        let mut out = Vec::new();
        for sub in crate::Cli::command().get_subcommands() {
            for arg in sub.get_arguments() {
                let Some(long) = arg.get_long() else { continue };
                let (name, off) = match long.strip_prefix("no-") {
                    Some(n) => (n.replace('-', "_"), true),
                    None => (long.replace('-', "_"), false),
                };
                let Some(p) = Parameter::named(&name) else {
                    continue;
                };
                if !NOT_PHYSICAL.contains(&(sub.get_name(), long)) {
                    out.push((format!("{} --{long}", sub.get_name()), arg.clone(), p, off));
                }
            }
        }
        out
    }

    /// Every physical flag of every command states its entry in
    /// [`PARAMETERS`]: its help (its doc comment) starts with the entry's
    /// text, unit and accepted range, and every input has a flag somewhere.
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
            seen.insert(p.name);
        }
        let declared: BTreeSet<_> = PARAMETERS.iter().map(|p| p.name).collect();
        assert_eq!(seen, declared);
    }

    /// Every physical flag's help ends with the library's default (what
    /// leaving it unset means where it may be unset; none for a flag), and
    /// a choice offers the words its entry lists.
    #[test]
    fn every_physical_flag_states_the_default() {
        let defaults = serde_json::to_value(Physical::default()).unwrap();
        for (at, arg, p, _) in physical_flags() {
            let help = arg.get_help().unwrap().to_string();
            let shown = help
                .rsplit_once("[default: ")
                .map(|(_, d)| d.trim_end_matches(']'));
            match &defaults[p.name] {
                Json::Null => assert_eq!(shown, Some(&*p.unset(&flag_of)), "{at}"),
                Json::Bool(_) => assert_eq!(shown, None, "{at}"),
                Json::Number(x) => {
                    assert_eq!(shown.and_then(|s| s.parse().ok()), x.as_f64(), "{at}")
                }
                Json::String(w) => {
                    assert_eq!(shown, Some(w.as_str()), "{at}");
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
