//! Stage 2 of the data flow: scene -> rapier world -> per-step snapshots.
//!
//! The world holds only what the level's `effects` call for (or everything
//! with `Options::all_effects`). Springs, loads and impulses are applied by
//! rigidlab itself so that their forces and work are known exactly. After each
//! step the engine state is copied into a plain-f64 [`Snapshot`](crate::snapshot::Snapshot).
//!
//! Box2D v3 is a second engine behind the same snapshot (`box2d/`, compiled once); the runner
//! drives either through [`Drive`] (`seam.rs`).
//!
//! The files in this folder are compiled twice: here against rapier2d (f32),
//! and as `crate::sim64` against rapier2d-f64, through the `rapier` alias.

pub(crate) use rapier2d as rapier;
/// The precision this copy of the stage is compiled for.
pub(crate) const PRECISION: crate::snapshot::Precision = crate::snapshot::Precision::F32;

pub mod angles;
mod arc_contacts;
mod arc_curvature;
mod arc_split;
mod arc_track;
pub mod box2d;
mod build;
mod contact_points;
mod coupling_tension;
mod couplings;
pub mod describe;
pub mod explosion_guard;
mod impacts;
mod interventions;
mod joint_sums;
pub mod joints;
pub mod options;
mod probes;
pub mod profiles;
mod readings;
pub mod seam;
pub mod settings;
mod setup;
mod step;
mod track_shape;
mod welds;
mod world;

pub use crate::snapshot::Precision;
pub use build::{capsule_inertia_shortfall, mass_properties, shared_shape, DEFAULT_DENSITY};
pub use options::{Effects, Engine, Options, SimError, SpinSplit};
pub use profiles::{scalar_profile_at, vector_profile_at};
pub use seam::Drive;
pub use settings::{Settings, StepCalls, Substepping};
pub use world::Simulation;
