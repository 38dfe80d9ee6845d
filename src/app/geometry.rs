//! Level shapes as drawable geometry, in the body frame (f64, SI): closed convex outlines for
//! filled shapes and open polylines for segments. The meshes and outlines the view draws come from
//! here, so every shape of `level::Shape` is drawn the same way.

use crate::level::{ArcSide, BodyDef, Level, Shape, TrackSide};
use glam::DVec2;

/// Drawable pieces of one body, in its frame.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Outline {
    /// Closed convex polygons (counter-clockwise), one per filled part.
    pub filled: Vec<Vec<DVec2>>,
    /// Circles (center, radius) among `filled`, for a spoke that shows the rotation.
    pub circles: Vec<(DVec2, f64)>,
    /// Line segments (no area), tracks' edges included.
    pub segments: Vec<(DVec2, DVec2)>,
    /// For a segment of an arc track (by index in `segments`): the unit normal, body frame,
    /// toward the arc's solid side, where its hatching goes.
    pub solid_side: Vec<(usize, DVec2)>,
}

/// An arc is drawn in pieces of at most this angle, rad (2 degrees): the engine's facets are far
/// finer (`level::curves`), and finer pieces would not show.
const ARC_DRAW_STEP: f64 = std::f64::consts::PI / 90.0;

/// Points on a circle outline.
const CIRCLE_SEGMENTS: usize = 40;

impl Outline {
    pub fn of(shape: &Shape) -> Outline {
        let mut o = Outline::default();
        add_shape(&mut o, shape, DVec2::ZERO, 0.0);
        o
    }

    /// Every point of the outline (for bounds).
    pub fn points(&self) -> impl Iterator<Item = DVec2> + '_ {
        self.filled
            .iter()
            .flatten()
            .copied()
            .chain(self.segments.iter().flat_map(|(a, b)| [*a, *b]))
    }

    /// True if the body-frame point lies inside a filled part (or within `tol` of a segment).
    pub fn contains(&self, p: DVec2, tol: f64) -> bool {
        self.filled.iter().any(|poly| convex_contains(poly, p, tol))
            || self
                .segments
                .iter()
                .any(|(a, b)| segment_distance(*a, *b, p) <= tol)
    }
}

fn add_shape(o: &mut Outline, shape: &Shape, offset: DVec2, angle: f64) {
    let rot = DVec2::from_angle(angle);
    let tr = |p: DVec2| offset + rot.rotate(p);
    match shape {
        Shape::Circle { radius } => {
            o.filled.push(
                arc(
                    DVec2::ZERO,
                    *radius,
                    0.0,
                    std::f64::consts::TAU,
                    CIRCLE_SEGMENTS,
                )
                .map(tr)
                .collect(),
            );
            o.circles.push((offset, *radius));
        }
        Shape::Box { width, height } => {
            let (w, h) = (0.5 * width, 0.5 * height);
            o.filled.push(
                [(-w, -h), (w, -h), (w, h), (-w, h)]
                    .into_iter()
                    .map(|(x, y)| tr(DVec2::new(x, y)))
                    .collect(),
            );
        }
        Shape::Capsule { length, radius } => {
            let l = 0.5 * length;
            let half = CIRCLE_SEGMENTS / 2;
            let pi = std::f64::consts::PI;
            let right = arc(DVec2::new(l, 0.0), *radius, -0.5 * pi, 0.5 * pi, half);
            let left = arc(DVec2::new(-l, 0.0), *radius, 0.5 * pi, 1.5 * pi, half);
            o.filled.push(right.chain(left).map(tr).collect());
        }
        Shape::Polygon { points } => {
            let pts: Vec<DVec2> = points.iter().map(|&(x, y)| tr(DVec2::new(x, y))).collect();
            o.filled.push(convex_hull(&pts));
        }
        Shape::Segment { a, b } => {
            o.segments
                .push((tr(DVec2::new(a.0, a.1)), tr(DVec2::new(b.0, b.1))));
        }
        Shape::Polyline {
            points,
            closed,
            solid,
        } => {
            let pts: Vec<DVec2> = points.iter().map(|&(x, y)| tr(DVec2::new(x, y))).collect();
            let n = pts.len();
            let edges = if *closed { n } else { n.saturating_sub(1) };
            for k in 0..edges {
                let (a, b) = (pts[k], pts[(k + 1) % n]);
                if let Some(side) = solid {
                    // The solid side's normal: the edge turned a quarter turn to that side.
                    let left = (b - a).perp().normalize_or(DVec2::Y);
                    let n = if *side == TrackSide::Left {
                        left
                    } else {
                        -left
                    };
                    o.solid_side.push((o.segments.len(), n));
                }
                o.segments.push((a, b));
            }
        }
        Shape::Arc {
            center,
            radius,
            start,
            end,
            side,
            ..
        } => {
            let c = DVec2::new(center.0, center.1);
            let sweep = end - start;
            let n = ((sweep / ARC_DRAW_STEP).ceil() as usize).clamp(4, 720);
            let mut pts: Vec<DVec2> = arc(c, *radius, *start, *end, n).collect();
            if pts.len() == n {
                // A full turn: close it.
                pts.push(pts[0]);
            }
            for w in pts.windows(2) {
                let mid = 0.5 * (w[0] + w[1]);
                let out = (mid - c).normalize_or(DVec2::X);
                // Riding inside, the solid is outside the circle; riding outside, within it.
                let solid = match side {
                    ArcSide::Inside => out,
                    ArcSide::Outside => -out,
                };
                o.solid_side.push((o.segments.len(), rot.rotate(solid)));
                o.segments.push((tr(w[0]), tr(w[1])));
            }
        }
        Shape::Compound { parts } => {
            for part in parts {
                let off = tr(DVec2::new(part.offset.0, part.offset.1));
                add_shape(o, &part.shape, off, angle + part.angle);
            }
        }
    }
}

/// `n + 1` points on an arc from angle `a0` to `a1` (the closing point is dropped for full circles).
fn arc(c: DVec2, r: f64, a0: f64, a1: f64, n: usize) -> impl Iterator<Item = DVec2> {
    let full = (a1 - a0 - std::f64::consts::TAU).abs() < 1e-12;
    let count = if full { n } else { n + 1 };
    (0..count).map(move |k| c + DVec2::from_angle(a0 + (a1 - a0) * k as f64 / n as f64) * r)
}

/// The analysis layer's hull (the one the level format's polygons use).
pub use crate::analysis::mass::convex_hull;

fn convex_contains(poly: &[DVec2], p: DVec2, tol: f64) -> bool {
    if poly.len() < 3 {
        return false;
    }
    (0..poly.len()).all(|k| {
        let a = poly[k];
        let b = poly[(k + 1) % poly.len()];
        let e = b - a;
        // Inside (left of every CCW edge), or within tol of it.
        e.perp_dot(p - a) >= -tol * e.length()
    })
}

pub fn segment_distance(a: DVec2, b: DVec2, p: DVec2) -> f64 {
    let e = b - a;
    let t = if e.length_squared() > 0.0 {
        ((p - a).dot(e) / e.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + e * t - p).length()
}

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
