//! One rigidlab step on Box2D: `substeps` calls of one substep each, with the step's loads
//! held and its impulse events applied at its start, every call's impulses read and summed.

use super::build::{v, Result};
use super::read::StepContacts;
use super::world::Simulation;
use crate::sim::{scalar_profile_at, vector_profile_at, SimError};
use crate::snapshot::{ImpulseState, LoadState, Snapshot};
use boxdd::{Position, Vec2};
use glam::DVec2;

/// A load held over the step: body, point in the body frame, force (world axes), couple.
type HeldLoad = (usize, DVec2, DVec2, f64);

fn pos(p: DVec2) -> Position {
    Position::new(p.x as _, p.y as _)
}

fn vec(p: DVec2) -> Vec2 {
    Vec2::new(p.x as f32, p.y as f32)
}

impl Simulation {
    /// Advances one step of `dt` and returns the new snapshot.
    pub fn step(&mut self) -> std::result::Result<&Snapshot, SimError> {
        let error = |s: &Snapshot, e: boxdd::Error| SimError {
            step: s.step + 1,
            time: s.time,
            body: String::new(),
            quantity: format!("could not be stepped by Box2D: {e}"),
        };
        if let Err(e) = self.step_calls() {
            return Err(error(&self.snapshot, e));
        }
        self.guard()?;
        Ok(&self.snapshot)
    }

    fn step_calls(&mut self) -> Result<()> {
        let dt = self.settings.dt;
        let n = self.settings.substeps.max(1);
        let h = dt / n as f64;
        let t0 = self.snapshot.time;
        self.apply_impulse_events(t0, dt)?;
        let loads = self.evaluate_loads(t0 + 0.5 * dt);
        self.clear_joint_impulses();
        let mut contacts = StepContacts::default();
        for _ in 0..n {
            let arms = self.joint_arms();
            self.apply_loads(&loads)?;
            // A failure found after Box2D advanced (a callback's) stops the run as one before.
            if let Some(e) = self.world.step(h as f32, 1)?.post_step_error() {
                return Err(e);
            }
            if self.contact_readings {
                self.add_contacts(&mut contacts)?;
            }
            self.add_joint_impulses(&arms, h)?;
            self.read_bodies()?;
        }
        self.store_contacts(contacts);
        self.read_joint_poses()?;
        let s = &mut self.snapshot;
        s.step += 1;
        s.time = t0 + dt;
        s.dt = dt;
        Ok(())
    }

    /// Applies the impulse events of this step at its start and lists them in the snapshot:
    /// those `describe::impulses_due` gives, as on rapier.
    fn apply_impulse_events(&mut self, t0: f64, dt: f64) -> Result<()> {
        self.snapshot.impulses.clear();
        for e in crate::sim::describe::impulses_due(&self.level.events, t0, dt) {
            let i = self.body_index(e.body);
            let p = self.snapshot.bodies[i].world_point(DVec2::new(e.point.0, e.point.1));
            let mut b = self.world.body(self.bodies[i])?;
            b.apply_linear_impulse(v(e.impulse), pos(p), true)?;
            b.apply_angular_impulse(e.angular as f32, true)?;
            self.snapshot.impulses.push(ImpulseState {
                name: e.name.to_string(),
                body: i,
                point: p,
                impulse: DVec2::new(e.impulse.0, e.impulse.1),
                angular_impulse: e.angular,
            });
        }
        Ok(())
    }

    /// The step's loads, evaluated at its middle `t_mid` and held over it; listed in the snapshot.
    fn evaluate_loads(&mut self, t_mid: f64) -> Vec<HeldLoad> {
        self.snapshot.loads.clear();
        let mut held = Vec::with_capacity(self.level.loads.len());
        for l in &self.level.loads {
            let i = self.body_index(&l.body);
            let local = DVec2::new(l.point.0, l.point.1);
            let f = l
                .force
                .as_ref()
                .map_or((0.0, 0.0), |f| vector_profile_at(f, t_mid));
            let f = DVec2::new(f.0, f.1);
            let m = l
                .torque
                .as_ref()
                .map_or(0.0, |m| scalar_profile_at(m, t_mid));
            held.push((i, local, f, m));
            self.snapshot.loads.push(LoadState {
                name: l.name.clone(),
                body: i,
                point: self.snapshot.bodies[i].world_point(local),
                force: f,
                torque: m,
            });
        }
        held
    }

    /// Applies the held loads for one call (Box2D clears applied forces after every call); the
    /// point of application moves with the body, as on rapier.
    fn apply_loads(&mut self, loads: &[HeldLoad]) -> Result<()> {
        for &(i, local, f, m) in loads {
            let p = self.snapshot.bodies[i].world_point(local);
            let mut b = self.world.body(self.bodies[i])?;
            b.apply_force(vec(f), pos(p), true)?;
            b.apply_torque(m as f32, true)?;
        }
        Ok(())
    }

    /// A blow between steps (the window's): impulse `j` (N s) at the world point `at` on body
    /// `i`, as on rapier (`sim::Simulation::apply_impulse`); false when there is no such body.
    pub fn apply_impulse(&mut self, i: usize, at: DVec2, j: DVec2) -> bool {
        let Some(&id) = self.bodies.get(i) else {
            return false;
        };
        let Ok(mut b) = self.world.body(id) else {
            return false;
        };
        b.apply_linear_impulse(vec(j), pos(at), true).is_ok()
    }

    /// Stops a run whose state became non-finite.
    fn guard(&self) -> std::result::Result<(), SimError> {
        for b in &self.snapshot.bodies {
            let finite = b.com.is_finite()
                && b.angle.is_finite()
                && b.velocity.is_finite()
                && b.omega.is_finite();
            if !finite {
                return Err(SimError {
                    step: self.snapshot.step,
                    time: self.snapshot.time,
                    body: b.name.clone(),
                    quantity: "state became non-finite (NaN or inf): the scene exploded".into(),
                });
            }
        }
        Ok(())
    }
}
