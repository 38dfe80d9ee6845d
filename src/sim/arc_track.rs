//! A circular arc track (`Shape::Arc`) as parry sees it: the true circle for a ball's contact,
//! its facets for everything else.
//!
//! Until 2026-12-06 an arc was only the one-sided polyline of its facets, and a ball riding it met
//! a kink of the facet angle at every vertex: its speed at a loop's top stayed about 3e-3 low at
//! any dt in f64, and the normal force came in one impulse per vertex (docs/known-gaps.md). An
//! [`ArcTrack`] keeps that polyline (the broad phase's box, ray casts, point queries, and the
//! contacts of shapes other than a ball, through `sim/arc_contacts.rs`) and the circle it
//! approximates, from which [`ArcTrack::touch`] gives a ball's contact exactly within the arc's
//! angles: along the radius, at the depth |d - R| - r ([`ArcTrack::spans_point`]; past the ends
//! the dispatcher uses the facets).

use super::rapier::parry::bounding_volume::{Aabb, BoundingSphere};
use super::rapier::parry::mass_properties::MassProperties;
use super::rapier::parry::query::{PointProjection, PointQuery, Ray, RayCast, RayIntersection};
use super::rapier::parry::shape::{FeatureId, Polyline, Shape, ShapeType, TypedShape};
use super::rapier::prelude::*;
use std::f64::consts::TAU;

/// A circular arc track in its body's frame, with the facets that stand for it where a ball is
/// not the other shape. A parry `Shape` of type `Custom`: only rigidlab's dispatcher
/// (`sim/arc_contacts.rs`) knows it, so every query on it must go through the world's
/// `narrow_phase.query_dispatcher()`, never parry's free functions.
#[derive(Clone)]
pub(crate) struct ArcTrack {
    /// The one-sided polyline of the arc's facets, as `build::shared_shape` made it before.
    pub polyline: Polyline,
    center: Vector,
    radius: Real,
    /// The end angles, rad, counter-clockwise from `start`; a full turn has no ends.
    start: f64,
    sweep: f64,
    full: bool,
    /// Bodies ride the concave side (a loop, a ring, a bowl): the solid lies outside the circle.
    inside: bool,
}

/// Where a ball touches an arc, in the arc's frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Touch {
    /// The point of the arc nearest the ball's center.
    pub point: Vector,
    /// Unit normal from the arc toward the ball's center (out of the track's solid).
    pub normal: Vector,
    /// Separation of the two surfaces, m: negative when they overlap.
    pub dist: Real,
}

impl ArcTrack {
    pub fn new(
        polyline: Polyline,
        center: Vector,
        radius: Real,
        (start, end): (f64, f64),
        inside: bool,
    ) -> Self {
        let sweep = end - start;
        ArcTrack {
            polyline,
            center,
            radius,
            start,
            sweep,
            full: (sweep - TAU).abs() < 1e-9,
            inside,
        }
    }

    /// Whether the direction at angle `theta` (rad) from the center falls within the arc.
    fn spans(&self, theta: f64) -> bool {
        self.full || (theta - self.start).rem_euclid(TAU) <= self.sweep
    }

    /// Whether a ball centered at `c` (arc frame) lies within the arc's angles, where
    /// [`ArcTrack::touch`] gives its contact with the circle. Past the ends the dispatcher
    /// hands the pair to the facets, whose one-sided end keeps the last facet's normal: a ball
    /// crossing from one arc onto the next one tangent to it (a ramp into a loop) is not pushed
    /// by the first arc's end point as by a corner. Measured 2026-12-06 on
    /// `levels/energy/curve_loop_the_loop.ron`: with the end point's own normal the ball lost
    /// 2% of its energy crossing from the ramp into the loop.
    pub fn spans_point(&self, c: Vector) -> bool {
        let arm = c - self.center;
        self.spans((arm.y as f64).atan2(arm.x as f64))
    }

    /// The circle in the arc's frame: its centre, its radius, and whether bodies ride inside.
    pub fn circle(&self) -> (Vector, Real, bool) {
        (self.center, self.radius, self.inside)
    }

    /// The arc's end point at angle `theta`.
    fn end_point(&self, theta: f64) -> Vector {
        self.center + Vector::new(theta.cos() as Real, theta.sin() as Real) * self.radius
    }

    /// A ball of radius `r` centered at `c` (arc frame) against the arc.
    ///
    /// Within the arc's angles the nearest point of the circle lies on the radius through c, at
    /// distance |d - R| from it (d = |c - O|): the surfaces are apart by R - d - r riding inside
    /// (the normal toward the center) and d - R - r riding outside (the normal away from it).
    /// Beyond the end angles the nearest point of the arc is its nearer end point E, apart by
    /// |c - E| - r along c - E; at the end angle both give the same contact, so a ball rolling off
    /// an arc's end meets no jump.
    pub fn touch(&self, c: Vector, r: Real) -> Touch {
        let arm = c - self.center;
        let d = arm.length();
        let theta = (arm.y as f64).atan2(arm.x as f64);
        if self.spans(theta) {
            // At the center every radius is nearest: take the arc's middle one.
            let u = if d > 0.0 {
                arm / d
            } else {
                let mid = self.start + self.sweep / 2.0;
                Vector::new(mid.cos() as Real, mid.sin() as Real)
            };
            let point = self.center + u * self.radius;
            return if self.inside {
                Touch {
                    point,
                    normal: -u,
                    dist: self.radius - d - r,
                }
            } else {
                Touch {
                    point,
                    normal: u,
                    dist: d - self.radius - r,
                }
            };
        }
        let (a, b) = (
            self.end_point(self.start),
            self.end_point(self.start + self.sweep),
        );
        let e = if (c - a).length() <= (c - b).length() {
            a
        } else {
            b
        };
        let w = c - e;
        let l = w.length();
        let normal = if l > 0.0 {
            w / l
        } else if self.inside {
            (self.center - e) / self.radius
        } else {
            (e - self.center) / self.radius
        };
        Touch {
            point: e,
            normal,
            dist: l - r,
        }
    }
}

/// The queries and shape data of a curved track that rapier sees as its `polyline` field (an
/// `Arc`, a `Track`): rays and point projections go to the polyline; its points lie on or
/// outside its circles (level::curves), so their box holds the circles' pieces; no mass, no CCD
/// thickness; never scaled (a scaled circle is no circle, and rigidlab never scales a collider).
/// Only the contact with a ball differs, in sim/arc_contacts.rs.
macro_rules! polyline_backed_shape {
    ($shape:ty) => {
        impl RayCast for $shape {
            fn cast_local_ray_and_get_normal(
                &self,
                ray: &Ray,
                max_time_of_impact: Real,
                solid: bool,
            ) -> Option<RayIntersection> {
                self.polyline
                    .cast_local_ray_and_get_normal(ray, max_time_of_impact, solid)
            }
        }

        impl PointQuery for $shape {
            fn project_local_point(&self, pt: Vector, solid: bool) -> PointProjection {
                self.polyline.project_local_point(pt, solid)
            }

            fn project_local_point_and_get_feature(
                &self,
                pt: Vector,
            ) -> (PointProjection, FeatureId) {
                self.polyline.project_local_point_and_get_feature(pt)
            }
        }

        impl Shape for $shape {
            fn compute_local_aabb(&self) -> Aabb {
                self.polyline.local_aabb()
            }

            fn compute_local_bounding_sphere(&self) -> BoundingSphere {
                self.polyline.local_aabb().bounding_sphere()
            }

            fn clone_dyn(&self) -> Box<dyn Shape> {
                Box::new(self.clone())
            }

            fn scale_dyn(&self, _scale: Vector, _num_subdivisions: u32) -> Option<Box<dyn Shape>> {
                None
            }

            fn mass_properties(&self, _density: Real) -> MassProperties {
                MassProperties::new(Vector::ZERO, 0.0, 0.0)
            }

            fn shape_type(&self) -> ShapeType {
                ShapeType::Custom
            }

            fn as_typed_shape(&self) -> TypedShape<'_> {
                TypedShape::Custom(self)
            }

            fn ccd_thickness(&self) -> Real {
                0.0
            }

            fn ccd_angular_thickness(&self) -> Real {
                self.polyline.ccd_angular_thickness()
            }
        }
    };
}
pub(super) use polyline_backed_shape;

polyline_backed_shape!(ArcTrack);

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn arc(inside: bool, start: f64, end: f64) -> ArcTrack {
        let pts = vec![Vector::new(1.0, 0.0), Vector::new(0.0, 1.0)];
        ArcTrack::new(
            Polyline::new(pts, None),
            Vector::new(0.0, 1.0),
            1.0,
            (start, end),
            inside,
        )
    }

    fn close(a: Vector, b: Vector) -> bool {
        (a - b).length() < 1e-6
    }

    #[test]
    fn a_ball_inside_touches_along_the_radius() {
        // Loop of R = 1 about (0, 1), open between pi and 3 pi / 2 (its lower left quarter).
        let loop_ = arc(true, -PI / 2.0, PI);
        // Ball r = 0.1 with G 0.9 from the center at the bottom: touching, normal up.
        let t = loop_.touch(Vector::new(0.0, 0.1), 0.1);
        assert!(t.dist.abs() < 1e-6 && close(t.normal, Vector::new(0.0, 1.0)));
        assert!(close(t.point, Vector::ZERO));
        // At the right side, 2 mm into the track.
        let t = loop_.touch(Vector::new(0.902, 1.0), 0.1);
        assert!((t.dist + 0.002).abs() < 1e-6 && close(t.normal, Vector::new(-1.0, 0.0)));
        // Past the end angle pi (up the left side, 0.5 below the end point (-1, 1)): the
        // end point is nearest, at distance hypot(0.1, 0.5) - 0.1.
        let t = loop_.touch(Vector::new(-0.9, 0.5), 0.1);
        assert!((t.dist as f64 - (0.26f64.sqrt() - 0.1)).abs() < 1e-6);
        assert!(close(t.point, Vector::new(-1.0, 1.0)));
    }

    #[test]
    fn a_ball_outside_touches_along_the_radius() {
        // A hump: the upper half of a circle about (0, 1), ridden on its outside.
        let hump = arc(false, 0.0, PI);
        let t = hump.touch(Vector::new(0.0, 2.1), 0.1);
        assert!(t.dist.abs() < 1e-6 && close(t.normal, Vector::new(0.0, 1.0)));
        assert!(close(t.point, Vector::new(0.0, 2.0)));
        // Past its end at (1, 1), below it: the end point, normal pointing from it to G.
        let t = hump.touch(Vector::new(1.0, 0.7), 0.1);
        assert!((t.dist - 0.2).abs() < 1e-6 && close(t.normal, Vector::new(0.0, -1.0)));
    }

    #[test]
    fn the_end_point_contact_meets_the_circles_at_the_end_angle() {
        let loop_ = arc(true, -PI / 2.0, PI);
        let just = |da: f64| {
            let a = PI + da;
            loop_.touch(
                Vector::new(0.0, 1.0) + Vector::new(a.cos() as Real, a.sin() as Real) * 0.9,
                0.1,
            )
        };
        let (before, after) = (just(-1e-6), just(1e-6));
        assert!((before.dist - after.dist).abs() < 1e-5);
        // Continuous, not equal: over the 2e-6 rad between the two centers the radius turns by
        // 1e-6 and the line from the end point (0.1 away) by atan(0.9 x 1e-6 / 0.1) = 9e-6, so
        // the normals differ by 1.0e-5; 2e-5 leaves room for f32's rounding of G (1.2e-7 of 1
        // m, 1.2e-6 of the normal over 0.1 m). A jump at the end would be of order 1.
        assert!((before.normal - after.normal).length() < 2e-5);
    }
}
