//! Stage 4b: questions, an exercise's asked quantity read from the run and compared with the
//! expected answer.
//!
//! Each question is read twice at the moment its `at` names:
//! - `engine`: the engine's own motion and reactions (positions, velocities, finite
//!   differences, the impulses rapier applied);
//! - `analysis`: the textbook formula for the quantity (documented on each
//!   [`Quantity`](crate::level::Quantity) variant) applied to the engine's state: its mass
//!   properties, pose and, for impacts and blows, its velocities just before. Where a quantity
//!   has no independent formula the analysis is `None`.
//!
//! A question passes on the engine value (the exercise grades the engine against the textbook);
//! the analysis value shows whether a miss is the engine's or the exercise's.
//!
//! Where things are:
//! - `probe`: [`QuestionProbe`], which watches the run and decides *when* to read (a time, an
//!   extreme, a crossing, a contact event, a blow);
//! - `dispatch`: the dispatcher, routing a quantity to its family with the meter and the
//!   family's state;
//! - the families, each owning its state over the run (its `State`) and how its quantities are
//!   accumulated and read: `motion`, `forces` (with the engine's free-body diagram in
//!   `free_body` and the force on an arc in `curved_contact`), `work_and_power`, `periods`,
//!   `rolling`, `impacts` (with the impulse-momentum solutions in `impact_solution`) and
//!   `linkages`;
//! - `meter`: what every quantity's meter holds whatever its family (the quantity, the level's
//!   facts, why its analysis does not apply);
//! - `contact_events`: the first contact of a pair, from touch to release;
//! - `level_facts`: what a question needs from the level beyond the snapshots;
//! - `sample`: the snapshots around a sample, and what a reading is;
//! - `snapshot_reading`, `contact_reading` and `step_work`: small readings of a snapshot, of a
//!   contact and of a step's work that the families share;
//! - `result`: the result a question reports, and grading a student's answer.
//!
//! Imports run one way: `probe` -> `dispatch` -> the families -> the shared types, with no
//! circle (tests/suite/docs/app_import_rule.rs); a family never imports another family, so
//! what two families share goes below both.
//!
//! Adding a quantity: its variant in `level/format/exercise.rs` (with its [`QuantityFamily`]),
//! its references in `level/validate/exercise.rs`, its reading in its family's file, and a
//! question with a known answer that asks it (tests/suite/questions/quantity_coverage.rs looks for one).
//!
//! [`QuantityFamily`]: crate::level::QuantityFamily

pub mod challenge;
mod contact_events;
mod contact_reading;
mod curved_contact;
mod dispatch;
mod forces;
mod free_body;
mod free_flight;
mod impact_solution;
mod impacts;
mod instants;
mod leaving;
pub mod level_facts;
mod linkages;
mod meter;
mod motion;
mod periods;
mod probe;
mod reference_forces;
mod result;
mod rolling;
mod sample;
mod snapshot_reading;
mod step_work;
pub mod units;
mod work_and_power;

pub use challenge::{ChallengeProbe, ChallengeResult};
pub use level_facts::LevelFacts;
pub use probe::{initial_in_f64, QuestionProbe};
pub use result::{grade_answer, QuestionResult, StudentGrade, CANNOT_BE_READ};
