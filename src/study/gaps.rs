//! The published engine gaps (docs/known-gaps.md) a failing level's scene matches, found by
//! the scene's pattern (its bodies, joints, couplings and what its questions and checks read),
//! never by the level's name: the advice names them when no setting it tried passes, so a
//! teacher reads which limit it is and whether any setting gets past it (issue 41).
//!
//! Each pattern is the cause its known-gaps row gives, read from the level as written, so a
//! scene that does not hold it is not told it: a free ball bouncing on a fixed floor is not a
//! jointed body, nor one resting on a support.

use crate::level::shape::bounds;
use crate::level::{BodyDef, BodyKind, Effect, Level, Quantity, Shape, When};
use crate::report::KnownGapRef;
use glam::DVec2;

/// One published gap: a short stable id, its section's heading in docs/known-gaps.md, and whether
/// a setting gets past it (the row's "which settings help").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct KnownGap {
    pub id: &'static str,
    pub heading: &'static str,
    pub setting_gets_past: bool,
    /// What gets past it, or that nothing does, in the row's words.
    pub past: &'static str,
}

pub const JOINTED_RESTITUTION: KnownGap = KnownGap {
    id: "restitution-leaves-joints-out",
    heading: "A jointed body is bounced as if it were free",
    setting_gets_past: false,
    past: "no setting passes away from the center of percussion",
};

pub const RESTING_RESTITUTION: KnownGap = KnownGap {
    id: "restitution-leaves-resting-contact-out",
    heading: "A body resting on a support is bounced as if it were free",
    setting_gets_past: false,
    past: "no setting passes",
};

pub const ROUGH_ECCENTRIC_BOUNCE: KnownGap = KnownGap {
    id: "rough-eccentric-impact-bounce",
    heading: "An eccentric impact with friction gets too much normal impulse",
    setting_gets_past: false,
    past: "no setting passes with e > 0: rapier's restitution pass bounces the normal row \
           without friction",
};

pub const JOINT_STRIKE: KnownGap = KnownGap {
    id: "joint-strike-between-fixed-bodies",
    heading: "A body crossing from one fixed track body to another strikes the second's end",
    setting_gets_past: false,
    past: "no setting passes: build the track as one `Track` of pieces (docs/levels.md), \
           which has no end at its joints",
};

/// Every gap the advice can name, in the order it names them.
pub const ALL: [KnownGap; 4] = [
    JOINTED_RESTITUTION,
    RESTING_RESTITUTION,
    ROUGH_ECCENTRIC_BOUNCE,
    JOINT_STRIKE,
];

/// How close two bodies' boxes must be at the start for one to rest on the other, m: rapier's
/// soft contact sinks a resting body by 6.9e-5 m (docs/known-gaps.md), far inside this.
const TOUCH: f64 = 1e-3;

/// The gaps the scene of `level` matches: each at most once, in the order above
/// (deterministic).
pub fn matching(level: &Level) -> Vec<KnownGap> {
    let mut out = Vec::new();
    let pairs = impact_pairs(level);
    let bounce: Vec<_> = pairs
        .iter()
        .filter(|(a, b)| pair_restitution(level, a, b) > 0.0)
        .collect();
    if bounce
        .iter()
        .any(|(a, b)| jointed(level, a) || jointed(level, b))
    {
        out.push(JOINTED_RESTITUTION);
    }
    if bounce
        .iter()
        .any(|(a, b)| struck_while_resting(level, a, b) || struck_while_resting(level, b, a))
    {
        out.push(RESTING_RESTITUTION);
    }
    if bounce.iter().any(|(a, b)| {
        pair_friction(level, a, b) > 0.0
            && [a, b]
                .iter()
                .any(|n| !jointed(level, n) && body(level, n).is_some_and(eccentric))
    }) {
        out.push(ROUGH_ECCENTRIC_BOUNCE);
    }
    if fixed_tracks_meet(level) {
        out.push(JOINT_STRIKE);
    }
    out
}

/// The gaps as the report's JSON names them.
pub fn refs(gaps: &[KnownGap]) -> Vec<KnownGapRef> {
    gaps.iter()
        .map(|g| KnownGapRef {
            id: g.id.to_string(),
            heading: g.heading.to_string(),
            setting_gets_past: g.setting_gets_past,
        })
        .collect()
}

/// The sentence the advice adds for them.
pub fn sentence(gaps: &[KnownGap]) -> String {
    let each: Vec<_> = gaps
        .iter()
        .map(|g| format!("`{}` (\"{}\"): {}", g.id, g.heading, g.past))
        .collect();
    format!(
        "; the scene matches the published gap{} of docs/known-gaps.md {}",
        if gaps.len() == 1 { "" } else { "s" },
        each.join("; ")
    )
}

/// The pairs of bodies the level's questions and checks read an impact or contact of.
fn impact_pairs(level: &Level) -> Vec<(String, String)> {
    let mut out: Vec<(String, String)> = Vec::new();
    let mut add = |a: &str, b: &str| {
        let p = (a.to_string(), b.to_string());
        if !out.contains(&p) {
            out.push(p);
        }
    };
    for q in &level.questions {
        match &q.quantity {
            Quantity::ReboundHeight { body, other }
            | Quantity::Restitution { body, other }
            | Quantity::EnergyLost { body, other }
            | Quantity::ContactImpulse { body, other, .. } => add(body, other),
            _ => {}
        }
        if let When::FirstContact {
            body,
            other: Some(o),
        }
        | When::ContactEnds {
            body,
            other: Some(o),
        } = &q.at
        {
            add(body, o);
        }
    }
    for c in &level.checks {
        if let (Some(b), Some(o)) = (&c.body, &c.other) {
            if matches!(c.kind, crate::level::CheckKind::Restitution) {
                add(b, o);
            }
        }
    }
    out
}

fn body<'a>(level: &'a Level, name: &str) -> Option<&'a BodyDef> {
    level.bodies.iter().find(|b| b.name == name)
}

/// The pair's coefficient: the larger of the two bodies' (rapier's rule, `BodyDef`), 0 without
/// the `restitution` effect.
fn pair_restitution(level: &Level, a: &str, b: &str) -> f64 {
    pair_coefficient(level, Effect::Restitution, a, b, |d| d.restitution)
}

/// As [`pair_restitution`] for friction.
fn pair_friction(level: &Level, a: &str, b: &str) -> f64 {
    pair_coefficient(level, Effect::Friction, a, b, |d| d.friction)
}

fn pair_coefficient(
    level: &Level,
    effect: Effect,
    a: &str,
    b: &str,
    of: impl Fn(&BodyDef) -> Option<f64>,
) -> f64 {
    if !level.effects.contains(&effect) {
        return 0.0;
    }
    [a, b]
        .iter()
        .filter_map(|n| body(level, n).and_then(&of))
        .fold(0.0, f64::max)
}

/// A moving body with a joint to anything.
fn jointed(level: &Level, name: &str) -> bool {
    level.effects.contains(&Effect::Joints)
        && body(level, name).is_some_and(|b| b.kind == BodyKind::Dynamic)
        && level
            .joints
            .iter()
            .any(|j| j.body1 == name || j.body2 == name)
}

/// A body whose contacts need not pass through its G: turning, and not a disc about G.
fn eccentric(b: &BodyDef) -> bool {
    b.kind == BodyKind::Dynamic
        && !b.lock_rotation
        && !matches!(b.shape, Some(Shape::Circle { .. }) | None)
}

/// `struck` (a moving body with no joint) lies at the start on a third body below it, and its
/// partner `by` starts above it, over it: it is struck or landed on into its support (n10_13a),
/// not met sideways on it (n10_13b, which the engine gets right). "Below" is along -y, the
/// default gravity's direction (a level that turns gravity is read as if it did not).
fn struck_while_resting(level: &Level, struck: &str, by: &str) -> bool {
    let (Some(s), Some(p)) = (body(level, struck), body(level, by)) else {
        return false;
    };
    if s.kind != BodyKind::Dynamic || jointed(level, struck) {
        return false;
    }
    let (Some(sb), Some(pb)) = (placed(s), placed(p)) else {
        return false;
    };
    // Above it: starting higher, over it (their spans across gravity overlap by more than a
    // touch, so a partner swinging in from the side, n5_16's bar, is not above it).
    let partner_above =
        pb.0 .1 >= sb.1 .1 - TOUCH && pb.1 .0.min(sb.1 .0) - pb.0 .0.max(sb.0 .0) > TOUCH;
    let on_support = level
        .bodies
        .iter()
        .filter(|o| o.name != struck && o.name != by)
        .filter_map(placed)
        .any(|ob| (ob.1 .1 - sb.0 .1).abs() <= TOUCH && ob.0 .0 < sb.1 .0 && ob.1 .0 > sb.0 .0);
    partner_above && on_support
}

fn placed(b: &BodyDef) -> Option<crate::level::shape::Aabb> {
    b.shape.as_ref().map(|s| bounds(s, b.position, b.angle))
}

/// A moving body in contact with a scene in which two fixed track bodies (segments, polylines,
/// arcs, tracks) continue one another: an end of one within [`TOUCH`] of an end of the other,
/// the two running on within 60 degrees of one line (a corner of a floor and a wall is not a
/// joint a body rides across). A body riding the first into its soft contact meets the second's
/// end there (n15_01's ramp `Arc` ending at the floor `Segment`'s end, n7_03's).
fn fixed_tracks_meet(level: &Level) -> bool {
    if !level.effects.contains(&Effect::Contacts)
        || !level.bodies.iter().any(|b| b.kind == BodyKind::Dynamic)
    {
        return false;
    }
    let ends: Vec<Vec<TrackEnd>> = level
        .bodies
        .iter()
        .filter(|b| b.kind == BodyKind::Fixed)
        .map(track_ends)
        .filter(|e| !e.is_empty())
        .collect();
    ends.iter().enumerate().any(|(i, a)| {
        ends[i + 1..].iter().any(|b| {
            a.iter().any(|(p, u)| {
                b.iter()
                    .any(|(q, w)| (*p - *q).length() <= TOUCH && u.dot(*w) < -0.5)
            })
        })
    })
}

/// Where a track ends (world) and the unit direction out past that end.
type TrackEnd = (DVec2, DVec2);

/// The ends of a fixed body's track: a segment's two, an open polyline's or a `Track`'s first
/// and last points, an arc's end points short of a full turn; none for other shapes.
fn track_ends(b: &BodyDef) -> Vec<TrackEnd> {
    let rot = DVec2::from_angle(b.angle);
    let at = DVec2::from(b.position);
    let out =
        |p: DVec2, beyond: DVec2| (at + rot.rotate(p), rot.rotate(beyond).normalize_or_zero());
    let line_ends = |first: DVec2, second: DVec2, before_last: DVec2, last: DVec2| {
        vec![out(first, first - second), out(last, last - before_last)]
    };
    let points = |ps: &[(f64, f64)]| -> Vec<TrackEnd> {
        let n = ps.len();
        if n < 2 {
            return Vec::new();
        }
        let d = |k: usize| DVec2::from(ps[k]);
        line_ends(d(0), d(1), d(n - 2), d(n - 1))
    };
    match &b.shape {
        Some(Shape::Segment { a, b }) => points(&[*a, *b]),
        Some(Shape::Polyline {
            points: ps,
            closed: false,
            ..
        }) => points(ps),
        Some(s @ Shape::Track { .. }) => {
            crate::level::curves::track_points(s).map_or_else(Vec::new, |(ps, _)| points(&ps))
        }
        Some(Shape::Arc {
            center,
            radius,
            start,
            end,
            ..
        }) if end - start < std::f64::consts::TAU - 1e-9 => {
            let c = DVec2::from(*center);
            let (s0, e0) = (DVec2::from_angle(*start), DVec2::from_angle(*end));
            // Past `start` the arc would run clockwise, past `end` counter-clockwise.
            vec![
                out(c + s0 * *radius, -s0.perp()),
                out(c + e0 * *radius, e0.perp()),
            ]
        }
        _ => Vec::new(),
    }
}
