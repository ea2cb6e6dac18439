//! `v2ref golden` (placeholder until its issue lands).

use std::process::ExitCode;
use v2ref::Result;

/// Flags of `golden`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Runs `golden`.
pub fn run(_args: Args) -> Result<ExitCode> {
    eprintln!("error: v2ref golden is not implemented yet");
    Ok(ExitCode::from(super::EXIT_BAD_INPUT))
}
