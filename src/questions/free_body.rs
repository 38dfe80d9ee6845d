//! The engine's free-body diagram as the questions read it: the external impulse on a body over
//! a step (PL-1), Newton-Euler centered on a sample (6/1), and the impulse a joint passes to the
//! bodies on one side of it (IM-3).
//!
//! One step's diagram is `analysis::kinetics::free_body`, the one the checks use (with the
//! solver's lever arms for contacts and joints).

use super::sample::Sample;
use super::snapshot_reading::is_massive;
use crate::analysis::kinetics::{self, Before};
use crate::analysis::Motion;
use crate::level::Coordinate;
use crate::snapshot::Snapshot;
use glam::DVec2;

/// Newton-Euler from the engine's free-body diagram, centered on the sample:
/// (sum F / m, sum M_G / I_G) over the two steps around it (6/1).
pub(super) fn newton_euler(f: &Sample, i: usize) -> Option<(DVec2, f64)> {
    let mut pairs = Vec::new();
    if let Some(p) = f.prev {
        pairs.push((p, f.cur));
    }
    if let Some(n) = f.next {
        pairs.push((f.cur, n));
    }
    let (mut j, mut m, mut t) = (DVec2::ZERO, 0.0, 0.0);
    for (a, b) in pairs {
        if b.is_initial() {
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

/// The external impulse on body i over the step from `a` to `b` and its angular impulse about G:
/// the free-body diagram of `analysis::kinetics` (PL-1, 6/1), with the solver's lever arms.
fn external_impulse(a: &Snapshot, b: &Snapshot, i: usize) -> (DVec2, f64) {
    let before = Motion::from(&a.bodies[i]);
    let (mut j, mut m) = (DVec2::ZERO, 0.0);
    for imp in kinetics::free_body(Before::One(i, &before), b, i, b.substeps) {
        j += imp.impulse;
        m += imp.moment_about_g();
    }
    (j, m)
}

/// The impulse joint k gave the bodies on its `moving` side over the step from `prev` to `s`:
/// their momentum change minus every other external impulse on them (gravity, loads, springs,
/// events, contacts and other joints reaching outside the group), IM-3.
pub(super) fn side_impulse(prev: &Snapshot, s: &Snapshot, k: usize, moving: usize) -> DVec2 {
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
        for &(_, coord, ratio) in c.terms.iter().filter(|t| side[t.0]) {
            match coord {
                Coordinate::X => j.x -= ratio * c.impulse,
                Coordinate::Y => j.y -= ratio * c.impulse,
                Coordinate::Angle => {}
            }
        }
    }
    j
}
