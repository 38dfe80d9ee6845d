//! The level file format: one exercise per RON file, SI units.
//!
//! Every struct rejects unknown fields. The reference with every field, its
//! unit and its default is `docs/levels.md`; keep the two in step.

use serde::{Deserialize, Serialize};

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
    /// Ratio constraints: pulleys, cables on drums, gears, racks (need `joints`).
    #[serde(default)]
    pub couplings: Vec<CouplingDef>,
    #[serde(default)]
    pub loads: Vec<LoadDef>,
    #[serde(default)]
    pub events: Vec<EventDef>,
    /// Theory-against-engine checks evaluated every step.
    #[serde(default)]
    pub checks: Vec<CheckDef>,
    /// The exercise's questions with their expected answers.
    #[serde(default)]
    pub questions: Vec<QuestionDef>,
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
    /// rapier's `num_internal_pgs_iterations`: solver sweeps per substep.
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
    Compound {
        parts: Vec<Part>,
    },
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

/// A theory-against-engine check run every step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CheckDef {
    pub kind: CheckKind,
    /// The body (or joint, or contact partner) the check is about; None = the whole scene.
    #[serde(default)]
    pub body: Option<String>,
    /// A second body where the check needs one (a contact partner, a fixed pivot body).
    #[serde(default)]
    pub other: Option<String>,
    /// A point, world frame, where the check needs one (fixed point O), m.
    #[serde(default)]
    pub point: Option<V2>,
    /// A time window [t1, t2], s: `impulse_momentum` checks every window inside it
    /// (default: the whole run).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub window: Option<(f64, f64)>,
    /// Relative tolerance on the maximum error (of the scale the check reports).
    pub tolerance: f64,
    /// Why this tolerance: the engine limitation or the discretization error it covers.
    #[serde(default)]
    pub why: String,
}

/// The kinds of check (the report uses these names).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CheckKind {
    /// Mass, centroid and I_G from the shape's formula against rapier's mass properties.
    MassProperties,
    /// Closed-form trajectory of a body under constant force (free fall, projectile).
    ConstantAcceleration,
    KineticEnergyG,
    KineticEnergyIc,
    AngularMomentumFixedPoint,
    CenterOfPercussion,
    NewtonEuler,
    WorkEnergy,
    ImpulseMomentum,
    Restitution,
}

impl CheckKind {
    /// The kind's name as a level file and the report write it.
    pub fn name(self) -> &'static str {
        match self {
            CheckKind::MassProperties => "mass_properties",
            CheckKind::ConstantAcceleration => "constant_acceleration",
            CheckKind::KineticEnergyG => "kinetic_energy_g",
            CheckKind::KineticEnergyIc => "kinetic_energy_ic",
            CheckKind::AngularMomentumFixedPoint => "angular_momentum_fixed_point",
            CheckKind::CenterOfPercussion => "center_of_percussion",
            CheckKind::NewtonEuler => "newton_euler",
            CheckKind::WorkEnergy => "work_energy",
            CheckKind::ImpulseMomentum => "impulse_momentum",
            CheckKind::Restitution => "restitution",
        }
    }
}

/// A question of the exercise, with its expected answer.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct QuestionDef {
    pub id: String,
    /// The question in words.
    pub ask: String,
    pub unit: String,
    /// The textbook answer (recomputed where the printed one is wrong).
    pub expected: f64,
    /// Relative tolerance on the engine's and the analysis layer's values.
    pub tolerance: f64,
    /// Relative tolerance a student's answer is graded with (default 0.01: three significant figures).
    #[serde(default = "default_student_tolerance")]
    pub student_tolerance: f64,
    /// What is measured.
    pub quantity: Quantity,
    /// When it is measured.
    #[serde(default)]
    pub at: When,
    /// Why the tolerance is what it is.
    #[serde(default)]
    pub why: String,
}

fn default_student_tolerance() -> f64 {
    0.01
}

/// A measurable quantity of one body, joint, spring, load or contact pair.
///
/// Every question is read twice (see `questions`): `engine` is what the engine did
/// (read from its motion and reactions), `analysis` is the textbook formula named below applied
/// to the engine's state (its mass properties, pose and pre-event velocities), or none where the
/// quantity has no independent formula. "Centered" forces are the mean of the two steps around
/// the sample; accelerations are central finite differences of the velocities.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Quantity {
    /// x of the mass center, m.
    X(String),
    /// y of the mass center, m.
    Y(String),
    /// Body angle, rad, continuous (turns add up) from the initial angle.
    Angle(String),
    /// x velocity of the mass center, m/s. Analysis: at an impact or impulse event (`FirstContact`,
    /// `ContactEnds`, `AfterEvent`), the impulse-momentum solution (IM-9/IM-11/IM-12, RM-10).
    Vx(String),
    /// y velocity of the mass center, m/s. Analysis as `Vx`.
    Vy(String),
    /// Speed of the mass center, m/s. Analysis as `Vx`.
    Speed(String),
    /// Angular velocity, rad/s. Analysis as `Vx`.
    Omega(String),
    /// Kinetic energy 1/2 m v^2 + 1/2 I w^2, J (6/9). Analysis: work-energy (RE-7)
    /// T0 + work of gravity, of the body's springs, loads and impulse events along the engine's path,
    /// i.e. assuming the body's joints and contacts do no work; given at configuration events
    /// (crossings, angles, extremes: not at `Time` or `End`, where the engine's configuration itself
    /// carries its integration error); at impacts and blows, the impulse-momentum solution's T.
    KineticEnergy(String),
    /// Magnitude of the joint reaction force (mean over the step), N.
    JointForce(String),
    /// Magnitude of the total contact force on a body from all contacts (mean over the step), N.
    ContactForce(String),
    /// Distance travelled by the mass center, m.
    Distance(String),

    /// The time of the `at` event, s (interpolated between steps for crossings). Needs an event
    /// `at` (not `Max`/`Min`). No analysis.
    Time,
    /// x acceleration of the mass center, m/s^2 (central difference). Analysis: sum F / m
    /// from the engine's free-body diagram (6/1).
    Ax(String),
    /// y acceleration of the mass center, m/s^2. Analysis as `Ax`.
    Ay(String),
    /// Magnitude of the mass-center acceleration, m/s^2. Analysis as `Ax`.
    Accel(String),
    /// Angular acceleration, rad/s^2 (central difference). Analysis: sum M_G / I_G (6/1).
    Alpha(String),
    /// x of a body point given in the body frame (m), world frame, m.
    PointX { body: String, point: V2 },
    /// y of a body point given in the body frame (m), world frame, m (a ladder's top).
    PointY { body: String, point: V2 },
    /// Speed of a body point given in the body frame (m), m/s: |v_G + omega k x r| (RK-6).
    /// Analysis as `Vx` (at impacts and blows).
    PointSpeed { body: String, point: V2 },
    /// Acceleration magnitude of a body point given in the body frame (m), m/s^2: engine = central
    /// difference of that material point's velocity; analysis = a_G + alpha k x r - omega^2 r (RK-10)
    /// with a_G and alpha from Newton-Euler on the engine's forces (6/1) and the engine's omega.
    PointAccel { body: String, point: V2 },
    /// The impulse of the named coupling (cable, pulley, gear) over the step divided by dt (centered):
    /// for unit ratios, the cable's tension, N (each term received `ratio` times it). No analysis.
    CouplingForce(String),
    /// Distance between two bodies' mass centers |r_B - r_A|, m.
    RelativeDistance(String, String),
    /// Relative speed |v_B - v_A| of two mass centers, m/s.
    RelativeSpeed(String, String),
    /// Angle of the second body minus that of the first, rad (continuous).
    RelativeAngle(String, String),
    /// Direction of the mass-center velocity, rad from +x (atan2). Analysis as `Vx`.
    Direction(String),
    /// Work of gravity on the body since the start, J: engine = the integral of m g . v dt
    /// (trapezoid over steps); analysis = m g . (r_G - r_G0) (path independence, 10.2.18).
    GravityWork(String),
    /// Work done by the named spring on the bodies since the start, J: engine = sum of the held
    /// spring force times its ends' displacements; analysis = -(1/2 k x^2 - 1/2 k x0^2) (10.2.21).
    SpringWork(String),
    /// Extension of the named spring (length - rest length), m. No analysis.
    SpringExtension(String),
    /// Work of the named load (force and couple) since the start, J: engine = sum of held
    /// force . displacement of its point + couple x turn; analysis = F . (r_P - r_P0) + M (theta -
    /// theta0) when the load is constant (10.3.2), none otherwise.
    LoadWork(String),
    /// Power of the named load at the sample, W (WE-10): P = F . v_P + M omega, with v_P the
    /// velocity of its point of application and the force held over the step. No analysis.
    LoadPower(String),
    /// Work of the friction forces between two bodies on `body` since the start, J: engine =
    /// sum of friction impulse . velocity of the body's contact point; analysis = -mu N s: the
    /// Coulomb law with the level's mu, the engine's normal force and slip (WE-6).
    FrictionWork { body: String, other: String },
    /// Period of a body swinging on the named pivot joint, s: engine = mean time between
    /// successive extremes of the body angle of the same kind; analysis = 4 sqrt(I_O/(m g d)) K(sin(theta_0/2))
    /// with I_O, m, d = |OG| and the amplitude theta_0 from the engine's initial state (exact large-amplitude period).
    PendulumPeriod { body: String, joint: String },
    /// Period of a body on springs, s: engine = mean time between successive extremes of its
    /// displacement along its first spring; analysis = 2 pi sqrt(m / sum k) with the engine's m
    /// and each spring's k = 2 V_e / x^2 from the snapshot.
    SpringPeriod(String),
    /// Acceleration of the mass center of a body rolling on `ground`, m/s^2 (downhill component,
    /// central difference): analysis = g sin(theta) / (1 + k_G^2 / r^2) with theta from the engine's
    /// contact normal, r = |G - contact point| and k_G^2 = I_G / m (RK-8 with 6/1).
    RollingAcceleration { body: String, ground: String },
    /// Friction force a rolling body needs from `ground`, N (centered): analysis =
    /// m g sin(theta) k_G^2 / (k_G^2 + r^2).
    RollingFriction { body: String, ground: String },
    /// Friction-to-normal force ratio F/N at the rolling contact (the least mu for rolling):
    /// analysis = tan(theta) k_G^2 / (k_G^2 + r^2).
    RollingFrictionNeeded { body: String, ground: String },
    /// Angular velocity of a link, rad/s: engine = the link's omega; analysis = the instantaneous
    /// center (RK-11) found from the velocities the neighbouring bodies give the pins `known` and
    /// `other` (two joints on the link); omega = |v_known| / |known - C| with its sign.
    LinkOmega {
        link: String,
        known: String,
        other: String,
    },
    /// Speed of the pin of joint `pin` as a point of `link`, m/s: engine = |v_G + omega k x r|;
    /// analysis = |omega_C| |pin - C| with C from `known` and `other` as in `LinkOmega`.
    PinSpeed {
        link: String,
        known: String,
        other: String,
        pin: String,
    },
    /// Reaction force of a joint on its moving body, N (centered mean over the step), as a
    /// component. Analysis, when one body is fixed and the other turns about the pin with no other
    /// joint or contact (fixed-axis rotation, PL-8/PL-12): R = m a_G - sum F with
    /// alpha = sum M_O / I_O and a_G = alpha k x r_{G/O} - omega^2 r_{G/O} from the engine's omega.
    JointReaction {
        joint: String,
        #[serde(default)]
        component: Component,
        /// Average over this time window centered on the sample, s (default: the two steps around
        /// it). rapier's reactions in a closed chain of soft joints fluctuate from step to step.
        #[serde(default)]
        window: f64,
    },
    /// Reaction impulse of a joint on its moving body over the step that ends at the sample, N s
    /// (with `AfterEvent`: the impulse through the pin during the blow). Analysis at `AfterEvent`:
    /// the pin impulse of the impulse-momentum solution (RM-10, CP-3).
    JointImpulse {
        joint: String,
        #[serde(default)]
        component: Component,
    },
    /// Normal force between two bodies (sum over contact points, centered), N. No analysis.
    ContactNormalForce { body: String, other: String },
    /// Torque (pin) or force (slider) the joint's motor applies to body2, N m or N (centered, or
    /// averaged over `window` s). Analysis: the one-degree-of-freedom power balance (RE-11):
    /// M omega_rel = sum (m a_G . v_G + I_G alpha omega) - power of gravity, loads and springs,
    /// over the dynamic bodies.
    MotorTorque {
        joint: String,
        #[serde(default)]
        window: f64,
    },
    /// Apex height of the mass center after the first contact of `body` with `other` ends
    /// (until the next contact), m. Analysis: the apex of free flight, y_c + v'^2 / (2 g), from
    /// the impact solution (IM-13).
    ReboundHeight { body: String, other: String },
    /// Coefficient of restitution measured across the first contact of the pair:
    /// e = -(v_rel' . n)/(v_rel . n) with the engine's velocities brought to the contact instant.
    /// Analysis: the coefficient the level declares for the pair (the textbook input, IM-9).
    Restitution { body: String, other: String },
    /// Mechanical energy (T + V_g) the pair loses across its first contact, J. Analysis: the
    /// kinetic-energy loss of the impulse-momentum solution (IM-14).
    EnergyLost { body: String, other: String },
}

/// The family a quantity belongs to: the file of `src/questions/` that reads it, so that adding
/// a quantity touches this file (the variant, its doc and its family), `validate.rs` and one
/// family file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum QuantityFamily {
    /// Positions, velocities and accelerations of bodies and body points, distance, time.
    Motion,
    /// Joint, contact, coupling and motor forces and impulses.
    Forces,
    /// Kinetic energy, works, power, and the springs' extension.
    WorkAndPower,
    /// Periods of pendulums and of masses on springs.
    Periods,
    /// A round body rolling on the ground.
    Rolling,
    /// What happens across a pair's first contact: rebound, restitution, energy lost.
    Impacts,
    /// Linkages read through the instantaneous center.
    Linkages,
}

impl Quantity {
    /// The family that reads this quantity (see [`QuantityFamily`]).
    pub fn family(&self) -> QuantityFamily {
        use Quantity as Q;
        use QuantityFamily as F;
        match self {
            Q::X(_)
            | Q::Y(_)
            | Q::Angle(_)
            | Q::Vx(_)
            | Q::Vy(_)
            | Q::Speed(_)
            | Q::Omega(_)
            | Q::Direction(_)
            | Q::Distance(_)
            | Q::Time
            | Q::Ax(_)
            | Q::Ay(_)
            | Q::Accel(_)
            | Q::Alpha(_)
            | Q::PointX { .. }
            | Q::PointY { .. }
            | Q::PointSpeed { .. }
            | Q::PointAccel { .. }
            | Q::RelativeDistance(..)
            | Q::RelativeSpeed(..)
            | Q::RelativeAngle(..) => F::Motion,
            Q::JointForce(_)
            | Q::ContactForce(_)
            | Q::ContactNormalForce { .. }
            | Q::CouplingForce(_)
            | Q::JointReaction { .. }
            | Q::JointImpulse { .. }
            | Q::MotorTorque { .. } => F::Forces,
            Q::KineticEnergy(_)
            | Q::GravityWork(_)
            | Q::SpringWork(_)
            | Q::SpringExtension(_)
            | Q::LoadWork(_)
            | Q::LoadPower(_)
            | Q::FrictionWork { .. } => F::WorkAndPower,
            Q::PendulumPeriod { .. } | Q::SpringPeriod(_) => F::Periods,
            Q::RollingAcceleration { .. }
            | Q::RollingFriction { .. }
            | Q::RollingFrictionNeeded { .. } => F::Rolling,
            Q::ReboundHeight { .. } | Q::Restitution { .. } | Q::EnergyLost { .. } => F::Impacts,
            Q::LinkOmega { .. } | Q::PinSpeed { .. } => F::Linkages,
        }
    }

    /// The time window the quantity is averaged over, s (0: the two steps around the sample).
    pub fn averaging_window(&self) -> f64 {
        match self {
            Quantity::JointReaction { window, .. } | Quantity::MotorTorque { window, .. } => {
                *window
            }
            _ => 0.0,
        }
    }
}

/// A component of a vector quantity.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum Component {
    /// The magnitude.
    #[default]
    Magnitude,
    /// The world x component.
    X,
    /// The world y component.
    Y,
    /// Along n, from the moving body's G toward the joint anchor (centripetal), signed.
    Normal,
    /// Along k x (G - anchor): the direction G moves for positive omega, signed.
    Tangential,
}

/// When a question's quantity is read.
///
/// Crossings are interpolated linearly between the two steps that bracket them (both the
/// quantity and the time); contact events read the nearest step on the stated side.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum When {
    /// At the end of the run.
    #[default]
    End,
    /// At this time, s (interpolated between the two steps around it).
    Time(f64),
    /// The largest value over the run (optionally from a time on).
    Max(#[serde(default)] f64),
    /// The smallest value over the run (optionally from a time on).
    Min(#[serde(default)] f64),
    /// The first time the body's (continuous) angle crosses `angle`, rad.
    Angle { body: String, angle: f64 },
    /// The first time the quantity `of` crosses `value` at or after `after` s.
    Crossing {
        of: Quantity,
        value: f64,
        #[serde(default)]
        after: f64,
    },
    /// The last step before `body` first touches `other` (any body when omitted): the
    /// pre-impact state. Velocity analyses use the state carried on to the contact instant.
    FirstContact {
        body: String,
        #[serde(default)]
        other: Option<String>,
    },
    /// The first step after the first contact of `body` with `other` (any body when omitted)
    /// stops pushing (and stays quiet for 0.05 s): the post-impact state, or the moment a body
    /// leaves a wall. Velocity analyses give the impact solution at the touching instant.
    ContactEnds {
        body: String,
        #[serde(default)]
        other: Option<String>,
    },
    /// The end of the step in which the named impulse event acted: the state just after the blow.
    AfterEvent(String),
    /// The end of the first step, when the joints first act: bodies whose initial velocities break a
    /// joint are caught by it impulsively (a plate whose corner is caught by a pivot). Velocity
    /// analyses use the impulse-momentum solution from the initial state, as for `AfterEvent`.
    FirstStep,
}
