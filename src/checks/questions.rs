//! Questions: an exercise's asked quantity, read from the run and compared with the expected answer.
//!
//! Each question is read twice at the moment its `at` names:
//! - `engine`: the engine's own motion and reactions (positions, velocities, finite
//!   differences, the impulses rapier applied);
//! - `analysis`: the textbook formula for the quantity (documented on each [`Quantity`]
//!   variant) applied to the engine's state: its mass properties, pose and, for impacts and
//!   blows, its velocities just before. Where a quantity has no independent formula the
//!   analysis is `None`.
//!
//! A question passes on the engine value (the exercise grades the engine against the textbook);
//! the analysis value shows whether a miss is the engine's or the exercise's.
//!
//! The probe reads each snapshot one step late, so that every sample has the steps on both sides
//! of it: accelerations are central differences of the velocities and "mean over the step" forces
//! are centered on the sample (the mean of the two steps around it).
//!
//! Textbook helpers that the analysis layer (`crate::analysis`) does not provide yet are local to
//! this file and named after the textbook quantity: [`elliptic_k`], [`pendulum_period`],
//! [`rolling_acceleration`], [`instant_center`], and the impulse-momentum solver
//! [`solve_impulses`] (a set of bodies, joints and one contact hit by impulses, RM-10/IM-9..12).

use crate::analysis::cross;
use crate::level::{BodyKind, Component, Effect, JointKind, Level, Quantity, QuestionDef, When};
use crate::snapshot::{BodyState, Coordinate, Snapshot};
use glam::DVec2;
use serde::{Deserialize, Serialize};
use std::collections::VecDeque;
use std::f64::consts::PI;
use std::sync::Arc;

/// One question's result (the JSON report's `questions[]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct QuestionResult {
    pub id: String,
    pub ask: String,
    pub unit: String,
    pub expected: f64,
    /// The answer computed by the analysis layer from the engine's state (textbook formula), if one applies.
    pub analysis: Option<f64>,
    /// The engine's own value.
    pub engine: f64,
    /// |engine - expected| / |expected| (absolute when expected is 0).
    pub rel_error: f64,
    /// |analysis - expected| / |expected| (absolute when expected is 0), when there is an analysis.
    #[serde(default)]
    pub analysis_rel_error: Option<f64>,
    pub tolerance: f64,
    pub passed: bool,
    /// Time at which the value was read, s.
    pub time: f64,
    pub why: String,
    /// Why a value is missing (the event never happened, too few oscillations, ...).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub note: String,
    /// A student's answer and its grade, when given with `--answer ID=VALUE`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub student: Option<StudentGrade>,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StudentGrade {
    pub answer: f64,
    pub rel_error: f64,
    pub passed: bool,
}

// ---------------------------------------------------------------------------------------------
// What the probe knows about the level.

#[derive(Debug, Clone, Default)]
struct BodyInfo {
    restitution: f64,
    friction: f64,
    /// Radius of a disc centered on the body origin (for the exact line of centers of an impact).
    disc: Option<f64>,
}

#[derive(Debug, Clone)]
struct JointInfo {
    kind: JointKind,
    body1: usize,
    body2: usize,
    anchor2: DVec2,
    axis: DVec2,
}

/// Level data some analyses need beyond the snapshot (declared coefficients, joint geometry).
#[derive(Debug, Clone, Default)]
struct Ctx {
    known: bool,
    bodies: Vec<BodyInfo>,
    joints: Vec<JointInfo>,
}

impl Ctx {
    fn of(level: &Level) -> Ctx {
        let has = |e: Effect| level.effects.contains(&e);
        let index = |n: &str| level.bodies.iter().position(|b| b.name == n).unwrap_or(0);
        let v = |p: (f64, f64)| DVec2::new(p.0, p.1);
        Ctx {
            known: true,
            bodies: level
                .bodies
                .iter()
                .map(|b| BodyInfo {
                    restitution: if has(Effect::Restitution) {
                        b.restitution.unwrap_or(0.0)
                    } else {
                        0.0
                    },
                    friction: if has(Effect::Friction) {
                        b.friction.unwrap_or(0.0)
                    } else {
                        0.0
                    },
                    disc: match &b.shape {
                        Some(crate::level::Shape::Circle { radius }) => Some(*radius),
                        _ => None,
                    },
                })
                .collect(),
            joints: if has(Effect::Joints) {
                level
                    .joints
                    .iter()
                    .map(|j| JointInfo {
                        kind: j.kind,
                        body1: index(&j.body1),
                        body2: index(&j.body2),
                        anchor2: v(j.anchor2),
                        axis: v(j.axis).normalize_or(DVec2::X),
                    })
                    .collect()
            } else {
                Vec::new()
            },
        }
    }

    /// The pair's coefficients as rapier combines them (the larger of the two, see `sim::build`).
    fn restitution(&self, a: usize, b: usize) -> f64 {
        let e = |i: usize| self.bodies.get(i).map_or(0.0, |x| x.restitution);
        e(a).max(e(b))
    }
    fn friction(&self, a: usize, b: usize) -> f64 {
        let m = |i: usize| self.bodies.get(i).map_or(0.0, |x| x.friction);
        m(a).max(m(b))
    }
}

// ---------------------------------------------------------------------------------------------
// Snapshot helpers.

fn body_ix(s: &Snapshot, name: &str) -> Option<usize> {
    s.body_index(name)
}

fn joint_ix(s: &Snapshot, name: &str) -> Option<usize> {
    s.joints.iter().position(|j| j.name == name)
}

fn is_massive(b: &BodyState) -> bool {
    b.kind == BodyKind::Dynamic && b.mass > 0.0
}

/// Inverse mass and inverse inertia (0 for fixed, kinematic and rotation-locked bodies).
fn inverse_mass(b: &BodyState) -> (f64, f64) {
    if !is_massive(b) {
        return (0.0, 0.0);
    }
    (
        1.0 / b.mass,
        if b.inertia > 0.0 {
            1.0 / b.inertia
        } else {
            0.0
        },
    )
}

fn perp(v: DVec2) -> DVec2 {
    DVec2::new(-v.y, v.x)
}

use crate::analysis::energy::body_kinetic_energy as kinetic_energy;
use crate::analysis::kinematics::body_point_velocity as point_velocity;

/// Body-frame coordinates of a world point.
fn to_local(b: &BodyState, p: DVec2) -> DVec2 {
    DVec2::from_angle(-b.angle).rotate(p - b.position)
}

/// Height above the origin against gravity (y when g points down), m.
fn height(g: DVec2, p: DVec2) -> f64 {
    if g.length() > 0.0 {
        -p.dot(g.normalize())
    } else {
        p.y
    }
}

/// Mechanical energy T + V_g of a body, J.
fn mechanical_energy(g: DVec2, b: &BodyState) -> f64 {
    kinetic_energy(b) - b.mass * g.dot(b.com)
}

/// A body moving under gravity alone over this stretch (dynamic, no joint, no coupling).
fn is_free(s: &Snapshot, i: usize) -> bool {
    is_massive(&s.bodies[i])
        && !s.joints.iter().any(|j| j.body1 == i || j.body2 == i)
        && !s.couplings.iter().any(|c| c.terms.iter().any(|t| t.0 == i))
}

/// A body state carried forward by `tau` at constant acceleration `a` and constant omega.
fn advance(b: &BodyState, tau: f64, a: DVec2) -> BodyState {
    let mut n = b.clone();
    n.com = b.com + b.velocity * tau + 0.5 * a * tau * tau;
    n.velocity = b.velocity + a * tau;
    n.angle = b.angle + b.omega * tau;
    n.position = n.com - DVec2::from_angle(n.angle).rotate(b.local_com);
    n
}

/// Total normal impulse over the step between `body` and `other` (any body when None), N s.
fn pair_normal_impulse(s: &Snapshot, body: usize, other: Option<usize>) -> f64 {
    s.contacts
        .iter()
        .filter(|c| {
            (c.body1 == body && other.is_none_or(|o| c.body2 == o))
                || (c.body2 == body && other.is_none_or(|o| c.body1 == o))
        })
        .flat_map(|c| c.points.iter())
        .map(|p| p.normal_impulse.max(0.0))
        .sum()
}

/// The sample and the snapshots on both sides of it.
#[derive(Clone, Copy)]
struct Frame<'a> {
    prev: Option<&'a Snapshot>,
    cur: &'a Snapshot,
    next: Option<&'a Snapshot>,
    /// The snapshots within the quantity's averaging window around the sample (at least cur).
    window: &'a [Snapshot],
}

impl Frame<'_> {
    /// Central difference of a per-snapshot value over time (one-sided at the ends).
    fn rate(&self, f: impl Fn(&Snapshot) -> Option<f64>) -> Option<f64> {
        let (a, b) = match (self.prev, self.next) {
            (Some(p), Some(n)) => (p, n),
            (Some(p), None) => (p, self.cur),
            (None, Some(n)) => (self.cur, n),
            (None, None) => return None,
        };
        let dt = b.time - a.time;
        if dt <= 0.0 {
            return None;
        }
        Some((f(b)? - f(a)?) / dt)
    }

    /// The snapshots whose steps straddle the sample: this step and the next one.
    fn steps(&self) -> impl Iterator<Item = &Snapshot> {
        std::iter::once(self.cur)
            .chain(self.next)
            .filter(|s| s.dt > 0.0)
    }

    /// The mean of a per-step impulse divided by dt (a force) over the steps of the window, or,
    /// without a window, over the two steps around the sample.
    fn windowed(&self, f: impl Fn(&Snapshot) -> Option<DVec2>) -> Option<DVec2> {
        if self.window.len() <= 2 {
            return self.centered(f);
        }
        // The window's first snapshot only bounds the first step.
        let (mut sum, mut n) = (DVec2::ZERO, 0.0);
        for s in self.window.iter().skip(1).filter(|s| s.dt > 0.0) {
            sum += f(s)? / s.dt;
            n += 1.0;
        }
        (n > 0.0).then(|| sum / n)
    }

    /// The mean over the two steps around the sample of a per-step impulse, divided by dt: a force.
    fn centered(&self, f: impl Fn(&Snapshot) -> Option<DVec2>) -> Option<DVec2> {
        let (mut sum, mut n) = (DVec2::ZERO, 0.0);
        for s in self.steps() {
            sum += f(s)? / s.dt;
            n += 1.0;
        }
        (n > 0.0).then(|| sum / n)
    }
}

// ---------------------------------------------------------------------------------------------
// Textbook helpers (local until `crate::analysis` has them).

/// The complete elliptic integral of the first kind K(k) = int_0^{pi/2} dphi / sqrt(1 - k^2 sin^2 phi),
/// by the arithmetic-geometric mean: K(k) = pi / (2 AGM(1, sqrt(1 - k^2))).
pub fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0, (1.0 - k * k).max(0.0).sqrt());
    for _ in 0..40 {
        let (a1, b1) = (0.5 * (a + b), (a * b).sqrt());
        a = a1;
        b = b1;
        if (a - b).abs() < 1e-16 * a {
            break;
        }
    }
    PI / (2.0 * a)
}

/// Period of a physical pendulum at amplitude theta0 (rad): T = 4 sqrt(I_O / (m g d)) K(sin(theta0/2));
/// at small amplitude this is 2 pi sqrt(I_O / (m g d)) (PL-5 with the exact energy integral).
pub fn pendulum_period(i_o: f64, m: f64, g: f64, d: f64, theta0: f64) -> f64 {
    4.0 * (i_o / (m * g * d)).sqrt() * elliptic_k((0.5 * theta0).sin())
}

/// Acceleration of the center of a round body rolling without slip down a slope theta:
/// a = g sin(theta) / (1 + k_G^2 / r^2) (RK-8 with 6/1; disc k^2 = r^2/2, hoop k^2 = r^2).
pub fn rolling_acceleration(g: f64, theta: f64, k_g: f64, r: f64) -> f64 {
    g * theta.sin() / (1.0 + k_g * k_g / (r * r))
}

/// The friction force rolling without slip needs: F = m g sin(theta) k_G^2 / (k_G^2 + r^2).
pub fn rolling_friction(m: f64, g: f64, theta: f64, k_g: f64, r: f64) -> f64 {
    m * g * theta.sin() * k_g * k_g / (k_g * k_g + r * r)
}

/// The instantaneous center of zero velocity (RK-11) from the velocity directions of two body
/// points: the intersection of the normals to v_P at P and to v_Q at Q. A point with (near) zero
/// velocity is itself the center. None when the normals are parallel (translation).
pub fn instant_center(p: DVec2, v_p: DVec2, q: DVec2, v_q: DVec2) -> Option<DVec2> {
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
    let (a, b) = (perp(v_p), perp(v_q));
    let det = cross(a, b);
    if det.abs() < 1e-12 * a.length() * b.length() {
        return None;
    }
    let s = cross(q - p, b) / det;
    Some(p + a * s)
}

/// Omega of a body from the velocity of one point and the instantaneous center:
/// v_P = omega k x (P - C), so omega = (k x (P - C)) . v_P / |P - C|^2.
pub fn omega_about_center(p: DVec2, v_p: DVec2, c: DVec2) -> f64 {
    let r = p - c;
    perp(r).dot(v_p) / r.length_squared()
}

/// One row of an impulse-momentum solve: sum over entries (body, lin, ang) of
/// lin . v_body + ang * omega_body must equal `target` after the blow.
#[derive(Debug, Clone)]
struct Row {
    entries: Vec<(usize, DVec2, f64)>,
    target: f64,
}

/// A row keeping the velocity of point p along d equal on both bodies (body2 minus body1).
fn point_row(s: &[BodyState], i1: usize, i2: usize, p: DVec2, d: DVec2, target: f64) -> Row {
    Row {
        entries: vec![
            (i1, -d, -cross(p - s[i1].com, d)),
            (i2, d, cross(p - s[i2].com, d)),
        ],
        target,
    }
}

fn row_velocity(r: &Row, s: &[BodyState]) -> f64 {
    r.entries
        .iter()
        .map(|(b, lin, ang)| lin.dot(s[*b].velocity) + ang * s[*b].omega)
        .sum()
}

/// Impulse-momentum for a set of rigid bodies hit by impulses (RM-10, IM-9 to IM-12, MK 6/8):
/// every constraint row reaches its target velocity by a multiplier impulse lambda, and
/// m dv = sum J, I_G domega = sum (r x J) for each body. `ext` holds (body, impulse, angular
/// impulse about G). Returns the states after the blow and the multipliers.
fn solve_impulses(
    s: &[BodyState],
    rows: &[Row],
    ext: &[(usize, DVec2, f64)],
) -> (Vec<BodyState>, Vec<f64>) {
    let inv: Vec<(f64, f64)> = s.iter().map(inverse_mass).collect();
    let mut u = s.to_vec();
    for (b, j, ang) in ext {
        u[*b].velocity += *j * inv[*b].0;
        u[*b].omega += ang * inv[*b].1;
    }
    let n = rows.len();
    let mut k = vec![vec![0.0; n + 1]; n];
    for (r, row_r) in rows.iter().enumerate() {
        for (c, row_c) in rows.iter().enumerate() {
            let mut sum = 0.0;
            for (b1, l1, a1) in &row_r.entries {
                for (b2, l2, a2) in &row_c.entries {
                    if b1 == b2 {
                        sum += l1.dot(*l2) * inv[*b1].0 + a1 * a2 * inv[*b1].1;
                    }
                }
            }
            k[r][c] = sum;
        }
        k[r][n] = row_r.target - row_velocity(row_r, &u);
    }
    let lambda = gauss(k);
    for (row, l) in rows.iter().zip(&lambda) {
        for (b, lin, ang) in &row.entries {
            u[*b].velocity += *lin * (l * inv[*b].0);
            u[*b].omega += ang * l * inv[*b].1;
        }
    }
    (u, lambda)
}

/// Solves the augmented system [K | b] by Gaussian elimination with partial pivoting; rows that
/// are redundant (zero pivot) get a zero multiplier.
fn gauss(mut a: Vec<Vec<f64>>) -> Vec<f64> {
    let n = a.len();
    let scale = (0..n)
        .map(|i| a[i][i].abs())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let mut pivot_ok = vec![true; n];
    for c in 0..n {
        let p = (c..n)
            .max_by(|&x, &y| a[x][c].abs().total_cmp(&a[y][c].abs()))
            .unwrap_or(c);
        a.swap(c, p);
        if a[c][c].abs() < 1e-12 * scale {
            pivot_ok[c] = false;
            continue;
        }
        let pivot: Vec<f64> = a[c][c..=n].to_vec();
        for (r, row) in a.iter_mut().enumerate() {
            if r != c {
                let f = row[c] / pivot[0];
                if f != 0.0 {
                    for (x, p) in row[c..=n].iter_mut().zip(&pivot) {
                        *x -= f * p;
                    }
                }
            }
        }
    }
    (0..n)
        .map(|i| if pivot_ok[i] { a[i][n] / a[i][i] } else { 0.0 })
        .collect()
}

/// The constraint rows of the level's joints (target: no relative velocity) and of the
/// snapshot's couplings, for the bodies in state `s`. Returns the rows and, per joint, the range
/// of its rows and its kind (to rebuild its impulse).
fn constraint_rows(ctx: &Ctx, snap: &Snapshot, s: &[BodyState]) -> (Vec<Row>, Vec<(usize, usize)>) {
    let mut rows = Vec::new();
    let mut ranges = Vec::new();
    for j in &ctx.joints {
        let start = rows.len();
        let (b1, b2) = (&s[j.body1], &s[j.body2]);
        let p2 = b2.world_point(j.anchor2);
        let axis = DVec2::from_angle(b1.angle).rotate(j.axis);
        let angle_row = Row {
            entries: vec![(j.body1, DVec2::ZERO, -1.0), (j.body2, DVec2::ZERO, 1.0)],
            target: 0.0,
        };
        match j.kind {
            JointKind::Revolute | JointKind::Fixed => {
                rows.push(point_row(s, j.body1, j.body2, p2, DVec2::X, 0.0));
                rows.push(point_row(s, j.body1, j.body2, p2, DVec2::Y, 0.0));
                if j.kind == JointKind::Fixed {
                    rows.push(angle_row);
                }
            }
            JointKind::Prismatic => {
                rows.push(point_row(s, j.body1, j.body2, p2, perp(axis), 0.0));
                rows.push(angle_row);
            }
            JointKind::PinSlot => rows.push(point_row(s, j.body1, j.body2, p2, perp(axis), 0.0)),
        }
        ranges.push((start, rows.len()));
    }
    for c in &snap.couplings {
        rows.push(Row {
            entries: c
                .terms
                .iter()
                .map(|&(b, coord, ratio)| match coord {
                    Coordinate::X => (b, DVec2::X * ratio, 0.0),
                    Coordinate::Y => (b, DVec2::Y * ratio, 0.0),
                    Coordinate::Angle => (b, DVec2::ZERO, ratio),
                })
                .collect(),
            target: 0.0,
        });
    }
    (rows, ranges)
}

/// The linear impulse a joint's rows gave body2, from their multipliers.
fn joint_impulse(
    ctx: &Ctx,
    s: &[BodyState],
    k: usize,
    range: (usize, usize),
    lambda: &[f64],
) -> DVec2 {
    let j = &ctx.joints[k];
    let l = &lambda[range.0..range.1];
    match j.kind {
        JointKind::Revolute | JointKind::Fixed => DVec2::new(l[0], l[1]),
        JointKind::Prismatic | JointKind::PinSlot => {
            perp(DVec2::from_angle(s[j.body1].angle).rotate(j.axis)) * l[0]
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Impacts and blows.

/// The first contact of a pair, carried back to the instant of touching, and (when the level's
/// coefficients are known) the impulse-momentum solution of the impact.
#[derive(Debug, Clone)]
struct Impact {
    /// Time of touching, s.
    t_c: f64,
    /// Every body's state at the touching instant (free bodies carried ballistically from the
    /// last step before contact; others at that step's state).
    pre: Vec<BodyState>,
    /// States right after the impact (None when the coefficients are unknown).
    post: Option<Vec<BodyState>>,
    /// Contact normal from body1 to body2 of the contact, and the two bodies.
    normal: DVec2,
    point: DVec2,
    i1: usize,
    i2: usize,
    /// Which bodies were free (carried ballistically).
    free: Vec<bool>,
}

/// Why a contact event's question has no impulse-momentum analysis.
const NO_IMPACT: &str = "no impact analysis: the bodies did not approach each other when the contact began (a contact from the start or one slid into, such as a ladder on its wall), so the answer is graded on the engine alone";

impl Impact {
    fn find(
        ctx: &Ctx,
        pre: &Snapshot,
        hit: &Snapshot,
        body: usize,
        other: Option<usize>,
    ) -> Option<Impact> {
        let c = hit
            .contacts
            .iter()
            .filter(|c| {
                (c.body1 == body && other.is_none_or(|o| c.body2 == o))
                    || (c.body2 == body && other.is_none_or(|o| c.body1 == o))
            })
            .max_by(|a, b| {
                let s = |c: &crate::snapshot::ContactState| {
                    c.points.iter().map(|p| p.normal_impulse).sum::<f64>()
                };
                s(a).total_cmp(&s(b))
            })?;
        let (i1, i2, n) = (c.body1, c.body2, c.normal);
        let w: f64 = c.points.iter().map(|p| p.normal_impulse.max(0.0)).sum();
        let count = c.points.len().max(1) as f64;
        let (p, d) = if w > 0.0 {
            (
                c.points
                    .iter()
                    .map(|q| q.point * q.normal_impulse.max(0.0))
                    .sum::<DVec2>()
                    / w,
                c.points
                    .iter()
                    .map(|q| q.distance * q.normal_impulse.max(0.0))
                    .sum::<f64>()
                    / w,
            )
        } else {
            (
                c.points.iter().map(|q| q.point).sum::<DVec2>() / count,
                c.points.iter().map(|q| q.distance).sum::<f64>() / count,
            )
        };
        // The material points that touch, found at the contact step and taken back to the step before.
        let l1 = to_local(&hit.bodies[i1], p);
        let l2 = to_local(&hit.bodies[i2], p + n * d);
        let (b1, b2) = (&pre.bodies[i1], &pre.bodies[i2]);
        let (q1, q2) = (b1.world_point(l1), b2.world_point(l2));
        let free: Vec<bool> = (0..pre.bodies.len()).map(|i| is_free(hit, i)).collect();
        let acc = |i: usize| if free[i] { pre.gravity } else { DVec2::ZERO };
        let discs = (
            ctx.bodies.get(i1).and_then(|x| x.disc),
            ctx.bodies.get(i2).and_then(|x| x.disc),
        );
        let (n, tau, disc_point) = match discs {
            // Two discs: the line of centers at touching, |d + w tau + a tau^2/2| = r1 + r2, instead of
            // the engine's speculative normal (taken up to a step before they touch).
            (Some(r1), Some(r2)) => {
                let (d0, w, a) = (
                    b2.com - b1.com,
                    b2.velocity - b1.velocity,
                    acc(i2) - acc(i1),
                );
                let mut t = 0.0;
                for _ in 0..30 {
                    let d = d0 + w * t + 0.5 * a * t * t;
                    let f = d.length() - (r1 + r2);
                    let df = d.normalize_or(DVec2::X).dot(w + a * t);
                    if df.abs() < 1e-15 {
                        break;
                    }
                    let step = f / df;
                    t -= step;
                    if step.abs() < 1e-15 {
                        break;
                    }
                }
                if !(t.is_finite() && t.abs() <= 2.0 * hit.dt) {
                    t = 0.0;
                }
                let nn = (d0 + w * t + 0.5 * a * t * t).normalize_or(n);
                if (w + a * t).dot(nn) >= 0.0 {
                    return None; // not approaching: no impact
                }
                let g1 = b1.com + b1.velocity * t + 0.5 * acc(i1) * t * t;
                (nn, t, Some(g1 + nn * r1))
            }
            _ => {
                let gap = (q2 - q1).dot(n);
                let v_n = (point_velocity(b2, q2) - point_velocity(b1, q1)).dot(n);
                let a_n = (acc(i2) - acc(i1)).dot(n);
                // Not approaching faster than gravity can close a gap in a step or two: a contact
                // that was there from the start or that the bodies slid into (a ladder on its wall,
                // a block set down), not an impact.
                if v_n >= -(2.0 * pre.gravity.length() * hit.dt + 1e-9) {
                    return None;
                }
                // gap + v_n tau + a_n tau^2 / 2 = 0 while approaching: the root nearest the last free
                // step, within three steps either way (negative when the engine let the bodies overlap
                // before the contact acted: the textbook impact is at the touching instant).
                let roots: Vec<f64> = if a_n.abs() < 1e-12 {
                    vec![-gap / v_n]
                } else {
                    let disc = v_n * v_n - 2.0 * a_n * gap;
                    if disc < 0.0 {
                        vec![]
                    } else {
                        let r = disc.sqrt();
                        vec![(-v_n - r) / a_n, (-v_n + r) / a_n]
                    }
                };
                let tau = roots
                    .into_iter()
                    .filter(|t| v_n + a_n * t < 0.0 && t.abs() <= 3.0 * hit.dt)
                    .min_by(|a, b| a.abs().total_cmp(&b.abs()))
                    .unwrap_or(0.0);
                (n, tau, None)
            }
        };
        let states: Vec<BodyState> = pre
            .bodies
            .iter()
            .enumerate()
            .map(|(i, b)| advance(b, tau, acc(i)))
            .collect();
        let point = disc_point.unwrap_or_else(|| states[i1].world_point(l1));
        let mut imp = Impact {
            t_c: pre.time + tau,
            pre: states,
            post: None,
            normal: n,
            point,
            i1,
            i2,
            free,
        };
        if ctx.known {
            let e = ctx.restitution(i1, i2);
            let mu = ctx.friction(i1, i2);
            let (mut rows, _) = constraint_rows(ctx, hit, &imp.pre);
            let mut normal = point_row(&imp.pre, i1, i2, point, n, 0.0);
            let approach = row_velocity(&normal, &imp.pre);
            normal.target = -e * approach;
            rows.push(normal);
            if mu > 0.0 {
                // A rough contact: the impact leaves no slip (RM-10: the plate pivots on the ledge).
                rows.push(point_row(&imp.pre, i1, i2, point, perp(n), 0.0));
            }
            imp.post = Some(solve_impulses(&imp.pre, &rows, &[]).0);
        }
        Some(imp)
    }
}

/// An impulse event and the impulse-momentum solution of the blow (RM-10).
#[derive(Debug, Clone)]
struct Blow {
    t0: f64,
    post: Vec<BodyState>,
    /// Linear impulse each level joint gave its body2 during the blow, N s.
    joint_impulse: Vec<DVec2>,
    free: Vec<bool>,
}

impl Blow {
    fn solve(ctx: &Ctx, pre: &Snapshot, hit: &Snapshot) -> Option<Blow> {
        if !ctx.known {
            return None;
        }
        let s = &pre.bodies;
        let ext: Vec<(usize, DVec2, f64)> = hit
            .impulses
            .iter()
            .map(|e| {
                (
                    e.body,
                    e.impulse,
                    cross(e.point - s[e.body].com, e.impulse) + e.angular_impulse,
                )
            })
            .collect();
        let (rows, ranges) = constraint_rows(ctx, hit, s);
        let (post, lambda) = solve_impulses(s, &rows, &ext);
        let joint_impulse = ranges
            .iter()
            .enumerate()
            .map(|(k, r)| joint_impulse(ctx, s, k, *r, &lambda))
            .collect();
        Some(Blow {
            t0: pre.time,
            post,
            joint_impulse,
            free: (0..s.len()).map(|i| is_free(hit, i)).collect(),
        })
    }

    fn post_at(&self, i: usize, t: f64, g: DVec2) -> BodyState {
        let a = if self.free[i] { g } else { DVec2::ZERO };
        advance(&self.post[i], (t - self.t0).max(0.0), a)
    }
}

/// The moments of a pair's first contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum PairEvent {
    /// This sample is the first with a contact force; the previous one is the pre-impact state.
    Touch,
    /// This sample is the first without a contact force after the first contact (not yet confirmed).
    Quiet,
    /// The contact force came back within the confirmation window: the last `Quiet` was a flicker.
    Resumed,
    /// The pair stayed without force for `QUIET_STEPS` samples: the contact ended at the `Quiet` sample.
    Released,
    /// This sample is the first of a second contact.
    Again,
}

/// How long a contact must stay without force before it counts as ended (at least `QUIET_STEPS`
/// samples and `QUIET_TIME` seconds): rapier's soft, speculative contact delivers a light contact
/// force in bursts, with quiet steps between them (a ladder sliding on a wall: gaps of up to 19 ms).
const QUIET_STEPS: u32 = 10;
const QUIET_TIME: f64 = 0.05;

/// Follows the contacts of one body with another (or with anything).
#[derive(Debug, Clone)]
struct PairTracker {
    body: String,
    other: Option<String>,
    ix: Option<(usize, Option<usize>)>,
    /// 0 before, 1 touching, 2 quiet (unconfirmed), 3 released, 4 touching again.
    phase: u8,
    quiet: u32,
    peak: f64,
    pre: Option<Snapshot>,
    hit: Option<Snapshot>,
    impact: Option<Impact>,
    release: Option<Snapshot>,
}

impl PairTracker {
    fn new(body: &str, other: Option<&str>) -> Self {
        PairTracker {
            body: body.to_string(),
            other: other.map(str::to_string),
            ix: None,
            phase: 0,
            quiet: 0,
            peak: 0.0,
            pre: None,
            hit: None,
            impact: None,
            release: None,
        }
    }

    fn update(&mut self, f: &Frame, ctx: &Ctx) -> Option<PairEvent> {
        if self.ix.is_none() {
            let b = body_ix(f.cur, &self.body)?;
            let o = match &self.other {
                Some(o) => Some(body_ix(f.cur, o)?),
                None => None,
            };
            self.ix = Some((b, o));
        }
        let (b, o) = self.ix?;
        let j = pair_normal_impulse(f.cur, b, o);
        // "Pushing": a normal impulse above a millionth of the largest one of this contact, so that
        // round-off and position correction between bodies left resting together do not count.
        let touching = j > 1e-6 * self.peak.max(f64::MIN_POSITIVE) && j > 0.0;
        match self.phase {
            0 if touching => {
                self.phase = 1;
                self.peak = j;
                self.pre = f.prev.cloned();
                self.hit = Some(f.cur.clone());
                if let Some(pre) = f.prev {
                    self.impact = Impact::find(ctx, pre, f.cur, b, o);
                }
                Some(PairEvent::Touch)
            }
            1 => {
                self.peak = self.peak.max(j);
                if touching {
                    None
                } else {
                    self.phase = 2;
                    self.quiet = 1;
                    self.release = Some(f.cur.clone());
                    Some(PairEvent::Quiet)
                }
            }
            2 => {
                if touching {
                    self.phase = 1;
                    self.peak = self.peak.max(j);
                    self.release = None;
                    Some(PairEvent::Resumed)
                } else {
                    self.quiet += 1;
                    let quiet_for =
                        f.cur.time - self.release.as_ref().map_or(f.cur.time, |r| r.time);
                    if self.quiet >= QUIET_STEPS && quiet_for >= QUIET_TIME {
                        self.phase = 3;
                        Some(PairEvent::Released)
                    } else {
                        None
                    }
                }
            }
            3 if touching => {
                self.phase = 4;
                Some(PairEvent::Again)
            }
            _ => None,
        }
    }

    /// The contact has ended (or is quiet and may be ending at the end of the run).
    fn ended(&self) -> bool {
        self.phase >= 2
    }
}

// ---------------------------------------------------------------------------------------------
// Reading a quantity.

#[derive(Debug, Clone, Copy, PartialEq)]
struct Reading {
    t: f64,
    engine: f64,
    analysis: Option<f64>,
}

fn lerp(a: Reading, b: Reading, f: f64) -> Reading {
    Reading {
        t: a.t + (b.t - a.t) * f,
        engine: a.engine + (b.engine - a.engine) * f,
        analysis: match (a.analysis, b.analysis) {
            (Some(x), Some(y)) => Some(x + (y - x) * f),
            _ => None,
        },
    }
}

/// The circumstance of a reading, for velocity analyses.
#[derive(Clone, Copy)]
enum Occasion<'a> {
    Plain,
    PreImpact(&'a Impact),
    PostImpact(&'a Impact),
    AfterBlow(&'a Blow),
}

/// Crossings of a signal through zero, by direction, at interpolated times.
#[derive(Debug, Clone, Default)]
struct Crossings {
    last: Option<(f64, f64)>,
    down: Vec<f64>,
    up: Vec<f64>,
}

impl Crossings {
    fn add(&mut self, t: f64, x: f64) {
        if let Some((t0, x0)) = self.last {
            if x0 > 0.0 && x <= 0.0 && x0 != x {
                self.down.push(t0 + (t - t0) * x0 / (x0 - x));
            } else if x0 < 0.0 && x >= 0.0 && x0 != x {
                self.up.push(t0 + (t - t0) * x0 / (x0 - x));
            }
        }
        self.last = Some((t, x));
    }

    /// Mean interval between successive crossings of the same direction: the period.
    fn period(&self) -> f64 {
        let diffs: Vec<f64> = [&self.down, &self.up]
            .iter()
            .flat_map(|v| v.windows(2).map(|w| w[1] - w[0]))
            .collect();
        if diffs.is_empty() {
            f64::NAN
        } else {
            diffs.iter().sum::<f64>() / diffs.len() as f64
        }
    }
}

/// Evaluates one quantity at every sample, keeping whatever it accumulates over the run.
#[derive(Clone)]
struct Meter {
    q: Quantity,
    ctx: Arc<Ctx>,
    init: Option<Snapshot>,
    /// Accumulated engine value (works, distance).
    acc: f64,
    /// Accumulated path work of springs and loads on the body (for the work-energy analysis).
    acc_path: f64,
    crossings: Crossings,
    /// Direction of the spring a `SpringPeriod` body oscillates along.
    axis: Option<DVec2>,
    pair: Option<PairTracker>,
    /// Running maximum (rebound height) and whether it is closed.
    peak: f64,
    /// Constant-load bookkeeping for `LoadWork`: the first load seen and whether it stayed equal.
    load0: Option<(DVec2, f64, DVec2, f64)>,
    load_constant: bool,
    /// Read at a configuration event (not a fixed time): see `Quantity::KineticEnergy`.
    configuration_event: bool,
}

impl Meter {
    fn new(q: &Quantity, ctx: Arc<Ctx>) -> Self {
        let pair = match q {
            Quantity::ReboundHeight { body, other }
            | Quantity::Restitution { body, other }
            | Quantity::EnergyLost { body, other } => Some(PairTracker::new(body, Some(other))),
            _ => None,
        };
        Meter {
            q: q.clone(),
            ctx,
            init: None,
            acc: 0.0,
            acc_path: 0.0,
            crossings: Crossings::default(),
            axis: None,
            pair,
            peak: f64::NEG_INFINITY,
            load0: None,
            load_constant: true,
            configuration_event: true,
        }
    }

    /// Accumulates what the quantity needs from the step that led to the sample.
    fn advance(&mut self, f: &Frame) {
        let s = f.cur;
        if self.init.is_none() {
            self.init = Some(s.clone());
        }
        let pair_event = match &mut self.pair {
            Some(p) => p.update(f, &self.ctx),
            None => None,
        };
        let Some(prev) = f.prev else {
            return;
        };
        let dt = s.time - prev.time;
        match &self.q {
            Quantity::Distance(b) => {
                if let Some(i) = body_ix(s, b) {
                    self.acc += (s.bodies[i].com - prev.bodies[i].com).length();
                }
            }
            Quantity::GravityWork(b) => {
                if let Some(i) = body_ix(s, b) {
                    let (b0, b1) = (&prev.bodies[i], &s.bodies[i]);
                    self.acc += b1.mass * s.gravity.dot(0.5 * (b0.velocity + b1.velocity)) * dt;
                }
            }
            Quantity::SpringWork(name) => {
                if let Some(sp) = s.springs.iter().find(|x| &x.name == name) {
                    self.acc +=
                        held_work(prev, s, sp.body1, sp.force_on_body1, sp.applied_at1, 0.0);
                    if let Some(b2) = sp.body2 {
                        self.acc += held_work(prev, s, b2, -sp.force_on_body1, sp.applied_at2, 0.0);
                    }
                }
            }
            Quantity::LoadWork(name) => {
                if let Some(l) = s.loads.iter().find(|l| &l.name == name) {
                    let b0 = &prev.bodies[l.body];
                    self.acc += held_work(prev, s, l.body, l.force, l.point, l.torque);
                    match self.load0 {
                        None => self.load0 = Some((l.force, l.torque, l.point, b0.angle)),
                        Some((f0, m0, _, _)) => {
                            if (l.force - f0).length() > 1e-12 * f0.length().max(1.0)
                                || (l.torque - m0).abs() > 1e-12 * m0.abs().max(1.0)
                            {
                                self.load_constant = false;
                            }
                        }
                    }
                }
            }
            Quantity::FrictionWork { body, other } => {
                if let (Some(i), Some(o)) = (body_ix(s, body), body_ix(s, other)) {
                    let mu = self.ctx.friction(i, o);
                    let mid = |k: usize| {
                        let mut m = s.bodies[k].clone();
                        m.velocity = 0.5 * (prev.bodies[k].velocity + s.bodies[k].velocity);
                        m.omega = 0.5 * (prev.bodies[k].omega + s.bodies[k].omega);
                        m
                    };
                    let (bi, bo) = (mid(i), mid(o));
                    for c in &s.contacts {
                        let sign = if c.body2 == i && c.body1 == o {
                            1.0
                        } else if c.body1 == i && c.body2 == o {
                            -1.0
                        } else {
                            continue;
                        };
                        let t = c.tangent();
                        for p in &c.points {
                            let slip = (point_velocity(&bi, p.point)
                                - point_velocity(&bo, p.point))
                            .dot(t);
                            self.acc +=
                                sign * p.tangent_impulse * point_velocity(&bi, p.point).dot(t);
                            self.acc_path -= mu * p.normal_impulse.max(0.0) * slip.abs();
                        }
                    }
                }
            }
            Quantity::KineticEnergy(b) => {
                if let Some(i) = body_ix(s, b) {
                    // Ground springs enter the analysis through their exact potential instead.
                    self.acc_path += path_work(prev, s, i, false);
                }
            }
            Quantity::JointReaction { joint: j, .. } => {
                if let Some(k) = joint_ix(s, j) {
                    let jj = &s.joints[k];
                    let i = if is_massive(&s.bodies[jj.body2]) {
                        jj.body2
                    } else {
                        jj.body1
                    };
                    self.acc_path += path_work(prev, s, i, true);
                }
            }
            Quantity::PendulumPeriod { body, .. } => {
                if let Some(i) = body_ix(s, body) {
                    if self.crossings.last.is_none() {
                        self.crossings.add(prev.time, prev.bodies[i].omega);
                    }
                    self.crossings.add(s.time, s.bodies[i].omega);
                }
            }
            Quantity::SpringPeriod(body) => {
                if let Some(i) = body_ix(s, body) {
                    if self.axis.is_none() {
                        let init = self.init.as_ref().unwrap_or(prev);
                        let sp = init
                            .springs
                            .iter()
                            .find(|x| x.body1 == i || x.body2 == Some(i));
                        self.axis = sp.map(|x| (x.point2 - x.point1).normalize_or(DVec2::X));
                        if let Some(a) = self.axis {
                            self.crossings
                                .add(prev.time, prev.bodies[i].velocity.dot(a));
                        }
                    }
                    if let Some(a) = self.axis {
                        self.crossings.add(s.time, s.bodies[i].velocity.dot(a));
                    }
                }
            }
            Quantity::ReboundHeight { body, .. } => {
                if let Some(i) = body_ix(s, body) {
                    let phase = self.pair.as_ref().map_or(0, |p| p.phase);
                    if pair_event == Some(PairEvent::Resumed) {
                        self.peak = f64::NEG_INFINITY;
                    }
                    if phase == 2 || phase == 3 {
                        self.peak = self.peak.max(height(s.gravity, s.bodies[i].com));
                    }
                }
            }
            _ => {}
        }
    }

    /// The quantity at the sample.
    fn read(&self, f: &Frame, occ: Occasion) -> Reading {
        let (engine, analysis) = self.value(f, occ).unwrap_or((f64::NAN, None));
        Reading {
            t: f.cur.time,
            engine,
            analysis: analysis.filter(|a| a.is_finite()),
        }
    }

    fn value(&self, f: &Frame, occ: Occasion) -> Option<(f64, Option<f64>)> {
        let s = f.cur;
        let ctx = &*self.ctx;
        let body = |name: &str| body_ix(s, name).map(|i| (i, &s.bodies[i]));
        // The state an impact or blow solution gives body i at this sample (velocity analyses).
        let solved = |i: usize| -> Option<BodyState> {
            match occ {
                Occasion::Plain => None,
                Occasion::PreImpact(imp) => Some(imp.pre[i].clone()),
                // The textbook's "just after the impact": the solution at the touching instant.
                Occasion::PostImpact(imp) => imp.post.as_ref().map(|p| p[i].clone()),
                Occasion::AfterBlow(b) => Some(b.post_at(i, s.time, s.gravity)),
            }
        };
        let init = self.init.as_ref();
        Some(match &self.q {
            Quantity::X(b) => (body(b)?.1.com.x, None),
            Quantity::Y(b) => (body(b)?.1.com.y, None),
            Quantity::Angle(b) => (body(b)?.1.angle, None),
            Quantity::Vx(b) => {
                let (i, x) = body(b)?;
                (x.velocity.x, solved(i).map(|y| y.velocity.x))
            }
            Quantity::Vy(b) => {
                let (i, x) = body(b)?;
                (x.velocity.y, solved(i).map(|y| y.velocity.y))
            }
            Quantity::Speed(b) => {
                let (i, x) = body(b)?;
                (x.velocity.length(), solved(i).map(|y| y.velocity.length()))
            }
            Quantity::Omega(b) => {
                let (i, x) = body(b)?;
                (x.omega, solved(i).map(|y| y.omega))
            }
            Quantity::Direction(b) => {
                let (i, x) = body(b)?;
                let dir = |v: DVec2| v.y.atan2(v.x);
                (dir(x.velocity), solved(i).map(|y| dir(y.velocity)))
            }
            Quantity::KineticEnergy(b) => {
                let (i, x) = body(b)?;
                let analysis = init.map(|s0| {
                    let b0 = &s0.bodies[i];
                    let springs: f64 = s
                        .springs
                        .iter()
                        .zip(&s0.springs)
                        .filter(|(sp, _)| sp.body2.is_none() && sp.body1 == i)
                        .map(|(sp, sp0)| sp0.energy - sp.energy)
                        .sum();
                    kinetic_energy(b0)
                        + x.mass * s.gravity.dot(x.com - b0.com)
                        + springs
                        + self.acc_path
                });
                let analysis = match occ {
                    Occasion::Plain => analysis.filter(|_| self.configuration_event),
                    _ => solved(i).map(|y| kinetic_energy(&y)),
                };
                (kinetic_energy(x), analysis)
            }
            Quantity::JointForce(j) => {
                let k = joint_ix(s, j)?;
                if s.dt <= 0.0 {
                    return None;
                }
                (s.joints[k].impulse_on_body2.length() / s.dt, None)
            }
            Quantity::JointReaction {
                joint, component, ..
            } => {
                // The initial snapshot has no joint states yet: take the joint from the first step.
                let js = if s.joints.is_empty() {
                    f.next.unwrap_or(s)
                } else {
                    s
                };
                let k = joint_ix(js, joint)?;
                let j = &js.joints[k];
                let moving_is_2 = is_massive(&s.bodies[j.body2]);
                let on_moving = f.windowed(|x| {
                    let jj = x.joints.get(k)?;
                    Some(if moving_is_2 {
                        jj.impulse_on_body2
                    } else {
                        -jj.impulse_on_body2
                    })
                })?;
                let (mb, anchor) = if moving_is_2 {
                    (j.body2, j.anchor1)
                } else {
                    (j.body1, j.anchor)
                };
                let comp = |r: DVec2| component_of(*component, r, s.bodies[mb].com, anchor);
                (comp(on_moving), self.pivot_reaction(f, k).map(comp))
            }
            Quantity::JointImpulse { joint, component } => {
                let k = joint_ix(s, joint)?;
                let j = &s.joints[k];
                let moving_is_2 = is_massive(&s.bodies[j.body2]);
                let sign = if moving_is_2 { 1.0 } else { -1.0 };
                let (mb, anchor) = if moving_is_2 {
                    (j.body2, j.anchor1)
                } else {
                    (j.body1, j.anchor)
                };
                let comp = |r: DVec2| component_of(*component, r, s.bodies[mb].com, anchor);
                let analysis = match occ {
                    Occasion::AfterBlow(b) => {
                        // The level's joints are in level order, as the snapshot's are.
                        b.joint_impulse.get(k).map(|x| comp(*x * sign))
                    }
                    _ => None,
                };
                // rapier reports a joint's reaction as its last substep's impulse times the substep
                // count, which misses a blow the joint absorbs in the first substep: the engine's value
                // is the impulse-momentum balance of the bodies on the joint's moving side instead.
                let engine = match f.prev {
                    Some(prev) => side_impulse(prev, s, k, mb),
                    None => j.impulse_on_body2 * sign,
                };
                (comp(engine), analysis)
            }
            Quantity::ContactForce(b) => {
                let i = body_ix(s, b)?;
                if s.dt <= 0.0 {
                    return None;
                }
                let total: DVec2 = s
                    .contacts
                    .iter()
                    .map(|c| {
                        if c.body2 == i {
                            c.impulse_on_body2()
                        } else if c.body1 == i {
                            -c.impulse_on_body2()
                        } else {
                            DVec2::ZERO
                        }
                    })
                    .sum();
                (total.length() / s.dt, None)
            }
            Quantity::ContactNormalForce { body: b, other } => {
                let (i, o) = (body_ix(s, b)?, body_ix(s, other)?);
                let n =
                    f.centered(|x| Some(DVec2::new(pair_normal_impulse(x, i, Some(o)), 0.0)))?;
                (n.x, None)
            }
            Quantity::Distance(_) => (self.acc, None),
            Quantity::Time => (s.time, None),
            Quantity::Ax(b) | Quantity::Ay(b) | Quantity::Accel(b) => {
                let i = body_ix(s, b)?;
                let ax = f.rate(|x| Some(x.bodies[i].velocity.x))?;
                let ay = f.rate(|x| Some(x.bodies[i].velocity.y))?;
                let newton = self.newton(f, i).map(|(a, _)| a);
                let pick = |a: DVec2| match &self.q {
                    Quantity::Ax(_) => a.x,
                    Quantity::Ay(_) => a.y,
                    _ => a.length(),
                };
                (pick(DVec2::new(ax, ay)), newton.map(pick))
            }
            Quantity::Alpha(b) => {
                let i = body_ix(s, b)?;
                let alpha = f.rate(|x| Some(x.bodies[i].omega))?;
                (alpha, self.newton(f, i).map(|(_, al)| al))
            }
            Quantity::PointX { body: b, point } => {
                (body(b)?.1.world_point(DVec2::new(point.0, point.1)).x, None)
            }
            Quantity::PointSpeed { body: b, point } => {
                let (i, x) = body(b)?;
                let local = DVec2::new(point.0, point.1);
                let speed = |y: &BodyState| point_velocity(y, y.world_point(local)).length();
                (speed(x), solved(i).map(|y| speed(&y)))
            }
            Quantity::PointAccel { body: b, point } => {
                let (i, x) = body(b)?;
                let local = DVec2::new(point.0, point.1);
                // The material point's velocity in each snapshot, differenced.
                let vp = |y: &Snapshot| {
                    let b = &y.bodies[i];
                    point_velocity(b, b.world_point(local))
                };
                let ax = f.rate(|y| Some(vp(y).x))?;
                let ay = f.rate(|y| Some(vp(y).y))?;
                let analysis = self.newton(f, i).map(|(a_g, alpha)| {
                    let r = x.world_point(local) - x.com;
                    (a_g + perp(r) * alpha - r * x.omega * x.omega).length()
                });
                (DVec2::new(ax, ay).length(), analysis)
            }
            Quantity::CouplingForce(name) => {
                let k = s
                    .couplings
                    .iter()
                    .position(|c| &c.name == name)
                    .or_else(|| {
                        f.next
                            .and_then(|n| n.couplings.iter().position(|c| &c.name == name))
                    })?;
                let force = f.centered(|y| Some(DVec2::new(y.couplings.get(k)?.impulse, 0.0)))?;
                (force.x, None)
            }
            Quantity::PointY { body: b, point } => {
                (body(b)?.1.world_point(DVec2::new(point.0, point.1)).y, None)
            }
            Quantity::RelativeDistance(a, b) => ((body(b)?.1.com - body(a)?.1.com).length(), None),
            Quantity::RelativeSpeed(a, b) => {
                ((body(b)?.1.velocity - body(a)?.1.velocity).length(), None)
            }
            Quantity::RelativeAngle(a, b) => (body(b)?.1.angle - body(a)?.1.angle, None),
            Quantity::GravityWork(b) => {
                let (i, x) = body(b)?;
                let g0 = init?.bodies[i].com;
                (self.acc, Some(x.mass * s.gravity.dot(x.com - g0)))
            }
            Quantity::SpringWork(name) => {
                let sp = s.springs.iter().find(|x| &x.name == name)?;
                let sp0 = init?.springs.iter().find(|x| &x.name == name)?;
                (self.acc, Some(sp0.energy - sp.energy))
            }
            Quantity::SpringExtension(name) => {
                (s.springs.iter().find(|x| &x.name == name)?.extension, None)
            }
            Quantity::LoadWork(name) => {
                let analysis = match (self.load0, self.load_constant) {
                    (Some((force, torque, p0, a0)), true) => {
                        let l = s.loads.iter().find(|l| &l.name == name)?;
                        let b0 = &init?.bodies[l.body];
                        let b = &s.bodies[l.body];
                        let p = b.world_point(to_local(b0, p0));
                        Some(force.dot(p - p0) + torque * (b.angle - a0))
                    }
                    _ => None,
                };
                (self.acc, analysis)
            }
            Quantity::LoadPower(name) => {
                let l = s.loads.iter().find(|l| &l.name == name)?;
                let b = &s.bodies[l.body];
                // The load's point as it is at the sample: l.point is where it was at the step's start.
                let p = b.world_point(to_local(&f.prev?.bodies[l.body], l.point));
                let v_p = b.velocity + b.omega * (p - b.com).perp();
                (l.force.dot(v_p) + l.torque * b.omega, None)
            }
            Quantity::FrictionWork { .. } => (self.acc, ctx.known.then_some(self.acc_path)),
            Quantity::PendulumPeriod { body: b, joint } => {
                (self.crossings.period(), self.pendulum_theory(s, b, joint))
            }
            Quantity::SpringPeriod(b) => {
                let i = body_ix(s, b)?;
                let k: f64 = init?
                    .springs
                    .iter()
                    .chain(&s.springs)
                    .filter(|x| (x.body1 == i || x.body2 == Some(i)) && x.extension.abs() > 1e-9)
                    .map(|x| (x.name.clone(), 2.0 * x.energy / (x.extension * x.extension)))
                    .fold(Vec::<(String, f64)>::new(), |mut v, (n, k)| {
                        if !v.iter().any(|(m, _)| *m == n) {
                            v.push((n, k));
                        }
                        v
                    })
                    .iter()
                    .map(|(_, k)| k)
                    .sum();
                let m = s.bodies[i].mass;
                (
                    self.crossings.period(),
                    (k > 0.0).then(|| 2.0 * PI * (m / k).sqrt()),
                )
            }
            Quantity::RollingAcceleration { body: b, ground }
            | Quantity::RollingFriction { body: b, ground }
            | Quantity::RollingFrictionNeeded { body: b, ground } => {
                let (i, o) = (body_ix(s, b)?, body_ix(s, ground)?);
                let roll = rolling_geometry(f, i, o)?;
                let x = &s.bodies[i];
                let g = s.gravity.length();
                let k = (x.inertia / x.mass).sqrt();
                match &self.q {
                    Quantity::RollingAcceleration { .. } => {
                        let ax = f.rate(|y| Some(y.bodies[i].velocity.x))?;
                        let ay = f.rate(|y| Some(y.bodies[i].velocity.y))?;
                        (
                            DVec2::new(ax, ay).dot(roll.downhill),
                            Some(rolling_acceleration(g, roll.theta, k, roll.r)),
                        )
                    }
                    Quantity::RollingFriction { .. } => (
                        roll.friction.abs(),
                        Some(rolling_friction(x.mass, g, roll.theta, k, roll.r)),
                    ),
                    _ => (
                        roll.friction.abs() / roll.normal,
                        Some(roll.theta.tan() * k * k / (k * k + roll.r * roll.r)),
                    ),
                }
            }
            Quantity::LinkOmega { link, known, other } => {
                let (_, l) = body(link)?;
                let ic = self.link_center(s, link, known, other);
                (l.omega, ic.map(|(w, _)| w))
            }
            Quantity::PinSpeed {
                link,
                known,
                other,
                pin,
            } => {
                let (li, l) = body(link)?;
                let k = joint_ix(s, pin)?;
                let j = &s.joints[k];
                let p = if j.body2 == li { j.anchor } else { j.anchor1 };
                let ic = self.link_center(s, link, known, other);
                (
                    point_velocity(l, p).length(),
                    ic.map(|(w, c)| (w * (p - c).length()).abs()),
                )
            }
            Quantity::MotorTorque { joint: j, .. } => {
                let k = joint_ix(s, j)?;
                let torque =
                    f.windowed(|x| Some(DVec2::new(x.joints.get(k)?.motor_impulse, 0.0)))?;
                // Over a window, the power balance is averaged over the same samples.
                let analysis = if f.window.len() > 2 {
                    let w = f.window;
                    let vals: Vec<f64> = (1..w.len() - 1)
                        .filter_map(|i| {
                            let g = Frame {
                                prev: Some(&w[i - 1]),
                                cur: &w[i],
                                next: Some(&w[i + 1]),
                                window: std::slice::from_ref(&w[i]),
                            };
                            self.power_balance(&g, k)
                        })
                        .collect();
                    (!vals.is_empty()).then(|| vals.iter().sum::<f64>() / vals.len() as f64)
                } else {
                    self.power_balance(f, k)
                };
                (torque.x, analysis)
            }
            Quantity::ReboundHeight { body: b, .. } => {
                let i = body_ix(s, b)?;
                let p = self.pair.as_ref()?;
                let engine = if p.ended() { self.peak } else { f64::NAN };
                let analysis = p.impact.as_ref().and_then(|imp| {
                    let post = &imp.post.as_ref()?[i];
                    let g = s.gravity.length();
                    let up = if g > 0.0 {
                        -post.velocity.dot(s.gravity / g)
                    } else {
                        0.0
                    };
                    Some(height(s.gravity, post.com) + up.max(0.0).powi(2) / (2.0 * g))
                });
                (engine, analysis)
            }
            Quantity::Restitution { .. } => {
                let p = self.pair.as_ref()?;
                let imp = p.impact.as_ref()?;
                let (pre, post) = (p.pre.as_ref()?, p.release.as_ref()?);
                let at = |snap: &Snapshot, i: usize| {
                    let a = if imp.free[i] {
                        snap.gravity
                    } else {
                        DVec2::ZERO
                    };
                    advance(&snap.bodies[i], imp.t_c - snap.time, a)
                };
                let rel = |snap: &Snapshot| {
                    let (b1, b2) = (at(snap, imp.i1), at(snap, imp.i2));
                    (point_velocity(&b2, imp.point) - point_velocity(&b1, imp.point))
                        .dot(imp.normal)
                };
                let e = -rel(post) / rel(pre);
                (e, ctx.known.then(|| ctx.restitution(imp.i1, imp.i2)))
            }
            Quantity::EnergyLost { body: b, other } => {
                let (i, o) = (body_ix(s, b)?, body_ix(s, other)?);
                let p = self.pair.as_ref()?;
                let (pre, post) = (p.pre.as_ref()?, p.release.as_ref()?);
                let e = |snap: &Snapshot| {
                    [i, o]
                        .iter()
                        .filter(|&&k| is_massive(&snap.bodies[k]))
                        .map(|&k| mechanical_energy(snap.gravity, &snap.bodies[k]))
                        .sum::<f64>()
                };
                let analysis = p.impact.as_ref().and_then(|imp| {
                    let post = imp.post.as_ref()?;
                    Some(
                        [i, o]
                            .iter()
                            .map(|&k| kinetic_energy(&imp.pre[k]) - kinetic_energy(&post[k]))
                            .sum::<f64>(),
                    )
                });
                (e(pre) - e(post), analysis)
            }
        })
    }

    /// Newton-Euler from the engine's free-body diagram, centered on the sample:
    /// (sum F / m, sum M_G / I_G) over the two steps around it (6/1).
    fn newton(&self, f: &Frame, i: usize) -> Option<(DVec2, f64)> {
        let mut pairs = Vec::new();
        if let Some(p) = f.prev {
            pairs.push((p, f.cur));
        }
        if let Some(n) = f.next {
            pairs.push((f.cur, n));
        }
        let (mut j, mut m, mut t) = (DVec2::ZERO, 0.0, 0.0);
        for (a, b) in pairs {
            if b.dt <= 0.0 {
                continue;
            }
            let (jj, mm) = external_impulse(a, b, i);
            j += jj;
            m += mm;
            t += b.dt;
        }
        let body = &f.cur.bodies[i];
        if t <= 0.0 || body.mass <= 0.0 {
            return None;
        }
        let alpha = if body.inertia > 0.0 {
            m / (body.inertia * t)
        } else {
            0.0
        };
        Some((j / (body.mass * t), alpha))
    }

    /// Fixed-axis rotation (PL-8, PL-12): the pivot reaction on the moving body, R = m a_G - sum F,
    /// with alpha = sum M_O / I_O and a_G = alpha k x r - omega^2 r; omega from work-energy
    /// (omega^2 = omega0^2 + 2 U / I_O with the work of gravity, loads and springs), its sign the
    /// engine's. Applies when one side of a revolute joint is fixed and the moving body has no
    /// other joint or contact.
    fn pivot_reaction(&self, f: &Frame, k: usize) -> Option<DVec2> {
        let s = f.cur;
        let js = if s.joints.is_empty() {
            f.next.unwrap_or(s)
        } else {
            s
        };
        let j = js.joints.get(k)?;
        if self.ctx.known
            && self
                .ctx
                .joints
                .get(k)
                .is_some_and(|x| x.kind != JointKind::Revolute)
        {
            return None;
        }
        let (mb, o) = if is_massive(&s.bodies[j.body2]) && !is_massive(&s.bodies[j.body1]) {
            (j.body2, j.anchor1)
        } else if is_massive(&s.bodies[j.body1]) && !is_massive(&s.bodies[j.body2]) {
            (j.body1, j.anchor)
        } else {
            return None;
        };
        let alone = js
            .joints
            .iter()
            .filter(|x| x.body1 == mb || x.body2 == mb)
            .count()
            == 1
            && !s.contacts.iter().any(|c| c.body1 == mb || c.body2 == mb)
            && !s
                .couplings
                .iter()
                .any(|c| c.terms.iter().any(|t| t.0 == mb));
        if !alone {
            return None;
        }
        let b = &s.bodies[mb];
        let r = b.com - o;
        let i_o = b.inertia + b.mass * r.length_squared();
        if i_o <= 0.0 {
            return None;
        }
        // Applied forces held around the sample (centered), their moments about O.
        let (mut force, mut moment) = (b.mass * s.gravity, cross(r, b.mass * s.gravity));
        let mut count = 0.0;
        let (mut fl, mut ml) = (DVec2::ZERO, 0.0);
        for x in f.steps() {
            for l in x.loads.iter().filter(|l| l.body == mb) {
                fl += l.force;
                ml += cross(l.point - o, l.force) + l.torque;
            }
            for sp in &x.springs {
                if sp.body1 == mb {
                    fl += sp.force_on_body1;
                    ml += cross(sp.applied_at1 - o, sp.force_on_body1);
                } else if sp.body2 == Some(mb) {
                    fl -= sp.force_on_body1;
                    ml += cross(sp.applied_at2 - o, -sp.force_on_body1);
                }
            }
            count += 1.0;
        }
        if count > 0.0 {
            force += fl / count;
            moment += ml / count;
        }
        let alpha = moment / i_o;
        // omega from work-energy: gravity's work is m g . (G - G0); loads' and springs' along the path.
        let init = self.init.as_ref()?;
        let b0 = &init.bodies[mb];
        let work = b.mass * s.gravity.dot(b.com - b0.com) + self.acc_path;
        let w2 = b0.omega * b0.omega + 2.0 * work / i_o;
        let omega = w2.max(0.0).sqrt() * if b.omega < 0.0 { -1.0 } else { 1.0 };
        let a_g = perp(r) * alpha - r * omega * omega;
        Some(b.mass * a_g - force)
    }

    /// The exact large-amplitude period of a body swinging about the joint's fixed anchor,
    /// from the engine's initial state.
    fn pendulum_theory(&self, s: &Snapshot, body: &str, joint: &str) -> Option<f64> {
        let i = body_ix(s, body)?;
        let j = &s.joints[joint_ix(s, joint)?];
        let o = if j.body2 == i { j.anchor1 } else { j.anchor };
        let b0 = &self.init.as_ref()?.bodies[i];
        let g = s.gravity.length();
        let r = b0.com - o;
        let d = r.length();
        if g <= 0.0 || d <= 0.0 {
            return None;
        }
        let i_o = b0.inertia + b0.mass * d * d;
        let cos_phi = r.dot(s.gravity / g) / d;
        let one_minus_cos = (1.0 - cos_phi) + i_o * b0.omega * b0.omega / (2.0 * b0.mass * g * d);
        if one_minus_cos >= 2.0 {
            return None;
        }
        let theta0 = (1.0 - one_minus_cos).clamp(-1.0, 1.0).acos();
        Some(pendulum_period(i_o, b0.mass, g, d, theta0))
    }

    /// The instantaneous center of a link from its two pins' velocities as points of the
    /// neighbouring bodies: (omega, C).
    fn link_center(
        &self,
        s: &Snapshot,
        link: &str,
        known: &str,
        other: &str,
    ) -> Option<(f64, DVec2)> {
        let li = body_ix(s, link)?;
        let pin = |name: &str| -> Option<(DVec2, DVec2)> {
            let j = &s.joints[joint_ix(s, name)?];
            let (nb, p) = if j.body1 == li {
                (j.body2, j.anchor)
            } else {
                (j.body1, j.anchor1)
            };
            let b = &s.bodies[nb];
            let v = if b.kind == BodyKind::Fixed {
                DVec2::ZERO
            } else {
                point_velocity(b, p)
            };
            Some((p, v))
        };
        let (p, vp) = pin(known)?;
        let (q, vq) = pin(other)?;
        match instant_center(p, vp, q, vq) {
            Some(c) => Some((omega_about_center(p, vp, c), c)),
            None => Some((0.0, p + perp(vp) * 1e12)),
        }
    }

    /// The one-degree-of-freedom power balance (RE-11): the motor's torque (force) times the
    /// joint rate equals the rate of change of kinetic energy of every dynamic body minus the
    /// power of gravity, loads and springs, all from the engine's state at the sample.
    fn power_balance(&self, f: &Frame, k: usize) -> Option<f64> {
        let s = f.cur;
        let j = &s.joints[k];
        let (b1, b2) = (&s.bodies[j.body1], &s.bodies[j.body2]);
        let kind = self
            .ctx
            .joints
            .get(k)
            .map_or(JointKind::Revolute, |x| x.kind);
        let rate = match kind {
            JointKind::Prismatic => {
                let axis = self
                    .ctx
                    .joints
                    .get(k)
                    .map_or(DVec2::X, |x| DVec2::from_angle(b1.angle).rotate(x.axis));
                (point_velocity(b2, j.anchor) - point_velocity(b1, j.anchor)).dot(axis)
            }
            _ => b2.omega - b1.omega,
        };
        if rate.abs() < 1e-9 {
            return None;
        }
        let mut dtdt = 0.0;
        let mut applied = 0.0;
        for (i, b) in s.bodies.iter().enumerate() {
            if !is_massive(b) {
                continue;
            }
            let ax = f.rate(|x| Some(x.bodies[i].velocity.x))?;
            let ay = f.rate(|x| Some(x.bodies[i].velocity.y))?;
            let alpha = f.rate(|x| Some(x.bodies[i].omega))?;
            dtdt += b.mass * DVec2::new(ax, ay).dot(b.velocity) + b.inertia * alpha * b.omega;
            applied += b.mass * s.gravity.dot(b.velocity);
        }
        let mut n = 0.0;
        let mut p_held = 0.0;
        for x in f.steps() {
            for l in &x.loads {
                let b = &s.bodies[l.body];
                let p = b.world_point(to_local(&x.bodies[l.body], l.point));
                p_held += l.force.dot(point_velocity(b, p)) + l.torque * b.omega;
            }
            for sp in &x.springs {
                p_held += sp
                    .force_on_body1
                    .dot(point_velocity(&s.bodies[sp.body1], sp.point1));
                if let Some(b2) = sp.body2 {
                    p_held -= sp
                        .force_on_body1
                        .dot(point_velocity(&s.bodies[b2], sp.point2));
                }
            }
            n += 1.0;
        }
        if n > 0.0 {
            applied += p_held / n;
        }
        Some((dtdt - applied) / rate)
    }
}

/// The external impulse on body i over the step from `a` to `b` and its angular impulse about G
/// (the free-body diagram of PL-1): gravity, loads, springs, event impulses, contacts, joints.
fn external_impulse(a: &Snapshot, b: &Snapshot, i: usize) -> (DVec2, f64) {
    let dt = b.dt;
    let body = &b.bodies[i];
    let g = 0.5 * (a.bodies[i].com + body.com);
    let mut j = body.mass * b.gravity * dt;
    let mut m = 0.0;
    for l in b.loads.iter().filter(|l| l.body == i) {
        j += l.force * dt;
        m += (cross(l.point - a.bodies[i].com, l.force) + l.torque) * dt;
    }
    for sp in &b.springs {
        if sp.body1 == i {
            j += sp.force_on_body1 * dt;
            m += cross(sp.applied_at1 - a.bodies[i].com, sp.force_on_body1) * dt;
        } else if sp.body2 == Some(i) {
            j -= sp.force_on_body1 * dt;
            m -= cross(sp.applied_at2 - a.bodies[i].com, sp.force_on_body1) * dt;
        }
    }
    for e in b.impulses.iter().filter(|e| e.body == i) {
        j += e.impulse;
        m += cross(e.point - a.bodies[i].com, e.impulse) + e.angular_impulse;
    }
    for c in &b.contacts {
        let sign = if c.body2 == i {
            1.0
        } else if c.body1 == i {
            -1.0
        } else {
            continue;
        };
        let t = c.tangent();
        for p in &c.points {
            let imp = (c.normal * p.normal_impulse + t * p.tangent_impulse) * sign;
            j += imp;
            m += cross(p.point - g, imp);
        }
    }
    for jt in &b.joints {
        if jt.body2 == i {
            j += jt.impulse_on_body2;
            m += jt.angular_impulse_on_body2;
        } else if jt.body1 == i {
            j -= jt.impulse_on_body2;
            m += jt.angular_impulse_on_body1;
        }
    }
    // A coupling gives each of its terms ratio x lambda along that coordinate (about G for angles).
    for c in &b.couplings {
        for &(body, coord, ratio) in c.terms.iter().filter(|t| t.0 == i) {
            let _ = body;
            match coord {
                Coordinate::X => j.x += ratio * c.impulse,
                Coordinate::Y => j.y += ratio * c.impulse,
                Coordinate::Angle => m += ratio * c.impulse,
            }
        }
    }
    (j, m)
}

/// The impulse joint k gave the bodies on its `moving` side over the step from `prev` to `s`:
/// their momentum change minus every other external impulse on them (gravity, loads, springs,
/// events, contacts and other joints reaching outside the group), IM-3.
fn side_impulse(prev: &Snapshot, s: &Snapshot, k: usize, moving: usize) -> DVec2 {
    let n = s.bodies.len();
    let mut side = vec![false; n];
    side[moving] = true;
    let mut grew = true;
    while grew {
        grew = false;
        for (q, j) in s.joints.iter().enumerate() {
            if q == k {
                continue;
            }
            for (a, b) in [(j.body1, j.body2), (j.body2, j.body1)] {
                if side[a] && !side[b] && is_massive(&s.bodies[b]) {
                    side[b] = true;
                    grew = true;
                }
            }
        }
    }
    let dt = s.dt;
    let mut j = DVec2::ZERO;
    for i in (0..n).filter(|&i| side[i]) {
        let b = &s.bodies[i];
        j += b.mass * (b.velocity - prev.bodies[i].velocity) - b.mass * s.gravity * dt;
    }
    for l in s.loads.iter().filter(|l| side[l.body]) {
        j -= l.force * dt;
    }
    for sp in &s.springs {
        let (a, b) = (side[sp.body1], sp.body2.is_some_and(|b| side[b]));
        if a && !b {
            j -= sp.force_on_body1 * dt;
        } else if b && !a {
            j += sp.force_on_body1 * dt;
        }
    }
    for e in s.impulses.iter().filter(|e| side[e.body]) {
        j -= e.impulse;
    }
    for c in &s.contacts {
        match (side[c.body1], side[c.body2]) {
            (false, true) => j -= c.impulse_on_body2(),
            (true, false) => j += c.impulse_on_body2(),
            _ => {}
        }
    }
    for (q, jt) in s.joints.iter().enumerate() {
        if q == k {
            continue;
        }
        match (side[jt.body1], side[jt.body2]) {
            (false, true) => j -= jt.impulse_on_body2,
            (true, false) => j += jt.impulse_on_body2,
            _ => {}
        }
    }
    for c in &s.couplings {
        for &(b, coord, ratio) in c.terms.iter().filter(|t| side[t.0]) {
            let _ = b;
            match coord {
                Coordinate::X => j.x -= ratio * c.impulse,
                Coordinate::Y => j.y -= ratio * c.impulse,
                Coordinate::Angle => {}
            }
        }
    }
    j
}

/// Work done on body i over the step from `prev` to `s` by its loads and by the springs attached
/// to it (the held force times the displacement of its point; ground springs only with `ground`).
fn path_work(prev: &Snapshot, s: &Snapshot, i: usize, ground: bool) -> f64 {
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
            w += held_work(prev, s, i, sp.force_on_body1, sp.applied_at1, 0.0);
        } else if sp.body2 == Some(i) {
            w += held_work(prev, s, i, -sp.force_on_body1, sp.applied_at2, 0.0);
        }
    }
    w
}

/// Work of a force F (and couple M) held over the step from `prev` to `s` on body i, applied at
/// the world point p (its position at the start of the step): U = (F . v_P,mid + M omega_mid) dt
/// with the step's mean velocity, which makes the works of a step add up to its change of kinetic
/// energy exactly (the analysis layer's `work_of_impulse`, WE-9 per step).
fn held_work(prev: &Snapshot, s: &Snapshot, i: usize, f: DVec2, p: DVec2, m: f64) -> f64 {
    let (b0, b1) = (&prev.bodies[i], &s.bodies[i]);
    let dt = s.time - prev.time;
    let v0 = point_velocity(b0, p);
    let v1 = point_velocity(b1, b1.world_point(to_local(b0, p)));
    (f.dot(0.5 * (v0 + v1)) + m * 0.5 * (b0.omega + b1.omega)) * dt
}

/// A vector's component as `Component` names it, with G the moving body's mass center and O the anchor.
fn component_of(c: Component, v: DVec2, g: DVec2, o: DVec2) -> f64 {
    let toward = (o - g).normalize_or(DVec2::X);
    match c {
        Component::Magnitude => v.length(),
        Component::X => v.x,
        Component::Y => v.y,
        Component::Normal => v.dot(toward),
        Component::Tangential => v.dot(perp(g - o).normalize_or(DVec2::Y)),
    }
}

/// The rolling contact of a body on the ground at the sample.
struct Roll {
    /// Slope angle: between the contact normal and the vertical, rad.
    theta: f64,
    /// |G - contact point|, m.
    r: f64,
    /// Unit vector along the surface, downhill.
    downhill: DVec2,
    /// Centered friction force on the body along `downhill` (N) and normal force (N).
    friction: f64,
    normal: f64,
}

fn rolling_geometry(f: &Frame, i: usize, o: usize) -> Option<Roll> {
    let s = f.cur;
    let c = s
        .contacts
        .iter()
        .find(|c| (c.body1 == i && c.body2 == o) || (c.body1 == o && c.body2 == i))?;
    // Normal from the ground to the body.
    let n = if c.body2 == i { c.normal } else { -c.normal };
    let p = c.points.iter().map(|x| x.point).sum::<DVec2>() / c.points.len().max(1) as f64;
    let g = s.gravity;
    if g.length() <= 0.0 {
        return None;
    }
    let gh = g.normalize();
    let along = gh - n * gh.dot(n);
    let downhill = along.normalize_or(perp(n));
    let theta = cross(n, -gh).abs().atan2(n.dot(-gh));
    let r = (s.bodies[i].com - p).length();
    let force = f.centered(|x| {
        let c = x
            .contacts
            .iter()
            .find(|c| (c.body1 == i && c.body2 == o) || (c.body1 == o && c.body2 == i))?;
        Some(if c.body2 == i {
            c.impulse_on_body2()
        } else {
            -c.impulse_on_body2()
        })
    })?;
    Some(Roll {
        theta,
        r,
        downhill,
        friction: force.dot(downhill),
        normal: force.dot(n),
    })
}

// ---------------------------------------------------------------------------------------------
// The probe.

/// Reads one question's quantity from every snapshot.
#[derive(Clone)]
pub struct QuestionProbe {
    def: QuestionDef,
    ctx: Arc<Ctx>,
    meter: Meter,
    /// The signal a crossing waits for.
    trigger: Option<Meter>,
    pair: Option<PairTracker>,
    hist: VecDeque<Snapshot>,
    last: Option<Reading>,
    last_signal: Option<f64>,
    value: Option<Reading>,
    /// A contact-end reading waiting for the contact to stay quiet.
    pending: Option<Reading>,
    done: bool,
    note: String,
    /// Averaging window of the quantity, s, and its half-width in steps.
    window: f64,
    lag: usize,
    /// Step number of the next sample to process.
    next_step: u64,
}

impl QuestionProbe {
    /// A probe without the level: analyses that need the level's declared coefficients or joint
    /// geometry (impacts, blows, friction work) are left out. Prefer [`QuestionProbe::for_level`].
    pub fn new(def: &QuestionDef) -> Self {
        Self::with_ctx(def, Ctx::default())
    }

    /// A probe that knows its level (restitution, friction, joints): every analysis applies.
    pub fn for_level(level: &Level, def: &QuestionDef) -> Self {
        Self::with_ctx(def, Ctx::of(level))
    }

    fn with_ctx(def: &QuestionDef, ctx: Ctx) -> Self {
        let ctx = Arc::new(ctx);
        let trigger = match &def.at {
            When::Angle { body, .. } => {
                Some(Meter::new(&Quantity::Angle(body.clone()), ctx.clone()))
            }
            When::Crossing { of, .. } => Some(Meter::new(of, ctx.clone())),
            _ => None,
        };
        let pair = match &def.at {
            When::FirstContact { body, other } | When::ContactEnds { body, other } => {
                Some(PairTracker::new(body, other.as_deref()))
            }
            _ => None,
        };
        let mut meter = Meter::new(&def.quantity, ctx.clone());
        meter.configuration_event = !matches!(def.at, When::Time(_) | When::End);
        QuestionProbe {
            def: def.clone(),
            meter,
            ctx,
            trigger,
            pair,
            hist: VecDeque::new(),
            last: None,
            last_signal: None,
            value: None,
            pending: None,
            done: false,
            note: String::new(),
            window: match &def.quantity {
                Quantity::JointReaction { window, .. } | Quantity::MotorTorque { window, .. } => {
                    *window
                }
                _ => 0.0,
            },
            lag: 1,
            next_step: 0,
        }
    }

    pub fn id(&self) -> &str {
        &self.def.id
    }

    pub fn observe(&mut self, s: &Snapshot) {
        // The initial snapshot reports mass 0 and local_com 0 (rapier computes mass properties
        // in the first step): take them from the first step, which leaves them unchanged.
        if s.step == 1 {
            if let Some(first) = self.hist.back_mut().filter(|f| f.step == 0) {
                for (b0, b1) in first.bodies.iter_mut().zip(&s.bodies) {
                    b0.mass = b1.mass;
                    b0.inertia = b1.inertia;
                    b0.local_com = b1.local_com;
                    b0.com = b0.world_point(b1.local_com);
                }
            }
            // The averaging window in steps, each side.
            if s.dt > 0.0 {
                self.lag = ((0.5 * self.window / s.dt).round() as usize).max(1);
            }
        }
        self.hist.push_back(s.clone());
        while self.ready() {
            self.process_next(true);
        }
    }

    /// Whether the next sample has its window's snapshots.
    fn ready(&self) -> bool {
        self.hist
            .back()
            .is_some_and(|b| b.step >= self.next_step + self.lag as u64 && b.step > self.next_step)
    }

    /// Processes the next unprocessed sample and drops the history it no longer needs.
    fn process_next(&mut self, more_coming: bool) {
        let Some(k) = self.hist.iter().position(|h| h.step == self.next_step) else {
            return;
        };
        self.process(k, more_coming);
        self.next_step += 1;
        let keep = self.lag.max(2);
        while self.hist.len() > keep + 1
            && self
                .hist
                .front()
                .is_some_and(|f| f.step + (keep as u64) < self.next_step)
        {
            self.hist.pop_front();
        }
    }

    /// Processes the sample at `hist[k]`.
    fn process(&mut self, k: usize, _more_coming: bool) {
        let mut hist = std::mem::take(&mut self.hist);
        hist.make_contiguous();
        let all = hist.as_slices().0;
        let lo = k.saturating_sub(self.lag);
        let hi = (k + self.lag).min(all.len() - 1);
        let frame = Frame {
            prev: k.checked_sub(1).map(|p| &all[p]),
            cur: &all[k],
            next: all.get(k + 1),
            window: if self.lag > 1 {
                &all[lo..=hi]
            } else {
                &all[k..=k]
            },
        };
        self.meter.advance(&frame);
        if let Some(t) = &mut self.trigger {
            t.advance(&frame);
        }
        let event = match &mut self.pair {
            Some(p) => p.update(&frame, &self.ctx),
            None => None,
        };
        let t = frame.cur.time;
        if !self.done {
            match self.def.at.clone() {
                When::End => self.value = Some(self.meter.read(&frame, Occasion::Plain)),
                When::Time(at) => {
                    let r = self.meter.read(&frame, Occasion::Plain);
                    if t >= at {
                        self.value = Some(match self.last {
                            Some(l) if l.t < at && t > l.t => lerp(l, r, (at - l.t) / (t - l.t)),
                            _ => r,
                        });
                        self.done = true;
                    } else {
                        self.value = Some(r);
                    }
                    self.last = Some(r);
                }
                When::Max(from) | When::Min(from) => {
                    let r = self.meter.read(&frame, Occasion::Plain);
                    let max = matches!(self.def.at, When::Max(_));
                    let better = self.value.is_none_or(|v| {
                        if max {
                            r.engine > v.engine
                        } else {
                            r.engine < v.engine
                        }
                    });
                    if t >= from && better && r.engine.is_finite() {
                        self.value = Some(r);
                    }
                }
                When::Angle { angle: value, .. } | When::Crossing { value, .. } => {
                    let after = match &self.def.at {
                        When::Crossing { after, .. } => *after,
                        _ => 0.0,
                    };
                    let r = self.meter.read(&frame, Occasion::Plain);
                    let sig = self
                        .trigger
                        .as_ref()
                        .map_or(f64::NAN, |m| m.read(&frame, Occasion::Plain).engine - value);
                    if let (Some(l), Some(s0)) = (self.last, self.last_signal) {
                        let crossed = l.t >= after
                            && s0.is_finite()
                            && sig.is_finite()
                            && s0 != 0.0
                            && (sig == 0.0 || (s0 > 0.0) != (sig > 0.0));
                        if crossed {
                            let f = s0 / (s0 - sig);
                            self.value = Some(lerp(l, r, f));
                            self.done = true;
                        }
                    }
                    self.last = Some(r);
                    self.last_signal = Some(sig);
                }
                When::FirstContact { .. } => {
                    let r = self.meter.read(&frame, Occasion::Plain);
                    if event == Some(PairEvent::Touch) {
                        if let Some(l) = self.last {
                            let imp = self.pair.as_ref().and_then(|p| p.impact.clone());
                            let analysis = match (&imp, frame.prev) {
                                (Some(imp), Some(prev)) => {
                                    let pf = Frame {
                                        prev: k.checked_sub(2).map(|p| &all[p]),
                                        cur: prev,
                                        next: Some(frame.cur),
                                        window: std::slice::from_ref(prev),
                                    };
                                    self.meter.read(&pf, Occasion::PreImpact(imp)).analysis
                                }
                                _ => None,
                            };
                            self.value = Some(Reading { analysis, ..l });
                        } else {
                            self.note =
                                "the body touches at the start: there is no pre-contact state"
                                    .into();
                        }
                        self.done = true;
                    }
                    self.last = Some(r);
                }
                When::ContactEnds { .. } => match event {
                    Some(PairEvent::Quiet) => {
                        let imp = self.pair.as_ref().and_then(|p| p.impact.clone());
                        let occ = match &imp {
                            Some(i) => Occasion::PostImpact(i),
                            None => {
                                self.note = NO_IMPACT.into();
                                Occasion::Plain
                            }
                        };
                        self.pending = Some(self.meter.read(&frame, occ));
                    }
                    Some(PairEvent::Resumed) => self.pending = None,
                    Some(PairEvent::Released) => {
                        self.value = self.pending.take();
                        self.done = true;
                    }
                    _ => {}
                },
                When::FirstStep => {
                    if frame.cur.step == 1 {
                        let blow = frame
                            .prev
                            .and_then(|p| Blow::solve(&self.ctx, p, frame.cur));
                        let occ = match &blow {
                            Some(b) => Occasion::AfterBlow(b),
                            None => Occasion::Plain,
                        };
                        self.value = Some(self.meter.read(&frame, occ));
                        self.done = true;
                    }
                }
                When::AfterEvent(name) => {
                    if frame.cur.impulses.iter().any(|e| e.name == name) {
                        let blow = frame
                            .prev
                            .and_then(|p| Blow::solve(&self.ctx, p, frame.cur));
                        let occ = match &blow {
                            Some(b) => Occasion::AfterBlow(b),
                            None => Occasion::Plain,
                        };
                        self.value = Some(self.meter.read(&frame, occ));
                        self.done = true;
                    }
                }
            }
        }
        self.hist = hist;
    }

    pub fn finish(mut self, student: Option<f64>) -> QuestionResult {
        while self.hist.iter().any(|h| h.step >= self.next_step) {
            self.process_next(false);
        }
        // A contact that went quiet before the run ended counts as ended.
        if !self.done {
            if let Some(p) = self.pending.take() {
                self.value = Some(p);
            }
        }
        if self.value.is_none() && self.note.is_empty() {
            self.note = match &self.def.at {
                When::End | When::Time(_) | When::Max(_) | When::Min(_) => "no sample".into(),
                w => format!("the event {w:?} did not happen in the run"),
            };
        }
        let r = self.value.unwrap_or(Reading {
            t: f64::NAN,
            engine: f64::NAN,
            analysis: None,
        });
        if r.engine.is_nan() && self.note.is_empty() {
            self.note = "the quantity could not be read (too few oscillations, no contact, or a missing item)".into();
        }
        let expected = self.def.expected;
        let err = |x: f64| {
            let e = if expected == 0.0 {
                x.abs()
            } else {
                (x - expected).abs() / expected.abs()
            };
            if e.is_nan() {
                f64::INFINITY
            } else {
                e
            }
        };
        let rel_error = err(r.engine);
        let analysis_rel_error = r.analysis.map(err);
        // The engine and the textbook formula on the engine's state must both agree with the
        // expected answer: a right engine number for the wrong reason is not a pass.
        let passed = rel_error <= self.def.tolerance
            && analysis_rel_error.is_none_or(|a| a <= self.def.tolerance);
        QuestionResult {
            id: self.def.id.clone(),
            ask: self.def.ask.clone(),
            unit: self.def.unit.clone(),
            expected,
            analysis: r.analysis,
            engine: r.engine,
            rel_error,
            analysis_rel_error,
            tolerance: self.def.tolerance,
            passed,
            time: r.t,
            why: self.def.why.clone(),
            note: self.note,
            student: student.map(|a| {
                let e = err(a);
                StudentGrade {
                    answer: a,
                    rel_error: e,
                    // Students are graded to their own tolerance (default 1%), not the engine's.
                    passed: e <= self.def.student_tolerance,
                }
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn elliptic_k_matches_tables() {
        // K(0) = pi/2; K(sin 45 deg) = 1.8540746773 (Abramowitz & Stegun table 17.1).
        assert!((elliptic_k(0.0) - PI / 2.0).abs() < 1e-15);
        assert!((elliptic_k(0.5f64.sqrt()) - 1.854_074_677_301_372).abs() < 1e-13);
        // K(sin 30 deg) = 1.6857503548.
        assert!((elliptic_k(0.5) - 1.685_750_354_812_596).abs() < 1e-13);
    }

    #[test]
    fn instant_center_from_two_velocity_directions() {
        // P = (0, 0) moving up and Q = (1, 1) moving right: the normals are y = 0 and x = 1, so C = (1, 0),
        // and v_P = omega k x (P - C) = omega (0, -1) gives omega = -1 (clockwise).
        let (p, vp) = (DVec2::ZERO, DVec2::Y);
        let c = instant_center(p, vp, DVec2::new(1.0, 1.0), DVec2::X).unwrap();
        assert!((c - DVec2::new(1.0, 0.0)).length() < 1e-12, "{c}");
        assert!((omega_about_center(p, vp, c) + 1.0).abs() < 1e-12);
        // A point at rest is its own center.
        let c = instant_center(p, vp, DVec2::new(2.0, 0.0), DVec2::ZERO).unwrap();
        assert_eq!(c, DVec2::new(2.0, 0.0));
        // Parallel normals: the link translates (no center).
        assert!(instant_center(p, vp, DVec2::new(1.0, 0.0), DVec2::new(0.0, -1.0)).is_none());
    }

    #[test]
    fn rolling_and_pendulum_formulas() {
        // Disc: a = 2/3 g sin(theta), F = 1/3 m g sin(theta); hoop: a = g sin(theta) / 2.
        let (g, th) = (9.81, 0.5235987755982988);
        assert!(
            (rolling_acceleration(g, th, 0.2 / 2f64.sqrt(), 0.2) - 9.81 * 0.5 * 2.0 / 3.0).abs()
                < 1e-12
        );
        assert!((rolling_acceleration(g, th, 0.2, 0.2) - 9.81 * 0.25).abs() < 1e-12);
        assert!(
            (rolling_friction(2.0, g, th, 0.2 / 2f64.sqrt(), 0.2) - 2.0 * 9.81 * 0.5 / 3.0).abs()
                < 1e-12
        );
        // Slender bar pinned at its end released from 90 deg: T = 2 pi sqrt(2L/3g) x 2K(sin 45)/pi.
        let t0 = 2.0 * PI * (2.0 / (3.0 * g)).sqrt();
        let t = pendulum_period(2.0 / 3.0, 2.0, g, 0.5, PI / 2.0);
        assert!((t / t0 - 1.180_340_599_016_096).abs() < 1e-12, "{}", t / t0);
        // Small amplitude tends to the linear period.
        assert!((pendulum_period(2.0 / 3.0, 2.0, g, 0.5, 1e-4) / t0 - 1.0).abs() < 1e-8);
    }

    #[test]
    fn impulse_solve_of_two_equal_balls() {
        // Direct central impact, e = 1, equal masses: the velocities swap (IM-9).
        let mk = |x: f64, v: f64| BodyState {
            name: String::new(),
            kind: BodyKind::Dynamic,
            position: DVec2::new(x, 0.0),
            angle: 0.0,
            com: DVec2::new(x, 0.0),
            velocity: DVec2::new(v, 0.0),
            omega: 0.0,
            mass: 2.0,
            inertia: 0.0,
            local_com: DVec2::ZERO,
        };
        let s = vec![mk(0.0, 3.0), mk(1.0, 0.0)];
        let mut row = point_row(&s, 0, 1, DVec2::new(0.5, 0.0), DVec2::X, 0.0);
        row.target = -row_velocity(&row, &s);
        let (post, l) = solve_impulses(&s, &[row], &[]);
        assert!((post[0].velocity.x - 0.0).abs() < 1e-12);
        assert!((post[1].velocity.x - 3.0).abs() < 1e-12);
        assert!((l[0] - 6.0).abs() < 1e-12);
    }
}
