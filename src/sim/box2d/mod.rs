//! A second engine behind the same snapshot: Box2D v3 through the `boxdd` crate.
//!
//! [`Simulation::new`] builds a Box2D world from the part of a level `support.rs` lets through
//! (anything else is refused with its place in the file, never run wrong), steps it at the
//! level's dt and substeps, and fills the plain-f64 [`Snapshot`](crate::snapshot::Snapshot) the analysis reads, as the
//! rapier stage does. One rigidlab step of `substeps` substeps is `substeps` Box2D calls of one
//! substep each, so that every impulse Box2D applies is read whole (docs/box2d-readings.md):
//! Box2D keeps a contact's and a joint's accumulated impulse of the last substep only.
//!
//! Native builds with the `box2d` feature only (`support.rs`, which refuses, builds everywhere);
//! Box2D types stay in this folder.

#[cfg(all(feature = "box2d", not(target_arch = "wasm32")))]
mod build;
#[cfg(all(feature = "box2d", not(target_arch = "wasm32")))]
mod read;
#[cfg(all(feature = "box2d", not(target_arch = "wasm32")))]
mod step;
pub mod support;
#[cfg(all(feature = "box2d", not(target_arch = "wasm32")))]
mod thread;
#[cfg(all(feature = "box2d", not(target_arch = "wasm32")))]
mod world;

pub use support::{not_built, refusal, Refusal};
#[cfg(all(feature = "box2d", not(target_arch = "wasm32")))]
pub use thread::Threaded;
#[cfg(all(feature = "box2d", not(target_arch = "wasm32")))]
pub use world::Simulation;
