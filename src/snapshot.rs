//! The per-step snapshot: plain f64 data, no rapier or Bevy types.
//!
//! This is the contract between the simulation (which fills it from the engine
//! after every physics step) and the analysis layer (pure functions over it).
//!
//! Conventions (textbook, see `textbook/concepts.md` "Notation"):
//! - the plane is x-y, k = +z out of the screen; angles, omega, alpha, torques
//!   and angular impulses are scalars, positive counter-clockwise;
//! - every impulse is the impulse over the **whole step** `[time - dt, time]`
//!   (rapier's contact impulses already are; joint impulses are converted, see
//!   `sim::joints`); the matching mean force is `impulse / dt`;
//! - "on body k" means the impulse/force acting on that body.

use glam::DVec2;
use serde::{Deserialize, Serialize};

/// The state of the scene right after a physics step (or at t = 0).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Snapshot {
    /// Number of steps taken so far (0 = initial state).
    pub step: u64,
    /// Simulated time at the end of this step, s.
    pub time: f64,
    /// Length of the step that led here, s (0 for the initial state).
    pub dt: f64,
    /// Substeps of that step (the run's resolved `Settings::substeps`, also on the initial
    /// state): where gravity acts within a step and how positions map to velocities depend on it.
    #[serde(default = "one")]
    pub substeps: usize,
    /// The engine's floating-point precision (rapier2d or rapier2d-f64): how finely its
    /// velocities and impulses are resolved.
    #[serde(default = "f32_precision")]
    pub precision: Precision,
    /// World gravity acceleration in effect, m/s^2 (zero if not declared).
    pub gravity: DVec2,
    pub bodies: Vec<BodyState>,
    pub contacts: Vec<ContactState>,
    pub joints: Vec<JointState>,
    pub springs: Vec<SpringState>,
    /// Ratio constraints (pulleys, cables, gears) and the impulse each applied over the step.
    pub couplings: Vec<CouplingState>,
    /// Applied loads (forces, torques) held during the step that led here.
    pub loads: Vec<LoadState>,
    /// Impulses applied by events at the start of the step that led here.
    pub impulses: Vec<ImpulseState>,
}

impl Snapshot {
    /// The state before any step (t = 0).
    pub fn is_initial(&self) -> bool {
        self.step == 0
    }
}

fn one() -> usize {
    1
}

fn f32_precision() -> Precision {
    Precision::F32
}

pub use crate::level::{BodyKind, Coordinate, Precision};

/// One rigid body.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BodyState {
    pub name: String,
    pub kind: BodyKind,
    /// Position of the body frame's origin, m.
    pub position: DVec2,
    /// Rotation of the body frame, rad, CCW; continuous (not wrapped to +-pi) so turns add up.
    pub angle: f64,
    /// Mass center G in world coordinates, m.
    pub com: DVec2,
    /// Velocity of the mass center v_G, m/s.
    pub velocity: DVec2,
    /// Angular velocity omega, rad/s, CCW.
    pub omega: f64,
    /// Mass m, kg (infinite mass bodies report 0).
    pub mass: f64,
    /// Centroidal moment of inertia I_G about the z axis, kg m^2 (0 if rotation is locked or fixed).
    pub inertia: f64,
    /// Mass center in the body frame, m.
    pub local_com: DVec2,
}

impl BodyState {
    /// World position of a point given in the body frame.
    pub fn world_point(&self, local: DVec2) -> DVec2 {
        self.position + DVec2::from_angle(self.angle).rotate(local)
    }
}

/// A contact pair between two bodies, with every point the solver used.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ContactState {
    /// Index into `Snapshot::bodies` of the first body.
    pub body1: usize,
    pub body2: usize,
    /// Unit normal, pointing from body1 to body2.
    pub normal: DVec2,
    pub points: Vec<ContactPoint>,
}

/// One contact point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ContactPoint {
    /// World position of the contact point (on body1's surface), m.
    pub point: DVec2,
    /// Separation distance (negative = penetration), m.
    pub distance: f64,
    /// Normal impulse over the step, N s (>= 0). Acts on body2 along +normal and on body1 along -normal.
    pub normal_impulse: f64,
    /// Friction impulse over the step along the tangent `(-n.y, n.x)`, N s, acting on body2 (body1 gets the opposite).
    pub tangent_impulse: f64,
    /// The lever arms (from body1's and from body2's mass center, world axes, m) at which the
    /// solver applied this point's impulses over the step: rapier's `solver_dp1/2`, taken at the
    /// midpoint of the two surface points and frozen at the manifold's last full narrow-phase
    /// update while rapier recycles it. Only meaningful on a side with mass. None when not known
    /// (a hand-built snapshot): the analysis then takes the point at the start of the step.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub arms: Option<(DVec2, DVec2)>,
    /// Inside a step only (None in every snapshot): the touching material points in body1's and
    /// body2's frames, with which the simulation places a contact read in an earlier rapier call
    /// of the step at the poses the step ends with.
    #[serde(skip)]
    pub local: Option<(DVec2, DVec2)>,
}

impl ContactState {
    /// Whether the contact pushed over the step (a point with a positive normal impulse): a
    /// body it touches is held by it, not flying free.
    pub fn pushes(&self) -> bool {
        self.points.iter().any(|p| p.normal_impulse > 0.0)
    }

    /// The tangent direction the friction impulse is measured along.
    pub fn tangent(&self) -> DVec2 {
        self.normal.perp()
    }

    /// Total impulse on body2 (normal + friction) over the step, N s.
    pub fn impulse_on_body2(&self) -> DVec2 {
        let t = self.tangent();
        self.points
            .iter()
            .map(|p| self.normal * p.normal_impulse + t * p.tangent_impulse)
            .sum()
    }
}

/// A joint's reaction over the step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JointState {
    pub name: String,
    pub body1: usize,
    pub body2: usize,
    /// World position of the joint anchor on body2, m.
    pub anchor: DVec2,
    /// World position of the joint anchor on body1, m (differs from `anchor` by the joint error).
    pub anchor1: DVec2,
    /// Reaction impulse on body2 over the step (world axes), N s. Body1 gets the opposite.
    pub impulse_on_body2: DVec2,
    /// Reaction angular impulse on body2 about its mass center over the step, N m s
    /// (includes the moment of the linear impulse about G2 and any constraint couple).
    pub angular_impulse_on_body2: f64,
    /// Reaction angular impulse on body1 about its mass center over the step, N m s.
    pub angular_impulse_on_body1: f64,
    /// The constraint couple on body2 (fixed joints, sliders), N m s over the step.
    pub couple_on_body2: f64,
    /// Impulse delivered by the joint motor to body2 over the step (N s for a slider, N m s for a pin).
    pub motor_impulse: f64,
    /// Impulse delivered by the joint limit to body2 over the step.
    pub limit_impulse: f64,
    /// Joint coordinate: relative angle (pin) or slide distance (slider).
    pub coordinate: f64,
}

/// A ratio constraint `sum(ratio_i * q_i) = const` and its reaction over the step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CouplingState {
    pub name: String,
    /// (body index, coordinate, ratio) per term.
    pub terms: Vec<(usize, Coordinate, f64)>,
    /// The generalized impulse lambda over the step: term i received `ratio_i * lambda`
    /// (N s along x/y, or N m s about its mass center for an angle term). For a cable with
    /// unit ratios, lambda / dt is the cable tension.
    pub impulse: f64,
    /// Current value of the sum, and its drift from the initial value (m or rad).
    pub value: f64,
    pub drift: f64,
    /// The bodies that carry the coupling and the impulse (N s) each received at its mass
    /// center over the step, delivered one rapier call late (see `sim/couplings.rs`): the pulley
    /// a cable runs over (`CouplingDef::over`) bears the cable's pull on the x and y terms;
    /// meshing gears (`gears`) bear the tooth force on their axles.
    #[serde(default)]
    pub carriers: Vec<(usize, DVec2)>,
}

impl CouplingState {
    /// Every impulse the coupling gave over the step: (body, impulse at the mass center (N s),
    /// couple (N m s)), its terms' first (term i received `ratio_i * impulse`), then the carriers'.
    pub fn body_impulses(&self) -> impl Iterator<Item = (usize, DVec2, f64)> + '_ {
        let terms = self.terms.iter().map(|&(body, coordinate, ratio)| {
            let x = ratio * self.impulse;
            match coordinate {
                Coordinate::X => (body, DVec2::new(x, 0.0), 0.0),
                Coordinate::Y => (body, DVec2::new(0.0, x), 0.0),
                Coordinate::Angle => (body, DVec2::ZERO, x),
            }
        });
        terms.chain(self.carriers.iter().map(|&(body, j)| (body, j, 0.0)))
    }
}

/// A linear spring applied by rigidlab (exact Hooke force).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SpringState {
    pub name: String,
    pub body1: usize,
    /// None when the spring is anchored to the ground.
    pub body2: Option<usize>,
    pub point1: DVec2,
    pub point2: DVec2,
    /// Current length, m.
    pub length: f64,
    /// Extension x = length - rest length, m.
    pub extension: f64,
    /// Tension (positive pulls the ends together), N, held during the step that led here.
    pub tension: f64,
    /// Elastic potential energy V_e = 1/2 k x^2 at the current length, J.
    pub energy: f64,
    /// Force on body1 held during the step that led here, N (body2 gets the opposite).
    pub force_on_body1: DVec2,
    /// Where the force acted on body1 / body2 during the step (start-of-step positions), m.
    pub applied_at1: DVec2,
    pub applied_at2: DVec2,
    /// A torsion spring (`Level::torsion_springs`): then `length` is the relative angle
    /// theta = angle1 - angle2 (rad), `extension` its deflection from rest, `tension` the
    /// spring's moment k x + c dx/dt (N m), `couple_on_body1` = -tension the couple held on
    /// body1 during the step (body2 gets the opposite), and there is no force.
    #[serde(default)]
    pub torsion: bool,
    #[serde(default)]
    pub couple_on_body1: f64,
    /// The damper's part c dx/dt of `tension`, held during the step that led here, N (N m for
    /// a torsion spring); zero without the `damping` effect. `tension - damper_tension` is the
    /// elastic part k x.
    #[serde(default)]
    pub damper_tension: f64,
}

/// An applied load held constant over the step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LoadState {
    pub name: String,
    pub body: usize,
    /// World point of application at the start of the step, m.
    pub point: DVec2,
    pub force: DVec2,
    pub torque: f64,
}

/// An impulse applied at the start of the step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ImpulseState {
    pub name: String,
    pub body: usize,
    pub point: DVec2,
    pub impulse: DVec2,
    pub angular_impulse: f64,
}

impl Snapshot {
    pub fn body_index(&self, name: &str) -> Option<usize> {
        self.bodies.iter().position(|b| b.name == name)
    }
}
