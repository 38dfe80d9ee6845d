//! Impact quantities, about the first contact of a pair: the rebound height after it, the
//! coefficient of restitution across it, and the mechanical energy it takes.
//!
//! The engine's values are measured across the contact as `contact_events` delimits it (the
//! snapshot before the touch and the first one without force after it); the analyses are the
//! impulse-momentum solution of the impact (`impact_solution`, IM-9 to IM-14) and the
//! level's declared restitution.

use super::contact_events::{ContactPhase, PairEvent, PairTracker};
use super::contact_reading::contact_component;
use super::level_facts::LevelFacts;
use super::meter::{EngineAndAnalysis, Meter};
use super::sample::Sample;
use super::snapshot_reading::{body_mechanical_energy, height, is_massive};
use crate::analysis::energy::body_kinetic_energy;
use crate::analysis::touching::{carried_back_at, free_acceleration, impact_at_touch, ReadAt};
use crate::analysis::Motion;
use crate::level::{ContactComponent, Quantity};
use crate::snapshot::Snapshot;
use glam::DVec2;

/// What an impact quantity accumulates over the run.
#[derive(Clone)]
pub(super) struct State {
    /// The pair the quantity is about.
    pub pair: Option<PairTracker>,
    /// Highest mass center since the contact went quiet (rebound height), m.
    pub rebound_apex: f64,
}

impl State {
    pub fn new(q: &Quantity) -> Self {
        State {
            pair: pair_tracker(q),
            rebound_apex: f64::NEG_INFINITY,
        }
    }

    /// Follows the pair over the step that led to the sample: what it did then.
    pub fn follow_pair(&mut self, f: &Sample, facts: &LevelFacts) -> Option<PairEvent> {
        self.pair.as_mut().and_then(|p| p.update(f, facts))
    }
}

/// The tracker of the pair an impact quantity is about (None for other quantities).
fn pair_tracker(q: &Quantity) -> Option<PairTracker> {
    match q {
        Quantity::ReboundHeight { body, other }
        | Quantity::Restitution { body, other }
        | Quantity::EnergyLost { body, other }
        | Quantity::ContactImpulse { body, other, .. } => Some(PairTracker::new(body, Some(other))),
        _ => None,
    }
}

/// Follows the rebound's apex over the step that led to `s` (`event`: what the pair did then).
pub(super) fn advance(m: &mut Meter, st: &mut State, s: &Snapshot, event: Option<PairEvent>) {
    if m.inapplicable.is_none() {
        m.inapplicable = not_applicable(m, st, s);
    }
    if let Quantity::ReboundHeight { body, .. } = &m.q {
        if let Some(i) = m.body_index(s, body) {
            let phase = st.pair.as_ref().map_or(ContactPhase::Before, |p| p.phase);
            // A flicker of the contact: the flight has not begun yet.
            if event == Some(PairEvent::Resumed) {
                st.rebound_apex = f64::NEG_INFINITY;
            }
            if matches!(phase, ContactPhase::Quiet | ContactPhase::Released) {
                st.rebound_apex = st.rebound_apex.max(height(s.gravity, s.bodies[i].com));
            }
        }
    }
}

/// Why the analysis of an impact quantity does not apply to the scene, if it does not: the
/// impact solution left out another contact in the impact's step (`ReboundHeight`, `EnergyLost`
/// and `ContactImpulse` read its post-impact state), or, for `ReboundHeight`, the body does not
/// fly free under gravity alone after the contact (y_c + v'^2 / (2 g) is a projectile's apex):
/// a joint, a spring, a coupling, a load or damping acts on it.
fn not_applicable(m: &Meter, st: &State, s: &Snapshot) -> Option<String> {
    if matches!(m.q, Quantity::Restitution { .. }) {
        return None;
    }
    if let Some(why) = st
        .pair
        .as_ref()
        .and_then(|p| p.impact.as_ref())
        .and_then(|imp| imp.left_out.clone())
    {
        return Some(why);
    }
    let Quantity::ReboundHeight { body, .. } = &m.q else {
        return None;
    };
    let i = m.body_index(s, body)?;
    let facts = &m.facts;
    let what = if let Some(j) = facts.joints.iter().find(|j| j.body1 == i || j.body2 == i) {
        format!("joint \"{}\" holds it", j.name)
    } else if let Some(sp) = facts.springs.iter().find(|x| x.holds(i)) {
        format!("spring \"{}\" pulls on it", sp.name)
    } else if let Some(c) = s
        .couplings
        .iter()
        .find(|c| c.terms.iter().any(|t| t.0 == i))
    {
        format!("coupling \"{}\" holds it", c.name)
    } else if let Some(l) = s.loads.iter().find(|l| l.body == i) {
        format!("load \"{}\" acts on it", l.name)
    } else if facts.bodies.get(i).is_some_and(|x| x.damped) {
        "it is damped".to_string()
    } else {
        return None;
    };
    Some(format!(
        "body \"{body}\" does not fly free after the contact ({what}): the rebound height y_c + v'^2 / (2 g) (IM-13) is the apex of a body under gravity alone"
    ))
}

/// Why an impact quantity has no engine value at the end of the run, when the pair says: it
/// never touched, its first contact was not an impact, or the contact never let go.
pub(super) fn why_missing(m: &Meter, st: &State) -> Option<String> {
    let p = st.pair.as_ref()?;
    Some(match (&m.q, p.phase) {
        (_, ContactPhase::Before) => "the two bodies never touched in the run".into(),
        (Quantity::Restitution { .. } | Quantity::EnergyLost { .. }, _) if p.impact.is_none() => {
            "the first contact was not an impact (the bodies were not approaching when they touched)".into()
        }
        (Quantity::Restitution { .. }, _) if p.release.is_none() && p.impulsive_end.is_none() => {
            "the contact lasts to the end of the run and the bodies never stopped approaching: e needs the state after the impact's compression ends (a lasting contact's impulse and energy are ContactImpulse and EnergyLost)".into()
        }
        (Quantity::ReboundHeight { .. }, _) if p.release.is_none() => {
            "the contact lasts to the end of the run: this needs the state after the bodies part (a lasting contact's impulse and energy are ContactImpulse and EnergyLost)".into()
        }
        _ => return None,
    })
}

/// The quantity at the sample.
pub(super) fn read(m: &Meter, st: &State, f: &Sample) -> Option<EngineAndAnalysis> {
    let s = f.cur;
    let p = st.pair.as_ref();
    Some(match &m.q {
        Quantity::ReboundHeight { body: b, .. } => {
            let i = m.body_index(s, b)?;
            let p = p?;
            let engine = if p.ended() { st.rebound_apex } else { f64::NAN };
            // The apex of free flight from the state right after the impact (IM-13).
            let analysis = p.impact.as_ref().map(|imp| {
                let post = &imp.post[i];
                let g = s.gravity.length();
                let up = if g > 0.0 {
                    -post.velocity.dot(s.gravity / g)
                } else {
                    0.0
                };
                height(s.gravity, post.com) + up.max(0.0).powi(2) / (2.0 * g)
            });
            (engine, analysis)
        }
        Quantity::Restitution { .. } => {
            let p = p?;
            let imp = p.impact.as_ref()?;
            // After: the end of the impulsive phase (the bodies no longer approach), as the
            // `restitution` check's bracket ends; else where the contact let go.
            let (pre, post) = (
                p.pre.as_ref()?,
                p.impulsive_end.as_ref().or(p.release.as_ref())?,
            );
            // Both brought to the touching instant as the check brings them
            // (`analysis::touching::impact_at_touch`): before at g while free, after at g only
            // while free and no longer pushed by the partner.
            // Resting on the partner after it: the contact pushed on in the next step (as the
            // check's bracket judges it; unknown at the run's end, taken as resting).
            let pushing = if p.impulsive_end.is_some() {
                p.pushing_after_impulse.unwrap_or(true)
            } else {
                false
            };
            let motion = |snap: &Snapshot, i: usize| Motion::from(&snap.bodies[i]);
            let (m_pre, m_post) = (
                [motion(pre, imp.i1), motion(pre, imp.i2)],
                [motion(post, imp.i1), motion(post, imp.i2)],
            );
            let before = |k: usize, i: usize| ReadAt {
                motion: &m_pre[k],
                time: pre.time,
                acc: if imp.free[i] {
                    free_acceleration(pre, i)
                } else {
                    DVec2::ZERO
                },
            };
            let after = |k: usize, i: usize| ReadAt {
                motion: &m_post[k],
                time: post.time,
                acc: carried_back_at(imp.free[i], pushing, free_acceleration(post, i)),
            };
            let e = impact_at_touch(
                imp.t_c,
                [before(0, imp.i1), before(1, imp.i2)],
                [after(0, imp.i1), after(1, imp.i2)],
                imp.point,
                imp.normal,
                DVec2::ZERO,
            )
            .e;
            (e, Some(m.facts.restitution(imp.i1, imp.i2)))
        }
        Quantity::EnergyLost { body: b, other } => {
            let (i, o) = (m.body_index(s, b)?, m.body_index(s, other)?);
            let p = p?;
            // After the impact: where the contact let go, or, for a contact that lasts (it never
            // ends, or forces other than the impact's worked while it lasted), the end of its
            // impulsive phase, so the work done after the blow (a pile in sand) is not counted.
            let lasting = p.release.is_none() || p.not_impulsive().is_some();
            let post = if lasting {
                p.impulsive_end.as_ref()
            } else {
                p.release.as_ref()
            };
            let (pre, post) = (p.pre.as_ref()?, post?);
            // T + V_g of the pair and V_e of the springs on either: a spring that holds a
            // struck body stores energy over the read interval that the impact did not take
            // (n14_18: 1/2 k x^2 = 5e-4 J of 0.48 J booked as lost before).
            let e = |snap: &Snapshot| {
                let bodies: f64 = [i, o]
                    .iter()
                    .filter(|&&k| is_massive(&snap.bodies[k]))
                    .map(|&k| body_mechanical_energy(snap.gravity, &snap.bodies[k]))
                    .sum();
                let on_pair = |k: usize| k == i || k == o;
                let elastic: f64 = snap
                    .springs
                    .iter()
                    .filter(|x| on_pair(x.body1) || x.body2.is_some_and(on_pair))
                    .map(|x| x.energy)
                    .sum();
                bodies + elastic
            };
            let analysis = p.impact.as_ref().map(|imp| {
                [i, o]
                    .iter()
                    .map(|&k| body_kinetic_energy(&imp.pre[k]) - body_kinetic_energy(&imp.post[k]))
                    .sum::<f64>()
            });
            (e(pre) - e(post), analysis)
        }
        Quantity::ContactImpulse {
            body: b, component, ..
        } => {
            let i = m.body_index(s, b)?;
            let p = p?;
            // The impact solution's impulse on the body, m (v' - v), when nothing else acts on
            // it impulsively (no joint), as the same component as the engine's value.
            let jointed = s.joints.iter().any(|j| j.body1 == i || j.body2 == i);
            let (vector, n) = p.contact_vector();
            let solved = p
                .impact
                .as_ref()
                .filter(|_| !jointed && p.not_impulsive().is_none())
                .map(|imp| {
                    let into = if imp.i2 == i { imp.normal } else { -imp.normal };
                    (
                        imp.pre[i].mass * (imp.post[i].velocity - imp.pre[i].velocity),
                        into,
                    )
                });
            if *component == ContactComponent::Normal {
                // The sum of the normal impulses since the touch (the normal may turn while the
                // contact lasts); its analysis the solution's normal part, m |(v' - v) . n|.
                let analysis = solved.map(|(j, into)| j.dot(into).abs());
                (p.contact_impulse(), analysis)
            } else {
                let n = n?;
                let analysis = solved.map(|(j, into)| contact_component(*component, j, into));
                (contact_component(*component, vector, n), analysis)
            }
        }
        q => unreachable!("{q:?} is not an impact quantity"),
    })
}
