//! Rigid-body kinematics (concepts.md section 5): body points, finite differences, the
//! instantaneous center of zero velocity (from omega, or from two points' velocity directions).

use super::{cross, k_cross};
use glam::DVec2;

/// Velocity of a body point: v_P = v_G + omega k x r_{P/G} (RK-6, RK-4 vector form).
///
/// # Examples
///
/// A wheel of radius 0.5 m rolling to the right at v_G = 2 m/s turns clockwise at
/// omega = -v_G / r = -4 rad/s: its top moves at 2 v_G and its contact point is at rest (RK-8).
/// ```
/// use glam::DVec2;
/// use rigidlab::analysis::kinematics::point_velocity;
/// let (v_g, omega) = (DVec2::new(2.0, 0.0), -4.0);
/// assert_eq!(point_velocity(v_g, omega, DVec2::new(0.0, 0.5)), DVec2::new(4.0, 0.0));
/// assert_eq!(point_velocity(v_g, omega, DVec2::new(0.0, -0.5)), DVec2::ZERO);
/// ```
pub fn point_velocity(v_g: DVec2, omega: f64, r: DVec2) -> DVec2 {
    v_g + k_cross(omega, r)
}

/// RK-6 for the material point of a snapshot's body now at world `p`: v_P = v_G + omega k x r_P/G.
pub fn body_point_velocity(b: &crate::snapshot::BodyState, p: DVec2) -> DVec2 {
    point_velocity(b.velocity, b.omega, p - b.com)
}

/// Acceleration of a body point: a_P = a_G + alpha k x r_{P/G} - omega^2 r_{P/G} (RK-10).
///
/// # Examples
///
/// The same wheel rolling at constant speed: its contact point, at rest, accelerates
/// towards G at omega^2 r = 16 x 0.5 = 8 m/s^2.
/// ```
/// use glam::DVec2;
/// use rigidlab::analysis::kinematics::point_acceleration;
/// let a = point_acceleration(DVec2::ZERO, 0.0, -4.0, DVec2::new(0.0, -0.5));
/// assert_eq!(a, DVec2::new(0.0, 8.0));
/// ```
pub fn point_acceleration(a_g: DVec2, alpha: f64, omega: f64, r: DVec2) -> DVec2 {
    a_g + k_cross(alpha, r) - omega * omega * r
}

/// Mass-center acceleration by a finite difference over one physics step, a_G = (v_1 - v_0)/dt
/// (`FD` in concepts.md: over the physics step, not the render frame).
#[inline]
pub fn acceleration_fd(v0: DVec2, v1: DVec2, dt: f64) -> DVec2 {
    // One reciprocal, which a loop over bodies computes once (a division costs ~10 products).
    (v1 - v0) * (1.0 / dt)
}

/// Angular acceleration by a finite difference over one physics step, alpha = (omega_1 - omega_0)/dt (RK-3).
#[inline]
pub fn angular_acceleration_fd(omega0: f64, omega1: f64, dt: f64) -> f64 {
    (omega1 - omega0) * (1.0 / dt)
}

/// An angle difference brought into (-pi, pi] (body angles are reported in that range).
pub fn wrap_angle(a: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    let r = a.rem_euclid(TAU);
    if r > PI {
        r - TAU
    } else {
        r
    }
}

/// The instantaneous center of zero velocity C: r_C = r_A + (k x v_A)/omega (RK-11).
/// `None` when omega = 0 (pure translation: C is at infinity) or when C lies farther than
/// `max_distance` from A (numerically at infinity).
///
/// # Examples
///
/// The rolling wheel's center at (0, 0.5) moving at 2 m/s with omega = -4 rad/s: C is
/// the contact point, (0, 0).
/// ```
/// use glam::DVec2;
/// use rigidlab::analysis::kinematics::instantaneous_center;
/// let c = instantaneous_center(DVec2::new(0.0, 0.5), DVec2::new(2.0, 0.0), -4.0, 1e6).unwrap();
/// assert!(c.length() < 1e-12);
/// assert_eq!(instantaneous_center(DVec2::ZERO, DVec2::X, 0.0, 1e6), None); // translation
/// ```
#[inline]
pub fn instantaneous_center(
    r_a: DVec2,
    v_a: DVec2,
    omega: f64,
    max_distance: f64,
) -> Option<DVec2> {
    if omega == 0.0 {
        return None;
    }
    let d = DVec2::new(-v_a.y, v_a.x) * (1.0 / omega);
    // A NaN or infinite distance fails the comparison too: None.
    if d.length_squared() <= max_distance * max_distance {
        Some(r_a + d)
    } else {
        None
    }
}

/// The instantaneous center of zero velocity C from the velocity directions of two points of a
/// body (RK-11, the graphical construction): the intersection of the normal to v_P at P with
/// the normal to v_Q at Q. A point with (near) zero velocity is itself the center. `None` when
/// the normals are parallel (the body translates) or both points are at rest.
pub fn instantaneous_center_from_two_points(
    p: DVec2,
    v_p: DVec2,
    q: DVec2,
    v_q: DVec2,
) -> Option<DVec2> {
    let scale = v_p.length().max(v_q.length());
    if scale == 0.0 {
        return None;
    }
    if v_q.length() < 1e-9 * scale {
        return Some(q);
    }
    if v_p.length() < 1e-9 * scale {
        return Some(p);
    }
    // P + s perp(v_p) = Q + u perp(v_q).
    let (a, b) = (v_p.perp(), v_q.perp());
    let det = cross(a, b);
    if det.abs() < 1e-12 * a.length() * b.length() {
        return None;
    }
    let s = cross(q - p, b) / det;
    Some(p + a * s)
}

/// Omega of a body from the velocity of one point P and the instantaneous center C (RK-11):
/// v_P = omega k x (P - C), so omega = (k x (P - C)) . v_P / |P - C|^2.
pub fn omega_about_center(p: DVec2, v_p: DVec2, c: DVec2) -> f64 {
    let r = p - c;
    r.perp().dot(v_p) / r.length_squared()
}

/// The velocity of the body's pose origin or mass center implied by the **positions** the
/// engine drew, for symplectic Euler over `substeps` substeps per step.
///
/// Symplectic Euler moves each substep with the substep's *new* velocity, so the displacement
/// over a step is dt times the mean substep velocity: dr_n/dt = v_{n-1} + c (v_n - v_{n-1}) with
/// c = (S + 1)/(2S) when the velocity changes linearly through the step. Solving with the next
/// step's displacement as well gives v_n = c dr_n/dt + (1 - c) dr_{n+1}/dt, exact for constant
/// acceleration (error O(dt^2) times the jerk). S -> infinity gives the central difference.
pub fn velocity_from_positions(dr_n: DVec2, dr_next: DVec2, dt: f64, substeps: usize) -> DVec2 {
    let c = substep_weight(substeps);
    (c * dr_n + (1.0 - c) * dr_next) / dt
}

/// The angular counterpart of [`velocity_from_positions`] (angle steps already unwrapped).
pub fn omega_from_angles(dtheta_n: f64, dtheta_next: f64, dt: f64, substeps: usize) -> f64 {
    let c = substep_weight(substeps);
    (c * dtheta_n + (1.0 - c) * dtheta_next) / dt
}

/// c = (S + 1)/(2S): the weight of the new end of the step in the mean substep velocity.
pub fn substep_weight(substeps: usize) -> f64 {
    let s = substeps.max(1) as f64;
    (s + 1.0) / (2.0 * s)
}

/// Relative velocity of body B's point over body A's point at a common world point:
/// v_{B/A} = (v_GB + omega_B k x r_{P/GB}) - (v_GA + omega_A k x r_{P/GA}) (RK-6 on each body).
pub fn relative_point_velocity(a: &super::Motion, b: &super::Motion, p: DVec2) -> DVec2 {
    b.velocity_at(p) - a.velocity_at(p)
}

/// Slip velocity at a contact: the tangential part of the relative velocity of the two bodies'
/// points at the contact, along t = (-n_y, n_x) (RK-8: zero when rolling without slipping).
pub fn slip_velocity(a: &super::Motion, b: &super::Motion, p: DVec2, normal: DVec2) -> f64 {
    relative_point_velocity(a, b, p).dot(normal.perp())
}

/// The slip of body b on body a in `snap`: the tangential velocity of b's contact point relative
/// to a's at their (impulse-weighted) contact point, along t = k x n with n the contact normal
/// from a into b, m/s (RK-8: zero while b rolls or sticks on a). None when they do not touch.
///
/// The contact point is the one the solver's friction acted at
/// ([`PairContact::solver_point`](super::impact::PairContact::solver_point)), on the rolling
/// body's rim: a soft contact lets the bodies overlap by a settled depth d, and the other
/// body's surface point lies d inside the rim, where a ball rolling at omega moves at omega d
/// (6.9e-3 m/s at 103 rad/s and d = 6.9e-5 m, 60 Hz; 2026-12-06). Without arms (a hand-built
/// snapshot), body1's surface point.
pub fn contact_slip(snap: &crate::snapshot::Snapshot, a: usize, b: usize) -> Option<f64> {
    let c = super::impact::pair_contact(snap, a, b)?;
    let (ma, mb) = (
        super::Motion::from(&snap.bodies[a]),
        super::Motion::from(&snap.bodies[b]),
    );
    Some(slip_velocity(
        &ma,
        &mb,
        c.solver_point.unwrap_or(c.point),
        c.normal,
    ))
}

/// How far body i's mass center sits below where a rigid contact would hold it: the sum, over
/// the contacts that touch i, of the deepest overlap of each along its normal (pointing out of
/// i's partner into i), negated. rapier's contacts are soft (a spring and damper in the normal
/// row): a body resting or rolling on a fixed floor settles into it by a depth that grows with
/// the step (6.9e-5 m at 1/60 s and 4 substeps against a fixed body; 2026-12-06), and gravity's
/// work over that depth is absorbed by the contact, which a rigid contact never does. The
/// rigid contact's configuration of G is `com - contact_sag`. Zero for a body touching nothing.
/// Exact for one contact or contacts with orthogonal normals; overlaps of a few 1e-5 m make the
/// rest second order.
pub fn contact_sag(snap: &crate::snapshot::Snapshot, i: usize) -> DVec2 {
    let mut sag = DVec2::ZERO;
    for c in &snap.contacts {
        let into_i = if c.body2 == i {
            c.normal
        } else if c.body1 == i {
            -c.normal
        } else {
            continue;
        };
        let depth = c.points.iter().map(|p| -p.distance).fold(0.0, f64::max);
        sag -= into_i * depth;
    }
    sag
}

/// Angular velocity of the line from A to B from the two points' velocities:
/// omega = (r_{B/A} x v_{B/A})_z / |r_{B/A}|^2 (RK-6 solved for omega).
pub fn omega_from_two_points(r_a: DVec2, v_a: DVec2, r_b: DVec2, v_b: DVec2) -> f64 {
    let r = r_b - r_a;
    cross(r, v_b - v_a) / r.length_squared()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn instant_center_from_two_velocity_directions() {
        // P = (0, 0) moving up and Q = (1, 1) moving right: the normals are y = 0 and x = 1, so C = (1, 0),
        // and v_P = omega k x (P - C) = omega (0, -1) gives omega = -1 (clockwise).
        let (p, vp) = (DVec2::ZERO, DVec2::Y);
        let c =
            instantaneous_center_from_two_points(p, vp, DVec2::new(1.0, 1.0), DVec2::X).unwrap();
        assert!((c - DVec2::new(1.0, 0.0)).length() < 1e-12, "{c}");
        assert!((omega_about_center(p, vp, c) + 1.0).abs() < 1e-12);
        // A point at rest is its own center.
        let c =
            instantaneous_center_from_two_points(p, vp, DVec2::new(2.0, 0.0), DVec2::ZERO).unwrap();
        assert_eq!(c, DVec2::new(2.0, 0.0));
        // Parallel normals: the link translates (no center).
        assert!(instantaneous_center_from_two_points(
            p,
            vp,
            DVec2::new(1.0, 0.0),
            DVec2::new(0.0, -1.0)
        )
        .is_none());
    }
}
