//! The level file format: one exercise per RON file, SI units.
//!
//! Every struct rejects unknown fields. The reference with every field, its
//! unit and its default is `docs/levels.md`; keep the two in step.

use serde::{Deserialize, Serialize};

mod challenge;
mod exercise;
pub use challenge::*;
pub use exercise::*;
pub mod units;

/// Body kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BodyKind {
    Fixed,
    Dynamic,
    Kinematic,
}

/// Default area density when a level gives neither mass nor density, kg/m^2.
pub const DEFAULT_DENSITY: f64 = 1000.0;

/// A 2D vector in a level file: `(x, y)`.
pub type V2 = (f64, f64);

/// One exercise: a scene plus the textbook question(s) about it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Level {
    pub title: String,
    #[serde(default)]
    pub source: Source,
    /// The problem as the textbook states it (givens with units).
    #[serde(default)]
    pub statement: String,
    /// Hints, shown one per wrong attempt, in order.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub hints: Vec<String>,
    /// The worked solution: shown after every question is answered right, or on request
    /// (which counts the solve as "solved with help").
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub solution: String,
    /// The physical effects the scene calls for; nothing else is simulated.
    #[serde(default)]
    pub effects: Vec<Effect>,
    #[serde(default)]
    pub world: World,
    pub bodies: Vec<BodyDef>,
    #[serde(default)]
    pub joints: Vec<JointDef>,
    #[serde(default)]
    pub springs: Vec<SpringDef>,
    /// Torsion springs (rotational spring-dampers between two bodies or a body and the ground).
    #[serde(default)]
    pub torsion_springs: Vec<TorsionSpringDef>,
    /// Ratio constraints: pulleys, cables on drums, gears, racks (need `joints`).
    #[serde(default)]
    pub couplings: Vec<CouplingDef>,
    #[serde(default)]
    pub loads: Vec<LoadDef>,
    #[serde(default)]
    pub events: Vec<EventDef>,
    /// A control the student sets and a goal the run must meet (docs/levels.md#challenges).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub challenge: Option<ChallengeDef>,
    /// Theory-against-engine checks evaluated every step.
    #[serde(default)]
    pub checks: Vec<CheckDef>,
    /// The exercise's questions with their expected answers.
    #[serde(default)]
    pub questions: Vec<QuestionDef>,
    /// Predict first: the window and the page hold the scene at t = 0 until the student has
    /// answered every question (or given up), then play the motion and show each answer beside
    /// the engine's and the analysis's values (docs/levels.md#predict-first).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub predict_first: bool,
}

/// Where the exercise comes from.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Source {
    #[serde(default)]
    pub book: String,
    #[serde(default)]
    pub problem: String,
}

/// The effects a level may declare (promise 3: simulate only what the scene calls for).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Effect {
    Gravity,
    Contacts,
    Friction,
    Restitution,
    Joints,
    Springs,
    Motors,
    Damping,
    Ccd,
    Sleeping,
}

impl Effect {
    pub const ALL: [Effect; 10] = [
        Effect::Gravity,
        Effect::Contacts,
        Effect::Friction,
        Effect::Restitution,
        Effect::Joints,
        Effect::Springs,
        Effect::Motors,
        Effect::Damping,
        Effect::Ccd,
        Effect::Sleeping,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Effect::Gravity => "gravity",
            Effect::Contacts => "contacts",
            Effect::Friction => "friction",
            Effect::Restitution => "restitution",
            Effect::Joints => "joints",
            Effect::Springs => "springs",
            Effect::Motors => "motors",
            Effect::Damping => "damping",
            Effect::Ccd => "ccd",
            Effect::Sleeping => "sleeping",
        }
    }
}

/// Floating-point precision of the engine (rapier2d or rapier2d-f64).
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Precision {
    #[default]
    F32,
    F64,
}

impl Precision {
    /// Machine epsilon: the relative spacing of numbers near 1. A velocity v held in this
    /// precision changes in steps of about |v| epsilon, so a force read from velocity
    /// differences over a step is resolved only to m |v| epsilon / dt per rounding.
    pub fn epsilon(self) -> f64 {
        match self {
            Precision::F32 => f32::EPSILON as f64,
            Precision::F64 => f64::EPSILON,
        }
    }

    pub fn is_f32(&self) -> bool {
        *self == Precision::F32
    }

    pub fn name(self) -> &'static str {
        match self {
            Precision::F32 => "f32",
            Precision::F64 => "f64",
        }
    }
}

/// World and solver settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct World {
    /// Gravity acceleration, m/s^2 (default (0, -9.81)). Needs `gravity`.
    pub gravity: Option<V2>,
    /// Physics step, s.
    pub dt: f64,
    /// rapier's `num_solver_iterations`: the number of substeps per step.
    pub substeps: usize,
    /// rapier's `num_internal_pgs_iterations` and `num_internal_stabilization_iterations`: the
    /// biased and the unbiased (friction's) solver sweeps per substep.
    pub solver_iterations: usize,
    /// Simulated time, s.
    pub duration: f64,
    /// Contact stiffness: rapier's `contact_softness.natural_frequency`, Hz (None: rapier's
    /// 30 Hz; contacts with fixed bodies use twice this, like rapier's 60 Hz default).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact_hz: Option<f64>,
    /// rapier's `RigidBody::set_allow_fast_rotation` on every body: lifts the (pi/4)/dt cap
    /// that rapier puts on |omega| (off by default, like rapier).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub allow_fast_rotation: bool,
    /// The engine's floating point: `f32` (rapier2d, the default, what games ship) or `f64`
    /// (rapier2d-f64), for small motions far from the origin (docs/levels.md).
    #[serde(skip_serializing_if = "Precision::is_f32")]
    pub precision: Precision,
    /// The physics engine: `rapier` (the default) or `box2d` (Box2D v3, native builds with the
    /// `box2d` feature; docs/engines.md says what it runs and what it refuses).
    #[serde(skip_serializing_if = "PhysicsEngine::is_rapier")]
    pub engine: PhysicsEngine,
}

/// The physics engine a level runs on (`world.engine`, `--engine`).
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PhysicsEngine {
    /// rapier2d (or rapier2d-f64 at `precision: f64`).
    #[default]
    Rapier,
    /// Box2D v3 through the `boxdd` crate (src/sim/box2d/).
    Box2d,
}

impl PhysicsEngine {
    pub fn is_rapier(&self) -> bool {
        *self == PhysicsEngine::Rapier
    }

    pub fn name(self) -> &'static str {
        match self {
            PhysicsEngine::Rapier => "rapier",
            PhysicsEngine::Box2d => "box2d",
        }
    }
}

impl Default for World {
    fn default() -> Self {
        World {
            gravity: None,
            dt: 1.0 / 60.0,
            substeps: 4,
            solver_iterations: 1,
            duration: 2.0,
            contact_hz: None,
            allow_fast_rotation: false,
            precision: Precision::F32,
            engine: PhysicsEngine::Rapier,
        }
    }
}

/// A rigid body.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodyDef {
    pub name: String,
    #[serde(default = "default_kind")]
    pub kind: BodyKind,
    /// None: a point (fixed anchors) or a body with given mass and inertia.
    #[serde(default)]
    pub shape: Option<Shape>,
    /// Position of the body frame origin, m.
    #[serde(default)]
    pub position: V2,
    /// Rotation, rad, counter-clockwise.
    #[serde(default)]
    pub angle: f64,
    /// Initial velocity of the mass center, m/s.
    #[serde(default)]
    pub velocity: V2,
    /// Initial angular velocity, rad/s, counter-clockwise.
    #[serde(default)]
    pub omega: f64,
    /// Mass, kg. Exclusive with `density`.
    #[serde(default)]
    pub mass: Option<f64>,
    /// Area density, kg/m^2 (default 1000 when neither mass nor density is given).
    #[serde(default)]
    pub density: Option<f64>,
    /// Centroidal moment of inertia I_G, kg m^2 (overrides the shape's).
    #[serde(default)]
    pub inertia: Option<f64>,
    /// Centroidal radius of gyration k_G, m: I_G = m k_G^2 (overrides the shape's).
    #[serde(default)]
    pub radius_of_gyration: Option<f64>,
    /// Lock rotation (particle models).
    #[serde(default)]
    pub lock_rotation: bool,
    /// Coulomb friction coefficient (needs `friction`); a pair uses the larger of its two values.
    #[serde(default)]
    pub friction: Option<f64>,
    /// Coefficient of restitution (needs `restitution`); a pair uses the larger of its two values.
    #[serde(default)]
    pub restitution: Option<f64>,
    /// Linear damping coefficient, 1/s (needs `damping`).
    #[serde(default)]
    pub linear_damping: Option<f64>,
    /// Angular damping coefficient, 1/s (needs `damping`).
    #[serde(default)]
    pub angular_damping: Option<f64>,
    /// A kinematic body's prescribed motion on top of its `velocity` and `omega` (none: it
    /// moves at them for ever). See [`Motion`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub motion: Option<Motion>,
}

/// A kinematic body's prescribed motion. The body frame's origin and angle follow it exactly
/// at every step's end (`src/level/motion.rs` gives its pose, velocity and acceleration at t).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Motion {
    /// Constant acceleration: x(t) = x0 + v0 t + a t^2 / 2, theta(t) = theta0 + omega0 t +
    /// alpha t^2 / 2 (a pushed cart, a lift starting up).
    Accelerate {
        /// a, m/s^2.
        acceleration: V2,
        /// alpha, rad/s^2.
        #[serde(default)]
        angular: f64,
    },
    /// A sinusoid about the start: x(t) = x0 + v0 t + A (sin(w t + phi) - sin(phi)),
    /// theta(t) = theta0 + omega0 t + Theta (sin(w t + phi) - sin(phi)) (a shaking support).
    Oscillate {
        /// A, m.
        #[serde(default)]
        amplitude: V2,
        /// Theta, rad.
        #[serde(default)]
        angular_amplitude: f64,
        /// w, rad/s: the circular frequency (2 pi f).
        omega: f64,
        /// phi, rad.
        #[serde(default)]
        phase: f64,
    },
}

impl BodyDef {
    /// The radius of a body whose shape is a disc about its origin (its G).
    pub fn disc_radius(&self) -> Option<f64> {
        match self.shape {
            Some(Shape::Circle { radius }) => Some(radius),
            _ => None,
        }
    }
}

fn default_kind() -> BodyKind {
    BodyKind::Dynamic
}

/// A collision/mass shape in the body frame. Sizes are full sizes, m.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Shape {
    Circle {
        radius: f64,
    },
    Box {
        width: f64,
        height: f64,
    },
    /// A stadium along the body x axis: `length` between the two cap centers.
    Capsule {
        length: f64,
        radius: f64,
    },
    /// A convex polygon (its convex hull is used), vertices in the body frame.
    Polygon {
        points: Vec<V2>,
    },
    /// A line segment (ground lines, walls): no area, so no mass.
    Segment {
        a: V2,
        b: V2,
    },
    /// A track through `points`, open or `closed`, concave allowed (rapier's polyline): no area,
    /// so no mass; never on a dynamic body (`level::curves`). `solid`: which side of the
    /// direction from the first point is solid, making it one-sided (bodies ride the other
    /// side); none: two-sided.
    Polyline {
        points: Vec<V2>,
        #[serde(default, skip_serializing_if = "std::ops::Not::not")]
        closed: bool,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        solid: Option<TrackSide>,
    },
    /// A circular arc track about `center`, radius m, counter-clockwise from `start` to `end`
    /// (rad), built as a polyline whose chords stay within `chord_error` (m, default 1e-7
    /// radius) of the circle, and as the circle itself for a ball's contact; `side` is where
    /// bodies ride. No mass; never on a dynamic body.
    Arc {
        #[serde(default)]
        center: V2,
        radius: f64,
        start: f64,
        end: f64,
        side: ArcSide,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        chord_error: Option<f64>,
    },
    /// A track of straight and circular pieces joined end to end from `start` (body frame, m):
    /// `Line(to:)`, `Arc(center:, sweep:)` (rad, counter-clockwise positive, its radius the
    /// distance from where it starts to `center`) and `Turn(radius:, angle:)` (tangent to the
    /// way the track heads, turning left for a positive angle; a first piece turns from
    /// `heading`, rad). `solid` is the side of the ground looking along the track (default
    /// `right`: drawn left to right with the ground below). Built as one polyline through every
    /// piece (each arc piece's facets within `chord_error`, m, default 1e-7 of its radius) and
    /// each arc piece's circle for a ball's contact (`level::track`). No mass; never on a
    /// dynamic body.
    Track {
        start: V2,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        heading: Option<f64>,
        pieces: Vec<TrackPiece>,
        #[serde(default = "ground_on_the_right")]
        solid: TrackSide,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        chord_error: Option<f64>,
    },
    Compound {
        parts: Vec<Part>,
    },
}

/// One piece of a `Track`, from where the piece before it ends.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum TrackPiece {
    /// A straight piece to `to` (m).
    Line { to: V2 },
    /// A circular piece about `center` (m) turning `sweep` rad, counter-clockwise positive.
    Arc { center: V2, sweep: f64 },
    /// A circular piece of `radius` m tangent to the track's heading, turning `angle` rad:
    /// positive to the left (counter-clockwise), negative to the right.
    Turn { radius: f64, angle: f64 },
}

/// A `Track`'s default ground: on the right of the way it runs.
fn ground_on_the_right() -> TrackSide {
    TrackSide::Right
}

/// Which side of an arc bodies ride on: `inside` (the concave side: a loop, a bowl, a ring; the
/// solid is outside the circle) or `outside` (the convex side: a hump; the solid is inside).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ArcSide {
    Inside,
    Outside,
}

/// Which side of a polyline, looking along it from its first point, is solid.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TrackSide {
    Left,
    Right,
}

/// One part of a compound shape.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Part {
    pub shape: Shape,
    #[serde(default)]
    pub offset: V2,
    #[serde(default)]
    pub angle: f64,
}

/// A joint between two bodies. Anchors are in each body's frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointDef {
    pub name: String,
    pub kind: JointKind,
    pub body1: String,
    pub body2: String,
    #[serde(default)]
    pub anchor1: V2,
    #[serde(default)]
    pub anchor2: V2,
    /// Slide axis in body1's frame (prismatic, pin_slot).
    #[serde(default = "default_axis")]
    pub axis: V2,
    /// Limits on the joint coordinate: rad (revolute) or m (prismatic).
    #[serde(default)]
    pub limits: Option<(f64, f64)>,
    /// A motor on the joint coordinate (needs `motors`).
    #[serde(default)]
    pub motor: Option<Motor>,
    /// The anchors may start apart, for a scene that tests how the engine snaps a stretched
    /// joint shut; otherwise they must meet at t = 0 (within 0.1 mm) or the level is rejected.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub starts_apart: bool,
}

fn default_axis() -> V2 {
    (1.0, 0.0)
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum JointKind {
    /// A pin: relative rotation free.
    Revolute,
    /// A slider along `axis`, no relative rotation.
    Prismatic,
    /// A weld.
    Fixed,
    /// A pin in a slot (point on a line): slides along `axis` and rotates.
    PinSlot,
}

impl JointKind {
    /// What the docs call it: pin, slider, weld, pin in a slot.
    pub fn describe(self) -> &'static str {
        match self {
            JointKind::Revolute => "pin",
            JointKind::Prismatic => "slider",
            JointKind::Fixed => "weld",
            JointKind::PinSlot => "pin in a slot",
        }
    }
}

/// A joint motor.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Motor {
    /// Drive the joint rate to `target` (rad/s or m/s).
    Velocity {
        target: f64,
        /// Largest torque (N m) or force (N) the motor may deliver.
        #[serde(default)]
        max_force: Option<f64>,
    },
    /// Drive the joint coordinate to `target` with a spring-damper servo.
    Position {
        target: f64,
        stiffness: f64,
        damping: f64,
        #[serde(default)]
        max_force: Option<f64>,
    },
}

/// A ratio constraint holding `sum(ratio_i * q_i)` at its initial value, where each q_i
/// is a body's mass-center x or y (m) or its angle (rad). An inextensible cable over a
/// massless pulley is `y_A + y_B = const`; a cable wound on a drum of radius r is
/// `y_A - r * angle_drum = const`; a gear pair is `r1 * angle_1 + r2 * angle_2 = const`.
/// The constraint is bilateral (a cable here can push as well as pull).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CouplingDef {
    pub name: String,
    /// At least two terms.
    pub terms: Vec<CouplingTerm>,
    /// The body the cable runs over (a pulley), which carries it: the cable is massless, so the
    /// pull it exerts on the bodies of its x and y terms is borne by this body's axle, at its
    /// mass center (Newton's third law through the cable). Without it the cable's pull on the
    /// carrier is not applied (a massless peg on the ground).
    #[serde(default)]
    pub over: Option<String>,
    /// The two angle terms are meshing external gears whose ratios are their pitch radii (m,
    /// the same sign): the tooth force, at the pitch point on the line of centers and across
    /// it, loads both axles.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub gears: bool,
}

/// One term `ratio * q` of a coupling.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CouplingTerm {
    pub body: String,
    pub coordinate: Coordinate,
    /// Dimensionless for x/y terms in a cable; a length (m) for an angle term.
    pub ratio: f64,
}

/// A body coordinate a coupling acts on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Coordinate {
    /// x of the mass center, m.
    X,
    /// y of the mass center, m.
    Y,
    /// The body's angle, rad.
    Angle,
}

/// A linear spring-damper applied as forces by rigidlab (exact Hooke law).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpringDef {
    pub name: String,
    pub body1: String,
    /// Attachment point in body1's frame, m.
    #[serde(default)]
    pub point1: V2,
    /// None: the spring's other end is fixed to the ground at `point2` (world frame).
    #[serde(default)]
    pub body2: Option<String>,
    #[serde(default)]
    pub point2: V2,
    /// Stiffness k, N/m.
    pub stiffness: f64,
    /// Rest (unstretched) length, m.
    pub rest_length: f64,
    /// Viscous damping c, N s/m (needs `damping`).
    #[serde(default)]
    pub damping: f64,
}

/// A torsion spring-damper applied as couples by rigidlab: on body1 the couple
/// -k (theta - theta_rest) - c dtheta/dt, theta = angle1 - angle2 (angle2 = 0 for the ground);
/// body2 gets the opposite. V_e = 1/2 k (theta - theta_rest)^2.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TorsionSpringDef {
    pub name: String,
    pub body1: String,
    /// None: the spring's other end is held by the ground.
    #[serde(default)]
    pub body2: Option<String>,
    /// Stiffness k, N m/rad.
    pub stiffness: f64,
    /// The relative angle theta at which it exerts no couple, rad (None: the one the level
    /// starts with).
    #[serde(default)]
    pub rest_angle: Option<f64>,
    /// Viscous damping c, N m s/rad (needs `damping`).
    #[serde(default)]
    pub damping: f64,
}

/// An applied force and/or torque on a body.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadDef {
    pub name: String,
    pub body: String,
    /// Point of application in the body frame, m (default: the body origin).
    #[serde(default)]
    pub point: V2,
    /// Force in world axes, N.
    #[serde(default)]
    pub force: Option<Profile<V2>>,
    /// Couple, N m, counter-clockwise.
    #[serde(default)]
    pub torque: Option<Profile<f64>>,
    /// The force turns with the body (follower load) instead of keeping its world direction.
    #[serde(default)]
    pub follow_body: bool,
}

/// A value over time: constant, or a table interpolated linearly (held at its ends).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Profile<T> {
    Constant(T),
    /// `[(t, value), ...]` with t in s, strictly increasing.
    Table(Vec<(f64, T)>),
}

/// Something that happens at a given time.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum EventDef {
    /// An impulse at a body point (strike a bar, kick a ball).
    Impulse {
        name: String,
        /// Time, s: applied at the start of the step that contains it.
        at: f64,
        body: String,
        /// Point of application in the body frame, m.
        #[serde(default)]
        point: V2,
        /// Linear impulse, N s, world axes.
        impulse: V2,
        /// Angular impulse (a couple's impulse), N m s.
        #[serde(default)]
        angular: f64,
    },
    /// Weld two bodies together with a fixed joint at their first contact (a bullet
    /// embedding in a block, a plastic impact that sticks). Needs `contacts` and `joints`.
    WeldOnContact {
        name: String,
        body1: String,
        body2: String,
    },
}

impl EventDef {
    pub fn name(&self) -> &str {
        match self {
            EventDef::Impulse { name, .. } | EventDef::WeldOnContact { name, .. } => name,
        }
    }
}
