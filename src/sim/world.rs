//! The running simulation of one level (compiled once per precision, see `sim/mod.rs`).

use super::build;
use super::rapier::prelude::*;
use crate::level::*;
use crate::sim::explosion_guard::{motion_energy, EnergyGuard, FACTOR, SUSTAIN};
use crate::sim::options::SimError;
use crate::sim::settings::{Settings, StepCalls};
use crate::snapshot::*;
use glam::DVec2;
use std::collections::HashMap;

/// A running simulation of one level.
pub struct Simulation {
    pub level: Level,
    /// The run's settings, resolved once from the level and the overrides.
    pub settings: Settings,
    pub world: PhysicsWorld,
    pub(super) bodies: Vec<RigidBodyHandle>,
    pub(super) joints: Vec<ImpulseJointHandle>,
    /// Definitions of `joints` (the level's, then welds created at run time).
    pub(super) joint_defs: Vec<JointDef>,
    /// Each joint's two bodies' indices (filled as `joint_defs` grows; see `read_joints_scaled`).
    pub(super) joint_bodies: Vec<(usize, usize)>,
    pub(super) body_index: HashMap<String, usize>,
    pub(super) snapshot: Snapshot,
    /// Initial value of each coupling's sum.
    pub(super) coupling_rest: Vec<f64>,
    /// Per coupling: the bodies that carry it (the pulley a cable runs `over`, or both meshing
    /// `gears`) and the impulse each is still owed, delivered during the next rapier call (see
    /// `sim/couplings.rs`).
    pub(super) carriers: Vec<Vec<(usize, DVec2)>>,
    /// Per coupling: its last rapier call's generalized force (impulse / call length), held over
    /// the next call so that rapier's solver meets the cable's pull (`sim/coupling_tension.rs`).
    pub(super) coupling_tension: Vec<f64>,
    /// Per body: the angular impulse over the step the couplings' projections gave its ideal
    /// velocity motor instead of it (`sim/coupling_tension.rs`), booked in the motor's reading.
    pub(super) motor_absorbed: Vec<f64>,
    /// Welds still waiting for their first contact: (event name, body1, body2).
    pub(super) pending_welds: Vec<(String, usize, usize)>,
    /// Bodies that loads, springs, carriers or held coupling tensions act on (their forces are
    /// reset before every rapier call).
    pub(super) forced_bodies: Vec<usize>,
    /// The bodies with a prescribed motion, by index (a step walks these, not every body).
    pub(super) prescribed: Vec<usize>,
    /// Each torsion spring's rest angle, rad (its own, or the relative angle at t = 0).
    pub(super) torsion_rest: Vec<f64>,
    /// Energy-explosion guard (see `sim::explosion_guard`).
    pub energy: EnergyGuard,
    /// The world's ball and arc colliders, for the step's plan (`sim::contact_points`).
    pub(super) round_colliders: super::contact_points::RoundColliders,
    /// Whether the snapshot carries the step's contacts (`Simulation::set_contact_readings`).
    pub(super) contact_readings: bool,
    /// Whether the level has a kinematic body (the energy guard reads its contacts).
    pub(super) has_kinematic: bool,
    /// The world's own normalized prediction distance, restored after a call the impact plan
    /// lowered it for (sim/impacts.rs).
    pub(super) prediction_distance: Real,
    /// Whether the last rapier call made an impact's contact: the next call then solves its
    /// unbiased pass to convergence too (sim/impacts.rs, `IMPACT_ITERATIONS`).
    pub(super) after_impact: bool,
    /// How many times the impact planner cut the last step's calls (sim/impacts.rs): what the
    /// tests read to see that a pair rapier never collides is not planned as an impact.
    pub last_step_cuts: usize,
    /// The length of the last rapier call, s: a contact's impulse from it over this is its
    /// force (sim/contact_points.rs, `spin_calls`).
    pub(super) last_call: f64,
    /// How the run's steps have been called so far (`Settings::as_run` reports them).
    pub calls: StepCalls,
    /// The joints' impulses over the last substeps of the last two steps, when its joint
    /// impulses are reconstructed (`Settings::split_at_blows`, sim/joint_sums.rs).
    pub(super) substeps_seen: super::joint_sums::SubstepHistory,
}

impl Simulation {
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

    /// Whether each snapshot carries the step's contacts (on by default). Reading 200 contact
    /// manifolds into f64 costs about 5% of rapier's step on a 200-box pile (`benches/core.rs`):
    /// a run whose readers use none turns it off (`runner::Observers::reads_contacts`), and its
    /// snapshots' `contacts` stay empty. Contacts are still read where the simulation itself needs
    /// them: a weld waiting for its bodies to touch, or a kinematic body whose pushes the energy
    /// guard counts as work.
    pub fn set_contact_readings(&mut self, on: bool) {
        self.contact_readings = on;
    }

    /// Whether this step's contacts are read (see [`Simulation::set_contact_readings`]).
    pub(super) fn contacts_wanted(&self) -> bool {
        self.contact_readings || !self.pending_welds.is_empty() || self.has_kinematic
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

    /// Moves each kinematic body with a prescribed motion from its pose at t0 to its pose at t1
    /// over the coming rapier call: rapier moves a kinematic body's center of mass at its
    /// linvel and turns it at its angvel about that point, so these are the mean rates between
    /// the two poses, computed in f64 from the motion itself. (Setting the next pose instead,
    /// rapier's position-based kinematic body, takes the rates from poses rounded to f32: at
    /// 37 m a pose's ulp over a 2 ms step is 2e-3 m/s of velocity noise, which shook a
    /// pendulum's omega across zero at its extremes.)
    ///
    /// rapier clamps every body's speed after each substep, a kinematic body's too (at its
    /// `max_linear_velocity`, 400 m/s, and its angular rate at (pi/4) / dt unless fast rotation
    /// is allowed): a motion past either would leave the body behind while the snapshot reads
    /// the motion's rates, so the run stops instead. Validation refuses such a motion at the
    /// level's own dt (`level/validate/bodies.rs`); this catches a `--dt` that makes it so.
    pub(super) fn prescribe_velocities(&mut self, t0: f64, t1: f64) -> Result<(), SimError> {
        use crate::level::motion::pose_at;
        let cap = self.world.integration_parameters.max_linear_velocity() as f64;
        let h = t1 - t0;
        let turn_cap = (!self.settings.allow_fast_rotation)
            .then(|| std::f64::consts::FRAC_PI_4 / self.settings.dt);
        for &i in &self.prescribed {
            let b = &self.level.bodies[i];
            let rb = &mut self.world.bodies[self.bodies[i]];
            let c = to_d(rb.local_center_of_mass());
            let com = |t: f64| {
                let p = pose_at(b, t);
                DVec2::new(p.linear.0, p.linear.1) + DVec2::from_angle(p.angular).rotate(c)
            };
            let turn = pose_at(b, t1).angular - pose_at(b, t0).angular;
            let (v, omega) = ((com(t1) - com(t0)) / h, turn / h);
            let fast = v.length().is_nan() || v.length() > cap * (1.0 + 1e-6);
            let spins = turn_cap.is_some_and(|m| omega.is_nan() || omega.abs() > m * (1.0 + 1e-6));
            if fast || spins {
                let what = if fast {
                    format!(
                        "{:.3e} m/s, past rapier's speed cap of {cap} m/s",
                        v.length()
                    )
                } else {
                    format!(
                        "{:.3e} rad/s, past rapier's cap of (pi/4) / dt = {:.4} rad/s",
                        omega.abs(),
                        turn_cap.unwrap_or_default()
                    )
                };
                return Err(SimError {
                    step: self.snapshot.step + 1,
                    time: t1,
                    body: b.name.clone(),
                    quantity: format!(
                        "has a prescribed motion that reaches {what}: rapier clamps every body's \
                         rates there, so the body would not follow its motion; keep the motion \
                         within the cap (docs/levels.md, \"motion\")"
                    ),
                });
            }
            rb.set_linvel(vd(v), true);
            rb.set_angvel(omega as Real, true);
        }
        Ok(())
    }

    /// A prescribed body's velocity and omega in the snapshot are its motion's at the step's
    /// end, not rapier's mean over the last call (they differ by a dt / 2 under a constant
    /// acceleration; the mean of the start and end readings is then the step's mean, which
    /// is what rapier moved it with).
    pub(super) fn prescribed_rates(&mut self) {
        let t = self.snapshot.time;
        for &i in &self.prescribed {
            let (b, def) = (&mut self.snapshot.bodies[i], &self.level.bodies[i]);
            let r = crate::level::motion::rate_at(def, t);
            let o = crate::level::motion::pose_at(def, t).angular;
            b.omega = r.angular;
            // The snapshot's velocity is G's: v_O + omega x (G - O).
            let arm = DVec2::from_angle(o).rotate(b.local_com);
            b.velocity = DVec2::new(r.linear.0, r.linear.1) + r.angular * arm.perp();
        }
    }

    /// Stops a run whose mechanical energy grew FACTOR times beyond its initial scale plus the
    /// work put in (see `sim::explosion_guard`).
    pub(super) fn energy_guard(&mut self) -> Result<(), SimError> {
        let Some((gain, reference)) = self.energy.check(&self.snapshot) else {
            return Ok(());
        };
        // Name the body with the most kinetic energy: the one the explosion flung.
        let s = &self.snapshot;
        let body = s
            .bodies
            .iter()
            .max_by(|a, b| motion_energy(a).total_cmp(&motion_energy(b)))
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

    /// Stops a run that rapier's speed cap holds rather than the scene's forces (see
    /// `sim::explosion_guard`).
    pub(super) fn speed_cap_guard(&mut self) -> Result<(), SimError> {
        let cap = self.world.integration_parameters.max_linear_velocity() as f64;
        let Some(stop) = self.energy.check_speed_cap(&self.snapshot, cap) else {
            return Ok(());
        };
        let s = &self.snapshot;
        Err(SimError {
            step: s.step,
            time: s.time,
            body: s.bodies[stop.body].name.clone(),
            quantity: stop.what,
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

    pub(super) fn guard(&self) -> Result<(), SimError> {
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

    /// Spring states from the current body poses and velocities.
    pub(super) fn spring_states(&self, with_force: bool) -> Vec<SpringState> {
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
            let damper = c * (v2 - v1).dot(u);
            let tension = s.stiffness * x + damper;
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
                torsion: false,
                couple_on_body1: 0.0,
                damper_tension: if with_force { damper } else { 0.0 },
            });
        }
        for (k, t) in self.level.torsion_springs.iter().enumerate() {
            let (theta, rate) = self.relative_angle(&t.body1, t.body2.as_deref());
            let x = theta - self.torsion_rest.get(k).copied().unwrap_or(theta);
            let c = if self.settings.effects.has(Effect::Damping) {
                t.damping
            } else {
                0.0
            };
            // The spring's moment M = k x + c dx/dt turns body1 back toward rest.
            let damper = c * rate;
            let moment = t.stiffness * x + damper;
            let i1 = self.body_index[&t.body1];
            let g1 = self.snapshot.bodies[i1].com;
            out.push(SpringState {
                name: t.name.clone(),
                body1: i1,
                body2: t.body2.as_ref().map(|b| self.body_index[b]),
                point1: g1,
                point2: g1,
                length: theta,
                extension: x,
                tension: if with_force { moment } else { 0.0 },
                energy: 0.5 * t.stiffness * x * x,
                force_on_body1: DVec2::ZERO,
                applied_at1: g1,
                applied_at2: g1,
                torsion: true,
                couple_on_body1: if with_force { -moment } else { 0.0 },
                damper_tension: if with_force { damper } else { 0.0 },
            });
        }
        out
    }

    /// A torsion spring's relative angle theta = angle1 - angle2 (angle2 = 0 for the ground),
    /// continuous from the last snapshot's angles, and its rate, from rapier's current state.
    pub(super) fn relative_angle(&self, body1: &str, body2: Option<&str>) -> (f64, f64) {
        let angle = |name: &str| {
            let i = self.body_index[name];
            let rb = &self.world.bodies[self.bodies[i]];
            let prev = self.snapshot.bodies.get(i).map_or(0.0, |b| b.angle);
            (
                prev + wrap_pi(rb.rotation().angle() as f64 - prev),
                rb.angvel() as f64,
            )
        };
        let (a1, w1) = angle(body1);
        let (a2, w2) = body2.map_or((0.0, 0.0), angle);
        (a1 - a2, w1 - w2)
    }
}

pub(super) use crate::sim::angles::wrap_pi;

pub(crate) fn to_d(v: Vector) -> DVec2 {
    DVec2::new(v.x as f64, v.y as f64)
}

pub(super) fn vd(v: DVec2) -> Vector {
    Vector::new(v.x as Real, v.y as Real)
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
