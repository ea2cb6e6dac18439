//! (placeholder: filled by the score work)
