//! Subcommands of the `v2ref` binary, one file each, and what they share.

/// `println!` that ends the process quietly (status 0) when stdout is
/// closed early (`v2ref claims | head`), instead of panicking.
macro_rules! outln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        if writeln!(std::io::stdout().lock(), $($arg)*).is_err() {
            std::process::exit(0);
        }
    }};
}

pub mod bias;
pub mod claims;
pub mod common;
pub mod estimate;
pub mod files;
pub mod golden;
pub mod grid;
pub mod inputs;
pub mod piston;
pub mod plan;
pub mod plan_svg;
pub mod reproduce;
pub mod score;
pub mod simulate;
pub mod snr;
pub mod synth;
pub mod vectors;

use std::io::IsTerminal;
use std::process::ExitCode;
use v2ref::Error;

/// Exit status for bad input.
pub const EXIT_BAD_INPUT: u8 = 2;

/// Library parameter names (Rust names, snake_case) whose flag is not
/// `--` + the name with `_` turned into `-`.
const FLAG_OF_PARAM: &[(&str, &str)] = &[
    ("spectrum", "--spectrum-csv"),
    ("peak_to_peak_rad", "--dispersion-pp-rad"),
    ("photons_per_sample", "--photons"),
    ("truth", "--sidecar"),
];

/// The flag that sets the library parameter `param`: an entry of
/// [`FLAG_OF_PARAM`], else `--` + `param` with `_` (or a legacy `-`) as `-`.
pub fn flag_of(param: &str) -> String {
    FLAG_OF_PARAM
        .iter()
        .find(|(p, _)| *p == param.replace('-', "_"))
        .map_or_else(
            || format!("--{}", param.replace('_', "-")),
            |(_, f)| (*f).to_owned(),
        )
}

/// Prints a library error as one line naming the flag
/// (`error: --flag: detail`, or `error: detail` where the error names no
/// parameter), and returns status 2.
pub fn fail(e: &Error) -> ExitCode {
    let line = match e.param() {
        Some(p) => format!("{}: {}", flag_of(p), e.detail()),
        None => e.detail(),
    };
    eprintln!("error: {}", line.replace('\n', " "));
    ExitCode::from(EXIT_BAD_INPUT)
}

/// Handles a clap parse error: help and version print normally (status 0);
/// anything else prints its first line and returns status 2.
pub fn clap_error(e: clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => {
            let _ = e.print();
            ExitCode::SUCCESS
        }
        _ => {
            let text = e.to_string();
            let first = text.lines().next().unwrap_or("error: bad arguments");
            eprintln!("{first}");
            ExitCode::from(EXIT_BAD_INPUT)
        }
    }
}

/// Parses a finite f64 (clap value parser).
pub fn finite_f64(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err("expected a finite number".into()),
    }
}

/// Prints `value` as one pretty JSON document on stdout.
pub fn print_json<T: serde::Serialize>(value: &T) {
    match serde_json::to_string_pretty(value) {
        Ok(s) => outln!("{s}"),
        Err(e) => eprintln!("error: cannot serialize the answer: {e}"),
    }
}

/// Prints aligned `name  value` rows.
pub fn print_rows(rows: &[(&str, String)]) {
    let width = rows.iter().map(|r| r.0.len()).max().unwrap_or(0);
    for (name, value) in rows {
        outln!("{name:<width$}  {value}");
    }
}

/// Whether progress bars should be drawn: stderr is a terminal and the user
/// did not ask for quiet.
pub fn show_progress(quiet: bool) -> bool {
    !quiet && std::io::stderr().is_terminal()
}

/// A progress bar over `len` steps, hidden when not [`show_progress`].
pub fn progress_bar(len: u64, quiet: bool, what: &str) -> indicatif::ProgressBar {
    if !show_progress(quiet) {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(len);
    if let Ok(style) =
        indicatif::ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} ({eta} left)")
    {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_message(what.to_owned());
    bar.enable_steady_tick(std::time::Duration::from_millis(150));
    bar
}

/// A spinner for work without countable steps, hidden when not
/// [`show_progress`]. Call `finish_and_clear` when done.
pub fn spinner(quiet: bool, what: &str) -> indicatif::ProgressBar {
    if !show_progress(quiet) {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new_spinner();
    bar.set_message(what.to_owned());
    bar.enable_steady_tick(std::time::Duration::from_millis(120));
    bar
}

#[cfg(test)]
mod tests {
    use super::flag_of;

    #[test]
    fn library_parameters_map_to_their_flags() {
        assert_eq!(flag_of("dx_um"), "--dx-um");
        assert_eq!(flag_of("read_noise"), "--read-noise");
        // Folders not yet converted still spell names with '-'.
        assert_eq!(flag_of("fringe-hz"), "--fringe-hz");
        assert_eq!(flag_of("spectrum"), "--spectrum-csv");
        assert_eq!(flag_of("photons_per_sample"), "--photons");
        assert_eq!(flag_of("peak_to_peak_rad"), "--dispersion-pp-rad");
    }
}
