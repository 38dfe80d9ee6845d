//! A coupling's last tension held over the next rapier call, so that rapier's solver meets the
//! cable's pull with the joints and motors of the bodies it couples.
//!
//! rigidlab projects couplings after each rapier call (`sim/couplings.rs`). Projected alone, a
//! cable's pull reaches a body only after rapier's solver: a velocity motor on a drum winding a
//! cable then brings the bare drum to its rate within the call, the projection pulls the drum
//! back by the load's impulse F h through the drum's share r^2 / I of the pair's mobility,
//! and the motor never sees the load: the drum settles F h r^2 / I short of its rate (8.345
//! rad/s for 10, `tests/newuser/linkages/n11_09`, 1/240 s and 4 substeps). Held over the next
//! call as a generalized force (its last call's impulse over the call's length), the pull acts
//! inside rapier's solve, where the motor answers it; the projection then takes only what the
//! tension changed by over the call (none in steady motion), and its impulse is added to the
//! held one as the call's.
//!
//! A coordinate an ideal velocity motor holds does not give in the projection (the motor
//! answers the cable: `Simulation::solve_couplings`); the couple the projection would have given
//! it is the motor's, booked in the motor's reading (`book_motor_absorbed`).
//!
//! An impact's call is left out of the tension carried on: its impulse over the call's length
//! is a blow, not a pull, and held over the next call would strike again.

use super::rapier::prelude::*;
use super::world::Simulation;
use crate::level::{Coordinate, Effect, JointKind, Motor};

impl Simulation {
    /// Applies each coupling's held tension to its terms: r_i T along x or y at the mass center,
    /// or the couple r_i T, on each dynamic body (after `apply_forces` reset them).
    pub(super) fn hold_coupling_tensions(&mut self) {
        if !self.settings.effects.has(Effect::Joints) {
            return;
        }
        for (k, c) in self.level.couplings.iter().enumerate() {
            let t = self.coupling_tension.get(k).copied().unwrap_or(0.0);
            if t == 0.0 {
                continue;
            }
            for term in &c.terms {
                let rb = &mut self.world.bodies[self.bodies[self.body_index[&term.body]]];
                if !rb.is_dynamic() {
                    continue;
                }
                let f = (term.ratio * t) as Real;
                match term.coordinate {
                    Coordinate::X => rb.add_force(Vector::new(f, 0.0), true),
                    Coordinate::Y => rb.add_force(Vector::new(0.0, f), true),
                    Coordinate::Angle => rb.add_torque(f, true),
                }
            }
        }
    }

    /// After a call of length `h` whose projection took `projected`: adds the held impulses,
    /// making each coupling's impulse over the call, and keeps it over `h` as the next call's
    /// tension, unless the call met an impact (`impact`: the tension held is kept).
    pub(super) fn close_coupling_call(&mut self, projected: &mut [f64], h: f64, impact: bool) {
        for (k, lambda) in projected.iter_mut().enumerate() {
            let Some(t) = self.coupling_tension.get_mut(k) else {
                continue;
            };
            *lambda += *t * h;
            if !impact && h > 0.0 {
                *t = *lambda / h;
            }
        }
    }

    /// Adds to each ideal motor's reading the couple the projections of the step gave it instead
    /// of its body (`motor_absorbed`), and clears it: on body2 as the motor's impulse and in both
    /// bodies' angular impulses.
    pub(super) fn book_motor_absorbed(&mut self) {
        if self.motor_absorbed.iter().all(|&x| x == 0.0) {
            return;
        }
        let held = self.motor_held_angles();
        for (j, def) in self.snapshot.joints.iter_mut().zip(&self.joint_defs) {
            let ideal = matches!(
                def.motor,
                Some(Motor::Velocity {
                    max_force: None,
                    ..
                })
            );
            if !ideal || def.kind != JointKind::Revolute {
                continue;
            }
            let (b1, b2) = (j.body1, j.body2);
            let (on2, held_body) = if held[b2] {
                (self.motor_absorbed[b2], b2)
            } else if held[b1] {
                (-self.motor_absorbed[b1], b1)
            } else {
                continue;
            };
            j.motor_impulse += on2;
            j.angular_impulse_on_body2 += on2;
            j.angular_impulse_on_body1 -= on2;
            self.motor_absorbed[held_body] = 0.0;
        }
        self.motor_absorbed.iter_mut().for_each(|x| *x = 0.0);
    }
}
