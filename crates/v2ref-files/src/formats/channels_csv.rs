//! The channel CSV file of `--channels-csv` / `channels_csv`, read at the
//! edges as every input file is (without waiting, a regular file only,
//! within [`MAX_CHANNELS_CSV_BYTES`]); its table is parsed against the
//! configuration's spectrum by `Physical::channels` (v2ref-commands), to
//! which the edges hand the text.

use crate::error::Result;
use std::path::Path;

/// Largest channel CSV file read, bytes: 4096 rows of three numbers take
/// well under 1 MiB; a longer file (or `/dev/zero`) is refused at once.
pub const MAX_CHANNELS_CSV_BYTES: u64 = 1 << 20;

/// The text of the channel CSV file at `path`; a refusal names
/// `channels_csv`.
pub fn read_channels_text(path: &Path) -> Result<String> {
    let accepted = "a CSV of at most 4096 channels";
    super::read_text(path, "channels_csv", MAX_CHANNELS_CSV_BYTES, accepted)
}
