//! Plane kinetics (concepts.md section 7): the free-body diagram of a body (or a set of
//! bodies) over one physics step, read from the snapshot, and the Newton-Euler residuals
//! against the kinetic diagram (6/1, 6/2, 6/4).
//!
//! A step's free-body diagram is a list of impulses, each with the point where it acted.
//! Sources and where their data comes from (see `snapshot.rs` for sign conventions):
//! - gravity: m g dt at G, taken at the mean of the substeps' start positions (rapier adds
//!   g h to the velocity at the start of each substep h = dt/S, wherever G then is);
//! - applied loads and springs: force dt held over the step; rapier turns a force at a point
//!   into a force at G plus the constant couple (r_{P/G} x F) computed at the start of the step,
//!   so the line of action moves with G but does not turn with the body;
//! - event impulses: applied at the start of the step at their point;
//! - contacts: every point's normal and friction impulse over the step, at the lever arms from G
//!   that rapier's solver used (`ContactPoint::arms`: its `solver_dp1/2`, frozen at the manifold's
//!   last full narrow-phase update while it recycles the manifold); for a snapshot without them,
//!   at the point carried back to where the narrow phase found it at the start of the step;
//! - joints: the reaction impulse summed over the substeps, at the anchor's arm from the gravity
//!   point, with the row solver's angular impulse about G (which carries any constraint couple and
//!   motor torque), each substep's about G where it began (`sim::Settings`, split substeps);
//! - couplings (pulleys, cables, gears): `ratio * lambda` along x or y at G, or as a couple for an
//!   angle term, and the reaction the body the cable runs over bears at its G (`over`, delivered
//!   one rapier call late). Each is listed on its own body, never cancelled inside a set.

use super::links::{merged, BodyLinks};
use super::{cross, Motion};
use crate::snapshot::Snapshot;
use glam::DVec2;

/// Where an impulse of the free-body diagram comes from (indices into the snapshot's lists).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Source {
    Gravity,
    Load(usize),
    Spring(usize),
    Event(usize),
    Contact {
        contact: usize,
        point: usize,
    },
    Joint(usize),
    /// A ratio constraint (pulley, cable, gear); the second index is the term.
    Coupling(usize, usize),
}

/// One impulse of a body's free-body diagram over a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepImpulse {
    /// The body it acts on (index into `Snapshot::bodies`).
    pub body: usize,
    pub source: Source,
    /// Impulse over the step, N s (world axes).
    pub impulse: DVec2,
    /// Where its line of action passes (world) while it acts: for moments about fixed points.
    pub point: DVec2,
    /// Its arm from the body's G while it acts: for moments about G.
    pub arm: DVec2,
    /// A pure couple's angular impulse, N m s.
    pub couple: f64,
    /// The body that takes the equal and opposite impulse (the other side of a contact, joint
    /// or spring); None when the reaction is outside the scene's bodies (gravity, loads, events,
    /// a spring to the ground, a coupling's axle). With a body of mass, the pair is internal to
    /// any set holding both (MK 6/5).
    pub other: Option<usize>,
}

impl StepImpulse {
    /// Angular impulse about the mass center, (r_{P/G} x J)_z + couple.
    pub fn moment_about_g(&self) -> f64 {
        cross(self.arm, self.impulse) + self.couple
    }

    /// Angular impulse about a fixed world point O, (r_{P/O} x J)_z + couple.
    pub fn moment_about(&self, o: DVec2) -> f64 {
        cross(self.point - o, self.impulse) + self.couple
    }
}

/// The mean of the substeps' start positions of G over a step, for S substeps and a G moving
/// linearly from g0 to g1: g0 + (S - 1)/(2S) (g1 - g0). This is where gravity's impulse acts.
pub fn gravity_point(g0: DVec2, g1: DVec2, substeps: usize) -> DVec2 {
    let s = substeps.max(1) as f64;
    g0 + (g1 - g0) * ((s - 1.0) / (2.0 * s))
}

/// The bodies' states at the start of a step (the previous snapshot's).
#[derive(Debug, Clone, Copy)]
pub enum Before<'a> {
    /// Every body, indexed like `Snapshot::bodies`.
    All(&'a [Motion]),
    /// Only one body (enough for that body's own free-body diagram).
    One(usize, &'a Motion),
    /// Only two bodies (enough for a pair's diagram, an impact's): the set is at most these two,
    /// and the walk does not touch the other bodies' states. A contact point without the
    /// solver's arms (`ContactPoint::arms`, which engine snapshots always carry) on a third body
    /// keeps its end-of-step position.
    Two([(usize, &'a Motion); 2]),
}

impl<'a> From<&'a [Motion]> for Before<'a> {
    fn from(v: &'a [Motion]) -> Self {
        Before::All(v)
    }
}

impl<'a> From<&'a Vec<Motion>> for Before<'a> {
    fn from(v: &'a Vec<Motion>) -> Self {
        Before::All(v)
    }
}

impl Before<'_> {
    /// Body i's state at the start of the step, if known.
    pub fn get(&self, i: usize) -> Option<&Motion> {
        match self {
            Before::All(v) => v.get(i),
            Before::One(k, m) => (*k == i).then_some(*m),
            Before::Two(pair) => pair.iter().find(|(k, _)| *k == i).map(|(_, m)| *m),
        }
    }

    /// Whether body i may be in the set (`One` and `Two` name the only bodies that may).
    fn admits(&self, i: usize) -> bool {
        match self {
            Before::All(_) => true,
            Before::One(k, _) => *k == i,
            Before::Two([(a, _), (b, _)]) => *a == i || *b == i,
        }
    }
}

/// Visits every external impulse on a set of bodies over the step that led to `snap`.
///
/// `before` holds the bodies' states at the start of the step (the previous snapshot); with
/// `Before::One(k, ..)` the set is at most body k. `in_set(i)`
/// selects the bodies. Bodies without mass (fixed, kinematic) are never in the set. Forces
/// between two bodies of the set are internal and are skipped (they cancel in the set's sums,
/// MK 6/5). For one body, use `|i| i == body`.
pub fn for_each_external_impulse(
    before: Before,
    snap: &Snapshot,
    substeps: usize,
    in_set: impl Fn(usize) -> bool,
    visit: impl FnMut(StepImpulse),
) {
    visit_impulses(before, snap, substeps, in_set, true, None, visit)
}

/// [`for_each_external_impulse`] for one body or a pair (`Before::One`, `Before::Two`), visiting
/// only the contacts and joints that `links` (built from `snap`) lists for them: the same impulses
/// in the same order, without scanning the scene's. With `Before::All` it scans as the other does.
pub fn for_each_external_impulse_linked(
    before: Before,
    snap: &Snapshot,
    substeps: usize,
    links: &BodyLinks,
    in_set: impl Fn(usize) -> bool,
    visit: impl FnMut(StepImpulse),
) {
    visit_impulses(before, snap, substeps, in_set, true, Some(links), visit)
}

/// Visits every impulse on every body with mass over the step that led to `snap`, both sides of
/// each contact, joint and spring: each body's own free-body diagram, all in one pass.
pub fn for_each_body_impulse(
    before: &[Motion],
    snap: &Snapshot,
    substeps: usize,
    visit: impl FnMut(StepImpulse),
) {
    visit_impulses(
        Before::All(before),
        snap,
        substeps,
        |_| true,
        false,
        None,
        visit,
    )
}

fn visit_impulses(
    before: Before,
    snap: &Snapshot,
    substeps: usize,
    in_set: impl Fn(usize) -> bool,
    skip_internal: bool,
    links: Option<&BodyLinks>,
    mut visit: impl FnMut(StepImpulse),
) {
    if snap.dt <= 0.0 {
        return;
    }
    let walk = Walk {
        before,
        snap,
        substeps,
        in_set,
        skip_internal,
        links,
    };
    walk.gravity(&mut visit);
    walk.loads(&mut visit);
    walk.springs(&mut visit);
    walk.events(&mut visit);
    walk.contacts(&mut visit);
    walk.joints(&mut visit);
    couplings(snap, &|i| walk.member(i), &|i| walk.g_point(i), &mut visit);
}

/// One walk over the impulses of the step that led to `snap`: the set it reads (`in_set`,
/// narrowed by `before`), and whether it skips the impulses internal to the set.
struct Walk<'a, F> {
    before: Before<'a>,
    snap: &'a Snapshot,
    substeps: usize,
    in_set: F,
    skip_internal: bool,
    links: Option<&'a BodyLinks>,
}

impl<F: Fn(usize) -> bool> Walk<'_, F> {
    fn member(&self, i: usize) -> bool {
        let snap = self.snap;
        i < snap.bodies.len()
            && snap.bodies[i].mass > 0.0
            && self.before.admits(i)
            && (self.in_set)(i)
    }

    fn start(&self, i: usize) -> DVec2 {
        self.before
            .get(i)
            .map_or(self.snap.bodies[i].com, |m| m.com)
    }

    fn g_point(&self, i: usize) -> DVec2 {
        gravity_point(self.start(i), self.snap.bodies[i].com, self.substeps)
    }

    /// Whether an impulse between two bodies is to be visited on neither side: neither is in
    /// the set, or it is internal to the set and the walk skips those.
    fn passes_by(&self, in1: bool, in2: bool) -> bool {
        !in1 && !in2 || self.skip_internal && in1 && in2
    }

    /// Every member's weight over the step, at its gravity point.
    fn gravity(&self, visit: &mut impl FnMut(StepImpulse)) {
        let snap = self.snap;
        if snap.gravity == DVec2::ZERO {
            return;
        }
        let n = snap.bodies.len();
        // With one or two bodies' start states only, the set is (at most) those: skip the scan.
        // The bodies in index order, each once.
        let (range, pair) = match self.before {
            Before::All(_) => (0..n, None),
            Before::One(k, _) => (k..(k + 1).min(n), None),
            Before::Two([(a, _), (b, _)]) => (
                0..0,
                Some(if a == b {
                    [a, usize::MAX]
                } else {
                    [a.min(b), a.max(b)]
                }),
            ),
        };
        let bodies = range.chain(pair.into_iter().flatten().filter(|&i| i < n));
        for i in bodies {
            let b = &snap.bodies[i];
            if self.member(i) {
                visit(StepImpulse {
                    body: i,
                    source: Source::Gravity,
                    impulse: b.mass * snap.gravity * snap.dt,
                    point: self.g_point(i),
                    arm: DVec2::ZERO,
                    couple: 0.0,
                    other: None,
                });
            }
        }
    }

    /// A force held over the step, applied by rapier as a force at G plus a constant couple.
    fn held(
        &self,
        i: usize,
        source: Source,
        p: DVec2,
        f: DVec2,
        torque: f64,
        other: Option<usize>,
    ) -> StepImpulse {
        let dt = self.snap.dt;
        let arm = p - self.start(i);
        StepImpulse {
            body: i,
            source,
            impulse: f * dt,
            point: self.g_point(i) + arm,
            arm,
            couple: torque * dt,
            other,
        }
    }

    fn loads(&self, visit: &mut impl FnMut(StepImpulse)) {
        for (k, l) in self.snap.loads.iter().enumerate() {
            if self.member(l.body) {
                visit(self.held(l.body, Source::Load(k), l.point, l.force, l.torque, None));
            }
        }
    }

    fn springs(&self, visit: &mut impl FnMut(StepImpulse)) {
        for (k, s) in self.snap.springs.iter().enumerate() {
            let (in1, in2) = (
                self.member(s.body1),
                s.body2.is_some_and(|b| self.member(b)),
            );
            if self.skip_internal && in1 && in2 {
                continue;
            }
            if in1 {
                visit(self.held(
                    s.body1,
                    Source::Spring(k),
                    s.applied_at1,
                    s.force_on_body1,
                    s.couple_on_body1,
                    s.body2,
                ));
            }
            if in2 {
                let b2 = s.body2.unwrap_or_default();
                visit(self.held(
                    b2,
                    Source::Spring(k),
                    s.applied_at2,
                    -s.force_on_body1,
                    -s.couple_on_body1,
                    Some(s.body1),
                ));
            }
        }
    }

    fn events(&self, visit: &mut impl FnMut(StepImpulse)) {
        for (k, e) in self.snap.impulses.iter().enumerate() {
            if self.member(e.body) {
                visit(StepImpulse {
                    body: e.body,
                    source: Source::Event(k),
                    impulse: e.impulse,
                    point: e.point,
                    arm: e.point - self.start(e.body),
                    couple: e.angular_impulse,
                    other: None,
                });
            }
        }
    }

    fn contacts(&self, visit: &mut impl FnMut(StepImpulse)) {
        let snap = self.snap;
        let before = &self.before;
        for k in ids(
            before,
            self.links,
            BodyLinks::contacts_of,
            snap.contacts.len(),
        ) {
            let c = &snap.contacts[k];
            let (in1, in2) = (self.member(c.body1), self.member(c.body2));
            if self.passes_by(in1, in2) {
                continue; // neither, or internal to the set
            }
            let t = c.tangent();
            // Carries body1's end-of-step points back to its start pose (one rotation per contact,
            // and only for points without the solver's arms).
            let mut back: Option<StartOfStep> = None;
            for (q, p) in c.points.iter().enumerate() {
                let j2 = c.normal * p.normal_impulse + t * p.tangent_impulse;
                let source = Source::Contact {
                    contact: k,
                    point: q,
                };
                // The lever arms from G that rapier's solver used (frozen at the narrow phase's last
                // full update of the manifold), else the point as the narrow phase found it at the
                // start of this step.
                let (arm1, arm2) = p.arms.unwrap_or_else(|| {
                    let back = back.get_or_insert_with(|| {
                        StartOfStep::new(&snap.bodies[c.body1], before.get(c.body1))
                    });
                    let p1 = back.point(p.point);
                    // The point on body2's surface: body1's point moved by the separation along n.
                    (
                        p1 - self.start(c.body1),
                        p1 + c.normal * p.distance - self.start(c.body2),
                    )
                });
                if in2 {
                    visit(StepImpulse {
                        body: c.body2,
                        source,
                        impulse: j2,
                        point: self.g_point(c.body2) + arm2,
                        arm: arm2,
                        couple: 0.0,
                        other: Some(c.body1),
                    });
                }
                if in1 {
                    visit(StepImpulse {
                        body: c.body1,
                        source,
                        impulse: -j2,
                        point: self.g_point(c.body1) + arm1,
                        arm: arm1,
                        couple: 0.0,
                        other: Some(c.body2),
                    });
                }
            }
        }
    }

    fn joints(&self, visit: &mut impl FnMut(StepImpulse)) {
        let snap = self.snap;
        for k in ids(
            &self.before,
            self.links,
            BodyLinks::joints_of,
            snap.joints.len(),
        ) {
            let j = &snap.joints[k];
            let (in1, in2) = (self.member(j.body1), self.member(j.body2));
            if self.passes_by(in1, in2) {
                continue;
            }
            let sides = [
                (
                    in2,
                    j.body2,
                    j.body1,
                    j.impulse_on_body2,
                    j.anchor,
                    j.angular_impulse_on_body2,
                ),
                (
                    in1,
                    j.body1,
                    j.body2,
                    -j.impulse_on_body2,
                    j.anchor1,
                    j.angular_impulse_on_body1,
                ),
            ];
            for (inside, body, other, imp, at, angular) in sides {
                if !inside {
                    continue;
                }
                let arm = at - snap.bodies[body].com;
                visit(StepImpulse {
                    body,
                    source: Source::Joint(k),
                    impulse: imp,
                    // Its angular impulse is about G where each substep's rows acted: placed, like a
                    // contact's, at the arm from the gravity point.
                    point: self.g_point(body) + arm,
                    arm,
                    // The row solver's angular impulse about G minus the moment of the linear part.
                    couple: angular - cross(arm, imp),
                    other: Some(other),
                });
            }
        }
    }
}

/// The contacts (or joints) a walk visits, ascending: every one, or with links and a set of one
/// or two bodies only theirs.
enum Ids<M> {
    All(std::ops::Range<usize>),
    Linked(M),
}

fn ids<'a>(
    before: &Before,
    links: Option<&'a BodyLinks>,
    of: fn(&BodyLinks, usize) -> &[u32],
    len: usize,
) -> Ids<impl Iterator<Item = usize> + 'a> {
    let lists = links.and_then(|l| match *before {
        Before::All(_) => None,
        Before::One(k, _) => Some((of(l, k), &[][..])),
        Before::Two([(a, _), (b, _)]) => Some((of(l, a), of(l, b))),
    });
    match lists {
        Some((a, b)) => Ids::Linked(merged(a, b)),
        None => Ids::All(0..len),
    }
}

impl<M: Iterator<Item = usize>> Iterator for Ids<M> {
    type Item = usize;
    fn next(&mut self) -> Option<usize> {
        match self {
            Ids::All(r) => r.next(),
            Ids::Linked(m) => m.next(),
        }
    }
}

/// Visits the coupling impulses on the set (see [`for_each_external_impulse`]).
fn couplings(
    snap: &Snapshot,
    member: &impl Fn(usize) -> bool,
    g_point: &impl Fn(usize) -> DVec2,
    visit: &mut impl FnMut(StepImpulse),
) {
    for (k, c) in snap.couplings.iter().enumerate() {
        // Term q for q < terms.len(); q = terms.len() is the body the cable runs over.
        for (q, (body, impulse, couple)) in c.body_impulses().enumerate() {
            if !member(body) {
                continue;
            }
            visit(StepImpulse {
                body,
                source: Source::Coupling(k, q),
                impulse,
                point: g_point(body),
                arm: DVec2::ZERO,
                couple,
                other: None,
            });
        }
    }
}

/// Carries points read at the end of a step on a body (carried along by it) back to where they
/// were at the start of the step: r_start = p0 + R(a0 - a1)(r_end - p1), one rotation per body.
#[derive(Debug, Clone, Copy)]
struct StartOfStep {
    from: DVec2,
    to: DVec2,
    rotation: Option<DVec2>,
}

impl StartOfStep {
    fn new(end: &crate::snapshot::BodyState, start: Option<&Motion>) -> Self {
        match start {
            Some(b0) => StartOfStep {
                from: end.position,
                to: b0.position,
                // A body that did not turn (the ground) needs no rotation.
                rotation: (b0.angle != end.angle).then(|| DVec2::from_angle(b0.angle - end.angle)),
            },
            None => StartOfStep {
                from: DVec2::ZERO,
                to: DVec2::ZERO,
                rotation: None,
            },
        }
    }

    fn point(&self, p_end: DVec2) -> DVec2 {
        let r = p_end - self.from;
        self.to + self.rotation.map_or(r, |q| q.rotate(r))
    }
}

/// The lever arms (on body1, on body2) of a contact point as the narrow phase found it at the start
/// of the step: body1's point carried back to its start pose, and on body2 that point moved by the
/// separation along n; arms from each body's G at the start of the step.
pub fn contact_arms_at_start(
    snap: &Snapshot,
    before: &[Motion],
    c: &crate::snapshot::ContactState,
    p: &crate::snapshot::ContactPoint,
) -> (DVec2, DVec2) {
    let p1 = StartOfStep::new(&snap.bodies[c.body1], before.get(c.body1)).point(p.point);
    let start = |i: usize| before.get(i).map_or(snap.bodies[i].com, |m| m.com);
    (
        p1 - start(c.body1),
        p1 + c.normal * p.distance - start(c.body2),
    )
}

/// Where a contact point read at the end of a step (`pose1_end * local_p1`, so carried along by
/// body1) was at the start of the step, when the narrow phase found it: the same body-1 point at
/// body1's start pose. Unknown start poses (a body outside `before`) keep the end position.
pub fn contact_point_at_start(
    body1_end: &Motion,
    body1_start: Option<&Motion>,
    p_end: DVec2,
) -> DVec2 {
    match body1_start {
        Some(b0) => {
            let local = DVec2::from_angle(-body1_end.angle).rotate(p_end - body1_end.position);
            b0.world_point(local)
        }
        None => p_end,
    }
}

/// The free-body diagram of one body over the step that led to `snap`.
/// `before`: the bodies' states at the start of the step (a `Before`, or every body's as a slice).
pub fn free_body<'a>(
    before: impl Into<Before<'a>>,
    snap: &Snapshot,
    body: usize,
    substeps: usize,
) -> Vec<StepImpulse> {
    let mut out = Vec::new();
    for_each_external_impulse(
        before.into(),
        snap,
        substeps,
        |i| i == body,
        |s| out.push(s),
    );
    out
}

/// The resultant of a step's impulses: sum J and the angular impulses about G and about O.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Resultant {
    /// Sum of impulses, N s (= sum F dt).
    pub impulse: DVec2,
    /// Sum of angular impulses about each body's own G, N m s.
    pub moment_g: f64,
    /// Sum of angular impulses about the fixed point O, N m s.
    pub moment_o: f64,
}

impl Resultant {
    pub fn add(&mut self, s: &StepImpulse, o: DVec2) {
        self.impulse += s.impulse;
        self.moment_g += s.moment_about_g();
        self.moment_o += s.moment_about(o);
    }
}

/// Newton-Euler over one step (6/1): sum F - m a_G and sum M_G - I_G alpha, with a_G and alpha
/// by finite differences of the velocities at the two ends of the step and the force sums as the
/// step's impulses over dt. Returns (force residual N, moment residual N m).
pub fn newton_euler_residual(
    m: f64,
    i_g: f64,
    before: &Motion,
    after: &Motion,
    sum_impulse: DVec2,
    sum_moment_g: f64,
    dt: f64,
) -> (DVec2, f64) {
    let a_g = super::kinematics::acceleration_fd(before.velocity, after.velocity, dt);
    let alpha = super::kinematics::angular_acceleration_fd(before.omega, after.omega, dt);
    (sum_impulse / dt - m * a_g, sum_moment_g / dt - i_g * alpha)
}

/// What a step's finite differences can resolve in the engine's precision: rapier rounds a
/// velocity v to about |v| eps at every update, a few updates per substep, so m dv over a step
/// carries rounding of up to m (|v0| + |v1|) eps n and I dw up to I (|w0| + |w1|) eps n (n
/// substeps). Divided by dt, these are the force and the moment about G that a free-body
/// diagram cannot be held to: a body coasting force-free after an impact reads m a_G of that
/// size against a diagram of zero. Returns (force, moment about G).
pub fn finite_difference_resolution(
    m: f64,
    i_g: f64,
    before: &Motion,
    after: &Motion,
    eps: f64,
    substeps: usize,
    dt: f64,
) -> (f64, f64) {
    let per = eps * substeps.max(1) as f64 / dt;
    (
        m * (before.velocity.length() + after.velocity.length()) * per,
        i_g * (before.omega.abs() + after.omega.abs()) * per,
    )
}

/// The kinetic-diagram moment about an arbitrary point P: I_G alpha + (rho x m a_G)_z with
/// rho = r_G - r_P (6/2). Equal to sum M_P.
pub fn kinetic_moment_about(m: f64, i_g: f64, alpha: f64, r_g: DVec2, a_g: DVec2, p: DVec2) -> f64 {
    i_g * alpha + cross(r_g - p, m * a_g)
}

/// The kinetic-diagram moment about a fixed pivot O of a body in fixed-axis rotation:
/// I_O alpha (6/4). Equal to sum M_O, in which the pivot reaction has no moment.
pub fn kinetic_moment_fixed_axis(i_o: f64, alpha: f64) -> f64 {
    i_o * alpha
}

/// The resultant force of a kinetic diagram, m a_G (6/1).
pub fn kinetic_force(m: f64, a_g: DVec2) -> DVec2 {
    m * a_g
}

/// The pin reaction on a body in fixed-axis rotation about a fixed pin O (PL-8, PL-12):
/// R = m a_G - sum F, with alpha = sum M_O / I_O (6/4) and a_G = alpha k x r - omega^2 r (RK-10
/// about O, which does not move), r = r_G - r_O. `force` is the resultant of the applied forces
/// (all but the pin's) and `moment_o` their moment about O with the applied couples; `i_o` is
/// I_O = I_G + m |r|^2 (MP-2, `mass::parallel_axis`), positive.
pub fn fixed_axis_reaction(
    m: f64,
    i_o: f64,
    r: DVec2,
    force: DVec2,
    moment_o: f64,
    omega: f64,
) -> DVec2 {
    let alpha = moment_o / i_o;
    let a_g = super::kinematics::point_acceleration(DVec2::ZERO, alpha, omega, r);
    kinetic_force(m, a_g) - force
}
