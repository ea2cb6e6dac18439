//! Subcommands of the `v2ref` binary, one file each, and what they share.

/// `println!` whose failure is checked ([`output::write_stdout_line`]):
/// quiet status 0 when the reader closed the pipe early
/// (`v2ref claims | head`), one line and a non-zero status otherwise.
macro_rules! outln {
    () => {
        $crate::cli::output::write_stdout_line(format_args!(""))
    };
    ($($arg:tt)*) => {
        $crate::cli::output::write_stdout_line(format_args!($($arg)*))
    };
}

/// `eprintln!` that does not panic when stderr cannot be written.
macro_rules! errln {
    ($($arg:tt)*) => {
        $crate::cli::output::write_stderr_line(format_args!($($arg)*))
    };
}

pub mod bias;
pub mod claims;
pub mod common;
pub mod estimate;
pub mod flags;
#[cfg(test)]
mod generated;
pub mod golden;
pub mod grid;
pub mod inputs;
pub mod instrument;
pub mod memory;
pub mod oifits;
pub mod output;
pub mod piston;
pub mod piston_observation;
pub mod plan;
pub mod plan_svg;
pub mod plan_verify;
pub mod reproduce;
pub mod score;
pub mod signals;
pub mod simulate;
pub mod snr;
pub mod synth;
pub mod vectors;

use std::io::IsTerminal;
use std::process::ExitCode;
use v2ref::Error;

/// Exit status for bad input.
pub const EXIT_BAD_INPUT: u8 = 2;

/// The flag that sets the library parameter `param`: `--` and its keyword
/// ([`v2ref::parameters::keyword_of`]) with `_` as `-`.
pub fn flag_of(param: &str) -> String {
    format!(
        "--{}",
        v2ref::parameters::keyword_of(param).replace('_', "-")
    )
}

/// Prints a library error as one line naming the flag
/// (`error: --flag: detail`, or `error: detail` where the error names no
/// parameter), and returns its status ([`output::exit_status`]: 2 for bad
/// input, 74 for an output that cannot be written).
pub fn fail(e: &Error) -> ExitCode {
    let line = match e.param() {
        Some(p) => format!("{}: {}", flag_of(p), e.detail()),
        None => e.detail(),
    };
    // A reader that closed the pipe early is told nothing (see output).
    if !output::is_broken_pipe(e) {
        errln!("error: {}", line.replace('\n', " "));
    }
    ExitCode::from(output::exit_status(e))
}

/// Handles a clap parse error: help and version print normally (status 0);
/// anything else prints its first line and returns status 2.
pub fn clap_error(e: clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => {
            // Help goes to stdout, checked like every other output.
            outln!("{}", e.render().to_string().trim_end());
            ExitCode::SUCCESS
        }
        ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            // A bare `v2ref`: the usage and the list of commands, on stderr
            // (it is not the answer to a request), status 2.
            errln!("{}", e.render().to_string().trim_end());
            ExitCode::from(EXIT_BAD_INPUT)
        }
        _ => {
            errln!("{}", first_paragraph(&e.to_string()));
            ExitCode::from(EXIT_BAD_INPUT)
        }
    }
}

/// The first paragraph of a clap message on one line: the line itself, and
/// when it ends with `:` the indented lines that follow (the missing
/// flags), so that the line names them.
fn first_paragraph(text: &str) -> String {
    let mut lines = text.lines();
    let mut line = lines.next().unwrap_or("error: bad arguments").to_owned();
    if line.ends_with(':') {
        for more in lines.take_while(|l| l.starts_with(' ')) {
            line.push(' ');
            line.push_str(more.trim());
        }
    }
    line
}

/// Parses a finite f64 (clap value parser).
pub fn finite_f64(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err("expected a finite number".into()),
    }
}

/// Parses a count (clap value parser): a whole number such as `1000000`,
/// also written `1e6` or `1_000_000`; a refusal says what is accepted.
pub fn count_u64(s: &str) -> Result<u64, String> {
    let t = s.trim().replace('_', "");
    if let Ok(n) = t.parse::<u64>() {
        return Ok(n);
    }
    // Scientific notation of an exact whole number up to 2^53 (where every
    // whole f64 is exact).
    match t.parse::<f64>() {
        Ok(x) if x >= 0.0 && x.fract() == 0.0 && x <= 2f64.powi(53) => Ok(x as u64),
        Ok(x) if x.is_finite() && x > 2f64.powi(53) => Err(format!(
            "{x:e} is too large; a whole number up to 9007199254740992 (2^53)"
        )),
        _ => Err("expected a whole number >= 0, for example 1000000 (or 1e6)".into()),
    }
}

/// [`count_u64`] as a `usize`.
pub fn count_usize(s: &str) -> Result<usize, String> {
    let n = count_u64(s)?;
    usize::try_from(n).map_err(|_| format!("{n} is too large for this machine"))
}

/// Parses `--threads` (clap value parser): 0 (all cores) up to
/// [`v2ref::montecarlo::max_threads`]; the answer does not depend on it.
pub fn thread_count(s: &str) -> Result<usize, String> {
    let n = count_usize(s)?;
    v2ref::montecarlo::check_threads(n).map_err(|e| e.detail())
}

/// Prints `value` as one pretty JSON document on stdout.
pub fn print_json<T: serde::Serialize>(value: &T) {
    match serde_json::to_string_pretty(value) {
        Ok(s) => outln!("{s}"),
        Err(e) => errln!("error: cannot serialize the answer: {e}"),
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
        let bar = indicatif::ProgressBar::hidden();
        bar.set_length(len);
        if !quiet {
            output::watch_cost(&bar, what);
        }
        return bar;
    }
    let bar = indicatif::ProgressBar::new(len);
    if let Ok(style) =
        indicatif::ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} ({eta} left)")
    {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_message(what.to_owned());
    output::steady_tick(&bar, std::time::Duration::from_millis(150));
    bar
}

/// A spinner for work without countable steps, hidden when not
/// [`show_progress`]. Call `finish_and_clear` when done.
pub fn spinner(quiet: bool, what: &str) -> indicatif::ProgressBar {
    if !show_progress(quiet) {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new_spinner();
    if let Ok(style) = indicatif::ProgressStyle::with_template("{spinner} {msg} ({elapsed} so far)")
    {
        bar.set_style(style);
    }
    bar.set_message(what.to_owned());
    output::steady_tick(&bar, std::time::Duration::from_millis(120));
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
        assert_eq!(flag_of("truth"), "--sidecar");
    }
}
