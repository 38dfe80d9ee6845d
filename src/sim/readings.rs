//! Reading the engine into the snapshot: bodies, contacts and joints after a rapier call, and
//! the sums of several calls' impulses over one step (split substeps).

use super::rapier::geometry::Contact;
use super::rapier::prelude::*;
use super::world::{to_d, wrap_pi, Simulation};
use super::{build, joints};
use crate::level::*;
use crate::snapshot::*;
use glam::DVec2;

/// The poses a rapier call built one joint's rows from.
pub(super) struct JointPoses {
    pub(super) pose1: Pose,
    pub(super) pose2: Pose,
    /// The two bodies' mass centers (world), from which rapier measured the rows' lever arms.
    pub(super) com1: DVec2,
    pub(super) com2: DVec2,
}

impl Simulation {
    pub(super) fn read_bodies(&mut self) {
        if self.snapshot.bodies.is_empty() {
            // Names, kinds and mass properties are set once: they do not change during a run.
            // Mass properties are the ones handed to rapier (parry's, from the shapes); rapier
            // itself only folds them into the body inside its first step.
            for (i, h) in self.bodies.iter().enumerate() {
                let rb = &self.world.bodies[*h];
                let def = &self.level.bodies[i];
                let dynamic = def.kind == BodyKind::Dynamic;
                let mp = build::mass_properties(def);
                self.snapshot.bodies.push(BodyState {
                    name: self.level.bodies[i].name.clone(),
                    kind: self.level.bodies[i].kind,
                    position: to_d(rb.translation()),
                    angle: rb.rotation().angle() as f64,
                    // From the pose, not rb.center_of_mass(): rapier refreshes that only inside a step.
                    com: to_d(*rb.position() * mp.local_com),
                    velocity: to_d(rb.linvel()),
                    omega: rb.angvel() as f64,
                    mass: if dynamic { mp.mass() as f64 } else { 0.0 },
                    inertia: if dynamic && !def.lock_rotation {
                        mp.principal_inertia() as f64
                    } else {
                        0.0
                    },
                    local_com: to_d(mp.local_com),
                });
            }
            return;
        }
        for (b, h) in self.snapshot.bodies.iter_mut().zip(&self.bodies) {
            let rb = &self.world.bodies[*h];
            let pose = rb.position();
            b.position = to_d(pose.translation);
            // Continuous angle: add the wrapped change since the last snapshot.
            b.angle += wrap_pi(pose.rotation.angle() as f64 - b.angle);
            let rot = DVec2::new(pose.rotation.re as f64, pose.rotation.im as f64);
            b.com = b.position + rot.rotate(b.local_com);
            b.velocity = to_d(rb.linvel());
            b.omega = rb.angvel() as f64;
        }
    }

    pub(super) fn read_contacts(&mut self) {
        self.read_contacts_with(false);
    }

    /// Reads the contacts; `local`: with each point's material points in its bodies' frames
    /// (`ContactPoint::local`), for a step of several rapier calls (see `place_at_step_end`).
    ///
    /// The common case, a pair of which neither shape is a ball, read at a step's end, has a
    /// loop of its own ([`plain_point`]): no ball's radius and no frame is asked or branched on
    /// a point.
    pub(super) fn read_contacts_with(&mut self, local: bool) {
        // A world without balls asks no collider its shape (two dynamic calls a pair, 1% of
        // rapier's step on a 200-box pile, callgrind 2026-12-07).
        let balls = !self.round_colliders.refresh(&self.world).balls.is_empty();
        let (colliders, bodies) = (&self.world.colliders, &self.world.bodies);
        // Overwrite the previous step's entries in place: no allocation per manifold in steady state.
        let contacts = &mut self.snapshot.contacts;
        let mut n = 0;
        for pair in self.world.narrow_phase.contact_pairs() {
            // Only a rigid pair has manifolds (`ContactPair::manifolds` is empty for two soft
            // surfaces, which rigidlab never builds). rapier's `has_any_active_contact`, read
            // from the fields: its accessors are calls across the crate, one a pair.
            let PairContacts::Rigid(rigid) = &pair.contacts else {
                continue;
            };
            let solver = if rigid.solver_clusters.is_empty() {
                &rigid.manifolds
            } else {
                &rigid.solver_clusters
            };
            if solver.iter().all(|m| m.data.solver_contacts.is_empty()) {
                continue;
            }
            // Colliders carry their body's index in user_data (set when the world is built).
            let (c1, c2) = (&colliders[pair.collider1], &colliders[pair.collider2]);
            let (b1, b2) = (c1.user_data as usize, c2.user_data as usize);
            let (pose1, pose2) = (*c1.position(), *c2.position());
            let (r1, r2) = if balls {
                (ball_radius(c1), ball_radius(c2))
            } else {
                (None, None)
            };
            let body_pose =
                |c: &Collider| c.parent().map_or(Pose::IDENTITY, |h| *bodies[h].position());
            // The frames only for a step of several calls, the rest of the pair's reading
            // shared by both.
            let frames = local.then(|| (body_pose(c1).inverse(), body_pose(c2).inverse()));
            let plain = r1.is_none() && r2.is_none() && frames.is_none();
            for m in &rigid.manifolds {
                if m.points.is_empty() {
                    continue;
                }
                if n == contacts.len() {
                    contacts.push(ContactState {
                        body1: 0,
                        body2: 0,
                        normal: DVec2::ZERO,
                        points: Vec::new(),
                    });
                }
                let c = &mut contacts[n];
                n += 1;
                c.body1 = b1;
                c.body2 = b2;
                c.normal = to_d(m.data.normal);
                c.points.clear();
                let normal = m.data.normal;
                if plain {
                    c.points.extend(
                        m.points
                            .iter()
                            .map(|pt| plain_point(pt, &pose1, &pose2, normal)),
                    );
                    continue;
                }
                c.points.extend(m.points.iter().map(|pt| {
                    // From the current poses: rapier recycles contacts, and a recycled point
                    // keeps the distance of its last full update (a 9 mm overlap read as 0).
                    // A ball's side at its surface point ([`surface_point`]).
                    let material1 = pose1 * pt.local_p1;
                    let (s1, s2) = (
                        surface_point(r1, material1, &pose1, normal),
                        surface_point(r2, pose2 * pt.local_p2, &pose2, -normal),
                    );
                    ContactPoint {
                        local: frames
                            .map(|(frame1, frame2)| (to_d(frame1 * s1), to_d(frame2 * s2))),
                        ..contact_point(pt, material1, (s2 - s1).dot(normal))
                    }
                }));
            }
        }
        contacts.truncate(n);
    }

    pub(super) fn read_joints(&mut self) {
        self.read_joints_scaled(self.substeps() as f64, None);
    }

    /// Each joint's two bodies' poses and mass centers now, before a rapier call builds its rows.
    pub(super) fn joint_poses(&self) -> Vec<JointPoses> {
        self.joint_poses_by(|rb| (*rb.position(), to_d(rb.center_of_mass())))
    }

    /// Each joint's two bodies' poses and mass centers as `pose_of` gives them from the bodies.
    pub(super) fn joint_poses_by(
        &self,
        pose_of: impl Fn(&RigidBody) -> (Pose, DVec2),
    ) -> Vec<JointPoses> {
        self.joints
            .iter()
            .map(|h| {
                let j = self
                    .world
                    .impulse_joints
                    .get(*h)
                    .expect("joint handles stay valid");
                let (pose1, com1) = pose_of(&self.world.bodies[j.body1()]);
                let (pose2, com2) = pose_of(&self.world.bodies[j.body2()]);
                JointPoses {
                    pose1,
                    pose2,
                    com1,
                    com2,
                }
            })
            .collect()
    }

    /// Joint states with the last substep's impulses times `n` (the substeps of one rapier call),
    /// read along rows rebuilt from `rows_from` (the poses the call started from) when given,
    /// else from the poses now (one substep of motion off: O(h) in the rows' direction).
    pub(super) fn read_joints_scaled(&mut self, n: f64, rows_from: Option<&[JointPoses]>) {
        // The joints' entries are overwritten in place (names are set once: a joint's name does
        // not change), and its bodies' indices found once: a split step reads the joints once
        // per substep, and a name cloned and hashed each time cost more than the reading.
        self.snapshot.joints.truncate(self.joints.len());
        while self.joint_bodies.len() < self.joint_defs.len() {
            let def = &self.joint_defs[self.joint_bodies.len()];
            let pair = (self.body_index[&def.body1], self.body_index[&def.body2]);
            self.joint_bodies.push(pair);
        }
        for (k, h) in self.joints.iter().enumerate() {
            let j = &self
                .world
                .impulse_joints
                .get(*h)
                .expect("joint handles stay valid");
            let def = &self.joint_defs[k];
            let (i1, i2) = self.joint_bodies[k];
            let (rb1, rb2) = (
                &self.world.bodies[self.bodies[i1]],
                &self.world.bodies[self.bodies[i2]],
            );
            // Mass properties do not change within a call (rapier refreshes a body's effective
            // inverse mass and inertia inside its step), so they are read now; only the poses and
            // G are the call's start.
            let (mut m1, mut m2) = (joints::BodyMetric::of(rb1), joints::BodyMetric::of(rb2));
            let r = match rows_from.and_then(|p| p.get(k)) {
                Some(p) => {
                    (m1.com, m2.com) = (p.com1, p.com2);
                    joints::last_substep_reaction(j, &p.pose1, &p.pose2, &m1, &m2)
                }
                None => joints::last_substep_reaction(j, rb1.position(), rb2.position(), &m1, &m2),
            };
            let frame1 = *rb1.position() * j.data.local_frame1;
            let frame2 = *rb2.position() * j.data.local_frame2;
            let coordinate = match def.kind {
                // As rapier's motor measures it: body2's turn relative to body1 since t = 0,
                // counter-clockwise positive, wrapped to (-pi, pi].
                JointKind::Revolute | JointKind::Fixed => super::world::wrap_pi(
                    (rb2.rotation().angle() - rb1.rotation().angle()) as f64
                        - (self.level.bodies[i2].angle - self.level.bodies[i1].angle),
                ),
                JointKind::Prismatic | JointKind::PinSlot => {
                    let axis = frame1.rotation * Vector::X;
                    (frame2.translation - frame1.translation).dot(axis) as f64
                }
            };
            // Joint rows restart each substep: the step's impulse is `substeps` times the last one.
            let state = JointState {
                name: String::new(),
                body1: i1,
                body2: i2,
                anchor: to_d(frame2.translation),
                anchor1: to_d(frame1.translation),
                impulse_on_body2: r.on_body2 * n,
                angular_impulse_on_body2: r.angular_on_body2 * n,
                angular_impulse_on_body1: r.angular_on_body1 * n,
                couple_on_body2: r.couple_on_body2 * n,
                motor_impulse: r.motor * n,
                limit_impulse: r.limit * n,
                coordinate,
            };
            match self.snapshot.joints.get_mut(k) {
                Some(e) => {
                    let name = std::mem::take(&mut e.name);
                    *e = JointState { name, ..state };
                }
                None => self.snapshot.joints.push(JointState {
                    name: def.name.clone(),
                    ..state
                }),
            }
        }
    }
}

/// Adds one rapier call's contacts to the step's sums: each earlier point's impulses go to the
/// nearest point of the same body pair's manifold (same ordinal), so every manifold's total
/// impulse is kept; contacts gone by the last call stay in the list with their last geometry.
pub(super) fn merge_contacts(sum: &mut Vec<ContactState>, now: &[ContactState]) {
    let old = std::mem::take(sum);
    *sum = now.to_vec();
    let mut used = vec![false; old.len()];
    // The k-th manifold of a body pair now meets the k-th of the same pair before: both lists
    // sorted by pair (stable, so each pair's manifolds keep their order) and walked together,
    // O(n log n) where counting each manifold's ordinal was O(n^2) per rapier call.
    let key = |c: &ContactState| (c.body1, c.body2);
    let mut now_order: Vec<usize> = (0..now.len()).collect();
    now_order.sort_by_key(|&k| key(&now[k]));
    let mut old_order: Vec<usize> = (0..old.len()).collect();
    old_order.sort_by_key(|&j| key(&old[j]));
    let (mut a, mut b) = (0, 0);
    while a < now_order.len() && b < old_order.len() {
        let (k, j) = (now_order[a], old_order[b]);
        match key(&now[k]).cmp(&key(&old[j])) {
            std::cmp::Ordering::Less => {
                a += 1;
                continue;
            }
            std::cmp::Ordering::Greater => {
                b += 1;
                continue;
            }
            std::cmp::Ordering::Equal => (a, b) = (a + 1, b + 1),
        }
        used[j] = true;
        let c = &mut sum[k];
        if c.points.is_empty() {
            c.points = old[j].points.clone();
            continue;
        }
        // The two calls' manifolds may differ in normal and in the solver's lever arms (a body
        // rolling over a faceted track meets the next facet, a rolling body's contact moves
        // along the other body, a wheel that struck a curb turns about its corner in the calls
        // after the impact). The step's impulse must keep two things: the vector sum (the
        // force, for Newton-Euler) and the sums of the normal and the friction parts each along
        // its own call's axes (their ratio is Coulomb's F/N, which `SlipStarts` compares with
        // mu to 0.1%). Both hold when the merged normal is the one along which the vector sum
        // splits in the ratio of the scalar sums: to first order the impulse-weighted mean of
        // the calls' normals (an impact's own, not a later call's after the bodies turned).
        // Each merged point keeps the lever arms of its larger part, moved along the line of
        // action so that its moment about each body's mass center is the sum of the two: the
        // moments and the work at the bodies' mid-step velocities (J . (v + w x a) = J . v +
        // w (a x J) in 2D) are then those of the separate impulses. Before, the scalars were
        // added along the newest call's axes at its arms: Newton-Euler residuals of 1.6e-2 N and
        // 3.2e-3 N m on a disc rolling in a ring of 7025 facets (0.9 mrad apart), and a wheel's
        // impact with a curb read with a normal 0.017 rad late.
        let n_old = old[j].normal;
        let n_new = c.normal;
        let vector =
            |n: DVec2, p: &ContactPoint| n * p.normal_impulse + n.perp() * p.tangent_impulse;
        let (mut normal_sum, mut friction_sum, mut total) = (0.0, 0.0, DVec2::ZERO);
        for (n, points) in [(n_old, &old[j].points), (n_new, &c.points)] {
            for p in points {
                normal_sum += p.normal_impulse;
                friction_sum += p.tangent_impulse;
                total += vector(n, p);
            }
        }
        let merged_normal = if total.length_squared() > 0.0 {
            let angle = total.to_angle() - friction_sum.atan2(normal_sum);
            DVec2::from_angle(angle)
        } else {
            n_new
        };
        // Each point as its impulse vector (in `tangent_impulse`'s place the vector's y while
        // merging: resolved along the merged normal at the end).
        let mut vectors: Vec<DVec2> = c.points.iter().map(|q| vector(n_new, q)).collect();
        for p in &old[j].points {
            let k = (0..c.points.len())
                .min_by(|&a, &b| {
                    (c.points[a].point - p.point)
                        .length_squared()
                        .total_cmp(&(c.points[b].point - p.point).length_squared())
                })
                .expect("non-empty");
            let q = &mut c.points[k];
            let j_q = vectors[k];
            let j_p = vector(n_old, p);
            let both = j_q + j_p;
            if let (Some((q1, q2)), Some((p1, p2))) = (q.arms, p.arms) {
                let p_larger = j_p.length_squared() > j_q.length_squared();
                let keep_moment = |qa: DVec2, pa: DVec2| {
                    let moment = qa.perp_dot(j_q) + pa.perp_dot(j_p);
                    let base = if p_larger { pa } else { qa };
                    let len2 = both.length_squared();
                    if len2 > 0.0 {
                        base - both.perp() * ((moment - base.perp_dot(both)) / len2)
                    } else {
                        base
                    }
                };
                q.arms = Some((keep_moment(q1, p1), keep_moment(q2, p2)));
            }
            vectors[k] = both;
        }
        c.normal = merged_normal;
        for (q, v) in c.points.iter_mut().zip(vectors) {
            q.normal_impulse = v.dot(merged_normal);
            q.tangent_impulse = v.dot(merged_normal.perp());
        }
    }
    for (j, o) in old.into_iter().enumerate() {
        if !used[j] {
            sum.push(o);
        }
    }
}

/// A contact point of a collider (at `pose`) in world axes: a ball's surface point along
/// `outward` (the normal pointing from it to the other body), whatever it has turned since the
/// contact was found; another shape's material point `local`.
///
/// rapier's point on a ball is the material point it found at the call's start, which has
/// turned with the ball since by w T and left the surface by r (1 - cos w T). Read from it, a
/// disc rolling at 0.4 m/s (r = 0.2 m) in one call of 1/60 s seemed to sink 1e-4 m deeper than
/// in four calls, and the rigid-contact path of the work-energy analysis
/// (questions/work_and_power.rs) booked gravity's work over it
/// (tests/suite/questions/contact_sag.rs, 2026-12-07).
///
/// `ball_radius`: the collider's radius if it is a ball ([`ball_radius`], asked once a pair);
/// `material`: the material point, `pose * local` (computed once by the caller, which reads
/// body1's as the contact's point too).
#[inline]
fn surface_point(
    ball_radius: Option<Real>,
    material: Vector,
    pose: &Pose,
    outward: Vector,
) -> Vector {
    match ball_radius {
        Some(r) => pose.translation + outward * r,
        None => material,
    }
}

/// A point of a contact between two shapes neither of which is a ball, read at a step's end:
/// `read_contacts_with`'s general reading with `surface_point` the material point and no
/// frames, the same operations in the same order.
#[inline]
fn plain_point(pt: &Contact, pose1: &Pose, pose2: &Pose, normal: Vector) -> ContactPoint {
    let (s1, s2) = (*pose1 * pt.local_p1, *pose2 * pt.local_p2);
    contact_point(pt, s1, (s2 - s1).dot(normal))
}

/// A contact point from rapier's: its point on body1 (`material1`, world axes), the
/// separation along the normal, the impulses and the solver's lever arms; no frames.
#[inline]
fn contact_point(pt: &Contact, material1: Vector, distance: Real) -> ContactPoint {
    ContactPoint {
        point: to_d(material1),
        distance: distance as f64,
        normal_impulse: pt.data.impulse as f64,
        tangent_impulse: pt.data.tangent_impulse[0] as f64,
        arms: Some((to_d(pt.data.solver_dp1), to_d(pt.data.solver_dp2))),
        local: None,
    }
}

/// The collider's radius if it is a ball.
fn ball_radius(collider: &Collider) -> Option<Real> {
    collider.shape().as_ball().map(|b| b.radius)
}

/// Places every contact of a step of several rapier calls at the poses the step ends with (a
/// contact that ended in an earlier call, such as an impact cut at its time of impact, was read
/// at that call's poses), as `read_contacts` reads rapier's own: the point on body1 and the
/// separation of the two material points along the normal. Clears `ContactPoint::local`.
pub(super) fn place_at_step_end(contacts: &mut [ContactState], bodies: &[BodyState]) {
    for c in contacts {
        for p in &mut c.points {
            if let Some((l1, l2)) = p.local.take() {
                let (p1, p2) = (
                    bodies[c.body1].world_point(l1),
                    bodies[c.body2].world_point(l2),
                );
                p.point = p1;
                p.distance = (p2 - p1).dot(c.normal);
            }
        }
    }
}

/// Adds one rapier call's joint impulses (world axes) to the step's sums; the rest of the
/// state (anchors, coordinate) is the latest call's.
pub(super) fn merge_joints(sum: &mut Vec<JointState>, now: &[JointState]) {
    // The geometry is the last call's; the impulses add up. Names are cloned once, when a joint
    // first enters the sum (a weld made during the step joins it then).
    for (k, n) in now.iter().enumerate() {
        let Some(s) = sum.get_mut(k) else {
            sum.push(n.clone());
            continue;
        };
        let name = std::mem::take(&mut s.name);
        let prev = std::mem::replace(s, JointState { name, ..*n });
        s.impulse_on_body2 += prev.impulse_on_body2;
        s.angular_impulse_on_body2 += prev.angular_impulse_on_body2;
        s.angular_impulse_on_body1 += prev.angular_impulse_on_body1;
        s.couple_on_body2 += prev.couple_on_body2;
        s.motor_impulse += prev.motor_impulse;
        s.limit_impulse += prev.limit_impulse;
    }
    sum.truncate(now.len());
}
