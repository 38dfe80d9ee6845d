//! The names overlay (N): each body's name beside it and each joint's name at its anchor, so the
//! scene says what the statement names (the cars A to F, a four-bar's O2, A, B, O4).
//!
//! A name's home is just outside its body, on the side away from the scene's middle (where the
//! free space usually is), turned toward a long body's thin side, never on the body's center; the label placer (`labels.rs`) then moves
//! it off other labels and bodies. A joint's name is pushed from its anchor away from the mass
//! centers of the bodies it joins, so it does not sit on the links. When that side is taken by
//! another body (a row of touching balls, as Newton's cradle's), the name turns to the nearest
//! side where it lies clear of the others and nearer its own body than any other (`Others`).

use super::draw::Drawing;
use super::geometry::Outline;
use super::labels::rect_hits_polygon;
use super::view::palette;
use crate::level::JointDef;
use crate::snapshot::{BodyKind, Snapshot};
use bevy::math::{Rect, Vec2};
use glam::DVec2;

/// Beyond this many named bodies, only the selected one is named (a pile of 30 boxes named box1
/// to box30 hides the scene; its statement does not name them one by one).
pub const MANY: usize = 12;

/// Draws the names of `s`'s bodies (with an outline) and of the level's `joints` into `d`;
/// `selected`, when set, is the only body named in a crowded scene.
pub fn names(
    s: &Snapshot,
    joints: &[JointDef],
    outlines: &[Outline],
    selected: Option<usize>,
    d: &mut Drawing,
) {
    let shown = shown_bodies(s, outlines, selected);
    let middle = middle(s, &shown);
    let others = if shown.is_empty() {
        Others::default_for(s)
    } else {
        Others::of(s, outlines)
    };
    for &i in &shown {
        let b = &s.bodies[i];
        let o = &outlines[i];
        let wanted = heading(o, b.position, b.angle, b.com, away(b.com - middle));
        let dir = others.free_side(i, &b.name, wanted, d.m_per_px);
        let at = b.com + dir * reach(o, b.position, b.angle, b.com, dir);
        d.tip_label(at, dir, b.name.clone(), palette::TEXT);
    }
    if shown.len() > MANY {
        return;
    }
    // The joints from the level and the current poses (the snapshot's joint states exist only
    // after a step).
    let find = |name: &str| s.bodies.iter().position(|b| b.name == name);
    for j in joints {
        let (Some(i1), Some(i2)) = (find(&j.body1), find(&j.body2)) else {
            continue;
        };
        if j.name.is_empty() {
            continue;
        }
        let anchor = s.bodies[i2].world_point(DVec2::new(j.anchor2.0, j.anchor2.1));
        let moving: Vec<DVec2> = [i1, i2]
            .into_iter()
            .map(|k| &s.bodies[k])
            .filter(|b| b.kind != BodyKind::Fixed)
            .map(|b| b.com)
            .collect();
        let from = if moving.is_empty() {
            middle
        } else {
            moving.iter().copied().sum::<DVec2>() / moving.len() as f64
        };
        d.tip_label(
            anchor,
            away(anchor - from),
            j.name.clone(),
            palette::REACTION,
        );
    }
}

/// A name's estimated size, px: 7.2 px a character of the 13 px font, 16 px a line (what the
/// label placer's tests assume; the placer then measures the real text).
const CHAR_PX: f64 = 7.2;
const LINE_PX: f64 = 16.0;
/// How far out `label_want` (scene.rs) pushes a tip label past its point, px, before half its
/// size along the way.
const PUSH_PX: f64 = 5.0;

/// Every body's outline, for finding the side of a body where its name is clear of the others.
struct Others<'a> {
    s: &'a Snapshot,
    /// Each body's outline, body frame (none for a crowded scene with no body named).
    outlines: &'a [Outline],
    /// Each body's farthest outline point from its mass center, m: a body whose circle of
    /// that radius is farther from a name than its own body is skipped unmeasured.
    radii: Vec<f64>,
}

impl<'a> Others<'a> {
    /// No outlines read: nothing is named (a crowded scene with no body selected).
    fn default_for(s: &'a Snapshot) -> Self {
        Others {
            s,
            outlines: &[],
            radii: Vec::new(),
        }
    }

    /// The radii from the outlines' own points: a body's placement is rigid, so its points lie
    /// as far from its mass center in the world as in its frame. The world polygons are built
    /// only for the bodies measured ([`Others::polygons`]): built for every body, they were
    /// 400,000 points a frame in a 10,000-grain pile, to name its one selected grain.
    fn of(s: &'a Snapshot, outlines: &'a [Outline]) -> Self {
        let radii = s
            .bodies
            .iter()
            .enumerate()
            .map(|(i, b)| {
                outlines.get(i).map_or(0.0, |o| {
                    o.filled
                        .iter()
                        .flatten()
                        .map(|p| (*p - b.local_com).length())
                        .fold(0.0, f64::max)
                })
            })
            .collect();
        Others { s, outlines, radii }
    }

    /// Body `k`'s filled polygons in the world.
    fn polygons(&self, k: usize) -> Vec<Vec<DVec2>> {
        let b = &self.s.bodies[k];
        self.outlines.get(k).map_or_else(Vec::new, |o| {
            o.filled
                .iter()
                .map(|poly| poly.iter().map(|p| b.world_point(*p)).collect())
                .collect()
        })
    }

    /// The way body `i`'s name goes: `wanted` when the name there lies clear of every other body
    /// and nearer its own than any other, else the nearest such way in steps of 22.5 degrees
    /// (down before up at equal turns: a hanging body's string is above it), else `wanted`.
    /// Newton's cradle's balls touch side by side: away from the middle, ball 3's name landed on
    /// ball 4 and the placer moved it under ball 4 (seen in the page, 2026-12-07); it now goes
    /// under ball 3. `m_per_px` (the drawing's scale) sizes the name; without one, `wanted`.
    fn free_side(&self, i: usize, text: &str, wanted: DVec2, m_per_px: f64) -> DVec2 {
        if !(m_per_px > 0.0 && m_per_px.is_finite())
            || self.outlines.get(i).is_none_or(|o| o.filled.is_empty())
        {
            return wanted;
        }
        let chars = text.chars().count() as f64;
        let size = DVec2::new(CHAR_PX * chars, LINE_PX);
        let step = std::f64::consts::PI / 8.0;
        let turns = (0..=8).flat_map(|k| {
            let a = k as f64 * step;
            // At equal turns, the one whose way points lower first.
            let (p, q) = (rotated(wanted, -a), rotated(wanted, a));
            if k == 0 || k == 8 {
                vec![p]
            } else if p.y <= q.y {
                vec![p, q]
            } else {
                vec![q, p]
            }
        });
        for dir in turns {
            if self.clear(i, dir, size, m_per_px) {
                return dir;
            }
        }
        wanted
    }

    /// Whether body `i`'s name of `size` px, out along `dir`, touches no other body and lies
    /// nearer body `i` than any other (px, in the world's orientation around `i`'s center).
    fn clear(&self, i: usize, dir: DVec2, size: DVec2, m_per_px: f64) -> bool {
        let b = &self.s.bodies[i];
        let px = |p: DVec2| screen_vec((p - b.com) / m_per_px);
        let own_polygons = self.polygons(i);
        let out = own_polygons
            .iter()
            .flatten()
            .map(|p| (*p - b.com).dot(dir) / m_per_px)
            .fold(0.0, f64::max);
        let push = out + PUSH_PX + 0.5 * (dir.x.abs() * size.x + dir.y.abs() * size.y);
        let center = screen_vec(dir * push);
        let half = screen_vec(0.5 * size);
        let r = Rect::from_corners(center - half, center + half);
        let gap = |polygons: &[Vec<DVec2>]| {
            polygons
                .iter()
                .map(|poly| gap_px(&r, &poly.iter().map(|p| px(*p)).collect::<Vec<_>>()))
                .fold(f32::INFINITY, f32::min)
        };
        let own = gap(&own_polygons);
        // A body whose bounding circle lies farther than `own` from the name's box cannot be
        // nearer it than its own body: only the near ones are measured (a pile of thousands).
        let reach = f64::from(half.length()) + f64::from(own);
        let center = b.com + dir * push * m_per_px;
        (0..self.radii.len())
            .filter(|&k| k != i)
            .filter(|&k| {
                (self.s.bodies[k].com - center).length() - self.radii[k] <= reach * m_per_px
            })
            .all(|k| gap(&self.polygons(k)) > own)
    }
}

/// `v` as the label placer's f32 vector (bevy's glam, not the physics' one).
fn screen_vec(v: DVec2) -> Vec2 {
    Vec2::new(v.x as f32, v.y as f32)
}

/// `v` turned by `a` rad.
fn rotated(v: DVec2, a: f64) -> DVec2 {
    DVec2::from_angle(a).rotate(v)
}

/// The distance between rectangle `r` and convex polygon `poly`, px: 0 when they overlap, else
/// the least distance from a corner of one to an edge of the other.
fn gap_px(r: &Rect, poly: &[Vec2]) -> f32 {
    if poly.is_empty() {
        return f32::INFINITY;
    }
    if rect_hits_polygon(r, poly) {
        return 0.0;
    }
    let corners = [
        r.min,
        Vec2::new(r.max.x, r.min.y),
        r.max,
        Vec2::new(r.min.x, r.max.y),
    ];
    let to_rect = poly
        .iter()
        .map(|p| (p.clamp(r.min, r.max) - *p).length())
        .fold(f32::INFINITY, f32::min);
    let to_poly = corners
        .iter()
        .flat_map(|c| {
            (0..poly.len()).map(move |k| segment_distance(*c, poly[k], poly[(k + 1) % poly.len()]))
        })
        .fold(f32::INFINITY, f32::min);
    to_rect.min(to_poly)
}

/// The distance from `p` to the segment from `a` to `b`.
fn segment_distance(p: Vec2, a: Vec2, b: Vec2) -> f32 {
    let e = b - a;
    let t = if e.length_squared() > 0.0 {
        ((p - a).dot(e) / e.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + e * t - p).length()
}

/// The bodies to name: those with a filled outline (a fixed point body such as a four-bar's
/// ground is named by its joints), only the selected one when there are more than [`MANY`].
fn shown_bodies(s: &Snapshot, outlines: &[Outline], selected: Option<usize>) -> Vec<usize> {
    let all: Vec<usize> = (0..s.bodies.len())
        .filter(|&i| outlines.get(i).is_some_and(|o| !o.filled.is_empty()))
        .collect();
    if all.len() <= MANY {
        return all;
    }
    all.into_iter().filter(|i| Some(*i) == selected).collect()
}

/// The middle of the named bodies' mass centers.
fn middle(s: &Snapshot, shown: &[usize]) -> DVec2 {
    if shown.is_empty() {
        return DVec2::ZERO;
    }
    shown.iter().map(|&i| s.bodies[i].com).sum::<DVec2>() / shown.len() as f64
}

/// The unit direction of `v`, or up when `v` is too short to have one (a lone body, a body at
/// the middle): a name above its body reads as a caption.
fn away(v: DVec2) -> DVec2 {
    let len = v.length();
    if len > 1e-9 && len.is_finite() {
        v / len
    } else {
        DVec2::Y
    }
}

/// The way a body's name goes: `away`, turned toward the body's thin side in proportion to how
/// long the body is (its corners' second moments: k = 1 - sqrt(minor / major), 0 for a square or
/// a disc, 0.95 for a bar 20 times as long as it is thick). A link's name then sits beside it
/// instead of past its far end (the four-bar's coupler was named 0.1 m beyond its end, as far
/// from it as from the crank), and the way turns continuously with the body, so the name does
/// not hop from one side to another as it swings (the pendulum's labels hold their places).
fn heading(o: &Outline, position: DVec2, angle: f64, com: DVec2, away: DVec2) -> DVec2 {
    let r = DVec2::from_angle(angle);
    let (mut xx, mut xy, mut yy) = (0.0, 0.0, 0.0);
    for p in o.filled.iter().flatten() {
        let q = position + r.rotate(*p) - com;
        xx += q.x * q.x;
        xy += q.x * q.y;
        yy += q.y * q.y;
    }
    let half_gap = (0.25 * (xx - yy) * (xx - yy) + xy * xy).sqrt();
    let (major, minor) = (0.5 * (xx + yy) + half_gap, 0.5 * (xx + yy) - half_gap);
    if major <= 0.0 || !major.is_finite() {
        return away;
    }
    let k = 1.0 - (minor.max(0.0) / major).sqrt();
    let u = DVec2::from_angle(0.5 * (2.0 * xy).atan2(xx - yy));
    let d = away - k * away.dot(u) * u;
    let len = d.length();
    if len > 1e-9 {
        d / len
    } else {
        away
    }
}

/// How far the body reaches from `com` along `dir`, m: the largest projection of its outline's
/// corners (its edge on that side), so the name starts past the body.
fn reach(o: &Outline, position: DVec2, angle: f64, com: DVec2, dir: DVec2) -> f64 {
    let r = DVec2::from_angle(angle);
    o.filled
        .iter()
        .flatten()
        .chain(o.circles.iter().map(|(c, _)| c))
        .map(|p| (position + r.rotate(*p) - com).dot(dir))
        .chain(
            o.circles
                .iter()
                .map(|(c, rad)| (position + r.rotate(*c) - com).dot(dir) + rad),
        )
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_name_goes_away_from_the_middle_or_up() {
        assert_eq!(away(DVec2::new(3.0, 4.0)), DVec2::new(0.6, 0.8));
        assert_eq!(away(DVec2::ZERO), DVec2::Y);
        assert_eq!(away(DVec2::NAN), DVec2::Y);
    }

    #[test]
    fn a_long_link_is_named_beside_its_middle() {
        // A 2 m by 0.1 m bar turned 30 degrees, the middle straight below it. Straight up, the
        // bar reaches 1 sin 30 + 0.05 cos 30 = 0.543 m (past its end). Its corners' moments
        // are 4 (along) and 0.01 (across): k = 1 - 0.05 = 0.95, the way is up less 0.95 of its
        // part along the bar, (0, 1) - 0.475 (cos 30, sin 30) = (-0.411, 0.763), unit
        // (-0.475, 0.880); the bar reaches 1 |d.u| + 0.05 |d.n| = 0.0289 + 0.0500 = 0.0789 m.
        let o = Outline {
            filled: vec![vec![
                DVec2::new(-1.0, -0.05),
                DVec2::new(1.0, -0.05),
                DVec2::new(1.0, 0.05),
                DVec2::new(-1.0, 0.05),
            ]],
            ..Default::default()
        };
        let a = 30f64.to_radians();
        let d = heading(&o, DVec2::ZERO, a, DVec2::ZERO, DVec2::Y);
        assert!((d - DVec2::new(-0.4748, 0.8801)).length() < 1e-3, "{d}");
        let out = reach(&o, DVec2::ZERO, a, DVec2::ZERO, d);
        assert!((out - 0.0789).abs() < 1e-3, "{out}");
        // A square keeps the way away from the middle.
        let sq = Outline {
            filled: vec![vec![
                DVec2::new(-1.0, -1.0),
                DVec2::new(1.0, -1.0),
                DVec2::new(1.0, 1.0),
                DVec2::new(-1.0, 1.0),
            ]],
            ..Default::default()
        };
        let v = DVec2::new(0.6, 0.8);
        assert!((heading(&sq, DVec2::ZERO, 0.3, DVec2::ZERO, v) - v).length() < 1e-12);
    }

    #[test]
    fn reach_is_the_edge_along_the_direction() {
        // A 2 m by 1 m box centered on its origin, turned a quarter turn: along x it reaches
        // half its height, 0.5 m; along y half its width, 1 m.
        let o = Outline {
            filled: vec![vec![
                DVec2::new(-1.0, -0.5),
                DVec2::new(1.0, -0.5),
                DVec2::new(1.0, 0.5),
                DVec2::new(-1.0, 0.5),
            ]],
            ..Default::default()
        };
        let q = std::f64::consts::FRAC_PI_2;
        assert!((reach(&o, DVec2::ZERO, q, DVec2::ZERO, DVec2::X) - 0.5).abs() < 1e-12);
        assert!((reach(&o, DVec2::ZERO, q, DVec2::ZERO, DVec2::Y) - 1.0).abs() < 1e-12);
    }
}
