//! Instants a question can wait for that are found from a signal over several samples: the
//! extreme of a quantity (`MaxOf`, `MinOf`) and the end or start of a contact's slip
//! (`SlipEnds`, `SlipStarts`). Each watcher is fed every sample and says, once, where between
//! two samples its instant lies; the probe then reads the question's quantity there.

use super::contact_reading::also_acting;
use super::level_facts::LevelFacts;
use super::sample::Reading;
use crate::analysis::closed_forms::{slide_to_roll_time, speed_when_rolling};
use crate::analysis::impact::{pair_contact, pair_normal_impulse};
use crate::analysis::kinematics::contact_slip;
use crate::snapshot::Snapshot;

/// Where an instant lies: between the previous sample's reading and this one's, a fraction of
/// the way (0 at the previous sample, 1 at this one).
pub(super) struct Found {
    pub from: Reading,
    pub fraction: f64,
}

/// The largest (or smallest) value of a signal, placed at the vertex of the parabola through the
/// three samples around its best sample. A parabola's vertex is exact for a quantity quadratic in
/// time (a projectile's height) and off by O(dt^2) of the period for a smooth extreme.
/// A sample's signal and the question's reading at it.
type Sampled = (f64, Reading);

#[derive(Clone, Default)]
pub(super) struct Extreme {
    max: bool,
    /// The last sample's signal and reading.
    last: Option<Sampled>,
    /// The best sample so far: the sample before it and its own signal and reading.
    best: Option<(Option<Sampled>, f64, Reading)>,
    /// The best sample waits for the one after it, to place the vertex.
    waiting: bool,
}

impl Extreme {
    pub fn new(max: bool) -> Self {
        Extreme {
            max,
            ..Default::default()
        }
    }

    /// Feeds a sample at or after the event's `after`; the reading the question gets so far
    /// (None to keep the one it has).
    pub fn feed(&mut self, sig: f64, r: Reading) -> Option<Reading> {
        let sig = if self.max { sig } else { -sig };
        let mut out = None;
        if self.waiting {
            self.waiting = false;
            if let Some((before, y1, best)) = &self.best {
                out = Some(match before {
                    Some((y0, r0)) => vertex(*y0, *r0, *y1, *best, sig, r),
                    None => *best,
                });
            }
        }
        if sig.is_finite() && self.best.as_ref().is_none_or(|(_, y, _)| sig > *y) {
            self.best = Some((self.last, sig, r));
            self.waiting = true;
            out = Some(r);
        }
        self.last = sig.is_finite().then_some((sig, r));
        out
    }
}

/// The reading at the vertex of the parabola through (r0, y0), (r1, y1), (r2, y2), three samples
/// a step apart: offset d = (y0 - y2) / (2 (y0 - 2 y1 + y2)) steps from the middle one (within
/// half a step of it, since y1 is the largest), read by interpolating toward the nearer side.
fn vertex(y0: f64, r0: Reading, y1: f64, r1: Reading, y2: f64, r2: Reading) -> Reading {
    let curvature = y0 - 2.0 * y1 + y2;
    let d = if curvature < 0.0 {
        (0.5 * (y0 - y2) / curvature).clamp(-0.5, 0.5)
    } else {
        0.0
    };
    if d < 0.0 {
        Reading::lerp(r0, r1, 1.0 + d)
    } else {
        Reading::lerp(r1, r2, d)
    }
}

/// A slip speed below which a contact counts as not sliding, m/s: rapier's sticking contacts
/// creep at up to a few mm/s (a disc on a pulled plank: 3.2 mm/s, docs/known-gaps.md).
const STUCK: f64 = 5e-3;
/// A slip that has fallen below this share of its largest value has ended: the contact sticks
/// (rapier catches a slip in the step it would change sign in, leaving its creep).
const ENDED_SHARE: f64 = 0.02;

/// The end or the start of the slip of body `body` on `other`, from the contact slip of the
/// samples (`analysis::kinematics::contact_slip`) while the two touch.
#[derive(Clone)]
pub(super) struct Slip {
    body: String,
    other: String,
    ends: bool,
    after: f64,
    /// The largest slip seen, m/s.
    peak: f64,
    /// The last samples (t, |slip|) while sliding (ends) or stuck (starts), newest last.
    history: Vec<(f64, f64)>,
    /// The reading at the last sample.
    last: Option<Reading>,
    /// The instant the slip would reach zero, s, once it has fallen below the end threshold.
    due: Option<f64>,
    /// The state when the slide began (t, slip, v along the floor, omega), for the closed form.
    start: Option<(f64, f64, f64, f64)>,
    /// `SlipStarts`: the reading at a step whose friction reached mu N, waiting for the slip
    /// that must follow it, and the largest slip seen while the contact held (its creep), m/s.
    candidate: Option<Reading>,
    creep: f64,
}

impl Slip {
    pub fn new(body: &str, other: &str, ends: bool, after: f64) -> Self {
        Slip {
            body: body.into(),
            other: other.into(),
            ends,
            after,
            peak: 0.0,
            history: Vec::new(),
            last: None,
            due: None,
            start: None,
            candidate: None,
            creep: 0.0,
        }
    }

    /// Feeds the sample `s` and its reading; where the event lies, once it has come.
    pub fn feed(&mut self, facts: &LevelFacts, s: &Snapshot, r: Reading) -> Option<Found> {
        let last = self.last.replace(r);
        let (i, o) = (
            facts.body_index(s, &self.body)?,
            facts.body_index(s, &self.other)?,
        );
        if s.time < self.after {
            return None;
        }
        if !self.ends {
            return self.slip_starts(facts, s, i, o, last);
        }
        let touching = pair_normal_impulse(s, i, Some(o), None) > 0.0;
        let slip = contact_slip(s, o, i).filter(|_| touching)?;
        let a = slip.abs();
        self.peak = self.peak.max(a);
        self.slip_ends(s, i, o, slip, a, last)
    }

    fn slip_ends(
        &mut self,
        s: &Snapshot,
        i: usize,
        o: usize,
        slip: f64,
        a: f64,
        last: Option<Reading>,
    ) -> Option<Found> {
        let t = s.time;
        if a > STUCK.max(ENDED_SHARE * self.peak) && self.due.is_none() {
            if self.start.is_none() {
                let b = &s.bodies[i];
                // Forward along the floor: rolling forward turns the body clockwise (RK-8).
                let along = pair_contact(s, o, i).map_or(glam::DVec2::X, |c| -c.normal.perp());
                self.start = Some((t, slip, b.velocity.dot(along), b.omega));
            }
            self.history.push((t, a));
            if self.history.len() > 2 {
                self.history.remove(0);
            }
            return None;
        }
        let &(t1, a1) = self.history.last()?;
        // The slip falls at a steady rate while it slides (Coulomb friction on a round body):
        // the rate over the last two sliding samples, or over the last one and this one.
        let rate = match self.history.as_slice() {
            &[(t0, a0), _] if a0 > a1 && t1 > t0 => (a0 - a1) / (t1 - t0),
            _ if a1 > a && t > t1 => (a1 - a) / (t - t1),
            _ => return None,
        };
        let due = *self.due.get_or_insert(t1 + a1 / rate);
        let from = last?;
        if due > t {
            // Zero is still ahead (the slip fell below the threshold before it): wait.
            return None;
        }
        let fraction = ((due - from.t) / (t - from.t)).clamp(0.0, 1.0);
        Some(Found { from, fraction })
    }

    /// Impending slip (the textbook's "starts to slide"): the step whose friction reaches mu N,
    /// the most Coulomb's law lets a sticking contact take. Sticking, the ratio F/N of the
    /// pair's friction to normal impulse stays below mu; the first step at mu (within 0.1%)
    /// begins the slide, placed where the ratio's straight-line rise over the two samples
    /// before reaches mu. The slip itself starts from zero speed (quadratically under a ramped
    /// load), so a speed threshold would place it late.
    fn slip_starts(
        &mut self,
        facts: &LevelFacts,
        s: &Snapshot,
        i: usize,
        o: usize,
        last: Option<Reading>,
    ) -> Option<Found> {
        // A step's impulses are its mean force: the ratio belongs to the step's middle (a
        // load, too, is evaluated there).
        let t = s.time - 0.5 * s.dt;
        let c = pair_contact(s, o, i)?;
        if c.normal_impulse <= 0.0 {
            return None;
        }
        let mu = facts.friction(i, o);
        let ratio = c.impulse_on_b.dot(c.normal.perp()).abs() / c.normal_impulse;
        if let Some(at) = self.candidate {
            // Friction at its limit is where a slide begins, if one follows: on a faceted curve
            // the normal force comes in bursts, and a dip between them brings F/N to mu for a
            // step while the contact holds. The slide is confirmed once the slip passes STUCK and
            // twice the creep the contact showed while it held (a disc on a faceted cylinder
            // creeps at 6 mm/s); a contact back well below the limit (F/N under 0.95 mu)
            // without it was such a dip.
            let slip = contact_slip(s, o, i).map_or(0.0, f64::abs);
            if slip > STUCK.max(2.0 * self.creep) {
                return Some(Found {
                    from: at,
                    fraction: 0.0,
                });
            }
            if ratio >= 0.95 * mu {
                return None;
            }
            self.candidate = None;
            self.history.clear();
        }
        if ratio < mu * (1.0 - 1e-3) {
            self.creep = self.creep.max(contact_slip(s, o, i).map_or(0.0, f64::abs));
            self.history.push((t, ratio));
            if self.history.len() > 2 {
                self.history.remove(0);
            }
            return None;
        }
        let &(t1, r1) = self.history.last()?;
        let from = last?;
        let onset = match self.history.as_slice() {
            &[(t0, r0), _] if r1 > r0 && t1 > t0 => (t1 + (mu - r1) * (t1 - t0) / (r1 - r0)).min(t),
            _ => t,
        };
        // The onset lies within the half step before the previous sample or after it: read
        // there on the straight line through the two samples (back up to one step).
        let fraction = ((onset - from.t) / (s.time - from.t)).clamp(-1.0, 1.0);
        let r = self.last?;
        self.candidate = Some(Reading::lerp(from, r, fraction));
        // A slide that has already begun needs no wait.
        let slip = contact_slip(s, o, i).map_or(0.0, f64::abs);
        (slip > STUCK.max(2.0 * self.creep)).then_some(Found {
            from: self.candidate?,
            fraction: 0.0,
        })
    }

    /// The textbook's time and speed at which the slide ends, for a round body sliding on a level
    /// fixed floor with nothing else on it (6/1 with F = mu N; 6/15): (t, speed), or why the
    /// closed form does not apply.
    pub fn closed_form(&self, facts: &LevelFacts, s: &Snapshot) -> Result<(f64, f64), String> {
        let (t0, slip0, v0, w0) = self
            .start
            .ok_or_else(|| "the slide's start was not seen".to_string())?;
        let (i, o) = (
            facts.body_index(s, &self.body).ok_or("no body")?,
            facts.body_index(s, &self.other).ok_or("no body")?,
        );
        let info = &facts.bodies[i];
        let r = info.disc.ok_or_else(|| {
            "the slide-to-roll time is for a round body (a circle centered on its origin)"
                .to_string()
        })?;
        if s.bodies[o].kind != crate::snapshot::BodyKind::Fixed {
            return Err("the floor moves: the slide-to-roll time is for a fixed floor".into());
        }
        let n = pair_contact(s, o, i).ok_or("no contact")?.normal;
        let g = s.gravity.length();
        if g <= 0.0 || n.dot(-s.gravity / g) < 1.0 - 1e-6 {
            return Err(
                "the floor is not level: the slide-to-roll time is for a level floor".into(),
            );
        }
        let held = also_acting(s, i, o).or_else(|| info.damped.then_some("damping"));
        if let Some(what) = held {
            return Err(format!(
                "{what} also acts on the body: the slide-to-roll closed form assumes its weight and the floor alone"
            ));
        }
        let k = info.textbook.radius_of_gyration();
        let mu = facts.friction(i, o);
        if mu <= 0.0 {
            return Err("the floor is frictionless: the body never rolls".into());
        }
        Ok((
            t0 + slide_to_roll_time(slip0, mu, g, k, r),
            speed_when_rolling(v0, w0, k, r).abs(),
        ))
    }
}
