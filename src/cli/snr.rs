//! `v2ref snr` (placeholder until its issue lands).

use std::process::ExitCode;
use v2ref::Result;

/// Flags of `snr`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Runs `snr`.
pub fn run(_args: Args) -> Result<ExitCode> {
    eprintln!("error: v2ref snr is not implemented yet");
    Ok(ExitCode::from(super::EXIT_BAD_INPUT))
}
