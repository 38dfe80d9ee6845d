//! Building the rapier world from a validated scene, with only the declared effects.

use super::arc_track::ArcTrack;
use super::rapier::parry::shape::{Polyline, PolylineFlags};
use super::rapier::prelude::*;
use super::track_shape::{TrackPart, TrackShape};
use crate::level::curves;
use crate::level::track::Walked;
use crate::level::{
    ArcSide, BodyDef, BodyKind, Effect, JointDef, JointKind, Level, Motor, Shape as LevelShape, V2,
};
use crate::sim::describe;
use crate::sim::options::Effects;
use crate::sim::settings::Settings;

pub(crate) fn v(p: V2) -> Vector {
    Vector::new(p.0 as Real, p.1 as Real)
}

/// The parry shape for a level shape. Nested compounds are flattened (parry forbids them).
pub fn shared_shape(s: &LevelShape) -> SharedShape {
    match s {
        LevelShape::Circle { radius } => SharedShape::ball(*radius as Real),
        LevelShape::Box { width, height } => {
            SharedShape::cuboid((*width / 2.0) as Real, (*height / 2.0) as Real)
        }
        LevelShape::Capsule { length, radius } => {
            SharedShape::capsule_x((*length / 2.0) as Real, *radius as Real)
        }
        LevelShape::Polygon { points } => {
            let pts: Vec<Vector> = points.iter().map(|p| v(*p)).collect();
            // Validation guarantees >= 3 points enclosing an area, so the hull exists.
            SharedShape::convex_hull(&pts).unwrap_or_else(|| SharedShape::ball(1e-3))
        }
        LevelShape::Segment { a, b } => SharedShape::segment(v(*a), v(*b)),
        LevelShape::Track { .. } => track(s),
        LevelShape::Polyline { .. } | LevelShape::Arc { .. } => {
            // Validation keeps tracks whole (at least two points, never in a compound).
            let (points, closed) = curves::track_points(s).unwrap_or_default();
            let mut pts: Vec<Vector> = points.iter().map(|p| v(*p)).collect();
            // parry's one-sided polyline collides on the right of its direction (a solid wound
            // counter-clockwise) and clamps each contact normal between its neighbouring faces'
            // normals, so a body riding a concave run of facets meets no vertex contact whose
            // normal, linearised over the step, would throw it off the track.
            let solid_left = match curves::solid_side(s) {
                Some(left) => left,
                None => {
                    let indices = closing(pts.len(), closed);
                    return SharedShape::polyline(pts, indices);
                }
            };
            if !solid_left {
                pts.reverse();
            }
            let indices = closing(pts.len(), closed);
            let facets = Polyline::with_flags(pts, indices, PolylineFlags::ORIENTED);
            match s {
                // A ball touches the circle itself (sim/arc_track.rs, sim/arc_contacts.rs).
                LevelShape::Arc {
                    center,
                    radius,
                    start,
                    end,
                    side,
                    ..
                } => SharedShape::new(ArcTrack::new(
                    facets,
                    v(*center),
                    *radius as Real,
                    (*start, *end),
                    *side == ArcSide::Inside,
                )),
                _ => SharedShape::new(facets),
            }
        }
        // parry forbids nested compounds: the leaves, with their composed poses.
        LevelShape::Compound { parts } => SharedShape::compound(
            describe::leaves(parts)
                .into_iter()
                .map(|l| {
                    (
                        Pose::new(v(l.offset), l.angle as Real),
                        shared_shape(l.shape),
                    )
                })
                .collect(),
        ),
    }
}

/// A `Track`: the one-sided polyline through all its pieces (as a `Polyline`'s), and each arc
/// piece's circle with its own facets, which a ball touches (sim/track_shape.rs).
fn track(s: &LevelShape) -> SharedShape {
    let LevelShape::Track {
        start,
        heading,
        pieces,
        solid,
        chord_error,
    } = s
    else {
        unreachable!("track() is called on a Track")
    };
    // Validation walks the track before a run: a track that does not walk never gets here.
    let facets = crate::level::track::Facets::Engine(*chord_error);
    let Ok(path) = crate::level::track::walk(*start, *heading, pieces, *solid, facets) else {
        return SharedShape::ball(1e-3);
    };
    let parts = path
        .pieces
        .iter()
        .enumerate()
        .map(|(k, piece)| match piece {
            Walked::Line { from, to } => TrackPart::Line(v(*from), v(*to)),
            Walked::Arc {
                center,
                radius,
                start,
                end,
                inside,
            } => {
                // The piece's own points: from the start of its first edge to the end of its last.
                let first = path.edge_piece.iter().position(|&p| p == k).unwrap_or(0);
                let last = path.edge_piece.iter().rposition(|&p| p == k).unwrap_or(0) + 1;
                let pts: Vec<Vector> = path.points[first..=last].iter().map(|p| v(*p)).collect();
                let ends = (pts[0], pts[pts.len() - 1]);
                let arc = ArcTrack::new(
                    Polyline::new(pts, None),
                    v(*center),
                    *radius as Real,
                    (*start, *end),
                    *inside,
                );
                TrackPart::Arc(Box::new(arc), ends)
            }
        })
        .collect();
    let mut pts: Vec<Vector> = path.points.iter().map(|p| v(*p)).collect();
    // parry's one-sided polyline has its solid on the left of its direction (as for `Polyline`).
    if *solid == crate::level::TrackSide::Right {
        pts.reverse();
    }
    let polyline = Polyline::with_flags(pts, None, PolylineFlags::ORIENTED);
    SharedShape::new(TrackShape::new(polyline, parts))
}

/// The index buffer of a closed polyline through `n` points (None: open, in order).
fn closing(n: usize, closed: bool) -> Option<Vec<[u32; 2]>> {
    let n = n as u32;
    (closed && n >= 3).then(|| (0..n).map(|k| [k, (k + 1) % n]).collect())
}

pub use crate::level::DEFAULT_DENSITY;

/// What parry2d 0.31.1 leaves out of a 2D capsule's centroidal moment of inertia, at unit
/// density, summed over every capsule of the shape (compound parts included).
///
/// parry builds a capsule as a rectangle plus a disc moved out to the two caps, and moves each
/// half disc by the 3D hemisphere's centroid offset 3r/8 where the half disc's is 4r/(3 pi)
/// (MP-9): its extra term is A_disc (l^2/4 + l 3r/8) instead of A_disc (l^2/4 + l 4r/(3 pi)). The
/// shortfall, A_disc l r (4/(3 pi) - 3/8) = pi r^3 l (4/(3 pi) - 3/8), is -1.2% of I_G for a
/// capsule 0.6 m long with r = 0.1 m (tests/suite/sim/impulse_conversions.rs measures it on parry's own value).
/// A pure centroidal term: it changes neither the mass nor the mass center, of the capsule or of
/// a compound holding it, and adds the same to the compound's I_G.
pub fn capsule_inertia_shortfall(s: &LevelShape) -> f64 {
    match s {
        LevelShape::Capsule { length, radius } => {
            let r = *radius;
            std::f64::consts::PI
                * r.powi(3)
                * length
                * (4.0 / (3.0 * std::f64::consts::PI) - 3.0 / 8.0)
        }
        LevelShape::Compound { parts } => parts
            .iter()
            .map(|p| capsule_inertia_shortfall(&p.shape))
            .sum(),
        _ => 0.0,
    }
}

/// Mass properties of a body: from the shape at its density or given mass (parry's, with the
/// capsule's shortfall made good: [`capsule_inertia_shortfall`]), then the inertia override.
pub fn mass_properties(b: &BodyDef) -> MassProperties {
    let shape = b.shape.as_ref().map(shared_shape);
    let unit = shape.as_ref().map(|s| s.mass_properties(1.0)).map(|u| {
        let extra = b.shape.as_ref().map_or(0.0, capsule_inertia_shortfall);
        MassProperties::new(
            u.local_com,
            u.mass(),
            (u.principal_inertia() as f64 + extra) as Real,
        )
    });
    let unit_mass = unit.map_or(0.0, |u| u.mass() as f64);
    let (mass, com, inertia) = match (b.mass, unit) {
        (Some(m), Some(u)) if unit_mass > 0.0 => {
            (m, u.local_com, u.principal_inertia() as f64 * m / unit_mass)
        }
        (Some(m), _) => (m, Vector::ZERO, 0.0),
        (None, Some(u)) => {
            let d = b.density.unwrap_or(DEFAULT_DENSITY);
            (unit_mass * d, u.local_com, u.principal_inertia() as f64 * d)
        }
        (None, None) => (0.0, Vector::ZERO, 0.0),
    };
    let inertia = match (b.inertia, b.radius_of_gyration) {
        (Some(i), _) => i,
        (None, Some(k)) => mass * k * k,
        _ => inertia,
    };
    MassProperties::new(com, mass as Real, inertia as Real)
}

pub(crate) fn body_builder(b: &BodyDef, fx: &Effects, fast_rotation: bool) -> RigidBodyBuilder {
    let builder = match b.kind {
        BodyKind::Fixed => RigidBodyBuilder::fixed(),
        BodyKind::Dynamic => RigidBodyBuilder::dynamic(),
        BodyKind::Kinematic => RigidBodyBuilder::kinematic_velocity_based(),
    };
    let (linear_damping, angular_damping) = describe::damping(b, fx);
    let mut builder = builder
        .translation(v(b.position))
        .rotation(b.angle as Real)
        .linvel(v(b.velocity))
        .angvel(b.omega as Real)
        .can_sleep(fx.has(Effect::Sleeping))
        .ccd_enabled(fx.has(Effect::Ccd) && b.kind == BodyKind::Dynamic)
        .linear_damping(linear_damping as Real)
        .angular_damping(angular_damping as Real);
    if b.kind == BodyKind::Dynamic {
        // Colliders get zero density: mass properties are the same with or without contacts.
        builder = builder.additional_mass_properties(mass_properties(b));
    }
    if b.lock_rotation {
        builder = builder.lock_rotations();
    }
    builder.allow_fast_rotation(fast_rotation)
}

/// Colliders for a body's shape, only when contacts are simulated.
pub(crate) fn colliders(b: &BodyDef, fx: &Effects) -> Vec<ColliderBuilder> {
    let Some(shape) = &b.shape else {
        return Vec::new();
    };
    let surface = describe::surface(b, fx);
    // A ball's solver point goes on its rim (sim/contact_points.rs).
    let hooks = if matches!(shape, LevelShape::Circle { .. }) {
        ActiveHooks::MODIFY_SOLVER_CONTACTS
    } else {
        ActiveHooks::empty()
    };
    vec![ColliderBuilder::new(shared_shape(shape))
        .active_hooks(hooks)
        .density(0.0)
        .friction(surface.friction as Real)
        .restitution(surface.restitution as Real)
        // The pair uses the larger coefficient: a level sets e or mu on one body and it applies as given.
        .friction_combine_rule(CoefficientCombineRule::Max)
        .restitution_combine_rule(CoefficientCombineRule::Max)]
}

pub(crate) fn joint(j: &JointDef, b1: &BodyDef, b2: &BodyDef) -> GenericJoint {
    let f = describe::joint_frames(j, b1, b2);
    let frame1 = Pose::new(v(f.anchor1), f.angle1 as Real);
    let frame2 = Pose::new(v(f.anchor2), f.angle2 as Real);
    let (mask, coord_axis) = match j.kind {
        JointKind::Revolute => (JointAxesMask::LOCKED_REVOLUTE_AXES, JointAxis::AngX),
        JointKind::Prismatic => (JointAxesMask::LOCKED_PRISMATIC_AXES, JointAxis::LinX),
        JointKind::Fixed => (JointAxesMask::LOCKED_FIXED_AXES, JointAxis::AngX),
        JointKind::PinSlot => (JointAxesMask::LOCKED_PIN_SLOT_AXES, JointAxis::LinX),
    };
    let mut g = GenericJointBuilder::new(mask)
        .local_frame1(frame1)
        .local_frame2(frame2)
        .contacts_enabled(false);
    if let Some((lo, hi)) = j.limits {
        g = g.limits(coord_axis, [lo as Real, hi as Real]);
    }
    match &j.motor {
        Some(Motor::Velocity { target, max_force }) => {
            // A very stiff velocity servo: holds the rate like a constraint, up to max_force.
            g = g
                .motor_model(coord_axis, MotorModel::ForceBased)
                .motor_velocity(coord_axis, *target as Real, 1e9);
            if let Some(f) = max_force {
                g = g.motor_max_force(coord_axis, *f as Real);
            }
        }
        Some(Motor::Position {
            target,
            stiffness,
            damping,
            max_force,
        }) => {
            g = g
                .motor_model(coord_axis, MotorModel::ForceBased)
                .motor_position(
                    coord_axis,
                    *target as Real,
                    *stiffness as Real,
                    *damping as Real,
                );
            if let Some(f) = max_force {
                g = g.motor_max_force(coord_axis, *f as Real);
            }
        }
        None => {}
    }
    g.build()
}

/// rapier's parameters for one step of the resolved settings (split substeps change `dt` and
/// `num_solver_iterations` around each call, see `world::Simulation::step`).
pub(crate) fn integration_parameters(s: &Settings) -> IntegrationParameters {
    let mut p = IntegrationParameters {
        dt: s.dt as Real,
        num_solver_iterations: s.substeps,
        num_internal_pgs_iterations: s.solver_iterations,
        // The unbiased pass is where rapier 0.36 solves friction (`friction_in_bias_pass` is off):
        // one sweep of it leaves an eccentric rough contact's normal row unconverged, and the
        // next substep's warm start then bounces the body (sim/impacts.rs, IMPACT_ITERATIONS).
        // The biased pass holds the normal rows alone, so its sweeps cannot converge friction.
        num_internal_stabilization_iterations: s.solver_iterations,
        max_ccd_substeps: if s.effects.has(Effect::Ccd) { 1 } else { 0 },
        contact_recycling: s.contact_recycling,
        ..Default::default()
    };
    if let Some(hz) = s.contact_hz {
        // Contacts with fixed bodies stay twice as stiff, as in rapier's defaults (30/60 Hz).
        p.contact_softness.natural_frequency = hz as Real;
        p.static_contact_softness.natural_frequency = (2.0 * hz) as Real;
    }
    p
}

/// Gravity is the level's only when declared (`--all-effects` cannot invent a gravity the level lacks).
pub(crate) fn gravity(level: &Level) -> Vector {
    if level.effects.contains(&Effect::Gravity) {
        v(level.world.gravity.unwrap_or((0.0, -9.81)))
    } else {
        Vector::ZERO
    }
}
