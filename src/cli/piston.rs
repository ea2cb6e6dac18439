//! `v2ref piston` (placeholder until its issue lands).

use std::process::ExitCode;
use v2ref::Result;

/// Flags of `piston`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Runs `piston`.
pub fn run(_args: Args) -> Result<ExitCode> {
    eprintln!("error: v2ref piston is not implemented yet");
    Ok(ExitCode::from(super::EXIT_BAD_INPUT))
}
