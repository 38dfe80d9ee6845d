//! Where the overlays' labels go on screen: a greedy placer over rectangles, so that with every
//! overlay on the labels stay off each other, off the bodies and inside the view.
//!
//! Each label has a home (where its overlay wants it: beside an arrow's tip, under a point) and
//! a size. Labels are placed in order; each takes the nearest candidate spot around its home (a
//! spiral of offsets of one label height and width) that is inside the view and covers no label
//! placed before it and no body. When no spot is free, it takes the one that covers the least:
//! other labels first, then bodies (a label must be readable; one over a body still is). Pure
//! geometry in logical pixels (y down), so it is tested on the library's levels without a window.
//!
//! From frame to frame a label keeps its spot while the spot stays free ([`place_keeping`]).

use super::label_grid::{self, BodyGrid};
use bevy::math::{Rect, Vec2};

/// A label to place: its preferred top-left corner and its size, logical pixels.
#[derive(Debug, Clone, Copy)]
pub struct Want {
    pub home: Vec2,
    pub size: Vec2,
}

/// Places `wants` in order inside `view`, avoiding each other and the convex `bodies` (screen
/// polygons). Returns each label's rectangle.
pub fn place(wants: &[Want], bodies: &[Vec<Vec2>], view: Rect) -> Vec<Rect> {
    place_keeping(wants, bodies, view, &[])
}

/// A label whose home moved farther than this since the last frame is a different label (or
/// jumped): it is placed afresh, px.
pub const KEEP_PX: f32 = 40.0;

/// [`place`] with hysteresis: `previous` is last frame's (home, rectangle) of each label, by
/// index. A label keeps its place beside its home (the same offset, so it moves with its point)
/// while that spot is inside the view and clear of bodies and of the labels kept before it; only
/// the others are placed afresh, around the kept ones. Without this, a label jumped back and
/// forth between two spots from one step to the next as its neighbours came and went.
pub fn place_keeping(
    wants: &[Want],
    bodies: &[Vec<Vec2>],
    view: Rect,
    previous: &[(Vec2, Rect)],
) -> Vec<Rect> {
    let grid = BodyGrid::new(bodies, view, rect_hits_polygon);
    let mut kept: Vec<Option<Rect>> = vec![None; wants.len()];
    for (k, w) in wants.iter().enumerate() {
        let Some((home, r)) = previous.get(k) else {
            continue;
        };
        if (*home - w.home).length() > KEEP_PX {
            continue;
        }
        let at = w.home + (r.min - *home);
        let r = inside(Rect::from_corners(at, at + w.size), view);
        let free = kept
            .iter()
            .flatten()
            .all(|p| overlap_area(p, &r.inflate(MARGIN)) == 0.0)
            && !grid.any(&r);
        if free {
            kept[k] = Some(r);
        }
    }
    let mut placed: Vec<Rect> = kept.iter().flatten().copied().collect();
    let mut out = Vec::with_capacity(wants.len());
    for (k, (w, keep)) in wants.iter().zip(&kept).enumerate() {
        if let Some(r) = keep {
            out.push(*r);
            continue;
        }
        // A label that must leave its spot takes the free spot nearest it, not the one
        // nearest its home (which may be across the body that pushed it out).
        let near = previous
            .get(k)
            .filter(|(home, _)| (*home - w.home).length() <= KEEP_PX)
            .map(|(home, r)| w.home + (r.min - *home));
        let r = place_one(w, &grid, view, &placed, near);
        placed.push(r);
        out.push(r);
    }
    out
}

/// The nearest free spot around `w`'s home (or the one covering least), given `placed`; with
/// `near` (where the label was), the free spot nearest that.
fn place_one(w: &Want, bodies: &BodyGrid, view: Rect, placed: &[Rect], near: Option<Vec2>) -> Rect {
    // A home past the view's edge is first brought inside: the spots around it then lie in
    // the view instead of collapsing onto the edge.
    let home = inside(Rect::from_corners(w.home, w.home + w.size), view).min;
    let mut best: Option<(Rect, (f32, f32, f32))> = None;
    for (k, off) in candidates(w.size).enumerate() {
        let r = inside(Rect::from_corners(home + off, home + off + w.size), view);
        let on_labels: f32 = placed
            .iter()
            .map(|p| overlap_area(p, &r.inflate(MARGIN)))
            .sum();
        // Bodies are counted only while this spot can still beat the best so far: over more
        // label area it cannot, nor past the best's count of bodies at equal area.
        let limit = match &best {
            Some((_, (l, _, _))) if on_labels > *l => continue,
            Some((_, (l, b, _))) if on_labels == *l => *b as usize,
            _ => usize::MAX,
        };
        let on_bodies = bodies.count_up_to(&r, limit) as f32;
        let order = near.map_or(k as f32, |p| (r.min - p).length());
        let cost = (on_labels, on_bodies, order);
        if on_labels == 0.0 && on_bodies == 0.0 && near.is_none() {
            return r;
        }
        if best.as_ref().is_none_or(|(_, c)| cost < *c) {
            best = Some((r, cost));
        }
    }
    best.map(|(r, _)| r)
        .unwrap_or_else(|| Rect::from_corners(home, home + w.size))
}

/// Clear space kept between two labels, px.
pub const MARGIN: f32 = 1.5;

/// Offsets from home to try, nearest first: home, then rings of one label height up and down
/// and one label width left and right, out to four rings.
fn candidates(size: Vec2) -> impl Iterator<Item = Vec2> {
    let (dx, dy) = (size.x + 6.0, size.y + 3.0);
    let mut offs = vec![Vec2::ZERO];
    for ring in 1..=4 {
        let r = ring as f32;
        offs.extend([
            Vec2::new(0.0, r * dy),
            Vec2::new(0.0, -r * dy),
            Vec2::new(r * dx, 0.0),
            Vec2::new(-r * dx, 0.0),
            Vec2::new(r * dx, r * dy),
            Vec2::new(-r * dx, r * dy),
            Vec2::new(r * dx, -r * dy),
            Vec2::new(-r * dx, -r * dy),
        ]);
        // Half steps sideways find the gaps between neighbours.
        offs.extend([
            Vec2::new(0.5 * r * dx, r * dy),
            Vec2::new(-0.5 * r * dx, -r * dy),
        ]);
    }
    offs.into_iter()
}

/// Where each of `wants` may go: every rectangle the placer may test for a label (each candidate
/// spot, and the spot kept from `previous`) lies in that label's rectangle. `view` and
/// `previous` as in [`place_keeping`]. A body [`apart`] from all of them is apart from every
/// spot, which is the first test [`rect_hits_polygon`] makes: leaving it out places every label
/// the same. The window passes the placer only the bodies that meet one
/// (`app::screen_bodies_within`): in a 10,000-grain pile every spot lies on grains, and each
/// label tried its 41 spots against all 10,000 (docs/benchmarks.md, "10,000 bodies").
pub fn reach(wants: &[Want], view: Rect, previous: &[(Vec2, Rect)]) -> Vec<Rect> {
    wants
        .iter()
        .enumerate()
        .map(|(k, w)| {
            let home = inside(Rect::from_corners(w.home, w.home + w.size), view).min;
            let mut all = Rect::from_corners(home, home + w.size);
            if let Some((h, r)) = previous.get(k) {
                let at = w.home + (r.min - *h);
                all = all.union(inside(Rect::from_corners(at, at + w.size), view));
            }
            for off in candidates(w.size) {
                let spot = Rect::from_corners(home + off, home + off + w.size);
                all = all.union(inside(spot, view));
            }
            all
        })
        .collect()
}

/// Whether polygon `poly` lies apart from `r` along x or y (touching counts as apart, as in
/// [`rect_hits_polygon`]): then it meets no rectangle inside `r`.
pub fn apart(r: &Rect, poly: &[Vec2]) -> bool {
    label_grid::bounds(poly).is_none_or(|(lo, hi)| {
        hi.x <= r.min.x || r.max.x <= lo.x || hi.y <= r.min.y || r.max.y <= lo.y
    })
}

/// `r` moved (not resized) to lie inside `view` where it fits.
fn inside(r: Rect, view: Rect) -> Rect {
    let size = r.size();
    let min_x = r
        .min
        .x
        .clamp(view.min.x, (view.max.x - size.x).max(view.min.x));
    let min_y = r
        .min
        .y
        .clamp(view.min.y, (view.max.y - size.y).max(view.min.y));
    Rect::from_corners(Vec2::new(min_x, min_y), Vec2::new(min_x, min_y) + size)
}

pub fn overlap_area(a: &Rect, b: &Rect) -> f32 {
    let i = a.intersect(*b);
    if i.is_empty() {
        0.0
    } else {
        i.width() * i.height()
    }
}

/// Whether rectangle `r` and convex polygon `poly` overlap (separating axes: the rectangle's two
/// and the polygon's edge normals). A polygon thinner than a pixel counts as a segment.
pub fn rect_hits_polygon(r: &Rect, poly: &[Vec2]) -> bool {
    if poly.is_empty() {
        return false;
    }
    let corners = [
        r.min,
        Vec2::new(r.max.x, r.min.y),
        r.max,
        Vec2::new(r.min.x, r.max.y),
    ];
    let separated = |axis: Vec2| {
        if axis.length_squared() == 0.0 {
            return false;
        }
        let (a0, a1) = corners
            .iter()
            .map(|c| c.dot(axis))
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            });
        let (b0, b1) = poly
            .iter()
            .map(|c| c.dot(axis))
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            });
        a1 <= b0 || b1 <= a0
    };
    if separated(Vec2::X) || separated(Vec2::Y) {
        return false;
    }
    for k in 0..poly.len() {
        let e = poly[(k + 1) % poly.len()] - poly[k];
        if separated(Vec2::new(-e.y, e.x)) {
            return false;
        }
    }
    true
}
