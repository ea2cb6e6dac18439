//! §2 of the paper, *General formalism*: the source and its spectrum, the
//! observation, the interferogram it produces (continuous and sampled), and
//! the two estimators computed from it; with the introduction's dynamic
//! range and the slow oracles beside the fast paths.

pub mod channels;
pub mod dynamic_range;
pub mod estimator;
pub mod interferogram;
pub mod observation;
pub mod oracle;
pub mod phase;
pub mod source;
pub mod spectrum;
