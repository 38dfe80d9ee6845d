//! Mass properties from the shape formulas (concepts.md section 6, MP-1 to MP-9).
//!
//! These are the textbook's numbers, computed from the level's description alone
//! (shape, mass or density, inertia or radius-of-gyration override): nothing here
//! asks the engine, so they can be compared with what rapier (parry) computed.

use crate::level::{BodyDef, Shape};
use glam::DVec2;
use std::f64::consts::PI;

/// Mass, mass center (body frame) and centroidal moment of inertia I_G of a body.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MassProps {
    /// m, kg.
    pub mass: f64,
    /// Mass center G in the body frame, m (MP-4).
    pub com: DVec2,
    /// I_G about the z axis through G, kg m^2 (MP-1).
    pub inertia: f64,
}

impl MassProps {
    /// Radius of gyration about G, k_G = sqrt(I_G / m) (MP-3).
    pub fn radius_of_gyration(&self) -> f64 {
        radius_of_gyration(self.inertia, self.mass)
    }

    /// Moment of inertia about the z axis through a point at distance `d` from G (MP-2).
    pub fn about(&self, d: f64) -> f64 {
        parallel_axis(self.inertia, self.mass, d)
    }
}

/// Disc (or solid cylinder) about its center: I = 1/2 m r^2 (MP-9).
pub fn disc_inertia(m: f64, r: f64) -> f64 {
    0.5 * m * r * r
}

/// Thin ring (hoop) about its center: I = m r^2 (MP-9, the point-mass form at distance r).
pub fn thin_ring_inertia(m: f64, r: f64) -> f64 {
    m * r * r
}

/// Annulus of inner radius r_i and outer radius r_o about its center: I = 1/2 m (r_i^2 + r_o^2)
/// (MP-1 integrated; r_i = 0 gives the disc, r_i -> r_o the thin ring).
pub fn ring_inertia(m: f64, r_inner: f64, r_outer: f64) -> f64 {
    0.5 * m * (r_inner * r_inner + r_outer * r_outer)
}

/// Homogeneous slender bar about its center: I_G = 1/12 m l^2 (MP-6).
pub fn slender_bar_inertia(m: f64, l: f64) -> f64 {
    m * l * l / 12.0
}

/// Slender bar about one end: I_O = 1/3 m l^2 (MP-6, = MP-2 with d = l/2).
///
/// # Examples
///
/// A 3 kg bar 2 m long pinned at one end: I_O = 1/3 (3)(2^2) = 4 kg m^2, which is also
/// I_G = 1 kg m^2 moved by the parallel-axis theorem through d = 1 m (MP-2).
/// ```
/// use rigidlab::analysis::mass::{parallel_axis, slender_bar_end_inertia, slender_bar_inertia};
/// assert_eq!(slender_bar_end_inertia(3.0, 2.0), 4.0);
/// assert_eq!(parallel_axis(slender_bar_inertia(3.0, 2.0), 3.0, 1.0), 4.0);
/// ```
pub fn slender_bar_end_inertia(m: f64, l: f64) -> f64 {
    m * l * l / 3.0
}

/// Rectangle a x b about its center: I = 1/12 m (a^2 + b^2) (MP-9).
pub fn rectangle_inertia(m: f64, a: f64, b: f64) -> f64 {
    m * (a * a + b * b) / 12.0
}

/// Point mass at distance d from the axis: I = m d^2 (MP-9).
pub fn point_mass_inertia(m: f64, d: f64) -> f64 {
    m * d * d
}

/// Capsule (stadium) of straight length `length` between the cap centers and radius r,
/// about its center: the rectangle 2r x length plus two half-discs moved out by the
/// parallel-axis theorem (MP-9). With a = 4r/(3 pi) the half-disc's centroid offset and
/// m_c the mass of both caps: I = m_r (L^2 + 4 r^2)/12 + m_c (r^2/2 + L^2/4 + L a).
pub fn capsule_inertia(m: f64, length: f64, radius: f64) -> f64 {
    let (l, r) = (length, radius);
    let (a_rect, a_caps) = (2.0 * r * l, PI * r * r);
    let area = a_rect + a_caps;
    if area <= 0.0 {
        return 0.0;
    }
    let (m_r, m_c) = (m * a_rect / area, m * a_caps / area);
    let a = 4.0 * r / (3.0 * PI);
    m_r * (l * l + 4.0 * r * r) / 12.0 + m_c * (r * r / 2.0 + l * l / 4.0 + l * a)
}

/// Parallel-axis theorem: I_O = I_G + m d^2, d the distance between the parallel axes (MP-2).
pub fn parallel_axis(i_g: f64, m: f64, d: f64) -> f64 {
    i_g + m * d * d
}

/// Radius of gyration k = sqrt(I / m) (MP-3); 0 for a massless body.
///
/// # Examples
///
/// The same bar about its end: k_O = sqrt(4 / 3) = 1.1547 m, so that I_O = m k_O^2.
/// ```
/// use rigidlab::analysis::mass::radius_of_gyration;
/// let k = radius_of_gyration(4.0, 3.0);
/// assert!((k - 1.154_700_538_4).abs() < 1e-10);
/// assert_eq!(radius_of_gyration(1.0, 0.0), 0.0);
/// ```
pub fn radius_of_gyration(i: f64, m: f64) -> f64 {
    if m > 0.0 {
        (i / m).max(0.0).sqrt()
    } else {
        0.0
    }
}

/// The area, centroid and polar second moment about the centroid (per unit density)
/// of a plane shape: what a density multiplies into mass properties.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AreaProps {
    /// A, m^2.
    pub area: f64,
    /// Centroid, m.
    pub centroid: DVec2,
    /// J_C = integral of |r - c|^2 dA, m^4.
    pub polar: f64,
}

/// Convex hull of a point set, counter-clockwise (Andrew's monotone chain): the level's
/// geometry ([`crate::level::shape::convex_hull`]); the level format uses the hull of a
/// polygon's points.
pub use crate::level::shape::convex_hull;

/// Area properties of a simple polygon by triangulation from the origin (MP-9 "polygon: by
/// triangulation"): each edge (p_i, p_i+1) spans a triangle with the origin of signed area
/// c_i / 2, c_i = p_i x p_i+1, and second moment c_i/12 (x_i^2 + x_i x_i+1 + x_i+1^2 + same in y).
///
/// # Examples
///
/// A 2 m x 1 m rectangle with a corner at the origin: A = 2 m^2, centroid (1, 0.5), and
/// J_C = A (a^2 + b^2) / 12 = 2 (4 + 1) / 12 = 0.8333 m^4 (MP-9 per unit density).
/// ```
/// use glam::DVec2;
/// use rigidlab::analysis::mass::polygon_area_props;
/// let p = polygon_area_props(&[
///     DVec2::new(0.0, 0.0), DVec2::new(2.0, 0.0), DVec2::new(2.0, 1.0), DVec2::new(0.0, 1.0),
/// ]);
/// assert!((p.area - 2.0).abs() < 1e-12);
/// assert!((p.centroid - DVec2::new(1.0, 0.5)).length() < 1e-12);
/// assert!((p.polar - 10.0 / 12.0).abs() < 1e-12);
/// ```
pub fn polygon_area_props(points: &[DVec2]) -> AreaProps {
    let n = points.len();
    let (mut a2, mut cx, mut cy, mut j) = (0.0, 0.0, 0.0, 0.0);
    for i in 0..n {
        let (p, q) = (points[i], points[(i + 1) % n]);
        let c = super::cross(p, q);
        a2 += c;
        cx += (p.x + q.x) * c;
        cy += (p.y + q.y) * c;
        j += c * (p.x * p.x + p.x * q.x + q.x * q.x + p.y * p.y + p.y * q.y + q.y * q.y);
    }
    let area = a2 / 2.0;
    if area.abs() < 1e-300 {
        return AreaProps::default();
    }
    let centroid = DVec2::new(cx, cy) / (3.0 * a2);
    let j_origin = j / 12.0;
    // Orientation-independent: divide out the sign of the area.
    let s = area.signum();
    AreaProps {
        area: area.abs(),
        centroid,
        polar: s * j_origin - area.abs() * centroid.length_squared(),
    }
}

/// Area properties of a level shape (in its own frame); segments have none.
pub fn shape_area_props(shape: &Shape) -> AreaProps {
    match shape {
        // The area is the level's geometry (`level::shape::area`); the second moment the
        // textbook's formula for the shape (MP-9), at unit density.
        Shape::Circle { radius } => centered(shape, |area| disc_inertia(area, *radius)),
        Shape::Box { width, height } => {
            centered(shape, |area| rectangle_inertia(area, *width, *height))
        }
        Shape::Capsule { length, radius } => {
            centered(shape, |area| capsule_inertia(area, *length, *radius))
        }
        Shape::Polygon { points } => {
            let pts: Vec<DVec2> = points.iter().map(|p| DVec2::new(p.0, p.1)).collect();
            polygon_area_props(&convex_hull(&pts))
        }
        Shape::Segment { .. }
        | Shape::Polyline { .. }
        | Shape::Arc { .. }
        | Shape::Track { .. } => AreaProps::default(),
        Shape::Compound { parts } => {
            // Each part moved to its offset and turned (turning keeps the polar moment), then
            // combined about the common centroid by the parallel-axis theorem (MP-2, MP-4).
            let placed: Vec<AreaProps> = parts
                .iter()
                .map(|p| {
                    let a = shape_area_props(&p.shape);
                    AreaProps {
                        centroid: DVec2::new(p.offset.0, p.offset.1)
                            + DVec2::from_angle(p.angle).rotate(a.centroid),
                        ..a
                    }
                })
                .collect();
            let area: f64 = placed.iter().map(|a| a.area).sum();
            if area <= 0.0 {
                return AreaProps::default();
            }
            let centroid = placed.iter().map(|a| a.centroid * a.area).sum::<DVec2>() / area;
            let polar = placed
                .iter()
                .map(|a| parallel_axis(a.polar, a.area, (a.centroid - centroid).length()))
                .sum();
            AreaProps {
                area,
                centroid,
                polar,
            }
        }
    }
}

/// The area properties of a shape symmetric about its body origin: its area, its centroid at
/// the origin, and its polar second moment from `polar(area)`.
fn centered(shape: &Shape, polar: impl Fn(f64) -> f64) -> AreaProps {
    let area = crate::level::shape::area(shape);
    AreaProps {
        area,
        centroid: DVec2::ZERO,
        polar: polar(area),
    }
}

/// Mass properties of a shape of uniform area density rho (MP-1: I = rho * integral r^2 dA).
pub fn of_shape(shape: &Shape, density: f64) -> MassProps {
    let a = shape_area_props(shape);
    MassProps {
        mass: density * a.area,
        com: a.centroid,
        inertia: density * a.polar,
    }
}

/// The textbook mass properties of a body as its level describes it: the shape's formula at
/// the given mass (or density, default `default_density`), then the level's I_G or k_G
/// override (MP-3: I_G = m k_G^2). Shapes without area (segments, no shape) put G at the body
/// origin and I_G = 0 unless overridden.
pub fn of_body(def: &BodyDef, default_density: f64) -> MassProps {
    let a = def.shape.as_ref().map(shape_area_props).unwrap_or_default();
    let mut mp = match (def.mass, def.density) {
        (Some(m), _) => MassProps {
            mass: m,
            com: a.centroid,
            inertia: if a.area > 0.0 {
                m * a.polar / a.area
            } else {
                0.0
            },
        },
        (None, d) => {
            let rho = d.unwrap_or(default_density);
            MassProps {
                mass: rho * a.area,
                com: a.centroid,
                inertia: rho * a.polar,
            }
        }
    };
    if let Some(i) = def.inertia {
        mp.inertia = i;
    } else if let Some(k) = def.radius_of_gyration {
        mp.inertia = mp.mass * k * k;
    }
    mp
}
