//! The reference trajectory's rolling contacts: a round body (a `Circle`) rolling without slip
//! on a fixed straight face (a box's, a polygon's, a segment's, a polyline's edge) or on a
//! fixed circular `Arc`, inside or outside (RK-8). Both are holonomic on a fixed surface: the
//! disc's center keeps its distance from the face (R - r from an arc's center inside, R + r
//! outside), and the material point at the contact has no velocity along the face. They enter
//! the reference as two constraint rows each, the normal row's multiplier the normal force N
//! and the tangent row's the friction force F.
//!
//! Found at the start from the level's geometry: a round dynamic body touching a fixed body
//! within 1e-6 m + 1e-4 of its size (as `resting_contacts` judges it). Any other touch at the
//! start is outside the reference, said with the reason: a body that is not round, a moving
//! other body (two moving bodies, a kinematic one), a corner, several places at once.

use crate::analysis::resting_contacts::{edges, gap, pieces, to_segment};
use crate::level::{ArcSide, BodyDef, BodyKind, Effect, Level, Shape};
use glam::DVec2;
use std::f64::consts::TAU;

/// The fixed surface a disc rolls on, in world axes.
#[derive(Debug, Clone, Copy)]
pub(super) enum Surface {
    /// The straight face from `a` to `b`, `normal` its unit normal toward the disc.
    Line { a: DVec2, b: DVec2, normal: DVec2 },
    /// The circle of `radius` about `center`, ridden `inside` or outside, over the arc from
    /// `start` counter-clockwise through `sweep` (rad).
    Circle {
        center: DVec2,
        radius: f64,
        inside: bool,
        start: f64,
        sweep: f64,
    },
}

/// The contact's frame for a disc of radius r whose center is at `c` moving at `v_c`.
pub(super) struct Frame {
    /// The unit normal from the surface into the disc.
    pub n: DVec2,
    /// The normal's rate, 1/s (zero on a straight face).
    pub n_rate: DVec2,
    /// The gap between the disc and the surface, m (zero while it rolls).
    pub gap: f64,
    /// The known part of the gap's second derivative beyond n . a_C: sigma |v_C,t|^2 / rho on a
    /// circle (rho'' = e . a_C + |v_C,t|^2 / rho), zero on a straight face.
    pub curvature: f64,
    /// Whether the contact point is on the surface (within the face's ends, the arc's sweep).
    pub on_surface: bool,
}

impl Surface {
    pub fn frame(&self, c: DVec2, v_c: DVec2, r: f64) -> Frame {
        match *self {
            Surface::Line { a, b, normal } => {
                let p = c - r * normal;
                let ab = (b - a).length_squared().max(f64::MIN_POSITIVE);
                let along = (p - a).dot(b - a) / ab;
                Frame {
                    n: normal,
                    n_rate: DVec2::ZERO,
                    gap: normal.dot(c - a) - r,
                    curvature: 0.0,
                    on_surface: (0.0..=1.0).contains(&along),
                }
            }
            Surface::Circle {
                center,
                radius,
                inside,
                start,
                sweep,
            } => {
                let sigma = if inside { -1.0 } else { 1.0 };
                let rho_vec = c - center;
                let rho = rho_vec.length().max(f64::MIN_POSITIVE);
                let e = rho_vec / rho;
                let v_t = v_c - v_c.dot(e) * e;
                let from_start = (e.y.atan2(e.x) - start).rem_euclid(TAU);
                Frame {
                    n: sigma * e,
                    n_rate: sigma * v_t / rho,
                    gap: sigma * (rho - (radius + sigma * r)),
                    curvature: sigma * v_t.length_squared() / rho,
                    on_surface: sweep >= TAU - 1e-9 || from_start <= sweep,
                }
            }
        }
    }
}

/// One disc rolling on one fixed surface.
#[derive(Debug, Clone)]
pub(super) struct Rolling {
    /// The disc's and the surface's level indices.
    pub body: usize,
    pub surface_body: usize,
    /// The disc's center in its body frame (from the body origin), m, and its radius.
    pub center: DVec2,
    pub radius: f64,
    pub surface: Surface,
    /// The pair's friction coefficient as rapier combines it (the larger of the two).
    pub mu: f64,
    /// "\"disc\" on \"floor\"", for the reasons.
    pub pair: String,
}

/// The rolling contacts of the level's dynamic bodies at the start, or why a touch is outside
/// the reference. None without the `contacts` effect.
pub(super) fn rolling_contacts(level: &Level) -> Result<Vec<Rolling>, String> {
    if !level.effects.contains(&Effect::Contacts) {
        return Ok(Vec::new());
    }
    let friction = level.effects.contains(&Effect::Friction);
    let mut out = Vec::new();
    for (k, body) in level.bodies.iter().enumerate() {
        if body.kind != BodyKind::Dynamic || body.shape.is_none() {
            continue;
        }
        let mut found: Option<Rolling> = None;
        for (j, other) in level.bodies.iter().enumerate() {
            if j == k || other.shape.is_none() {
                continue;
            }
            let Some(surface) = touch(body, other)? else {
                continue;
            };
            let pair = format!("\"{}\" on \"{}\"", body.name, other.name);
            if found.is_some() {
                return Err(format!(
                    "\"{}\" touches two bodies at the start: the reference rolls a body on one surface",
                    body.name
                ));
            }
            let mu = if friction {
                body.friction
                    .unwrap_or(0.0)
                    .max(other.friction.unwrap_or(0.0))
            } else {
                0.0
            };
            let radius = body.disc_radius().unwrap_or(0.0);
            found = Some(Rolling {
                body: k,
                surface_body: j,
                center: DVec2::ZERO,
                radius,
                surface,
                mu,
                pair,
            });
        }
        out.extend(found);
    }
    Ok(out)
}

/// The surface `body` rolls on when it touches `other` at the start, None when they do not
/// touch, or why the touch is outside the reference.
fn touch(body: &BodyDef, other: &BodyDef) -> Result<Option<Surface>, String> {
    let at = DVec2::new(body.position.0, body.position.1);
    let pair = format!("\"{}\" touches \"{}\" at the start", body.name, other.name);
    let Some(mine) = pieces(body) else {
        return Err(format!(
            "\"{}\" has a shape whose contacts the reference does not read (a compound)",
            body.name
        ));
    };
    let size = mine
        .iter()
        .flat_map(|p| p.core.iter().map(move |c| (*c - at).length() + p.radius))
        .fold(0.0, f64::max);
    let tol = 1e-6 + 1e-4 * size;
    let disc = body.disc_radius();
    let surface = if let Some(Shape::Arc { .. }) = &other.shape {
        let Some(arc) = arc_of(other) else {
            return Ok(None);
        };
        let touching = match disc {
            Some(r) => arc_gap(&arc, at, r).is_some_and(|g| g.abs() <= tol),
            // A body that is not round: its outline's points against the circle.
            None => mine.iter().any(|p| {
                outline_points(&p.core).iter().any(|q| {
                    let rho = (*q - arc_center(&arc)).length();
                    (rho - arc_radius(&arc)).abs() <= p.radius + tol
                })
            }),
        };
        if !touching {
            return Ok(None);
        }
        arc
    } else {
        let Some(theirs) = pieces(other) else {
            return Err(format!(
                "\"{}\" has a shape whose contacts the reference does not read (a compound)",
                other.name
            ));
        };
        let touching: Vec<_> = theirs
            .iter()
            .filter(|b| mine.iter().any(|a| gap(a, b) <= tol))
            .collect();
        if touching.is_empty() {
            return Ok(None);
        }
        if disc.is_none() {
            return Err(format!(
                "{pair}, and is not round: the reference holds a round body rolling on a fixed surface (a flat face sticks or slides)"
            ));
        }
        let [piece] = touching.as_slice() else {
            return Err(format!(
                "{pair} in several places (a corner between two faces)"
            ));
        };
        line_under(at, disc.unwrap_or(0.0), piece, tol)
            .ok_or_else(|| format!("{pair} on a corner or a rounded edge, not a flat face"))?
    };
    if disc.is_none() {
        return Err(format!(
            "{pair}, and is not round: the reference holds a round body rolling on a fixed surface"
        ));
    }
    if other.kind != BodyKind::Fixed {
        return Err(format!(
            "{pair}, which moves: the reference holds rolling on fixed surfaces (a contact between two moving bodies is outside it)"
        ));
    }
    Ok(Some(surface))
}

/// The flat face of the fixed piece a disc centered at `c` lies on, inside the face's ends.
fn line_under(c: DVec2, r: f64, piece: &crate::level::shape::Piece, tol: f64) -> Option<Surface> {
    if piece.radius != 0.0 {
        return None;
    }
    let (d, t, s, e) = edges(&piece.core)
        .into_iter()
        .map(|(s, e)| {
            let (d, t) = to_segment(c, s, e);
            (d, t, s, e)
        })
        .min_by(|x, y| x.0.total_cmp(&y.0))?;
    if (d - r).abs() > tol || !(1e-9..=1.0 - 1e-9).contains(&t) {
        return None;
    }
    let mut normal = (e - s).normalize().perp();
    if normal.dot(c - s) < 0.0 {
        normal = -normal;
    }
    Some(Surface::Line { a: s, b: e, normal })
}

/// A fixed body's arc track in world axes.
fn arc_of(b: &BodyDef) -> Option<Surface> {
    let Some(Shape::Arc {
        center,
        radius,
        start,
        end,
        side,
        ..
    }) = &b.shape
    else {
        return None;
    };
    let turn = DVec2::from_angle(b.angle);
    Some(Surface::Circle {
        center: DVec2::new(b.position.0, b.position.1)
            + turn.rotate(DVec2::new(center.0, center.1)),
        radius: *radius,
        inside: *side == ArcSide::Inside,
        start: start + b.angle,
        sweep: end - start,
    })
}

fn arc_center(s: &Surface) -> DVec2 {
    match s {
        Surface::Circle { center, .. } => *center,
        Surface::Line { a, .. } => *a,
    }
}

fn arc_radius(s: &Surface) -> f64 {
    match s {
        Surface::Circle { radius, .. } => *radius,
        Surface::Line { .. } => 0.0,
    }
}

/// The gap of a disc centered at `c` on the arc's side, None where the arc does not span it.
fn arc_gap(s: &Surface, c: DVec2, r: f64) -> Option<f64> {
    let f = s.frame(c, DVec2::ZERO, r);
    f.on_surface.then_some(f.gap)
}

/// A core's vertices and 15 points along each edge (a flat face touching a circle between
/// its corners).
fn outline_points(core: &[DVec2]) -> Vec<DVec2> {
    let mut out = core.to_vec();
    for (s, e) in edges(core) {
        out.extend((1..16).map(|i| s + (e - s) * (i as f64 / 16.0)));
    }
    out
}
