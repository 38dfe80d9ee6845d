//! When, within the coming rapier call, two separated bodies will first touch.
//!
//! Why: rapier 0.36 solves an impact as a speculative contact. A pair within its prediction
//! distance (2 cm) at the start of a call gets a contact constraint built from that start pose,
//! and when the gap closes inside the call the constraint stops the approach then, along the
//! normal and with the lever arms of the start, up to v h before the bodies touch. For two discs
//! meeting obliquely at 2 m/s that normal is off by the tangential drift over the gap: 1.8 % of
//! the impulse solution at dt = 1/240 s from a 1 cm gap, first order in dt (tests/impact_approach.rs).
//!
//! So a call whose pairs will touch inside it is cut at the time of impact: rapier advances to the
//! touching pose (where the speculative allowance gap / t equals the approach speed, so nothing
//! pushes), and the rest of the call starts from bodies in contact, whose normal and arms are the
//! textbook's. The time comes from parry's nonlinear shape cast over each pair rapier's broad
//! phase knows (pairs further apart than the broad phase's margin are not seen, as for rapier).

use super::rapier::parry::bounding_volume::{Aabb, BoundingVolume};
use super::rapier::parry::query::{self, NonlinearRigidMotion, ShapeCastStatus};
use super::rapier::prelude::*;
use crate::snapshot::BodyState;

/// A cut closer than this fraction of the call to either end is not worth a rapier call: the
/// speculative normal then comes from a pose within that fraction of v h of touching.
const EDGE: Real = 1e-3;

/// Pairs closer than this, m, are already in contact: their impact (if any) is under way.
const TOUCHING: Real = 1e-6;

/// The earliest time in (EDGE h, (1 - EDGE) h) at which two separated colliders, at least one on
/// a dynamic body, touch when their bodies move over the call of length `h` as rapier will move
/// them: at the velocity after the call's gravity kick (symplectic Euler: v' = v + g h, then
/// x' = x + v' h), rotating about their mass centers. `bodies` gives each body's mass center in
/// its frame (by the collider's user_data index), which rapier itself only knows after a step.
///
/// Candidate pairs come from the colliders' bounding boxes swept over the call on the current
/// poses (rapier's own pair list is a step old: a pair it first sees in this call is not in it).
/// The search is over all pairs, which is fine for the graded scenes this runs on (a few dozen
/// bodies; `Settings::cut_at_impact`).
pub(crate) fn first_impact(world: &PhysicsWorld, bodies: &[BodyState], h: Real) -> Option<Real> {
    let moving: Vec<Moving> = world
        .colliders
        .iter()
        .filter_map(|(_, c)| Moving::of(world, c, bodies, h))
        .collect();
    let mut first: Option<Real> = None;
    for (k, a) in moving.iter().enumerate() {
        for b in &moving[k + 1..] {
            if !(a.dynamic || b.dynamic) || a.body == b.body || !a.swept.intersects(&b.swept) {
                continue;
            }
            // Bodies joined with contacts off never touch (sim/build.rs joints).
            if world
                .impulse_joints
                .joints_between(a.body, b.body)
                .any(|(_, j)| !j.data.contacts_enabled())
            {
                continue;
            }
            let (ca, cb) = (a.collider, b.collider);
            match query::distance(ca.position(), ca.shape(), cb.position(), cb.shape()) {
                Ok(d) if d.distance > TOUCHING => {}
                _ => continue,
            }
            if std::env::var_os("TOI_DEBUG").is_some() { eprintln!("cand {:?} {:?}", query::distance(ca.position(), ca.shape(), cb.position(), cb.shape()).map(|d| d.distance), query::cast_shapes_nonlinear(&a.motion, ca.shape(), &b.motion, cb.shape(), 0.0, h, true)); }
            let Ok(Some(hit)) = query::cast_shapes_nonlinear(
                &a.motion,
                ca.shape(),
                &b.motion,
                cb.shape(),
                0.0,
                h,
                true,
            ) else {
                continue;
            };
            if hit.status != ShapeCastStatus::Converged {
                continue;
            }
            let t = hit.time_of_impact;
            if t > EDGE * h && t < (1.0 - EDGE) * h && first.is_none_or(|f| t < f) {
                first = Some(t);
            }
        }
    }
    first
}

/// A collider and how it moves over the call.
struct Moving<'a> {
    collider: &'a Collider,
    body: RigidBodyHandle,
    dynamic: bool,
    motion: NonlinearRigidMotion,
    /// Its bounding box over the whole call.
    swept: Aabb,
}

impl<'a> Moving<'a> {
    fn of(world: &PhysicsWorld, c: &'a Collider, bodies: &[BodyState], h: Real) -> Option<Self> {
        let body = c.parent()?;
        let (motion, dynamic) = motion(world, c, bodies, h)?;
        let start = c.compute_aabb();
        // The box at the end of the call, grown by the most a point can swing about the mass
        // center (|w| h times the box's half diagonal, plus the distance to the mass center).
        let reach = (start.half_extents().length()
            + (motion.start * motion.local_center - start.center()).length())
            * motion.angvel.abs()
            * h;
        let end = start.translated(motion.linvel * h);
        Some(Moving {
            collider: c,
            body,
            dynamic,
            motion,
            swept: start.merged(&end).loosened(reach + TOUCHING),
        })
    }
}

/// A collider's motion over the call, and whether its body is dynamic.
fn motion(
    world: &PhysicsWorld,
    c: &Collider,
    bodies: &[BodyState],
    h: Real,
) -> Option<(NonlinearRigidMotion, bool)> {
    let rb = world.bodies.get(c.parent()?)?;
    let dynamic = rb.is_dynamic();
    let local_com = bodies
        .get(c.user_data as usize)
        .map(|b| Vector::new(b.local_com.x as Real, b.local_com.y as Real))
        .unwrap_or_default();
    // The mass center in the collider's frame: the collider may sit off its body's origin.
    let com_world = *rb.position() * local_com;
    let local_center = c.position().inverse() * com_world;
    let kick = if dynamic {
        world.gravity * rb.gravity_scale() * h
    } else {
        Vector::ZERO
    };
    Some((
        NonlinearRigidMotion::new(*c.position(), local_center, rb.linvel() + kick, rb.angvel()),
        dynamic,
    ))
}
