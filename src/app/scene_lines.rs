//! The scene as lines, textbook style: body outlines with rotation spokes, pins and their
//! supports, joints, springs, couplings (an unwinding string as its cord), ground hatching, the
//! scale bar, and the selected body's highlight.

use super::draw::{si, Drawing, Prim};
use super::geometry::{self, Outline};
use super::view::{palette, SceneIndex, View};
use crate::level::{Coordinate, CouplingDef, JointKind, Level};
use crate::snapshot::{BodyKind, Snapshot};
use bevy::prelude::*;
use glam::DVec2;

/// Bodies (outlines, rotation spokes, pins), joints, springs and ground as lines.
pub fn scene_lines(
    level: &Level,
    outlines: &[Outline],
    index: &SceneIndex,
    s: &Snapshot,
    m_per_px: f64,
    d: &mut Drawing,
) {
    body_lines(outlines, index, s, m_per_px, d);
    joint_lines(level, outlines, index, s, m_per_px, d);
    coupling_lines(level, outlines, index, s, m_per_px, d);
    spring_lines(s, m_per_px, d);
}

/// Each body's outline, rotation spokes, ground hatching, pin support and mass center.
fn body_lines(
    outlines: &[Outline],
    index: &SceneIndex,
    s: &Snapshot,
    m_per_px: f64,
    d: &mut Drawing,
) {
    // Ground hatching goes on the side away from the moving bodies.
    let (sum, n) = s
        .bodies
        .iter()
        .filter(|b| b.kind != BodyKind::Fixed)
        .fold((DVec2::ZERO, 0usize), |(s, n), b| (s + b.com, n + 1));
    let toward = (n > 0).then(|| sum / n as f64);
    for (i, b) in s.bodies.iter().enumerate() {
        let Some(o) = outlines.get(i) else { continue };
        let to_world = geometry::place(o, b.position, b.angle);
        if index.meshed.get(i).copied().unwrap_or(false) {
            // Its mesh draws it whole (app/ball_meshes.rs); labels keep off its octagon.
            let (c, r) = o.circles.first().copied().unwrap_or((DVec2::ZERO, 0.0));
            d.balls.push((to_world(c), r));
            continue;
        }
        let color = palette::OUTLINE;
        for poly in &o.filled {
            let world: Vec<DVec2> = poly.iter().map(|p| to_world(*p)).collect();
            d.bodies.push(world.clone());
            d.prims.push(Prim::Poly(world, true, color));
        }
        // A spoke on each circle shows the rotation.
        for (c, r) in &o.circles {
            d.prims.push(Prim::Line(
                to_world(*c),
                to_world(*c + DVec2::new(*r, 0.0)),
                color,
            ));
        }
        for (k, (a, bb)) in o.segments.iter().enumerate() {
            let (a, bb) = (to_world(*a), to_world(*bb));
            if b.kind == BodyKind::Fixed {
                // An arc's pieces hatch on its solid side; lines away from the moving bodies.
                match o
                    .solid_side
                    .binary_search_by_key(&k, |(i, _)| *i)
                    .ok()
                    .map(|j| &o.solid_side[j])
                {
                    Some((_, n)) => {
                        let n = DVec2::from_angle(b.angle).rotate(*n);
                        let mid = 0.5 * (a + bb);
                        ground(a, bb, m_per_px, Some(mid - n), d);
                    }
                    None => ground(a, bb, m_per_px, toward, d),
                }
            } else {
                d.prims.push(Prim::Line(a, bb, color));
            }
        }
        if b.kind == BodyKind::Fixed
            && o.filled.is_empty()
            && o.segments.is_empty()
            && !index.jointed[i]
        {
            pin_support(b.position, m_per_px, d);
        }
        // Mass center symbol on moving bodies.
        if b.kind != BodyKind::Fixed && b.mass > 0.0 {
            d.prims.push(Prim::Circle(b.com, 3.0 * m_per_px, color));
        }
    }
}

/// Each joint's symbol at its anchor, the light links that reach it and the supports of fixed
/// point bodies.
fn joint_lines(
    level: &Level,
    outlines: &[Outline],
    index: &SceneIndex,
    s: &Snapshot,
    m_per_px: f64,
    d: &mut Drawing,
) {
    // Joints and couplings from the level and the current poses (the snapshot's joint states
    // exist only after a step).
    for (def, &(i1, i2)) in level.joints.iter().zip(&index.joints) {
        let (b1, b2) = (&s.bodies[i1], &s.bodies[i2]);
        let anchor1 = b1.world_point(DVec2::new(def.anchor1.0, def.anchor1.1));
        let anchor = b2.world_point(DVec2::new(def.anchor2.0, def.anchor2.1));
        let r = 4.0 * m_per_px;
        // An anchor off a moving body's shape is reached by a light rigid link (a pendulum rod).
        for (bi, a) in [(i2, anchor), (i1, anchor1)] {
            let b = &s.bodies[bi];
            if b.kind == BodyKind::Fixed {
                continue;
            }
            let local = DVec2::from_angle(-b.angle).rotate(a - b.position);
            let inside = outlines
                .get(bi)
                .is_some_and(|o| o.contains(local, m_per_px));
            if !inside {
                link(b.com, a, m_per_px, d);
            }
        }
        match def.kind {
            JointKind::Revolute => {
                d.prims.push(Prim::Circle(anchor, r, palette::JOINT));
                d.prims.push(Prim::Circle(anchor, 0.4 * r, palette::JOINT));
            }
            JointKind::Fixed => {
                let q = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                    .map(|(x, y)| anchor + DVec2::new(x, y) * r)
                    .to_vec();
                d.prims.push(Prim::Poly(q, true, palette::JOINT));
            }
            JointKind::Prismatic | JointKind::PinSlot => {
                let axis = DVec2::new(def.axis.0, def.axis.1).normalize_or(DVec2::X);
                let u = DVec2::from_angle(b1.angle).rotate(axis);
                let n = u.perp() * r;
                let half = u * 24.0 * m_per_px;
                // The slot: two rails along the axis through body1's anchor.
                for side in [-1.0, 1.0] {
                    d.prims.push(Prim::Line(
                        anchor1 - half + n * side,
                        anchor1 + half + n * side,
                        palette::JOINT,
                    ));
                }
                d.prims.push(Prim::Circle(anchor, 0.8 * r, palette::JOINT));
            }
        }
        // A fixed point body shows as a pin support where the joint holds it.
        for (bi, a) in [(i1, anchor1), (i2, anchor)] {
            if s.bodies[bi].kind == BodyKind::Fixed
                && outlines
                    .get(bi)
                    .is_some_and(|o| o.filled.is_empty() && o.segments.is_empty())
            {
                pin_support(a, m_per_px, d);
            }
        }
    }
}

/// Couplings: a dashed line between their bodies, or the string a body unwinds from.
fn coupling_lines(
    level: &Level,
    outlines: &[Outline],
    index: &SceneIndex,
    s: &Snapshot,
    m_per_px: f64,
    d: &mut Drawing,
) {
    // Couplings (pulleys, cables, gears) have no drawn path: a dashed line joins their bodies;
    // a string unwinding from one body (a yo-yo's) is drawn as the cord it is.
    for (def, bodies) in level.couplings.iter().zip(&index.couplings) {
        if let Some((i, side)) = unwinding(def, bodies) {
            unwinding_string(level, outlines, s, (i, side), &def.name, m_per_px, d);
            continue;
        }
        for w in bodies.windows(2) {
            d.prims.push(Prim::Dashed(
                s.bodies[w[0]].com,
                s.bodies[w[1]].com,
                palette::COUPLING,
            ));
        }
        if let Some(&first) = bodies.first() {
            d.label(
                s.bodies[first].com,
                Vec2::new(0.0, 16.0),
                def.name.clone(),
                palette::COUPLING,
            );
        }
    }
}

/// Springs as coils, with a support where one end is fixed in the world.
fn spring_lines(s: &Snapshot, m_per_px: f64, d: &mut Drawing) {
    for sp in &s.springs {
        if sp.torsion {
            coil(sp.point1, m_per_px, d);
            continue;
        }
        spring(sp.point1, sp.point2, m_per_px, d);
        if sp.body2.is_none() {
            pin_support(sp.point2, m_per_px, d);
        }
    }
}

/// A coupling that is a string unwinding from one body: a y term and an angle term of the same
/// body, a y + b theta = const (the yo-yo's y - r theta = const). Then a v_y + b omega = 0, and
/// the point at (s, 0) from G, moving up at v_y + omega s, is at rest for s = b / a: the string
/// leaves there and runs straight up (r to the left of the yo-yo's axle for b / a = -r).
/// Returns the body and s. An x term with an angle term is a rolling contact or a rack, not a
/// string, and keeps its dashed line.
fn unwinding(def: &CouplingDef, bodies: &[usize]) -> Option<(usize, f64)> {
    // One body index per term: the same body in both.
    let (&body, rest) = bodies.split_first()?;
    if rest.iter().any(|&k| k != body) {
        return None;
    }
    let [t1, t2] = def.terms.as_slice() else {
        return None;
    };
    let (y, angle) = match (t1.coordinate, t2.coordinate) {
        (Coordinate::Y, Coordinate::Angle) => (t1, t2),
        (Coordinate::Angle, Coordinate::Y) => (t2, t1),
        _ => return None,
    };
    let side = angle.ratio / y.ratio;
    (side.is_finite() && side != 0.0).then_some((body, side))
}

/// The unwinding string of body `i` (leaving at `side` m beside its center): the axle it winds
/// on, and the cord from there straight up to its fixed end, a support four body radii above
/// where the body started (the level gives the string's top no place of its own; fixed, so the
/// string pays out as the body falls).
fn unwinding_string(
    level: &Level,
    outlines: &[Outline],
    s: &Snapshot,
    (i, side): (usize, f64),
    name: &str,
    m_per_px: f64,
    d: &mut Drawing,
) {
    let (Some(b), Some(def)) = (s.bodies.get(i), level.bodies.get(i)) else {
        return;
    };
    let reach = outlines
        .get(i)
        .into_iter()
        .flat_map(|o| o.filled.iter().flatten())
        .map(|p| p.length())
        .fold(0.0, f64::max);
    let leaves = b.com + DVec2::new(side, 0.0);
    let top = DVec2::new(leaves.x, def.position.1 + 4.0 * reach.max(side.abs()));
    if top.y <= leaves.y {
        return;
    }
    d.prims
        .push(Prim::Circle(b.com, side.abs(), palette::COUPLING));
    d.prims.push(Prim::Line(leaves, top, palette::COUPLING));
    pin_support(top, m_per_px, d);
    d.label(
        0.5 * (leaves + top),
        Vec2::ZERO,
        name.to_string(),
        palette::COUPLING,
    );
}

/// A light rod between two points: a narrow outlined bar.
fn link(a: DVec2, b: DVec2, m_per_px: f64, d: &mut Drawing) {
    let e = b - a;
    if e.length() <= 1e-12 {
        return;
    }
    let n = e.normalize().perp() * 1.5 * m_per_px;
    d.prims.push(Prim::Poly(
        vec![a + n, b + n, b - n, a - n],
        true,
        palette::OUTLINE,
    ));
}

/// A zigzag spring between two points, with straight end leads.
fn spring(a: DVec2, b: DVec2, m_per_px: f64, d: &mut Drawing) {
    let e = b - a;
    let len = e.length();
    if len <= 1e-12 {
        return;
    }
    let u = e / len;
    let n = u.perp();
    let lead = 0.15 * len;
    let coils = 8;
    let amp = (6.0 * m_per_px).min(0.15 * len);
    let mut pts = vec![a, a + u * lead];
    for k in 0..(2 * coils) {
        let s = lead + (len - 2.0 * lead) * (k as f64 + 0.5) / (2 * coils) as f64;
        let side = if k % 2 == 0 { 1.0 } else { -1.0 };
        pts.push(a + u * s + n * amp * side);
    }
    pts.push(b - u * lead);
    pts.push(b);
    d.prims.push(Prim::Poly(pts, false, palette::SPRING));
}

/// A torsion spring: a flat spiral around body1's G (the format gives it no place of its own: its
/// couples act on whole bodies), 2.5 turns out to 12 px.
fn coil(c: DVec2, m_per_px: f64, d: &mut Drawing) {
    let turns = 2.5;
    let n = 60;
    let pts = (0..=n)
        .map(|k| {
            let f = k as f64 / n as f64;
            let r = (3.0 + 9.0 * f) * m_per_px;
            c + DVec2::from_angle(f * turns * std::f64::consts::TAU) * r
        })
        .collect();
    d.prims.push(Prim::Poly(pts, false, palette::SPRING));
}

/// Ground: the line with hatching on its solid side (textbook support symbol): away from
/// `toward` (the moving bodies), else below a left-to-right line.
fn ground(a: DVec2, b: DVec2, m_per_px: f64, toward: Option<DVec2>, d: &mut Drawing) {
    d.prims.push(Prim::Line(a, b, palette::GROUND));
    let e = b - a;
    let len = e.length();
    if len <= 0.0 {
        return;
    }
    let u = e / len;
    let mut down = -u.perp();
    if let Some(t) = toward {
        if (t - a).dot(down) > 0.0 {
            down = -down;
        }
    }
    let spacing = 10.0 * m_per_px;
    let n = ((len / spacing) as usize).min(4000);
    let h = 7.0 * m_per_px;
    for k in 0..=n {
        let p = a + u * (k as f64 * spacing);
        d.prims
            .push(Prim::Line(p, p + (down - u) * h, palette::GROUND));
    }
}

/// A fixed pin: a small triangle with hatching under it.
fn pin_support(p: DVec2, m_per_px: f64, d: &mut Drawing) {
    let s = 8.0 * m_per_px;
    let tri = vec![p, p + DVec2::new(-s, s * 1.4), p + DVec2::new(s, s * 1.4)];
    // Drawn upward (a ceiling pin): pendulums hang from their pivots.
    d.prims.push(Prim::Poly(tri, true, palette::GROUND));
    ground(
        p + DVec2::new(s * 1.4, s * 1.4),
        p + DVec2::new(-s * 1.4, s * 1.4),
        m_per_px,
        None,
        d,
    );
    d.prims
        .push(Prim::Circle(p, 3.0 * m_per_px, palette::JOINT));
}

/// A scale bar in the lower left corner of the view: a round length near 120 px, labelled in m.
pub fn scale_bar(view: &View, d: &mut Drawing) {
    let target = 120.0 * view.m_per_px;
    let mag = 10f64.powf(target.log10().floor());
    let len = [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|k| k * mag)
        .rfind(|l| *l <= target)
        .unwrap_or(mag);
    let vp = view.viewport;
    let a = view.to_world(Vec2::new(vp.min.x + 20.0, vp.max.y - 24.0));
    let b = a + DVec2::new(len, 0.0);
    let tick = DVec2::new(0.0, 5.0 * view.m_per_px);
    d.prims.push(Prim::Line(a, b, palette::TEXT));
    d.prims.push(Prim::Line(a - tick, a + tick, palette::TEXT));
    d.prims.push(Prim::Line(b - tick, b + tick, palette::TEXT));
    d.label(
        0.5 * (a + b),
        Vec2::new(0.0, -12.0),
        si(len, "m"),
        palette::TEXT,
    );
}

/// The selected body's outline, drawn again in the highlight color.
pub fn highlight(outlines: &[Outline], s: &Snapshot, i: usize, d: &mut Drawing) {
    let (Some(o), Some(b)) = (outlines.get(i), s.bodies.get(i)) else {
        return;
    };
    let to_world = geometry::place(o, b.position, b.angle);
    for poly in &o.filled {
        d.prims.push(Prim::Poly(
            poly.iter().map(|p| to_world(*p)).collect(),
            true,
            palette::FRICTION,
        ));
    }
    for (a, bb) in &o.segments {
        d.prims
            .push(Prim::Line(to_world(*a), to_world(*bb), palette::FRICTION));
    }
}
