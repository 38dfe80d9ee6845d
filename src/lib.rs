//! rigidlab: a 2D rigid-body sandbox that checks rapier2d against the engineering-dynamics textbook.
//!
//! Data flows one way, a module per stage:
//! `level` (file -> validated scene) -> `sim` (rapier world with only the declared
//! effects -> per-step [`snapshot::Snapshot`]) -> `analysis` (textbook quantities,
//! pure functions) -> `checks` (theory against engine) -> `report` (table, JSON, CSV).
//! The Bevy sandbox (`app`, behind the `app` feature) is a thin shell over the same core.

pub mod level;
pub mod sim;
pub mod snapshot;
