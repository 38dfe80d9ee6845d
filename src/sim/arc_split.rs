//! Whether a step's substeps are split into one-substep rapier calls because a ball rides an
//! `Arc`'s circle on the chord contact (sim/arc_curvature.rs).
//!
//! rapier makes its contacts once a call, so the chord contact's normal, the chord's plane and
//! its normal speed are set at the call's start and held over the call's substeps. On a circle
//! of G's path radius rho at speed v the chord is exact at the call's ends only: between them the
//! solver keeps G on a plane that lags the circle by about v^2 t (h - t) / (2 rho) at a time t
//! into a call of length h, and the contact pushes in hops, once a call, with what it did not
//! push in the substeps between. Measured 2026-12-06 at the level's 4 substeps a 1 ms call:
//! tests/newuser/curved/n14_15 (a puck off a smooth cylinder at 1.2 m/s) read the normal force
//! at 30 degrees over 0.01 s 4.4e-2 low, n14_14's leaving angle was 1.06e-2 off at 8 substeps,
//! and the loop's N at the top (n14_02) changed with the substeps. In one-substep calls the
//! chord is exact at every substep's end, as a spinning ball's contact is
//! (sim/contact_points.rs, `spin_calls`), at the price of a call a substep
//! (runner/budget.rs prices it from the start).
//!
//! Only the pairs the chord contact takes (a dynamic ball, smooth, on a fixed arc): a rough
//! pair keeps rapier's plane and its calls.

use super::arc_track::ArcTrack;
use super::contact_points::RoundColliders;
use super::rapier::prelude::*;

/// rapier's contact prediction distance (its default, 2 mm at a length unit of 1 m): a ball
/// this near an arc's circle at the start is in contact for the first call.
const START_GAP: Real = 2e-3;

/// Whether a dynamic, smooth ball touches a fixed arc's circle: in the last call's contacts, or
/// on the first step (before rapier made any) within [`START_GAP`] of the circle.
///
/// `round`: the world's arcs and balls (`contact_points::RoundColliders`), so that a step does
/// not test every collider's shape.
pub(crate) fn smooth_ball_rides_arc(
    world: &PhysicsWorld,
    round: &RoundColliders,
    first_step: bool,
) -> bool {
    round.arcs.iter().any(|&arc_h| {
        let Some(arc_c) = world.colliders.get(arc_h) else {
            return false;
        };
        let Some(arc) = arc_c.shape().as_shape::<ArcTrack>() else {
            return false;
        };
        let arc_fixed = arc_c
            .parent()
            .and_then(|b| world.bodies.get(b))
            .is_none_or(|b| b.is_fixed());
        if !arc_fixed || arc_c.friction() != 0.0 {
            return false;
        }
        let rides = |ball_h: ColliderHandle| {
            let Some(ball_c) = world.colliders.get(ball_h) else {
                return false;
            };
            let Some(ball) = ball_c.shape().as_ball() else {
                return false;
            };
            let dynamic = ball_c
                .parent()
                .and_then(|b| world.bodies.get(b))
                .is_some_and(|b| b.is_dynamic());
            let c = arc_c
                .position()
                .inverse_transform_point(ball_c.position().translation);
            dynamic
                && ball_c.friction() == 0.0
                && arc.spans_point(c)
                && (!first_step || arc.touch(c, ball.radius).dist <= START_GAP)
        };
        if first_step {
            round.balls.iter().any(|&h| h != arc_h && rides(h))
        } else {
            world
                .narrow_phase
                .contact_pairs_with(arc_h)
                .filter(|pair| pair.has_any_active_contact())
                .any(|pair| {
                    rides(if pair.collider1 == arc_h {
                        pair.collider2
                    } else {
                        pair.collider1
                    })
                })
        }
    })
}
