//! The running simulation of one level (compiled once per precision, see `sim/mod.rs`).

use super::rapier::prelude::*;
use super::{build, joints};
use crate::level::*;
use crate::sim::energy::{EnergyGuard, FACTOR, SUSTAIN};
use crate::sim::options::{Options, SimError};
use crate::sim::settings::{Settings, Substepping};
use crate::snapshot::*;
use glam::DVec2;
use std::collections::HashMap;

/// A running simulation of one level.
pub struct Simulation {
    pub level: Level,
    /// The run's settings, resolved once from the level and the overrides.
    pub settings: Settings,
    pub world: PhysicsWorld,
    bodies: Vec<RigidBodyHandle>,
    joints: Vec<ImpulseJointHandle>,
    /// Definitions of `joints` (the level's, then welds created at run time).
    joint_defs: Vec<JointDef>,
    body_index: HashMap<String, usize>,
    snapshot: Snapshot,
    /// Initial value of each coupling's sum.
    coupling_rest: Vec<f64>,
    /// Welds still waiting for their first contact: (event name, body1, body2).
    pending_welds: Vec<(String, usize, usize)>,
    /// Bodies that loads or springs act on (their forces are reset every step).
    forced_bodies: Vec<usize>,
    /// Energy-explosion guard (see `sim::energy`).
    pub energy: EnergyGuard,
}

impl Simulation {
    pub fn new(scene: &Scene, opts: &Options) -> Self {
        let level = scene.level.clone();
        let settings = Settings::resolve(&level, opts, super::PRECISION);
        let effects = &settings.effects;
        let mut world = PhysicsWorld::new();
        world.gravity = build::gravity(&level);
        world.integration_parameters = build::integration_parameters(&settings);
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
        let mut joints = Vec::new();
        if effects.has(Effect::Joints) {
            for j in &level.joints {
                let (i1, i2) = (body_index[&j.body1], body_index[&j.body2]);
                let data = build::joint(j, &level.bodies[i1], &level.bodies[i2]);
                joints.push(world.insert_impulse_joint(bodies[i1], bodies[i2], data));
            }
        }
        let mut sim = Simulation {
            snapshot: Snapshot {
                step: 0,
                time: 0.0,
                dt: 0.0,
                substeps: settings.substeps,
                precision: settings.precision,
                gravity: DVec2::new(world.gravity.x as f64, world.gravity.y as f64),
                bodies: Vec::new(),
                contacts: Vec::new(),
                joints: Vec::new(),
                springs: Vec::new(),
                couplings: Vec::new(),
                loads: Vec::new(),
                impulses: Vec::new(),
            },
            level,
            settings,
            world,
            bodies,
            joints,
            joint_defs: Vec::new(),
            body_index,
            coupling_rest: Vec::new(),
            pending_welds: Vec::new(),
            forced_bodies: Vec::new(),
            energy: EnergyGuard::default(),
        };
        sim.joint_defs = if sim.settings.effects.has(Effect::Joints) {
            sim.level.joints.clone()
        } else {
            Vec::new()
        };
        sim.pending_welds = sim
            .level
            .events
            .iter()
            .filter_map(|e| match e {
                EventDef::WeldOnContact { name, body1, body2 } => {
                    Some((name.clone(), sim.body_index[body1], sim.body_index[body2]))
                }
                _ => None,
            })
            .collect();
        let mut forced: Vec<usize> = sim
            .level
            .loads
            .iter()
            .map(|l| sim.body_index[&l.body])
            .collect();
        for s in &sim.level.springs {
            forced.push(sim.body_index[&s.body1]);
            forced.extend(s.body2.as_ref().map(|b| sim.body_index[b]));
        }
        forced.sort_unstable();
        forced.dedup();
        sim.forced_bodies = forced;
        sim.read_bodies();
        sim.snapshot.springs = sim.spring_states(false);
        sim.coupling_rest = sim
            .level
            .couplings
            .iter()
            .map(|c| sim.coupling_value(c))
            .collect();
        sim.snapshot.couplings = sim.coupling_states(&vec![0.0; sim.level.couplings.len()]);
        sim.energy = EnergyGuard::new(&sim.snapshot);
        sim
    }

    /// The run's resolved settings.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// The physics step, s.
    pub fn dt(&self) -> f64 {
        self.settings.dt
    }

    pub fn substeps(&self) -> usize {
        self.settings.substeps
    }

    /// Number of steps the level's duration takes at the current dt.
    pub fn total_steps(&self) -> u64 {
        (self.level.world.duration / self.dt()).round().max(1.0) as u64
    }

    /// The state after the last step (or the initial state).
    pub fn snapshot(&self) -> &Snapshot {
        &self.snapshot
    }

    pub fn body_handle(&self, name: &str) -> Option<RigidBodyHandle> {
        self.body_index.get(name).map(|&i| self.bodies[i])
    }

    pub fn body_handles(&self) -> &[RigidBodyHandle] {
        &self.bodies
    }

    /// Advances one physics step and refreshes the snapshot.
    pub fn step(&mut self) -> Result<&Snapshot, SimError> {
        let dt = self.dt();
        let t0 = self.snapshot.time;
        let step = self.snapshot.step + 1;
        self.energy.record(&self.snapshot);

        // Impulses whose time falls in [t0, t0 + dt) act at the start of this step.
        self.snapshot.impulses.clear();
        for e in &self.level.events {
            let EventDef::Impulse {
                name,
                at,
                body,
                point,
                impulse,
                angular,
            } = e
            else {
                continue;
            };
            // The event acts at the start of the step that begins nearest to its time.
            if *at >= t0 - 0.5 * dt && *at < t0 + 0.5 * dt {
                let i = self.body_index[body];
                let rb = &mut self.world.bodies[self.bodies[i]];
                let p = *rb.position() * build::v(*point);
                rb.apply_impulse_at_point(build::v(*impulse), p, true);
                rb.apply_torque_impulse(*angular as Real, true);
                self.snapshot.impulses.push(ImpulseState {
                    name: name.clone(),
                    body: i,
                    point: to_d(p),
                    impulse: DVec2::new(impulse.0, impulse.1),
                    angular_impulse: *angular,
                });
            }
        }

        // Loads: forces held over the step, evaluated at its middle.
        self.snapshot.loads.clear();
        let t_mid = t0 + 0.5 * dt;
        let mut loads = Vec::with_capacity(self.level.loads.len());
        for l in &self.level.loads {
            let i = self.body_index[&l.body];
            let rb = &self.world.bodies[self.bodies[i]];
            let p = *rb.position() * build::v(l.point);
            let mut f = l.force.as_ref().map_or((0.0, 0.0), |f| sample2(f, t_mid));
            if l.follow_body {
                let r =
                    DVec2::from_angle(rb.rotation().angle() as f64).rotate(DVec2::new(f.0, f.1));
                f = (r.x, r.y);
            }
            let m = l.torque.as_ref().map_or(0.0, |m| sample1(m, t_mid));
            // Held in the body frame: the point of application moves with the body.
            loads.push((i, build::v(l.point), build::v(f), m as Real));
            self.snapshot.loads.push(LoadState {
                name: l.name.clone(),
                body: i,
                point: to_d(p),
                force: DVec2::new(f.0, f.1),
                torque: m,
            });
        }

        // Split substeps (see `Substepping::Split`): rapier is advanced n times at dt/n with one
        // substep each. Springs are then evaluated before every substep (rapier's own substeps
        // see only the forces set before its step: a spring held over n > 1 substeps is not
        // symplectic and gains energy, x2.5e4 in 10 s at omega dt = 0.5 with 4 substeps), and
        // contact and joint impulses are summed over the n calls into the step's snapshot.
        let n = self.substeps().max(1);
        let split = self.settings.substepping == Substepping::Split;
        let calls = if split { n } else { 1 };
        let h = dt / calls as f64;
        let mut lambdas = vec![0.0; self.level.couplings.len()];
        let mut springs: Vec<SpringState> = Vec::new();
        let mut joint_sum: Vec<JointState> = Vec::new();
        let mut contact_sum: Vec<ContactState> = Vec::new();
        {
            let p = &mut self.world.integration_parameters;
            p.dt = h as Real;
            p.num_solver_iterations = if split { 1 } else { n };
        }
        for call in 0..calls {
            self.apply_forces(&loads);
            let mut now = self.spring_states(true);
            for s in &now {
                let rb1 = &mut self.world.bodies[self.bodies[s.body1]];
                rb1.add_force_at_point(vd(s.force_on_body1), vd(s.applied_at1), true);
                if let Some(b2) = s.body2 {
                    let rb2 = &mut self.world.bodies[self.bodies[b2]];
                    rb2.add_force_at_point(vd(-s.force_on_body1), vd(s.applied_at2), true);
                }
            }
            // The snapshot reports the mean force over the step (its impulse / dt).
            for sp in now.iter_mut() {
                sp.force_on_body1 /= calls as f64;
                sp.tension /= calls as f64;
            }
            if call == 0 {
                springs = now;
            } else {
                for (a, b) in springs.iter_mut().zip(&now) {
                    a.force_on_body1 += b.force_on_body1;
                    a.tension += b.tension;
                }
            }
            // rapier builds a substep's joint rows from the poses it starts from: keep them,
            // so the call's impulses (all of one substep) are read along the very rows they
            // acted on.
            let rows_from = split.then(|| self.joint_poses());
            self.world.step();
            for (l, x) in lambdas.iter_mut().zip(self.solve_couplings()) {
                *l += x;
            }
            if let Some(poses) = rows_from {
                self.read_contacts();
                merge_contacts(&mut contact_sum, &self.snapshot.contacts);
                self.read_joints_scaled(1.0, Some(&poses));
                merge_joints(&mut joint_sum, &self.snapshot.joints);
            }
        }
        {
            let p = &mut self.world.integration_parameters;
            p.dt = dt as Real;
            p.num_solver_iterations = n;
        }

        self.snapshot.step = step;
        self.snapshot.time = step as f64 * dt;
        self.snapshot.dt = dt;
        self.snapshot.substeps = n;
        self.read_bodies();
        self.guard()?;
        if split {
            self.snapshot.contacts = contact_sum;
        } else {
            self.read_contacts();
        }
        self.weld_on_contact();
        // Welds created now get their first impulses next step.
        if split {
            self.snapshot.joints = joint_sum;
        } else {
            self.read_joints();
        }
        self.snapshot.couplings = self.coupling_states(&lambdas);
        // Spring state: forces held during the step, length and energy at its end.
        let end = self.spring_states(false);
        self.snapshot.springs = springs
            .into_iter()
            .zip(end)
            .map(|(held, now)| SpringState {
                force_on_body1: held.force_on_body1,
                tension: held.tension,
                applied_at1: held.applied_at1,
                applied_at2: held.applied_at2,
                ..now
            })
            .collect();
        self.energy.add_work(&self.snapshot);
        self.energy_guard()?;
        Ok(&self.snapshot)
    }

    /// Stops a run whose mechanical energy grew FACTOR times beyond its initial scale plus the
    /// work put in (see `sim::energy`).
    fn energy_guard(&mut self) -> Result<(), SimError> {
        let Some((gain, reference)) = self.energy.check(&self.snapshot) else {
            return Ok(());
        };
        // Name the body with the most kinetic energy: the one the explosion flung.
        let s = &self.snapshot;
        let body = s
            .bodies
            .iter()
            .max_by(|a, b| {
                let t = |b: &BodyState| {
                    b.mass * b.velocity.length_squared() + b.inertia * b.omega * b.omega
                };
                t(a).total_cmp(&t(b))
            })
            .map_or(String::new(), |b| b.name.clone());
        Err(SimError {
            step: s.step,
            time: s.time,
            body,
            quantity: format!(
                "carries the most of an energy gain of {gain:.3e} J, over {FACTOR:.0e} times the \
                 reference {reference:.3e} J (initial energy scale plus the work of loads, motors \
                 and impulses) for {SUSTAIN} s: the scene exploded; try a smaller dt or more \
                 substeps"
            ),
        })
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

    fn guard(&self) -> Result<(), SimError> {
        for b in &self.snapshot.bodies {
            let bad = |q: &str| SimError {
                step: self.snapshot.step,
                time: self.snapshot.time,
                body: b.name.clone(),
                quantity: q.to_string(),
            };
            if !(b.com.is_finite() && b.angle.is_finite()) {
                return Err(bad(
                    "position became non-finite (NaN or inf): the scene exploded",
                ));
            }
            if !(b.velocity.is_finite() && b.omega.is_finite()) {
                return Err(bad(
                    "velocity became non-finite (NaN or inf): the scene exploded",
                ));
            }
        }
        Ok(())
    }

    fn read_bodies(&mut self) {
        if self.snapshot.bodies.is_empty() {
            // Names, kinds and mass properties are set once: they do not change during a run.
            // Mass properties are the ones handed to rapier (parry's, from the shapes); rapier
            // itself only folds them into the body inside its first step.
            for (i, h) in self.bodies.iter().enumerate() {
                let rb = &self.world.bodies[*h];
                let def = &self.level.bodies[i];
                let dynamic = def.kind == BodyKind::Dynamic;
                let mp = build::mass_properties(def);
                self.snapshot.bodies.push(BodyState {
                    name: self.level.bodies[i].name.clone(),
                    kind: self.level.bodies[i].kind,
                    position: to_d(rb.translation()),
                    angle: rb.rotation().angle() as f64,
                    // From the pose, not rb.center_of_mass(): rapier refreshes that only inside a step.
                    com: to_d(*rb.position() * mp.local_com),
                    velocity: to_d(rb.linvel()),
                    omega: rb.angvel() as f64,
                    mass: if dynamic { mp.mass() as f64 } else { 0.0 },
                    inertia: if dynamic && !def.lock_rotation {
                        mp.principal_inertia() as f64
                    } else {
                        0.0
                    },
                    local_com: to_d(mp.local_com),
                });
            }
            return;
        }
        for (b, h) in self.snapshot.bodies.iter_mut().zip(&self.bodies) {
            let rb = &self.world.bodies[*h];
            let pose = rb.position();
            b.position = to_d(pose.translation);
            // Continuous angle: add the wrapped change since the last snapshot.
            b.angle += wrap_pi(pose.rotation.angle() as f64 - b.angle);
            let rot = DVec2::new(pose.rotation.re as f64, pose.rotation.im as f64);
            b.com = b.position + rot.rotate(b.local_com);
            b.velocity = to_d(rb.linvel());
            b.omega = rb.angvel() as f64;
        }
    }

    fn read_contacts(&mut self) {
        // Overwrite the previous step's entries in place: no allocation per manifold in steady state.
        let contacts = &mut self.snapshot.contacts;
        let mut n = 0;
        for pair in self.world.narrow_phase.contact_pairs() {
            if !pair.has_any_active_contact() {
                continue;
            }
            // Colliders carry their body's index in user_data (set when the world is built).
            let (c1, c2) = (
                &self.world.colliders[pair.collider1],
                &self.world.colliders[pair.collider2],
            );
            let (b1, b2) = (c1.user_data as usize, c2.user_data as usize);
            let (pose1, pose2) = (*c1.position(), *c2.position());
            for m in pair.manifolds() {
                if m.points.is_empty() {
                    continue;
                }
                if n == contacts.len() {
                    contacts.push(ContactState {
                        body1: 0,
                        body2: 0,
                        normal: DVec2::ZERO,
                        points: Vec::new(),
                    });
                }
                let c = &mut contacts[n];
                n += 1;
                c.body1 = b1;
                c.body2 = b2;
                c.normal = to_d(m.data.normal);
                c.points.clear();
                c.points.extend(m.points.iter().map(|pt| ContactPoint {
                    point: to_d(pose1 * pt.local_p1),
                    // From the current poses: rapier recycles contacts, and a recycled point
                    // keeps the distance of its last full update (a 9 mm overlap read as 0).
                    distance: ((pose2 * pt.local_p2 - pose1 * pt.local_p1).dot(m.data.normal))
                        as f64,
                    normal_impulse: pt.data.impulse as f64,
                    tangent_impulse: pt.data.tangent_impulse[0] as f64,
                    arms: Some((to_d(pt.data.solver_dp1), to_d(pt.data.solver_dp2))),
                }));
            }
        }
        contacts.truncate(n);
    }

    fn read_joints(&mut self) {
        self.read_joints_scaled(self.substeps() as f64, None);
    }

    /// Each joint's two bodies' poses and mass centers now, before a rapier call builds its rows.
    fn joint_poses(&self) -> Vec<JointPoses> {
        self.joints
            .iter()
            .map(|h| {
                let j = self
                    .world
                    .impulse_joints
                    .get(*h)
                    .expect("joint handles stay valid");
                let (rb1, rb2) = (&self.world.bodies[j.body1()], &self.world.bodies[j.body2()]);
                JointPoses {
                    pose1: *rb1.position(),
                    pose2: *rb2.position(),
                    com1: to_d(rb1.center_of_mass()),
                    com2: to_d(rb2.center_of_mass()),
                }
            })
            .collect()
    }

    /// Joint states with the last substep's impulses times `n` (the substeps of one rapier call),
    /// read along rows rebuilt from `rows_from` (the poses the call started from) when given,
    /// else from the poses now (one substep of motion off: O(h) in the rows' direction).
    fn read_joints_scaled(&mut self, n: f64, rows_from: Option<&[JointPoses]>) {
        self.snapshot.joints.clear();
        for (k, h) in self.joints.iter().enumerate() {
            let j = &self
                .world
                .impulse_joints
                .get(*h)
                .expect("joint handles stay valid");
            let def = &self.joint_defs[k];
            let (i1, i2) = (self.body_index[&def.body1], self.body_index[&def.body2]);
            let (rb1, rb2) = (
                &self.world.bodies[self.bodies[i1]],
                &self.world.bodies[self.bodies[i2]],
            );
            // Mass properties do not change within a call (rapier refreshes a body's effective
            // inverse mass and inertia inside its step), so they are read now; only the poses and
            // G are the call's start.
            let (mut m1, mut m2) = (joints::BodyMetric::of(rb1), joints::BodyMetric::of(rb2));
            let r = match rows_from.and_then(|p| p.get(k)) {
                Some(p) => {
                    (m1.com, m2.com) = (p.com1, p.com2);
                    joints::last_substep_reaction(j, &p.pose1, &p.pose2, &m1, &m2)
                }
                None => joints::last_substep_reaction(j, rb1.position(), rb2.position(), &m1, &m2),
            };
            let frame1 = *rb1.position() * j.data.local_frame1;
            let frame2 = *rb2.position() * j.data.local_frame2;
            let coordinate = match def.kind {
                JointKind::Revolute | JointKind::Fixed => {
                    (rb2.rotation().angle() - rb1.rotation().angle()) as f64
                        - (self.level.bodies[i2].angle - self.level.bodies[i1].angle)
                }
                JointKind::Prismatic | JointKind::PinSlot => {
                    let axis = frame1.rotation * Vector::X;
                    (frame2.translation - frame1.translation).dot(axis) as f64
                }
            };
            // Joint rows restart each substep: the step's impulse is `substeps` times the last one.
            self.snapshot.joints.push(JointState {
                name: def.name.clone(),
                body1: i1,
                body2: i2,
                anchor: to_d(frame2.translation),
                anchor1: to_d(frame1.translation),
                impulse_on_body2: r.on_body2 * n,
                angular_impulse_on_body2: r.angular_on_body2 * n,
                angular_impulse_on_body1: r.angular_on_body1 * n,
                couple_on_body2: r.couple_on_body2 * n,
                motor_impulse: r.motor * n,
                limit_impulse: r.limit * n,
                coordinate,
            });
        }
    }

    /// Clears the user forces of loaded and sprung bodies and applies the step's loads.
    fn apply_forces(&mut self, loads: &[(usize, Vector, Vector, Real)]) {
        for &i in &self.forced_bodies {
            // rapier keeps forces and torques apart: both must be cleared, or every
            // couple (and the moment of every off-center force) accumulates step after step.
            // Only bodies that carry loads or springs: touching a body through `&mut` marks
            // it as changed, and rapier then redoes per-body work for it in the next step.
            let rb = &mut self.world.bodies[self.bodies[i]];
            rb.reset_forces(false);
            rb.reset_torques(false);
        }
        for &(i, local, f, m) in loads {
            let rb = &mut self.world.bodies[self.bodies[i]];
            let p = *rb.position() * local;
            rb.add_force_at_point(f, p, true);
            rb.add_torque(m, true);
        }
    }

    /// Spring states from the current body poses and velocities.
    fn spring_states(&self, with_force: bool) -> Vec<SpringState> {
        let mut out = Vec::with_capacity(self.level.springs.len());
        if !self.settings.effects.has(Effect::Springs) {
            return out;
        }
        for s in &self.level.springs {
            let i1 = self.body_index[&s.body1];
            let rb1 = &self.world.bodies[self.bodies[i1]];
            let p1 = *rb1.position() * build::v(s.point1);
            let v1 = rb1.velocity_at_point(p1);
            let (i2, p2, v2) = match &s.body2 {
                Some(b2) => {
                    let i2 = self.body_index[b2];
                    let rb2 = &self.world.bodies[self.bodies[i2]];
                    let p2 = *rb2.position() * build::v(s.point2);
                    (Some(i2), p2, rb2.velocity_at_point(p2))
                }
                None => (None, build::v(s.point2), Vector::ZERO),
            };
            let (p1, p2, v1, v2) = (to_d(p1), to_d(p2), to_d(v1), to_d(v2));
            let d = p2 - p1;
            let length = d.length();
            let x = length - s.rest_length;
            let u = if length > 1e-12 {
                d / length
            } else {
                DVec2::ZERO
            };
            // Tension T = k x + c dx/dt pulls body1 toward body2 (Hooke's law, eq. 3/23 of MK).
            let c = if self.settings.effects.has(Effect::Damping) {
                s.damping
            } else {
                0.0
            };
            let tension = s.stiffness * x + c * (v2 - v1).dot(u);
            out.push(SpringState {
                name: s.name.clone(),
                body1: i1,
                body2: i2,
                point1: p1,
                point2: p2,
                length,
                extension: x,
                tension: if with_force { tension } else { 0.0 },
                energy: 0.5 * s.stiffness * x * x,
                force_on_body1: if with_force { u * tension } else { DVec2::ZERO },
                applied_at1: p1,
                applied_at2: p2,
            });
        }
        out
    }
}

/// The poses a rapier call built one joint's rows from.
struct JointPoses {
    pose1: Pose,
    pose2: Pose,
    /// The two bodies' mass centers (world), from which rapier measured the rows' lever arms.
    com1: DVec2,
    com2: DVec2,
}

/// Wraps an angle difference to (-pi, pi].
fn wrap_pi(a: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    a - TAU * ((a + PI) / TAU).floor()
}

impl Simulation {
    fn coordinate(&self, body: usize, c: Coordinate) -> (f64, f64, f64) {
        // (q, dq/dt, inverse generalized mass) of a body coordinate.
        let rb = &self.world.bodies[self.bodies[body]];
        let mp = rb.mass_properties();
        let dynamic = rb.is_dynamic();
        let com = *rb.position() * mp.local_mprops.local_com;
        match c {
            Coordinate::X => (
                com.x as f64,
                rb.linvel().x as f64,
                if dynamic {
                    mp.effective_inv_mass.x as f64
                } else {
                    0.0
                },
            ),
            Coordinate::Y => (
                com.y as f64,
                rb.linvel().y as f64,
                if dynamic {
                    mp.effective_inv_mass.y as f64
                } else {
                    0.0
                },
            ),
            Coordinate::Angle => {
                let prev = self.snapshot.bodies[body].angle;
                let q = prev + wrap_pi(rb.rotation().angle() as f64 - prev);
                (
                    q,
                    rb.angvel() as f64,
                    if dynamic {
                        mp.effective_world_inv_inertia as f64
                    } else {
                        0.0
                    },
                )
            }
        }
    }

    fn coupling_value(&self, c: &CouplingDef) -> f64 {
        c.terms
            .iter()
            .map(|t| t.ratio * self.coordinate(self.body_index[&t.body], t.coordinate).0)
            .sum()
    }

    /// Enforces every coupling after rapier's step: Gauss-Seidel on velocities (the impulse
    /// lambda that makes sum(c_i v_i) = 0; exact in one pass for a single coupling, iterated for
    /// couplings that share a body), then a position projection that removes the drift without
    /// adding velocity. Returns each coupling's impulse over the step.
    fn solve_couplings(&mut self) -> Vec<f64> {
        let n = self.level.couplings.len();
        let mut lambdas = vec![0.0; n];
        if n == 0 || !self.settings.effects.has(Effect::Joints) {
            return lambdas;
        }
        let terms: Vec<Vec<(usize, Coordinate, f64)>> = self
            .level
            .couplings
            .iter()
            .map(|c| {
                c.terms
                    .iter()
                    .map(|t| (self.body_index[&t.body], t.coordinate, t.ratio))
                    .collect()
            })
            .collect();
        for pass in 0..2 {
            // pass 0: velocities; pass 1: positions.
            for _sweep in 0..64 {
                let mut worst: f64 = 0.0;
                for (k, ts) in terms.iter().enumerate() {
                    let (mut num, mut den) = (0.0, 0.0);
                    for &(b, c, r) in ts {
                        let (q, v, w) = self.coordinate(b, c);
                        num += r * if pass == 0 { v } else { q };
                        den += r * r * w;
                    }
                    if den <= 0.0 {
                        continue;
                    }
                    let target = if pass == 0 {
                        0.0
                    } else {
                        self.coupling_rest[k]
                    };
                    let mu = -(num - target) / den;
                    worst = worst.max((num - target).abs());
                    if pass == 0 {
                        lambdas[k] += mu;
                    }
                    for &(b, c, r) in ts {
                        let w = self.coordinate(b, c).2;
                        if w == 0.0 {
                            continue;
                        }
                        let d = (r * w * mu) as Real;
                        let rb = &mut self.world.bodies[self.bodies[b]];
                        match (pass, c) {
                            (0, Coordinate::X) => {
                                rb.set_linvel(rb.linvel() + Vector::new(d, 0.0), true)
                            }
                            (0, Coordinate::Y) => {
                                rb.set_linvel(rb.linvel() + Vector::new(0.0, d), true)
                            }
                            (0, Coordinate::Angle) => rb.set_angvel(rb.angvel() + d, true),
                            (_, Coordinate::X) => {
                                rb.set_translation(rb.translation() + Vector::new(d, 0.0), true)
                            }
                            (_, Coordinate::Y) => {
                                rb.set_translation(rb.translation() + Vector::new(0.0, d), true)
                            }
                            (_, Coordinate::Angle) => {
                                // Turn about the mass center, not the body origin.
                                let local_com = rb.mass_properties().local_mprops.local_com;
                                let com = *rb.position() * local_com;
                                let rot = Rotation::new(rb.rotation().angle() + d);
                                rb.set_position(Pose::from_parts(com - rot * local_com, rot), true);
                            }
                        }
                    }
                }
                if worst < 1e-12 {
                    break;
                }
            }
        }
        lambdas
    }

    fn coupling_states(&self, lambdas: &[f64]) -> Vec<CouplingState> {
        self.level
            .couplings
            .iter()
            .enumerate()
            .map(|(k, c)| {
                let value = self.coupling_value(c);
                CouplingState {
                    name: c.name.clone(),
                    terms: c
                        .terms
                        .iter()
                        .map(|t| (self.body_index[&t.body], t.coordinate, t.ratio))
                        .collect(),
                    impulse: lambdas[k],
                    value,
                    drift: value - self.coupling_rest[k],
                }
            })
            .collect()
    }

    /// Creates the fixed joint of a `WeldOnContact` event once its bodies touch.
    fn weld_on_contact(&mut self) {
        let mut k = 0;
        while k < self.pending_welds.len() {
            let (name, b1, b2) = self.pending_welds[k].clone();
            let touch = self
                .snapshot
                .contacts
                .iter()
                .find(|c| (c.body1 == b1 && c.body2 == b2) || (c.body1 == b2 && c.body2 == b1));
            let Some(point) = touch
                .and_then(|c| {
                    c.points
                        .iter()
                        .find(|p| p.normal_impulse > 0.0 || p.distance <= 0.0)
                })
                .map(|p| p.point)
            else {
                k += 1;
                continue;
            };
            let (h1, h2) = (self.bodies[b1], self.bodies[b2]);
            let p = Pose::from_parts(
                Vector::new(point.x as Real, point.y as Real),
                Rotation::IDENTITY,
            );
            let f1 = self.world.bodies[h1].position().inverse() * p;
            let f2 = self.world.bodies[h2].position().inverse() * p;
            let joint = GenericJointBuilder::new(JointAxesMask::LOCKED_FIXED_AXES)
                .local_frame1(f1)
                .local_frame2(f2)
                .contacts_enabled(false)
                .build();
            self.joints
                .push(self.world.insert_impulse_joint(h1, h2, joint));
            let (n1, n2) = (
                self.level.bodies[b1].name.clone(),
                self.level.bodies[b2].name.clone(),
            );
            let to_v2 = |v: Vector| (v.x as f64, v.y as f64);
            self.joint_defs.push(JointDef {
                name,
                kind: JointKind::Fixed,
                body1: n1,
                body2: n2,
                anchor1: to_v2(f1.translation),
                anchor2: to_v2(f2.translation),
                axis: (1.0, 0.0),
                limits: None,
                motor: None,
                starts_apart: false,
            });
            self.pending_welds.remove(k);
        }
    }
}

/// Adds one rapier call's contacts to the step's sums: each earlier point's impulses go to the
/// nearest point of the same body pair's manifold (same ordinal), so every manifold's total
/// impulse is kept; contacts gone by the last call stay in the list with their last geometry.
fn merge_contacts(sum: &mut Vec<ContactState>, now: &[ContactState]) {
    let old = std::mem::take(sum);
    *sum = now.to_vec();
    let mut used = vec![false; old.len()];
    for (k, c) in sum.iter_mut().enumerate() {
        let ordinal = now[..k]
            .iter()
            .filter(|o| o.body1 == c.body1 && o.body2 == c.body2)
            .count();
        let Some(j) = old
            .iter()
            .enumerate()
            .filter(|(_, o)| o.body1 == c.body1 && o.body2 == c.body2)
            .map(|(j, _)| j)
            .nth(ordinal)
        else {
            continue;
        };
        used[j] = true;
        if c.points.is_empty() {
            c.points = old[j].points.clone();
            continue;
        }
        for p in &old[j].points {
            let q = c
                .points
                .iter_mut()
                .min_by(|a, b| {
                    (a.point - p.point)
                        .length_squared()
                        .total_cmp(&(b.point - p.point).length_squared())
                })
                .expect("non-empty");
            q.normal_impulse += p.normal_impulse;
            q.tangent_impulse += p.tangent_impulse;
        }
    }
    for (j, o) in old.into_iter().enumerate() {
        if !used[j] {
            sum.push(o);
        }
    }
}

/// Adds one rapier call's joint impulses (world axes) to the step's sums; the rest of the
/// state (anchors, coordinate) is the latest call's.
fn merge_joints(sum: &mut Vec<JointState>, now: &[JointState]) {
    let old = std::mem::take(sum);
    *sum = now.to_vec();
    for (s, o) in sum.iter_mut().zip(old) {
        s.impulse_on_body2 += o.impulse_on_body2;
        s.angular_impulse_on_body2 += o.angular_impulse_on_body2;
        s.angular_impulse_on_body1 += o.angular_impulse_on_body1;
        s.couple_on_body2 += o.couple_on_body2;
        s.motor_impulse += o.motor_impulse;
        s.limit_impulse += o.limit_impulse;
    }
}

pub(crate) fn to_d(v: Vector) -> DVec2 {
    DVec2::new(v.x as f64, v.y as f64)
}

fn vd(v: DVec2) -> Vector {
    Vector::new(v.x as Real, v.y as Real)
}

/// Linear interpolation in a time table, held constant beyond its ends. Times increase
/// (validated), so the row is found by bisection: O(log n) a step for a table of any length.
fn interp<T: Copy>(rows: &[(f64, T)], t: f64, lerp: impl Fn(T, T, f64) -> T) -> T {
    if t <= rows[0].0 {
        return rows[0].1;
    }
    // The first row at or after t; rows[k - 1].0 < t <= rows[k].0.
    let k = rows.partition_point(|r| r.0 < t);
    if k >= rows.len() {
        return rows[rows.len() - 1].1;
    }
    let (a, b) = (rows[k - 1], rows[k]);
    lerp(a.1, b.1, (t - a.0) / (b.0 - a.0))
}

pub fn sample2(p: &Profile<V2>, t: f64) -> V2 {
    match p {
        Profile::Constant(v) => *v,
        Profile::Table(rows) => interp(rows, t, |a, b, s| {
            (a.0 + (b.0 - a.0) * s, a.1 + (b.1 - a.1) * s)
        }),
    }
}

pub fn sample1(p: &Profile<f64>, t: f64) -> f64 {
    match p {
        Profile::Constant(v) => *v,
        Profile::Table(rows) => interp(rows, t, |a, b, s| a + (b - a) * s),
    }
}

impl crate::sim::options::Engine for Simulation {
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
