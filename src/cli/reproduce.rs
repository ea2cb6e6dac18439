//! `v2ref reproduce` (placeholder until its issue lands).

use std::process::ExitCode;
use v2ref::Result;

/// Flags of `reproduce`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Runs `reproduce`.
pub fn run(_args: Args) -> Result<ExitCode> {
    eprintln!("error: v2ref reproduce is not implemented yet");
    Ok(ExitCode::from(super::EXIT_BAD_INPUT))
}
