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
pub mod channels;
pub mod claims;
pub mod common;
pub mod estimate;
pub mod flags;
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
pub mod targets;
pub mod vectors;

use std::io::IsTerminal;
use std::process::ExitCode;
use v2ref_core::Error;

/// Exit status for bad input.
pub const EXIT_BAD_INPUT: u8 = 2;

/// The flag that sets the library parameter `param`: `--` and its keyword
/// ([`v2ref_commands::parameters::keyword_of`]) with `_` as `-`.
pub fn flag_of(param: &str) -> String {
    format!(
        "--{}",
        v2ref_commands::parameters::keyword_of(param).replace('_', "-")
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

/// The command line with each negative number that follows a `--flag`
/// joined to it (`--dec-deg -1e-3` read as `--dec-deg=-1e-3`). clap's
/// `allow_negative_numbers` takes `-1e3` but not an exponent with a sign
/// (its test of a number, in clap_lex, allows digits, one `.` and one
/// `e` only), so `-1e-3` was split into the short flags `-1`, `-e`, ...
/// and refused as an unexpected argument. Joined, the value is the flag's
/// whatever it starts with, and its own parser checks it.
pub fn negative_numbers_joined(
    args: impl IntoIterator<Item = std::ffi::OsString>,
) -> Vec<std::ffi::OsString> {
    let mut out: Vec<std::ffi::OsString> = Vec::new();
    for arg in args {
        let negative_number = arg
            .to_str()
            .and_then(|a| a.strip_prefix('-'))
            .is_some_and(|rest| {
                rest.starts_with(|c: char| c.is_ascii_digit() || c == '.')
                    && rest.parse::<f64>().is_ok()
            });
        let after_flag = out
            .last()
            .and_then(|f| f.to_str())
            .is_some_and(|f| f.len() > 2 && f.starts_with("--") && !f.contains('='));
        if negative_number && after_flag && out.len() > 1 {
            let flag = out.pop().expect("a flag before");
            let mut joined = flag;
            joined.push("=");
            joined.push(&arg);
            out.push(joined);
        } else {
            out.push(arg);
        }
    }
    out
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
/// The number is read exactly, as decimal digits: `1.5`, and `1.0000000000000001`
/// (which a float would round to 1), are refused, not rounded.
pub fn count_u64(s: &str) -> Result<u64, String> {
    const ACCEPTED: &str = "expected a whole number >= 0, for example 1000000 (or 1e6)";
    let t = s.trim().replace('_', "");
    if let Ok(n) = t.parse::<u64>() {
        return Ok(n);
    }
    match exact_whole(&t) {
        Some(Ok(n)) => Ok(n),
        Some(Err(())) => Err(format!(
            "{t} is too large; a whole number up to {}",
            u64::MAX
        )),
        None => Err(format!("{t}: {ACCEPTED}")),
    }
}

/// `t` (`DIGITS[.DIGITS][e[+-]DIGITS]`) as a whole number, read in
/// decimal: None when it is not one (a fraction, a sign, not a number),
/// `Some(Err)` when it is beyond `u64`.
fn exact_whole(t: &str) -> Option<Result<u64, ()>> {
    let (mantissa, exp) = match t.find(['e', 'E']) {
        Some(i) => (&t[..i], t[i + 1..].parse::<i64>().ok()?),
        None => (t, 0),
    };
    let (int, frac) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let all_digits = |p: &str| p.bytes().all(|b| b.is_ascii_digit());
    if int.len() + frac.len() == 0 || !all_digits(int) || !all_digits(frac) {
        return None;
    }
    let digits = format!("{int}{frac}");
    let digits = digits.trim_start_matches('0');
    if digits.is_empty() {
        return Some(Ok(0));
    }
    // The value is digits × 10^scale.
    let scale = exp.checked_sub(frac.len() as i64)?;
    let whole = if scale < 0 {
        let cut = usize::try_from(-scale).ok()?;
        let kept = digits.len().checked_sub(cut)?;
        if !digits[kept..].bytes().all(|b| b == b'0') {
            return None;
        }
        digits[..kept].to_owned()
    } else if (digits.len() as i64).saturating_add(scale) > 20 {
        return Some(Err(()));
    } else {
        format!("{digits}{}", "0".repeat(scale as usize))
    };
    Some(whole.parse::<u64>().map_err(|_| ()))
}

/// [`count_u64`] as a `usize`.
pub fn count_usize(s: &str) -> Result<usize, String> {
    let n = count_u64(s)?;
    usize::try_from(n).map_err(|_| format!("{n} is too large for this machine"))
}

/// Parses `--threads` (clap value parser): 0 (all cores) up to
/// [`v2ref_core::montecarlo::max_threads`]; the answer does not depend on it.
pub fn thread_count(s: &str) -> Result<usize, String> {
    let n = count_usize(s)?;
    v2ref_core::montecarlo::check_threads(n).map_err(|e| e.detail())
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

/// Whether progress bars should be drawn: stderr is a terminal that moves
/// its cursor (not `TERM=dumb`: the bar is redrawn with escape codes, which
/// such a terminal prints as they are) and the user did not ask for quiet.
/// Where none is drawn, a long run is announced in one plain line instead
/// ([`output::watch_rate`]).
pub fn show_progress(quiet: bool) -> bool {
    let dumb = std::env::var_os("TERM").is_some_and(|t| t == "dumb");
    !quiet && !dumb && std::io::stderr().is_terminal()
}

/// A progress bar over `len` steps, hidden when not [`show_progress`].
pub fn progress_bar(len: u64, quiet: bool, what: &str) -> indicatif::ProgressBar {
    if !show_progress(quiet) {
        let bar = indicatif::ProgressBar::hidden();
        bar.set_length(len);
        // A warning that the run will take long, not progress: said under
        // --quiet too.
        output::watch_rate(&bar, what);
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
