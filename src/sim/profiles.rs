//! Time tables of loads, read by the step: the level's own interpolation (`level/profiles.rs`).

pub use crate::level::profiles::{scalar_profile_at, vector_profile_at};
