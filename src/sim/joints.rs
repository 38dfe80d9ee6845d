//! Converting rapier's stored joint impulses into world-axis reactions.
//!
//! rapier 0.36 does not store a joint's reaction. `ImpulseJoint::impulses`
//! holds, per constrained axis, the impulse of the **last substep** along the
//! Jacobian rows that the solver used, and those rows are not the joint's axes:
//! `JointConstraintHelper::finalize_constraints` orthogonalizes each block of
//! rows (modified Gram-Schmidt in the metric of the two bodies' inverse mass and
//! inertia) before solving. Reading `impulses` as (x, y) components is right
//! only when the rows happen to be orthogonal already (e.g. a bob hanging
//! straight down), which is why a swinging pendulum's x component looks wrong.
//!
//! Here we rebuild the rows exactly as rapier does (`joint_velocity_constraint.rs`,
//! `joint_constraint_helper.rs`: lock rows, then limit rows in one block; motor
//! rows in their own block), apply the same orthogonalization, and sum
//! `impulse_i * row_i`. That is the impulse the solver actually applied in the
//! last substep. Joint rows restart from zero each substep (`warmstart_joints`
//! is false), so the whole step's impulse is `substeps * last` to first order in
//! the substep (exact for a steady load). Tests: `tests/suite/sim/impulse_conversions.rs`.
//!
//! Rows are rebuilt from the poses at the end of the step, whereas rapier built
//! them at the start of the last substep: the difference is one substep of
//! motion, O(h) in the direction of the rows.

use super::rapier::prelude::*;
use glam::DVec2;

/// One constraint row: impulse `lambda` gives body1 `+lin * lambda` and
/// angular `+a1 * lambda`, body2 `-lin * lambda` and `-a2 * lambda` (rapier's sign convention).
#[derive(Clone, Copy, Debug, Default)]
struct Row {
    lin: DVec2,
    a1: f64,
    a2: f64,
    bounded: bool,
    impulse: f64,
}

/// What a body contributes to the metric.
#[derive(Clone, Copy, Debug)]
pub struct BodyMetric {
    pub com: DVec2,
    /// Effective inverse mass per world axis (0 for fixed bodies or locked translations).
    pub inv_mass: DVec2,
    /// Effective world inverse inertia (0 for fixed bodies or locked rotation).
    pub inv_inertia: f64,
}

impl BodyMetric {
    pub fn of(rb: &RigidBody) -> Self {
        // Kinematic, fixed and sleeping bodies enter rapier's solver with zero inverse mass.
        let dynamic = rb.is_dynamic() && !rb.is_sleeping();
        let com = rb.center_of_mass();
        let mp = rb.mass_properties();
        BodyMetric {
            com: DVec2::new(com.x as f64, com.y as f64),
            inv_mass: if dynamic {
                DVec2::new(
                    mp.effective_inv_mass.x as f64,
                    mp.effective_inv_mass.y as f64,
                )
            } else {
                DVec2::ZERO
            },
            inv_inertia: if dynamic {
                mp.effective_world_inv_inertia as f64
            } else {
                0.0
            },
        }
    }
}

/// The reaction a joint applied in the last substep, in world axes.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Reaction {
    /// Linear impulse on body2, N s.
    pub on_body2: DVec2,
    /// Angular impulse on body2 about its mass center, N m s.
    pub angular_on_body2: f64,
    /// Angular impulse on body1 about its mass center, N m s.
    pub angular_on_body1: f64,
    /// The pure couple part on body2 (rows with no linear part before orthogonalization).
    pub couple_on_body2: f64,
    /// Motor impulse (scalar along its axis, on body2 with rapier's sign flipped to "drives body2 positively").
    pub motor: f64,
    /// Limit impulse (scalar).
    pub limit: f64,
}

fn to_d(v: Vector) -> DVec2 {
    DVec2::new(v.x as f64, v.y as f64)
}

fn cross(r: DVec2, e: DVec2) -> f64 {
    r.x * e.y - r.y * e.x
}

fn dot(c: &Row, d: &Row, b1: &BodyMetric, b2: &BodyMetric) -> f64 {
    let imsum = b1.inv_mass + b2.inv_mass;
    c.lin.dot(imsum * d.lin) + b1.inv_inertia * c.a1 * d.a1 + b2.inv_inertia * c.a2 * d.a2
}

/// rapier's `finalize_constraints`: modified Gram-Schmidt; bounded rows are not removed from later rows.
fn orthogonalize(rows: &mut [Row], b1: &BodyMetric, b2: &BodyMetric) {
    for j in 0..rows.len() {
        let djj = dot(&rows[j], &rows[j], b1, b2);
        let inv = if djj != 0.0 { 1.0 / djj } else { 0.0 };
        if rows[j].bounded {
            continue;
        }
        for i in (j + 1)..rows.len() {
            let coeff = dot(&rows[i], &rows[j], b1, b2) * inv;
            let cj = rows[j];
            let ci = &mut rows[i];
            ci.lin -= cj.lin * coeff;
            ci.a1 -= cj.a1 * coeff;
            ci.a2 -= cj.a2 * coeff;
        }
    }
}

/// Rebuilds the rows of `joint` between bodies with poses `pose1`, `pose2` and sums the last substep's impulses.
pub fn last_substep_reaction(
    ij: &ImpulseJoint,
    pose1: &Pose,
    pose2: &Pose,
    b1: &BodyMetric,
    b2: &BodyMetric,
) -> Reaction {
    let joint = &ij.data;
    let frame1 = *pose1 * joint.local_frame1;
    let frame2 = *pose2 * joint.local_frame2;
    let rot = frame1.rotation;
    let basis = [
        DVec2::new(rot.re as f64, rot.im as f64),
        DVec2::new(-rot.im as f64, rot.re as f64),
    ];
    let f1 = to_d(frame1.translation);
    let f2 = to_d(frame2.translation);
    let lin_err = f2 - f1;

    let locked = joint.locked_axes.bits();
    let limited = joint.limit_axes.bits() & !locked;
    let motorized = joint.motor_axes.bits() & !locked;

    // Body1's application point snaps free axes to frame2's origin (JointConstraintHelper::new).
    let mut center1 = f2;
    for (i, axis) in basis.iter().enumerate() {
        if locked & (1 << i) != 0 {
            center1 -= *axis * lin_err.dot(*axis);
        }
    }
    let r1 = center1 - b1.com;
    let r2 = f2 - b2.com;
    let lin_row = |axis: DVec2| Row {
        lin: axis,
        a1: cross(r1, axis),
        a2: cross(r2, axis),
        ..Default::default()
    };
    let ang_row = || Row {
        lin: DVec2::ZERO,
        a1: 1.0,
        a2: 1.0,
        ..Default::default()
    };

    // Motor block (its own Gram-Schmidt block; motor rows are bounded by max force).
    let mut out = Reaction::default();
    {
        let mut rows = Vec::new();
        if motorized & (1 << 2) != 0 {
            rows.push(Row {
                bounded: true,
                impulse: joint.motors[2].impulse as f64,
                ..ang_row()
            });
        }
        for (i, axis) in basis.iter().enumerate() {
            if motorized & (1 << i) != 0 {
                rows.push(Row {
                    bounded: true,
                    impulse: joint.motors[i].impulse as f64,
                    ..lin_row(*axis)
                });
            }
        }
        orthogonalize(&mut rows, b1, b2);
        for r in &rows {
            out.motor -= r.impulse; // body2 receives -row * impulse
            out.on_body2 -= r.lin * r.impulse;
            out.angular_on_body2 -= r.a2 * r.impulse;
            out.angular_on_body1 += r.a1 * r.impulse;
        }
    }

    // Lock rows (angular first, then linear), then limit rows: one block.
    let mut rows: Vec<Row> = Vec::with_capacity(6);
    if locked & (1 << 2) != 0 {
        rows.push(Row {
            impulse: ij.impulses.z as f64,
            ..ang_row()
        });
    }
    for (i, axis) in basis.iter().enumerate() {
        if locked & (1 << i) != 0 {
            rows.push(Row {
                impulse: ij.impulses[i] as f64,
                ..lin_row(*axis)
            });
        }
    }
    let n_locked = rows.len();
    if limited & (1 << 2) != 0 {
        rows.push(Row {
            bounded: true,
            impulse: joint.limits[2].impulse as f64,
            ..ang_row()
        });
    }
    for (i, axis) in basis.iter().enumerate() {
        if limited & (1 << i) != 0 {
            rows.push(Row {
                bounded: true,
                impulse: joint.limits[i].impulse as f64,
                ..lin_row(*axis)
            });
        }
    }
    // The couple part: lock rows that start as pure angular rows (before orthogonalization mixes them).
    let couple_rows: Vec<bool> = rows.iter().map(|r| r.lin == DVec2::ZERO).collect();
    orthogonalize(&mut rows, b1, b2);

    for (k, r) in rows.iter().enumerate() {
        out.on_body2 -= r.lin * r.impulse;
        out.angular_on_body2 -= r.a2 * r.impulse;
        out.angular_on_body1 += r.a1 * r.impulse;
        if couple_rows[k] && k < n_locked {
            out.couple_on_body2 -= r.impulse;
        }
        if k >= n_locked {
            out.limit += -r.impulse;
        }
    }
    out
}
