//! A body placed inside another by a parameter's range: at a corner of the ranges, the center of
//! one colliding body's collider lies within another's shape, where at the nominal values it
//! does not (a block pushed into its incline by a large angle, a ball into a wall). Such a
//! start is blown apart by the overlap's correction, so the variant could not be graded.

use super::super::format::{BodyKind, Effect, Level};
use super::super::shape;
use glam::DVec2;

/// Pairs (outer, inner) of bodies that collide (contacts on, not joined, one of them dynamic)
/// where the inner one's collider center lies inside the outer one's shape.
pub fn inside_pairs(level: &Level) -> Vec<(String, String)> {
    if !level.effects.contains(&Effect::Contacts) {
        return Vec::new();
    }
    let joined = |a: &str, b: &str| {
        level
            .joints
            .iter()
            .any(|j| (j.body1 == a && j.body2 == b) || (j.body1 == b && j.body2 == a))
    };
    let mut out = Vec::new();
    for outer in &level.bodies {
        let Some(outer_shape) = &outer.shape else {
            continue;
        };
        let outline = shape::outline(outer_shape);
        let to_local = |p: DVec2| {
            DVec2::from_angle(-outer.angle)
                .rotate(p - DVec2::new(outer.position.0, outer.position.1))
        };
        for inner in &level.bodies {
            let Some(inner_shape) = &inner.shape else {
                continue;
            };
            let moving = outer.kind == BodyKind::Dynamic || inner.kind == BodyKind::Dynamic;
            if inner.name == outer.name || !moving || joined(&outer.name, &inner.name) {
                continue;
            }
            let c = shape::center(inner_shape);
            let center = DVec2::new(inner.position.0, inner.position.1)
                + DVec2::from_angle(inner.angle).rotate(DVec2::new(c.0, c.1));
            if outline.contains(to_local(center), 0.0) {
                out.push((outer.name.clone(), inner.name.clone()));
            }
        }
    }
    out
}
