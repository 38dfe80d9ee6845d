//! A spring's damper held over a rapier call at the call's mean rate, not its start's.
//!
//! rigidlab holds each force over a call (`forces.rs`). A damper held at the rate c dL/dt of
//! the call's start lags the motion by half a call: summed over a decay, the bodies lose c h
//! v0^2 / 4 less than the textbook's -integral of c (dL/dt)^2 dt (h the call's length; 2.5e-4
//! J of 0.375 on a damped pair at 1 ms and 4 substeps). The damper is held instead at the mean
//! of the call's start and end rates (the trapezoid, second order), with the end rate
//! predicted from the free bodies' response to the forces held over the call and to the damper
//! itself, solved for it (implicit in the damper: no step is too long for a stiff one):
//!
//!   F = c (u0 + u1) / 2,  u1 = u1e + h (F_e - F) / mu   =>
//!   F = (c (u0 + u1e) / 2 + c h F_e / (2 mu)) / (1 + c h / (2 mu)),
//!
//! u0 the rate at the call's start, u1e its end rate predicted with the explicit force F_e = c
//! u0 held, 1/mu the pair's free inverse mass along the axis (1/m + (r x n)^2 / I_G summed over
//! the dynamic ends; 1/I_G for a torsion spring). Joints and contacts are not in the
//! prediction: where they carry the ends the correction is part of the lag, not all of it.

use super::super::rapier::prelude::*;
use super::super::world::{to_d, vd, Simulation};
use crate::level::Effect;
use crate::snapshot::SpringState;
use glam::DVec2;

/// A body's response to what is held on it over the call: its velocities now, its
/// accelerations under the held forces and gravity, its inverse mass (per axis) and inertia.
struct Response {
    v: DVec2,
    omega: f64,
    a: DVec2,
    alpha: f64,
    inv_m: DVec2,
    inv_i: f64,
    com: DVec2,
}

impl Simulation {
    /// Holds each spring's damper at the call's predicted mean rate (module doc): adds the
    /// difference from the explicit damper force already applied, and books it in `springs`.
    pub(super) fn hold_dampers_at_mean_rate(&mut self, springs: &mut [SpringState], h: f64) {
        // `spring_states` lists the springs, then the torsion springs, in the level's order.
        let dampings: Vec<f64> = if self.settings.effects.has(Effect::Damping) {
            let linear = self.level.springs.iter().map(|s| s.damping);
            linear
                .chain(self.level.torsion_springs.iter().map(|t| t.damping))
                .collect()
        } else {
            Vec::new()
        };
        for (s, &c) in springs.iter_mut().zip(&dampings) {
            if c == 0.0 {
                continue;
            }
            let r1 = self.response(s.body1);
            let r2 = s.body2.map(|b| self.response(b));
            let change = if s.torsion {
                torsion_change(c, &r1, r2.as_ref(), h)
            } else {
                linear_change(c, s, &r1, r2.as_ref(), h)
            };
            if change == 0.0 || !change.is_finite() {
                continue;
            }
            self.add_damper_change(s, change);
        }
    }

    /// What body `i` feels over the call (`Response`).
    fn response(&self, i: usize) -> Response {
        let rb = &self.world.bodies[self.bodies[i]];
        let mp = rb.mass_properties();
        let inv_m = DVec2::new(
            mp.effective_inv_mass.x as f64,
            mp.effective_inv_mass.y as f64,
        );
        let inv_i = mp.effective_world_inv_inertia as f64;
        let moves = |x: f64| if x > 0.0 { 1.0 } else { 0.0 };
        let g = to_d(self.world.gravity) * rb.gravity_scale() as f64;
        let f = to_d(rb.user_force());
        Response {
            v: to_d(rb.linvel()),
            omega: rb.angvel() as f64,
            a: f * inv_m + DVec2::new(g.x * moves(inv_m.x), g.y * moves(inv_m.y)),
            alpha: rb.user_torque() as f64 * inv_i,
            inv_m,
            inv_i,
            com: to_d(mp.world_com),
        }
    }

    /// Applies `change` more damper tension (body1 pulled toward body2, or turned back for a
    /// torsion spring) and books it in the spring's held force.
    fn add_damper_change(&mut self, s: &mut SpringState, change: f64) {
        let axis = (s.applied_at2 - s.applied_at1).normalize_or_zero();
        let f = axis * change;
        let rb1 = &mut self.world.bodies[self.bodies[s.body1]];
        if s.torsion {
            rb1.add_torque(-change as Real, true);
        } else {
            rb1.add_force_at_point(vd(f), vd(s.applied_at1), true);
        }
        if let Some(b2) = s.body2 {
            let rb2 = &mut self.world.bodies[self.bodies[b2]];
            if s.torsion {
                rb2.add_torque(change as Real, true);
            } else {
                rb2.add_force_at_point(vd(-f), vd(s.applied_at2), true);
            }
        }
        s.damper_tension += change;
        s.tension += change;
        if s.torsion {
            s.couple_on_body1 -= change;
        } else {
            s.force_on_body1 += f;
        }
    }
}

/// The trapezoid damper force less the explicit one, from the rate `u0` at the call's start,
/// the end rate `u1e` predicted with the explicit force held, and the pair's free inverse mass
/// `inv_mu` along the spring (module doc).
fn trapezoid_change(c: f64, u0: f64, u1e: f64, inv_mu: f64, h: f64) -> f64 {
    let f_e = c * u0;
    let f = (0.5 * c * (u0 + u1e) + 0.5 * c * h * f_e * inv_mu) / (1.0 + 0.5 * c * h * inv_mu);
    f - f_e
}

/// A linear spring's change: rates and inverse masses along the axis from body1's end to
/// body2's (a fixed end at rest).
fn linear_change(c: f64, s: &SpringState, r1: &Response, r2: Option<&Response>, h: f64) -> f64 {
    let n = (s.applied_at2 - s.applied_at1).normalize_or_zero();
    let end = |r: &Response, p: DVec2, dt: f64| {
        let arm = p - r.com;
        let v = r.v + dt * r.a;
        let w = r.omega + dt * r.alpha;
        (v + w * DVec2::new(-arm.y, arm.x)).dot(n)
    };
    let inv_mass = |r: &Response, p: DVec2| {
        let arm = p - r.com;
        let lever = arm.perp_dot(n);
        n.x * n.x * r.inv_m.x + n.y * n.y * r.inv_m.y + lever * lever * r.inv_i
    };
    let (v2_0, v2_1, inv2) = r2.map_or((0.0, 0.0, 0.0), |r| {
        (
            end(r, s.applied_at2, 0.0),
            end(r, s.applied_at2, h),
            inv_mass(r, s.applied_at2),
        )
    });
    let u0 = v2_0 - end(r1, s.applied_at1, 0.0);
    let u1e = v2_1 - end(r1, s.applied_at1, h);
    let inv_mu = inv_mass(r1, s.applied_at1) + inv2;
    trapezoid_change(c, u0, u1e, inv_mu, h)
}

/// A torsion spring's change: the relative rate omega1 - omega2 and 1/I1 + 1/I2.
fn torsion_change(c: f64, r1: &Response, r2: Option<&Response>, h: f64) -> f64 {
    let (w2_0, w2_1, inv2) = r2.map_or((0.0, 0.0, 0.0), |r| {
        (r.omega, r.omega + h * r.alpha, r.inv_i)
    });
    let u0 = r1.omega - w2_0;
    let u1e = r1.omega + h * r1.alpha - w2_1;
    trapezoid_change(c, u0, u1e, r1.inv_i + inv2, h)
}
