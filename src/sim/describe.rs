//! The engine-free description of what each engine builds and when it applies an event, in
//! plain f64 from the level: rapier's world (`sim/build.rs`, `sim/step/forces.rs`) and Box2D's
//! (`sim/box2d/build.rs`, `sim/box2d/step.rs`) both call these, so the two engines are handed
//! the same scene by one rule, and only the conversion to each engine's types is written twice.
//! Compiled once (both rapier precisions and Box2D share it).

use crate::level::{BodyDef, Effect, EventDef, JointDef, Part, Shape, V2};
use crate::sim::options::Effects;

/// An impulse event that falls in a step: its name, body, point (body frame, m), impulse
/// (world axes, N s) and angular impulse (N m s).
pub struct DueImpulse<'a> {
    pub name: &'a str,
    pub body: &'a str,
    pub point: V2,
    pub impulse: V2,
    pub angular: f64,
}

/// The level's impulse events that act at the start of the step [t0, t0 + dt): those whose
/// time falls in [t0 - dt / 2, t0 + dt / 2), so that each acts at the start of the step that
/// begins nearest to its time, once.
pub fn impulses_due(events: &[EventDef], t0: f64, dt: f64) -> impl Iterator<Item = DueImpulse<'_>> {
    events.iter().filter_map(move |e| match e {
        EventDef::Impulse {
            name,
            at,
            body,
            point,
            impulse,
            angular,
        } if *at >= t0 - 0.5 * dt && *at < t0 + 0.5 * dt => Some(DueImpulse {
            name,
            body,
            point: *point,
            impulse: *impulse,
            angular: *angular,
        }),
        _ => None,
    })
}

/// A body's surface as both engines build it: its friction and restitution coefficients where
/// the level declares the effect, else 0 (a pair then uses the larger of its two bodies'
/// values, on both engines).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Surface {
    pub friction: f64,
    pub restitution: f64,
}

/// [`Surface`] of a body under the run's effects.
pub fn surface(b: &BodyDef, fx: &Effects) -> Surface {
    let on = |e: Effect, v: Option<f64>| if fx.has(e) { v.unwrap_or(0.0) } else { 0.0 };
    Surface {
        friction: on(Effect::Friction, b.friction),
        restitution: on(Effect::Restitution, b.restitution),
    }
}

/// A body's linear and angular damping coefficients, 1/s: the level's where `damping` is
/// declared, else none.
pub fn damping(b: &BodyDef, fx: &Effects) -> (f64, f64) {
    if fx.has(Effect::Damping) {
        (
            b.linear_damping.unwrap_or(0.0),
            b.angular_damping.unwrap_or(0.0),
        )
    } else {
        (0.0, 0.0)
    }
}

/// A joint's two local frames, each an anchor in its body's frame (m) and an angle (rad).
/// Frame 1 carries the joint's axis as its x axis; frame 2 is turned so that both frames
/// coincide in the level's initial configuration (a weld and a slider keep the bodies' relative
/// angle).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointFrames {
    pub anchor1: V2,
    pub angle1: f64,
    pub anchor2: V2,
    pub angle2: f64,
}

/// [`JointFrames`] of joint `j` between bodies `b1` and `b2`.
pub fn joint_frames(j: &JointDef, b1: &BodyDef, b2: &BodyDef) -> JointFrames {
    let n = j.axis.0.hypot(j.axis.1);
    let axis_angle = (j.axis.1 / n).atan2(j.axis.0 / n);
    JointFrames {
        anchor1: j.anchor1,
        angle1: axis_angle,
        anchor2: j.anchor2,
        angle2: axis_angle + b1.angle - b2.angle,
    }
}

/// One leaf of a compound shape: a shape that is not a compound, placed in the body frame at
/// `offset` (m) turned by `angle` (rad).
pub struct Leaf<'a> {
    pub offset: V2,
    pub angle: f64,
    pub shape: &'a Shape,
}

/// A compound's parts flattened into leaves, nested compounds' poses composed (a part's pose
/// is in its parent compound's frame).
pub fn leaves(parts: &[Part]) -> Vec<Leaf<'_>> {
    let mut out = Vec::new();
    flatten(parts, ((0.0, 0.0), 0.0), &mut out);
    out
}

fn flatten<'a>(parts: &'a [Part], base: (V2, f64), out: &mut Vec<Leaf<'a>>) {
    let ((bx, by), ba) = base;
    let (s, c) = ba.sin_cos();
    for p in parts {
        let (x, y) = p.offset;
        let offset = (bx + c * x - s * y, by + s * x + c * y);
        let angle = ba + p.angle;
        match &p.shape {
            Shape::Compound { parts } => flatten(parts, (offset, angle), out),
            shape => out.push(Leaf {
                offset,
                angle,
                shape,
            }),
        }
    }
}
