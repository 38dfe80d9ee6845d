//! The textbook's solution of an impact or a blow, from the engine's state just before it and
//! the level's declared coefficients and joints: the touching instant and the states right
//! after ([`Impact`], IM-9 to IM-14, RM-10), and the states and pin impulses after an impulse
//! event ([`Blow`], RM-10, CP-3). The questions' velocity, energy and impulse analyses at those
//! events read them (see `sample::Occasion`).

use super::level_facts::LevelFacts;
use super::snapshot_reading::{carried_forward, to_local};
use crate::analysis::cross;
use crate::analysis::impulse_solver::{
    coupling_row, joint_impulse, joint_rows, point_row, row_velocity, solve_impulses, ConstraintRow,
};
use crate::analysis::touching::{flies_free, Approaching};
use crate::analysis::Motion;
use crate::snapshot::{BodyState, ContactState, Snapshot};
use glam::DVec2;

/// The constraint rows of the level's joints (target: no relative velocity) and of the
/// snapshot's couplings, for the bodies in state `s`. Returns the rows and, per joint, the range
/// of its rows (to rebuild its impulse).
fn constraint_rows(
    facts: &LevelFacts,
    snap: &Snapshot,
    s: &[BodyState],
) -> (Vec<ConstraintRow>, Vec<(usize, usize)>) {
    let mut rows = Vec::new();
    let mut ranges = Vec::new();
    for j in &facts.joints {
        let start = rows.len();
        rows.extend(joint_rows(s, j.kind, j.body1, j.body2, j.anchor2, j.axis));
        ranges.push((start, rows.len()));
    }
    for c in &snap.couplings {
        rows.push(coupling_row(&c.terms));
    }
    (rows, ranges)
}

/// The first contact of a pair, carried back to the instant of touching, and the
/// impulse-momentum solution of the impact.
#[derive(Debug, Clone)]
pub(super) struct Impact {
    /// Time of touching, s.
    pub t_c: f64,
    /// Every body's state at the touching instant (free bodies carried ballistically from the
    /// last step before contact; others at that step's state).
    pub pre: Vec<BodyState>,
    /// States right after the impact (the impulse-momentum solution with the level's e and mu).
    pub post: Vec<BodyState>,
    /// Contact normal from body1 to body2 of the contact, the contact point, and the two bodies.
    pub normal: DVec2,
    pub point: DVec2,
    pub i1: usize,
    pub i2: usize,
    /// Which bodies were free (carried ballistically).
    pub free: Vec<bool>,
}

/// Why a contact event's question has no impulse-momentum analysis.
pub(super) const NO_IMPACT: &str = "no impact analysis: the bodies did not approach each other when the contact began (a contact from the start or one slid into, such as a ladder on its wall), so the answer is graded on the engine alone";

impl Impact {
    /// The impact of `body` with `other` (any body when None) that the snapshot `hit` shows
    /// first, `pre` being the snapshot before it; None when the bodies were not approaching.
    pub fn find(
        facts: &LevelFacts,
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
                let s = |c: &ContactState| c.points.iter().map(|p| p.normal_impulse).sum::<f64>();
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
        // Free over [pre, touching]: under gravity alone, so neither jointed nor pushed by a
        // contact in the step before (a wheel rolling on its floor into a curb is held up by the
        // floor until the impact: carried with g, it gained g tau downward and H about the
        // corner was 1% off).
        let supported = |i: usize| {
            pre.contacts
                .iter()
                .any(|c| (c.body1 == i || c.body2 == i) && c.pushes())
        };
        let free: Vec<bool> = (0..pre.bodies.len())
            .map(|i| flies_free(hit, i) && !supported(i))
            .collect();
        let acc = |i: usize| if free[i] { pre.gravity } else { DVec2::ZERO };
        let disc = |i: usize| facts.bodies.get(i).and_then(|x| x.disc);
        let (m1, m2) = (Motion::from(b1), Motion::from(b2));
        let touch = Approaching {
            pre: [&m1, &m2],
            acc: [acc(i1), acc(i2)],
            points: [q1, q2],
            normal: n,
            discs: [disc(i1), disc(i2)],
        }
        .touching(pre.gravity.length(), hit.dt)?;
        let (n, tau, disc_point) = (touch.normal, touch.tau, touch.disc_point);
        let states: Vec<BodyState> = pre
            .bodies
            .iter()
            .enumerate()
            .map(|(i, b)| carried_forward(b, tau, acc(i)))
            .collect();
        let point = disc_point.unwrap_or_else(|| states[i1].world_point(l1));
        let e = facts.restitution(i1, i2);
        let mu = facts.friction(i1, i2);
        let (mut rows, _) = constraint_rows(facts, hit, &states);
        let mut normal = point_row(&states, i1, i2, point, n, 0.0);
        let approach = row_velocity(&normal, &states);
        normal.target = -e * approach;
        rows.push(normal);
        let post = if mu > 0.0 {
            rough_impact(&states, rows, (i1, i2), point, n, mu)
        } else {
            solve_impulses(&states, &rows, &[]).0
        };
        Some(Impact {
            t_c: pre.time + tau,
            pre: states,
            post,
            normal: n,
            point,
            i1,
            i2,
            free,
        })
    }
}

/// The states after an impact at a rough contact (Coulomb friction mu) whose normal row is the
/// last of `rows`. If friction can stop the slip at the contact, it does (RM-10: the plate
/// pivots on the ledge): the tangential impulse J_t needed is within mu J_n. Else the contact
/// slides through the impact and friction gives mu J_n against the slip (a spinning disc
/// striking a wall: the sticking answer asks 1/3 N s of a friction that gives 0.24 N s). J_n
/// is linear in J_t, J_n = J_n0 + c J_t (one more solve gives c), so J_t = mu J_n0 / (1 - mu c).
fn rough_impact(
    states: &[BodyState],
    mut rows: Vec<ConstraintRow>,
    (i1, i2): (usize, usize),
    point: DVec2,
    n: DVec2,
    mu: f64,
) -> Vec<BodyState> {
    let k = rows.len() - 1;
    rows.push(point_row(states, i1, i2, point, n.perp(), 0.0));
    let (stuck, lambda) = solve_impulses(states, &rows, &[]);
    let (j_n, j_t) = (lambda[k], lambda[k + 1]);
    if j_t.abs() <= mu * j_n.abs() {
        return stuck;
    }
    rows.pop();
    // A tangential impulse tau on body2 along the sticking impulse's direction (-tau on body1).
    let dir = n.perp() * j_t.signum();
    let ext = |tau: f64| {
        let (on2, on1) = (dir * tau, -dir * tau);
        vec![
            (i2, on2, cross(point - states[i2].com, on2)),
            (i1, on1, cross(point - states[i1].com, on1)),
        ]
    };
    let n0 = solve_impulses(states, &rows, &[]).1[k];
    let c = solve_impulses(states, &rows, &ext(1.0)).1[k] - n0;
    let tau = mu * n0 / (1.0 - mu * c);
    solve_impulses(states, &rows, &ext(tau)).0
}

/// An impulse event and the impulse-momentum solution of the blow (RM-10).
#[derive(Debug, Clone)]
pub(super) struct Blow {
    t0: f64,
    post: Vec<BodyState>,
    /// Linear impulse each level joint gave its body2 during the blow, N s.
    pub joint_impulse: Vec<DVec2>,
    free: Vec<bool>,
}

impl Blow {
    /// The blow of the impulse events in `hit`, on the state of `pre`.
    pub fn solve(facts: &LevelFacts, pre: &Snapshot, hit: &Snapshot) -> Blow {
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
        let (rows, ranges) = constraint_rows(facts, hit, s);
        let (post, lambda) = solve_impulses(s, &rows, &ext);
        let joint_impulse = facts
            .joints
            .iter()
            .zip(&ranges)
            .map(|(j, r)| joint_impulse(j.kind, s[j.body1].angle, j.axis, &lambda[r.0..r.1]))
            .collect();
        Blow {
            t0: pre.time,
            post,
            joint_impulse,
            free: (0..s.len()).map(|i| flies_free(hit, i)).collect(),
        }
    }

    /// Body i's state at time t after the blow (carried ballistically when free).
    pub fn post_at(&self, i: usize, t: f64, g: DVec2) -> BodyState {
        let a = if self.free[i] { g } else { DVec2::ZERO };
        carried_forward(&self.post[i], (t - self.t0).max(0.0), a)
    }
}
