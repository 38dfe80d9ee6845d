//! The running Box2D simulation of one level: built, stepped (`step.rs`), read (`read.rs`).

use super::support::{refusal, Refusal};
use super::{build, read};

use crate::level::{Level, LevelError, Scene};
use crate::sim::{Options, Settings, SimError};
use crate::snapshot::{Precision, Snapshot};
use boxdd::{BodyId, JointId, ShapeId, World};
use std::collections::HashMap;

/// A running Box2D simulation of one level.
pub struct Simulation {
    pub level: Level,
    /// The run's settings, resolved as for rapier (`Settings::resolve`, f32).
    pub settings: Settings,
    pub(super) world: World,
    /// The level's bodies, in its order.
    pub(super) bodies: Vec<BodyId>,
    /// Each shape's body (its index in `bodies`).
    pub(super) shapes: HashMap<ShapeId, usize>,
    pub(super) joints: Vec<JointId>,
    /// Each joint's two bodies' indices.
    pub(super) joint_pairs: Vec<(usize, usize)>,
    pub(super) snapshot: Snapshot,
    /// Whether the snapshot carries the step's contacts.
    pub(super) contact_readings: bool,
}

impl Simulation {
    /// Builds the world of a scene, or refuses it with the level item Box2D cannot run.
    pub fn new(scene: &Scene, opts: &Options) -> Result<Self, LevelError> {
        let level = scene.level.clone();
        let locate = |r: Refusal| {
            let text = crate::level::read_text(&scene.file).ok();
            r.locate(&scene.file, text.as_deref())
        };
        if let Some(r) = refusal(&level) {
            return Err(locate(r));
        }
        if opts.precision == Some(Precision::F64) {
            return Err(LevelError::new(
                &scene.file,
                (0, 0),
                "--precision f64 is not supported by the box2d engine",
                "Box2D runs in f32 here; leave --precision out, or run on rapier",
            ));
        }
        let settings = Settings::resolve(&level, opts, Precision::F32);
        Self::build(level, settings).map_err(|e| {
            LevelError::new(
                &scene.file,
                (0, 0),
                format!("Box2D could not build this scene: {e}"),
                "run this level on rapier (--engine rapier); docs/engines.md lists what box2d runs",
            )
        })
    }

    fn build(level: Level, settings: Settings) -> build::Result<Self> {
        let (world, g) = build::world(&level, &settings)?;
        let snapshot = read::empty_snapshot(&settings, g);
        let mut sim = Simulation {
            level,
            settings,
            world,
            bodies: Vec::new(),
            shapes: HashMap::new(),
            joints: Vec::new(),
            joint_pairs: Vec::new(),
            snapshot,
            contact_readings: true,
        };
        sim.insert_bodies()?;
        sim.insert_joints()?;
        sim.read_initial_state()?;
        Ok(sim)
    }

    /// The physics step, s.
    pub fn dt(&self) -> f64 {
        self.settings.dt
    }

    /// Number of steps the level's duration takes at the current dt (as on rapier).
    pub fn total_steps(&self) -> u64 {
        (self.level.world.duration / self.dt()).round().max(1.0) as u64
    }

    /// Whether each snapshot carries the step's contacts (on by default; see
    /// `sim::Simulation::set_contact_readings`).
    pub fn set_contact_readings(&mut self, on: bool) {
        self.contact_readings = on;
    }

    /// The state after the last step (or the initial state).
    pub fn snapshot(&self) -> &Snapshot {
        &self.snapshot
    }

    /// Runs the whole duration, calling `each` with every snapshot (the initial one first).
    pub fn run(&mut self, mut each: impl FnMut(&Snapshot)) -> Result<(), SimError> {
        each(&self.snapshot);
        for _ in 0..self.total_steps() {
            let s = self.step()?;
            each(s);
        }
        Ok(())
    }
}

impl crate::sim::Engine for Simulation {
    fn step(&mut self) -> Result<&Snapshot, SimError> {
        Simulation::step(self)
    }
    fn snapshot(&self) -> &Snapshot {
        Simulation::snapshot(self)
    }
    fn dt(&self) -> f64 {
        Simulation::dt(self)
    }
    fn total_steps(&self) -> u64 {
        Simulation::total_steps(self)
    }
}

impl crate::sim::Drive for Simulation {
    fn level(&self) -> &Level {
        &self.level
    }
    fn settings(&self) -> &Settings {
        &self.settings
    }
    fn settings_as_run(&self) -> Settings {
        self.settings.clone()
    }
    fn set_contact_readings(&mut self, on: bool) {
        Simulation::set_contact_readings(self, on)
    }
    fn snapshot(&self) -> &Snapshot {
        Simulation::snapshot(self)
    }
    fn run_each(&mut self, each: &mut dyn FnMut(&Snapshot)) -> Result<(), SimError> {
        self.run(each)
    }
}
