//! Stage 3: the textbook quantities, as pure functions over plain data.
//!
//! Every function takes plain numbers, glam `DVec2`s or the snapshot structs
//! (never rapier or Bevy types), is named as the textbook names the quantity,
//! and cites its equation in `textbook/concepts.md` (MK numbers such as 6/9,
//! otherwise the catalog's ids such as RK-11 or MP-2).
//!
//! Conventions (concepts.md "Notation"): plane x-y, k = +z out of the screen;
//! omega, alpha, moments and angular momenta are scalars, positive
//! counter-clockwise; `r_{B/A} = r_B - r_A`; `(a x b)_z = a_x b_y - a_y b_x`;
//! `k x (x, y) = (-y, x)`.
//!
//! Topics, one module each:
//! - [`mass`]: mass, mass center and I_G from the shape formulas, parallel axis, radius of gyration;
//! - [`kinematics`]: point velocity and acceleration, finite differences, the instantaneous center;
//! - [`closed_forms`]: exercise answers in closed form: pendulum and spring periods, rolling on a slope;
//! - [`energy`]: kinetic energy in its three forms, potentials, power, the work-energy ledger;
//! - [`momentum`]: linear momentum, angular momentum about G, about any point, about a fixed axis;
//! - [`curved_path`]: the normal force on a body whose G rides a circle (PN-2), the radius of its path;
//! - [`kinetics`]: the free-body diagram of a body over a step and the Newton-Euler residuals;
//! - [`impact`]: impact detection from contact impulses, restitution, energy lost, H about the contact;
//! - [`percussion`]: the center of percussion and the pivot reaction of a struck pinned body;
//! - [`impulse_solver`]: impulse-momentum for a whole mechanism hit by a blow or an impact;
//! - [`frame`]: all of the above for every body and the scene in one pass per step;
//! - [`links`]: which contacts and joints touch each body, for readings about one body or a pair.
//! - [`small_oscillations`]: the modes and periods of any mechanism linearized about its equilibrium (PL-14).
//! - [`reference`](mod@reference): the reference trajectory, the equations of motion integrated in f64 (Dop853), with the joints' reactions.

pub mod applied_forces;
pub mod closed_forms;
pub mod curved_path;
pub mod energy;
pub mod frame;
pub mod impact;
pub mod impulse_solver;
pub mod kinematics;
pub mod kinetics;
pub mod links;
pub mod mass;
pub mod momentum;
pub mod oscillation;
pub mod percussion;
pub mod reference;
pub mod resting_contacts;
pub mod small_oscillations;
pub mod touching;
pub mod virtual_work;

use crate::snapshot::BodyState;
use glam::DVec2;

/// The z component of the planar cross product, `(a x b)_z = a_x b_y - a_y b_x`.
#[inline]
pub fn cross(a: DVec2, b: DVec2) -> f64 {
    a.x * b.y - a.y * b.x
}

/// `omega k x r` = `omega (-r_y, r_x)`: the velocity a rotation omega gives the point at r.
#[inline]
pub fn k_cross(omega: f64, r: DVec2) -> DVec2 {
    DVec2::new(-r.y, r.x) * omega
}

/// The motion state of one body at one instant: a plain copy of what the snapshot holds,
/// cheap to keep from one step to the next.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Motion {
    /// Body frame origin, m.
    pub position: DVec2,
    /// Body angle, rad (CCW).
    pub angle: f64,
    /// Mass center G, world, m.
    pub com: DVec2,
    /// v_G, m/s.
    pub velocity: DVec2,
    /// omega, rad/s (CCW).
    pub omega: f64,
}

impl From<&BodyState> for Motion {
    fn from(b: &BodyState) -> Self {
        Motion {
            position: b.position,
            angle: b.angle,
            com: b.com,
            velocity: b.velocity,
            omega: b.omega,
        }
    }
}

impl Motion {
    /// World position of a point given in the body frame.
    pub fn world_point(&self, local: DVec2) -> DVec2 {
        self.position + DVec2::from_angle(self.angle).rotate(local)
    }

    /// Body-frame coordinates of the world point `p` (the inverse of [`Motion::world_point`]).
    pub fn local_point(&self, p: DVec2) -> DVec2 {
        DVec2::from_angle(-self.angle).rotate(p - self.position)
    }

    /// Velocity of the body point now at world position `p` (RK-6).
    pub fn velocity_at(&self, p: DVec2) -> DVec2 {
        kinematics::point_velocity(self.velocity, self.omega, p - self.com)
    }

    /// The state `tau` later (earlier when negative) for a body at constant acceleration `a` of
    /// G and constant omega: a body flying free under gravity (no moment about G), carried from
    /// a step's end to the instant of an impact inside it (`touching`).
    pub fn carried(&self, tau: f64, a: DVec2) -> Motion {
        let com = self.com + self.velocity * tau + 0.5 * a * tau * tau;
        let turn = self.omega * tau;
        Motion {
            position: com - DVec2::from_angle(turn).rotate(self.com - self.position),
            angle: self.angle + turn,
            com,
            velocity: self.velocity + a * tau,
            omega: self.omega,
        }
    }

    /// The state halfway through a step in velocity (mean of the two ends): the velocity at
    /// which the work of a step's impulse is exact for a rigid body (see [`energy::work_of_impulse`]).
    pub fn mid(a: &Motion, b: &Motion) -> Motion {
        Motion {
            position: b.position,
            angle: b.angle,
            com: b.com,
            velocity: 0.5 * (a.velocity + b.velocity),
            omega: 0.5 * (a.omega + b.omega),
        }
    }
}
