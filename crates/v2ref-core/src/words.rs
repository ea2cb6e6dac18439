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
