//! What is legal in a level but probably not meant: warnings, located like errors, that do not
//! stop the run.
//!
//! Bodies created at one point with contacts on: rapier finds every pair of them touching, so a
//! pile of k coincident bodies costs k(k-1)/2 contact pairs each step and is blown apart by the
//! overlap's correction (measured: 2,000 discs at one point took 114 s and 6.1 GB before this
//! warning existed). Bodies joined by a joint do not collide (sim/build.rs turns their contacts
//! off), so a pin between two coincident bodies is not warned about.

use super::{BodyDef, BodyKind, Effect, Level, LevelError, LevelWarning, Locator, Shape, V2};
use std::collections::HashMap;
use std::path::Path;

/// Centers closer than this, m, count as one point.
const SAME_POINT: f64 = 1e-6;

/// The warnings of a valid level (`text` is its source, for positions).
pub fn find(file: &Path, text: &str, level: &Level) -> Vec<LevelWarning> {
    let mut out = Vec::new();
    if level.effects.contains(&Effect::Contacts) {
        out.extend(coincident_bodies(file, text, level));
    }
    out
}

/// The center of a shape's bounding box in its body's frame (polygons are often written in world
/// coordinates on a body at the origin, so the body position alone says little).
fn local_center(shape: &Shape) -> V2 {
    let rotate = |p: V2, a: f64| (p.0 * a.cos() - p.1 * a.sin(), p.0 * a.sin() + p.1 * a.cos());
    match shape {
        Shape::Circle { .. } | Shape::Box { .. } | Shape::Capsule { .. } => (0.0, 0.0),
        Shape::Segment { a, b } => ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0),
        Shape::Polygon { points } => {
            let (lo, hi) = points.iter().fold(
                (
                    (f64::INFINITY, f64::INFINITY),
                    (f64::NEG_INFINITY, f64::NEG_INFINITY),
                ),
                |(lo, hi), p| {
                    (
                        (lo.0.min(p.0), lo.1.min(p.1)),
                        (hi.0.max(p.0), hi.1.max(p.1)),
                    )
                },
            );
            ((lo.0 + hi.0) / 2.0, (lo.1 + hi.1) / 2.0)
        }
        Shape::Compound { parts } => {
            let n = parts.len().max(1) as f64;
            parts.iter().fold((0.0, 0.0), |acc, p| {
                let c = rotate(local_center(&p.shape), p.angle);
                (
                    acc.0 + (p.offset.0 + c.0) / n,
                    acc.1 + (p.offset.1 + c.1) / n,
                )
            })
        }
    }
}

/// Where a body's collider is centered in the world.
fn world_center(b: &BodyDef, shape: &Shape) -> V2 {
    let c = local_center(shape);
    let (s, co) = b.angle.sin_cos();
    (
        b.position.0 + c.0 * co - c.1 * s,
        b.position.1 + c.0 * s + c.1 * co,
    )
}

/// Groups of at least two colliding bodies (one of them moving) whose colliders are centered
/// at one point.
fn coincident_bodies(file: &Path, text: &str, level: &Level) -> Vec<LevelWarning> {
    let key = |p: (f64, f64)| {
        (
            (p.0 / SAME_POINT).round() as i64,
            (p.1 / SAME_POINT).round() as i64,
        )
    };
    let mut groups: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    for (i, b) in level.bodies.iter().enumerate() {
        if let Some(shape) = &b.shape {
            groups
                .entry(key(world_center(b, shape)))
                .or_default()
                .push(i);
        }
    }
    let joined = |a: &str, b: &str| {
        level
            .joints
            .iter()
            .any(|j| (j.body1 == a && j.body2 == b) || (j.body1 == b && j.body2 == a))
    };
    let mut found: Vec<Vec<usize>> = groups
        .into_values()
        .filter(|g| g.iter().any(|&i| level.bodies[i].kind == BodyKind::Dynamic))
        .filter(|g| {
            g.iter().enumerate().any(|(n, &i)| {
                g[n + 1..]
                    .iter()
                    .any(|&k| !joined(&level.bodies[i].name, &level.bodies[k].name))
            })
        })
        .collect();
    found.sort();
    if found.is_empty() {
        return Vec::new();
    }
    let loc = Locator::new(text);
    found
        .iter()
        .map(|g| {
            let first = &level.bodies[g[0]];
            let at = first
                .shape
                .as_ref()
                .map_or(first.position, |s| world_center(first, s));
            let k = g.len();
            let names: Vec<&str> = g
                .iter()
                .take(4)
                .map(|&i| level.bodies[i].name.as_str())
                .collect();
            LevelWarning(LevelError::new(
                file,
                loc.item_pos("bodies", &first.name),
                format!(
                    "{k} bodies start at the same point ({}, {}): {}{}; their colliders overlap, \
                     rapier pushes them apart violently and checks {} contact pairs every step",
                    at.0,
                    at.1,
                    names.join(", "),
                    if k > names.len() { ", ..." } else { "" },
                    k * (k - 1) / 2
                ),
                "give each body its own position, or join bodies that are one part with a weld",
            ))
        })
        .collect()
}
