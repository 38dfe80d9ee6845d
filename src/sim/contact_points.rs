//! Where the solver takes a round body's contact: on the round body's own surface.
//!
//! rapier 0.36 puts a contact's solver point, the point its normal and friction rows act at and
//! their lever arms reach, halfway between the two surfaces' contact points
//! (`geometry/narrow_phase/pair_update.rs`: `point = (p1 + anchor2) * 0.5`, frozen as
//! `solver_dp1`/`solver_dp2`). While two bodies overlap by a depth p, a disc's friction row then
//! makes the disc roll without slip about a point p/2 inside its rim: its rolling radius is
//! r - p/2, and its rim creeps on the other body at omega p/2. Measured on a disc rolling on a
//! pulled plank (r = 0.15 m, 19 rad/s after 1 s; tests/suite/sim/friction_moving_bodies.rs): the two
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
//!
//! Second, a spinning ball keeps its contact. Within a call rapier follows each contact's
//! separation from anchors that ride their bodies' rigid motion, so a ball's anchor turns with
//! the ball and leaves the point facing the other body: the solver sees that body fall away at
//! the rim's centripetal acceleration r w^2. This hook gives rapier the normal speed that
//! cancels the turn over the call ([`spin_offset_rate`]), exact at a call's start and end, and
//! the simulation calls rapier one substep at a time while a ball spins in contact
//! ([`spinning_ball_touches`]), so that those are the only instants rapier reads.

use super::rapier::prelude::*;

/// The hook rigidlab steps rapier with (`world::Simulation::step`); ball colliders ask for it
/// with `ActiveHooks::MODIFY_SOLVER_CONTACTS` (`build::colliders`).
pub(crate) struct RoundContactPoints {
    /// The length of the rapier call the contacts are built for (s): a spinning ball's anchor
    /// is followed over it ([`spin_offset_rate`]), a ball on an arc turns over it
    /// (sim/arc_curvature.rs).
    pub call_dt: Real,
    /// The world's gravity (a ball on an arc: the friction rows' share of its normal impulse).
    pub gravity: Vector,
}

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
        let arc_call = self.arc_call(context, ball1);
        let ModifiableContacts::Rigid(m) = &mut context.contacts else {
            return;
        };
        if let Some(call) = arc_call {
            // Third: a ball on an arc's circle follows the circle over the call
            // (sim/arc_curvature.rs).
            *m.normal = call.normal;
            *m.restitution = call.restitution;
            if let Some(mu) = call.friction {
                *m.friction = mu;
            }
            for sc in m.solver_contacts.iter_mut() {
                sc.dist = call.dist;
                if ball1 {
                    sc.anchor1 = call.ball_point;
                } else {
                    sc.anchor2 = call.ball_point;
                }
                sc.tangent_velocity += call.normal * call.normal_speed;
            }
        } else if m.manifold.subshape1 == super::arc_contacts::CIRCLE
            && *m.restitution < 1.0
            && m.manifold
                .points
                .iter()
                .any(|p| p.data.warmstart_impulse != 0.0)
        {
            // The dispatcher shows the circle's contact as new to every call: a resting one
            // bounces no more than rapier would bounce it.
            *m.restitution = 0.0;
        }
        let n = *m.normal;
        let ball_body = if ball1 {
            context.rigid_body1
        } else {
            context.rigid_body2
        };
        let (center, omega) = ball_body
            .and_then(|h| context.bodies.get(h))
            .map_or((None, 0.0), |rb| (Some(rb.center_of_mass()), rb.angvel()));
        for sc in m.solver_contacts.iter_mut() {
            // rapier keeps (anchor2 - p1) . n = dist with p1 = anchor1 moved along n, and takes
            // the midpoint of p1 and anchor2: anchor2 = B + n dist / 2 puts it at B, the ball's
            // point (anchor1 for collider 1, anchor2 for collider 2; anchor1 then only gives p1
            // its tangential place, B's).
            let b = if ball1 { sc.anchor1 } else { sc.anchor2 };
            sc.anchor1 = b;
            sc.anchor2 = b + n * (sc.dist * 0.5);
            if let Some(c) = center {
                sc.tangent_velocity += n * spin_offset_rate(b - c, omega, self.call_dt, n, ball1);
            }
        }
    }
}

impl RoundContactPoints {
    /// How a ball's contact with an arc's circle is handed to the solver for this call, or
    /// None for any other pair (sim/arc_curvature.rs).
    fn arc_call(
        &self,
        context: &ContactModificationContext,
        ball1: bool,
    ) -> Option<super::arc_curvature::ArcCall> {
        let m = context.rigid()?;
        if m.manifold.subshape1 != super::arc_contacts::CIRCLE || m.solver_contacts.len() != 1 {
            return None;
        }
        let (ball_h, arc_h, ball_body, arc_body) = if ball1 {
            (
                context.collider1,
                context.collider2,
                context.rigid_body1,
                context.rigid_body2,
            )
        } else {
            (
                context.collider2,
                context.collider1,
                context.rigid_body2,
                context.rigid_body1,
            )
        };
        let (ball_c, arc_c) = (
            context.colliders.get(ball_h)?,
            context.colliders.get(arc_h)?,
        );
        // An arc's circle, or the circle of a track's arc piece nearest the ball (the piece the
        // dispatcher gave the contact of: sim/track_shape.rs).
        let local = arc_c
            .position()
            .inverse_transform_point(ball_c.position().translation);
        let arc = super::track_shape::curved(arc_c.shape())?.circle(local)?;
        let ball = ball_c.shape().as_ball()?;
        // A moving track keeps rapier's plane (the module's doc).
        if arc_body
            .and_then(|h| context.bodies.get(h))
            .is_some_and(|rb| !rb.is_fixed())
        {
            return None;
        }
        let rb = context.bodies.get(ball_body?)?;
        if !rb.is_dynamic() {
            return None;
        }
        let center = ball_c.position().translation;
        // rapier's own newness: a contact that bore no load in the last call.
        let resting = m
            .manifold
            .points
            .iter()
            .any(|p| p.data.warmstart_impulse != 0.0);
        let state = super::arc_curvature::Ball {
            center,
            r: ball.radius,
            w: rb.velocity_at_point(center),
            rough: (m.friction.abs() > 0.0).then(|| super::arc_curvature::Rough {
                mu: *m.friction,
                inv_mass: rb.mass_properties().effective_inv_mass.x,
                inv_inertia: rb.mass_properties().effective_world_inv_inertia,
                omega: rb.angvel(),
            }),
        };
        super::arc_curvature::for_ball_on_arc(
            arc,
            arc_c.position(),
            state,
            ball1,
            (*m.restitution, resting),
            self.gravity,
            self.call_dt,
        )
    }
}

/// The normal speed that cancels, over a call of length `call_dt`, the drift of a spinning
/// ball's anchor off its surface point.
///
/// rapier follows a contact's separation within a call from anchors fixed in each body
/// (`contact_with_coulomb_friction.rs`, `update`: dist = dist0 + (p1 - p2) . n with p1, p2
/// carried by each body's rigid motion; the stabilization pass reads it after the positions are
/// integrated). A ball's anchor at arm a from its center turns with the ball, so after a time t
/// it has left the surface point facing the other body by (R(w t) a - a) . n = r (1 - cos w t)
/// along the normal, away from the contact: the solver sees the floor fall away at the rim's
/// centripetal acceleration r w^2 and pushes only m (g - r w^2) against it. A disc (r = 0.2 m)
/// spun at 5 rad/s on a floor got 0.49 to 0.55 of m g dt in its first step, at 20 rad/s none,
/// and sank 3.3 mm at 1/60 s (2026-11-26; tests/suite/sim/spinning_contact.rs holds the fix). The ball's true surface point
/// keeps its arm: it moves with the center only.
///
/// rapier adds `tangent_velocity * t` to p1 in that update (its tangential part is the
/// conveyor speed of the friction rows; the normal part only enters the separation), so a normal
/// part s = -(R(w T) a - a) . n / T takes the drift out exactly at the call's start and end
/// (the updates of a one-substep call) and leaves a residual of at most r w^2 T^2 / 8 between
/// (an apparent overlap, which the soft contact's bias treats gently) for several substeps a call.
/// For the ball as collider 2 the drift enters with the opposite sign.
fn spin_offset_rate(
    arm: Vector,
    omega: Real,
    call_dt: Real,
    n: Vector,
    ball_is_first: bool,
) -> Real {
    if call_dt <= 0.0 || omega == 0.0 {
        return 0.0;
    }
    let (s, c) = (omega * call_dt).sin_cos();
    let turned = Vector::new(c * arm.x - s * arm.y, s * arm.x + c * arm.y);
    let drift = (turned - arm).dot(n) / call_dt;
    if ball_is_first {
        -drift
    } else {
        drift
    }
}

/// Whether this step's rapier calls must each be one substep for a spinning ball's contact.
///
/// The normal speed [`spin_offset_rate`] hands rapier is exact at a call's start and end only:
/// over a call of several substeps the drift, quadratic in time, leaves a residual of up to
/// r w^2 T^2 / 8 between, an apparent overlap the contact's bias pushes out. Measured on a disc
/// (r = 0.2 m) spun on a floor in one call of 4 or 16 substeps (2026-11-27): its first normal
/// impulse was 2% to 8% short at a residual of 0.17 mm, 25% at 1.1 mm, and at 2.8 mm the disc
/// rose 0.44 mm; and a disc rolling off a cylinder (`tests/newuser/curved/n7_04`) left it 1.3e-2
/// early at a residual of 14 um, where it leaves within 1.6e-3 split. Calls of one substep see
/// the separation only at their start and end, so the step is split wherever a dynamic ball
/// touching something (a contact pair with solver contacts from the last step, or any ball in
/// the first step, before rapier has met a pair) turns fast enough that its rim's centripetal
/// acceleration r w^2, the rate at which the solver would see the other body fall away, reaches
/// 1e-3 of gravity's (of 9.81 m/s^2 where the level has none): the normal force error the
/// library's 1e-3 rule for analyses allows. The price: a collision detection per substep, and on
/// a faceted concave track more energy lost than in rapier's own substeps (docs/known-gaps.md).
///
/// `balls`: the world's ball colliders ([`RoundColliders`]), so that a step does not test every
/// collider's shape.
pub(crate) fn spinning_ball_touches(
    world: &PhysicsWorld,
    balls: &[ColliderHandle],
    first_step: bool,
) -> bool {
    let g = match world.gravity.length() {
        g if g > 0.0 => g,
        _ => 9.81,
    };
    balls.iter().any(|&handle| {
        let Some(collider) = world.colliders.get(handle) else {
            return false;
        };
        let Some(ball) = collider.shape().as_ball() else {
            return false;
        };
        let Some(body) = collider.parent().and_then(|b| world.bodies.get(b)) else {
            return false;
        };
        let w = body.angvel();
        body.is_dynamic()
            && ball.radius * w * w >= 1e-3 * g
            && (first_step
                || world
                    .narrow_phase
                    .contact_pairs_with(handle)
                    .any(|pair| pair.has_any_active_contact()))
    })
}

/// The colliders the step's plan looks at (`step/plan.rs`): the balls ([`spinning_ball_touches`])
/// and the arcs (`arc_split::smooth_ball_rides_arc`), found once rather than by testing every
/// collider's shape each step (the two scans of a 200-box pile's 201 colliders cost about 14,000
/// instructions a step, 1.9% of rapier's step, callgrind 2026-12-07). Refound if the world's
/// colliders change in number (rigidlab inserts them only when it builds the world).
#[derive(Debug, Clone, Default)]
pub(crate) struct RoundColliders {
    pub balls: Vec<ColliderHandle>,
    pub arcs: Vec<ColliderHandle>,
    /// The number of colliders the lists were found among.
    of: usize,
}

impl RoundColliders {
    /// The lists, refound when the world's colliders changed in number.
    pub(crate) fn refresh(&mut self, world: &PhysicsWorld) -> &Self {
        if self.of != world.colliders.len() {
            *self = Self::of(world);
        }
        self
    }

    fn of(world: &PhysicsWorld) -> Self {
        let mut out = RoundColliders {
            of: world.colliders.len(),
            ..Default::default()
        };
        for (h, c) in world.colliders.iter() {
            if c.shape().as_ball().is_some() {
                out.balls.push(h);
            } else if c.shape().as_shape::<super::arc_track::ArcTrack>().is_some() {
                out.arcs.push(h);
            }
        }
        out
    }
}
