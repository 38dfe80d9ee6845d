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
//! cancels the turn over the call ([`spin_offset_rate`]), exact at a call's start and end. The
//! drift is quadratic in time and rapier takes only a speed (its `tangent_velocity`, linear in
//! the time into the call: `contact_with_coulomb_friction.rs`, `update`), and the solver's lever
//! arm is the very point whose separation it follows (`solver_dp1`, frozen after this hook), so
//! no hook cancels the drift between a call's ends: where the residual left there matters
//! ([`spin_calls`]), the simulation calls rapier one substep at a time (or in fewer, shorter
//! calls), whose ends are the only instants rapier reads.

use super::rapier::prelude::*;
use crate::sim::SpinSplit;

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

/// How many rapier calls this step's `n` substeps need for a spinning ball's contact: 1 (one
/// call of n) where no ball's turn disturbs its contact, else n (one substep a call), or in a
/// lenient step the fewest calls, a divisor of n, that bring the turn's residual within bounds.
///
/// The normal speed [`spin_offset_rate`] hands rapier is exact at a call's start and end only:
/// over a call of length T the drift, quadratic in time, leaves an apparent overlap of up to
/// r w^2 T^2 / 8 between, which the contact's bias pushes against. Measured on a disc
/// (r = 0.2 m) spun on a floor in one call of 4 or 16 substeps (2026-11-27): its first normal
/// impulse was 2% to 8% short at a residual of 0.17 mm, 25% at 1.1 mm, and at 2.8 mm the disc
/// rose 0.44 mm; and a disc rolling off a cylinder (`tests/newuser/curved/n7_04`) left it 1.3e-2
/// early at a residual of 14 um, where it leaves within 1.6e-3 split.
///
/// What the residual does depends on the contact's load. rapier's soft contact is a spring of
/// natural frequency f (its `static_contact_softness` against a fixed body, 60 Hz, else
/// `contact_softness`, 30 Hz, or the level's `contact_hz`): under a load of a = N / m it sags
/// a / (2 pi f)^2 (6.9e-5 m for a disc resting on a floor under g, measured in
/// tests/suite/sim/spinning_contact.rs), and an apparent overlap e changes its force by
/// e / sag of N within the call. Over calls of one length the ball rides out by the residual's
/// mean, two thirds of its peak: the contact stays compressed through each call, and its
/// impulse over a call is the spring's, as long as the peak is within 1.5 sags ([`SLACK`]).
/// Where it is not, the ball hops within the call. That bound is what a lenient step keeps
/// (`strict` false: no question reads when a contact starts, ends or slips): measured
/// 2026-12-07, the library's discs, hoop and wheel rolling on inclines and floors read every
/// answer within 1e-5 of the split run's with it (docs/accuracy.md).
///
/// A contact near its friction limit or near leaving is not so forgiving: the force swinging
/// within a call reaches mu N or zero in a substep before the step's mean does, and so does a
/// switch from one call to several (the ball settles by the mean it rode out by). Measured
/// 2026-12-07 on a disc rolling, slipping and leaving a cylinder (tests/newuser/curved/n14_16,
/// n14_17): split at one sag, its leaving angle read 3.5e-2 to 4.4e-2 off (2e-2 allowed), never
/// split 2.0e-2, split at half a sag 7.2e-3 and 5.4e-3, as when always split. So where a
/// question reads a contact's start, end or slip (`strict`), a step is split into one-substep
/// calls once the residual passes half a sag times the friction's margin, 1 - |F| / (mu N)
/// ([`STRICT`]): the split comes early and whole, while the contact still bears its load.
/// Pairs are judged one by one (the least loaded goes slack first), from the impulses each
/// carried over the last rapier call.
///
/// Balls count if dynamic and turning fast enough that their rim's centripetal acceleration
/// r w^2 reaches 1e-3 of gravity's (of 9.81 m/s^2 where the level has none), in contact pairs
/// with solver contacts from the last step, or any ball in the first step, before rapier has met
/// a pair and where no load is known yet (then one substep a call). The price of a split: a
/// collision detection per call, and on a faceted concave track more energy lost than in
/// rapier's own substeps (docs/known-gaps.md).
///
/// `balls`: the world's ball colliders ([`RoundColliders`]), so that a step does not test every
/// collider's shape.
pub(crate) fn spin_calls(
    world: &PhysicsWorld,
    balls: &[ColliderHandle],
    step: SpinStep,
    rule: SpinSplit,
) -> usize {
    let n = step.substeps.max(1);
    if n == 1 || rule == SpinSplit::Never {
        return 1;
    }
    let g = match world.gravity.length() {
        g if g > 0.0 => g,
        _ => 9.81,
    };
    let mut calls = 1;
    for &handle in balls {
        let Some(collider) = world.colliders.get(handle) else {
            continue;
        };
        let Some(ball) = collider.shape().as_ball() else {
            continue;
        };
        let Some(body) = collider.parent().and_then(|b| world.bodies.get(b)) else {
            continue;
        };
        let w = body.angvel();
        if !body.is_dynamic() || ball.radius * w * w < 1e-3 * g {
            continue;
        }
        let mut touching = world
            .narrow_phase
            .contact_pairs_with(handle)
            .filter(|pair| pair.has_any_active_contact());
        if step.first || rule == SpinSplit::Always {
            if step.first || touching.next().is_some() {
                return n;
            }
            continue;
        }
        let residual = (ball.radius * w * w) as f64 * step.dt * step.dt / 8.0;
        let mass = body.mass() as f64;
        for pair in touching {
            let other = if pair.collider1 == handle {
                pair.collider2
            } else {
                pair.collider1
            };
            let load = Load::of(pair, mass, step.last_call);
            let sag = load.per_mass / softness(world, other).powi(2);
            if step.strict {
                if residual > STRICT * sag * load.friction_margin {
                    return n;
                }
            } else {
                calls = calls.max(calls_within(residual, SLACK * sag, n));
            }
        }
    }
    calls
}

/// What the spin rule reads of a step.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SpinStep {
    /// The step's length, s.
    pub dt: f64,
    /// Its substeps.
    pub substeps: usize,
    /// The length of the last rapier call, whose impulses give each contact's load, s.
    pub last_call: f64,
    /// Whether it is the run's first step (no load known).
    pub first: bool,
    /// Whether a question reads when a contact starts, ends or slips (`Settings::
    /// reads_contact_events`): then the strict rule.
    pub strict: bool,
}

/// A contact pair's load over the last rapier call.
struct Load {
    /// Its normal force per unit mass of the ball, m/s^2.
    per_mass: f64,
    /// 1 - |F| / (mu N): how far its friction is from the cone (1 when smooth or unloaded).
    friction_margin: f64,
}

impl Load {
    fn of(pair: &ContactPair, mass: f64, last_call: f64) -> Load {
        let (mut normal, mut tangent, mut mu): (f64, f64, f64) = (0.0, 0.0, 0.0);
        for m in pair.solver_manifolds() {
            mu = mu.max(m.data.friction as f64);
            for p in &m.points {
                normal += p.data.impulse as f64;
                tangent += p.data.tangent_impulse.sum() as f64;
            }
        }
        let per_mass = if last_call > 0.0 && mass > 0.0 {
            normal / (mass * last_call)
        } else {
            0.0
        };
        let friction_margin = if mu > 0.0 && normal > 0.0 {
            (1.0 - tangent.abs() / (mu * normal)).clamp(0.0, 1.0)
        } else {
            1.0
        };
        Load {
            per_mass,
            friction_margin,
        }
    }
}

/// The natural angular frequency of a ball's soft contact with `other`, rad/s: rapier's static
/// softness against a fixed body (or none), its contact softness against a moving one.
fn softness(world: &PhysicsWorld, other: ColliderHandle) -> f64 {
    let fixed = world
        .colliders
        .get(other)
        .and_then(|c| c.parent())
        .and_then(|b| world.bodies.get(b))
        .is_none_or(|b| b.is_fixed());
    let p = &world.integration_parameters;
    let soft = if fixed {
        p.static_contact_softness
    } else {
        p.contact_softness
    };
    soft.natural_frequency as f64 * std::f64::consts::TAU
}

/// The fewest calls, a divisor of `n`, over which the residual (`residual` over one call of the
/// step) stays within `bound`: the residual falls with the square of the call's length.
fn calls_within(residual: f64, bound: f64, n: usize) -> usize {
    (1..=n)
        .filter(|&m| n.is_multiple_of(m))
        .find(|&m| residual <= bound * (m * m) as f64)
        .unwrap_or(n)
}

/// The residual a lenient step's calls may leave, in sags: the contact stays compressed through
/// a call up to 1.5 ([`spin_calls`]).
const SLACK: f64 = 1.5;

/// The residual past which a strict step is split, in sags times the friction's margin
/// (measured on tests/newuser/curved/n14_16 and n14_17, [`spin_calls`]).
const STRICT: f64 = 0.5;

/// The colliders the step's plan looks at (`step/plan.rs`): the balls ([`spin_calls`])
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
    /// The lists, refound when the world's colliders changed in number. A collider's shape is
    /// never swapped in place in `src/sim` (no `set_shape`): the hook and the contact reading
    /// (`readings.rs`, which asks no shape in a world without balls) rely on it, so a change that
    /// swaps one must refind the lists.
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
