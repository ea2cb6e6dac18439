//! The spectral channels among the physical inputs: three ways to give
//! them (`channels`, `resolution`, `channels_csv`), at most one at a time,
//! made into the library's [`Channels`] of the configuration's spectrum
//! (docs/conventions.md §16). None given is the wide band as it always
//! was: no channel object is made and no code path changes.

use super::Physical;
use crate::error::{Error, Result};
use crate::formalism::channels::Channels;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// The names of the inputs that give channels, in the order of
/// [`super::PARAMETERS`].
pub const CHANNEL_INPUTS: [&str; 3] = ["channels", "resolution", "channels_csv"];

/// A channel table's CSV text and the name of the file it was read from.
/// The edges read the file (without waiting, a regular file only,
/// `v2ref_files::formats::channels_csv::read_channels_text`); the table is parsed against the
/// configuration's spectrum by [`Physical::channels`], since its edges are
/// checked against the band. Serialized as the file's name.
#[derive(Debug, Clone, PartialEq)]
pub struct ChannelsFile {
    path: PathBuf,
    text: String,
}

impl ChannelsFile {
    /// The CSV `text` read from the file `path`.
    pub fn new(path: &Path, text: String) -> ChannelsFile {
        ChannelsFile {
            path: path.to_owned(),
            text,
        }
    }

    /// The file's name.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The file's text.
    pub fn text(&self) -> &str {
        &self.text
    }
}

impl Serialize for ChannelsFile {
    /// As the file's name, the value the user gave.
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        self.path.serialize(s)
    }
}

/// `e` with the parameter `channels` named `to` (the input the user gave).
pub fn renamed_channels(e: Error, to: &'static str) -> Error {
    match e {
        Error::Invalid {
            param: "channels",
            reason,
        } => Error::Invalid { param: to, reason },
        e => e.renamed("channels", to),
    }
}

impl Physical {
    /// The channel inputs given, by name (at most one is accepted).
    fn channel_inputs_given(&self) -> Vec<&'static str> {
        let given = [
            self.channels.is_some(),
            self.resolution.is_some(),
            self.channels_csv.is_some(),
        ];
        CHANNEL_INPUTS
            .iter()
            .zip(given)
            .filter_map(|(name, on)| on.then_some(*name))
            .collect()
    }

    /// The channel input given (`channels`, `resolution` or
    /// `channels_csv`), or None: what a refusal of the channels names.
    pub fn channel_input(&self) -> Option<&'static str> {
        self.channel_inputs_given().first().copied()
    }

    /// The spectral channels of this configuration's spectrum, or None
    /// when no channel input is given (the wide band). Refused: two
    /// channel inputs at once ([`Error::Invalid`] naming both); a count
    /// outside 1 to `MAX_CHANNELS`, a resolution ≤ 0 or giving more
    /// channels than that, a table that does not parse or whose channels
    /// overlap, are out of order or leave the band (each naming the input
    /// given).
    pub fn channels(&self) -> Result<Option<Channels>> {
        let given = self.channel_inputs_given();
        if let [first, second, ..] = given[..] {
            return Err(Error::Invalid {
                param: first,
                reason: format!("cannot be used with {second} (give one of them)"),
            });
        }
        let Some(&input) = given.first() else {
            return Ok(None);
        };
        let spectrum = self.spectrum()?;
        let channels = match (self.channels, self.resolution, &self.channels_csv) {
            (Some(count), _, _) => Channels::equal(&spectrum, count),
            (_, Some(r), _) => Channels::from_resolution(&spectrum, r),
            (_, _, Some(file)) => {
                Channels::from_csv_str(&spectrum, file.text()).map_err(|e| match e {
                    Error::Invalid { param, reason } => Error::Invalid {
                        param,
                        reason: format!("{}: {reason}", file.path().display()),
                    },
                    e => e,
                })
            }
            (None, None, None) => unreachable!("one channel input is given"),
        };
        channels.map(Some).map_err(|e| renamed_channels(e, input))
    }

    /// Refuses the channel inputs in a command that does not take them
    /// yet (`command`: its name), naming the input given; Ok when none
    /// is given. A command that ignored them would answer for the wide
    /// band as if for the channels.
    pub fn refuse_channels(&self, command: &str) -> Result<()> {
        match self.channel_input() {
            None => Ok(()),
            Some(input) => Err(Error::Invalid {
                param: input,
                reason: format!(
                    "not taken by `{command}` yet; bias, snr and simulate answer per channel"
                ),
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::parameters::{ChannelsFile, Physical};
    use std::path::Path;

    /// None given: no channels; two given: refused naming both; each one
    /// alone makes its channels, a refusal naming the input given.
    #[test]
    fn one_channel_input_at_most_each_refusal_naming_it() {
        let none = Physical::default();
        assert_eq!(none.channels().unwrap(), None);
        assert!(none.refuse_channels("plan").is_ok());
        let both = Physical {
            channels: Some(4),
            resolution: Some(30.0),
            ..Physical::DEFAULT
        };
        let e = both.channels().unwrap_err().to_string();
        assert!(
            e.starts_with("channels: ") && e.contains("resolution"),
            "{e}"
        );
        let four = Physical {
            channels: Some(4),
            ..Physical::DEFAULT
        };
        assert_eq!(four.channels().unwrap().unwrap().count(), 4);
        let e = four.refuse_channels("plan").unwrap_err().to_string();
        assert!(e.starts_with("channels: not taken by `plan`"), "{e}");
        let r = Physical {
            resolution: Some(-1.0),
            ..Physical::DEFAULT
        };
        assert_eq!(r.channels().unwrap_err().param(), Some("resolution"));
        let text = "wavelength_lo_um,wavelength_hi_um,response\n2.1,2.2,1\n2.15,2.3,1\n";
        let csv = Physical {
            channels_csv: Some(ChannelsFile::new(Path::new("c.csv"), text.into())),
            ..Physical::DEFAULT
        };
        let e = csv.channels().unwrap_err();
        assert_eq!(e.param(), Some("channels_csv"));
        assert!(e.to_string().contains("c.csv: "), "{e}");
    }
}
