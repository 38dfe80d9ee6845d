//! `Leaves`: the instant a body leaves another, read by the body's path, not by the contact's
//! force, and the textbook's analysis of a smooth body leaving a convex circle.
//!
//! `ContactEnds` reads the first step without a normal impulse: where a contact's push fades to
//! zero (a puck over a cylinder) rapier's soft contact delivers it in bursts, and the last one
//! falls a step or more from the instant the textbook's N = 0 names (0.8 degrees late on a
//! cylinder, issue 41). `Leaves` follows the gap between the two surfaces (for an `Arc`, its
//! true circle) and its rate from the bodies' velocities. While the surfaces touch, the gap
//! stays within the soft contact's sag and its acceleration near zero (the sag eases as N falls:
//! measured 5e-3 m/s^2 on tests/newuser/curved/n14_14); once they part, the gap's acceleration
//! is the free flight's relative acceleration along the normal, which rises from zero in a
//! straight line where N fell to zero smoothly (on a cylinder, d/dt (v^2/rho - g cos phi)). The
//! instant is where that straight line, through the first two samples wholly after the parting,
//! reaches zero: the gap "starts growing for good". Confirmed once the gap passes
//! [`SEPARATED`], a distance no soft contact's sag reaches; a body that parts with a jump in its
//! acceleration (a blow, a bounce) is placed at the start of the step in which it jumped.
//!
//! Measured 2026-12-07 on n14_14 (a puck leaving a 0.5 m cylinder, textbook t* = 0.487323 s):
//! 0.487246 s, 8e-5 s early (2.7e-4 rad of its path).

use super::level_facts::LevelFacts;
use super::sample::Reading;
use crate::analysis::curved_path::{leaving_angle_cos_on_convex_circle, PathSide};
use crate::analysis::kinematics::body_point_velocity;
use crate::snapshot::Snapshot;
use glam::DVec2;

/// The surfaces touch while their gap is within this, m: rapier's allowed linear error (1 mm at
/// a length unit of 1 m), the depth its soft contact may sag to and leave.
const TOUCHING: f64 = 1e-3;
/// The surfaces have parted for good once their gap passes this, m: twice the sag allowed.
const SEPARATED: f64 = 2e-3;
/// The gap's acceleration is noise below this fraction of gravity (or of 1 m/s^2 without it):
/// a contact's easing sag gives 5e-3 m/s^2, a puck leaving a cylinder reaches 0.1 m/s^2 1.3 ms
/// after it parts.
const NOISE_OF_G: f64 = 1e-2;
/// How far back a parting may lie from the first sample whose gap acceleration is past the
/// noise, s: ten times the noise's rise time at a slow parting (a 5 m cylinder, about 5 ms).
const KEEP_BEFORE: f64 = 0.05;

/// The gap between the two bodies' surfaces, m, and its rate of growth, m/s, at `s`; None where
/// the pair is not one `Leaves` follows (validation refuses those).
pub(super) fn surface_gap(
    facts: &LevelFacts,
    s: &Snapshot,
    b: usize,
    o: usize,
) -> Option<(f64, f64)> {
    let r = facts.bodies.get(b)?.disc?;
    let body = &s.bodies[b];
    let c = body.position;
    let v = body_point_velocity(body, c);
    let other = facts.bodies.get(o)?;
    let (arm, rate_sign, gap_of) = if let Some(arc) = other.arc {
        let arm = c - arc.center;
        if !arc.spans(arm) {
            // Past the arc's ends its nearer end point is the nearest point of the track.
            let end = |a: f64| arc.center + arc.radius * DVec2::from_angle(a);
            let (e0, e1) = (end(arc.start), end(arc.start + arc.sweep));
            let e = if c.distance(e0) <= c.distance(e1) {
                e0
            } else {
                e1
            };
            let u = (c - e).try_normalize()?;
            return Some((c.distance(e) - r, u.dot(v)));
        }
        let d = arm.length();
        match arc.side {
            PathSide::Outside => (arm, 1.0, d - arc.radius - r),
            PathSide::Inside => (arm, -1.0, arc.radius - d - r),
        }
    } else {
        let ro = other.disc?;
        let ob = &s.bodies[o];
        let arm = c - ob.position;
        let rel = v - body_point_velocity(ob, ob.position);
        let u = arm.try_normalize()?;
        return Some((arm.length() - r - ro, u.dot(rel)));
    };
    let u = arm.try_normalize()?;
    Some((gap_of, rate_sign * u.dot(v)))
}

/// Where the body left: between the readings `from` and `to`, a fraction of the way.
pub(super) struct Left {
    pub from: Reading,
    pub to: Reading,
    pub fraction: f64,
}

/// Watches a pair for the instant the body leaves (see the module's doc).
#[derive(Clone)]
pub(super) struct Leaving {
    body: String,
    other: String,
    after: f64,
    /// The last sample's time and gap rate.
    last: Option<(f64, f64)>,
    /// Whether the surfaces have touched (at or after `after`).
    touched: bool,
    /// The readings of the last [`KEEP_BEFORE`] s before the gap's acceleration last rose past
    /// the noise, and since; and the gap's acceleration over each step since, (mid-step time, a).
    readings: Vec<Reading>,
    rise: Vec<(f64, f64)>,
    /// Whether the last sample's gap was past zero.
    parted: bool,
    /// The first state the body touched the other in, at or after `after` (the analysis's
    /// starting point).
    pub start: Option<std::sync::Arc<Snapshot>>,
}

impl Leaving {
    pub fn new(body: &str, other: &str, after: f64) -> Self {
        Leaving {
            body: body.to_string(),
            other: other.to_string(),
            after,
            last: None,
            touched: false,
            readings: Vec::new(),
            rise: Vec::new(),
            parted: false,
            start: None,
        }
    }

    /// Feeds the sample `s` with the question's reading `r` at it; where the body left, once
    /// the gap confirms it.
    pub fn feed(
        &mut self,
        facts: &LevelFacts,
        s: &std::sync::Arc<Snapshot>,
        r: Reading,
    ) -> Option<Left> {
        let b = facts.body_index(s, &self.body)?;
        let o = facts.body_index(s, &self.other)?;
        let (gap, rate) = surface_gap(facts, s, b, o)?;
        let last = self.last.replace((s.time, rate));
        if s.time < self.after || !gap.is_finite() || !rate.is_finite() {
            return None;
        }
        if gap <= TOUCHING && !self.touched {
            self.touched = true;
            self.start = Some(s.clone());
        }
        let (t0, rate0) = last?;
        if !self.touched || s.time <= t0 {
            return None;
        }
        let a = (rate - rate0) / (s.time - t0);
        let noise = NOISE_OF_G * s.gravity.length().max(1.0);
        if a <= noise || rate <= 0.0 {
            // Not parting (yet): keep the readings of the last KEEP_BEFORE s, where a parting
            // found later may lie (the gap's acceleration rises past the noise some steps
            // after the surfaces part: 1.3 ms on a 0.5 m cylinder).
            let from = s.time - KEEP_BEFORE;
            let old = self.readings.iter().take_while(|x| x.t < from).count();
            self.readings
                .drain(..old.min(self.readings.len().saturating_sub(4)));
            self.rise.clear();
        } else {
            self.rise.push((0.5 * (t0 + s.time), a));
        }
        self.readings.push(r);
        self.parted = gap > 0.0;
        (gap > SEPARATED && !self.rise.is_empty()).then(|| self.place())?
    }

    /// At the run's end: where the body left, when its surfaces have parted (a gap past zero,
    /// its acceleration past the noise for three steps) but not yet by [`SEPARATED`].
    pub fn at_run_end(&mut self) -> Option<Left> {
        (self.parted && self.rise.len() >= 3).then(|| self.place())?
    }

    /// The instant the gap's acceleration, in a straight line through the first two samples
    /// wholly after the parting (the first one's step holds the parting itself), reaches zero.
    fn place(&mut self) -> Option<Left> {
        let t = match self.rise.as_slice() {
            [_, (t1, a1), (t2, a2), ..] if a2 > a1 => t2 - a2 * (t2 - t1) / (a2 - a1),
            // A jump in the acceleration: the start of the step it jumped in.
            _ => self.readings.first()?.t,
        };
        let rs = &self.readings;
        let t = t.clamp(rs.first()?.t, rs.last()?.t);
        let k = rs.iter().position(|x| x.t >= t)?;
        let (from, to) = (rs[k.saturating_sub(1)], rs[k]);
        let fraction = if to.t > from.t {
            (t - from.t) / (to.t - from.t)
        } else {
            1.0
        };
        self.rise.clear();
        self.readings.clear();
        Some(Left { from, to, fraction })
    }
}

/// Which value of the leaving point the textbook gives: `PolarAngle` of G about the circle's
/// centre, or G's speed.
#[derive(Clone, Copy)]
pub(super) enum LeavingValue {
    PolarAngle,
    Speed,
}

/// The textbook's leaving point of a smooth body on the outside of a fixed circle under gravity
/// alone, from the state it touched in (`start`, WE-14 and PN-2 with N = 0:
/// `analysis::curved_path::leaving_angle_cos_on_convex_circle`), or why it does not apply.
pub(super) fn leaving_analysis(
    facts: &LevelFacts,
    start: &Snapshot,
    (b, o): (usize, usize),
    want: LeavingValue,
) -> Result<f64, String> {
    let info = &facts.bodies[b];
    let arc = match facts.bodies[o].arc {
        Some(arc) if arc.side == PathSide::Outside => arc,
        Some(_) => return Err("no leaving analysis: the body rides the inside of the arc (the textbook's is for the outside of a cylinder)".into()),
        None => return Err("no leaving analysis: the other body is not a fixed circular track (the textbook's is for a cylinder)".into()),
    };
    let r = info
        .disc
        .ok_or("no leaving analysis: the body is not a disc")?;
    if facts.friction(b, o) != 0.0 {
        return Err("no leaving analysis: the pair has friction, so the body may roll or slip and its energy is not the particle's (the textbook's assumes a smooth surface)".into());
    }
    let held = facts.joints.iter().any(|j| j.body1 == b || j.body2 == b)
        || facts.springs.iter().any(|s| s.holds(b));
    if held || !info.loads.is_empty() || info.damped {
        return Err("no leaving analysis: forces other than gravity and the track act on the body (a joint, spring, load or damping)".into());
    }
    let g_vec = start.gravity;
    let g = g_vec.length();
    if g <= 0.0 {
        return Err(
            "no leaving analysis: without gravity nothing pulls the body off the circle's path"
                .into(),
        );
    }
    let body = &start.bodies[b];
    let rho = arc.radius + r;
    let arm = body.com - arc.center;
    let up = -g_vec / g;
    let u = arm
        .try_normalize()
        .ok_or("no leaving analysis: G at the circle's centre")?;
    let tangent = u.perp();
    let v_t = body.velocity.dot(tangent);
    if body.velocity.dot(u).abs() > 1e-3 * body.velocity.length().max(1e-3) {
        return Err("no leaving analysis: the body does not start moving along the circle".into());
    }
    let cos_a = u.dot(up);
    let c = leaving_angle_cos_on_convex_circle(g, rho, v_t, cos_a).ok_or(
        "no leaving analysis: the body leaves the circle at once (its speed needs more than the weight's normal part)",
    )?;
    // It leaves phi* from the top on the side it moves toward, once past the top if it climbs
    // over it (v^2 > 2 g rho (1 - cos phi_a)), else on its own side (angles counter-clockwise).
    let top = up.y.atan2(up.x);
    let own_side = up.perp_dot(u).signum() * f64::from(up.perp_dot(u).abs() > 1e-12);
    let moving = v_t.signum() * f64::from(v_t != 0.0);
    let climbs_over = v_t * v_t > 2.0 * g * rho * (1.0 - cos_a);
    let side = if own_side == 0.0 || moving * own_side < 0.0 && climbs_over {
        moving
    } else {
        own_side
    };
    if side == 0.0 {
        return Err("no leaving analysis: the body rests balanced on the top (the textbook's body never leaves)".into());
    }
    let dir = DVec2::from_angle(top + side * c.acos());
    if !arc.spans(dir) {
        return Err(
            "no leaving analysis: by the textbook the body would leave past the arc's end".into(),
        );
    }
    Ok(match want {
        LeavingValue::PolarAngle => dir.y.atan2(dir.x),
        LeavingValue::Speed => (g * rho * c).sqrt(),
    })
}

/// The leaving value a question at `Leaves` asks for, when the textbook gives it: `PolarAngle`
/// of the body about the arc's centre, or its `Speed`; Err with why for a `PolarAngle` about
/// another point; None for any other quantity (its own analysis stays).
pub(super) fn wanted(
    facts: &LevelFacts,
    q: &crate::level::Quantity,
    (body, other): (&str, &str),
) -> Option<Result<LeavingValue, String>> {
    use crate::level::Quantity;
    match q {
        Quantity::PolarAngle { body: b, about } if b == body => {
            let o = facts.level_index(other)?;
            let centre = facts.bodies[o].arc.map(|a| a.center);
            let at = DVec2::new(about.0, about.1);
            Some(match centre {
                Some(c) if c.distance(at) <= 1e-9 * (1.0 + c.length()) => {
                    Ok(LeavingValue::PolarAngle)
                }
                Some(_) => Err("no leaving analysis: the polar angle is not about the arc's centre".into()),
                None => Err("no leaving analysis: the other body is not a fixed circular track (the textbook's is for a cylinder)".into()),
            })
        }
        Quantity::Speed(b) if b == body => Some(Ok(LeavingValue::Speed)),
        _ => None,
    }
}
