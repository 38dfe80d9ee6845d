//! The engine's free-body diagram as the questions read it: analysis's diagram
//! (`analysis::kinetics::for_each_external_impulse`, the one the checks read), summed for
//! Newton-Euler centered on a sample (6/1) and for the impulse a joint passes to the bodies on
//! one side of it (IM-3). Contact moments use the solver's lever arms (`ContactPoint::arms`).

use super::sample::Sample;
use super::snapshot_reading::is_massive;
use crate::analysis::kinetics::{for_each_external_impulse, Before, Source};
use crate::analysis::links::joined_bodies;
use crate::analysis::Motion;
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
/// the sums of body i's free-body diagram (PL-1).
fn external_impulse(a: &Snapshot, b: &Snapshot, i: usize) -> (DVec2, f64) {
    let start = Motion::from(&a.bodies[i]);
    let (mut j, mut m) = (DVec2::ZERO, 0.0);
    for_each_external_impulse(
        Before::One(i, &start),
        b,
        b.substeps,
        |k| k == i,
        |s| {
            j += s.impulse;
            m += s.moment_about_g();
        },
    );
    (j, m)
}

/// The angular impulse about the fixed world point `o` of body i's free-body diagram over the
/// step from `a` to `b`: each impulse's moment about O at its point of application (6/17).
pub(super) fn external_moment_about(a: &Snapshot, b: &Snapshot, i: usize, o: DVec2) -> f64 {
    let start = Motion::from(&a.bodies[i]);
    let mut m = 0.0;
    for_each_external_impulse(
        Before::One(i, &start),
        b,
        b.substeps,
        |k| k == i,
        |s| m += s.moment_about(o),
    );
    m
}

/// The contact force body i's motion needs from body o, centered on the sample: its momentum
/// change over the two steps around it minus every other impulse of its free-body diagram
/// (gravity, loads, springs, events), over their time (6/1). None where that is not the
/// contact's force alone: a body without mass, or one that another contact, a joint or a
/// coupling also holds.
pub(super) fn contact_needed(f: &Sample, i: usize, o: usize) -> Option<DVec2> {
    // Over the quantity's window when it has one (its steps, from its first snapshot to its
    // last), else over the two steps around the sample.
    let (prev, next, steps): (&Snapshot, &Snapshot, Vec<&Snapshot>) = if f.window.len() > 2 {
        let w = f.window;
        (
            &w[0],
            &w[w.len() - 1],
            w[1..].iter().map(|x| &**x).collect(),
        )
    } else {
        (f.prev?, f.next?, vec![&**f.cur, &**f.next?])
    };
    let body = &f.cur.bodies[i];
    if !is_massive(body) {
        return None;
    }
    let mut known = DVec2::ZERO;
    for b in steps {
        if b.is_initial() {
            return None;
        }
        let mut held_otherwise = false;
        for_each_external_impulse(
            Before::All(&[]),
            b,
            b.substeps,
            |k| k == i,
            |s| match s.source {
                Source::Contact { .. } if s.other == Some(o) => {}
                Source::Contact { .. } | Source::Joint(_) | Source::Coupling(..) => {
                    held_otherwise = true
                }
                _ => known += s.impulse,
            },
        );
        if held_otherwise || b.joints.iter().any(|j| j.body1 == i || j.body2 == i) {
            return None;
        }
    }
    let t = next.time - prev.time;
    (t > 0.0).then(|| (body.mass * (next.bodies[i].velocity - prev.bodies[i].velocity) - known) / t)
}

/// The impulse joint k gave the bodies on its `moving` side over the step from `prev` to `s`:
/// their momentum change minus every other external impulse on them (gravity, loads, springs,
/// events, contacts and other joints reaching outside the group), IM-3.
pub(super) fn side_impulse(prev: &Snapshot, s: &Snapshot, k: usize, moving: usize) -> DVec2 {
    // The bodies joined to `moving` through joints other than k (bodies with mass only).
    let side = joined_bodies(
        s.bodies.len(),
        [moving],
        s.joints
            .iter()
            .enumerate()
            .filter(|&(q, _)| q != k)
            .map(|(_, j)| (j.body1, j.body2)),
        |_| true,
        |b| is_massive(&s.bodies[b]),
    );
    let mut j = DVec2::ZERO;
    for (i, b) in s.bodies.iter().enumerate().filter(|&(i, _)| side[i]) {
        j += b.mass * (b.velocity - prev.bodies[i].velocity);
    }
    // Only the sum of impulses is read, so the start-of-step poses (for moments) are not needed.
    for_each_external_impulse(
        Before::All(&[]),
        s,
        s.substeps,
        |i| side[i],
        |imp| {
            if imp.source != Source::Joint(k) {
                j -= imp.impulse;
            }
        },
    );
    j
}
