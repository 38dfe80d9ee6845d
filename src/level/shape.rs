//! Each shape's verbs, one function per verb, as Box2D v3's `src/shape.c` has them: its name,
//! the sizes validation holds in range, its area, its convex hull, its bounds, its center, its
//! convex pieces (a core swept by a radius), its flat outline and inscribed radius (the
//! editor's placement), the facets of a track, and its outline (the points the window and the
//! editor draw). Validation, the warnings, the editor, the analysis, the run budget and the
//! window call these verbs instead of matching on [`Shape`]. What stays outside, and why: the
//! collider (`sim/build.rs`: rapier's types stay in `src/sim`), the mass center and second
//! moment (`analysis/mass.rs`), the tracks' own facets (`level/curves.rs`), and the edits and
//! inspector rows that change one named field of one variant. A new shape is its variant in
//! `format.rs`, its arms here, its collider and its second moment (CONTRIBUTING.md, "where to
//! add").
//!
//! What is here is plane geometry with no mass in it. The mass center and the second moment of
//! area stay in `analysis/mass.rs`, because they are the textbook's formulas (MP-4, MP-9) that
//! the `mass_properties` check holds the engine to, and a formula lives once, in
//! `src/analysis`. The area is here because validation, the level's warnings and the analysis
//! all need it, and the level stage may import nothing above it.

use super::curves;
use super::format::{ArcSide, Shape, TrackSide, V2};
use glam::DVec2;
use std::f64::consts::PI;

/// The shape's name, as the level file spells its variant in lower case (the window's legend).
pub fn name(s: &Shape) -> &'static str {
    match s {
        Shape::Circle { .. } => "circle",
        Shape::Box { .. } => "box",
        Shape::Capsule { .. } => "capsule",
        Shape::Polygon { .. } => "polygon",
        Shape::Segment { .. } => "segment",
        Shape::Polyline { .. } => "polyline",
        Shape::Arc { .. } => "arc",
        Shape::Track { .. } => "track",
        Shape::Compound { .. } => "compound",
    }
}

/// How small a size may be.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Least {
    /// Greater than zero.
    Positive,
    /// Zero or more.
    NonNegative,
}

/// One size of a shape that validation holds to a range: its value, its name in an error
/// ("box width") and how small it may be. Sizes are in m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Size {
    pub value: f64,
    pub what: &'static str,
    pub least: Least,
}

/// The sizes of a shape given by numbers alone, in the order validation reports them; empty
/// for the shapes given by points (polygons, segments, tracks) and for compounds, whose
/// validation reads their points and parts (`level/validate/bodies.rs`).
pub fn sizes(s: &Shape) -> Vec<Size> {
    let size = |value: f64, what, least| Size { value, what, least };
    match s {
        Shape::Circle { radius } => vec![size(*radius, "circle radius", Least::Positive)],
        Shape::Box { width, height } => vec![
            size(*width, "box width", Least::Positive),
            size(*height, "box height", Least::Positive),
        ],
        Shape::Capsule { length, radius } => vec![
            size(*length, "capsule length", Least::NonNegative),
            size(*radius, "capsule radius", Least::Positive),
        ],
        Shape::Polygon { .. }
        | Shape::Segment { .. }
        | Shape::Polyline { .. }
        | Shape::Arc { .. }
        | Shape::Track { .. }
        | Shape::Compound { .. } => Vec::new(),
    }
}

/// The area A of a shape, m^2: what a density multiplies into a mass (a polygon's convex hull,
/// as the engine builds it; segments and tracks have none; a compound's parts add up).
pub fn area(s: &Shape) -> f64 {
    match s {
        Shape::Circle { radius } => PI * radius * radius,
        Shape::Box { width, height } => width * height,
        Shape::Capsule { length, radius } => 2.0 * radius * length + PI * radius * radius,
        Shape::Polygon { points } => polygon_area(&convex_hull(&dvec(points))).abs(),
        Shape::Segment { .. }
        | Shape::Polyline { .. }
        | Shape::Arc { .. }
        | Shape::Track { .. } => 0.0,
        Shape::Compound { parts } => parts.iter().map(|p| area(&p.shape)).sum(),
    }
}

/// The signed area of a polygon through `points` in order (the shoelace formula): positive
/// counter-clockwise.
pub fn polygon_area(points: &[DVec2]) -> f64 {
    let n = points.len();
    (0..n)
        .map(|i| points[i].perp_dot(points[(i + 1) % n]))
        .sum::<f64>()
        / 2.0
}

/// The convex hull of a point set, counter-clockwise from the lowest of the leftmost points
/// (Andrew's monotone chain); points on an edge are dropped. The level format uses the hull of
/// a polygon's points.
pub fn convex_hull(points: &[DVec2]) -> Vec<DVec2> {
    let mut p: Vec<DVec2> = points.to_vec();
    p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let turn = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o);
    let half = |pts: &mut dyn Iterator<Item = DVec2>| {
        let mut h: Vec<DVec2> = Vec::new();
        for q in pts {
            while h.len() >= 2 && turn(h[h.len() - 2], h[h.len() - 1], q) <= 0.0 {
                h.pop();
            }
            h.push(q);
        }
        h.pop();
        h
    };
    let mut hull = half(&mut p.iter().copied());
    hull.extend(half(&mut p.iter().rev().copied()));
    hull
}

/// An axis-aligned box, (min, max), m.
pub type Aabb = ((f64, f64), (f64, f64));

/// The box of a shape placed at `at` turned by `angle` rad: its points, each widened by the
/// radius it is swept by (a circle's or a capsule's; an arc's whole circle).
pub fn bounds(s: &Shape, at: V2, angle: f64) -> Aabb {
    let (sin, cos) = angle.sin_cos();
    let place = |p: V2| (at.0 + cos * p.0 - sin * p.1, at.1 + sin * p.0 + cos * p.1);
    let points = |ps: &[V2], r: f64| {
        let mut b = (
            (f64::INFINITY, f64::INFINITY),
            (f64::NEG_INFINITY, f64::NEG_INFINITY),
        );
        for &p in ps {
            let q = place(p);
            b.0 = (b.0 .0.min(q.0 - r), b.0 .1.min(q.1 - r));
            b.1 = (b.1 .0.max(q.0 + r), b.1 .1.max(q.1 + r));
        }
        b
    };
    match s {
        Shape::Circle { radius } => points(&[(0.0, 0.0)], *radius),
        Shape::Box { width, height } => {
            let (w, h) = (width / 2.0, height / 2.0);
            points(&[(-w, -h), (w, -h), (w, h), (-w, h)], 0.0)
        }
        Shape::Capsule { length, radius } => {
            points(&[(-length / 2.0, 0.0), (length / 2.0, 0.0)], *radius)
        }
        Shape::Polygon { points: ps } => points(ps, 0.0),
        Shape::Segment { a, b } => points(&[*a, *b], 0.0),
        Shape::Polyline { points: ps, .. } => points(ps, 0.0),
        Shape::Arc { center, radius, .. } => points(&[*center], *radius),
        Shape::Track { .. } => points(&track_drawn(s), 0.0),
        Shape::Compound { parts } => {
            let mut b = (
                (f64::INFINITY, f64::INFINITY),
                (f64::NEG_INFINITY, f64::NEG_INFINITY),
            );
            for p in parts {
                let q = bounds(&p.shape, place(p.offset), angle + p.angle);
                b.0 = (b.0 .0.min(q.0 .0), b.0 .1.min(q.0 .1));
                b.1 = (b.1 .0.max(q.1 .0), b.1 .1.max(q.1 .1));
            }
            b
        }
    }
}

/// Where a shape is centered in its body's frame: the middle of its points' box (polygons are
/// often written in world coordinates on a body at the origin), an arc's center, the mean of a
/// compound's parts' centers.
pub fn center(s: &Shape) -> V2 {
    match s {
        Shape::Circle { .. } | Shape::Box { .. } | Shape::Capsule { .. } => (0.0, 0.0),
        Shape::Segment { a, b } => ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0),
        Shape::Arc { center, .. } => *center,
        Shape::Track { .. } => {
            let ((x0, y0), (x1, y1)) = bounds(s, (0.0, 0.0), 0.0);
            ((x0 + x1) / 2.0, (y0 + y1) / 2.0)
        }
        Shape::Polygon { points } | Shape::Polyline { points, .. } => {
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
                let c = DVec2::from_angle(p.angle).rotate(DVec2::from(center(&p.shape)));
                (
                    acc.0 + (p.offset.0 + c.x) / n,
                    acc.1 + (p.offset.1 + c.y) / n,
                )
            })
        }
    }
}

/// A convex piece of a shape in its body's frame: the core's vertices (1: a point, 2: a
/// segment, 3 or more: a polygon as the level lists it) swept by `radius` (Box2D's shape proxy).
#[derive(Debug, Clone, PartialEq)]
pub struct Piece {
    pub core: Vec<DVec2>,
    pub radius: f64,
}

/// The convex pieces of a shape, body frame: one for a round or flat shape, one per edge of a
/// polyline; None for an arc track and a compound, which no reader of pieces models yet.
pub fn pieces(s: &Shape) -> Option<Vec<Piece>> {
    let piece = |core: Vec<DVec2>, radius: f64| Piece { core, radius };
    Some(match s {
        Shape::Circle { radius } => vec![piece(vec![DVec2::ZERO], *radius)],
        Shape::Box { width, height } => {
            let (hx, hy) = (0.5 * width, 0.5 * height);
            vec![piece(
                dvec(&[(-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy)]),
                0.0,
            )]
        }
        Shape::Capsule { length, radius } => vec![piece(
            vec![
                DVec2::new(-0.5 * length, 0.0),
                DVec2::new(0.5 * length, 0.0),
            ],
            *radius,
        )],
        Shape::Polygon { points } => vec![piece(dvec(points), 0.0)],
        Shape::Segment { a, b } => vec![piece(dvec(&[*a, *b]), 0.0)],
        Shape::Polyline { points, closed, .. } => {
            let mut out: Vec<Piece> = points.windows(2).map(|e| piece(dvec(e), 0.0)).collect();
            if *closed && points.len() > 2 {
                out.push(piece(dvec(&[points[points.len() - 1], points[0]]), 0.0));
            }
            out
        }
        Shape::Arc { .. } | Shape::Track { .. } | Shape::Compound { .. } => return None,
    })
}

/// A shape's flat outline in its body's frame, where one is exact: a box's corners and a
/// polygon's hull counter-clockwise, a segment's two ends; None for round shapes, tracks and
/// compounds (what the editor's placement snaps against).
pub fn flat_outline(s: &Shape) -> Option<Vec<DVec2>> {
    match s {
        Shape::Box { width, height } => {
            let (w, h) = (width / 2.0, height / 2.0);
            Some(dvec(&[(-w, -h), (w, -h), (w, h), (-w, h)]))
        }
        Shape::Polygon { points } => Some(convex_hull(&dvec(points))),
        Shape::Segment { a, b } => Some(dvec(&[*a, *b])),
        Shape::Circle { .. }
        | Shape::Capsule { .. }
        | Shape::Polyline { .. }
        | Shape::Arc { .. }
        | Shape::Track { .. }
        | Shape::Compound { .. } => None,
    }
}

/// The radius of the largest circle about the body origin inside a shape, m (where the editor
/// may put a pin); 0 for the shapes it does not place pins in.
pub fn inscribed_radius(s: &Shape) -> f64 {
    match s {
        Shape::Circle { radius } => *radius,
        Shape::Box { width, height } => width.min(*height) / 2.0,
        Shape::Polygon { points } => {
            let h = convex_hull(&dvec(points));
            if h.len() < 3 {
                return 0.0;
            }
            (0..h.len())
                .map(|i| {
                    let (a, b) = (h[i], h[(i + 1) % h.len()]);
                    (b - a).perp_dot(-a).abs() / (b - a).length().max(1e-300)
                })
                .fold(f64::INFINITY, f64::min)
        }
        Shape::Capsule { .. }
        | Shape::Segment { .. }
        | Shape::Polyline { .. }
        | Shape::Arc { .. }
        | Shape::Track { .. }
        | Shape::Compound { .. } => 0.0,
    }
}

/// The facets a curved track is built of (an `Arc`'s from its chord error, capped at
/// [`curves::MAX_ARC_FACETS`]; a `Polyline`'s points), summed over a compound; 0 for the others.
pub fn facets(s: &Shape) -> f64 {
    match s {
        Shape::Arc {
            radius,
            start,
            end,
            chord_error,
            ..
        } => {
            let e = curves::chord_error(*radius, *chord_error);
            curves::arc_facets(*radius, (end - start).abs(), e).min(curves::MAX_ARC_FACETS) as f64
        }
        Shape::Polyline { points, .. } => points.len() as f64,
        Shape::Track { .. } => curves::track_points(s).map_or(0.0, |(p, _)| p.len() as f64),
        Shape::Compound { parts } => parts.iter().map(|p| facets(&p.shape)).sum(),
        Shape::Circle { .. }
        | Shape::Box { .. }
        | Shape::Capsule { .. }
        | Shape::Polygon { .. }
        | Shape::Segment { .. } => 0.0,
    }
}

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

/// The outline the window and the editor draw and pick, in the body frame.
pub fn outline(s: &Shape) -> Outline {
    let mut o = Outline::default();
    add_outline(&mut o, s, DVec2::ZERO, 0.0);
    o
}

fn add_outline(o: &mut Outline, shape: &Shape, offset: DVec2, angle: f64) {
    let rot = DVec2::from_angle(angle);
    let tr = |p: DVec2| offset + rot.rotate(p);
    match shape {
        Shape::Circle { radius } => {
            o.filled.push(
                arc_points(
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
            let right = arc_points(DVec2::new(l, 0.0), *radius, -0.5 * PI, 0.5 * PI, half);
            let left = arc_points(DVec2::new(-l, 0.0), *radius, 0.5 * PI, 1.5 * PI, half);
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
        } => polyline_outline(o, points, *closed, *solid, tr),
        Shape::Track { solid, .. } => {
            polyline_outline(o, &track_drawn(shape), false, Some(*solid), tr)
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
            let mut pts: Vec<DVec2> = arc_points(c, *radius, *start, *end, n).collect();
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
                add_outline(o, &part.shape, off, angle + part.angle);
            }
        }
    }
}

/// A polyline track's edges, with the normal toward its solid side for a one-sided one.
fn polyline_outline(
    o: &mut Outline,
    points: &[V2],
    closed: bool,
    solid: Option<TrackSide>,
    tr: impl Fn(DVec2) -> DVec2,
) {
    let pts: Vec<DVec2> = points.iter().map(|&(x, y)| tr(DVec2::new(x, y))).collect();
    let n = pts.len();
    let edges = if closed { n } else { n.saturating_sub(1) };
    for k in 0..edges {
        let (a, b) = (pts[k], pts[(k + 1) % n]);
        if let Some(side) = solid {
            // The solid side's normal: the edge turned a quarter turn to that side.
            let left = (b - a).perp().normalize_or(DVec2::Y);
            let n = if side == TrackSide::Left { left } else { -left };
            o.solid_side.push((o.segments.len(), n));
        }
        o.segments.push((a, b));
    }
}

/// A `Track`'s points as the window draws them (arc pieces in steps of [`ARC_DRAW_STEP`]); its
/// start alone where it does not walk (validation refuses such a track before a run).
fn track_drawn(s: &Shape) -> Vec<V2> {
    let Shape::Track {
        start,
        heading,
        pieces,
        solid,
        ..
    } = s
    else {
        return Vec::new();
    };
    let step = super::track::Facets::Step(ARC_DRAW_STEP);
    super::track::walk(*start, *heading, pieces, *solid, step)
        .map_or_else(|_| vec![*start], |path| path.points)
}

/// `n + 1` points on an arc from angle `a0` to `a1` (the closing point is dropped for full circles).
fn arc_points(c: DVec2, r: f64, a0: f64, a1: f64, n: usize) -> impl Iterator<Item = DVec2> {
    let full = (a1 - a0 - std::f64::consts::TAU).abs() < 1e-12;
    let count = if full { n } else { n + 1 };
    (0..count).map(move |k| c + DVec2::from_angle(a0 + (a1 - a0) * k as f64 / n as f64) * r)
}

impl Outline {
    /// The outline of a shape ([`outline`]).
    pub fn of(shape: &Shape) -> Outline {
        outline(shape)
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

/// The distance from `p` to the segment a-b, m.
pub fn segment_distance(a: DVec2, b: DVec2, p: DVec2) -> f64 {
    let e = b - a;
    let t = if e.length_squared() > 0.0 {
        ((p - a).dot(e) / e.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + e * t - p).length()
}

/// Level points as vectors.
fn dvec(points: &[V2]) -> Vec<DVec2> {
    points.iter().map(|&p| DVec2::from(p)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::level::format::Part;

    /// A capsule is a rectangle 2 r x l and a disc of radius r: A = 2 r l + pi r^2.
    #[test]
    fn capsule_area_is_rectangle_plus_disc() {
        let a = area(&Shape::Capsule {
            length: 2.0,
            radius: 0.5,
        });
        assert!((a - (2.0 + PI * 0.25)).abs() < 1e-12, "got {a}");
    }

    /// A polygon's area is its hull's: a 2 m square with a notch point inside has 4 m^2, where
    /// the shoelace over the listed points gives 4 - 0.5 = 3.5 m^2.
    #[test]
    fn polygon_area_is_the_hulls() {
        let points = vec![(0.0, 0.0), (1.0, 0.5), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)];
        let listed: Vec<DVec2> = points.iter().map(|&p| DVec2::from(p)).collect();
        assert!((polygon_area(&listed) - 3.5).abs() < 1e-12);
        assert!((area(&Shape::Polygon { points }) - 4.0).abs() < 1e-12);
    }

    /// A 2 m x 1 m box turned a quarter turn about (1, 1) spans 1 m in x and 2 m in y; a
    /// compound's parts are placed by their offsets, turned with the body.
    #[test]
    fn bounds_turn_with_the_body() {
        let quarter = std::f64::consts::FRAC_PI_2;
        let b = Shape::Box {
            width: 2.0,
            height: 1.0,
        };
        let ((x0, y0), (x1, y1)) = bounds(&b, (1.0, 1.0), quarter);
        for (got, want) in [(x0, 0.5), (x1, 1.5), (y0, 0.0), (y1, 2.0)] {
            assert!((got - want).abs() < 1e-12, "{got} for {want}");
        }
        let c = Shape::Compound {
            parts: vec![Part {
                shape: Shape::Circle { radius: 0.5 },
                offset: (3.0, 0.0),
                angle: 0.0,
            }],
        };
        let ((x0, y0), (x1, y1)) = bounds(&c, (0.0, 0.0), quarter);
        for (got, want) in [(x0, -0.5), (x1, 0.5), (y0, 2.5), (y1, 3.5)] {
            assert!((got - want).abs() < 1e-12, "{got} for {want}");
        }
    }
}
