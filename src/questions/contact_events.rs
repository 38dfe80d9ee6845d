//! The first contact of a pair of bodies, followed from touch to release: when it begins (and
//! the impact it begins with), when it goes quiet, and when it has stayed quiet long enough to
//! count as ended. Questions asked at `FirstContact`/`ContactEnds`, and the impact quantities
//! (rebound, restitution, energy lost), read these events.

use super::free_flight::FlightFromStart;
use super::impact_solution::Impact;
use super::level_facts::LevelFacts;
use super::sample::Sample;
use crate::analysis::impact::{pair_contact, pair_normal_impulse};
use crate::analysis::kinematics::body_point_velocity;
use crate::snapshot::Snapshot;
use glam::DVec2;
use std::sync::Arc;

/// The moments of a pair's first contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum PairEvent {
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

/// Where the pair is in its first contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum ContactPhase {
    /// Not touched yet.
    Before,
    /// Pushing on each other.
    Touching,
    /// Without force since the last `Quiet` event, not yet long enough to count as ended.
    Quiet,
    /// The first contact has ended.
    Released,
    /// Touching again: a second contact began.
    Again,
}

/// How long a contact must stay without force before it counts as ended (at least `QUIET_STEPS`
/// samples and `QUIET_TIME` seconds): rapier's soft, speculative contact delivers a light contact
/// force in bursts, with quiet steps between them (a ladder sliding on a wall: gaps of up to 19 ms).
const QUIET_STEPS: u32 = 10;
const QUIET_TIME: f64 = 0.05;

/// Follows the contacts of one body with another (or with anything).
#[derive(Debug, Clone)]
pub(super) struct PairTracker {
    body: String,
    other: Option<String>,
    /// The body indices, once found in a snapshot.
    indices: Option<(usize, Option<usize>)>,
    pub phase: ContactPhase,
    /// Samples without force since the last `Quiet` event.
    quiet_samples: u32,
    /// The largest normal impulse of the contact so far, N s.
    peak: f64,
    /// The contact's normal impulse summed from the touch, N s, and what the pair's weights
    /// delivered over the same steps, N s (see [`PairTracker::not_impulsive`]).
    contact_impulse: f64,
    weight_impulse: f64,
    /// The contact's whole impulse on `body` (normal and friction) summed from the touch, N s,
    /// and the last normal of the pair seen, pointing into `body`.
    contact_vector: DVec2,
    normal_into_body: Option<DVec2>,
    /// The snapshot before the first touch (the pre-impact state).
    pub pre: Option<Arc<Snapshot>>,
    /// The impact the first touch was (None when the bodies were not approaching).
    pub impact: Option<Impact>,
    /// The first snapshot without force (the post-impact state), while quiet or released.
    pub release: Option<Arc<Snapshot>>,
    /// The end of the contact's impulsive phase (for a contact that lasts, such as a ram driving
    /// a pile into sand, the post-impact state): the first snapshot in which the bodies no longer
    /// approach along the impact's normal (within 1% of the approach speed); without an impact,
    /// the last one before the contact impulse fell to twice what the weights give in a step.
    pub impulsive_end: Option<Arc<Snapshot>>,
    /// Whether the contact still pushed (any normal impulse) in the step after `impulsive_end`:
    /// the body then rests on its partner and is not carried back at g, as the `restitution`
    /// check's bracket judges it (None until that step is seen).
    pub pushing_after_impulse: Option<bool>,
    /// The pair's flight from the level's start, while both have flown free since it: the
    /// impact's pre-impact state in closed form (`free_flight`).
    flight: FlightFromStart,
}

impl PairTracker {
    pub fn new(body: &str, other: Option<&str>) -> Self {
        PairTracker {
            body: body.to_string(),
            other: other.map(str::to_string),
            indices: None,
            phase: ContactPhase::Before,
            quiet_samples: 0,
            peak: 0.0,
            contact_impulse: 0.0,
            weight_impulse: 0.0,
            contact_vector: DVec2::ZERO,
            normal_into_body: None,
            impulsive_end: None,
            pushing_after_impulse: None,
            pre: None,
            impact: None,
            release: None,
            flight: FlightFromStart::default(),
        }
    }

    /// Follows the pair to the sample `f`; the event the sample is, if any.
    pub fn update(&mut self, f: &Sample, facts: &LevelFacts) -> Option<PairEvent> {
        if self.indices.is_none() {
            let b = f.cur.body_index(&self.body)?;
            let o = match &self.other {
                Some(o) => Some(f.cur.body_index(o)?),
                None => None,
            };
            self.indices = Some((b, o));
        }
        let (b, o) = self.indices?;
        if let Some(p) = f.prev.filter(|p| p.step == 0) {
            self.flight.follow(p, (b, o), facts);
        }
        let j = pair_normal_impulse(f.cur, b, o, None);
        // "Pushing": a normal impulse above a millionth of the largest one of this contact, so that
        // round-off and position correction between bodies left resting together do not count.
        let touching = j > 1e-6 * self.peak.max(f64::MIN_POSITIVE) && j > 0.0;
        let weight = |i: usize| f.cur.bodies[i].mass * f.cur.gravity.length();
        let weights_step = (weight(b) + o.map_or(0.0, weight)) * f.cur.dt;
        if touching && !matches!(self.phase, ContactPhase::Released | ContactPhase::Again) {
            self.contact_impulse += j;
            self.weight_impulse += weights_step;
            self.add_vector(f.cur, b, o);
        }
        let event = match self.phase {
            ContactPhase::Before if touching => {
                self.phase = ContactPhase::Touching;
                self.peak = j;
                self.pre = f.prev.cloned();
                if let Some(pre) = f.prev {
                    self.impact = Impact::find(facts, pre, f.cur, b, o);
                    // The solution's states from the flight's closed form where there is one;
                    // the touching instant, point and normal stay the engine's, which its own
                    // e and impulses are read at.
                    let exact = self.flight.exact(pre, (b, o));
                    let solved = exact.and_then(|x| Impact::find(facts, &x, f.cur, b, o));
                    if let (Some(imp), Some(x)) = (self.impact.as_mut(), solved) {
                        imp.pre = x.pre;
                        imp.post = x.post;
                    }
                }
                Some(PairEvent::Touch)
            }
            ContactPhase::Touching => {
                self.peak = self.peak.max(j);
                if touching {
                    None
                } else {
                    self.phase = ContactPhase::Quiet;
                    self.quiet_samples = 1;
                    self.release = Some(f.cur.clone());
                    Some(PairEvent::Quiet)
                }
            }
            ContactPhase::Quiet => {
                if touching {
                    self.phase = ContactPhase::Touching;
                    self.peak = self.peak.max(j);
                    self.release = None;
                    Some(PairEvent::Resumed)
                } else {
                    self.quiet_samples += 1;
                    let quiet_for =
                        f.cur.time - self.release.as_ref().map_or(f.cur.time, |r| r.time);
                    if self.quiet_samples >= QUIET_STEPS && quiet_for >= QUIET_TIME {
                        self.phase = ContactPhase::Released;
                        Some(PairEvent::Released)
                    } else {
                        None
                    }
                }
            }
            ContactPhase::Released if touching => {
                self.phase = ContactPhase::Again;
                Some(PairEvent::Again)
            }
            _ => None,
        };
        if self.pushing_after_impulse.is_none()
            && self
                .impulsive_end
                .as_ref()
                .is_some_and(|e| e.time < f.cur.time)
        {
            self.pushing_after_impulse = Some(j > 0.0);
        }
        // Checked from the touch on, the touch's own step included: rapier often completes an
        // impact within that one step.
        if self.phase != ContactPhase::Before && self.impulsive_end.is_none() {
            if let Some(imp) = &self.impact {
                // The impact is over once the bodies no longer approach along its normal: then
                // they move together (e = 0) or apart (the restitution phase is done).
                let rel = |x: &Snapshot| {
                    let v = |i: usize| body_point_velocity(&x.bodies[i], imp.point);
                    (v(imp.i2) - v(imp.i1)).dot(imp.normal)
                };
                let approach = rel(self.pre.as_deref().unwrap_or(f.cur));
                if rel(f.cur) >= -1e-2 * approach.abs() {
                    self.impulsive_end = Some(f.cur.clone());
                }
            } else if j <= 2.0 * weights_step {
                self.impulsive_end = f.prev.cloned();
            }
        }
        self.flight.follow(f.cur, (b, o), facts);
        event
    }

    /// Why the state at the end of the contact is not the impact's post-impact state, when it is
    /// not: over the contact the pair's weights delivered more than a tenth of the contact's own
    /// normal impulse, so forces other than the impact's shaped the motion while it lasted (a body
    /// pushed along a wall, a ladder sliding off it). In a real impact the contact impulse
    /// dominates: a ball dropped 1 m onto the floor with e = 0.5 takes a contact impulse 6.6 m
    /// (or more) against m g over a contact of a few steps, a ratio below 0.05.
    pub fn not_impulsive(&self) -> Option<String> {
        (self.weight_impulse > 0.1 * self.contact_impulse).then(|| {
            format!(
                "no impact analysis: the contact was not impulsive (over it the weights delivered {:.3e} N s against the contact's {:.3e} N s), so its end is not a post-impact state; the answer is graded on the engine alone",
                self.weight_impulse, self.contact_impulse
            )
        })
    }

    /// The normal impulse the contact has transmitted since the touch, N s.
    pub fn contact_impulse(&self) -> f64 {
        self.contact_impulse
    }

    /// The whole impulse (normal and friction) the contact has given `body` since the touch,
    /// N s, and the contact's normal into `body` (None before the touch).
    pub fn contact_vector(&self) -> (DVec2, Option<DVec2>) {
        (self.contact_vector, self.normal_into_body)
    }

    /// Adds the step's contact impulse on body b from o (from any body when None).
    fn add_vector(&mut self, s: &Snapshot, b: usize, o: Option<usize>) {
        let mut others: Vec<usize> = match o {
            Some(o) => vec![o],
            None => s
                .contacts
                .iter()
                .filter_map(|c| {
                    (c.body1 == b)
                        .then_some(c.body2)
                        .or((c.body2 == b).then_some(c.body1))
                })
                .collect(),
        };
        // A pair with several manifolds appears once: pair_contact sums them all.
        others.sort_unstable();
        others.dedup();
        for k in others {
            // pair_contact(s, k, b): the normal from k into b and the impulse on b.
            if let Some(c) = pair_contact(s, k, b) {
                self.contact_vector += c.impulse_on_b;
                self.normal_into_body.get_or_insert(c.normal);
            }
        }
    }

    /// The contact has ended (or is quiet and may be ending at the end of the run).
    pub fn ended(&self) -> bool {
        matches!(
            self.phase,
            ContactPhase::Quiet | ContactPhase::Released | ContactPhase::Again
        )
    }
}
