//! The bodies the label placer keeps labels off, binned on a grid of screen cells, so that a
//! candidate spot is tested only against the bodies near it.
//!
//! In a 10,000-grain pile every spot a label may take lies on grains, so each label tried each
//! of its 41 spots against every grain: 17 ms a frame for the 16 labels of one selected grain
//! (2026-12-07, load 9; docs/benchmarks.md, "10,000 bodies"). A body whose box is at most a
//! cell across is filed under the cell of its box's lower corner; a rectangle can meet it only
//! if that cell lies between one cell before the rectangle's lower corner and the rectangle's
//! upper corner, so those cells (from two before, against rounding) hold every small body it
//! can meet. Larger bodies (the ground, a wall) are
//! listed apart and always tested. What a rectangle meets is decided by the placer's own test
//! (`labels::rect_hits_polygon`, handed in) as before: the placement is the same.

use bevy::math::{Rect, Vec2};

/// A cell's side is twice the bodies' mean box size, within these, logical pixels: a grain of
/// the 10,000-grain pile is 3.6 px across at the window's fit (cells of 8 px, about 5 grains),
/// a label about 100 x 16 px.
const MIN_CELL: f32 = 8.0;
const MAX_CELL: f32 = 64.0;

/// The bodies, binned.
pub struct BodyGrid<'a> {
    bodies: &'a [Vec<Vec2>],
    /// Whether a rectangle meets a body (the placer's test).
    hits: fn(&Rect, &[Vec2]) -> bool,
    /// Bodies more than a cell across, tested for every rectangle.
    large: Vec<usize>,
    /// The grid's lower corner (the view's), its cells' side and its size in cells.
    origin: Vec2,
    cell: f32,
    cols: i32,
    rows: i32,
    /// The small bodies filed cell by cell, row by row: cell c's are
    /// `filed[starts[c]..starts[c + 1]]` (one allocation, not one a cell).
    starts: Vec<u32>,
    filed: Vec<u32>,
}

impl<'a> BodyGrid<'a> {
    /// `bodies` (convex screen polygons) binned over `view`; a body outside it goes to the
    /// nearest edge cell, which keeps the rule above (cells are clamped on both sides alike).
    /// `hits` says whether a rectangle meets a body; it must find none apart from the
    /// rectangle along x or y.
    pub fn new(bodies: &'a [Vec<Vec2>], view: Rect, hits: fn(&Rect, &[Vec2]) -> bool) -> Self {
        let boxes: Vec<Option<(Vec2, Vec2)>> = bodies.iter().map(|p| bounds(p)).collect();
        let sizes = boxes
            .iter()
            .flatten()
            .map(|(lo, hi)| (*hi - *lo).max_element());
        let n = boxes.iter().flatten().count().max(1) as f32;
        let cell = (2.0 * sizes.sum::<f32>() / n).clamp(MIN_CELL, MAX_CELL);
        let cols = ((view.width() / cell).ceil() as i32).clamp(1, 4096);
        let rows = ((view.height() / cell).ceil() as i32).clamp(1, 4096);
        let mut grid = BodyGrid {
            bodies,
            hits,
            large: Vec::new(),
            origin: view.min,
            cell,
            cols,
            rows,
            starts: vec![0; (cols * rows) as usize + 1],
            filed: Vec::new(),
        };
        // Each small body's cell, counted, then filed by a counting sort.
        let mut home: Vec<(u32, u32)> = Vec::with_capacity(bodies.len());
        for (k, b) in boxes.iter().enumerate() {
            let Some((lo, hi)) = *b else {
                continue;
            };
            if hi.x - lo.x > cell || hi.y - lo.y > cell {
                grid.large.push(k);
            } else {
                let (c, r) = grid.cell_of(lo);
                let at = (r * cols + c) as u32;
                home.push((at, k as u32));
                grid.starts[at as usize + 1] += 1;
            }
        }
        for c in 1..grid.starts.len() {
            grid.starts[c] += grid.starts[c - 1];
        }
        let mut next = grid.starts.clone();
        grid.filed = vec![0; home.len()];
        for (at, k) in home {
            grid.filed[next[at as usize] as usize] = k;
            next[at as usize] += 1;
        }
        grid
    }

    /// The cell of point `p`, clamped into the grid.
    fn cell_of(&self, p: Vec2) -> (i32, i32) {
        let d = (p - self.origin) / self.cell;
        (
            (d.x.floor() as i32).clamp(0, self.cols - 1),
            (d.y.floor() as i32).clamp(0, self.rows - 1),
        )
    }

    /// The bodies `r` may meet: the large ones, then those filed from one cell (two, against
    /// rounding) before `r`'s lower corner to its upper corner's cell.
    fn near(&self, r: &Rect) -> impl Iterator<Item = usize> + '_ {
        let (c0, r0) = self.cell_of(r.min - Vec2::splat(2.0 * self.cell));
        let (c1, r1) = self.cell_of(r.max);
        let small = (r0..=r1).flat_map(move |row| {
            // A row's cells c0..=c1 are filed side by side.
            let (a, b) = (row * self.cols + c0, row * self.cols + c1 + 1);
            self.filed[self.starts[a as usize] as usize..self.starts[b as usize] as usize]
                .iter()
                .map(|k| *k as usize)
        });
        self.large.iter().copied().chain(small)
    }

    /// How many bodies `r` meets, counted up to one past `limit`.
    pub fn count_up_to(&self, r: &Rect, limit: usize) -> usize {
        let mut n = 0;
        for k in self.near(r) {
            if (self.hits)(r, &self.bodies[k]) {
                n += 1;
                if n > limit {
                    break;
                }
            }
        }
        n
    }

    /// Whether `r` meets any body.
    pub fn any(&self, r: &Rect) -> bool {
        self.near(r).any(|k| (self.hits)(r, &self.bodies[k]))
    }
}

/// A polygon's box (lower and upper corners); None when it has no point.
pub fn bounds(poly: &[Vec2]) -> Option<(Vec2, Vec2)> {
    let first = *poly.first()?;
    Some(
        poly.iter()
            .fold((first, first), |(lo, hi), p| (lo.min(*p), hi.max(*p))),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::app::labels::rect_hits_polygon;
    use proptest::prelude::*;

    /// A regular `n`-gon of radius `r` about `c`: convex, as the placer's bodies are (none for
    /// n = 0, an empty body).
    fn ngon(c: Vec2, r: f32, n: usize) -> Vec<Vec2> {
        (0..n)
            .map(|k| c + r * Vec2::from_angle(std::f32::consts::TAU * k as f32 / n as f32))
            .collect()
    }

    proptest! {
        /// The grid meets exactly what testing every body meets, so placing labels through it
        /// changes no place: small bodies and large ones (a tenth are ten times larger),
        /// empty ones, bodies and rectangles inside the view, across its edges and beyond.
        #[test]
        fn the_grid_meets_what_every_body_meets(
            bodies in prop::collection::vec(
                (-200.0f32..1200.0, -200.0f32..900.0, 0.5f32..20.0, 0usize..10), 0..300),
            rects in prop::collection::vec(
                (-300.0f32..1300.0, -300.0f32..1000.0, 1.0f32..200.0, 1.0f32..60.0), 1..40),
        ) {
            let view = Rect::new(0.0, 0.0, 1000.0, 700.0);
            let polys: Vec<Vec<Vec2>> = bodies
                .iter()
                .map(|&(x, y, r, n)| {
                    let r = if n == 9 { 10.0 * r } else { r };
                    ngon(Vec2::new(x, y), r, if n < 3 { 0 } else { n })
                })
                .collect();
            let grid = BodyGrid::new(&polys, view, rect_hits_polygon);
            for &(x, y, w, h) in &rects {
                let r = Rect::new(x, y, x + w, y + h);
                let every = polys.iter().filter(|p| rect_hits_polygon(&r, p)).count();
                prop_assert_eq!(grid.count_up_to(&r, usize::MAX), every, "{:?}", r);
                prop_assert_eq!(grid.any(&r), every > 0, "{:?}", r);
                prop_assert_eq!(grid.count_up_to(&r, 0), every.min(1), "{:?}", r);
            }
        }
    }
}
