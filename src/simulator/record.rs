//! Where the records of what a computation was asked were first defined;
//! their home is [`crate::record`]. Kept, crate-private, for the import of
//! `crate::parameters`.

pub(crate) use crate::record::{AtmosphereRecord, ObservationRecord};
