//! The simulation stage at the precision a run asks for: the level's `world.precision`, or the
//! `--precision` override. `sim` is compiled twice (rapier2d and rapier2d-f64, see
//! `sim/mod.rs`); this picks one of the two once, when the run is built, and forwards to it,
//! so the runner and the window drive either the same way. A level run on Box2D (`--engine`,
//! the window's solver panel, or `world.engine`) runs Box2D here too, on a thread of its own
//! (`sim::box2d::Threaded`: boxdd's world is `!Send`); one Box2D refuses runs rapier, with the
//! refusal kept in [`AnySimulation::refused`] for the window to show.

use crate::level::{Level, PhysicsEngine, Precision, Scene};
use crate::sim::{Options, Settings, SimError};
use crate::snapshot::Snapshot;
use glam::DVec2;

/// A running simulation of one level, in f32 or f64.
pub struct AnySimulation {
    /// The level (as `sim::Simulation::level`; it does not change during a run).
    pub level: Level,
    /// The run's settings, resolved once (as `sim::Simulation::settings`).
    pub settings: Settings,
    /// Why the engine asked for (Box2D) does not run this level and rapier does instead: the
    /// refusal, with the level item it names (None when the engine asked for runs).
    pub refused: Option<String>,
    engine: Engine,
}

enum Engine {
    F32(Box<crate::sim::Simulation>),
    F64(Box<crate::sim64::Simulation>),
    #[cfg(all(feature = "box2d", not(target_arch = "wasm32")))]
    Box2d(Box<crate::sim::box2d::Threaded>),
}

/// Forwards a call to whichever precision's simulation runs.
macro_rules! forward {
    ($self:expr, $sim:ident => $call:expr) => {
        match &$self.engine {
            Engine::F32($sim) => $call,
            Engine::F64($sim) => $call,
            #[cfg(all(feature = "box2d", not(target_arch = "wasm32")))]
            Engine::Box2d($sim) => $call,
        }
    };
    (mut $self:expr, $sim:ident => $call:expr) => {
        match &mut $self.engine {
            Engine::F32($sim) => $call,
            Engine::F64($sim) => $call,
            #[cfg(all(feature = "box2d", not(target_arch = "wasm32")))]
            Engine::Box2d($sim) => $call,
        }
    };
}

impl AnySimulation {
    /// The engine `Options::engine` names, else the level's `world.engine`: rapier at the
    /// run's precision, or Box2D on its thread; rapier, with [`AnySimulation::refused`] saying
    /// why, when Box2D refuses the level or is not in this build. The runner refuses such a
    /// level instead (`runner::engine_for`); the window shows the refusal and runs rapier.
    pub fn new(scene: &Scene, opts: &Options) -> Self {
        match opts.engine.unwrap_or(scene.level.world.engine) {
            PhysicsEngine::Rapier => Self::on_rapier(scene, opts, None),
            PhysicsEngine::Box2d => Self::box2d(scene, opts),
        }
    }

    /// rapier at the run's precision.
    fn on_rapier(scene: &Scene, opts: &Options, refused: Option<String>) -> Self {
        let precision = opts.precision.unwrap_or(scene.level.world.precision);
        let engine = match precision {
            Precision::F32 => Engine::F32(Box::new(crate::sim::Simulation::new(scene, opts))),
            Precision::F64 => Engine::F64(Box::new(crate::sim64::Simulation::new(scene, opts))),
        };
        let (level, settings) = match &engine {
            Engine::F32(s) => (s.level.clone(), s.settings.clone()),
            Engine::F64(s) => (s.level.clone(), s.settings.clone()),
            #[cfg(all(feature = "box2d", not(target_arch = "wasm32")))]
            Engine::Box2d(s) => (s.level.clone(), s.settings.clone()),
        };
        AnySimulation {
            level,
            settings,
            refused,
            engine,
        }
    }

    #[cfg(all(feature = "box2d", not(target_arch = "wasm32")))]
    fn box2d(scene: &Scene, opts: &Options) -> Self {
        match crate::sim::box2d::Threaded::new(scene, opts) {
            Ok(t) => AnySimulation {
                level: t.level.clone(),
                settings: t.settings.clone(),
                refused: None,
                engine: Engine::Box2d(Box::new(t)),
            },
            Err(e) => Self::on_rapier(scene, opts, Some(e.message)),
        }
    }

    #[cfg(not(all(feature = "box2d", not(target_arch = "wasm32"))))]
    fn box2d(scene: &Scene, opts: &Options) -> Self {
        let why = crate::sim::box2d::not_built().message;
        Self::on_rapier(scene, opts, Some(why))
    }

    /// The engine that runs (rapier when Box2D was asked for and refused).
    pub fn engine(&self) -> PhysicsEngine {
        match self.engine {
            #[cfg(all(feature = "box2d", not(target_arch = "wasm32")))]
            Engine::Box2d(_) => PhysicsEngine::Box2d,
            _ => PhysicsEngine::Rapier,
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
        match &self.engine {
            Engine::F32(s) => s.settings.as_run(&s.calls),
            Engine::F64(s) => s.settings.as_run(&s.calls),
            #[cfg(all(feature = "box2d", not(target_arch = "wasm32")))]
            Engine::Box2d(s) => s.settings.clone(),
        }
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
