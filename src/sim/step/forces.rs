//! The forces rigidlab applies itself, so that their impulses and work are known exactly:
//! impulse events, loads, springs and dampers, and the pulls couplings owe their carriers.

use super::super::build;
use super::super::profiles::{scalar_profile_at, vector_profile_at};
use super::super::rapier::prelude::*;
use super::super::world::{to_d, vd, Simulation};
use super::calls::StepReadings;
use super::plan::Call;
use crate::snapshot::*;
use glam::DVec2;

/// A load held over the step: the body's index, the point (body frame), the force (world) and
/// the couple.
pub(super) type HeldLoad = (usize, Vector, Vector, Real);

impl Simulation {
    /// Applies the impulse events of this step to their bodies and lists them in the snapshot.
    pub(super) fn apply_impulse_events(&mut self, t0: f64, dt: f64) {
        self.snapshot.impulses.clear();
        // Each acts at the start of the step that begins nearest to its time (`describe`).
        for e in crate::sim::describe::impulses_due(&self.level.events, t0, dt) {
            let i = self.body_index[e.body];
            let rb = &mut self.world.bodies[self.bodies[i]];
            let p = *rb.position() * build::v(e.point);
            rb.apply_impulse_at_point(build::v(e.impulse), p, true);
            rb.apply_torque_impulse(e.angular as Real, true);
            self.snapshot.impulses.push(ImpulseState {
                name: e.name.to_string(),
                body: i,
                point: to_d(p),
                impulse: DVec2::new(e.impulse.0, e.impulse.1),
                angular_impulse: e.angular,
            });
        }
    }

    /// The step's loads, forces held over the step, evaluated at its middle `t_mid`; listed in
    /// the snapshot.
    pub(super) fn evaluate_loads(&mut self, t_mid: f64) -> Vec<HeldLoad> {
        self.snapshot.loads.clear();
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
        loads
    }

    /// The forces held over one rapier call: the step's loads, the pulls the carriers are owed
    /// (sim/couplings.rs), the couplings' last tensions (sim/coupling_tension.rs), springs evaluated at the call's start and dampers at its predicted
    /// mean rate (`dampers.rs`), which `readings` sums as the step's mean.
    pub(super) fn apply_call_forces(
        &mut self,
        loads: &[HeldLoad],
        call: &Call,
        dt: f64,
        readings: &mut StepReadings,
    ) {
        self.apply_forces(loads);
        self.load_carriers(call.h, &mut readings.carried);
        self.hold_coupling_tensions();
        let mut springs = self.apply_springs();
        self.hold_dampers_at_mean_rate(&mut springs, call.h);
        readings.add_springs(springs, call.h / dt, call.first);
    }

    /// Clears the user forces of loaded and sprung bodies and applies the step's loads.
    fn apply_forces(&mut self, loads: &[HeldLoad]) {
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

    /// Applies each spring's and torsion spring's force (with its damper's) from the bodies'
    /// current poses and velocities, and returns the springs' states.
    fn apply_springs(&mut self) -> Vec<SpringState> {
        let springs = self.spring_states(true);
        for s in &springs {
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
        springs
    }
}
