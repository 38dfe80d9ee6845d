//! The work of the forces held on a body over one step, which the force and the work families
//! share: loads, events' impulses and springs, each at its point's mean velocity over the step.

use super::snapshot_reading::to_local;
use crate::analysis::energy::power;
use crate::analysis::kinematics::body_point_velocity;
use crate::snapshot::Snapshot;
use glam::DVec2;

/// Work done on body i over the step from `prev` to `s` by its loads and by the springs attached
/// to it (the held force times the displacement of its point; ground springs only with `ground`).
pub(super) fn path_work(prev: &Snapshot, s: &Snapshot, i: usize, ground: bool) -> f64 {
    let mut w = 0.0;
    for l in s.loads.iter().filter(|l| l.body == i) {
        w += held_work(prev, s, i, l.force, l.point, l.torque);
    }
    // An event's impulse J at P does J . v_P,mid (exact for a free rigid body, see held_work).
    for e in s.impulses.iter().filter(|e| e.body == i) {
        let dt = s.time - prev.time;
        if dt > 0.0 {
            w += held_work(prev, s, i, e.impulse / dt, e.point, e.angular_impulse / dt);
        }
    }
    for sp in &s.springs {
        if sp.body2.is_none() && !ground {
            continue;
        }
        if sp.body1 == i {
            w += held_work(
                prev,
                s,
                i,
                sp.force_on_body1,
                sp.applied_at1,
                sp.couple_on_body1,
            );
        } else if sp.body2 == Some(i) {
            w += held_work(
                prev,
                s,
                i,
                -sp.force_on_body1,
                sp.applied_at2,
                -sp.couple_on_body1,
            );
        }
    }
    w
}

/// Work of a force F (and couple M) held over the step from `prev` to `s` on body i, applied at
/// the world point p (its position at the start of the step): U = (F . v_P,mid + M omega_mid) dt
/// with the step's mean velocity, which makes the works of a step add up to its change of kinetic
/// energy exactly (the analysis layer's `work_of_impulse`, WE-9 per step).
pub(super) fn held_work(
    prev: &Snapshot,
    s: &Snapshot,
    i: usize,
    f: DVec2,
    p: DVec2,
    m: f64,
) -> f64 {
    let (b0, b1) = (&prev.bodies[i], &s.bodies[i]);
    let dt = s.time - prev.time;
    let v0 = body_point_velocity(b0, p);
    let v1 = body_point_velocity(b1, b1.world_point(to_local(b0, p)));
    power(f, 0.5 * (v0 + v1), m, 0.5 * (b0.omega + b1.omega)) * dt
}
