//! The engine seam: what the runner drives, whichever engine fills the snapshot.
//!
//! rapier (`crate::simulation::AnySimulation`, f32 or f64) and Box2D (`sim::box2d`) each
//! implement [`Drive`]; the runner picks one at its entry (`runner::engine_for`) and everything
//! after it (checks, questions, challenge, report) reads only the snapshots.

use crate::level::Level;
use crate::sim::{Settings, SimError};
use crate::snapshot::Snapshot;

/// A simulation of one level that the runner can drive to its end.
pub trait Drive {
    /// The level being run (it does not change during a run).
    fn level(&self) -> &Level;
    /// The run's resolved settings.
    fn settings(&self) -> &Settings;
    /// The settings as a report states them (how the steps so far were called).
    fn settings_as_run(&self) -> Settings;
    /// Whether snapshots carry the step's contacts.
    fn set_contact_readings(&mut self, on: bool);
    /// The state after the last step (or the initial state).
    fn snapshot(&self) -> &Snapshot;
    /// Runs the whole duration, calling `each` with every snapshot (the initial one first).
    fn run_each(&mut self, each: &mut dyn FnMut(&Snapshot)) -> Result<(), SimError>;
}
