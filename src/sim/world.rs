//! The running simulation of one level (compiled once per precision, see `sim/mod.rs`).

use super::build;
use super::profiles::{scalar_profile_at, vector_profile_at};
use super::rapier::prelude::*;
use super::readings::{merge_contacts, merge_joints, place_at_step_end};
use crate::level::*;
use crate::sim::explosion_guard::{motion_energy, EnergyGuard, FACTOR, SUSTAIN};
use crate::sim::options::{Options, SimError};
use crate::sim::settings::{Settings, StepCalls, Substepping};
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
    /// Welds still waiting for their first contact: (event name, body1, body2).
    pub(super) pending_welds: Vec<(String, usize, usize)>,
    /// Bodies that loads or springs act on (their forces are reset every step).
    pub(super) forced_bodies: Vec<usize>,
    /// Each torsion spring's rest angle, rad (its own, or the relative angle at t = 0).
    pub(super) torsion_rest: Vec<f64>,
    /// Energy-explosion guard (see `sim::explosion_guard`).
    pub energy: EnergyGuard,
    /// Whether the snapshot carries the step's contacts (`Simulation::set_contact_readings`).
    pub(super) contact_readings: bool,
    /// Whether the level has a kinematic body (the energy guard reads its contacts).
    has_kinematic: bool,
    /// The world's own normalized prediction distance, restored after a call the impact plan
    /// lowered it for (sim/impacts.rs).
    pub(super) prediction_distance: Real,
    /// Whether the last rapier call made an impact's contact: the next call then solves its
    /// unbiased pass to convergence too (sim/impacts.rs, `IMPACT_ITERATIONS`).
    pub(super) after_impact: bool,
    /// How many times the impact planner cut the last step's calls (sim/impacts.rs): what the
    /// tests read to see that a pair rapier never collides is not planned as an impact.
    pub last_step_cuts: usize,
    /// How the run's steps have been called so far (`Settings::as_run` reports them).
    pub calls: StepCalls,
}

impl Simulation {
    // Not yet split into named steps (issue 44): builds the rapier world from a scene in the order rapier needs.
    #[allow(clippy::too_many_lines)]
    pub fn new(scene: &Scene, opts: &Options) -> Self {
        let level = scene.level.clone();
        let settings = Settings::resolve(&level, opts, super::PRECISION);
        let effects = &settings.effects;
        let mut world = PhysicsWorld::new();
        // A ball on an arc track touches the circle, not its facets (sim/arc_contacts.rs).
        world
            .narrow_phase
            .set_query_dispatcher(super::arc_contacts::dispatcher());
        world.gravity = build::gravity(&level);
        world.integration_parameters = build::integration_parameters(&settings);
        let prediction_distance = world.integration_parameters.normalized_prediction_distance;
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
            joint_bodies: Vec::new(),
            body_index,
            coupling_rest: Vec::new(),
            carriers: Vec::new(),
            pending_welds: Vec::new(),
            forced_bodies: Vec::new(),
            torsion_rest: Vec::new(),
            energy: EnergyGuard::default(),
            contact_readings: true,
            prediction_distance,
            after_impact: false,
            last_step_cuts: 0,
            calls: StepCalls::default(),
            has_kinematic: scene
                .level
                .bodies
                .iter()
                .any(|b| b.kind == BodyKind::Kinematic),
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
        for t in &sim.level.torsion_springs {
            forced.push(sim.body_index[&t.body1]);
            forced.extend(t.body2.as_ref().map(|b| sim.body_index[b]));
        }
        sim.carriers = sim
            .level
            .couplings
            .iter()
            .map(|c| {
                let over = c.over.iter().map(|b| (sim.body_index[b], DVec2::ZERO));
                let gears = c
                    .terms
                    .iter()
                    .filter(|_| c.gears)
                    .map(|t| (sim.body_index[&t.body], DVec2::ZERO));
                over.chain(gears).collect()
            })
            .collect();
        forced.extend(sim.carriers.iter().flatten().map(|c| c.0));
        forced.sort_unstable();
        forced.dedup();
        forced.sort_unstable();
        forced.dedup();
        sim.forced_bodies = forced;
        sim.read_bodies();
        sim.prescribed_rates();
        sim.torsion_rest = sim
            .level
            .torsion_springs
            .iter()
            .map(|t| {
                t.rest_angle
                    .unwrap_or_else(|| sim.relative_angle(&t.body1, t.body2.as_deref()).0)
            })
            .collect();
        sim.snapshot.springs = sim.spring_states(false);
        sim.coupling_rest = sim
            .level
            .couplings
            .iter()
            .map(|c| sim.coupling_value(c))
            .collect();
        let none = vec![0.0; sim.level.couplings.len()];
        let carried: Vec<Vec<DVec2>> = sim
            .carriers
            .iter()
            .map(|c| vec![DVec2::ZERO; c.len()])
            .collect();
        sim.snapshot.couplings = sim.coupling_states(&none, &carried);
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
    fn contacts_wanted(&self) -> bool {
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

    /// Advances one physics step and refreshes the snapshot.
    // Not yet split into named steps (issue 44): one rapier call's phases (forces, impact cuts, split substeps, readings) share the world's borrows.
    #[allow(clippy::too_many_lines)]
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
            let mut f = l
                .force
                .as_ref()
                .map_or((0.0, 0.0), |f| vector_profile_at(f, t_mid));
            if l.follow_body {
                let r =
                    DVec2::from_angle(rb.rotation().angle() as f64).rotate(DVec2::new(f.0, f.1));
                f = (r.x, r.y);
            }
            let m = l
                .torque
                .as_ref()
                .map_or(0.0, |m| scalar_profile_at(m, t_mid));
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
        // A spinning ball's contact is followed exactly only over one-substep calls
        // (sim/contact_points.rs).
        let split = self.settings.substepping == Substepping::Split
            || (n > 1
                && super::contact_points::spinning_ball_touches(
                    &self.world,
                    self.snapshot.step == 0,
                ));
        // The rapier calls of this step, (length, rapier substeps): n calls of one substep when
        // split, else one call of n; an impact cut (sim/impacts.rs) divides a call in two.
        let mut calls: std::collections::VecDeque<(f64, usize)> = if split {
            std::iter::repeat_n((dt / n as f64, 1), n).collect()
        } else {
            std::iter::once((dt, n)).collect()
        };
        let mut cuts = 0;
        // A blow (an impulse event) this step: its first call solves friction to convergence, as
        // an impact's does (sim/impacts.rs, IMPACT_ITERATIONS).
        let blow = !self.snapshot.impulses.is_empty();
        // Whether the coming call is the short one a cut planned for its contact (then no pair
        // touching in it is cut again).
        let mut impact_call_next = false;
        let mut merged = split;
        let mut lambdas = vec![0.0; self.level.couplings.len()];
        let mut carried: Vec<Vec<DVec2>> = self
            .carriers
            .iter()
            .map(|c| vec![DVec2::ZERO; c.len()])
            .collect();
        let mut springs: Vec<SpringState> = Vec::new();
        let mut joint_sum: Vec<JointState> = Vec::new();
        let mut contact_sum: Vec<ContactState> = Vec::new();
        let mut first_call = true;
        let contacts_wanted = self.contacts_wanted();
        // The time into the step at which the coming call starts.
        let mut elapsed = 0.0;
        while let Some((mut h, sub)) = calls.pop_front() {
            let mut prediction = None;
            let impact_call = std::mem::take(&mut impact_call_next);
            // Whether this call makes an impact's contact or takes a blow (sim/impacts.rs,
            // IMPACT_ITERATIONS).
            let mut impact_now = impact_call || (first_call && blow);
            if self.settings.impact_cuts && cuts < super::impacts::MAX_CUTS {
                let plan = self.plan_call(h, !impact_call);
                prediction = Some(plan.prediction);
                if let Some(t) = plan.cut {
                    // The contact is made in a short call after the cut, where rapier's soft
                    // contact acts as a nearly rigid one (its softness grows with the call's
                    // length), then the rest of the call.
                    let impact = (h - t).min(h * super::impacts::IMPACT_CALL);
                    if h - t - impact > 0.0 {
                        calls.push_front((h - t - impact, sub));
                    }
                    if t > 0.0 {
                        calls.push_front((impact, sub));
                        impact_call_next = true;
                        h = t;
                    } else {
                        h = impact;
                        impact_now = true;
                    }
                    cuts += 1;
                    merged = true;
                }
            }
            {
                let p = &mut self.world.integration_parameters;
                p.dt = h as Real;
                p.num_solver_iterations = sub;
                p.normalized_prediction_distance =
                    prediction.map_or(self.prediction_distance, |x| x as Real);
                // An impact's call and the one after it solve friction to convergence.
                p.num_internal_stabilization_iterations = if impact_now || self.after_impact {
                    self.settings
                        .solver_iterations
                        .max(super::impacts::IMPACT_ITERATIONS)
                } else {
                    self.settings.solver_iterations
                };
                self.after_impact = impact_now;
            }
            self.apply_forces(&loads);
            self.load_carriers(h, &mut carried);
            let mut now = self.spring_states(true);
            for s in &now {
                let rb1 = &mut self.world.bodies[self.bodies[s.body1]];
                if s.torsion {
                    rb1.add_torque(s.couple_on_body1 as Real, true);
                } else {
                    rb1.add_force_at_point(vd(s.force_on_body1), vd(s.applied_at1), true);
                }
                if let Some(b2) = s.body2 {
                    let rb2 = &mut self.world.bodies[self.bodies[b2]];
                    if s.torsion {
                        rb2.add_torque(-s.couple_on_body1 as Real, true);
                    } else {
                        rb2.add_force_at_point(vd(-s.force_on_body1), vd(s.applied_at2), true);
                    }
                }
            }
            // The snapshot reports the mean force over the step (its impulse / dt).
            let weight = h / dt;
            for sp in now.iter_mut() {
                sp.force_on_body1 *= weight;
                sp.tension *= weight;
                sp.damper_tension *= weight;
                sp.couple_on_body1 *= weight;
            }
            if first_call {
                springs = now;
            } else {
                for (a, b) in springs.iter_mut().zip(&now) {
                    a.force_on_body1 += b.force_on_body1;
                    a.tension += b.tension;
                    a.damper_tension += b.damper_tension;
                    a.couple_on_body1 += b.couple_on_body1;
                }
            }
            first_call = false;
            // rapier builds a substep's joint rows from the poses it starts from: keep them,
            // so the call's impulses (all of one substep) are read along the very rows they
            // acted on.
            let rows_from = (split || self.settings.impact_cuts).then(|| self.joint_poses());
            self.prescribe_velocities(t0 + elapsed, t0 + elapsed + h)?;
            elapsed += h;
            // Round bodies' friction acts on their rims, not halfway into an overlap
            // (sim/contact_points.rs).
            self.world.step_with_events(
                &super::contact_points::RoundContactPoints {
                    call_dt: h as Real,
                    gravity: self.world.gravity,
                },
                &(),
            );
            let call_lambdas = self.solve_couplings();
            self.owe_carriers(&call_lambdas);
            for (l, x) in lambdas.iter_mut().zip(call_lambdas) {
                *l += x;
            }
            // A call of several rapier substeps holds the last one's joint impulses only.
            if let Some(poses) = rows_from.filter(|_| split || merged || !calls.is_empty()) {
                if contacts_wanted {
                    self.read_contacts_with(true);
                    merge_contacts(&mut contact_sum, &self.snapshot.contacts);
                }
                self.read_joints_scaled(sub as f64, Some(&poses));
                merge_joints(&mut joint_sum, &self.snapshot.joints);
            }
        }
        self.last_step_cuts = cuts;
        self.calls.steps += 1;
        if split && n > 1 && self.settings.substepping != Substepping::Split {
            self.calls.split_for_spin += 1;
        }
        if cuts > 0 {
            self.calls.cut += 1;
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
        self.prescribed_rates();
        self.guard()?;
        if !contacts_wanted {
            self.snapshot.contacts.clear();
        } else if merged {
            place_at_step_end(&mut contact_sum, &self.snapshot.bodies);
            self.snapshot.contacts = contact_sum;
        } else {
            self.read_contacts();
        }
        self.weld_on_contact();
        // Welds created now get their first impulses next step.
        if merged {
            self.snapshot.joints = joint_sum;
        } else {
            self.read_joints();
        }
        self.snapshot.couplings = self.coupling_states(&lambdas, &carried);
        // Spring state: forces held during the step, length and energy at its end.
        let end = self.spring_states(false);
        self.snapshot.springs = springs
            .into_iter()
            .zip(end)
            .map(|(held, now)| SpringState {
                force_on_body1: held.force_on_body1,
                tension: held.tension,
                damper_tension: held.damper_tension,
                couple_on_body1: held.couple_on_body1,
                applied_at1: held.applied_at1,
                applied_at2: held.applied_at2,
                ..now
            })
            .collect();
        self.energy.add_work(&self.snapshot);
        self.energy_guard()?;
        self.speed_cap_guard()?;
        Ok(&self.snapshot)
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
    fn prescribe_velocities(&mut self, t0: f64, t1: f64) -> Result<(), SimError> {
        use crate::level::motion::pose_at;
        let cap = self.world.integration_parameters.max_linear_velocity() as f64;
        let h = t1 - t0;
        let turn_cap = (!self.settings.allow_fast_rotation)
            .then(|| std::f64::consts::FRAC_PI_4 / self.settings.dt);
        for (i, b) in self.level.bodies.iter().enumerate() {
            if b.motion.is_none() {
                continue;
            }
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
    fn prescribed_rates(&mut self) {
        let t = self.snapshot.time;
        for (b, def) in self.snapshot.bodies.iter_mut().zip(&self.level.bodies) {
            if def.motion.is_some() {
                let r = crate::level::motion::rate_at(def, t);
                let o = crate::level::motion::pose_at(def, t).angular;
                b.omega = r.angular;
                // The snapshot's velocity is G's: v_O + omega x (G - O).
                let arm = DVec2::from_angle(o).rotate(b.local_com);
                b.velocity = DVec2::new(r.linear.0, r.linear.1) + r.angular * arm.perp();
            }
        }
    }

    /// Stops a run whose mechanical energy grew FACTOR times beyond its initial scale plus the
    /// work put in (see `sim::explosion_guard`).
    fn energy_guard(&mut self) -> Result<(), SimError> {
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
    fn speed_cap_guard(&mut self) -> Result<(), SimError> {
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
    fn relative_angle(&self, body1: &str, body2: Option<&str>) -> (f64, f64) {
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

/// Wraps an angle difference to (-pi, pi].
pub(super) fn wrap_pi(a: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    a - TAU * ((a + PI) / TAU).floor()
}

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
