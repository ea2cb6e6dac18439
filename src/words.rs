//! The words that name a choice of the library (a bin window, a bias
//! convention, a source model, …): one list per choice, here in the core,
//! from which each edge builds what it needs — the CLI its possible values
//! and their help, Python its check of a keyword argument — and which JSON
//! uses (each enum's serde name is its word; the tests below hold them to
//! it). The core depends on no command-line parser for this.

use crate::error::{Error, Result};

/// One accepted word of a choice.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Word<T> {
    /// The word, as typed on the command line, in Python and in JSON.
    pub word: &'static str,
    /// The value it names.
    pub value: T,
    /// What it means, one line (the CLI's `--help` lists it).
    pub help: &'static str,
}

/// A choice named by words.
pub trait Words: Copy + PartialEq + Sized + 'static {
    /// Every value once, with its word, in the order the words are offered.
    const WORDS: &'static [Word<Self>];

    /// The word of this value.
    fn word(self) -> &'static str {
        Self::WORDS
            .iter()
            .find(|w| w.value == self)
            .map_or("unnamed", |w| w.word)
    }

    /// The value named `word`, or [`Error::Invalid`] under `param` listing
    /// the words accepted (`'x' is not one of: a, b`).
    fn from_word(param: &'static str, word: &str) -> Result<Self> {
        Self::WORDS
            .iter()
            .find(|w| w.word == word)
            .map(|w| w.value)
            .ok_or_else(|| Error::Invalid {
                param,
                reason: format!("'{word}' is not one of: {}", Self::listed(", ")),
            })
    }

    /// The words, joined by `separator`.
    fn listed(separator: &str) -> String {
        let words: Vec<&str> = Self::WORDS.iter().map(|w| w.word).collect();
        words.join(separator)
    }
}

#[cfg(test)]
mod tests {
    use super::Words;
    use crate::conformance::estimate::BiasConvention;
    use crate::formalism::estimator::BinWindow;
    use crate::noise::Formula;
    use crate::parameters::SourceKind;
    use crate::piston::spectrum::PistonPsdModel;
    use crate::piston::PistonReference;
    use crate::simulator::RowLayout;

    /// Each word is its value's serde name (what JSON writes), once, and
    /// names that value back; a word not listed is refused naming the
    /// parameter and the words.
    fn check<T: Words + serde::Serialize + std::fmt::Debug>() {
        let mut seen = Vec::new();
        for w in T::WORDS {
            assert_eq!(serde_json::to_value(w.value).unwrap(), w.word, "{w:?}");
            assert_eq!(w.value.word(), w.word);
            assert_eq!(T::from_word("p", w.word).unwrap(), w.value);
            assert!(!w.help.is_empty() && !seen.contains(&w.word), "{w:?}");
            seen.push(w.word);
        }
        let e = T::from_word("p", "nope").unwrap_err().to_string();
        assert!(
            e.contains(&format!("'nope' is not one of: {}", T::listed(", "))),
            "{e}"
        );
    }

    #[test]
    fn words_are_the_serde_names() {
        check::<BinWindow>();
        check::<BiasConvention>();
        check::<Formula>();
        check::<SourceKind>();
        check::<PistonReference>();
        check::<PistonPsdModel>();
        check::<RowLayout>();
        check::<crate::plan::photometry::Band2Mass>();
        assert_eq!(BinWindow::listed(", "), "positive, band, all");
        assert_eq!(RowLayout::listed(" or "), "sequences or observation");
    }
}
