//! `v2ref simulate` (placeholder until its issue lands).

use std::process::ExitCode;
use v2ref::Result;

/// Flags of `simulate`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Runs `simulate`.
pub fn run(_args: Args) -> Result<ExitCode> {
    eprintln!("error: v2ref simulate is not implemented yet");
    Ok(ExitCode::from(super::EXIT_BAD_INPUT))
}
