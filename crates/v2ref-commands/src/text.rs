//! Text from data made safe to show: [`printable`] (in `v2ref-core`, where
//! the target list's reader uses it too).

pub use v2ref_core::text::printable;
