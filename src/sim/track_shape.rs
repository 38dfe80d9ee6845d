//! A `Track` shape (`level/track.rs`) as parry sees it: one polyline through all its pieces,
//! and each arc piece's circle as an [`ArcTrack`], which a ball touches exactly as it touches an
//! `Arc` (the same touch, the same manifold in `sim/arc_contacts.rs`, the same call in
//! `sim/arc_curvature.rs`).
//!
//! A ball is on the circle of the piece nearest its center, when that piece is an arc and the
//! ball lies within its angles ([`Curved::circle`] and [`ArcTrack::spans_point`]); elsewhere it
//! touches the one polyline, whose joints have no end to strike (a ramp `Arc` ending on a
//! separate `Segment` floor made a ball strike the segment's end: docs/known-gaps.md).

use super::arc_track::ArcTrack;
use super::rapier::parry::bounding_volume::{Aabb, BoundingSphere};
use super::rapier::parry::mass_properties::MassProperties;
use super::rapier::parry::query::{PointProjection, PointQuery, Ray, RayCast, RayIntersection};
use super::rapier::parry::shape::{FeatureId, Polyline, Shape, ShapeType, TypedShape};
use super::rapier::prelude::*;

/// One piece of a track, in its body's frame.
#[derive(Clone)]
pub(crate) enum TrackPart {
    /// A straight piece between two points.
    Line(Vector, Vector),
    /// An arc piece (boxed: a line is a tenth of its size) and its two end points.
    Arc(Box<ArcTrack>, (Vector, Vector)),
}

impl TrackPart {
    /// How far a point `c` lies from the piece's true line or circle, m.
    fn distance(&self, c: Vector) -> Real {
        match self {
            TrackPart::Line(a, b) => {
                let e = *b - *a;
                let t =
                    ((c - *a).dot(e) / e.length_squared().max(Real::MIN_POSITIVE)).clamp(0.0, 1.0);
                (*a + e * t - c).length()
            }
            TrackPart::Arc(arc, (a, b)) => {
                if arc.spans_point(c) {
                    let (center, radius, _) = arc.circle();
                    ((c - center).length() - radius).abs()
                } else {
                    (c - *a).length().min((c - *b).length())
                }
            }
        }
    }
}

/// A track of straight and circular pieces, a parry `Shape` of type `Custom` known only to
/// rigidlab's dispatcher (as [`ArcTrack`]).
#[derive(Clone)]
pub(crate) struct TrackShape {
    /// The one-sided polyline through every piece.
    pub polyline: Polyline,
    parts: Vec<TrackPart>,
}

impl TrackShape {
    pub fn new(polyline: Polyline, parts: Vec<TrackPart>) -> Self {
        TrackShape { polyline, parts }
    }

    /// The arc piece nearest a point `c` (track frame), None when the nearest is straight.
    /// Ties go to the piece written first: at a tangent joint both give the same contact.
    fn nearest_arc(&self, c: Vector) -> Option<&ArcTrack> {
        let mut best: Option<(&TrackPart, Real)> = None;
        for part in &self.parts {
            let d = part.distance(c);
            if best.is_none_or(|(_, bd)| d < bd) {
                best = Some((part, d));
            }
        }
        match best?.0 {
            TrackPart::Arc(arc, _) => Some(arc.as_ref()),
            TrackPart::Line(..) => None,
        }
    }
}

/// A curved track: an `Arc`, or a `Track` of pieces.
#[derive(Clone, Copy)]
pub(crate) enum Curved<'a> {
    Arc(&'a ArcTrack),
    Track(&'a TrackShape),
}

/// The curved track `g` is, if it is one.
pub(crate) fn curved(g: &dyn Shape) -> Option<Curved<'_>> {
    match g.as_shape::<ArcTrack>() {
        Some(arc) => Some(Curved::Arc(arc)),
        None => g.as_shape::<TrackShape>().map(Curved::Track),
    }
}

impl<'a> Curved<'a> {
    /// The facets every query but a ball's contact uses.
    pub fn facets(self) -> &'a Polyline {
        match self {
            Curved::Arc(arc) => &arc.polyline,
            Curved::Track(track) => &track.polyline,
        }
    }

    /// The circle a ball centered at `c` (track frame) rides, if any: an `Arc`'s own, a
    /// `Track`'s nearest arc piece. Whether the ball lies within its angles is the caller's
    /// ([`ArcTrack::spans_point`]).
    pub fn circle(self, c: Vector) -> Option<&'a ArcTrack> {
        match self {
            Curved::Arc(arc) => Some(arc),
            Curved::Track(track) => track.nearest_arc(c),
        }
    }
}

super::arc_track::polyline_backed_shape!(TrackShape);

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// A quarter-circle ramp R = 1 about (0, 1) from (-1, 1) to (0, 0), then a floor to (1, 0).
    fn ramp_floor() -> TrackShape {
        let arc = ArcTrack::new(
            Polyline::new(vec![Vector::new(-1.0, 1.0), Vector::ZERO], None),
            Vector::new(0.0, 1.0),
            1.0,
            (PI, 1.5 * PI),
            true,
        );
        let pts = vec![Vector::new(-1.0, 1.0), Vector::ZERO, Vector::new(1.0, 0.0)];
        TrackShape::new(
            Polyline::new(pts, None),
            vec![
                TrackPart::Arc(Box::new(arc), (Vector::new(-1.0, 1.0), Vector::ZERO)),
                TrackPart::Line(Vector::ZERO, Vector::new(1.0, 0.0)),
            ],
        )
    }

    #[test]
    fn a_ball_rides_the_nearest_pieces_circle() {
        let track = ramp_floor();
        let c = Curved::Track(&track);
        // On the ramp, 45 degrees up: its circle.
        let on_ramp = Vector::new(-0.6, 0.4);
        assert!(c.circle(on_ramp).is_some_and(|a| a.spans_point(on_ramp)));
        // On the floor: none (the facets, a line).
        assert!(c.circle(Vector::new(0.5, 0.1)).is_none());
    }
}
