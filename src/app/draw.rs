//! A frame's line drawing as plain data (world coordinates, m), then emitted as gizmos.
//!
//! The scene and overlay builders fill a [`Drawing`] from the snapshot; `emit_gizmos` turns it into
//! Bevy gizmos and the labels are painted by egui in screen space. Keeping the drawing as data lets
//! the frame benchmark time everything up to the renderer.

use bevy::gizmos::config::GizmoConfigGroup;
use bevy::gizmos::gizmos::GizmoBuffer;
use bevy::prelude::*;
use glam::DVec2;

/// Bevy's glam (0.32) from the core's (0.33): field copy.
pub fn v2(p: DVec2) -> Vec2 {
    Vec2::new(p.x as f32, p.y as f32)
}

/// One line primitive, world coordinates.
#[derive(Debug, Clone, PartialEq)]
pub enum Prim {
    Line(DVec2, DVec2, Color),
    /// A polyline, closed or open.
    Poly(Vec<DVec2>, bool, Color),
    /// An arrow; the tip length is in pixels (screen-constant heads).
    Arrow(DVec2, DVec2, Color),
    Circle(DVec2, f64, Color),
    /// A dot of a given radius in pixels.
    Dot(DVec2, f64, Color),
    /// A dashed line (dash length in pixels).
    Dashed(DVec2, DVec2, Color),
    /// A circular arrow (couple, angular velocity) around a point, radius in pixels, CCW if positive.
    Curl(DVec2, f64, f64, Color),
}

/// A text label at a world point, offset in pixels.
#[derive(Debug, Clone, PartialEq)]
pub struct Label {
    pub at: DVec2,
    pub offset: Vec2,
    /// Screen direction (y down) to push the label out along, clear of the point (arrow tips);
    /// zero: centered on the point.
    pub dir: Vec2,
    pub text: String,
    pub color: Color,
    pub size: f32,
}

/// The steps of a frame's drawing, in order: the scene's lines, the overlays (one system each,
/// `overlay_systems.rs`), the tools' marks, then the scale bar and the gizmos.
#[derive(SystemSet, Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DrawStep {
    Scene,
    Overlays,
    Marks,
    Finish,
}

/// What a frame draws besides the filled meshes.
#[derive(Resource, Debug, Clone, Default)]
pub struct Drawing {
    pub prims: Vec<Prim>,
    pub labels: Vec<Label>,
    /// The bodies' filled convex parts, world coordinates: labels are kept off them.
    pub bodies: Vec<Vec<DVec2>>,
    /// The balls drawn by their meshes (app/ball_meshes.rs), center and radius, world
    /// coordinates: labels are kept off their circumscribed octagons ([`ball_octagon`], built
    /// on screen), built only for the balls near a label (`app::screen_bodies_within`).
    pub balls: Vec<(DVec2, f64)>,
    /// Meters per logical pixel of the view the drawing was built for.
    pub m_per_px: f64,
}

impl Drawing {
    pub fn clear(&mut self, m_per_px: f64) {
        self.prims.clear();
        self.labels.clear();
        self.bodies.clear();
        self.balls.clear();
        self.m_per_px = m_per_px;
    }
    pub fn label(&mut self, at: DVec2, offset: Vec2, text: impl Into<String>, color: Color) {
        self.labels.push(Label {
            at,
            offset,
            dir: Vec2::ZERO,
            text: text.into(),
            color,
            size: 13.0,
        });
    }

    /// A label just beyond an arrow's tip, along the arrow (world direction `dir`).
    pub fn tip_label(&mut self, tip: DVec2, dir: DVec2, text: impl Into<String>, color: Color) {
        let d = Vec2::new(dir.x as f32, -dir.y as f32).normalize_or_zero();
        self.labels.push(Label {
            at: tip,
            offset: Vec2::ZERO,
            dir: if d == Vec2::ZERO {
                Vec2::new(0.0, -1.0)
            } else {
                d
            },
            text: text.into(),
            color,
            size: 13.0,
        });
    }
}

/// The octagon around a ball's circle (`center`, radius `r`), in the coordinates `center` and
/// `r` are given in (the label placer's screen pixels, y down: the octagon is symmetric): what
/// the labels keep off for a ball drawn by its mesh. Its sides touch the circle; its vertices,
/// at multiples of 45 degrees, lie [`octagon_reach`] out, which bounds it on each axis.
pub fn ball_octagon(center: Vec2, r: f32) -> Vec<Vec2> {
    // cos and sin of k 45 degrees, k = 0..8, without 80,000 sine calls a frame in a pile.
    const H: f32 = std::f32::consts::FRAC_1_SQRT_2;
    const WAYS: [(f32, f32); 8] = [
        (1.0, 0.0),
        (H, H),
        (0.0, 1.0),
        (-H, H),
        (-1.0, 0.0),
        (-H, -H),
        (0.0, -1.0),
        (H, -H),
    ];
    let big = octagon_reach(r);
    WAYS.iter()
        .map(|(c, s)| center + Vec2::new(*c, *s) * big)
        .collect()
}

/// How far [`ball_octagon`]'s vertices lie from its center: r / cos(pi / 8).
pub fn octagon_reach(r: f32) -> f32 {
    r / (std::f32::consts::PI / 8.0).cos()
}

/// Screen-constant sizes (pixels) of heads and dashes.
const ARROW_HEAD_PX: f64 = 9.0;
const DASH_PX: f64 = 6.0;

/// How far, in pixels, a drawn chord may stray from the circle it stands for: a tenth of a
/// pixel, which no line width shows. Small circles (a mass-center ring, a grain of a 10,000-body
/// pile a few pixels wide) need far fewer segments than the 48 a large one is drawn with.
const CHORD_PX: f64 = 0.1;

/// A polyline's points closer than this to the last point drawn are skipped, pixels: the sagitta
/// of a 1 px chord on a circle of radius r px is 1/(8 r) px, under CHORD_PX from r = 1.25 px.
const MIN_STEP_PX: f64 = 1.0;

/// Segments for a circle of `r_px` pixels: the fewest whose chords stay within `CHORD_PX` of
/// the arc (sagitta r (1 - cos(pi / n)) <= CHORD_PX), between 6 and `max`.
pub fn circle_resolution(r_px: f64, max: u32) -> u32 {
    if r_px.is_nan() || r_px <= CHORD_PX {
        return 6.min(max);
    }
    let n = (std::f64::consts::PI / (1.0 - CHORD_PX / r_px).acos()).ceil();
    (n.min(max as f64) as u32).clamp(6.min(max), max)
}

/// A polyline's points as drawn at `m_per_px`: each point closer than `MIN_STEP_PX` to the
/// last one kept is skipped (a 40-point circle outline 4 pixels across gives about 12); the
/// first and last points are always kept.
pub fn thinned(pts: &[DVec2], m_per_px: f64) -> impl Iterator<Item = Vec2> + '_ {
    let step2 = (MIN_STEP_PX * m_per_px).powi(2);
    let n = pts.len();
    let mut last: Option<DVec2> = None;
    pts.iter().enumerate().filter_map(move |(k, p)| {
        let keep = k + 1 == n || last.is_none_or(|l| (*p - l).length_squared() >= step2);
        keep.then(|| {
            last = Some(*p);
            v2(*p)
        })
    })
}

pub fn emit_gizmos(drawing: Res<Drawing>, mut gizmos: Gizmos) {
    emit(&drawing, &mut gizmos);
}

/// The drawing as gizmo line vertices (the CPU side of the line rendering).
pub fn emit<C: GizmoConfigGroup, K: 'static + Send + Sync>(
    drawing: &Drawing,
    gizmos: &mut GizmoBuffer<C, K>,
) {
    let px = drawing.m_per_px.max(1e-12);
    // Arrows last, over the markers and outlines (a pin's impulse arrow ended under the pin).
    let arrow = |p: &&Prim| matches!(p, Prim::Arrow(..) | Prim::Curl(..));
    let (arrows, rest): (Vec<&Prim>, Vec<&Prim>) = drawing.prims.iter().partition(arrow);
    for p in rest.into_iter().chain(arrows) {
        match p {
            Prim::Line(a, b, c) => gizmos.line_2d(v2(*a), v2(*b), *c),
            Prim::Poly(pts, closed, c) => {
                let it = thinned(pts, px);
                if *closed && pts.len() > 2 {
                    gizmos.linestrip_2d(it.chain(std::iter::once(v2(pts[0]))), *c);
                } else {
                    gizmos.linestrip_2d(it, *c);
                }
            }
            Prim::Arrow(a, b, c) => {
                let len = (*b - *a).length();
                if len <= 0.5 * px {
                    continue;
                }
                // The shaft as a line, the head as a strip: Bevy draws the strips (circles,
                // outlines) after the lines, so a head drawn with `arrow_2d` went under a pin's
                // dot; strips keep their order, and arrows come last.
                let u = (*b - *a) / len;
                let h = (ARROW_HEAD_PX * px).min(0.5 * len);
                let back = *b - u * h;
                let side = u.perp() * 0.45 * h;
                gizmos.line_2d(v2(*a), v2(*b), *c);
                gizmos.linestrip_2d([v2(back + side), v2(*b), v2(back - side)], *c);
            }
            Prim::Circle(center, r, c) => {
                gizmos
                    .circle_2d(Isometry2d::from_translation(v2(*center)), *r as f32, *c)
                    .resolution(circle_resolution(r / px, 48));
            }
            Prim::Dot(center, r_px, c) => {
                // A small filled-looking dot: concentric circles.
                let r = r_px * px;
                for k in 1..=3 {
                    gizmos
                        .circle_2d(
                            Isometry2d::from_translation(v2(*center)),
                            (r * k as f64 / 3.0) as f32,
                            *c,
                        )
                        .resolution(circle_resolution(r_px * k as f64 / 3.0, 16));
                }
            }
            Prim::Dashed(a, b, c) => {
                let d = *b - *a;
                let len = d.length();
                if len <= 0.0 {
                    continue;
                }
                let dash = DASH_PX * px;
                let n = (len / (2.0 * dash)).ceil() as usize;
                let u = d / len;
                for k in 0..n.min(2000) {
                    let s0 = 2.0 * dash * k as f64;
                    let s1 = (s0 + dash).min(len);
                    gizmos.line_2d(v2(*a + u * s0), v2(*a + u * s1), *c);
                }
            }
            Prim::Curl(center, r_px, sign, c) => {
                // Three quarters of a circle with a head at the end, turning the way of `sign`.
                let r = r_px * px;
                let n = 24;
                let a0 = -0.75 * std::f64::consts::PI;
                let sweep = 1.5 * std::f64::consts::PI * sign.signum();
                let pts: Vec<DVec2> = (0..=n)
                    .map(|k| *center + DVec2::from_angle(a0 + sweep * k as f64 / n as f64) * r)
                    .collect();
                gizmos.linestrip_2d(pts.iter().copied().map(v2), *c);
                let end = pts[n];
                let tangent = DVec2::from_angle(a0 + sweep).perp() * sign.signum();
                let h = ARROW_HEAD_PX * px;
                let back = end - tangent * h;
                let side = tangent.perp() * 0.45 * h;
                gizmos.line_2d(v2(end), v2(back + side), *c);
                gizmos.line_2d(v2(end), v2(back - side), *c);
            }
        }
    }
}

/// Formats a value with 3 significant figures and its SI unit.
pub fn si(value: f64, unit: &str) -> String {
    let a = value.abs();
    let s = if a == 0.0 || (1e-3..1e5).contains(&a) {
        let digits = if a == 0.0 {
            2
        } else {
            (2 - a.log10().floor() as i32).clamp(0, 6) as usize
        };
        format!("{value:.digits$}")
    } else {
        format!("{value:.2e}")
    };
    if unit.is_empty() {
        s
    } else {
        format!("{s} {unit}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_small_circle_gets_the_segments_its_size_needs() {
        // Sagitta r (1 - cos(pi / n)) <= 0.1 px: 48 segments hold it up to r = 46.7 px
        // (0.1 / (1 - cos(pi / 48))), and a 3 px ring needs 13 (pi / acos(1 - 0.1 / 3) = 12.1).
        assert_eq!(circle_resolution(46.0, 48), 48);
        assert_eq!(circle_resolution(500.0, 48), 48);
        assert_eq!(circle_resolution(3.0, 48), 13);
        for r in [0.0, 0.05, 0.5, 1.0, 2.0, 3.0, 10.0, 30.0] {
            let n = circle_resolution(r, 48);
            let sagitta = r * (1.0 - (std::f64::consts::PI / n as f64).cos());
            assert!(
                n >= 6 && (sagitta <= CHORD_PX + 1e-12 || n == 48),
                "{r} px: {n}"
            );
        }
        assert_eq!(circle_resolution(f64::NAN, 48), 6);
    }

    #[test]
    fn thinning_keeps_what_a_pixel_shows() {
        // A 40-point circle 2 px in radius (perimeter 12.6 px): points 1 px apart or more.
        let pts: Vec<DVec2> = (0..40)
            .map(|k| DVec2::from_angle(std::f64::consts::TAU * k as f64 / 40.0) * 2.0)
            .collect();
        let kept: Vec<Vec2> = thinned(&pts, 1.0).collect();
        assert!(kept.len() < 20 && kept.len() >= 10, "{}", kept.len());
        assert_eq!(kept[0], v2(pts[0]));
        assert_eq!(*kept.last().unwrap(), v2(pts[39]));
        // At 100 px per metre unit (m_per_px = 0.01) nothing is dropped.
        assert_eq!(thinned(&pts, 0.01).count(), 40);
    }

    #[test]
    fn si_keeps_three_significant_figures() {
        assert_eq!(si(3.13209, "m/s"), "3.13 m/s");
        assert_eq!(si(19.62, "N"), "19.6 N");
        assert_eq!(si(0.0123, "m"), "0.0123 m");
        assert_eq!(si(1234.0, "J"), "1234 J");
        assert_eq!(si(2.5e-6, "N"), "2.50e-6 N");
    }
}
