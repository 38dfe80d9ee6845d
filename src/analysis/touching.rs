//! The touching instant of an impact: IM-9's "just before" and "just after" are the states at
//! the instant the bodies touch, not at the ends of the engine's step.
//!
//! The engine makes a contact in the step in which the bodies meet, anywhere inside it, and
//! reports states only at the step's ends: a ball falling onto a floor gains g tau before the
//! touch and loses g (h - tau) after it, so velocities read at the step's ends put e off by up
//! to g h / v (a second new user's ball dropped 0.8 m with e = 0.6 read 0.6031 to 0.6047 at
//! 4 to 16 substeps, its second bounce 0.586 to 0.610). The instant is solved from the state
//! at the start of the step, each body carried at the constant acceleration it has while it
//! flies free (gravity) or none (held by a joint or a support, where the carry is not
//! attempted); the questions' impact solution (`questions::impact_solution`) and the
//! `restitution` check both take it from here.

use super::impulse_solver::is_massive;
use super::Motion;
use crate::snapshot::Snapshot;
use glam::DVec2;

/// Whether body i of `s` moves under gravity alone but for its contacts: dynamic, with mass,
/// neither jointed nor coupled. With no contact pushing it either, it flies free, and its
/// approach to an impact is carried at g.
pub fn flies_free(s: &Snapshot, i: usize) -> bool {
    is_massive(&s.bodies[i])
        && !s.joints.iter().any(|j| j.body1 == i || j.body2 == i)
        && !s.couplings.iter().any(|c| c.terms.iter().any(|t| t.0 == i))
}

/// The acceleration body i flies at over the step `s` ends: gravity and the forces the engine
/// held on it during that step (its springs' and dampers', its loads'; the snapshot's mean
/// forces, N), over its mass. A body on a spring is carried to its impact at g alone
/// otherwise: a ball held by a spring (the tenth new user's tests/newuser/impacts/n10_01b) read its
/// approach speed 3.108 for 3.102 m/s and the energy lost up to 4.75e-3 high. A torsion
/// spring's couple and a force's moment about G are left out: the carry is G's.
pub fn free_acceleration(s: &Snapshot, i: usize) -> DVec2 {
    let m = s.bodies[i].mass;
    if !(m > 0.0 && m.is_finite()) {
        return s.gravity;
    }
    let mut force = DVec2::ZERO;
    for sp in s.springs.iter().filter(|sp| !sp.torsion) {
        if sp.body1 == i {
            force += sp.force_on_body1;
        }
        if sp.body2 == Some(i) {
            force -= sp.force_on_body1;
        }
    }
    for l in s.loads.iter().filter(|l| l.body == i) {
        force += l.force;
    }
    s.gravity + force / m
}

/// When and where a pair touches, from their states at the start of the step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Touching {
    /// Time from the start state to the touch, s (negative when the engine let the bodies
    /// overlap before its contact acted).
    pub tau: f64,
    /// Contact normal from the first body to the second at the touch.
    pub normal: DVec2,
    /// Where a disc of the pair touches, on its rim along the normal (for two discs, on the
    /// line of centers). None for two other shapes: the caller's material point carried to the
    /// touch. (A spinning disc's material point at the contact at the step's end was elsewhere
    /// at the touch: a disc striking a wall at 20 rad/s read its approach 1% fast from it.)
    pub disc_point: Option<DVec2>,
}

/// Two bodies' states at the start of the step in which they touch, with what the solution
/// needs of each.
#[derive(Debug, Clone, Copy)]
pub struct Approaching<'a> {
    pub pre: [&'a Motion; 2],
    /// Each body's acceleration over the approach: gravity while it flies free, else zero.
    pub acc: [DVec2; 2],
    /// The material points that touch, at the start state (world), m.
    pub points: [DVec2; 2],
    /// The engine's contact normal, first body to second.
    pub normal: DVec2,
    /// The radius of each body that is a disc about its G (the line of centers is then exact).
    pub discs: [Option<f64>; 2],
}

impl Approaching<'_> {
    /// The touching instant within a few steps of length `dt` of the start state, or None when
    /// the pair is not approaching (a contact there from the start, or one slid into: a ladder
    /// on its wall, a block set down), which gravity alone could close in a step or two:
    /// `gravity` is |g|.
    pub fn touching(&self, gravity: f64, dt: f64) -> Option<Touching> {
        let [b1, b2] = self.pre;
        let [a1, a2] = self.acc;
        match self.discs {
            // Two discs: the line of centers at touching, |d + w tau + a tau^2/2| = r1 + r2,
            // instead of the engine's speculative normal (taken up to a step before they touch).
            [Some(r1), Some(r2)] => {
                let (d0, w, a) = (b2.com - b1.com, b2.velocity - b1.velocity, a2 - a1);
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
                if !(t.is_finite() && t.abs() <= 2.0 * dt) {
                    t = 0.0;
                }
                let n = (d0 + w * t + 0.5 * a * t * t).normalize_or(self.normal);
                if (w + a * t).dot(n) >= 0.0 {
                    return None;
                }
                Some(Touching {
                    tau: t,
                    normal: n,
                    disc_point: Some(b1.carried(t, a1).com + n * r1),
                })
            }
            _ => {
                let n = self.normal;
                // A disc's touching point is on its rim along the normal, whatever it spins.
                let [mut q1, mut q2] = self.points;
                if let [Some(r1), _] = self.discs {
                    q1 = b1.com + n * r1;
                }
                if let [_, Some(r2)] = self.discs {
                    q2 = b2.com - n * r2;
                }
                let gap = (q2 - q1).dot(n);
                let v_n = (b2.velocity_at(q2) - b1.velocity_at(q1)).dot(n);
                let a_n = (a2 - a1).dot(n);
                // Not approaching faster than gravity can close a gap in a step or two.
                if v_n >= -(2.0 * gravity * dt + 1e-9) {
                    return None;
                }
                // gap + v_n tau + a_n tau^2 / 2 = 0 while approaching: the root nearest the start
                // state, within three steps either way (negative when the engine let the bodies
                // overlap before the contact acted: the textbook impact is at the touching instant).
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
                    .filter(|t| v_n + a_n * t < 0.0 && t.abs() <= 3.0 * dt)
                    .min_by(|a, b| a.abs().total_cmp(&b.abs()))
                    .unwrap_or(0.0);
                // A disc touches on its rim, r along the normal from its G.
                let rim = match self.discs {
                    [Some(r1), _] => Some(b1.carried(tau, a1).com + n * r1),
                    [_, Some(r2)] => Some(b2.carried(tau, a2).com - n * r2),
                    _ => None,
                };
                Some(Touching {
                    tau,
                    normal: n,
                    disc_point: rim,
                })
            }
        }
    }
}

/// One side of an impact's reading: a body's state, when it was read, s, and the acceleration
/// it is carried at from then to the touching instant.
#[derive(Debug, Clone, Copy)]
pub struct ReadAt<'a> {
    pub motion: &'a Motion,
    pub time: f64,
    pub acc: DVec2,
}

/// The acceleration a body's state after an impact is carried back at: gravity while it flies
/// free of the partner (`free`, see [`flies_free`], and the pair's contact no longer pushing
/// there), none while the contact still pushes or a joint holds it (a ball with e = 0 resting
/// on the floor, carried back with g, would read e = g (t - t_touch) / v; a ball still in
/// contact while friction acts takes no g either, since the floor bears its weight).
pub fn carried_back_at(free: bool, pushing: bool, gravity: DVec2) -> DVec2 {
    if free && !pushing {
        gravity
    } else {
        DVec2::ZERO
    }
}

/// e and the impact's other measures at the touching instant (IM-9): the pair's states before
/// and after, each carried to `touch_time` at its acceleration, the relative velocity of the
/// touching point along the normal. The one reading the `restitution` check and the
/// `Restitution` question share (they read one impact 0.9931 and 1.0005 before: the question
/// carried the state after back at g while the contact still pushed).
pub fn impact_at_touch(
    touch_time: f64,
    before: [ReadAt; 2],
    after: [ReadAt; 2],
    point: DVec2,
    normal: DVec2,
    impulse_on_b: DVec2,
) -> super::impact::ImpactMeasure {
    let at = |r: &ReadAt| r.motion.carried(touch_time - r.time, r.acc);
    let [a0, b0] = [at(&before[0]), at(&before[1])];
    let [a1, b1] = [at(&after[0]), at(&after[1])];
    super::impact::measure_impact((&a0, &a1), (&b0, &b1), point, normal, impulse_on_b)
}
