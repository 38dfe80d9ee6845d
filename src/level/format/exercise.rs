//! The exercise part of a level: checks (theory against engine, every step) and questions
//! (a quantity, when it is read, the expected answer), with the quantities a question can ask.

use super::*;

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
    /// A one-degree-of-freedom mechanism's motor against virtual work (VW-2, VW-5).
    VirtualWork,
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
            CheckKind::VirtualWork => "virtual_work",
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
    /// Typical wrong answers, each with the message a student who gives it reads
    /// (docs/levels.md#mistakes).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub mistakes: Vec<Mistake>,
}

/// A typical wrong answer to a question (forgetting an inertia, I_G where I_O is needed, a
/// sign): a student's answer within the question's `student_tolerance` of `value` (and not
/// right) gets `message`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Mistake {
    /// The wrong answer, in the question's unit (a number or an expression, like `expected`).
    pub value: f64,
    /// What the student reads: what was probably done wrong, not the right answer.
    pub message: String,
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
    /// x of the mass center, m. Analysis: at `Time` or `End`, the reference trajectory
    /// (`analysis::reference`), when the scene fits it.
    X(String),
    /// y of the mass center, m. Analysis as `X`.
    Y(String),
    /// Body angle, rad, continuous (turns add up) from the initial angle. Analysis as `X`.
    Angle(String),
    /// x velocity of the mass center, m/s. Analysis: at an impact or impulse event (`FirstContact`,
    /// `ContactEnds`, `AfterEvent`), the impulse-momentum solution (IM-9/IM-11/IM-12, RM-10);
    /// at `Time` or `End`, the reference trajectory as for `X`.
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
    /// Relative acceleration |a_B - a_A| of two mass centers, m/s^2 (central differences,
    /// RK-10). Analysis: the difference of each body's sum F / m from the engine's free-body
    /// diagram (6/1); a fixed or kinematic body's acceleration is its own central difference.
    RelativeAccel(String, String),
    /// Angular momentum of `body` about the fixed world point `point` (m), kg m^2/s, H_O =
    /// I_G omega + (r_G - O) x m v_G (6/15). Analysis: the angular impulse-momentum ledger about
    /// O (6/17, RM-6), H_O(0) plus the sum of the moments about O of the body's free-body
    /// diagram's impulses over the steps.
    AngularMomentumAbout { body: String, point: V2 },
    /// Direction of the mass-center velocity, rad from +x (atan2). Analysis as `Vx`.
    Direction(String),
    /// Work of gravity on the body since the start, J: engine = the integral of m g . v dt
    /// (trapezoid over steps); analysis = m g . (r_G - r_G0) (path independence, 10.2.18).
    GravityWork(String),
    /// Work done by the named spring's elastic part k x on the bodies since the start, J (the
    /// damper's c dx/dt is not in it: ask `DamperWork`): engine = sum of the held elastic force
    /// (the held tension less its damper part) times its ends' displacements; analysis =
    /// -(1/2 k x^2 - 1/2 k x0^2) (10.2.21).
    SpringWork(String),
    /// Work done by the named spring's damper (c dx/dt) on the bodies since the start, J (zero
    /// without the `damping` effect): engine = sum of the held damper force times its ends'
    /// displacements; analysis = -sum c (dL)^2 / dt over the steps, with dL each step's change
    /// of the spring's length (WE-1 with F = c dL/dt).
    DamperWork(String),
    /// The named spring's tension, N (N m for a torsion spring), positive in tension (pulling
    /// its ends together), centered: k x + c dx/dt as the engine held it. Analysis: k x with the
    /// level's k and the extension at the sample, plus c times the central difference of the
    /// length (Hooke's law with a viscous damper, WE-5).
    SpringForce(String),
    /// Extension of the named spring (length - rest length), m. No analysis.
    SpringExtension(String),
    /// Work of the named load (force and couple) since the start, J: engine = sum of held
    /// force . displacement of its point + couple x turn; analysis = F . (r_P - r_P0) + M (theta -
    /// theta0) when the load is constant (10.3.2), none otherwise.
    LoadWork(String),
    /// Power of the named load at the sample, W (WE-10): P = F . v_P + M omega, with v_P the
    /// velocity of its point of application and the force held over the step. No analysis.
    LoadPower(String),
    /// Work of the friction forces `other` exerts on `body` since the start, J: the friction
    /// force on `body` dotted with the velocity of `body`'s material contact point, summed over
    /// steps (WE-1; `energy::friction_work_on_body`). Engine: each step's friction impulse times
    /// that point's mean velocity, at the solver's lever arm. Analysis: Coulomb's kinetic
    /// friction mu N against the slip, -mu N sgn(slip) v_P . t per step with the level's mu and
    /// the engine's N (WE-6); none when the contact sticks on a moving `other`. On a fixed
    /// `other` this is the pair's loss -mu N s; on two moving bodies it can be positive.
    FrictionWork { body: String, other: String },
    /// The energy friction between two bodies takes out, J (negative): the two bodies' friction
    /// works added, each step's friction impulse times the slip velocity (WE-6). Engine: at the
    /// solver's lever arms and the step's mean velocities; analysis: -mu N |slip| per step.
    FrictionLoss { body: String, other: String },
    /// Mechanical efficiency of a mechanism over the run, 1 (WE-12, energy form): the work done
    /// against the `output` load, -U_output, over the work done by the `input` load or motor
    /// (a load's name, or a motorized joint's), U_input, both since the start. Engine: both works
    /// summed from the held forces and the motor's impulses; analysis, when both are constant
    /// loads: their path-independent works F . (r_P - r_P0) + M (theta - theta0) (10.3.2).
    Efficiency { input: String, output: String },
    /// Period of a body swinging on the named pivot joint, s: engine = mean time between
    /// successive extremes of the body angle of the same kind; analysis = 4 sqrt(I_O/(m g d)) K(sin(theta_0/2))
    /// with I_O, m, d = |OG| and the amplitude theta_0 from the engine's initial state (exact large-amplitude period).
    PendulumPeriod { body: String, joint: String },
    /// Period of a body on springs, s: engine = mean time between successive extremes of its
    /// displacement along its first spring; analysis = 2 pi sqrt(m / sum k) with the engine's m
    /// and each spring's k = 2 V_e / x^2 from the snapshot.
    SpringPeriod(String),
    /// Period of one mode of small oscillation of the mechanism that holds `body`, s; `mode` 0 is
    /// the slowest. Analysis: the eigen-period 2 pi / omega_i of K phi = omega^2 M phi about the
    /// equilibrium (PL-14, `analysis::small_oscillations`; the damped 2 pi / omega_d with
    /// dampers). Engine: the mean time between same-direction zero crossings of the modal rate
    /// eta_i' = phi_i^T M v (per body m dx_G . v_G + I_G dtheta omega, v relative to the
    /// support), which holds mode i alone in the linear motion whatever the start mixes.
    ModePeriod { body: String, mode: usize },
    /// The angle a body swings about (or rests at), rad: engine = the middle of its last whole
    /// swing (the mean of the angle's last two extremes; the angle at the sample when it has
    /// not swung twice and is still); analysis = the equilibrium of its mechanism found by the
    /// linearized method (PL-14), in the frame of a support that may accelerate uniformly
    /// (gravity g - a there: tan(theta) = a / g for a pendulum, VW-4).
    EquilibriumAngle(String),
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
    /// The contact force on `body` from `other` (summed over their contact points, centered),
    /// N, as a [`ContactComponent`] (default: the normal part). Analysis: while the contact
    /// slips, the friction part is Coulomb's mu N with the engine's N (WE-6); otherwise, when
    /// this contact is the only one on `body` and no joint or coupling holds it, the force its
    /// motion needs beyond the known forces, m a_G - (gravity, loads, springs) (6/1).
    ContactForceFrom {
        body: String,
        other: String,
        #[serde(default)]
        component: ContactComponent,
        /// Average over this time window centered on the sample, s (default: the two steps
        /// around it). A body riding a faceted curve gets its normal force at the vertices, in
        /// bursts from step to step.
        #[serde(default)]
        window: f64,
    },
    /// The slip speed at the contact of `body` with `other`: the magnitude of the tangential
    /// velocity of `body`'s contact point relative to `other`'s, m/s (zero while it rolls or
    /// sticks, RK-8). NaN while they do not touch. No analysis.
    SlipSpeed { body: String, other: String },
    /// The polar angle of the mass center about the world point `about`: atan2(y_G - y_O,
    /// x_G - x_O), rad, counter-clockwise from +x, in (-pi, pi]. Where a body leaves a cylinder
    /// centered at O. Analysis: at `Leaves` of a smooth `Circle` from the outside of a fixed
    /// `Arc`, about the arc's centre, the textbook's leaving angle; else none.
    PolarAngle { body: String, about: (f64, f64) },
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
    /// The normal impulse the first contact of `body` with `other` has transmitted, from the
    /// touch to the sample (the whole impact when read at `ContactEnds`), N s. Analysis, when the
    /// contact began as an impact and `body` has no joint: m |v' - v| of `body` from the
    /// impulse-momentum solution (IM-9). With `component` (default `Normal`): the contact's
    /// whole impulse on `body` as a [`ContactComponent`]; the tangential part's analysis is
    /// m (v' - v) . t of the same solution.
    ContactImpulse {
        body: String,
        other: String,
        #[serde(default)]
        component: ContactComponent,
    },
    /// Speed of point `point` of `body` relative to point `of_point` of `of` (points in their
    /// body frames), |v_P - v_Q|, m/s (v_D/B of a connecting rod). Analysis, for two points of one
    /// body: |omega| |r_P/Q| (RK-5), with the engine's omega.
    RelativePointSpeed {
        body: String,
        point: V2,
        of: String,
        of_point: V2,
    },
    /// Distance from the pin of `joint` to the center of percussion of `body` (a body turning
    /// about that pin), m: q = k_O^2 / r_bar = (I_G + m r_bar^2) / (m r_bar) (CP-1). Engine: with
    /// rapier's m and I_G and the engine's pin and G; analysis: with the shape formula's.
    PercussionDistance { body: String, joint: String },
    /// Kinetic energy of a group of bodies, sum of 1/2 m v^2 + 1/2 I w^2, J (a bar with the
    /// bullet welded into it). Analysis at impacts and blows: the impulse-momentum solution's.
    GroupKineticEnergy(Vec<String>),
    /// Magnitude of the linear momentum of a group of bodies, |sum m v_G|, N s (6/12). Analysis
    /// at impacts and blows: the impulse-momentum solution's.
    GroupMomentum(Vec<String>),
}

impl Quantity {
    /// The quantity's SI unit, as docs/levels.md's table of quantities gives it: a question's
    /// `unit` must parse (`level::units`) to a unit of this size and dimension (validation;
    /// `1/s` passes for rad/s, `J` for N m). Levels are in SI, and a question's `expected` is
    /// compared with the engine's SI values as it is. Two depend on what they name in `level`:
    /// a motor's `MotorTorque` is N m on a pin and N on a slider, and a torsion spring's
    /// `SpringExtension` is rad.
    pub fn si_unit(&self, level: &Level) -> &'static str {
        use Quantity as Q;
        match self {
            Q::X(_)
            | Q::Y(_)
            | Q::Distance(_)
            | Q::PointX { .. }
            | Q::PointY { .. }
            | Q::RelativeDistance(..)
            | Q::ReboundHeight { .. }
            | Q::PercussionDistance { .. } => "m",
            Q::SpringExtension(s) => {
                if level.torsion_springs.iter().any(|t| t.name == *s) {
                    "rad"
                } else {
                    "m"
                }
            }
            Q::Angle(_) | Q::Direction(_) | Q::RelativeAngle(..) | Q::PolarAngle { .. } => "rad",
            Q::Vx(_)
            | Q::Vy(_)
            | Q::Speed(_)
            | Q::PointSpeed { .. }
            | Q::RelativeSpeed(..)
            | Q::RelativePointSpeed { .. }
            | Q::SlipSpeed { .. }
            | Q::PinSpeed { .. } => "m/s",
            Q::Omega(_) | Q::LinkOmega { .. } => "rad/s",
            Q::Ax(_)
            | Q::Ay(_)
            | Q::Accel(_)
            | Q::PointAccel { .. }
            | Q::RelativeAccel(..)
            | Q::RollingAcceleration { .. } => "m/s^2",
            Q::Alpha(_) => "rad/s^2",
            Q::Time | Q::PendulumPeriod { .. } | Q::SpringPeriod(_) | Q::ModePeriod { .. } => "s",
            Q::EquilibriumAngle(_) => "rad",
            Q::JointForce(_)
            | Q::ContactForce(_)
            | Q::ContactNormalForce { .. }
            | Q::ContactForceFrom { .. }
            | Q::CouplingForce(_)
            | Q::JointReaction { .. }
            | Q::RollingFriction { .. } => "N",
            Q::SpringForce(s) => {
                if level.torsion_springs.iter().any(|t| t.name == *s) {
                    "N m"
                } else {
                    "N"
                }
            }
            Q::AngularMomentumAbout { .. } => "kg m^2/s",
            Q::JointImpulse { .. } | Q::ContactImpulse { .. } | Q::GroupMomentum(_) => "N s",
            Q::MotorTorque { joint, .. } => {
                let slider = level
                    .joints
                    .iter()
                    .any(|j| j.name == *joint && j.kind == JointKind::Prismatic);
                if slider {
                    "N"
                } else {
                    "N m"
                }
            }
            Q::KineticEnergy(_)
            | Q::GravityWork(_)
            | Q::SpringWork(_)
            | Q::LoadWork(_)
            | Q::FrictionWork { .. }
            | Q::FrictionLoss { .. }
            | Q::DamperWork(_)
            | Q::EnergyLost { .. }
            | Q::GroupKineticEnergy(_) => "J",
            Q::LoadPower(_) => "W",
            Q::RollingFrictionNeeded { .. } | Q::Restitution { .. } | Q::Efficiency { .. } => "1",
        }
    }

    /// The variant's name, for messages: `Omega`, `JointReaction`.
    pub fn variant_name(&self) -> String {
        let debug = format!("{self:?}");
        debug
            .split(|c: char| !c.is_alphanumeric())
            .next()
            .unwrap_or_default()
            .to_string()
    }
}

/// The family a quantity belongs to: the file of `src/questions/` that reads it, so that adding
/// a quantity touches this file (the variant, its doc, its unit and its family),
/// `validate/exercise.rs` and one family file; `questions/dispatch.rs` routes by family and
/// changes only for a new family.
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
            | Q::RelativeAngle(..)
            | Q::RelativeAccel(..)
            | Q::AngularMomentumAbout { .. }
            | Q::RelativePointSpeed { .. }
            | Q::PolarAngle { .. }
            | Q::SlipSpeed { .. } => F::Motion,
            Q::JointForce(_)
            | Q::ContactForce(_)
            | Q::ContactNormalForce { .. }
            | Q::ContactForceFrom { .. }
            | Q::CouplingForce(_)
            | Q::SpringForce(_)
            | Q::JointReaction { .. }
            | Q::JointImpulse { .. }
            | Q::MotorTorque { .. } => F::Forces,
            Q::KineticEnergy(_)
            | Q::GravityWork(_)
            | Q::SpringWork(_)
            | Q::SpringExtension(_)
            | Q::LoadWork(_)
            | Q::LoadPower(_)
            | Q::FrictionWork { .. }
            | Q::FrictionLoss { .. }
            | Q::DamperWork(_)
            | Q::Efficiency { .. }
            | Q::GroupKineticEnergy(_)
            | Q::GroupMomentum(_) => F::WorkAndPower,
            Q::PendulumPeriod { .. }
            | Q::SpringPeriod(_)
            | Q::ModePeriod { .. }
            | Q::EquilibriumAngle(_) => F::Periods,
            Q::RollingAcceleration { .. }
            | Q::RollingFriction { .. }
            | Q::RollingFrictionNeeded { .. } => F::Rolling,
            Q::ReboundHeight { .. }
            | Q::Restitution { .. }
            | Q::EnergyLost { .. }
            | Q::ContactImpulse { .. } => F::Impacts,
            Q::LinkOmega { .. } | Q::PinSpeed { .. } | Q::PercussionDistance { .. } => F::Linkages,
        }
    }

    /// The time window the quantity is averaged over, s (0: the two steps around the sample).
    pub fn averaging_window(&self) -> f64 {
        match self {
            Quantity::JointReaction { window, .. }
            | Quantity::MotorTorque { window, .. }
            | Quantity::ContactForceFrom { window, .. } => *window,
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

/// A component of a contact's force or impulse on a body, in the contact's frame: n is the
/// contact normal pointing from the other body into this one, t = k x n (n turned a quarter
/// turn counterclockwise).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum ContactComponent {
    /// Along n: the push, positive.
    #[default]
    Normal,
    /// Along t, signed: the friction part.
    Tangential,
    /// The magnitude of the tangential part: "the friction force".
    Friction,
    /// The world x component.
    X,
    /// The world y component.
    Y,
    /// The magnitude of the whole force or impulse.
    Magnitude,
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
    /// The instant the quantity `of` is largest, at or after `after` s: the vertex of the parabola
    /// through the three samples around its largest sample (the time of the highest point, the
    /// speed at the greatest compression). With `Time`, the time of that instant.
    MaxOf {
        of: Quantity,
        #[serde(default)]
        after: f64,
    },
    /// The instant the quantity `of` is smallest, at or after `after` s (as `MaxOf`).
    MinOf {
        of: Quantity,
        #[serde(default)]
        after: f64,
    },
    /// The instant `body` stops slipping on `other`, at or after `after` s: it starts rolling or
    /// sticking. Found where the slip falls below 2% of its largest value so far, and placed
    /// where the slip's straight-line fall over the step before reaches zero.
    SlipEnds {
        body: String,
        other: String,
        #[serde(default)]
        after: f64,
    },
    /// The instant `body` starts to slide on `other`, at or after `after` s: impending slip,
    /// where the friction the contact takes reaches mu N (Coulomb's limit), placed where the
    /// ratio F/N's straight-line rise over the two steps before reaches mu.
    SlipStarts {
        body: String,
        other: String,
        #[serde(default)]
        after: f64,
    },
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
    /// The instant `body` leaves `other` (at or after `after` s), by the body's path: where the
    /// gap between the two surfaces (for an `Arc`, its true circle, not its facets) starts
    /// growing for good, placed where the gap's acceleration, rising in a straight line after
    /// the surfaces part, reaches zero (between steps). `body` is a `Circle`, `other` an `Arc`
    /// on a fixed body or a `Circle`. A smooth `Circle` leaving the outside of a fixed `Arc`
    /// under gravity alone has the textbook's analysis (`PolarAngle` about the arc's centre,
    /// `Speed`, `Time`: docs/levels.md).
    Leaves {
        body: String,
        other: String,
        #[serde(default)]
        after: f64,
    },
    /// The end of the step in which the named impulse event acted: the state just after the blow.
    AfterEvent(String),
    /// The end of the first step, when the joints first act: bodies whose initial velocities break a
    /// joint are caught by it impulsively (a plate whose corner is caught by a pivot). Velocity
    /// analyses use the impulse-momentum solution from the initial state, as for `AfterEvent`.
    FirstStep,
}
