//! The names overlay (N): each body's name beside it and each joint's name at its anchor, so the
//! scene says what the statement names (the cars A to F, a four-bar's O2, A, B, O4).
//!
//! A name's home is just outside its body, on the side away from the scene's middle (where the
//! free space usually is), turned toward a long body's thin side, never on the body's center; the label placer (`labels.rs`) then moves
//! it off other labels and bodies. A joint's name is pushed from its anchor away from the mass
//! centers of the bodies it joins, so it does not sit on the links.

use super::draw::Drawing;
use super::geometry::Outline;
use super::view::palette;
use crate::level::JointDef;
use crate::snapshot::{BodyKind, Snapshot};
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
    for &i in &shown {
        let b = &s.bodies[i];
        let o = &outlines[i];
        let dir = heading(o, b.position, b.angle, b.com, away(b.com - middle));
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
