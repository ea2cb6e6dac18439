//! The records of what a computation was asked (the `inputs` object of
//! the JSON answers), at their home, [`crate::record`], below the
//! paper's effects that carry them; re-exported here, where they were
//! first defined.

pub use crate::record::{
    AtmosphereRecord, InputsRecord, ObservationRecord, OuterScale, SamplingRecord,
};
