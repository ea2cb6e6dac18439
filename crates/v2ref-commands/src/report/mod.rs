//! The reports the commands' answers hold: what a run of `bias`, `snr`,
//! `simulate` and `piston` found, with the inputs it was asked.

pub mod bias;
pub mod channels;
pub mod model_comparison;
pub mod noise;
pub mod piston;
pub mod simulator;
