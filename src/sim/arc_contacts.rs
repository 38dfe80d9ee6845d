//! The query dispatcher that gives a ball on an arc track its exact contact.
//!
//! rapier 0.36 asks its narrow phase's `PersistentQueryDispatcher` for every pair's contact
//! manifolds (`geometry/narrow_phase/pair_update.rs`), and lets a world replace it
//! (`NarrowPhase::set_query_dispatcher`). [`ArcContacts`] is chained before parry's
//! `DefaultQueryDispatcher` ([`dispatcher`]): for a pair with an [`ArcTrack`] it answers itself,
//! for any other pair it says `Unsupported` and the default one answers as before.
//!
//! - A ball against an arc, its center within the arc's angles: one contact point from
//!   [`ArcTrack::touch`], the circle's own radius as the normal, kept from call to call (its
//!   impulse warm-starts the next call, where a polyline's contact moved from facet to facet as
//!   new manifolds). Past the arc's ends, the facets ([`ArcTrack::spans_point`]).
//! - Any other shape against an arc (a block on a ramp), and every query but contacts: the
//!   arc's facets, through the default dispatcher, exactly as before the arc had a circle.
//! - A `Track` of pieces (sim/track_shape.rs) the same way: a ball within the angles of its
//!   nearest piece, when that is an arc, touches that piece's circle; elsewhere the track's one
//!   polyline.

use super::arc_track::ArcTrack;
use super::rapier::parry::query::details::NormalConstraints;
use super::rapier::parry::query::{
    ClosestPoints, Contact, ContactManifold, ContactManifoldsWorkspace, DefaultQueryDispatcher,
    NonlinearRigidMotion, PersistentQueryDispatcher, QueryDispatcher, ShapeCastHit,
    ShapeCastOptions, ShapeDistance, ShapeIntersection, TrackedContact, Unsupported,
};
use super::rapier::parry::shape::{Ball, PackedFeatureId, Shape};
use super::rapier::prelude::*;
use super::track_shape::{curved, Curved};

/// Answers the pairs that hold an arc track; `Unsupported` for the others.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct ArcContacts;

/// The world's dispatcher: [`ArcContacts`], then parry's default.
pub(crate) fn dispatcher() -> impl PersistentQueryDispatcher<ContactManifoldData, ContactData> {
    ArcContacts.chain(DefaultQueryDispatcher)
}

/// A pair seen from the arc (or track): the arc, the other shape, and whether the arc is the
/// pair's first.
struct ArcPair<'a> {
    arc: Curved<'a>,
    other: &'a dyn Shape,
    arc_first: bool,
}

fn arc_pair<'a>(g1: &'a dyn Shape, g2: &'a dyn Shape) -> Option<ArcPair<'a>> {
    match (curved(g1), curved(g2)) {
        (Some(arc), _) => Some(ArcPair {
            arc,
            other: g2,
            arc_first: true,
        }),
        (None, Some(arc)) => Some(ArcPair {
            arc,
            other: g1,
            arc_first: false,
        }),
        (None, None) => None,
    }
}

/// The shape the default dispatcher is handed for `g`: an arc's (a track's) facets, or `g`.
fn facets(g: &dyn Shape) -> &dyn Shape {
    match curved(g) {
        Some(c) => c.facets(),
        None => g,
    }
}

/// A ball's contact with an arc, in each shape's frame: (point1, point2, normal1, normal2,
/// dist) as parry's `Contact` holds them, shape 1 first. `pos12` is shape 2's pose in shape
/// 1's frame.
/// The circle whose angles the ball's center lies within (its track's nearest arc piece), if
/// any: else its contact is the facets'.
fn within<'a>(pos12: &Pose, arc: Curved<'a>, arc_first: bool) -> Option<&'a ArcTrack> {
    let c = if arc_first {
        pos12.translation
    } else {
        pos12.inverse().translation
    };
    arc.circle(c).filter(|a| a.spans_point(c))
}

fn ball_contact(
    pos12: &Pose,
    arc: &ArcTrack,
    ball: &Ball,
    arc_first: bool,
) -> (Vector, Vector, Vector, Vector, Real) {
    let r = ball.radius;
    if arc_first {
        // The ball's center is pos12's translation in the arc's frame.
        let t = arc.touch(pos12.translation, r);
        let n2 = pos12.rotation.inverse() * -t.normal;
        (t.point, n2 * r, t.normal, n2, t.dist)
    } else {
        let t = arc.touch(pos12.inverse().translation, r);
        let n1 = pos12.rotation * -t.normal;
        (n1 * r, t.point, n1, t.normal, t.dist)
    }
}

/// The subshape ids of a ball's manifold with an arc's circle: no facet's index, so the facets'
/// branch knows to start afresh.
pub(crate) const CIRCLE: u32 = u32::MAX;

/// The one-point manifold of a ball on an arc, kept in `manifolds[0]` so that its contact's
/// impulses carry over to the next call (parry's ball-ball manifold does the same).
///
/// Its last call's total `impulse` is set to zero (the warm-start impulses stay): rapier's
/// solver takes a contact with a zero `impulse` as new, and bounces only new contacts (unless
/// e >= 1), while the circle's contact is turned by rapier's restitution pass in every call
/// (sim/arc_curvature.rs, which decides newness itself from the warm-start impulse). rapier
/// writes the call's impulse back after solving, so readings are unchanged.
fn ball_manifold<M>(
    pos12: &Pose,
    arc: &ArcTrack,
    ball: &Ball,
    arc_first: bool,
    prediction: Real,
    manifolds: &mut Vec<ContactManifold<M, ContactData>>,
) where
    M: Default,
{
    if manifolds.len() != 1 || manifolds[0].subshape1 != CIRCLE {
        manifolds.clear();
        manifolds.push(ContactManifold::with_data(CIRCLE, CIRCLE, M::default()));
    }
    let m = &mut manifolds[0];
    let (p1, p2, n1, n2, dist) = ball_contact(pos12, arc, ball, arc_first);
    if dist >= prediction {
        m.points.clear();
        return;
    }
    let face = PackedFeatureId::face(0);
    let contact = TrackedContact::new(p1, p2, face, face, dist);
    match m.points.first_mut() {
        Some(kept) => {
            kept.copy_geometry_from(contact);
            kept.data.impulse = 0.0;
            m.points.truncate(1);
        }
        None => m.points.push(contact),
    }
    m.local_n1 = n1;
    m.local_n2 = n2;
}

impl QueryDispatcher for ArcContacts {
    fn intersection_test(
        &self,
        pos12: &Pose,
        g1: &dyn Shape,
        g2: &dyn Shape,
    ) -> Result<ShapeIntersection, Unsupported> {
        arc_pair(g1, g2).ok_or(Unsupported)?;
        DefaultQueryDispatcher.intersection_test(pos12, facets(g1), facets(g2))
    }

    fn distance(
        &self,
        pos12: &Pose,
        g1: &dyn Shape,
        g2: &dyn Shape,
    ) -> Result<ShapeDistance, Unsupported> {
        arc_pair(g1, g2).ok_or(Unsupported)?;
        DefaultQueryDispatcher.distance(pos12, facets(g1), facets(g2))
    }

    fn contact(
        &self,
        pos12: &Pose,
        g1: &dyn Shape,
        g2: &dyn Shape,
        prediction: Real,
    ) -> Result<Option<Contact>, Unsupported> {
        let pair = arc_pair(g1, g2).ok_or(Unsupported)?;
        let circle = within(pos12, pair.arc, pair.arc_first);
        if let Some((ball, arc)) = pair.other.as_ball().zip(circle) {
            let (p1, p2, n1, n2, dist) = ball_contact(pos12, arc, ball, pair.arc_first);
            return Ok((dist <= prediction).then(|| Contact::new(p1, p2, n1, n2, dist)));
        }
        DefaultQueryDispatcher.contact(pos12, facets(g1), facets(g2), prediction)
    }

    fn closest_points(
        &self,
        pos12: &Pose,
        g1: &dyn Shape,
        g2: &dyn Shape,
        max_dist: Real,
    ) -> Result<ClosestPoints, Unsupported> {
        arc_pair(g1, g2).ok_or(Unsupported)?;
        DefaultQueryDispatcher.closest_points(pos12, facets(g1), facets(g2), max_dist)
    }

    fn cast_shapes(
        &self,
        pos12: &Pose,
        local_vel12: Vector,
        g1: &dyn Shape,
        g2: &dyn Shape,
        options: ShapeCastOptions,
    ) -> Result<Option<ShapeCastHit>, Unsupported> {
        arc_pair(g1, g2).ok_or(Unsupported)?;
        DefaultQueryDispatcher.cast_shapes(pos12, local_vel12, facets(g1), facets(g2), options)
    }

    fn cast_shapes_nonlinear(
        &self,
        motion1: &NonlinearRigidMotion,
        g1: &dyn Shape,
        motion2: &NonlinearRigidMotion,
        g2: &dyn Shape,
        start_time: Real,
        end_time: Real,
        stop_at_penetration: bool,
    ) -> Result<Option<ShapeCastHit>, Unsupported> {
        // A time of impact on the facets, within half the chord error of the circle's.
        arc_pair(g1, g2).ok_or(Unsupported)?;
        DefaultQueryDispatcher.cast_shapes_nonlinear(
            motion1,
            facets(g1),
            motion2,
            facets(g2),
            start_time,
            end_time,
            stop_at_penetration,
        )
    }
}

impl<M> PersistentQueryDispatcher<M, ContactData> for ArcContacts
where
    M: Default + Clone + Send + Sync,
{
    fn contact_manifolds(
        &self,
        pos12: &Pose,
        g1: &dyn Shape,
        g2: &dyn Shape,
        prediction: Real,
        manifolds: &mut Vec<ContactManifold<M, ContactData>>,
        workspace: &mut Option<ContactManifoldsWorkspace>,
    ) -> Result<(), Unsupported> {
        let pair = arc_pair(g1, g2).ok_or(Unsupported)?;
        let circle = within(pos12, pair.arc, pair.arc_first);
        if let Some((ball, arc)) = pair.other.as_ball().zip(circle) {
            // A workspace left by the facets stays: rapier takes a pair's manifold count as
            // stable unless it holds one, and a count changed without one panics its solver
            // graph ("stale ContactRef", manifold_store.rs). The facets' branch drops it.
            ball_manifold(pos12, arc, ball, pair.arc_first, prediction, manifolds);
            return Ok(());
        }
        if manifolds
            .iter()
            .any(|m| m.subshape1 == CIRCLE || m.subshape2 == CIRCLE)
        {
            // The circle's manifold is none of the facets': they start afresh.
            manifolds.clear();
            *workspace = None;
        }
        DefaultQueryDispatcher.contact_manifolds(
            pos12,
            facets(g1),
            facets(g2),
            prediction,
            manifolds,
            workspace,
        )
    }

    fn contact_manifold_convex_convex(
        &self,
        _pos12: &Pose,
        _g1: &dyn Shape,
        _g2: &dyn Shape,
        _normal_constraints1: Option<&dyn NormalConstraints>,
        _normal_constraints2: Option<&dyn NormalConstraints>,
        _prediction: Real,
        _manifold: &mut ContactManifold<M, ContactData>,
    ) -> Result<(), Unsupported> {
        // An arc is not convex: parry never asks this of it.
        Err(Unsupported)
    }
}

/// parry's `query::contact` (world poses in, world points out) through the world's dispatcher,
/// which knows arc tracks where parry's free function does not.
pub(crate) fn contact(
    dispatcher: &dyn PersistentQueryDispatcher<ContactManifoldData, ContactData>,
    pos1: &Pose,
    g1: &dyn Shape,
    pos2: &Pose,
    g2: &dyn Shape,
    prediction: Real,
) -> Option<Contact> {
    let mut c = dispatcher
        .contact(&pos1.inv_mul(pos2), g1, g2, prediction)
        .ok()??;
    c.transform_by_mut(pos1, pos2);
    Some(c)
}
