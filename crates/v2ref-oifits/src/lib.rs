//! OIFITS, the exchange format of optical interferometry (Pauls et al.
//! 2005, PASP 117, 1255; version 2: Duvert, Young & Hummel 2017, A&A 597,
//! A8): squared visibilities written as OIFITS v2 (module `write`) and read
//! from OIFITS v1 or v2 (`read`).
//!
//! **Writing is safe Rust** (`fits_write.rs`): the cards laid out as
//! cfitsio (NASA HEASARC's reference implementation, which wrote these
//! files before) lays them out, binary tables, `CHECKSUM` and `DATASUM`; no
//! C compiler. A file is built in memory and written with the atomic
//! pattern of [`crate::formats::atomic`].
//!
//! **Reading is safe Rust** ([`fits`], [`table`]): every size
//! a header announces is checked against the file's bytes before a value
//! is read, and `CHECKSUM`/`DATASUM` are verified where present.
//!
//! What is written (one broadband channel: an estimate sums the band):
//! `OI_TARGET`, `OI_ARRAY` (two stations on the baseline, east–west),
//! `OI_WAVELENGTH` (effective wavelength `1/σ_eff`, width of the band's
//! support) and `OI_VIS2` (one row per interferogram), one
//! `OI_WAVELENGTH`/`OI_VIS2` pair per `INSNAME` (one per estimator). The
//! estimator, window of bins and bias convention are the keywords
//! `V2R_EST`, `V2R_BINS`, `V2R_BIAS` of each `OI_VIS2` table.
//!
//! **Spectral channels** (`NWAVE` = C, [`docs::estimates_doc_channels`],
//! [`Setting::with_channels`]): `OI_WAVELENGTH` holds one row per channel
//! of the set, in its order (increasing wavenumber, so `EFF_WAVE`
//! decreases): `EFF_WAVE = 1/σ_eff,j` and `EFF_BAND` the width in
//! wavelength of channel j's support, of its own spectrum; `VIS2DATA`,
//! `VIS2ERR` and `FLAG` hold C values per row (`TDIMn = '(C)'`,
//! `INSMODE = 'DISPERSED'`), `VIS2ERR` of channel j the closed form of
//! channel j's model. One channel over the whole band writes the broadband
//! file byte for byte.
//!
//! **Reading channels** ([`read_oifits_estimates`] given
//! [`Expected::channels_m`], the set's channels' wavelength ranges from
//! [`wavelength_ranges_m`]): every table must hold `NWAVE` = C; each
//! `EFF_WAVE` is matched to the one channel whose range holds it (slack:
//! 1e-4 of the channel's width at its ends, and at least the float32
//! rounding of `EFF_WAVE`), one per channel, in whatever order the file
//! lists them (a pipeline's decreasing wavelength included); each table
//! is matched on its own. `FLAG` is per channel: a flagged (row, channel)
//! leaves the row out of that channel only, for every estimator read
//! ([`ChannelEstimates::flagged`], and its truth
//! [`ChannelEstimates::truth_for_kept_rows`]); a channel with fewer than
//! [`min_unflagged_rows`] unflagged rows is refused. Without the set's
//! channels a table must hold `NWAVE` = 1, as before. The command line's
//! `estimate` and `score` are wired to these in a later round.

// The modules of the crates below under their own names, so that a path
// reads the same in every crate of the workspace (`crate::formats::…`).
#[allow(unused_imports)]
pub(crate) use v2ref_commands::{parameters, plan};
#[allow(unused_imports)]
pub(crate) use v2ref_core::{
    bounds, conformance, error, formalism, manifest, noise, simulator, Error, Result,
};
#[allow(unused_imports)]
pub(crate) use v2ref_files::{atomic, formats};

pub mod docs;
pub mod fits;
mod fits_write;
mod integrity;
pub(crate) mod observing;
mod order;
pub(crate) mod read;
#[cfg(test)]
mod reader_tests;
mod scored;
mod select;
mod select_channels;
pub(crate) mod setting;
pub mod table;
pub(crate) mod write;

pub use integrity::ReadOptions;
pub use observing::{iota, Site};
pub use observing::{ObservingContext, ObservingSpec};
pub use order::choose_tables;
pub use read::{parse_oifits, read_oifits_file, read_vis2_tables, OifitsFile, Vis2Table};
pub use scored::{
    min_unflagged_rows, truth_for_kept_rows, wavelength_ranges_m, ChannelEstimates, Expected,
    OifitsEstimates,
};
pub use select::{read_oifits_estimates, Choice};
pub use setting::Setting;
pub use write::{to_bytes, write_oifits, Key, KeyValue, OifitsDoc, Vis2Out};

use std::path::Path;

/// The extensions of a FITS file (lower case, without the dot).
pub const FITS_EXTENSIONS: [&str; 3] = ["fits", "oifits", "fit"];

/// True when `path` ends in one of [`FITS_EXTENSIONS`] (any case),
/// possibly followed by `.gz` (a gzipped file, read and written as such).
pub fn is_fits_path(path: &Path) -> bool {
    let plain = if is_gzip_path(path) {
        path.file_stem().map(Path::new).unwrap_or(path)
    } else {
        path
    };
    plain
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .is_some_and(|e| FITS_EXTENSIONS.contains(&e.as_str()))
}

/// True when `path` ends in `.gz` (any case).
pub fn is_gzip_path(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("gz"))
}

/// Keyword naming the estimator of an `OI_VIS2` table (`V1SQ` or `V2SQ`).
pub const KEY_ESTIMATOR: &str = "V2R_EST";
/// Keyword naming the window of Fourier bins the estimates sum.
pub const KEY_BINS: &str = "V2R_BINS";
/// Keyword naming the bias convention the estimates subtract.
pub const KEY_BIAS: &str = "V2R_BIAS";

/// The value of [`KEY_ESTIMATOR`] for an estimator.
pub fn estimator_key(e: crate::conformance::score::Estimator) -> &'static str {
    e.pick("V1SQ", "V2SQ")
}

/// The default `INSNAME` of an estimator's tables.
pub fn default_insname(e: crate::conformance::score::Estimator) -> &'static str {
    e.pick("V2REF_V1SQ", "V2REF_V2SQ")
}

/// Refuses (parameter `param`) a path whose extension is not a FITS one:
/// an OIFITS file is never written under a `.csv` or `.npy` name.
pub fn check_fits_extension(path: &Path, param: &'static str) -> Result<()> {
    if is_fits_path(path) {
        return Ok(());
    }
    let ext = path
        .extension()
        .map(|e| format!(".{}", e.to_string_lossy()))
        .unwrap_or_else(|| "no extension".into());
    Err(Error::data(
        param,
        path,
        "",
        format!("{ext}; an OIFITS file is written as .fits, .oifits or .fit (each possibly .gz)"),
    ))
}

/// Writes a plan's predicted observation at its recommended setting
/// (`plan --oifits`, Python's `plan(oifits=...)`), where and when
/// `observing` says; `param` names the file. False, and nothing written,
/// when no setting reaches the target: the plan itself says so, and is no
/// less an answer (same exit status).
pub fn write_plan(
    path: &Path,
    param: &'static str,
    (inputs, plan): (&crate::plan::PlanInputs, &crate::plan::Plan),
    observing: &ObservingContext,
) -> Result<bool> {
    let Some(point) = plan.recommended.as_ref() else {
        return Ok(false);
    };
    write_oifits(path, param, &docs::plan_doc(inputs, point, observing)?)?;
    Ok(true)
}
