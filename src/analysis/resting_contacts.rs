//! Contacts a mechanism rests on at the start, as the linearization (PL-14,
//! `small_oscillations`) can hold them: a round body rolling without slip (RK-8) or sliding on a
//! smooth flat face of a fixed body, or a flat face lying on a smooth one. Any other contact
//! that touches a moving body at the start (a corner on a face, a face on a rough face where
//! Coulomb friction sticks and slips, two moving bodies, a curved track) is outside the
//! linearization, and the analysis says so rather than leave the contact out.
//!
//! The geometry is the level's: every shape as convex pieces (a core polygon, segment or point
//! swept by a radius), their distance from the vertex-to-edge distances, "touching" within
//! 1e-6 m + 1e-4 of the member's size (a body placed on a face by hand; rounding is far under
//! it, and a body placed a visible gap above a face is not resting on it).

use crate::level::{BodyDef, BodyKind, Effect, Level};
use glam::DVec2;

/// How a contact holds its body, in the linearization.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Hold {
    /// A round body of this radius rolling without slip on the face: its center keeps its
    /// distance from the face, and x_along + r theta is constant (RK-8).
    Rolling { radius: f64 },
    /// A round body on a smooth face: its center keeps its distance from the face.
    Sliding,
    /// A flat face lying on a smooth face: the body keeps its distance and its angle.
    Flat,
}

/// One resting contact: `body` on the face of a fixed body with outward unit `normal`.
#[derive(Debug, Clone, PartialEq)]
pub struct RestingContact {
    pub body: usize,
    /// The round body's center in its own frame (rolling and sliding; unused for a flat face,
    /// which holds G's distance from the face and the angle).
    pub point: DVec2,
    pub normal: DVec2,
    pub hold: Hold,
}

/// A convex piece of a shape in world coordinates: the core's vertices (1: a point, 2: a
/// segment, 3 or more: a polygon) swept by `radius`.
type Piece = crate::level::shape::Piece;

/// The convex pieces of a body's shape ([`crate::level::shape::pieces`]), world frame; None
/// for a shape this model does not read (an arc track, a compound).
pub(crate) fn pieces(b: &BodyDef) -> Option<Vec<Piece>> {
    let at = DVec2::new(b.position.0, b.position.1);
    let w = |p: DVec2| at + DVec2::from_angle(b.angle).rotate(p);
    let local = crate::level::shape::pieces(b.shape.as_ref()?)?;
    Some(
        local
            .into_iter()
            .map(|p| Piece {
                core: p.core.into_iter().map(w).collect(),
                radius: p.radius,
            })
            .collect(),
    )
}

/// The edges of a core: none for a point, one for a segment, the closed loop of a polygon.
pub(crate) fn edges(core: &[DVec2]) -> Vec<(DVec2, DVec2)> {
    match core.len() {
        0 | 1 => Vec::new(),
        2 => vec![(core[0], core[1])],
        n => (0..n).map(|i| (core[i], core[(i + 1) % n])).collect(),
    }
}

/// Distance from p to the segment ab, and where along it (0 to 1) the nearest point is.
pub(crate) fn to_segment(p: DVec2, a: DVec2, b: DVec2) -> (f64, f64) {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    ((p - (a + ab * t)).length(), t)
}

/// Whether p lies inside a polygon core (3 or more vertices, either winding).
fn inside(p: DVec2, core: &[DVec2]) -> bool {
    if core.len() < 3 {
        return false;
    }
    let signs: Vec<f64> = edges(core)
        .iter()
        .map(|(a, b)| (*b - *a).perp_dot(p - *a))
        .collect();
    signs.iter().all(|s| *s >= 0.0) || signs.iter().all(|s| *s <= 0.0)
}

/// The gap between two pieces (negative or zero when one's vertex is inside the other).
pub(crate) fn gap(a: &Piece, b: &Piece) -> f64 {
    let r = a.radius + b.radius;
    if a.core.iter().any(|p| inside(*p, &b.core)) || b.core.iter().any(|p| inside(*p, &a.core)) {
        return -r;
    }
    let one_way = |x: &Piece, y: &Piece| {
        let es = edges(&y.core);
        x.core
            .iter()
            .map(|p| {
                if es.is_empty() {
                    (*p - y.core[0]).length()
                } else {
                    es.iter()
                        .map(|(s, e)| to_segment(*p, *s, *e).0)
                        .fold(f64::INFINITY, f64::min)
                }
            })
            .fold(f64::INFINITY, f64::min)
    };
    one_way(a, b).min(one_way(b, a)) - r
}

/// A member's size: the largest distance of its cores' vertices from its position, plus radius.
fn size(ps: &[Piece], at: DVec2) -> f64 {
    ps.iter()
        .flat_map(|p| p.core.iter().map(move |c| (*c - at).length() + p.radius))
        .fold(0.0, f64::max)
}

/// The resting contacts of the moving bodies `moving` (indices into `level.bodies`), or why one
/// of them touches something the linearization cannot hold. `pressed` is the effective gravity
/// (g less a support's acceleration): a contact holds only where it presses the body onto the
/// face. None of this applies without the `contacts` effect.
pub fn resting_contacts(
    level: &Level,
    moving: &[usize],
    pressed: DVec2,
) -> Result<Vec<RestingContact>, String> {
    if !level.effects.contains(&Effect::Contacts) {
        return Ok(Vec::new());
    }
    let friction = level.effects.contains(&Effect::Friction);
    let mut out = Vec::new();
    for &k in moving {
        let body = &level.bodies[k];
        let Some(mine) = pieces(body) else {
            return Err(format!(
                "\"{}\" has a shape whose contacts the linearization does not read",
                body.name
            ));
        };
        let at = DVec2::new(body.position.0, body.position.1);
        let tol = 1e-6 + 1e-4 * size(&mine, at);
        for (j, other) in level.bodies.iter().enumerate() {
            if j == k || other.shape.is_none() {
                continue;
            }
            let Some(theirs) = pieces(other) else {
                return Err(format!(
                    "\"{}\" has a shape whose contacts the linearization does not read",
                    other.name
                ));
            };
            let touching: Vec<(&Piece, &Piece)> = mine
                .iter()
                .flat_map(|a| theirs.iter().map(move |b| (a, b)))
                .filter(|(a, b)| gap(a, b) <= tol)
                .collect();
            if touching.is_empty() {
                continue;
            }
            let pair = format!("\"{}\" touches \"{}\" at the start", body.name, other.name);
            if other.kind != BodyKind::Fixed {
                return Err(format!(
                    "{pair}, which moves: the linearization holds contacts on fixed faces only"
                ));
            }
            let mu = if friction {
                body.friction
                    .unwrap_or(0.0)
                    .max(other.friction.unwrap_or(0.0))
            } else {
                0.0
            };
            let [(a, b)] = touching.as_slice() else {
                return Err(format!("{pair} in several places"));
            };
            out.push(classify(k, body, a, b, tol, mu, pressed, &pair)?);
        }
    }
    Ok(out)
}

/// One touching pair of pieces as a hold, or why it is none: the member's piece `a` on the
/// fixed piece `b`, whose touching feature must be a straight edge.
#[allow(clippy::too_many_arguments)]
fn classify(
    k: usize,
    body: &BodyDef,
    a: &Piece,
    b: &Piece,
    tol: f64,
    mu: f64,
    pressed: DVec2,
    pair: &str,
) -> Result<RestingContact, String> {
    // The fixed edge the member lies on: the nearest to the member's core, touched inside its
    // ends (a corner of the fixed body is not a face).
    let near = |p: DVec2| {
        edges(&b.core)
            .into_iter()
            .map(|(s, e)| {
                let (d, t) = to_segment(p, s, e);
                (d, t, s, e)
            })
            .min_by(|x, y| x.0.total_cmp(&y.0))
    };
    let touching: Vec<(DVec2, (f64, f64, DVec2, DVec2))> = a
        .core
        .iter()
        .filter_map(|p| near(*p).map(|n| (*p, n)))
        .filter(|(_, n)| n.0 - a.radius - b.radius <= tol)
        .collect();
    let Some((p, (_, t, s, e))) = touching.first().copied() else {
        return Err(format!(
            "{pair} along a feature the linearization does not read"
        ));
    };
    if !(1e-6..=1.0 - 1e-6).contains(&t) {
        return Err(format!(
            "{pair} on a corner: the linearization holds a body on a flat face"
        ));
    }
    // The face's outward normal: from the face toward the member.
    // (Toward the member's core's middle: a touching vertex lies on the face itself.)
    let middle = a.core.iter().copied().sum::<DVec2>() / a.core.len() as f64;
    let along = (e - s).normalize();
    let mut normal = along.perp();
    if normal.dot(middle - s) < 0.0 {
        normal = -normal;
    }
    if pressed.dot(normal) >= 0.0 {
        return Err(format!(
            "{pair}, but nothing presses it onto the face (gravity along the outward normal is {:.3} m/s^2): the contact may open",
            pressed.dot(normal)
        ));
    }
    let to_local = |w: DVec2| {
        DVec2::from_angle(-body.angle).rotate(w - DVec2::new(body.position.0, body.position.1))
    };
    if a.core.len() == 1 && a.radius > 0.0 {
        let hold = if mu > 0.0 {
            Hold::Rolling { radius: a.radius }
        } else {
            Hold::Sliding
        };
        return Ok(RestingContact {
            body: k,
            point: to_local(p),
            normal,
            hold,
        });
    }
    // A flat face: two core vertices on the one fixed edge.
    let flush = touching.len() >= 2
        && touching
            .iter()
            .all(|(_, n)| n.2 == s && n.3 == e && (1e-6..=1.0 - 1e-6).contains(&n.1));
    if !flush {
        return Err(format!(
            "{pair} at a corner: a body that can rock on its corner is outside the linearization"
        ));
    }
    if mu > 0.0 {
        return Err(format!(
            "{pair}, a flat face on a face with friction (mu = {mu}): Coulomb friction sticks or slips, which no linearization holds"
        ));
    }
    Ok(RestingContact {
        body: k,
        point: DVec2::ZERO,
        normal,
        hold: Hold::Flat,
    })
}
