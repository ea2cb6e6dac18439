//! The functions of `v2ref._v2ref`: one per CLI command, each building the
//! same answer as the command (`src/cli/<command>.rs`) from the same
//! library calls.
//!
//! By concern: `paper.rs` answers the paper's effects one at a time
//! (`bias`, `snr`, `piston`, `claims`); `simulator.rs` the end-to-end
//! simulator and the conformance kit (`simulate`, `synthesize`, `estimate`,
//! `score`), `dispersed.rs` its dispersed sets (rows, C, N); `plan.rs` the planner (`plan`, `photon_rate`); `data.rs`
//! checks the arrays and sidecars they are given. The enum arguments and
//! the answers are parsed and built here.

mod data;
mod dispersed;
pub(crate) mod paper;
pub(crate) mod plan;
pub(crate) mod powered;
pub(crate) mod simulator;
mod targets;

use super::ok;
use crate::conformance::estimate::BiasConvention;
use crate::error::Result;
use crate::formalism::estimator::BinWindow;
use crate::noise::Formula;
use crate::words::Words;
use pyo3::prelude::*;

/// The `bins` argument.
fn window(s: &str) -> Result<BinWindow> {
    BinWindow::from_word("bins", s)
}

/// The `bias` argument.
fn convention(s: &str) -> Result<BiasConvention> {
    BiasConvention::from_word("bias", s)
}

/// The `formula` argument.
fn formula(s: &str) -> Result<Formula> {
    Formula::from_word("formula", s)
}

/// `check_threads`: a thread count checked as `--threads` is (0 to
/// `montecarlo::max_threads()`).
#[pyfunction]
fn check_threads(threads: usize) -> PyResult<usize> {
    ok(crate::montecarlo::check_threads(threads))
}

/// Adds the functions to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(check_threads, m)?)?;
    m.add_function(wrap_pyfunction!(plan::photon_rate, m)?)?;
    m.add_function(wrap_pyfunction!(plan::plan, m)?)?;
    m.add_function(wrap_pyfunction!(targets::plan_targets, m)?)?;
    m.add_function(wrap_pyfunction!(targets::_targets_rows, m)?)?;
    m.add_function(wrap_pyfunction!(simulator::estimate, m)?)?;
    m.add_function(wrap_pyfunction!(simulator::synthesize, m)?)?;
    m.add_function(wrap_pyfunction!(powered::powered_set, m)?)?;
    m.add_function(wrap_pyfunction!(powered::_powered_rows, m)?)?;
    m.add_function(wrap_pyfunction!(simulator::simulate, m)?)?;
    m.add_function(wrap_pyfunction!(paper::bias, m)?)?;
    m.add_function(wrap_pyfunction!(paper::snr, m)?)?;
    m.add_function(wrap_pyfunction!(paper::piston, m)?)?;
    m.add_function(wrap_pyfunction!(paper::claims, m)?)?;
    m.add_function(wrap_pyfunction!(simulator::score, m)?)?;
    m.add_function(wrap_pyfunction!(dispersed::score_channels_answer, m)?)?;
    Ok(())
}
