//! `ContactForceFrom` on a fixed circular track (`Shape::Arc`): the textbook's normal force on a
//! curve from the state at the instant, N = m v^2 / rho + m g cos(theta) inside the circle and
//! m g cos(theta) - m v^2 / rho outside it (`analysis::curved_path`, PN-2), rho the radius of
//! G's path (R - r inside, R + r outside for a disc of radius r).
//!
//! It is the analysis of the `Normal` component, and of `Magnitude`, `X` and `Y` where the pair
//! has no friction (the whole force is then N along the radius), when the other body is a fixed
//! `Arc` and the body a disc (a `Circle`: G at its center, so the contact normal runs through G).
//! At each snapshot it reads it assumes, else "not applicable" with the reason: the disc touches
//! the arc on its circle (a contact with the track, G within 1% of rho from the arc's center,
//! within the arc's sweep, the engine's contact normal within a facet's turn or 0.02 rad of the
//! radius: not an end vertex), and only its weight and the track act on it (no joint, spring,
//! load, coupling, damping or other pushing contact). With a `window` the formula is averaged
//! over the window's snapshots (trapezoid), as the engine's impulses are; without one it is the
//! state at the sample. A `Polyline` track is not a circle: its own curvature is its facets',
//! so it keeps Newton's analysis over the window (`forces::contact_force_analysis`).

use super::contact_reading::{also_acting, contact_component};
use super::level_facts::ArcTrack;
use super::meter::Meter;
use super::sample::Sample;
use crate::analysis::curved_path::{disc_path_radius, normal_force_on_circular_path};
use crate::analysis::impact::pair_contact;
use crate::level::ContactComponent;
use crate::snapshot::Snapshot;
use glam::DVec2;

/// How far G may sit off its path's circle, relative to rho, and still ride it: rapier lets a
/// contact sink by up to 1 mm (its allowed linear error) and a faceted arc's chords straddle
/// the circle by half the chord error; a body on another track or flying misses by far more.
const OFF_CIRCLE: f64 = 1e-2;

/// The least angle, rad, by which the engine's contact normal may miss the radius through G:
/// a one-sided arc clamps the normal between its neighbouring facets' (within a facet's turn);
/// at an open arc's end vertex or on another part of the body it turns away.
const OFF_RADIUS: f64 = 2e-2;

/// The track and rho when the question's analysis is PN-2 on the arc's circle: `other` is a
/// fixed `Arc`, the body a disc that fits (rho > 0), and the component `Normal`, or a part of
/// the whole force where the pair has no friction.
fn path(m: &Meter, i: usize, o: usize, c: ContactComponent) -> Option<(ArcTrack, f64)> {
    let track = m.facts.bodies.get(o)?.arc?;
    let r = m.facts.bodies.get(i)?.disc?;
    let whole = matches!(
        c,
        ContactComponent::Magnitude | ContactComponent::X | ContactComponent::Y
    ) && m.facts.friction(i, o) == 0.0;
    if !(matches!(c, ContactComponent::Normal) || whole) {
        return None;
    }
    let rho = disc_path_radius(track.radius, r, track.side);
    (rho > 0.0).then_some((track, rho))
}

/// Why PN-2 on the arc's circle does not give body i's normal force at snapshot `x`; None
/// where it does. At the sample (`at_sample`) the pair must be in contact; at the other
/// snapshots of a window G on the circle suffices: a step may report no contact as the body
/// crosses from facet to facet (an empty manifold), and the engine's mean over the window
/// counts that step's zero impulse too.
fn breaks(
    m: &Meter,
    x: &Snapshot,
    i: usize,
    o: usize,
    track: &ArcTrack,
    rho: f64,
    at_sample: bool,
) -> Option<String> {
    if m.facts.bodies.get(i).is_some_and(|b| b.damped) {
        return Some("the body has damping, a force besides its weight and the track".into());
    }
    if let Some(what) = also_acting(x, i, o) {
        return Some(format!(
            "{what} acts on the body besides its weight and the track"
        ));
    }
    let contact = pair_contact(x, o, i);
    if contact.is_none() && at_sample {
        return Some("the body does not touch the track".into());
    }
    let d = x.bodies.get(i)?.com - track.center;
    if (d.length() - rho).abs() > OFF_CIRCLE * rho {
        return Some(format!(
            "G is {:.4} m from the arc's center, off its path's circle of radius {rho:.4} m",
            d.length()
        ));
    }
    if !track.spans(d) {
        return Some("G is beyond the arc's ends".into());
    }
    let radial = match track.side {
        crate::analysis::curved_path::PathSide::Inside => -d,
        crate::analysis::curved_path::PathSide::Outside => d,
    }
    .normalize_or_zero();
    let c = contact?;
    let off = crate::analysis::cross(radial, c.normal)
        .abs()
        .atan2(radial.dot(c.normal));
    let allowed = OFF_RADIUS.max(track.facet);
    (off > allowed).then(|| {
        format!(
            "the contact normal is {off:.3} rad off the radius through G (an end vertex of the arc, or another part of the body touches)"
        )
    })
}

/// The force PN-2 gives body i at snapshot `x`: N along its direction (m g the only other force).
fn formula(x: &Snapshot, i: usize, track: &ArcTrack, rho: f64) -> Option<DVec2> {
    let b = x.bodies.get(i)?;
    let (n, dir) = normal_force_on_circular_path(
        b.mass,
        b.com,
        b.velocity,
        track.center,
        rho,
        b.mass * x.gravity,
        track.side,
    )?;
    Some(n * dir)
}

/// Each sample, for a question whose analysis is PN-2 on an arc: whether the sample meets its
/// assumptions (`m.inapplicable` says why not, and is cleared where they hold). False for a
/// question PN-2 does not answer (the caller's analysis then applies).
pub(super) fn advance(
    m: &mut Meter,
    s: &Snapshot,
    i: usize,
    o: usize,
    c: ContactComponent,
) -> bool {
    let Some((track, rho)) = path(m, i, o, c) else {
        return false;
    };
    m.inapplicable = breaks(m, s, i, o, &track, rho, true).map(|why| {
        format!("the normal force on a circular path (PN-2, m v^2 / rho with rho = {rho:.4} m) assumes a disc riding the arc with only its weight besides: {why}")
    });
    true
}

/// The textbook's contact force on body i from the arc o as component `c` (n the engine's
/// contact normal into i at the sample), where PN-2 answers the question: None where it does
/// not (the caller's analysis applies), Some(None) where a snapshot it reads breaks its
/// assumptions.
pub(super) fn analysis(
    m: &Meter,
    f: &Sample,
    i: usize,
    o: usize,
    n: DVec2,
    c: ContactComponent,
) -> Option<Option<f64>> {
    let (track, rho) = path(m, i, o, c)?;
    let at = |x: &Snapshot| {
        if breaks(m, x, i, o, &track, rho, std::ptr::eq(x, &**f.cur)).is_some() {
            None
        } else {
            formula(x, i, &track, rho)
        }
    };
    let force = if f.window.len() > 2 {
        // The engine's reading is the mean of the window's steps, from its first snapshot to its
        // last: the formula's mean over the same time, by the trapezoid rule.
        let w = f.window;
        let (mut sum, mut span) = (DVec2::ZERO, 0.0);
        for k in 1..w.len() {
            let h = w[k].time - w[k - 1].time;
            match (at(&w[k - 1]), at(&w[k])) {
                (Some(a), Some(b)) => sum += 0.5 * h * (a + b),
                _ => return Some(None),
            }
            span += h;
        }
        (span > 0.0).then(|| sum / span)
    } else {
        at(f.cur)
    };
    Some(force.map(|v| contact_component(c, v, n)))
}
