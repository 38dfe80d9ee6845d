//! Periods of oscillation: a body swinging on a pivot, a body on springs.
//!
//! The engine's period is the mean time between successive zero crossings of the same
//! direction of the body's velocity (angular for a pendulum, along the spring for a spring
//! mass), i.e. between its extremes; the analyses are the exact large-amplitude pendulum period
//! (PL-5 with the elliptic integral) and 2 pi sqrt(m / k).

use super::meter::{EngineAndAnalysis, Meter};
use super::sample::Sample;
use super::snapshot_reading::joint_index;
use crate::analysis::closed_forms::{pendulum_period, reduced_mass, spring_mass_period};
pub(super) use crate::analysis::oscillation::Crossings;
use crate::level::Quantity;
use crate::snapshot::Snapshot;
use glam::DVec2;

/// Follows the oscillating velocity over the step from `prev` to `s`.
pub(super) fn advance(m: &mut Meter, prev: &Snapshot, s: &Snapshot) {
    match &m.q {
        Quantity::PendulumPeriod { body, .. } => {
            if let Some(i) = m.body_index(s, body) {
                if m.crossings.is_empty() {
                    m.crossings.add(prev.time, prev.bodies[i].omega);
                }
                m.crossings.add(s.time, s.bodies[i].omega);
            }
        }
        Quantity::SpringPeriod(body) => {
            if let Some(i) = m.body_index(s, body) {
                // The rate the spring stretches at, along its axis: the body's velocity, less the
                // partner's when both ends are free (a pair drifting on a floor oscillates about
                // its moving mass center, and a body's own velocity may never turn back).
                let rate = |snap: &Snapshot, a: DVec2, partner: Option<usize>| {
                    let v = snap.bodies[i].velocity
                        - partner.map_or(DVec2::ZERO, |j| snap.bodies[j].velocity);
                    v.dot(a)
                };
                if m.spring_axis.is_none() {
                    let init: &Snapshot = m.init.as_deref().unwrap_or(prev);
                    let sp = init
                        .springs
                        .iter()
                        .find(|x| !x.torsion && (x.body1 == i || x.body2 == Some(i)));
                    m.spring_axis = sp.map(|x| (x.point2 - x.point1).normalize_or(DVec2::X));
                    m.spring_partner = spring_partner(init, i);
                    if let Some(a) = m.spring_axis {
                        m.crossings.add(prev.time, rate(prev, a, m.spring_partner));
                    }
                }
                if let Some(a) = m.spring_axis {
                    m.crossings.add(s.time, rate(s, a, m.spring_partner));
                }
            }
        }
        _ => {}
    }
}

/// The quantity at the sample.
pub(super) fn read(m: &Meter, f: &Sample) -> Option<EngineAndAnalysis> {
    let s = f.cur;
    Some(match &m.q {
        Quantity::PendulumPeriod { body: b, joint } => {
            (m.crossings.period(), pendulum_theory(m, s, b, joint))
        }
        Quantity::SpringPeriod(b) => {
            let i = m.body_index(s, b)?;
            // Each spring's k = 2 V_e / x^2, from the first snapshot where it is stretched.
            let k: f64 = m
                .init
                .as_ref()?
                .springs
                .iter()
                .chain(&s.springs)
                .filter(|x| {
                    !x.torsion && (x.body1 == i || x.body2 == Some(i)) && x.extension.abs() > 1e-9
                })
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
            // Two free bodies on their springs: the relative motion, with the reduced mass.
            let mass = match m.spring_partner {
                Some(j) => reduced_mass(s.bodies[i].mass, s.bodies[j].mass),
                None => s.bodies[i].mass,
            };
            (
                m.crossings.period(),
                (k > 0.0).then(|| spring_mass_period(mass, k)),
            )
        }
        q => unreachable!("{q:?} is not a period"),
    })
}

/// The exact large-amplitude period of a body swinging about the joint's fixed anchor,
/// from the engine's initial state.
fn pendulum_theory(m: &Meter, s: &Snapshot, body: &str, joint: &str) -> Option<f64> {
    let i = m.body_index(s, body)?;
    let j = &s.joints[joint_index(s, joint)?];
    let o = if j.body2 == i { j.anchor1 } else { j.anchor };
    let b0 = &m.init.as_ref()?.bodies[i];
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

/// The free body at the other end of every spring of body i, when there is one and only one
/// (dynamic, neither jointed nor on another spring): then the pair's relative motion is a single
/// vibration of the reduced mass. None for a body on a spring to the ground (or on several).
fn spring_partner(s: &Snapshot, i: usize) -> Option<usize> {
    let ends = |x: &crate::snapshot::SpringState| -> Option<Option<usize>> {
        if x.torsion {
            return None;
        }
        match (x.body1 == i, x.body2) {
            (true, other) => Some(other),
            (false, Some(b)) if b == i => Some(Some(x.body1)),
            _ => None,
        }
    };
    let mut others = s.springs.iter().filter_map(ends);
    let j = others.next()??;
    if !others.all(|o| o == Some(j)) || s.bodies[j].mass <= 0.0 {
        return None;
    }
    let jointed = s.joints.iter().any(|x| x.body1 == j || x.body2 == j);
    let other_springs = s.springs.iter().any(|x| {
        !x.torsion && (x.body1 == j || x.body2 == Some(j)) && !(x.body1 == i || x.body2 == Some(i))
    });
    (!jointed && !other_springs).then_some(j)
}
