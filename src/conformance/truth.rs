//! The truth of a synth set (placeholder).
