//! `Simulation::new` and its phases (here, not in world.rs, so that the world and its setup do
//! not import each other): the rapier world filled from the scene in the order rapier needs
//! (world, bodies with their colliders, joints), then what the step keeps beside it (welds to
//! come, forced bodies, carriers), then the initial readings the first step starts from.

use super::build;
use super::rapier::prelude::*;
use super::world::Simulation;
use crate::level::*;
use crate::sim::explosion_guard::EnergyGuard;
use crate::sim::options::Options;
use crate::sim::settings::{Settings, StepCalls};
use crate::snapshot::*;
use glam::DVec2;
use std::collections::HashMap;

/// An empty rapier world with the run's gravity and integration parameters, and the world's own
/// normalized prediction distance (restored after a call the impact plan lowers it for).
pub(super) fn empty_world(level: &Level, settings: &Settings) -> (PhysicsWorld, Real) {
    let mut world = PhysicsWorld::new();
    // A ball on an arc track touches the circle, not its facets (sim/arc_contacts.rs).
    world
        .narrow_phase
        .set_query_dispatcher(super::arc_contacts::dispatcher());
    world.gravity = build::gravity(level);
    world.integration_parameters = build::integration_parameters(settings);
    let prediction_distance = world.integration_parameters.normalized_prediction_distance;
    (world, prediction_distance)
}

/// Inserts the level's bodies (with their colliders when contacts are declared): their handles,
/// in the level's order, and each body's index by name.
pub(super) fn insert_bodies(
    world: &mut PhysicsWorld,
    level: &Level,
    settings: &Settings,
) -> (Vec<RigidBodyHandle>, HashMap<String, usize>) {
    let effects = &settings.effects;
    let contacts = effects.has(Effect::Contacts);
    let mut bodies = Vec::new();
    let mut body_index = HashMap::new();
    for (i, b) in level.bodies.iter().enumerate() {
        let h = world.insert_body(build::body_builder(
            b,
            effects,
            settings.allow_fast_rotation,
        ));
        if contacts {
            for c in build::colliders(b, effects) {
                // user_data carries the body's index for reading contacts back.
                world.insert_collider(c.user_data(i as u128), Some(h));
            }
        }
        // rapier folds mass properties into a body only inside its first step; an impulse
        // event at t = 0 (applied before that step) would then see zero mass and do nothing.
        let rb = &mut world.bodies[h];
        rb.recompute_mass_properties_from_colliders(&world.colliders);
        bodies.push(h);
        body_index.insert(b.name.clone(), i);
    }
    (bodies, body_index)
}

/// Inserts the level's joints between its bodies, when joints are declared.
pub(super) fn insert_joints(
    world: &mut PhysicsWorld,
    level: &Level,
    settings: &Settings,
    bodies: &[RigidBodyHandle],
    body_index: &HashMap<String, usize>,
) -> Vec<ImpulseJointHandle> {
    let mut joints = Vec::new();
    if settings.effects.has(Effect::Joints) {
        for j in &level.joints {
            let (i1, i2) = (body_index[&j.body1], body_index[&j.body2]);
            let data = build::joint(j, &level.bodies[i1], &level.bodies[i2]);
            joints.push(world.insert_impulse_joint(bodies[i1], bodies[i2], data));
        }
    }
    joints
}

/// The snapshot before the first reading: the run's settings and gravity, no body yet.
pub(super) fn empty_snapshot(settings: &Settings, gravity: Vector) -> Snapshot {
    Snapshot {
        step: 0,
        time: 0.0,
        dt: 0.0,
        substeps: settings.substeps,
        precision: settings.precision,
        gravity: DVec2::new(gravity.x as f64, gravity.y as f64),
        bodies: Vec::new(),
        contacts: Vec::new(),
        joints: Vec::new(),
        springs: Vec::new(),
        couplings: Vec::new(),
        loads: Vec::new(),
        impulses: Vec::new(),
    }
}

impl Simulation {
    /// Builds the rapier world of a scene, in the order rapier needs, and reads its initial state.
    pub fn new(scene: &Scene, opts: &Options) -> Self {
        let level = scene.level.clone();
        let settings = Settings::resolve(&level, opts, super::PRECISION);
        let (mut world, prediction_distance) = empty_world(&level, &settings);
        let (bodies, body_index) = insert_bodies(&mut world, &level, &settings);
        let joints = insert_joints(&mut world, &level, &settings, &bodies, &body_index);
        let mut sim = Simulation {
            snapshot: empty_snapshot(&settings, world.gravity),
            level,
            settings,
            world,
            bodies,
            joints,
            joint_defs: Vec::new(),
            joint_bodies: Vec::new(),
            body_index,
            coupling_rest: Vec::new(),
            coupling_tension: Vec::new(),
            motor_absorbed: Vec::new(),
            carriers: Vec::new(),
            pending_welds: Vec::new(),
            forced_bodies: Vec::new(),
            prescribed: Vec::new(),
            torsion_rest: Vec::new(),
            energy: EnergyGuard::default(),
            round_colliders: Default::default(),
            contact_readings: true,
            prediction_distance,
            after_impact: false,
            last_step_cuts: 0,
            last_call: 0.0,
            calls: StepCalls::default(),
            substeps_seen: Default::default(),
            has_kinematic: scene
                .level
                .bodies
                .iter()
                .any(|b| b.kind == BodyKind::Kinematic),
        };
        sim.keep_step_bookkeeping();
        sim.read_initial_state();
        sim
    }

    /// What the step keeps beside the rapier world, from the level: the joints' definitions,
    /// the welds waiting for a contact, the couplings' carriers and the bodies whose forces the
    /// step resets.
    pub(super) fn keep_step_bookkeeping(&mut self) {
        self.joint_defs = if self.settings.effects.has(Effect::Joints) {
            self.level.joints.clone()
        } else {
            Vec::new()
        };
        self.pending_welds = self
            .level
            .events
            .iter()
            .filter_map(|e| match e {
                EventDef::WeldOnContact { name, body1, body2 } => {
                    Some((name.clone(), self.body_index[body1], self.body_index[body2]))
                }
                _ => None,
            })
            .collect();
        self.carriers = self
            .level
            .couplings
            .iter()
            .map(|c| {
                let over = c.over.iter().map(|b| (self.body_index[b], DVec2::ZERO));
                let gears = c
                    .terms
                    .iter()
                    .filter(|_| c.gears)
                    .map(|t| (self.body_index[&t.body], DVec2::ZERO));
                over.chain(gears).collect()
            })
            .collect();
        self.forced_bodies = self.forced_bodies();
        self.prescribed = (0..self.level.bodies.len())
            .filter(|&i| self.level.bodies[i].motion.is_some())
            .collect();
    }

    /// The bodies that loads, springs, couplings' carriers or couplings' held tensions act on,
    /// each once.
    fn forced_bodies(&self) -> Vec<usize> {
        let mut forced: Vec<usize> = self
            .level
            .loads
            .iter()
            .map(|l| self.body_index[&l.body])
            .collect();
        for s in &self.level.springs {
            forced.push(self.body_index[&s.body1]);
            forced.extend(s.body2.as_ref().map(|b| self.body_index[b]));
        }
        for t in &self.level.torsion_springs {
            forced.push(self.body_index[&t.body1]);
            forced.extend(t.body2.as_ref().map(|b| self.body_index[b]));
        }
        forced.extend(self.carriers.iter().flatten().map(|c| c.0));
        for c in &self.level.couplings {
            forced.extend(c.terms.iter().map(|t| self.body_index[&t.body]));
        }
        forced.sort_unstable();
        forced.dedup();
        forced
    }

    /// The initial snapshot (bodies, springs, couplings) and what is measured from it: torsion
    /// springs' rest angles, couplings' initial sums, the energy guard's scale.
    pub(super) fn read_initial_state(&mut self) {
        self.read_bodies();
        self.prescribed_rates();
        self.torsion_rest = self
            .level
            .torsion_springs
            .iter()
            .map(|t| {
                t.rest_angle
                    .unwrap_or_else(|| self.relative_angle(&t.body1, t.body2.as_deref()).0)
            })
            .collect();
        self.snapshot.springs = self.spring_states(false);
        self.coupling_rest = self
            .level
            .couplings
            .iter()
            .map(|c| self.coupling_value(c))
            .collect();
        let none = vec![0.0; self.level.couplings.len()];
        self.coupling_tension = none.clone();
        self.motor_absorbed = vec![0.0; self.bodies.len()];
        let carried: Vec<Vec<DVec2>> = self
            .carriers
            .iter()
            .map(|c| vec![DVec2::ZERO; c.len()])
            .collect();
        self.snapshot.couplings = self.coupling_states(&none, &carried);
        self.energy = EnergyGuard::new(&self.snapshot);
    }
}
