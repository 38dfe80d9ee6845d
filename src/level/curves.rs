//! Curved static tracks: the facets of a circular arc (their count from the radius and a
//! chord-error bound) and the self-intersection test of a polyline. The engine builds both as a
//! polyline (an arc's circle too, which a ball touches: `sim/arc_track.rs`), the window draws
//! the same points, and validation tests them.

use super::format::{ArcSide, Shape, TrackSide, V2};
use std::f64::consts::TAU;

/// The default chord-error bound of an arc, relative to its radius: 1e-7 R gives facets of
/// 2 acos(1 - 1e-7) = 8.9e-4 rad, 7025 to a full turn. A body other than a ball riding on the
/// inside of a faceted arc meets a kink of that angle at every vertex and loses the normal part
/// of its velocity there, a fraction (8.9e-4)^2 of its kinetic energy, 0.56% over a whole turn
/// (docs/levels.md); a ball touches the circle itself (`sim/arc_track.rs`).
pub const DEFAULT_CHORD_ERROR: f64 = 1e-7;

/// The most facets one arc may have (a finer chord error is refused with the count it gives).
pub const MAX_ARC_FACETS: usize = 65_536;

/// The most points one polyline may have (self-intersection is tested on every pair of edges).
pub const MAX_POLYLINE_POINTS: usize = 10_000;

/// The chord-error bound of an arc, m: the given one or [`DEFAULT_CHORD_ERROR`] times `radius`.
pub fn chord_error(radius: f64, given: Option<f64>) -> f64 {
    given.unwrap_or(DEFAULT_CHORD_ERROR * radius)
}

/// The angle of one facet, rad: the largest whose sagitta R (1 - cos(a / 2)) is at most `e`.
pub fn facet_angle(radius: f64, e: f64) -> f64 {
    2.0 * (1.0 - (e / radius).min(1.0)).acos()
}

/// How many facets an arc of `radius` sweeping `sweep` rad needs for a chord error `e`.
/// Non-finite or absurd inputs give `usize::MAX` (validation refuses the arc before the engine
/// builds it).
pub fn arc_facets(radius: f64, sweep: f64, e: f64) -> usize {
    let n = (sweep / facet_angle(radius, e)).ceil();
    if n.is_finite() && n >= 1.0 && n <= MAX_ARC_FACETS as f64 {
        n as usize
    } else if n.is_finite() && n < 1.0 {
        1
    } else {
        usize::MAX
    }
}

/// The vertices of an arc's facets, counter-clockwise from `start` to `end`, and whether they
/// close (a full turn). The vertices lie at 2 R / (1 + cos(a / 2)), a the facet angle, so the
/// chords straddle the circle: every point of the track is within half the chord error of it.
pub fn arc_points(center: V2, radius: f64, start: f64, end: f64, e: f64) -> (Vec<V2>, bool) {
    let sweep = end - start;
    let n = arc_facets(radius, sweep, e).min(MAX_ARC_FACETS);
    let a = sweep / n as f64;
    let rv = 2.0 * radius / (1.0 + (a / 2.0).cos());
    let closed = (sweep - TAU).abs() < 1e-9;
    let count = if closed { n } else { n + 1 };
    let points = (0..count)
        .map(|k| {
            let t = start + a * k as f64;
            (center.0 + rv * t.cos(), center.1 + rv * t.sin())
        })
        .collect();
    (points, closed)
}

/// The points of a track shape (`Polyline`, `Arc` or `Track`) and whether it closes; None for
/// the others and for a `Track` that does not walk (validation refuses it).
pub fn track_points(s: &Shape) -> Option<(Vec<V2>, bool)> {
    match s {
        Shape::Track {
            start,
            heading,
            pieces,
            solid,
            chord_error,
        } => super::track::walk(
            *start,
            *heading,
            pieces,
            *solid,
            super::track::Facets::Engine(*chord_error),
        )
        .ok()
        .map(|path| (path.points, false)),
        Shape::Polyline { points, closed, .. } => Some((points.clone(), *closed)),
        Shape::Arc {
            center,
            radius,
            start,
            end,
            chord_error: e,
            ..
        } => Some(arc_points(
            *center,
            *radius,
            *start,
            *end,
            chord_error(*radius, *e),
        )),
        _ => None,
    }
}

/// For a one-sided track, whether its solid lies on the left of its points' order (an arc's run
/// counter-clockwise: its `outside` side has the solid within the circle, on the left); None
/// for a two-sided polyline and for the other shapes.
pub fn solid_side(s: &Shape) -> Option<bool> {
    match s {
        Shape::Polyline { solid, .. } => solid.map(|side| side == TrackSide::Left),
        Shape::Arc { side, .. } => Some(*side == ArcSide::Outside),
        Shape::Track { solid, .. } => Some(*solid == TrackSide::Left),
        _ => None,
    }
}

/// True for the shapes that are static tracks only (no area, never on a dynamic body).
pub fn is_track(s: &Shape) -> bool {
    matches!(
        s,
        Shape::Polyline { .. } | Shape::Arc { .. } | Shape::Track { .. }
    )
}

/// What is wrong with a polyline's geometry, by point index.
#[derive(Debug, Clone, PartialEq)]
pub enum PolylineFault {
    /// Points `k` and `k + 1` (cyclically) coincide.
    ZeroEdge(usize),
    /// The edge from point `i` and the edge from point `j` cross, touch or overlap.
    Crossing(usize, usize),
}

/// The first fault of a polyline through `points` (closing back to the first when `closed`):
/// a zero-length edge, or two edges that meet anywhere but at the point they share.
pub fn polyline_fault(points: &[V2], closed: bool) -> Option<PolylineFault> {
    let n = points.len();
    let edges = if closed { n } else { n.saturating_sub(1) };
    let edge = |k: usize| (points[k], points[(k + 1) % n]);
    for k in 0..edges {
        let (a, b) = edge(k);
        if a == b {
            return Some(PolylineFault::ZeroEdge(k));
        }
    }
    for i in 0..edges {
        for j in i + 1..edges {
            let (a, b) = edge(i);
            let (c, d) = edge(j);
            let next = j == i + 1;
            let wrap = closed && i == 0 && j == edges - 1;
            if next || wrap {
                // Neighbours share a point; they fault only when they fold back on each other.
                let (p, q, r) = if next { (a, b, d) } else { (b, a, c) };
                let (u, w) = ((q.0 - p.0, q.1 - p.1), (r.0 - q.0, r.1 - q.1));
                let cross = u.0 * w.1 - u.1 * w.0;
                let dot = u.0 * w.0 + u.1 * w.1;
                let scale = (u.0.hypot(u.1) * w.0.hypot(w.1)).max(f64::MIN_POSITIVE);
                if cross.abs() <= 1e-12 * scale && dot < 0.0 {
                    return Some(PolylineFault::Crossing(i, j));
                }
                continue;
            }
            if segments_meet(a, b, c, d) {
                return Some(PolylineFault::Crossing(i, j));
            }
        }
    }
    None
}

/// Orientation of c about the line a -> b: the sign of (b - a) x (c - a).
fn orient(a: V2, b: V2, c: V2) -> f64 {
    (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)
}

fn on_segment(a: V2, b: V2, p: V2) -> bool {
    p.0 >= a.0.min(b.0) && p.0 <= a.0.max(b.0) && p.1 >= a.1.min(b.1) && p.1 <= a.1.max(b.1)
}

/// Whether the closed segments ab and cd have a point in common.
pub(crate) fn segments_meet(a: V2, b: V2, c: V2, d: V2) -> bool {
    let (o1, o2) = (orient(a, b, c), orient(a, b, d));
    let (o3, o4) = (orient(c, d, a), orient(c, d, b));
    if o1 * o2 < 0.0 && o3 * o4 < 0.0 {
        return true;
    }
    (o1 == 0.0 && on_segment(a, b, c))
        || (o2 == 0.0 && on_segment(a, b, d))
        || (o3 == 0.0 && on_segment(c, d, a))
        || (o4 == 0.0 && on_segment(c, d, b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn facets_bound_the_chord_error() {
        // R = 2 m, e = 1e-4 m: a = 2 acos(1 - 5e-5) = 0.0200003 rad, a quarter turn in 79 facets.
        let n = arc_facets(2.0, TAU / 4.0, 1e-4);
        assert_eq!(n, 79);
        let (pts, closed) = arc_points((1.0, -1.0), 2.0, 0.0, TAU / 4.0, 1e-4);
        assert!(!closed);
        assert_eq!(pts.len(), 80);
        // Every chord's middle and every vertex within e/2 of the circle.
        for w in pts.windows(2) {
            let m = ((w[0].0 + w[1].0) / 2.0 - 1.0, (w[0].1 + w[1].1) / 2.0 + 1.0);
            let v = (w[0].0 - 1.0, w[0].1 + 1.0);
            assert!((m.0.hypot(m.1) - 2.0).abs() <= 0.5e-4 + 1e-12);
            assert!((v.0.hypot(v.1) - 2.0).abs() <= 0.5e-4 + 1e-12);
        }
        let (full, closed) = arc_points((0.0, 0.0), 1.0, 0.0, TAU, 1e-3);
        assert!(closed);
        assert_eq!(full.len(), arc_facets(1.0, TAU, 1e-3));
    }

    #[test]
    fn polyline_faults_found() {
        let z = [(0.0, 0.0), (1.0, 0.0), (2.0, 1.0)];
        assert_eq!(polyline_fault(&z, false), None);
        assert_eq!(polyline_fault(&z, true), None);
        let bow = [(0.0, 0.0), (1.0, 1.0), (1.0, 0.0), (0.0, 1.0)];
        assert_eq!(
            polyline_fault(&bow, false),
            Some(PolylineFault::Crossing(0, 2))
        );
        let dup = [(0.0, 0.0), (1.0, 0.0), (1.0, 0.0)];
        assert_eq!(
            polyline_fault(&dup, false),
            Some(PolylineFault::ZeroEdge(1))
        );
        let back = [(0.0, 0.0), (2.0, 0.0), (1.0, 0.0)];
        assert_eq!(
            polyline_fault(&back, false),
            Some(PolylineFault::Crossing(0, 1))
        );
        // A concave U is fine.
        let u = [(0.0, 1.0), (0.0, 0.0), (1.0, 0.0), (1.0, 1.0)];
        assert_eq!(polyline_fault(&u, false), None);
    }
}
