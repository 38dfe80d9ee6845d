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
use crate::analysis::touching::{flies_free, free_acceleration, Approaching};
use crate::analysis::Motion;
use crate::level::BodyKind;
use crate::snapshot::{BodyState, ContactState, Snapshot};
use glam::DVec2;

/// The bodies an impact or blow solution moves with the `struck` ones: the dynamic bodies
/// joined to them through the level's joints and the step's couplings (a fixed or kinematic body
/// passes nothing on: its motion is given).
fn solved_set(facts: &LevelFacts, hit: &Snapshot, struck: &[usize]) -> Vec<bool> {
    let n = hit.bodies.len();
    let dynamic = |i: usize| {
        hit.bodies
            .get(i)
            .is_some_and(|b| b.kind == BodyKind::Dynamic)
    };
    let mut set = vec![false; n];
    for &i in struck.iter().filter(|&&i| dynamic(i)) {
        set[i] = true;
    }
    let links: Vec<Vec<usize>> = facts
        .joints
        .iter()
        .map(|j| vec![j.body1, j.body2])
        .chain(
            hit.couplings
                .iter()
                .map(|c| c.terms.iter().map(|t| t.0).collect()),
        )
        .collect();
    loop {
        let mut grew = false;
        for l in &links {
            if l.iter().any(|&i| set.get(i).copied().unwrap_or(false)) {
                for &i in l {
                    if i < n && dynamic(i) && !set[i] {
                        set[i] = true;
                        grew = true;
                    }
                }
            }
        }
        if !grew {
            return set;
        }
    }
}

/// Why the impulse-momentum solution of the impact or blow in the step that led to `hit` does
/// not hold, if it does not: the solution holds the event's own pair (`own`), the level's joints
/// and the couplings, and leaves every other contact out, so a contact that gave a body of the
/// solved mechanism an impulse in that step makes its answer one of the wrong problem (a block
/// lying on a floor struck downward: the solution gives it the blow's J / m, the floor stops it).
///
/// A contact counts when its impulse on the pair's second body changed from the step before
/// (`pre`) by more than the larger of 1% of the event's impulse `event` (N s) and twice what the
/// solved bodies' weights deliver in a step: a contact that only goes on carrying a weight (a
/// ball lying on the floor struck sideways: the floor gives m g dt, and friction at most
/// mu m g dt, as in every step) is the non-impulsive force the textbook's impulse-momentum
/// balance neglects (IM-9).
pub(super) fn left_out_contact(
    facts: &LevelFacts,
    pre: &Snapshot,
    hit: &Snapshot,
    struck: &[usize],
    own: Option<(usize, usize)>,
    event: f64,
) -> Option<String> {
    let set = solved_set(facts, hit, struck);
    let in_set = |i: usize| set.get(i).copied().unwrap_or(false);
    let weights: f64 = (0..set.len())
        .filter(|&i| set[i])
        .map(|i| hit.bodies[i].mass * hit.gravity.length())
        .sum();
    let floor = (0.01 * event.abs()).max(2.0 * weights * hit.dt);
    let is_own =
        |a: usize, b: usize| own.is_some_and(|(x, y)| (a, b) == (x, y) || (a, b) == (y, x));
    // The impulse on b of all of the pair's manifolds in a snapshot.
    let on = |snap: &Snapshot, a: usize, b: usize| -> DVec2 {
        snap.contacts
            .iter()
            .map(|c| {
                if (c.body1, c.body2) == (a, b) {
                    c.impulse_on_body2()
                } else if (c.body1, c.body2) == (b, a) {
                    -c.impulse_on_body2()
                } else {
                    DVec2::ZERO
                }
            })
            .sum()
    };
    // A joint's limit or motor in the solved set: the solution holds the joints as ideal
    // constraints, without the stop a limit makes or the impulse a motor adds in the step.
    let joint_part = |snap: &Snapshot, name: &str| {
        snap.joints
            .iter()
            .find(|j| j.name == name)
            .map_or((0.0, 0.0), |j| (j.limit_impulse, j.motor_impulse))
    };
    let joint = hit
        .joints
        .iter()
        .filter(|j| in_set(j.body1) || in_set(j.body2))
        .flat_map(|j| {
            let (limit, motor) = joint_part(hit, &j.name);
            let (limit0, motor0) = joint_part(pre, &j.name);
            [
                ("limit", &j.name, (limit - limit0).abs()),
                ("motor", &j.name, (motor - motor0).abs()),
            ]
        })
        .filter(|x| x.2 > floor)
        .max_by(|x, y| x.2.total_cmp(&y.2));
    if let Some((part, name, d)) = joint {
        return Some(format!(
            "the {part} of joint \"{name}\" gave an impulse of {d:.3e} in the same step (against the event's {event:.3e} N s), which the impulse-momentum solution leaves out: it holds the joints as ideal constraints, without their limits and motors"
        ));
    }
    hit.contacts
        .iter()
        .filter(|c| (in_set(c.body1) || in_set(c.body2)) && !is_own(c.body1, c.body2))
        .map(|c| {
            let (a, b) = (c.body1, c.body2);
            (a, b, (on(hit, a, b) - on(pre, a, b)).length())
        })
        .filter(|x| x.2 > floor)
        .max_by(|x, y| x.2.total_cmp(&y.2))
        .map(|(a, b, d)| {
            let name = |i: usize| hit.bodies.get(i).map_or("?", |x| x.name.as_str());
            format!(
                "the contact of \"{}\" with \"{}\" gave an impulse of {d:.3e} N s in the same step (against the event's {event:.3e} N s), which the impulse-momentum solution leaves out: it holds the joints, the couplings and, at an impact, the pair's own contact only",
                name(a),
                name(b)
            )
        })
}

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
    /// Why the solution does not hold: another contact on the solved bodies in the impact's
    /// step ([`left_out_contact`]).
    pub left_out: Option<String>,
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
        // The initial snapshot holds no contact readings (none has been solved yet): there a
        // body is supported when a third body pushes on it in the first step (a wheel placed
        // on its floor that meets a curb in that step, n2_03b: carried with g, w' read 1e-2 off
        // where the engine read 3.5e-3).
        let pushes_on = |c: &crate::snapshot::ContactState, i: usize| {
            (c.body1 == i || c.body2 == i) && c.pushes()
        };
        let pair = |c: &crate::snapshot::ContactState| {
            (c.body1, c.body2) == (i1, i2) || (c.body1, c.body2) == (i2, i1)
        };
        let supported = |i: usize| {
            pre.contacts.iter().any(|c| pushes_on(c, i))
                || (pre.step == 0
                    && pre.contacts.is_empty()
                    && hit.contacts.iter().any(|c| !pair(c) && pushes_on(c, i)))
        };
        let free: Vec<bool> = (0..pre.bodies.len())
            .map(|i| flies_free(hit, i) && !supported(i))
            .collect();
        // A kinematic body moves as the level prescribes: carried at its mean acceleration over
        // the step (an oscillating platform accelerates at A w^2 sin(w t); carried at constant
        // velocity, the ball's rebound off it read 1.5e-3 low, the fifteenth new user's n15_11b).
        let acc = |i: usize| {
            if free[i] {
                free_acceleration(hit, i)
            } else if hit.bodies[i].kind == BodyKind::Kinematic && hit.dt > 0.0 {
                (hit.bodies[i].velocity - pre.bodies[i].velocity) / hit.dt
            } else {
                DVec2::ZERO
            }
        };
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
        let event = crate::analysis::impact::pair_normal_impulse(hit, i1, Some(i2), None);
        let left_out = left_out_contact(facts, pre, hit, &[i1, i2], Some((i1, i2)), event);
        Some(Impact {
            left_out,
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
    /// Why the solution does not hold: another contact on the struck mechanism in the blow's
    /// step ([`left_out_contact`]).
    pub left_out: Option<String>,
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
        let struck: Vec<usize> = hit.impulses.iter().map(|e| e.body).collect();
        let event: f64 = hit.impulses.iter().map(|e| e.impulse.length()).sum();
        Blow {
            left_out: left_out_contact(facts, pre, hit, &struck, None, event),
            t0: pre.time,
            post,
            joint_impulse,
            // Carried at g after the blow only when nothing held it up before (a block lying on
            // a floor and struck sideways stays on it: carried at g it read v_y = -g dt).
            free: (0..s.len())
                .map(|i| {
                    flies_free(hit, i)
                        && !pre
                            .contacts
                            .iter()
                            .any(|c| (c.body1 == i || c.body2 == i) && c.pushes())
                })
                .collect(),
        }
    }

    /// Body i's state at time t after the blow (carried ballistically when free).
    pub fn post_at(&self, i: usize, t: f64, g: DVec2) -> BodyState {
        let a = if self.free[i] { g } else { DVec2::ZERO };
        carried_forward(&self.post[i], (t - self.t0).max(0.0), a)
    }
}
