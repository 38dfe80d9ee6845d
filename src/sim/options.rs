//! Engine-independent parts of the simulation stage: options, effect sets, errors.

use crate::level::{Effect, Level};
use crate::snapshot::Snapshot;

/// Overrides of the level's solver settings (CLI flags, studies).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Options {
    pub dt: Option<f64>,
    pub substeps: Option<usize>,
    pub solver_iterations: Option<usize>,
    /// Run every stage (colliders in collision detection, CCD, sleeping, ...) for comparison.
    pub all_effects: bool,
    /// How substeps are taken (None: split where springs or joints need it, see `Settings`).
    pub substepping: Option<crate::sim::Substepping>,
    /// The engine's floating point (None: the level's `world.precision`). Read by
    /// [`crate::simulation::AnySimulation`], which builds the engine of that precision.
    pub precision: Option<crate::level::Precision>,
    /// Cut rapier's calls at times of impact (None: where the scene allows, see
    /// `Settings::impact_cuts`); `Some(false)` measures rapier's own speculative contacts.
    pub impact_cuts: Option<bool>,
    /// The engine (None: the level's `world.engine`). Read at the runner's entry
    /// (`runner::run_graded`, `runner::run_scene`), which builds that engine's simulation.
    pub engine: Option<crate::level::PhysicsEngine>,
    /// When a step in which a spinning ball touches something is split into one-substep calls
    /// (sim/contact_points.rs): by the rule (the default), or always and never, to measure the
    /// rule against the one-substep reference and the cost before the spinning fix.
    pub spin_split: SpinSplit,
}

/// When a step in which a spinning ball touches something is split into several rapier calls
/// (sim/contact_points.rs, `spin_calls`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum SpinSplit {
    /// Where the turn's residual over one call would disturb the contact: past 1.5 sags of the
    /// contact under its load, or where a question reads a contact's start, end or slip, past
    /// half a sag times the friction's margin.
    #[default]
    Rule,
    /// Every step in which a ball spinning with r w^2 >= 1e-3 g touches something (the rule of
    /// 2026-11-27 to 2026-12-06).
    Always,
    /// Never for spin: one call a step, as before 2026-11-27 (the spin's normal speed is still
    /// handed to rapier).
    Never,
}

/// The set of effects a world was built with.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Effects(Vec<Effect>);

impl Effects {
    pub fn of(level: &Level, all: bool) -> Self {
        if all {
            Effects(Effect::ALL.to_vec())
        } else {
            let mut e = level.effects.clone();
            e.sort();
            Effects(e)
        }
    }
    pub fn has(&self, e: Effect) -> bool {
        self.0.contains(&e)
    }
    pub fn names(&self) -> Vec<String> {
        self.0.iter().map(|e| e.name().to_string()).collect()
    }
}

/// A run that went wrong: a non-finite state or an explosion.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("step {step} (t = {time:.4} s): body \"{body}\" {quantity}")]
pub struct SimError {
    pub step: u64,
    pub time: f64,
    pub body: String,
    pub quantity: String,
}

/// What every precision's `Simulation` offers, so studies can drive f32 and f64 side by side.
pub trait Engine {
    fn step(&mut self) -> Result<&Snapshot, SimError>;
    fn snapshot(&self) -> &Snapshot;
    fn dt(&self) -> f64;
    fn total_steps(&self) -> u64;
}
