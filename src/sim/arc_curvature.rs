//! A ball riding an `Arc` track follows the circle over a rapier call, not the tangent of the
//! call's start.
//!
//! rapier 0.36 holds a contact's normal fixed over a call and solves it as a plane. A ball
//! riding a circle of G's path radius rho at speed v then leaves the call along the tangent of
//! its start: it gets no centripetal push, and the next call finds it moving into the track at
//! v sin(phi) (phi = v h / rho, the angle the radius turns over a call of length h) and takes
//! that out inelastically, a loss of phi^2 / 2 of its kinetic energy per call: first order in
//! h over a run (2.06e-2 of the speed at a 1 m loop's top at 1 ms, docs/known-gaps.md).
//!
//! The exact discrete motion over a call: G moves along the chord of its path circle from the
//! angle it starts at to phi further on, and its velocity turns by phi. The chord is
//! perpendicular to the radius at phi / 2, so [`for_ball_on_arc`] hands rapier that radius as the
//! contact's normal n_h (the plane of the chord) and the separation from the chord, d cos(phi/2)
//! for a surface gap d along the radius (exact in both sides: G at D from the centre lies
//! D cos(phi/2) along n_h, the chord rho cos(phi/2)). In the call's substeps the solver keeps G
//! off that plane, so G slides along the chord. What remains is the velocity's turn: a velocity
//! V t0 (t0 the tangent at the start) has the component -/+ V sin(phi/2) along n_h (toward the
//! plane inside the circle, away from it outside), and at the call's end it must have the
//! opposite one, V t_phi . n_h = +/- V sin(phi/2), which the non-penetration rows alone cannot
//! give (they only stop an approach):
//! - Riding inside (a loop, a ring, a bowl): the normal speed must leave the plane at
//!   c = V sin(phi/2): the reflection of the velocity in the chord's plane, which turns it by phi
//!   and keeps its size. rapier's end-of-call restitution pass drives a contact's normal speed
//!   to e times its approach speed at the call's start: e = s / a for the wanted separation
//!   speed s and the approach a = c + u (u the radial approach, -w_r cos(phi/2)). s = c plus
//!   the level's own bounce e_l u of an approach that is an impact (a new contact), or minus u
//!   for a ball already moving off the track (u < 0: nothing to take out). rapier only bounces
//!   a contact it sees as new unless e >= 1, so the dispatcher (sim/arc_contacts.rs) shows the
//!   circle's contact as new to every call, and this hook decides newness the way
//!   rapier would (no warm-start impulse from the last call: no load borne).
//! - Riding outside (a hump, a cylinder): the normal speed must reach c = -V sin(phi/2), an
//!   approach the rows allow when the plane recedes: the contact's normal speed (rapier's
//!   `tangent_velocity` along the normal moves the first body's contact point over the call)
//!   opens the separation the unbiased pass reads at the call's end by |c| h, so it lets G
//!   approach at |c| and no faster. Where gravity's push toward the track is less than the
//!   centripetal need the rows' impulse falls to zero and the ball leaves the circle, as the
//!   textbook's N = m g cos(theta) - m v^2 / rho < 0 says.
//!
//! A rough pair inside an arc rides the chord too ([`rough_call`], 2026-12-07): G's chord speed
//! at the call's end takes the friction impulse the rows will give, and the call's friction
//! coefficient is scaled so that the rows' bound is mu times the whole normal impulse, the
//! restitution pass's push (which comes after them) included. A slow roller at coarse steps
//! loses about 1e-3 of its speed to the chord (the library's ring at 1/240 s; not traced, and
//! neither the restitution pass nor the friction bound: docs/known-gaps.md). A rough ball
//! outside an arc keeps rapier's plane and its first-order loss.
//!
//! Only a ball on an arc of a fixed body, its centre within the arc's angles (the circle's
//! manifold), and a dynamic ball: a moving track keeps rapier's plane.

use super::arc_track::ArcTrack;
use super::rapier::prelude::*;

/// How a ball's contact with an arc is handed to the solver for one call.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ArcCall {
    /// The contact normal from collider 1 to collider 2 (rapier's convention): the radius at
    /// the call's half-turn.
    pub normal: Vector,
    /// The separation from the chord's plane, m.
    pub dist: Real,
    /// The ball's solver anchor: its surface point facing the track along `normal`.
    pub ball_point: Vector,
    /// The restitution coefficient for the call.
    pub restitution: Real,
    /// The contact's speed along `normal` (rapier's `tangent_velocity`'s normal part).
    pub normal_speed: Real,
    /// A rough pair's friction coefficient for the call ([`rough_call`]); None: the level's.
    pub friction: Option<Real>,
}

/// The circle and the ball's motion about it.
struct Ride {
    /// Unit normal from the track toward the ball's centre at the call's start.
    n: Vector,
    /// The circle's centre (world) and G's distance from it.
    o: Vector,
    d: Real,
    inside: bool,
    /// The surface gap along the radius, m.
    gap: Real,
}

fn ride(arc: &ArcTrack, arc_pose: &Pose, ball_center: Vector, r: Real) -> Option<Ride> {
    let (center, radius, inside) = arc.circle();
    let o = arc_pose * center;
    let arm = ball_center - o;
    let d = arm.length();
    let rho = if inside { radius - r } else { radius + r };
    if d <= 0.0 || rho <= 0.0 {
        return None;
    }
    let u = arm / d;
    let (n, gap) = if inside {
        (-u, radius - d - r)
    } else {
        (u, d - radius - r)
    };
    Some(Ride {
        n,
        o,
        d,
        inside,
        gap,
    })
}

fn rotate(v: Vector, angle: Real) -> Vector {
    let (s, c) = angle.sin_cos();
    Vector::new(c * v.x - s * v.y, s * v.x + c * v.y)
}

/// A dynamic ball at the call's start.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Ball {
    pub center: Vector,
    pub r: Real,
    /// The centre's velocity.
    pub w: Vector,
    /// A rough pair's friction and the ball's inertia; None for a smooth pair.
    pub rough: Option<Rough>,
}

/// The call of a ball (collider `ball1 ? 1 : 2`) on an arc track, or None where rapier's plane
/// stays (see the module's doc). `level_e` is the level's restitution for the pair, `resting`
/// whether the contact bore load in the last call, `gravity` the world's.
pub(crate) fn for_ball_on_arc(
    arc: &ArcTrack,
    arc_pose: &Pose,
    ball: Ball,
    ball1: bool,
    (level_e, resting): (Real, bool),
    gravity: Vector,
    h: Real,
) -> Option<ArcCall> {
    let (ball_center, r, w) = (ball.center, ball.r, ball.w);
    let ride = ride(arc, arc_pose, ball_center, r)?;
    // The tangent counter-clockwise about the centre: the radius (and the normal, along it
    // either way) turns at G's angular rate about the centre, (w . perp) / D.
    let outward = if ride.inside { -ride.n } else { ride.n };
    let perp = Vector::new(-outward.y, outward.x);
    let phi = w.dot(perp) / ride.d * h;
    // A ball that passes the arc's end within the call flies on from there: the chord would turn
    // it past the end (measured 2026-12-06 on tests/newuser/curved/n6_13, a disc leaving a guide
    // 30 degrees up: its apex 4.9e-3 high). Its last call keeps rapier's plane.
    let end = ride.o + rotate(ball_center - ride.o, phi);
    if !arc.spans_point(arc_pose.inverse_transform_point(end)) {
        return None;
    }
    let n_half = rotate(ride.n, phi / 2.0);
    let cos_half = (phi / 2.0).cos();
    // The velocity's parts along n_half (track -> ball, positive away from the track): the
    // approach the turn makes, c_a, and the radial approach u.
    let c_a = -(w.dot(perp) * perp.dot(n_half));
    let u = -(w.dot(ride.n) * cos_half);
    let approach = c_a + u;
    // The call's end velocity must lie along the tangent there, t_end: its part along the
    // chord t_half is the start's and gravity's over the call (the rows keep it), so its part
    // along n_half is s0 = V (t_end . n_half) / (t_end . t_half). Without gravity's share the
    // velocity leaves each call turned a little too far or too short, and the radial speed left
    // over builds up from call to call (measured: +4e-3 of the speed at the loop's top at 1 ms).
    let t_half = rotate(perp, phi / 2.0);
    let t_end = rotate(perp, phi);
    let turn = t_end.dot(n_half) / t_end.dot(t_half);
    let mut along = w.dot(t_half) + gravity.dot(t_half) * h;
    let mut friction = None;
    if let Some(rough) = ball.rough {
        // A rough ball outside (a disc over a cylinder) keeps rapier's plane: not traced yet.
        if !ride.inside {
            return None;
        }
        // The impact's share of the wanted separation speed (the same e as below).
        let e_u = if resting && level_e < 1.0 {
            0.0
        } else {
            level_e
        } * u.max(0.0);
        let chord = Chord {
            n_half,
            t_half,
            turn,
            approach,
            e_u,
        };
        let share = rough_call(&rough, &ball, &chord, gravity, h)?;
        along = share.along;
        friction = Some(share.mu);
    }
    // (along * a) / b, not along * turn: a smooth ball's rounding stays as it was.
    let s0 = along * t_end.dot(n_half) / t_end.dot(t_half);
    let to_rapier = if ball1 { -n_half } else { n_half };
    let mut call = ArcCall {
        normal: to_rapier,
        dist: ride.gap * cos_half,
        ball_point: ball_center - n_half * r,
        restitution: if resting && level_e < 1.0 {
            0.0
        } else {
            level_e
        },
        normal_speed: 0.0,
        friction,
    };
    if ride.inside {
        if approach > 0.0 && s0 > 0.0 {
            let e_impact = if resting && level_e < 1.0 {
                0.0
            } else {
                level_e
            };
            let s = s0 + e_impact * u.max(0.0);
            call.restitution = s / approach;
        }
    } else if s0 < 0.0 {
        // rapier moves collider 1's point by the normal speed times the time into the call and
        // reads the separation along -normal: a point moving along -normal opens it.
        call.normal_speed = s0;
    }
    Some(call)
}

/// A rough ball's friction and inertia, for [`rough_call`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct Rough {
    /// The pair's friction coefficient (rapier's, combined).
    pub mu: Real,
    /// The ball's inverse mass, and inverse moment of inertia about G (0 with its rotation
    /// locked).
    pub inv_mass: Real,
    pub inv_inertia: Real,
    /// The ball's angular velocity, rad/s.
    pub omega: Real,
}

/// A call's chord as [`for_ball_on_arc`] builds it, for [`rough_call`].
struct Chord {
    /// The radius at the half-turn (track -> ball) and the chord's direction.
    n_half: Vector,
    t_half: Vector,
    /// The end velocity's part along `n_half` per unit of its part along `t_half`.
    turn: Real,
    /// The ball's approach to the chord's plane at the call's start, m/s.
    approach: Real,
    /// The level's bounce of an impact's radial approach (e u), m/s.
    e_u: Real,
}

/// What friction does over a rough ball's call on a concave arc.
struct RoughShare {
    /// G's speed along the chord at the call's end, friction's impulse in.
    along: Real,
    /// The friction coefficient to hand rapier for the call.
    mu: Real,
}

/// A rough ball's call on a concave arc: G's speed along the chord at the call's end and the
/// friction coefficient that makes rapier's friction rows the textbook's mu N, or None where
/// the substeps bear no load (rapier's plane stays).
///
/// Two things the smooth chord leaves out (they read the disc rolling in a ring 1.1e-3 low at
/// the bottom, 2026-12-06):
/// - The end velocity's part along the radius, s0 = along turn, is set from G's speed along the
///   chord at the call's end, and friction changes that speed: a rolling disc's centre gains
///   g_t h / (1 + k^2 / r^2), not gravity's g_t h. The radial speed left over builds up from
///   call to call as the smooth ball's did without gravity's share. Here `along` takes the
///   friction impulse the rows will give: the one that stops the contact's slip along the chord
///   (J = -slip / (1/m + r^2 / I), the normal rows pass through G and leave the slip alone) if
///   it lies within the cone, else mu J_n against the slip.
/// - rapier's friction rows are bounded by mu times the normal impulse of the substeps, where
///   the chord's normal impulse comes in two parts: the substeps' (stopping the approach and
///   gravity's push into the plane, m (a - g . n h)) and the restitution pass's after them
///   (m s, turning the velocity). The second is outside the rows' bound, so a sliding ball got
///   mu times only about half the centripetal impulse. The call's coefficient is scaled by
///   J_n / J_sub so the bound is mu J_n, the textbook's mu N h.
fn rough_call(
    rough: &Rough,
    ball: &Ball,
    chord: &Chord,
    gravity: Vector,
    h: Real,
) -> Option<RoughShare> {
    // Phase 1: the substeps' normal impulse.
    let m = 1.0 / rough.inv_mass;
    let j_sub = m * (chord.approach - gravity.dot(chord.n_half) * h);
    if !(j_sub > 0.0 && rough.inv_mass > 0.0) {
        return None;
    }
    // The whole call's: the restitution pass adds m s where it turns the velocity.
    let j_n = |along: Real| {
        let s0 = along * chord.turn;
        if chord.approach > 0.0 && s0 > 0.0 {
            j_sub + m * (s0 + chord.e_u)
        } else {
            j_sub
        }
    };
    // Phase 2: the contact point's slip along the chord at the call's end without friction.
    let arm = -chord.n_half * ball.r;
    let spin = Vector::new(-arm.y, arm.x) * rough.omega;
    let g_t = gravity.dot(chord.t_half) * h;
    let slip = (ball.w + spin).dot(chord.t_half) + g_t;
    let free = ball.w.dot(chord.t_half) + g_t;
    // Phase 3: rolling if the impulse that stops the slip lies within the cone, else sliding.
    let k_t = rough.inv_mass + rough.inv_inertia * ball.r * ball.r;
    let j_stick = -slip / k_t;
    let rolls = free + rough.inv_mass * j_stick;
    let along = if j_stick.abs() <= rough.mu * j_n(rolls) {
        rolls
    } else {
        // J_f = -sigma mu J_n(along) and along = free + J_f / m: linear in along.
        let sigma = slip.signum();
        let pushed = chord.approach > 0.0 && free * chord.turn > 0.0;
        let (base, per) = if pushed {
            (j_sub / m + chord.e_u, chord.turn)
        } else {
            (j_sub / m, 0.0)
        };
        (free - sigma * rough.mu * base) / (1.0 + sigma * rough.mu * per)
    };
    Some(RoughShare {
        along,
        mu: rough.mu * j_n(along) / j_sub,
    })
}
