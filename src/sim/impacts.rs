//! Impacts at the instant the bodies touch (issue 13): the step is cut at the time of impact.
//!
//! rapier computes a pair's contact manifold at the start of each call, within its prediction
//! distance (2 cm by default), and acts on it in that call: two bodies a few millimetres apart
//! got the whole bounce with the normal and lever arms of the approach, not of the impact, an
//! error first order in the distance moved per step (the oblique discs 1.8% off at 1/240 s from
//! any gap; started touching, 2e-4). So where `Settings::impact_cuts` is on, the prediction
//! distance is [`PREDICTION`] and, before each rapier call, the earliest time of impact among
//! the approaching pairs is found (parry's nonlinear shape cast: translation and rotation over
//! the call, the velocities including gravity's change over it). The call is cut there: the
//! bodies arrive just apart, and the next call sees the contact where it happens.

use super::rapier::parry::query::{self, NonlinearRigidMotion};
use super::rapier::prelude::*;
use super::world::Simulation;

/// rapier's prediction distance with impact cuts, m (with a length unit of 1 m): contacts are
/// made within 20 um, so a pair closing from further away is cut at its time of impact first.
pub const PREDICTION: f64 = 2e-5;

/// How far apart a cut leaves the bodies, m: well inside [`PREDICTION`], so the next call makes
/// the contact, and small against any body (the normal's error is of order this over the radii).
const ARRIVE_APART: f64 = 2e-6;

/// The call after a cut, in which the contact is made, as a fraction of the call that was cut.
pub const IMPACT_CALL: f64 = 1.0 / 64.0;

/// Cuts per step at most (a step with more impacts than this leaves the later ones to rapier's
/// prediction).
pub const MAX_CUTS: usize = 4;

impl Simulation {
    /// The time, s from now and before `horizon`, at which the first approaching pair without a
    /// contact comes within [`ARRIVE_APART`], if any does: 0 for a pair already within the
    /// prediction distance, whose contact the coming call makes.
    pub(super) fn time_of_impact(&self, horizon: f64) -> Option<f64> {
        let first = self.first_impact(horizon, 0.0)?;
        // Gravity changes the velocities over the call: cast again with their mean up to the
        // first estimate (a body dropped onto the ground at 1/240 s arrives 85 um later than at
        // its starting velocity).
        self.first_impact(horizon, first).or(Some(first))
    }

    fn first_impact(&self, horizon: f64, gravity_time: f64) -> Option<f64> {
        let w = &self.world;
        let g = w.gravity * (0.5 * gravity_time) as Real;
        let motion = |co: &Collider| -> (NonlinearRigidMotion, Aabb, bool) {
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
                    let sweep = (v.length() + rb.angvel().abs() * reach) * horizon as Real;
                    let mut swept = aabb;
                    swept.mins -= Vector::splat(sweep);
                    swept.maxs += Vector::splat(sweep);
                    (
                        NonlinearRigidMotion::new(*co.position(), com_in_collider, v, rb.angvel()),
                        swept,
                        true,
                    )
                }
                _ => (
                    NonlinearRigidMotion::constant_position(*co.position()),
                    aabb,
                    false,
                ),
            }
        };
        let moving: Vec<_> = w
            .colliders
            .iter()
            .map(|(h, co)| (h, co, motion(co)))
            .collect();
        let mut best: Option<f64> = None;
        for (a, (h1, co1, (m1, box1, moves1))) in moving.iter().enumerate() {
            for (h2, co2, (m2, box2, moves2)) in &moving[a + 1..] {
                if !(*moves1 || *moves2) || co1.parent() == co2.parent() || !box1.intersects(box2) {
                    continue;
                }
                if !w
                    .narrow_phase
                    .contact_pair(*h1, *h2)
                    .is_none_or(|p| !p.has_any_active_contact())
                {
                    continue;
                }
                let apart =
                    query::distance(co1.position(), co1.shape(), co2.position(), co2.shape())
                        .map_or(0.0, |d| d.distance as f64);
                let end = best.unwrap_or(horizon) as Real;
                let Ok(Some(hit)) =
                    query::cast_shapes_nonlinear(m1, co1.shape(), m2, co2.shape(), 0.0, end, true)
                else {
                    continue;
                };
                let t = if apart <= PREDICTION {
                    // Already within reach and closing: the contact is made in this call.
                    0.0
                } else {
                    // Arrive ARRIVE_APART short of touching: back off along the closing speed.
                    let t = hit.time_of_impact as f64;
                    let closing = (apart / t.max(1e-12)).max(1e-9);
                    let t = t - ARRIVE_APART / closing;
                    // A call needs some length: closer than a millionth of the call is now.
                    if t < 1e-6 * horizon {
                        0.0
                    } else {
                        t
                    }
                };
                if t < horizon && best.is_none_or(|b| t < b) {
                    best = Some(t);
                }
            }
        }
        best
    }
}
