//! §6 of the paper, *Effect of differential piston*: the turbulence and the
//! differential-piston spectrum, piston sequences, scans through them, and
//! the Monte Carlo of the bias and scatter they give V1 and V2.

pub mod simulation;
pub mod turbulence;

pub use simulation::*;
