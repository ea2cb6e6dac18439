//! The one declaration's machinery: [`physical_inputs!`] turns one list of
//! entries (field, type, default, unit, range, help) into the struct
//! [`super::Physical`], its defaults, the constants of [`super::Parameter`],
//! the table [`super::PARAMETERS`] and a setter by key
//! ([`super::Physical::set`]) through which the edges fill it from what they
//! parsed ([`Value`]); each field's type says how it is given ([`Input`]).

use super::SpectrumFile;
use crate::error::{Error, Result};
use crate::words::Words;

/// How an input is given at the edges, from its field's type: the CLI's
/// value parser and Python's extraction follow it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A finite number (`f64`, or `Option<f64>` when it may be unset).
    Number,
    /// A count (`usize`).
    Count,
    /// True or false (`bool`): the CLI's flag turns it on, or off
    /// (`--no-NAME`) when it is on by default.
    Flag,
    /// One of a choice's words ([`Words`]).
    Word,
    /// A spectrum CSV file, read by the edges (`read_spectrum_file` of the crate `v2ref-files`, feature
    /// `files`).
    File,
}

/// An input's value as an edge parsed it, or as the defaults hold it.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// Not given: an `Option` input left unset.
    Unset,
    /// A number.
    Number(f64),
    /// A count.
    Count(usize),
    /// True or false.
    Flag(bool),
    /// A choice's word, as typed.
    Word(String),
    /// A spectrum's table, read from its file.
    Spectrum(SpectrumFile),
}

/// A type a physical input may have: how it is given and read back.
pub trait Input: Sized {
    /// How it is given.
    const KIND: Kind;
    /// The value `v` given for the input `name`, or [`Error::Invalid`]
    /// naming it (a word not of the choice, a value of another kind).
    fn from_value(name: &'static str, v: Value) -> Result<Self>;
    /// This value as an edge would give it.
    fn to_value(&self) -> Value;
    /// A choice's words, each with its help; none for other kinds.
    fn words() -> Vec<(&'static str, &'static str)> {
        Vec::new()
    }
}

/// A value of the wrong kind for the input `name`.
fn wrong(name: &'static str, v: &Value) -> Error {
    Error::Invalid {
        param: name,
        reason: format!("{v:?} is not a value of this input"),
    }
}

/// [`Input`] of a plain type and of its `Option` (unset: [`Value::Unset`]).
macro_rules! input {
    ($ty:ty, $kind:ident) => {
        impl Input for $ty {
            const KIND: Kind = Kind::$kind;
            fn from_value(name: &'static str, v: Value) -> Result<Self> {
                match v {
                    Value::$kind(x) => Ok(x),
                    v => Err(wrong(name, &v)),
                }
            }
            fn to_value(&self) -> Value {
                Value::$kind(self.clone())
            }
        }
    };
}

input!(f64, Number);
input!(usize, Count);
input!(bool, Flag);

impl Input for Option<f64> {
    const KIND: Kind = Kind::Number;
    fn from_value(name: &'static str, v: Value) -> Result<Self> {
        match v {
            Value::Unset => Ok(None),
            v => f64::from_value(name, v).map(Some),
        }
    }
    fn to_value(&self) -> Value {
        self.map_or(Value::Unset, Value::Number)
    }
}

impl Input for Option<SpectrumFile> {
    const KIND: Kind = Kind::File;
    fn from_value(name: &'static str, v: Value) -> Result<Self> {
        match v {
            Value::Unset => Ok(None),
            Value::Spectrum(s) => Ok(Some(s)),
            v => Err(wrong(name, &v)),
        }
    }
    fn to_value(&self) -> Value {
        self.clone().map_or(Value::Unset, Value::Spectrum)
    }
}

/// A choice among words is an input of kind `Word` (one impl per type: a
/// blanket impl over the oracle's trait would not be coherent across crates).
macro_rules! word_input {
    ($($t:ty),+ $(,)?) => {$(
        impl Input for $t {
            const KIND: Kind = Kind::Word;
            fn from_value(name: &'static str, v: Value) -> Result<Self> {
                match v {
                    Value::Word(w) => <$t as Words>::from_word(name, &w),
                    v => Err(wrong(name, &v)),
                }
            }
            fn to_value(&self) -> Value {
                Value::Word(self.word().to_owned())
            }
            fn words() -> Vec<(&'static str, &'static str)> {
                <$t as Words>::WORDS.iter().map(|w| (w.word, w.help)).collect()
            }
        }
    )+};
}

word_input!(
    crate::formalism::estimator::BinWindow,
    crate::simulator::RowLayout,
    crate::simulator::estimate::BiasConvention,
    crate::noise::appendix::Formula,
    crate::record::PistonReference,
    crate::piston::spectrum::PistonPsdModel,
    crate::parameters::SourceKind,
    crate::plan::photometry::Band2Mass,
);

/// Declares every physical input once. Each entry is the field's doc
/// comment, `name: Type = default,` the key's constant (`NAME`), then the
/// texts of its [`super::Parameter`] (`unit`, `accepted`, `what`, `note`,
/// `unset`, `why`). It makes the struct `Physical` (one field per entry,
/// in this order), `Physical::DEFAULT`, `Parameter::NAME` (whose `kind` is
/// the type's [`Input::KIND`]), `PARAMETERS`, `Physical::set` and
/// `Physical::get` by key and `Physical::words`.
macro_rules! physical_inputs {
    ($(
        $(#[$doc:meta])*
        $field:ident: $ty:ty = $default:expr, $key:ident {
            unit: $unit:expr,
            accepted: $accepted:expr,
            what: $what:expr,
            note: $note:expr,
            unset: $unset:expr,
            why: $why:expr $(,)?
        }
    )*) => {
        /// Every physical input of one configuration (see the module doc),
        /// declared once ([`PARAMETERS`]). Field names are the Python keyword
        /// arguments and, with `_` as `-`, the CLI's flags (a flag on by
        /// default, `photon_noise`, is turned off by `--no-photon-noise`).
        #[derive(Debug, Clone, PartialEq, Serialize)]
        pub struct Physical {
            $( $(#[$doc])* pub $field: $ty, )*
        }

        impl Physical {
            /// The defaults: the paper's K-band case, a 43 mas disk at 40
            /// cycles/arcsec, 400 nm at 2.2 µm, 128 samples of 0.5 µm, 10
            /// photons per sample (a constant, for the CLI's flag defaults).
            pub const DEFAULT: Physical = Physical { $( $field: $default, )* };

            /// Sets the input `key` to `value` (as an edge parsed it), or
            /// [`crate::Error::Invalid`] naming it: a word not of its
            /// choice, a value of another kind.
            pub fn set(&mut self, key: &Parameter, value: $crate::parameters::Value) -> Result<()> {
                use $crate::parameters::Input;
                $( if key.name == stringify!($field) {
                    self.$field = <$ty>::from_value(key.name, value)?;
                    return Ok(());
                } )*
                Err(Error::Invalid { param: "key", reason: format!("{}: not a physical input", key.name) })
            }

            /// The words of the choice `key`, each with its help (none for
            /// an input of another kind).
            pub fn words(key: &Parameter) -> Vec<(&'static str, &'static str)> {
                $( if key.name == stringify!($field) {
                    return <$ty as $crate::parameters::Input>::words();
                } )*
                Vec::new()
            }

            /// The value of the input `key` ([`crate::parameters::Value::Unset`] for an
            /// unknown key).
            pub fn get(&self, key: &Parameter) -> $crate::parameters::Value {
                use $crate::parameters::Input;
                $( if key.name == stringify!($field) {
                    return self.$field.to_value();
                } )*
                $crate::parameters::Value::Unset
            }
        }

        impl Parameter {
            $(
                #[doc = concat!("`", stringify!($field), "`.")]
                pub const $key: Parameter = Parameter {
                    name: stringify!($field),
                    unit: $unit,
                    accepted: $accepted,
                    what: $what,
                    note: $note,
                    unset: $unset,
                    why: $why,
                    kind: <$ty as $crate::parameters::Input>::KIND,
                };
            )*
        }

        /// Every field of [`Physical`], in declaration order.
        pub const PARAMETERS: [Parameter; [$(stringify!($field)),*].len()] = [ $( Parameter::$key, )* ];
    };
}

pub(crate) use physical_inputs;

#[cfg(test)]
mod tests {
    use super::{Kind, Value};
    use crate::parameters::{Parameter, Physical, SpectrumFile, PARAMETERS};

    /// A value of `p` other than `now` (its kind's).
    fn another(p: &Parameter, now: &Value) -> Value {
        match now {
            Value::Number(x) => Value::Number(x + 0.5),
            Value::Count(n) => Value::Count(n + 1),
            Value::Flag(b) => Value::Flag(!b),
            Value::Word(w) => {
                let words = Physical::words(p);
                let other = words.iter().find(|(o, _)| o != w).expect("two words");
                Value::Word(other.0.to_owned())
            }
            Value::Unset if p.kind == Kind::File => {
                let table =
                    crate::formalism::spectrum::Spectrum::tabulated(vec![0.4, 0.5], vec![1.0, 2.0]);
                Value::Spectrum(SpectrumFile::new("t.csv".as_ref(), table.unwrap()))
            }
            Value::Unset => Value::Number(1.5),
            Value::Spectrum(_) => Value::Unset,
        }
    }

    /// Each key sets its own field and no other: a value other than the
    /// default, set by key, is read back by that key while every other
    /// input keeps its default (a setter that wrote another field, or
    /// none, fails); its kind is the one its value takes.
    #[test]
    fn each_key_sets_its_own_field() {
        let d = Physical::DEFAULT;
        for p in &PARAMETERS {
            let value = another(p, &d.get(p));
            let mut q = d.clone();
            q.set(p, value.clone()).unwrap();
            assert_eq!(q.get(p), value, "{}", p.name);
            for o in PARAMETERS.iter().filter(|o| o.name != p.name) {
                assert_eq!(q.get(o), d.get(o), "{} moved {}", p.name, o.name);
            }
        }
    }

    /// A value of another kind, or a word not of the choice, is refused
    /// naming the input.
    #[test]
    fn a_value_of_another_kind_is_refused_naming_the_input() {
        let mut p = Physical::DEFAULT;
        let e = p.set(&Parameter::SAMPLES, Value::Number(1.0)).unwrap_err();
        assert_eq!(e.param(), Some("samples"));
        let e = p.set(&Parameter::SOURCE, Value::Word("disk".into()));
        assert_eq!(e.unwrap_err().param(), Some("source"));
        assert_eq!(p, Physical::DEFAULT);
    }

    mod one_more_input {
        //! The declaration of two inputs, as a new one is added: one entry
        //! each makes the field, its default, its key, its kind and its
        //! setter.
        use crate::error::{Error, Result};
        use crate::parameters::{Kind, Parameter, Value};
        use serde::Serialize;

        super::super::physical_inputs! {
            /// A length, m.
            length_m: f64 = 2.0, EXAMPLE_LENGTH_M {
                unit: "m",
                accepted: "> 0",
                what: "A length",
                note: "",
                unset: "",
                why: "",
            }
            /// A number that may be unset.
            limit: Option<f64> = None, EXAMPLE_LIMIT {
                unit: "",
                accepted: "0 to 1",
                what: "A limit",
                note: "",
                unset: "none",
                why: "",
            }
        }

        #[test]
        fn one_entry_declares_an_input() {
            assert_eq!(PARAMETERS.map(|p| p.name), ["length_m", "limit"]);
            assert_eq!(Parameter::EXAMPLE_LENGTH_M.unit, "m");
            assert_eq!(Parameter::EXAMPLE_LIMIT.kind, Kind::Number);
            let mut p = Physical::DEFAULT;
            assert_eq!((p.length_m, p.limit), (2.0, None));
            p.set(&Parameter::EXAMPLE_LIMIT, Value::Number(0.5))
                .unwrap();
            assert_eq!(p.limit, Some(0.5));
            assert_eq!(p.get(&Parameter::EXAMPLE_LENGTH_M), Value::Number(2.0));
            assert!(Physical::words(&Parameter::EXAMPLE_LENGTH_M).is_empty());
        }
    }
}
