//! Where the solver takes a round body's contact: on the round body's own surface.
//!
//! rapier 0.36 puts a contact's solver point, the point its normal and friction rows act at and
//! their lever arms reach, halfway between the two surfaces' contact points
//! (`geometry/narrow_phase/pair_update.rs`: `point = (p1 + anchor2) * 0.5`, frozen as
//! `solver_dp1`/`solver_dp2`). While two bodies overlap by a depth p, a disc's friction row then
//! makes the disc roll without slip about a point p/2 inside its rim: its rolling radius is
//! r - p/2, and its rim creeps on the other body at omega p/2. Measured on a disc rolling on a
//! pulled plank (r = 0.15 m, 19 rad/s after 1 s; tests/sim_friction_moving_bodies.rs): the two
//! soft dynamic bodies overlap 0.7 mm at 1/240 s, the rim crept 6.4 mm/s and the slip over omega
//! was 0.33 mm, half the overlap, at every setting tried; the friction force came out 0.25%
//! above the textbook's, as a rolling radius 0.33 mm short predicts.
//!
//! The textbook's disc rolls on its rim, so for a pair in which exactly one collider is a ball
//! this hook moves the solver point onto the ball's surface point, keeping the separation rapier
//! measured: the ball's anchor stays, and the other's moves along the normal so that the
//! midpoint rapier takes is the ball's point. The normal row still passes through the ball's
//! center; only the friction row's lever arm changes, from r - p/2 to r. Two balls keep rapier's
//! midpoint (each rolls on a rim; neither can be favoured).

use super::rapier::prelude::*;

/// The hook rigidlab steps rapier with (`world::Simulation::step`); ball colliders ask for it
/// with `ActiveHooks::MODIFY_SOLVER_CONTACTS` (`build::colliders`).
pub(crate) struct RoundContactPoints;

impl PhysicsHooks for RoundContactPoints {
    fn modify_solver_contacts(&self, context: &mut ContactModificationContext) {
        let is_ball = |h: ColliderHandle| {
            context
                .colliders
                .get(h)
                .is_some_and(|c| c.shape().as_ball().is_some())
        };
        let (ball1, ball2) = (is_ball(context.collider1), is_ball(context.collider2));
        if ball1 == ball2 {
            return;
        }
        let ModifiableContacts::Rigid(m) = &mut context.contacts else {
            return;
        };
        let n = *m.normal;
        for sc in m.solver_contacts.iter_mut() {
            // rapier keeps (anchor2 - p1) . n = dist with p1 = anchor1 moved along n, and takes
            // the midpoint of p1 and anchor2: anchor2 = B + n dist / 2 puts it at B, the ball's
            // point (anchor1 for collider 1, anchor2 for collider 2; anchor1 then only gives p1
            // its tangential place, B's).
            let b = if ball1 { sc.anchor1 } else { sc.anchor2 };
            sc.anchor1 = b;
            sc.anchor2 = b + n * (sc.dist * 0.5);
        }
    }
}
