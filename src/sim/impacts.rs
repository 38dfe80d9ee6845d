//! Impacts at the instant the bodies touch (issue 13): each rapier call is planned around the
//! impacts in it.
//!
//! rapier makes a pair's contact manifold at the start of each call within its prediction
//! distance (2 cm by default) and acts on it in that call: a new contact that approaches is
//! bounced at the call's end (`apply_restitution`) with the normal and lever arms of the call's
//! start, up to a step before the bodies touch (the oblique discs were 1.8% off at 1/240 s from
//! any gap; started touching, 2e-4), and once it has pushed at all, the touch is no longer new
//! and gets no bounce. So, before each call, for the pairs that approach as an impact does (faster
//! than gravity alone closes a gap; [`Simulation::plan_call`]):
//! - the prediction distance of the call is lowered below their gaps, so rapier makes no contact
//!   for them before they touch (resting stacks, whose pairs do not approach, keep rapier's
//!   2 cm, which they were tuned with);
//! - the call is cut at the first time of impact among them (parry's nonlinear shape cast:
//!   translation and rotation, the velocities including gravity's change over the call), so the
//!   bodies arrive [`ARRIVE_APART`] apart;
//! - the contact is then made in a short call ([`IMPACT_CALL`] of the call), with the manifold
//!   of the touching configuration, where rapier's soft contact acts nearly rigidly.
//!
//! A pair further than the prediction distance is cut too when it meets within the call, except
//! one that moves in a call more than the thicker of the two is thick: there rapier tunnels,
//! which only `ccd` prevents (a bullet that crosses a wall within a step tunnels unless the
//! level declares it).

use super::rapier::parry::query::NonlinearRigidMotion;
use super::rapier::prelude::*;
use super::world::Simulation;

/// Closer than this, m, a pair touches: its contact is rapier's.
pub const TOUCHING: f64 = 1e-5;

/// How far apart a cut leaves the bodies, m: within [`TOUCHING`], and small against any body (the
/// normal's error is of order this over the radii).
const ARRIVE_APART: f64 = 2e-6;

/// The call after a cut, in which the contact is made, as a fraction of the call that was cut.
pub const IMPACT_CALL: f64 = 1.0 / 64.0;

/// Cuts per step at most (a step with more impacts than this leaves the later ones to rapier's
/// prediction).
pub const MAX_CUTS: usize = 4;

/// Sweeps of rapier's unbiased pass in an impact's call and in the call after it (at least; the
/// run's `solver_iterations` if more).
///
/// rapier 0.36 solves a contact's friction only in the unbiased (stabilization) pass, one sweep
/// per substep by default, after the normal row; the biased pass, repeated
/// `num_internal_pgs_iterations` times, holds the normal row alone. In an eccentric rough impact
/// the contact's inverse mass matrix K couples the rows (c = K_nt^2 / (K_nn K_tt) > 0): the
/// friction that stops the slip drives the contact point back into the floor, and one sweep
/// leaves it approaching at c v_n. The next substep's warm start re-applies the whole impulse
/// (right for a steady force, an overshoot after a blow), the normal row takes back only its own
/// share, and friction's correction pushes the point out: after three substeps it separates at
/// e_rapier = c (1 - 2c) (c <= 1/4) or c^2 (3 - 4c) (1/4 <= c <= 1/2) of the approach with
/// e = 0, along the sticking impulse (1 + e_rapier times it). Run to convergence the sweeps give
/// the sticking impulse within c^n; the call after the impact is included because its first
/// substep warm-starts with the impact's impulse when the impact call has a single substep. A
/// blow (an impulse event) driving a resting body into its floor is met the same way: the first
/// call of its step and the next (a block struck obliquely down rose at 0.83 m/s; converged, 0).
/// tests/suite/sim/eccentric_friction.rs measures both.
pub const IMPACT_ITERATIONS: usize = 32;

/// How far ahead, in calls, an approaching pair is looked for (its closing speed is its gap over
/// its time of impact).
const LOOKAHEAD: f64 = 64.0;

/// The plan of one rapier call.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CallPlan {
    /// Where to cut the call, s from its start, if an impact falls in it (0: the pair is
    /// already within reach, and the coming call is the short one that makes the contact).
    pub cut: Option<f64>,
    /// rapier's (normalized) prediction distance for the call, m.
    pub prediction: f64,
}

impl Simulation {
    /// The plan of the coming call of length `horizon` (see the module doc). `new_touches`:
    /// whether a pair placed touching that closes at impact speed, with no contact made yet, is
    /// an impact of this call (not in the short call a cut planned: its pair arrives touching).
    pub(super) fn plan_call(&self, horizon: f64, new_touches: bool) -> CallPlan {
        let first = self.scan(horizon, 0.0, new_touches);
        // Gravity changes the velocities over the call: cast again with their mean up to the
        // first estimate (a body dropped onto the ground at 1/240 s arrives 85 um later than at
        // its starting velocity).
        match first.cut {
            Some(t) if t > 0.0 => {
                let again = self.scan(horizon, t, new_touches);
                CallPlan {
                    cut: again.cut.or(first.cut),
                    prediction: again.prediction.min(first.prediction),
                }
            }
            _ => first,
        }
    }

    fn scan(&self, horizon: f64, gravity_time: f64, new_touches: bool) -> CallPlan {
        let w = &self.world;
        let rapier_prediction = self.settings_prediction();
        let g = w.gravity * (0.5 * gravity_time) as Real;
        let ahead = horizon * LOOKAHEAD;
        let motion = |co: &Collider| -> (NonlinearRigidMotion, Aabb, f64) {
            let aabb = co.compute_aabb();
            match co.parent().map(|h| &w.bodies[h]) {
                Some(rb) if rb.is_dynamic() || rb.is_kinematic() => {
                    let v = if rb.is_dynamic() {
                        rb.linvel() + g * rb.gravity_scale()
                    } else {
                        rb.linvel()
                    };
                    let local_com = rb.mass_properties().local_mprops.local_com;
                    // The collider's pose moves with its body about the body's mass center.
                    let com_in_collider = co.position().inverse() * (*rb.position() * local_com);
                    let reach = aabb.half_extents().length() * 2.0;
                    // No point of the collider moves faster than this.
                    let speed = v.length() + rb.angvel().abs() * reach;
                    let sweep = speed * horizon as Real;
                    let mut near = aabb;
                    near.mins -= Vector::splat(sweep.max(rapier_prediction as Real));
                    near.maxs += Vector::splat(sweep.max(rapier_prediction as Real));
                    (
                        NonlinearRigidMotion::new(*co.position(), com_in_collider, v, rb.angvel()),
                        near,
                        speed as f64,
                    )
                }
                _ => (
                    NonlinearRigidMotion::constant_position(*co.position()),
                    aabb,
                    0.0,
                ),
            }
        };
        let moving: Vec<_> = w
            .colliders
            .iter()
            .map(|(handle, co)| (handle, co, motion(co)))
            .collect();
        // An impact closes faster than gravity alone can close a gap over two calls (a body
        // resting on another, or sliding into it, is not an impact).
        let slow = 2.0 * w.gravity.length() as f64 * horizon + 1e-3;
        let mut plan = CallPlan {
            cut: None,
            prediction: rapier_prediction,
        };
        // rapier makes no contact between two bodies that a joint with its contacts off joins
        // (every joint rigidlab builds, sim/build.rs; rapier's `pair_update.rs` filters them the
        // same way), so such a pair is never an impact. Planned as one, a four-bar's links
        // touching at their pins once their colliders are on (all effects) were cut for as they
        // closed, each cut's call at IMPACT_ITERATIONS: 5x the run's cost for the same motion
        // (tests/suite/sim/impact_planner_joints.rs).
        let jointed = |a: &Collider, b: &Collider| match (a.parent(), b.parent()) {
            (Some(p), Some(q)) => w
                .impulse_joints
                .joints_between(p, q)
                .any(|(_, j)| !j.data.contacts_enabled),
            _ => false,
        };
        for (a, (h1, co1, (m1, box1, speed1))) in moving.iter().enumerate() {
            for (h2, co2, (m2, box2, speed2)) in &moving[a + 1..] {
                // Two bodies that cannot close fast enough to make an impact (a resting stack) are
                // passed over before any query.
                if speed1 + speed2 <= slow
                    || co1.parent() == co2.parent()
                    || !box1.intersects(box2)
                    || jointed(co1, co2)
                {
                    continue;
                }
                // Where the two are nearest, and how fast they close there (the velocities of
                // the two surface points along the normal).
                let reach = (box1.maxs - box1.mins)
                    .length()
                    .max((box2.maxs - box2.mins).length());
                // Through the world's dispatcher: parry's free functions know no arc track.
                let dispatcher = w.narrow_phase.query_dispatcher();
                let Some(c) = super::arc_contacts::contact(
                    dispatcher,
                    co1.position(),
                    co1.shape(),
                    co2.position(),
                    co2.shape(),
                    reach,
                ) else {
                    continue;
                };
                let apart = c.dist as f64;
                let point_velocity = |m: &NonlinearRigidMotion, p: Vector| {
                    let center = m.start * m.local_center;
                    let r = p - center;
                    m.linvel + Vector::new(-r.y, r.x) * m.angvel
                };
                let closing = ((point_velocity(m1, c.point1) - point_velocity(m2, c.point2))
                    .dot(c.normal1)) as f64;
                if closing <= slow {
                    continue;
                }
                if apart <= TOUCHING {
                    // Touching and closing at impact speed. A pair rapier has made a contact for
                    // is rapier's (a ladder sliding on its wall, whose contact pushes in bursts:
                    // making it in a short call changed that ladder from 8.6e-3 to 1.28e-2 off at
                    // 1/960 s). A pair with no contact yet (two bodies placed touching and moving
                    // into each other: a level's first step) is an impact like one met from a
                    // gap, made in a short call: else rapier bounces it over the whole call and
                    // the rebound lacks gravity's change over the call (a ball placed on a rough
                    // floor read e = (2 + g dt)/4 for 0.5).
                    let made = w
                        .narrow_phase
                        .contact_pair(*h1, *h2)
                        .is_some_and(|pair| pair.manifolds().iter().any(|m| !m.points.is_empty()));
                    if new_touches && !made {
                        plan.cut = Some(0.0);
                    }
                    continue;
                }
                let Ok(Some(hit)) = dispatcher.cast_shapes_nonlinear(
                    m1,
                    co1.shape(),
                    m2,
                    co2.shape(),
                    0.0,
                    ahead as Real,
                    true,
                ) else {
                    continue;
                };
                let t_hit = hit.time_of_impact as f64;
                if t_hit >= horizon && apart > rapier_prediction {
                    // Out of rapier's sight and not meeting within the call.
                    continue;
                }
                // A pair that moves more in a call than the thicker of the two is thick is
                // where rapier tunnels (a bullet through a wall): only `ccd` prevents that, as
                // the level declares it or not.
                let thickness = |co: &Collider| {
                    let e = co.compute_aabb().half_extents() * 2.0;
                    e.x.min(e.y) as f64
                };
                let moved = (m1.linvel - m2.linvel).length() as f64 * horizon;
                if moved > thickness(co1).max(thickness(co2)) {
                    continue;
                }
                // No contact for this pair until it touches.
                plan.prediction = plan.prediction.min(0.5 * apart).max(2.0 * TOUCHING);
                if t_hit < horizon {
                    // Arrive ARRIVE_APART short of touching; a call needs some length.
                    let t = t_hit - ARRIVE_APART / closing;
                    let t = if t < 1e-6 * horizon { 0.0 } else { t };
                    if plan.cut.is_none_or(|c| t < c) {
                        plan.cut = Some(t);
                    }
                }
            }
        }
        plan
    }

    /// rapier's prediction distance for this run when no impact lowers it, m (the world's own
    /// normalized distance times its length unit).
    fn settings_prediction(&self) -> f64 {
        (self.prediction_distance * self.world.integration_parameters.length_unit) as f64
    }
}
