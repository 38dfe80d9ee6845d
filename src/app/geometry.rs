//! Level shapes as drawable geometry, in the body frame (f64, SI): the outline each shape gives
//! (`level::shape::outline`, closed convex polygons for filled shapes and segments for lines),
//! its triangles for a mesh, bounds and clipping. The meshes and outlines the view draws come
//! from here, so every shape of `level::Shape` is drawn the same way.

use crate::level::{BodyDef, Level};
use glam::DVec2;

/// The outline of a shape, drawn and picked: the level's geometry (`level::shape::outline`).
pub use crate::level::shape::Outline;

/// The level's hull (the one the level format's polygons use).
pub use crate::level::shape::convex_hull;

/// Triangles (fan) of the filled parts, body frame, as f32 xyz (for a Bevy mesh).
pub fn triangles(o: &Outline) -> Vec<[f32; 3]> {
    let mut out = Vec::new();
    for poly in &o.filled {
        for k in 1..poly.len().saturating_sub(1) {
            for p in [poly[0], poly[k], poly[k + 1]] {
                out.push([p.x as f32, p.y as f32, 0.0]);
            }
        }
    }
    out
}

/// An axis-aligned box, m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    pub min: DVec2,
    pub max: DVec2,
}

impl Bounds {
    pub fn empty() -> Self {
        Bounds {
            min: DVec2::splat(f64::INFINITY),
            max: DVec2::splat(f64::NEG_INFINITY),
        }
    }
    pub fn add(&mut self, p: DVec2) {
        if p.is_finite() {
            self.min = self.min.min(p);
            self.max = self.max.max(p);
        }
    }
    pub fn is_empty(&self) -> bool {
        !(self.min.x <= self.max.x && self.min.y <= self.max.y)
    }
    pub fn center(&self) -> DVec2 {
        0.5 * (self.min + self.max)
    }
    pub fn size(&self) -> DVec2 {
        self.max - self.min
    }
}

/// The part of segment a-b inside the box (Liang-Barsky), if any.
pub fn clip_segment(a: DVec2, b: DVec2, w: &Bounds) -> Option<(DVec2, DVec2)> {
    let d = b - a;
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-d.x, a.x - w.min.x),
        (d.x, w.max.x - a.x),
        (-d.y, a.y - w.min.y),
        (d.y, w.max.y - a.y),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    (t0 <= t1).then(|| (a + d * t0, a + d * t1))
}

/// A body's outline placed at a pose.
pub fn place(o: &Outline, position: DVec2, angle: f64) -> impl Fn(DVec2) -> DVec2 {
    let _ = o;
    let r = DVec2::from_angle(angle);
    move |p| position + r.rotate(p)
}

/// The bounds of a body at a pose: its outline, or its origin for a point body.
pub fn body_bounds(def: &BodyDef, outline: &Outline, position: DVec2, angle: f64, b: &mut Bounds) {
    let _ = def;
    let to_world = place(outline, position, angle);
    let mut any = false;
    for p in outline.points() {
        b.add(to_world(p));
        any = true;
    }
    if !any {
        b.add(position);
    }
}

/// Bounds of a level's initial scene (bodies, spring ground points).
pub fn level_bounds(level: &Level) -> Bounds {
    let mut b = Bounds::empty();
    for body in &level.bodies {
        let o = body.shape.as_ref().map(Outline::of).unwrap_or_default();
        body_bounds(
            body,
            &o,
            DVec2::new(body.position.0, body.position.1),
            body.angle,
            &mut b,
        );
    }
    for s in &level.springs {
        if s.body2.is_none() {
            b.add(DVec2::new(s.point2.0, s.point2.1));
        }
    }
    b
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::level::Shape;

    #[test]
    fn hull_drops_inner_points_and_turns_ccw() {
        let pts = [(0.0, 0.0), (2.0, 0.0), (1.0, 0.5), (2.0, 2.0), (0.0, 2.0)]
            .map(|(x, y)| DVec2::new(x, y));
        let h = convex_hull(&pts);
        assert_eq!(h.len(), 4);
        let area: f64 = (0..h.len())
            .map(|k| h[k].perp_dot(h[(k + 1) % h.len()]))
            .sum::<f64>()
            / 2.0;
        assert!((area - 4.0).abs() < 1e-12, "CCW area 4, got {area}");
    }

    #[test]
    fn clipping_keeps_the_part_inside() {
        let w = Bounds {
            min: DVec2::new(0.0, 0.0),
            max: DVec2::new(1.0, 1.0),
        };
        let (p, q) = clip_segment(DVec2::new(-1.0, 0.5), DVec2::new(3.0, 0.5), &w).unwrap();
        assert!(
            (p - DVec2::new(0.0, 0.5)).length() < 1e-12
                && (q - DVec2::new(1.0, 0.5)).length() < 1e-12
        );
        assert!(clip_segment(DVec2::new(-1.0, 2.0), DVec2::new(3.0, 2.0), &w).is_none());
    }

    #[test]
    fn capsule_outline_spans_length_plus_diameter() {
        let o = Outline::of(&Shape::Capsule {
            length: 2.0,
            radius: 0.5,
        });
        let mut b = Bounds::empty();
        o.points().for_each(|p| b.add(p));
        assert!((b.size() - DVec2::new(3.0, 1.0)).length() < 1e-9, "{:?}", b);
        assert!(o.contains(DVec2::new(1.2, 0.0), 0.0));
        assert!(!o.contains(DVec2::new(0.0, 0.6), 0.0));
    }
}
