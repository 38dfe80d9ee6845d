//! Small readings of a snapshot that several families share: finding a joint, a body's local
//! coordinates and height, whether it flies free, carrying it forward in time (a pair's normal
//! impulse is `analysis::impact::pair_normal_impulse`).

use crate::analysis::energy::body_kinetic_energy;
pub(super) use crate::analysis::impulse_solver::is_massive;
use crate::snapshot::{BodyState, Snapshot};
use glam::DVec2;

/// The index of the named joint in the snapshot.
pub(super) fn joint_index(s: &Snapshot, name: &str) -> Option<usize> {
    s.joints.iter().position(|j| j.name == name)
}

/// Body-frame coordinates of a world point.
pub(super) fn to_local(b: &BodyState, p: DVec2) -> DVec2 {
    DVec2::from_angle(-b.angle).rotate(p - b.position)
}

/// Height above the origin against gravity (y when g points down), m.
pub(super) fn height(g: DVec2, p: DVec2) -> f64 {
    if g.length() > 0.0 {
        -p.dot(g.normalize())
    } else {
        p.y
    }
}

/// Mechanical energy T + V_g of a body, J (6/9 and WE-13 of `analysis::energy`).
pub(super) fn body_mechanical_energy(g: DVec2, b: &BodyState) -> f64 {
    body_kinetic_energy(b) + crate::analysis::energy::gravity_potential(b.mass, g, b.com)
}

/// A body state carried forward by `tau` at constant acceleration `a` and constant omega.
pub(super) fn carried_forward(b: &BodyState, tau: f64, a: DVec2) -> BodyState {
    let m = crate::analysis::Motion::from(b).carried(tau, a);
    let mut n = b.clone();
    n.com = m.com;
    n.velocity = m.velocity;
    n.angle = m.angle;
    // From the body's own G offset (the carried frame origin agrees to rounding).
    n.position = n.com - DVec2::from_angle(n.angle).rotate(b.local_com);
    n
}
