//! Building a Box2D world from a validated scene (the subset `support.rs` lets through).
//!
//! Mass properties are rigidlab's own (`sim::mass_properties`, the ones the rapier world gets),
//! set on each body with `b2Body_SetMassData`: both engines move the same masses, and the
//! analysis reads the same m and I_G.

use super::world::Simulation;
use crate::level::*;
use crate::sim::{describe, mass_properties, Effects, Settings};
use boxdd::{
    shapes, BodyBuilder, BodyId, BodyType, ConstraintTuning, Foundation, JointId, MassData,
    MotionLocks, Position, PrismaticJointDef, RevoluteJointDef, ShapeDef, ShapeId, SurfaceMaterial,
    Transform, Vec2, WeldJointDef, World, WorldBuilder,
};
use glam::DVec2;

pub(super) type Result<T> = std::result::Result<T, boxdd::Error>;

pub(super) fn v(p: V2) -> Vec2 {
    Vec2::new(p.0 as f32, p.1 as f32)
}

/// Gravity in effect: the level's (default (0, -9.81)) when `gravity` is declared, else none.
pub(super) fn gravity(level: &Level, fx: &Effects) -> DVec2 {
    if fx.has(Effect::Gravity) {
        let g = level.world.gravity.unwrap_or((0.0, -9.81));
        DVec2::new(g.0, g.1)
    } else {
        DVec2::ZERO
    }
}

/// The restitution threshold, m/s: Box2D bounces a contact only when it approaches faster. Its
/// default (1 m/s) would land a textbook impact of 0.5 m/s dead; rigidlab sets the speed that
/// gravity gives in one step, |g| dt (0.16 m/s at 60 Hz), so that a body resting on a bouncy
/// floor (approach speed about |g| h per substep) is not kicked, and every impact faster than
/// that bounces with its e. Without gravity, 1 mm/s.
pub(super) fn restitution_threshold(g: DVec2, dt: f64) -> f32 {
    (g.length() * dt).max(1e-3) as f32
}

pub(super) fn world(level: &Level, settings: &Settings) -> Result<(World, DVec2)> {
    let foundation = Foundation::initialize_default()?;
    let fx = &settings.effects;
    let g = gravity(level, fx);
    let mut def = WorldBuilder::from(foundation.world_def())
        .gravity(Vec2::new(g.x as f32, g.y as f32))
        .restitution_threshold(restitution_threshold(g, settings.dt))
        .enable_sleep(fx.has(Effect::Sleeping))
        .enable_continuous(fx.has(Effect::Ccd));
    if let Some(hz) = settings.contact_hz {
        def = def.contact_hertz(hz as f32);
    }
    let mut world = foundation.create_world(def.build()?)?;
    // The pair uses the larger coefficient, as on rapier (`sim/build.rs`): a level sets e or mu
    // on one body and it applies as given (Box2D's default friction mix is the geometric mean).
    world.set_friction_callback(
        boxdd::MixerId::from_bytes(*b"rigidlab: friction = max(a, b)  "),
        |a, b| a.coefficient.max(b.coefficient),
    )?;
    world.set_restitution_callback(
        boxdd::MixerId::from_bytes(*b"rigidlab: restitution = max(a,b)"),
        |a, b| a.coefficient.max(b.coefficient),
    )?;
    Ok((world, g))
}

fn body_type(kind: BodyKind) -> BodyType {
    match kind {
        BodyKind::Fixed => BodyType::Static,
        BodyKind::Dynamic => BodyType::Dynamic,
        BodyKind::Kinematic => BodyType::Kinematic,
    }
}

impl Simulation {
    /// Adds the level's bodies, their shapes (only when contacts are declared) and their masses.
    pub(super) fn insert_bodies(&mut self) -> Result<()> {
        let fx = self.settings.effects.clone();
        let fast = self.settings.allow_fast_rotation;
        for (i, b) in self.level.bodies.clone().iter().enumerate() {
            let mp = mass_properties(b);
            let com = DVec2::new(mp.local_com.x as f64, mp.local_com.y as f64);
            // Box2D's kinematic body moves its origin at its linear velocity; the level gives
            // the mass center's, which is the origin's for a body that does not turn (a
            // turning kinematic body is refused).
            let (linear_damping, angular_damping) = describe::damping(b, &fx);
            let def = BodyBuilder::from(Foundation::initialize_default()?.body_def())
                .body_type(body_type(b.kind))
                .position(Position::new(b.position.0 as _, b.position.1 as _))
                .angle(b.angle as f32)
                .linear_velocity(v(b.velocity))
                .angular_velocity(b.omega as f32)
                .linear_damping(linear_damping as f32)
                .angular_damping(angular_damping as f32)
                .enable_sleep(fx.has(Effect::Sleeping))
                .allow_fast_rotation(fast)
                .motion_locks(MotionLocks::new(false, false, b.lock_rotation))
                // As on rapier (`Settings::contact_recycling`, always off): a recycled contact
                // keeps its anchors while the body slides on, so a sliding bowling ball's floor
                // hopped (its step's normal impulse from 0.25 to 1.75 m g dt) and a rolling hoop
                // turned on stale lever arms (its acceleration 12.6% short).
                .enable_contact_recycling(false)
                .build()?;
            let id = self.world.create_body(def)?;
            self.bodies.push(id);
            if fx.has(Effect::Contacts) {
                if let Some(shape) = &b.shape {
                    let def = shape_def(b, &fx)?;
                    for s in add_shape(&mut self.world, id, &def, shape, Transform::IDENTITY)? {
                        self.shapes.insert(s, i);
                    }
                    // Shapes made without updating the mass leave it marked stale, which Box2D
                    // asserts against when it steps: fold them in once (density 0, so nothing),
                    // then set rigidlab's mass below.
                    self.world.body(id)?.apply_mass_from_shapes()?;
                }
            }
            if b.kind == BodyKind::Dynamic {
                let inertia = if b.lock_rotation {
                    0.0
                } else {
                    mp.principal_inertia()
                };
                let data =
                    MassData::new(mp.mass(), Vec2::new(com.x as f32, com.y as f32), inertia)?;
                self.world.body(id)?.set_mass_data(data)?;
            }
        }
        Ok(())
    }

    /// Adds the level's joints: pins, sliders and welds (the ones `support.rs` lets through).
    pub(super) fn insert_joints(&mut self) -> Result<()> {
        let stiffest = ConstraintTuning::new(joint_hertz(&self.settings), JOINT_DAMPING_RATIO)?;
        for j in self.level.joints.clone() {
            let (i1, i2) = (self.body_index(&j.body1), self.body_index(&j.body2));
            let (b1, b2) = (&self.level.bodies[i1], &self.level.bodies[i2]);
            // The frames rapier gets too (`describe::joint_frames`).
            let f = describe::joint_frames(&j, b1, b2);
            let frame1 = Transform::from_pos_angle(v(f.anchor1), f.angle1 as f32)?;
            let frame2 = Transform::from_pos_angle(v(f.anchor2), f.angle2 as f32)?;
            let base = self
                .world
                .joint_base(self.bodies[i1], self.bodies[i2])?
                .with_local_frames(frame1, frame2)
                .with_constraint_tuning(stiffest)
                .with_collide_connected(false);
            let id: JointId = match j.kind {
                JointKind::Revolute => self
                    .world
                    .create_revolute_joint(&RevoluteJointDef::new(base))?,
                JointKind::Prismatic => self
                    .world
                    .create_prismatic_joint(&PrismaticJointDef::new(base))?,
                JointKind::Fixed => self.world.create_weld_joint(&WeldJointDef::new(base))?,
                JointKind::PinSlot => unreachable!("refused by support.rs"),
            };
            self.joints.push(id);
            self.joint_pairs.push((i1, i2));
        }
        Ok(())
    }

    pub(super) fn body_index(&self, name: &str) -> usize {
        self.level
            .bodies
            .iter()
            .position(|b| b.name == name)
            .expect("validated levels name existing bodies")
    }
}

/// Box2D's default damping ratio of a joint's position correction (`b2DefaultJointDef`), kept.
const JOINT_DAMPING_RATIO: f32 = 2.0;

/// The frequency of a joint's position correction, Hz: the highest Box2D allows, a quarter of
/// the call rate (`b2PrepareJoint` clamps to 0.25 / h; rigidlab's calls are one substep of
/// h = dt / substeps each). Box2D's default, 60 Hz, leaves a loaded joint apart by its
/// steady-state error g / (2 pi f)^2 (the soft step's bias balancing the impulse it relaxes
/// every substep): 6.9e-5 m under a weight, which a 2 kg bar pendulum released at 5 degrees
/// took as 3.6% more drop of G than its d (1 - cos 5 deg) = 1.9 mm, and the work-energy
/// analysis of its kinetic energy read 3.6e-2 high (kinetics/classic_physical_pendulum_small,
/// dt 2 ms, 4 substeps: 500 Hz, 9.9e-7 m). rapier's joints correct the whole error every
/// substep (their natural frequency is 1e6 Hz), which this comes nearest to. At 60 Hz steps
/// of 4 substeps the cap is 60 Hz itself: a finer step is what closes the joint there.
pub(super) fn joint_hertz(settings: &Settings) -> f32 {
    let h = settings.dt / settings.substeps.max(1) as f64;
    (0.25 / h) as f32
}

/// The shape definition: the body's surface as rapier gets it (`describe::surface`).
fn shape_def(b: &BodyDef, fx: &Effects) -> Result<ShapeDef> {
    let surface = describe::surface(b, fx);
    let material = SurfaceMaterial::new()
        .with_friction(surface.friction as f32)?
        .with_restitution(surface.restitution as f32)?;
    ShapeDef::builder()
        .material(material)
        .density(0.0)
        // Masses are set once, from rigidlab's mass properties.
        .update_body_mass(false)
        .build()
}

fn add_shape(
    world: &mut World,
    body: BodyId,
    def: &ShapeDef,
    shape: &Shape,
    at: Transform,
) -> Result<Vec<ShapeId>> {
    if let Shape::Compound { parts } = shape {
        // The leaves rapier's compound has (`describe::leaves`).
        let mut ids = Vec::new();
        for l in describe::leaves(parts) {
            let t = Transform::from_pos_angle(v(l.offset), l.angle as f32)?;
            ids.extend(add_shape(world, body, def, l.shape, t)?);
        }
        return Ok(ids);
    }
    let place = |p: V2| -> Vec2 { at.transform_point(v(p)) };
    let mut b = world.body(body)?;
    let id = match shape {
        Shape::Circle { radius } => {
            b.create_circle(def, &shapes::circle(place((0.0, 0.0)), *radius as f32)?)?
        }
        Shape::Box { width, height } => b.create_polygon(
            def,
            &shapes::offset_box_polygon(*width as f32 / 2.0, *height as f32 / 2.0, at)?,
        )?,
        Shape::Capsule { length, radius } => b.create_capsule(
            def,
            &boxdd::Capsule::new(
                place((-length / 2.0, 0.0)),
                place((length / 2.0, 0.0)),
                *radius as f32,
            )?,
        )?,
        Shape::Polygon { points } => b.create_polygon(
            def,
            &shapes::polygon_from_points(points.iter().map(|&p| place(p)), 0.0)?,
        )?,
        Shape::Segment { a, b: e } => {
            b.create_segment(def, &shapes::segment(place(*a), place(*e))?)?
        }
        Shape::Compound { .. } => unreachable!("handled above"),
        Shape::Polyline { .. } | Shape::Arc { .. } | Shape::Track { .. } => {
            unreachable!("refused by support.rs")
        }
    };
    Ok(vec![id])
}
