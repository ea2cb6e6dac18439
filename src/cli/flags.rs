//! The physical flags, made from the library's one declaration
//! ([`v2ref_commands::parameters::PARAMETERS`]): each input's flag (its name, value
//! parser, default, help) follows from its entry, and a group of flags
//! ([`physical_flags!`]) only lists the keys of the inputs it holds, in
//! the order `--help` shows them. Reading the flags back sets each input by
//! its key ([`Physical::set`]); a spectrum's file is read here, at the edge.

use super::common::{help, help_off};
use clap::builder::{PossibleValue, PossibleValuesParser};
use clap::{Arg, ArgAction, ArgMatches, Command};
use std::path::PathBuf;
use std::sync::OnceLock;
use v2ref_commands::parameters::{Kind, Parameter, Physical, Value, PARAMETERS};

/// How a group's number flags take a value that starts with `-`: as a
/// negative number only, or whatever follows (then the value parser says
/// what is wrong with it).
#[derive(Debug, Clone, Copy)]
pub enum Hyphen {
    /// `allow_negative_numbers`.
    NegativeNumbers,
    /// `allow_hyphen_values`.
    Values,
}

/// Flags that cannot be given together: the first names the second.
const CONFLICTS: [(Parameter, Parameter); 1] =
    [(Parameter::SPATIAL_FREQ_CPAS, Parameter::BASELINE_M)];

/// An input's flag names and default as clap keeps them (`'static`).
struct Names {
    /// The argument's id: the input's name, `no_` before it for a flag on
    /// by default (which the flag turns off).
    id: String,
    /// `--` this.
    long: String,
    /// The value's placeholder in `--help`.
    value_name: String,
    /// The default shown and used, for an input that is not unset by default.
    default: Option<String>,
    /// The flag turns the input off.
    off: bool,
}

impl Names {
    /// The names of the flag of `p`, from its declaration and default.
    fn of(p: &Parameter) -> Names {
        let off = Physical::DEFAULT.get(p) == Value::Flag(true);
        let id = if off {
            format!("no_{}", p.name)
        } else {
            p.name.to_owned()
        };
        let default = match Physical::DEFAULT.get(p) {
            Value::Number(x) => Some(x.to_string()),
            Value::Count(n) => Some(n.to_string()),
            Value::Word(w) => Some(w),
            _ => None,
        };
        Names {
            long: id.replace('_', "-"),
            value_name: match p.kind {
                Kind::File => "FILE".to_owned(),
                _ => p.name.to_uppercase(),
            },
            id,
            default,
            off,
        }
    }
}

/// The names of the input `p` (a declared one: the keys are the
/// declaration's constants).
fn names(p: &Parameter) -> &'static Names {
    static ALL: OnceLock<Vec<Names>> = OnceLock::new();
    let all = ALL.get_or_init(|| PARAMETERS.iter().map(Names::of).collect());
    let i = PARAMETERS.iter().position(|q| q.name == p.name);
    &all[i.expect("a key of the declaration")]
}

/// The flag of the input `p`.
pub fn arg(p: &Parameter, hyphen: Hyphen) -> Arg {
    let n = names(p);
    let arg = Arg::new(n.id.as_str()).long(n.long.as_str());
    if p.kind == Kind::Flag {
        let text = if n.off { help_off(p) } else { help(p) };
        return arg.action(ArgAction::SetTrue).help(text);
    }
    let arg = arg
        .value_name(n.value_name.as_str())
        .required(false)
        .action(ArgAction::Set)
        .help(help(p));
    let arg = match p.kind {
        Kind::Count => arg.value_parser(super::count_usize),
        Kind::Word => {
            let words = Physical::words(p).into_iter();
            arg.value_parser(PossibleValuesParser::new(
                words.map(|(w, h)| PossibleValue::new(w).help(h)),
            ))
        }
        Kind::File => arg.value_parser(clap::value_parser!(PathBuf)),
        _ => arg.value_parser(super::finite_f64),
    };
    let arg = match &n.default {
        Some(d) => arg.default_value(d.as_str()),
        None => arg,
    };
    let arg = match CONFLICTS.iter().find(|(a, _)| a.name == p.name) {
        Some((_, b)) => arg.conflicts_with(names(b).id.as_str()),
        None => arg,
    };
    match (p.kind, hyphen) {
        (Kind::Number | Kind::Count, Hyphen::NegativeNumbers) => arg.allow_negative_numbers(true),
        (Kind::Number | Kind::Count, Hyphen::Values) => arg.allow_hyphen_values(true),
        _ => arg,
    }
}

/// `cmd` with the flags of `keys` and their group `group` (what
/// `--sidecar` of `estimate` conflicts with).
pub fn augment(cmd: Command, group: &'static str, keys: &[&Parameter], hyphen: Hyphen) -> Command {
    let members = keys.iter().map(|p| names(p).id.as_str());
    let group = clap::ArgGroup::new(group).multiple(true).args(members);
    keys.iter()
        .fold(cmd.group(group), |cmd, p| cmd.arg(arg(p, hyphen)))
}

/// What a group's flags gave: each input's value, or the name of a
/// spectrum's file, read when the inputs are set.
#[derive(Debug, Clone, Default)]
pub struct Given(Vec<(&'static Parameter, Option<PathBuf>, Value)>);

impl Given {
    /// The values of the flags of `keys` in `m` (their defaults when not
    /// given).
    pub fn read(m: &ArgMatches, keys: &[&'static Parameter]) -> Given {
        let given = keys.iter().map(|&p| {
            let id = names(p).id.as_str();
            let (file, value) = match p.kind {
                Kind::Flag => (None, Value::Flag(m.get_flag(id) != names(p).off)),
                Kind::Number => (
                    None,
                    m.get_one(id).copied().map_or(Value::Unset, Value::Number),
                ),
                Kind::Count => (
                    None,
                    m.get_one(id).copied().map_or(Value::Unset, Value::Count),
                ),
                Kind::Word => (
                    None,
                    m.get_one::<String>(id)
                        .cloned()
                        .map_or(Value::Unset, Value::Word),
                ),
                Kind::File => (m.get_one::<PathBuf>(id).cloned(), Value::Unset),
            };
            (p, file, value)
        });
        Given(given.collect())
    }

    /// Sets the inputs these flags hold in `p`, reading a spectrum's file.
    pub fn apply_to(&self, p: &mut Physical) -> v2ref_core::Result<()> {
        for (key, file, value) in &self.0 {
            let value = match file {
                Some(path) => Value::Spectrum(
                    v2ref_files::formats::spectrum_csv::read_spectrum_file(path)?,
                ),
                None => value.clone(),
            };
            p.set(key, value)?;
        }
        Ok(())
    }
}

/// A group of physical flags, `Name, Hyphen: KEY, KEY, …` (the keys of
/// [`Parameter`], in the order of `--help`): a clap [`clap::Args`] whose
/// group is `Name`, and `apply_to` setting the inputs they hold.
macro_rules! physical_flags {
    ($(#[$doc:meta])* $name:ident, $hyphen:ident: $($key:ident),+ $(,)?) => {
        $(#[$doc])*
        #[derive(Debug, Clone)]
        pub struct $name($crate::cli::flags::Given);

        impl $name {
            /// The inputs of these flags.
            const KEYS: &'static [&'static v2ref_commands::parameters::Parameter] =
                &[$(&v2ref_commands::parameters::Parameter::$key),+];

            /// Sets the inputs these flags hold in `p` (a spectrum's file
            /// read here).
            pub fn apply_to(&self, p: &mut v2ref_commands::parameters::Physical) -> v2ref_core::Result<()> {
                self.0.apply_to(p)
            }
        }

        impl clap::FromArgMatches for $name {
            fn from_arg_matches(m: &clap::ArgMatches) -> ::std::result::Result<Self, clap::Error> {
                Ok($name($crate::cli::flags::Given::read(m, Self::KEYS)))
            }
            fn update_from_arg_matches(&mut self, m: &clap::ArgMatches) -> ::std::result::Result<(), clap::Error> {
                *self = Self::from_arg_matches(m)?;
                Ok(())
            }
        }

        impl clap::Args for $name {
            fn group_id() -> Option<clap::Id> {
                Some(clap::Id::from(stringify!($name)))
            }
            fn augment_args(cmd: clap::Command) -> clap::Command {
                use $crate::cli::flags::{augment, Hyphen};
                augment(cmd, stringify!($name), Self::KEYS, Hyphen::$hyphen)
            }
            fn augment_args_for_update(cmd: clap::Command) -> clap::Command {
                Self::augment_args(cmd)
            }
        }
    };
}

pub(crate) use physical_flags;
