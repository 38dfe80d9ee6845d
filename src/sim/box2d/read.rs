//! Reading Box2D into the snapshot: bodies after a step, and each call's contact and joint
//! impulses summed over the step (docs/box2d-readings.md says how and in which units).

use super::build::Result;
use super::world::Simulation;
use crate::level::{BodyKind, JointKind};
use crate::sim::{mass_properties, Settings};
use crate::snapshot::*;
use boxdd::{Position, ShapeId, Vec2};
use glam::DVec2;
use std::collections::{HashMap, HashSet};

pub(super) fn d(v: Vec2) -> DVec2 {
    DVec2::new(v.x as f64, v.y as f64)
}

fn dp(p: Position) -> DVec2 {
    DVec2::new(p.x as f64, p.y as f64)
}

/// `a` wrapped to (-pi, pi].
fn wrap_pi(a: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    let w = (a + PI).rem_euclid(TAU) - PI;
    if w <= -PI {
        w + TAU
    } else {
        w
    }
}

pub(super) fn empty_snapshot(settings: &Settings, gravity: DVec2) -> Snapshot {
    Snapshot {
        step: 0,
        time: 0.0,
        dt: 0.0,
        substeps: settings.substeps,
        precision: Precision::F32,
        gravity,
        bodies: Vec::new(),
        contacts: Vec::new(),
        joints: Vec::new(),
        springs: Vec::new(),
        couplings: Vec::new(),
        loads: Vec::new(),
        impulses: Vec::new(),
    }
}

/// Where a joint's reaction acts, taken before a Box2D call (Box2D's solver holds its joint
/// arms at the call's start): from body1's and body2's mass centers, world axes, m.
pub(super) struct JointArms {
    r1: DVec2,
    r2: DVec2,
}

/// The contacts of a step, summed over its Box2D calls: each contact point keeps its impulses
/// whole, the geometry of the last call that saw it.
#[derive(Default)]
pub(super) struct StepContacts {
    contacts: Vec<ContactState>,
    /// (the two shapes, Box2D's feature id of the point) -> (index in `contacts`, index in its
    /// points). Keyed by shapes, not by Box2D's contact id: boxdd brands that id with the step
    /// it was read after, so one contact read after two calls would count as two.
    points: HashMap<(ShapeId, ShapeId, u16), (usize, usize)>,
    pairs: HashMap<(ShapeId, ShapeId), usize>,
    /// Each point's impulse summed as a vector (world axes, N s, on body2): a contact's normal
    /// turns within a step (a bar rocking on a small round ledge turned it 5e-3 rad a step), so
    /// the calls' scalar impulses, each along its own call's normal, are added as vectors and
    /// split along the last call's normal and tangent at the step's end (`store_contacts`).
    vectors: Vec<Vec<DVec2>>,
    /// Each point's moments about body1's and body2's mass centers, summed over the calls with
    /// each call's own arms (N m s): the arms move within a step too (`store_contacts`).
    moments: Vec<Vec<(f64, f64)>>,
}

impl Simulation {
    pub(super) fn read_initial_state(&mut self) -> Result<()> {
        for b in &self.level.bodies {
            let mp = mass_properties(b);
            let dynamic = b.kind == BodyKind::Dynamic;
            self.snapshot.bodies.push(BodyState {
                name: b.name.clone(),
                kind: b.kind,
                position: DVec2::new(b.position.0, b.position.1),
                angle: b.angle,
                com: DVec2::ZERO,
                velocity: DVec2::ZERO,
                omega: 0.0,
                mass: if dynamic { mp.mass() as f64 } else { 0.0 },
                inertia: if dynamic && !b.lock_rotation {
                    mp.principal_inertia() as f64
                } else {
                    0.0
                },
                local_com: DVec2::new(mp.local_com.x as f64, mp.local_com.y as f64),
            });
        }
        self.read_bodies()?;
        self.read_joint_poses()
    }

    /// Poses and velocities of every body (f32 in Box2D, widened to f64).
    pub(super) fn read_bodies(&mut self) -> Result<()> {
        for (k, id) in self.bodies.iter().enumerate() {
            let body = self.world.body(*id)?;
            let b = &mut self.snapshot.bodies[k];
            b.position = dp(body.position()?);
            // Continuous angle: add the wrapped change since the last snapshot.
            b.angle += wrap_pi(body.rotation()?.angle() as f64 - b.angle);
            b.com = b.world_point(b.local_com);
            // A dynamic body's linear velocity is its mass center's (its mass data's center);
            // a fixed or kinematic body does not turn here, so its origin's is its center's.
            b.velocity = d(body.linear_velocity()?);
            b.omega = body.angular_velocity()? as f64;
        }
        Ok(())
    }

    /// Each joint's arms before a call.
    pub(super) fn joint_arms(&self) -> Vec<JointArms> {
        let s = &self.snapshot;
        self.level
            .joints
            .iter()
            .zip(&self.joint_pairs)
            .map(|(j, &(i1, i2))| {
                let (b1, b2) = (&s.bodies[i1], &s.bodies[i2]);
                let p1 = b1.world_point(DVec2::new(j.anchor1.0, j.anchor1.1));
                let p2 = b2.world_point(DVec2::new(j.anchor2.0, j.anchor2.1));
                // A slider's rows act at body2's anchor on both bodies (Box2D's prismatic
                // Jacobian uses d + rA on body A); a pin's and a weld's at each body's anchor.
                let on1 = if j.kind == JointKind::Prismatic {
                    p2
                } else {
                    p1
                };
                JointArms {
                    r1: on1 - b1.com,
                    r2: p2 - b2.com,
                }
            })
            .collect()
    }

    /// Adds one call's joint reactions (`b2Joint_GetConstraintForce` and `...Torque`, the
    /// call's impulse divided by its substep, times the call's length `h`) to the step's sums.
    pub(super) fn add_joint_impulses(&mut self, arms: &[JointArms], h: f64) -> Result<()> {
        for (k, id) in self.joints.iter().enumerate() {
            let joint = self.world.joint(*id)?;
            let j = d(joint.constraint_force()?) * h;
            let couple = joint.constraint_torque()? as f64 * h;
            let a = &arms[k];
            let s = &mut self.snapshot.joints[k];
            s.impulse_on_body2 += j;
            s.couple_on_body2 += couple;
            s.angular_impulse_on_body2 += a.r2.perp_dot(j) + couple;
            s.angular_impulse_on_body1 -= a.r1.perp_dot(j) + couple;
        }
        Ok(())
    }

    /// Clears the joints' impulse sums before a step.
    pub(super) fn clear_joint_impulses(&mut self) {
        for s in &mut self.snapshot.joints {
            s.impulse_on_body2 = DVec2::ZERO;
            s.angular_impulse_on_body2 = 0.0;
            s.angular_impulse_on_body1 = 0.0;
            s.couple_on_body2 = 0.0;
        }
    }

    /// The joints' anchors and coordinates at the current poses (the impulses are kept).
    pub(super) fn read_joint_poses(&mut self) -> Result<()> {
        let s = &mut self.snapshot;
        for (k, (j, &(i1, i2))) in self.level.joints.iter().zip(&self.joint_pairs).enumerate() {
            let (b1, b2) = (&s.bodies[i1], &s.bodies[i2]);
            let anchor1 = b1.world_point(DVec2::new(j.anchor1.0, j.anchor1.1));
            let anchor = b2.world_point(DVec2::new(j.anchor2.0, j.anchor2.1));
            let (l1, l2) = (&self.level.bodies[i1], &self.level.bodies[i2]);
            let coordinate = match j.kind {
                // As on rapier: body2's turn relative to body1 since t = 0, wrapped.
                JointKind::Revolute | JointKind::Fixed => {
                    wrap_pi((b2.angle - b1.angle) - (l2.angle - l1.angle))
                }
                JointKind::Prismatic | JointKind::PinSlot => {
                    let axis = DVec2::from_angle(b1.angle)
                        .rotate(DVec2::new(j.axis.0, j.axis.1).normalize());
                    (anchor - anchor1).dot(axis)
                }
            };
            let state = JointState {
                name: j.name.clone(),
                body1: i1,
                body2: i2,
                anchor,
                anchor1,
                impulse_on_body2: DVec2::ZERO,
                angular_impulse_on_body2: 0.0,
                angular_impulse_on_body1: 0.0,
                couple_on_body2: 0.0,
                motor_impulse: 0.0,
                limit_impulse: 0.0,
                coordinate,
            };
            match s.joints.get_mut(k) {
                Some(e) => {
                    e.anchor = anchor;
                    e.anchor1 = anchor1;
                    e.coordinate = coordinate;
                }
                None => s.joints.push(state),
            }
        }
        Ok(())
    }

    /// Adds one call's contacts to the step's sums. Box2D's manifold point after a call of one
    /// substep holds what that call applied: `totalNormalImpulse` (warm start, solve, relax and
    /// restitution together) and `tangentImpulse` (warm start and solve); its normal points from
    /// shape A to shape B and its tangent is the normal's right perpendicular, rigidlab's the left
    /// one, so the friction impulse changes sign.
    pub(super) fn add_contacts(&mut self, sum: &mut StepContacts) -> Result<()> {
        let mut seen = HashSet::new();
        for id in &self.bodies {
            let data = self.world.body(*id)?.contact_data()?;
            for c in data {
                if c.manifold.is_empty() || !seen.insert(c.contact_id) {
                    continue;
                }
                let (Some(&b1), Some(&b2)) = (
                    self.shapes.get(&c.shape_id_a),
                    self.shapes.get(&c.shape_id_b),
                ) else {
                    continue;
                };
                let normal = d(c.manifold.normal);
                let com1 = self.snapshot.bodies[b1].com;
                let k = *sum
                    .pairs
                    .entry((c.shape_id_a, c.shape_id_b))
                    .or_insert_with(|| {
                        sum.contacts.push(ContactState {
                            body1: b1,
                            body2: b2,
                            normal,
                            points: Vec::new(),
                        });
                        sum.contacts.len() - 1
                    });
                sum.contacts[k].normal = normal;
                let tangent = normal.perp();
                for p in c.manifold.points() {
                    let (arm1, arm2) = (d(p.anchor_a), d(p.anchor_b));
                    let separation = p.separation as f64;
                    // Box2D's anchors lead from the mass centers at the call's start (the
                    // snapshot's bodies, read after the call) to the midpoint between the
                    // surfaces; body1's surface point is half the separation back along the normal.
                    let point = com1 + arm1 - 0.5 * separation * normal;
                    let at = *sum
                        .points
                        .entry((c.shape_id_a, c.shape_id_b, p.id))
                        .or_insert_with(|| {
                            sum.contacts[k].points.push(ContactPoint {
                                point,
                                distance: separation,
                                normal_impulse: 0.0,
                                tangent_impulse: 0.0,
                                arms: None,
                                local: None,
                            });
                            (k, sum.contacts[k].points.len() - 1)
                        });
                    let q = &mut sum.contacts[at.0].points[at.1];
                    q.point = point;
                    q.distance = separation;
                    q.arms = Some((arm1, arm2));
                    if sum.vectors.len() <= at.0 {
                        sum.vectors.resize(at.0 + 1, Vec::new());
                        sum.moments.resize(at.0 + 1, Vec::new());
                    }
                    let (v, m) = (&mut sum.vectors[at.0], &mut sum.moments[at.0]);
                    if v.len() <= at.1 {
                        v.resize(at.1 + 1, DVec2::ZERO);
                        m.resize(at.1 + 1, (0.0, 0.0));
                    }
                    let j =
                        p.total_normal_impulse as f64 * normal - p.tangent_impulse as f64 * tangent;
                    v[at.1] += j;
                    m[at.1].0 -= arm1.perp_dot(j);
                    m[at.1].1 += arm2.perp_dot(j);
                }
            }
        }
        Ok(())
    }

    pub(super) fn store_contacts(&mut self, mut sum: StepContacts) {
        let (vectors, moments) = (&sum.vectors, &sum.moments);
        for ((c, v), m) in sum.contacts.iter_mut().zip(vectors).zip(moments) {
            let (n, t) = (c.normal, c.normal.perp());
            for ((q, &j), &(m1, m2)) in c.points.iter_mut().zip(v).zip(m) {
                q.normal_impulse = j.dot(n);
                q.tangent_impulse = j.dot(t);
                q.arms = q
                    .arms
                    .map(|(a1, a2)| (arm_for(a1, -j, m1), arm_for(a2, j, m2)));
            }
        }
        self.snapshot.contacts = sum.contacts;
    }
}

/// The arm at which the step's impulse `j` on a body has the step's summed moment `moment`
/// about its mass center: the last call's arm `last`, moved across `j`'s line of action, so
/// that `arm x j = moment` (the impulse and its moment both exact); `last` when j is nil.
fn arm_for(last: DVec2, j: DVec2, moment: f64) -> DVec2 {
    let jj = j.length_squared();
    if jj < 1e-30 {
        return last;
    }
    // perp_dot(j.perp(), j) = -|j|^2.
    last - (moment - last.perp_dot(j)) / jj * j.perp()
}
