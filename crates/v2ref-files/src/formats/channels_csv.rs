//! The channel CSV file of `--channels-csv` / `channels_csv`, read at the
//! edges as every input file is (without waiting, a regular file only,
//! within [`MAX_CHANNELS_CSV_BYTES`]); its table is parsed against the
//! configuration's spectrum by `Physical::channels`.

use crate::error::Result;
use crate::parameters::{ChannelsFile, MAX_CHANNELS_CSV_BYTES};
use std::path::Path;

/// The text of the channel CSV file at `path`, with its name; a refusal
/// names `channels_csv`.
pub fn read_channels_file(path: &Path) -> Result<ChannelsFile> {
    let accepted = "a CSV of at most 4096 channels";
    let text = super::read_text(path, "channels_csv", MAX_CHANNELS_CSV_BYTES, accepted)?;
    Ok(ChannelsFile::new(path, text))
}
