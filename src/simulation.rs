//! The simulation stage at the precision a run asks for: the level's `world.precision`, or the
//! `--precision` override. `sim` is compiled twice (rapier2d and rapier2d-f64, see
//! `sim/mod.rs`); this picks one of the two once, when the run is built, and forwards to it,
//! so the runner and the window drive either the same way.

use crate::level::{Level, Precision, Scene};
use crate::sim::{Options, Settings, SimError};
use crate::snapshot::Snapshot;
use glam::DVec2;

/// A running simulation of one level, in f32 or f64.
pub struct AnySimulation {
    /// The level (as `sim::Simulation::level`; it does not change during a run).
    pub level: Level,
    /// The run's settings, resolved once (as `sim::Simulation::settings`).
    pub settings: Settings,
    engine: Engine,
}

enum Engine {
    F32(Box<crate::sim::Simulation>),
    F64(Box<crate::sim64::Simulation>),
}

/// Forwards a call to whichever precision's simulation runs.
macro_rules! forward {
    ($self:expr, $sim:ident => $call:expr) => {
        match &$self.engine {
            Engine::F32($sim) => $call,
            Engine::F64($sim) => $call,
        }
    };
    (mut $self:expr, $sim:ident => $call:expr) => {
        match &mut $self.engine {
            Engine::F32($sim) => $call,
            Engine::F64($sim) => $call,
        }
    };
}

impl AnySimulation {
    /// rapier at the run's precision, whatever `world.engine` or `Options::engine` say: the
    /// window and the studies run rapier; the runner picks the engine (`runner::engine_for`).
    pub fn new(scene: &Scene, opts: &Options) -> Self {
        let precision = opts.precision.unwrap_or(scene.level.world.precision);
        let engine = match precision {
            Precision::F32 => Engine::F32(Box::new(crate::sim::Simulation::new(scene, opts))),
            Precision::F64 => Engine::F64(Box::new(crate::sim64::Simulation::new(scene, opts))),
        };
        let (level, settings) = match &engine {
            Engine::F32(s) => (s.level.clone(), s.settings.clone()),
            Engine::F64(s) => (s.level.clone(), s.settings.clone()),
        };
        AnySimulation {
            level,
            settings,
            engine,
        }
    }

    pub fn precision(&self) -> Precision {
        self.settings.precision
    }

    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// The settings as a report states them: how the steps so far were really called
    /// (`sim::Settings::as_run`).
    pub fn settings_as_run(&self) -> Settings {
        forward!(self, s => s.settings.as_run(&s.calls))
    }

    pub fn dt(&self) -> f64 {
        self.settings.dt
    }

    pub fn substeps(&self) -> usize {
        self.settings.substeps
    }

    pub fn total_steps(&self) -> u64 {
        forward!(self, s => s.total_steps())
    }

    pub fn snapshot(&self) -> &Snapshot {
        forward!(self, s => s.snapshot())
    }

    pub fn step(&mut self) -> Result<&Snapshot, SimError> {
        forward!(mut self, s => s.step())
    }

    pub fn run(&mut self, each: impl FnMut(&Snapshot)) -> Result<(), SimError> {
        forward!(mut self, s => s.run(each))
    }

    /// Whether snapshots carry the step's contacts (`sim::Simulation::set_contact_readings`).
    pub fn set_contact_readings(&mut self, on: bool) {
        forward!(mut self, s => s.set_contact_readings(on))
    }

    /// A blow between steps (`sim::Simulation::apply_impulse`).
    pub fn apply_impulse(&mut self, i: usize, at: DVec2, j: DVec2) -> bool {
        forward!(mut self, s => s.apply_impulse(i, at, j))
    }
}

impl crate::sim::Engine for AnySimulation {
    fn step(&mut self) -> Result<&Snapshot, SimError> {
        AnySimulation::step(self)
    }
    fn snapshot(&self) -> &Snapshot {
        AnySimulation::snapshot(self)
    }
    fn dt(&self) -> f64 {
        AnySimulation::dt(self)
    }
    fn total_steps(&self) -> u64 {
        AnySimulation::total_steps(self)
    }
}

impl crate::sim::Drive for AnySimulation {
    fn level(&self) -> &Level {
        &self.level
    }
    fn settings(&self) -> &Settings {
        &self.settings
    }
    fn settings_as_run(&self) -> Settings {
        AnySimulation::settings_as_run(self)
    }
    fn set_contact_readings(&mut self, on: bool) {
        AnySimulation::set_contact_readings(self, on)
    }
    fn snapshot(&self) -> &Snapshot {
        AnySimulation::snapshot(self)
    }
    fn run_each(&mut self, each: &mut dyn FnMut(&Snapshot)) -> Result<(), SimError> {
        self.run(each)
    }
}
