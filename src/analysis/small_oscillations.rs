//! Small oscillations about an equilibrium (PL-14): the periods of a mechanism's modes from its
//! equations of motion linearized about the equilibrium, for any scene of bodies, joints,
//! couplings, springs, torsion springs, dampers, constant loads and gravity.
//!
//! The method, general rather than exercise by exercise:
//! 1. Full coordinates q = (x_G, y_G, L theta) per dynamic body (L, the mechanism's size, makes
//!    every coordinate a length, so one step size and one tolerance serve them all); the joints,
//!    couplings and locked rotations are constraints g(q) = 0.
//! 2. A local chart of the constraint manifold: at a point q* the null space N of the
//!    constraint Jacobian (orthonormal, from its SVD, so redundant constraints are fine), and
//!    q(s) = project(q* + N s), where project is the Gauss-Newton minimal-norm projection
//!    q <- q - G(q)^+ g(q) back onto g = 0.
//! 3. The equilibrium: from the level's initial configuration, Newton steps on V(q(s)) with a
//!    line search, to the minimum of the potential on the manifold nearest the start (a scene
//!    that starts at rest in equilibrium is its own answer after one step).
//! 4. At the equilibrium: M_r = N^T M N, K_r = the Hessian of V(q(s)) at s = 0 by central
//!    differences (the projection's curvature brings in the geometric stiffness a pendulum's
//!    m g d needs), C_r = N^T C N from the dampers.
//! 5. The modes: K_r phi = omega^2 M_r phi (undamped periods 2 pi / omega); with dampers, the
//!    eigenvalues lambda = -sigma +- i omega_d of the first-order system, each matched to the
//!    undamped mode of nearest |lambda| (exact for proportional damping), period 2 pi / omega_d.
//!
//! The finite-difference step is h = 1e-4 L: the truncation error of the central second
//! difference is about (h / L)^2 = 1e-8 relative, the rounding error about eps V / (K h^2)
//! = 1e-16 x 1e8 = 1e-8 relative with V measured from the start (so no large absolute height
//! enters), and the projection converges to 1e-13 L, well under h^2 / L. Tests hold the periods
//! to 1e-6 relative.
//!
//! A support (the kinematic bodies the mechanism hangs on) moving with constant velocity is an
//! inertial frame; with a constant acceleration a, gravity is replaced by g - a in its frame
//! (`Mechanism::support_acceleration`, from a kinematic support's `Motion::Accelerate`). Contacts, joint limits (unless the equilibrium sits on
//! one) and motors are not in the model: a motor or a time-varying or follower load makes the
//! analysis refuse, with the reason.

use crate::analysis::links::joined_bodies;
use crate::analysis::mass::of_body;
use crate::analysis::resting_contacts::{resting_contacts, Hold, RestingContact};
use crate::level::{BodyKind, Coordinate, Effect, JointKind, Level, Profile, DEFAULT_DENSITY};
use glam::DVec2;
use nalgebra::{DMatrix, DVector};
use std::f64::consts::PI;

/// One body of the mechanism, as the level gives it at t = 0.
#[derive(Debug, Clone, PartialEq)]
pub struct Member {
    pub name: String,
    /// Whether it is a coordinate of the model (a dynamic body); otherwise it holds its
    /// initial pose in the support's frame (fixed, or a kinematic support).
    pub moves: bool,
    pub mass: f64,
    /// I_G, kg m^2 (MP-1).
    pub inertia: f64,
    /// G in the body frame, m.
    pub local_com: DVec2,
    /// The body frame's origin and angle at t = 0.
    pub position: DVec2,
    pub angle: f64,
    /// v_G and omega at t = 0, relative to the support.
    pub velocity: DVec2,
    pub omega: f64,
    pub lock_rotation: bool,
    /// The body's linear and angular damping, 1/s: forces -m d v and couples -I d omega.
    pub linear_damping: f64,
    pub angular_damping: f64,
}

/// A joint: anchors in the bodies' frames (from the origin), axis in body1's frame (unit).
#[derive(Debug, Clone, PartialEq)]
pub struct Link {
    pub kind: JointKind,
    pub body1: usize,
    pub body2: usize,
    pub anchor1: DVec2,
    pub anchor2: DVec2,
    pub axis: DVec2,
    pub limits: Option<(f64, f64)>,
}

/// A linear spring-damper: body1's point (its frame) to body2's point (its frame), or to a
/// ground point (world frame) when `body2` is None.
#[derive(Debug, Clone, PartialEq)]
pub struct LinearSpring {
    pub body1: usize,
    pub point1: DVec2,
    pub body2: Option<usize>,
    pub point2: DVec2,
    pub stiffness: f64,
    pub rest_length: f64,
    pub damping: f64,
}

/// A torsion spring-damper on theta = angle1 - angle2 (angle2 = 0 for the ground).
#[derive(Debug, Clone, PartialEq)]
pub struct TorsionSpring {
    pub body1: usize,
    pub body2: Option<usize>,
    pub stiffness: f64,
    pub rest_angle: f64,
    pub damping: f64,
}

/// A constant force (world axes, at a body-frame point) and couple on a body.
#[derive(Debug, Clone, PartialEq)]
pub struct ConstantLoad {
    pub body: usize,
    pub point: DVec2,
    pub force: DVec2,
    pub torque: f64,
}

/// The mechanism the linearization is taken of: plain data, from a level or by hand.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Mechanism {
    pub members: Vec<Member>,
    pub links: Vec<Link>,
    /// Ratio constraints sum(ratio_i q_i) = const (the couplings), held at their initial value.
    pub ratios: Vec<Vec<(usize, Coordinate, f64)>>,
    pub springs: Vec<LinearSpring>,
    pub torsion_springs: Vec<TorsionSpring>,
    pub loads: Vec<ConstantLoad>,
    pub gravity: DVec2,
    /// The support's constant acceleration a: in its frame gravity is g - a.
    pub support_acceleration: DVec2,
    /// The support's velocity at t = 0 (the members' velocities are relative to it).
    pub support_velocity: DVec2,
    /// The faces the members rest on at the start, held as rolling or smooth contacts.
    pub contacts: Vec<RestingContact>,
}

/// One mode of small oscillation.
#[derive(Debug, Clone, PartialEq)]
pub struct Mode {
    /// Undamped natural circular frequency omega_n, rad/s.
    pub omega: f64,
    /// 2 pi / omega_n, s.
    pub period: f64,
    /// Damped circular frequency omega_d (= omega_n without dampers); None when overdamped.
    pub omega_d: Option<f64>,
    /// 2 pi / omega_d, s: the period the motion shows (None when overdamped).
    pub damped_period: Option<f64>,
    /// Per member: (dx_G, dy_G, dtheta) of the mode shape (mass-normalized in the chart).
    pub shape: Vec<(DVec2, f64)>,
    /// The share of the start's oscillation energy in this mode (0 to 1).
    pub energy_share: f64,
}

/// The linearized motion about the equilibrium.
#[derive(Debug, Clone, PartialEq)]
pub struct SmallOscillations {
    /// Per member: G and angle at the equilibrium.
    pub equilibrium: Vec<(DVec2, f64)>,
    /// The oscillating modes, lowest frequency first.
    pub modes: Vec<Mode>,
    /// Directions of zero stiffness (free motions: a cart's drift on a smooth floor).
    pub free_motions: usize,
    /// How far the start is from the equilibrium, in the chart (m, angles times L).
    pub offset: f64,
    /// The period at the start's amplitude along the most excited mode's path: the energy
    /// integral T = 2 int ds sqrt(m(s) / (2 (E - V(s)))) between the turning points of the path
    /// q(s) = project(q_eq + s phi), with m(s) = |dq/ds|_M^2 and E the start's whole energy
    /// (RE-7). Exact for one degree of freedom (the pendulum's elliptic-integral period, PL-5);
    /// for several, the motion held to the mode's shape. None when the start is at rest in
    /// equilibrium.
    pub amplitude_period: Option<f64>,
    /// |amplitude_period / undamped period - 1|: how far "small" is from the start's swing.
    pub period_error: f64,
}

/// The largest estimated period error for which the linearized period is offered (0.5 %: a
/// pendulum swinging to about 16 degrees).
pub const SMALL_AMPLITUDE_PERIOD_ERROR: f64 = 0.005;

/// The share of the oscillation energy a mode needs for a zero-crossing period to be its period.
pub const DOMINANT_MODE_SHARE: f64 = 0.98;

impl SmallOscillations {
    /// The mode the start excites, when one mode holds at least [`DOMINANT_MODE_SHARE`] of the
    /// oscillation energy (then the zero crossings of any coordinate it moves repeat with its
    /// period); otherwise why not.
    pub fn excited(&self) -> Result<&Mode, String> {
        let best = self
            .modes
            .iter()
            .enumerate()
            .max_by(|a, b| a.1.energy_share.total_cmp(&b.1.energy_share))
            .ok_or("the mechanism has no oscillating mode")?;
        if best.1.energy_share <= 0.0 {
            return Err("the start is at rest in equilibrium: nothing oscillates".into());
        }
        if best.1.energy_share < DOMINANT_MODE_SHARE {
            let shares: Vec<String> = self
                .modes
                .iter()
                .enumerate()
                .map(|(k, m)| format!("mode {} {:.1} %", k + 1, 100.0 * m.energy_share))
                .collect();
            return Err(format!(
                "the start excites several modes ({}): the motion is not periodic with one period; start in one mode's shape",
                shares.join(", ")
            ));
        }
        Ok(best.1)
    }
}

impl Mechanism {
    /// The mechanism of `level` that holds body `around` (its index in `level.bodies`): the
    /// dynamic bodies joined to it by joints, couplings and springs, and what holds them, with
    /// only the level's declared effects. Err when the scene is outside the model (a motor, a
    /// load that changes or turns, a support that rotates or supports that move apart).
    // Not yet split into named steps (issue 44): builds the mechanism's coordinates, constraints and forces from a level in one pass.
    #[allow(clippy::too_many_lines)]
    pub fn of_level(level: &Level, around: usize) -> Result<Mechanism, String> {
        let has = |e: Effect| level.effects.contains(&e);
        let v = |p: (f64, f64)| DVec2::new(p.0, p.1);
        let index = |n: &str| level.bodies.iter().position(|b| b.name == n);
        let dynamic = |k: usize| level.bodies[k].kind == BodyKind::Dynamic;
        let n = level.bodies.len();
        if around >= n || !dynamic(around) {
            return Err("the body is not a dynamic body".into());
        }
        // Pairs of bodies that act on each other.
        let mut pairs: Vec<(usize, Option<usize>)> = Vec::new();
        if has(Effect::Joints) {
            for j in &level.joints {
                pairs.push((index(&j.body1).ok_or("joint body")?, index(&j.body2)));
            }
            for c in &level.couplings {
                let bodies: Vec<usize> = c.terms.iter().filter_map(|t| index(&t.body)).collect();
                for w in bodies.windows(2) {
                    pairs.push((w[0], Some(w[1])));
                }
            }
        }
        if has(Effect::Springs) {
            for s in &level.springs {
                let b2 = s.body2.as_deref().and_then(index);
                pairs.push((index(&s.body1).ok_or("spring body")?, b2));
            }
            for s in &level.torsion_springs {
                let b2 = s.body2.as_deref().and_then(index);
                pairs.push((index(&s.body1).ok_or("spring body")?, b2));
            }
        }
        // The connected set of dynamic bodies and what holds them (fixed and kinematic bodies
        // join it but do not pass it on).
        let inside = joined_bodies(
            n,
            [around],
            pairs.iter().filter_map(|&(a, b)| Some((a, b?))),
            dynamic,
            |_| true,
        );
        // The support: every kinematic body the set hangs on moves with one velocity, unturned.
        let mut support: Option<DVec2> = None;
        let mut support_acceleration: Option<DVec2> = None;
        let mut grounded = false;
        for (_, b) in level.bodies.iter().enumerate().filter(|(k, _)| inside[*k]) {
            match b.kind {
                BodyKind::Dynamic => {}
                BodyKind::Fixed => grounded = true,
                BodyKind::Kinematic => {
                    if b.omega != 0.0 {
                        return Err(format!(
                            "\"{}\", a kinematic body the mechanism hangs on, turns: its frame is not inertial",
                            b.name
                        ));
                    }
                    // A prescribed motion: a uniform acceleration is a frame where gravity
                    // reads g - a; anything else drives the mechanism (forced, not free,
                    // vibration) or turns its frame.
                    let ak = match b.motion {
                        None => DVec2::ZERO,
                        Some(m) => match m.uniform_translation() {
                            Some(a) => v(a),
                            None => {
                                return Err(format!(
                                    "\"{}\", a kinematic body the mechanism hangs on, has a prescribed {}: the motion is forced, not a free oscillation about an equilibrium",
                                    b.name,
                                    match m {
                                        crate::level::Motion::Oscillate { .. } => "oscillation",
                                        crate::level::Motion::Accelerate { .. } => "rotation",
                                    }
                                ))
                            }
                        },
                    };
                    let vk = v(b.velocity);
                    if support.is_some_and(|s| (s - vk).length() > 1e-12)
                        || support_acceleration.is_some_and(|s| (s - ak).length() > 1e-12)
                    {
                        return Err(
                            "the kinematic bodies that hold the mechanism move apart".into()
                        );
                    }
                    support = Some(vk);
                    support_acceleration = Some(ak);
                }
            }
        }
        let ground_springs = pairs
            .iter()
            .any(|&(a, b)| inside[a] && b.is_none() && dynamic(a));
        let v_support = support.unwrap_or(DVec2::ZERO);
        let a_support = support_acceleration.unwrap_or(DVec2::ZERO);
        if (v_support != DVec2::ZERO || a_support != DVec2::ZERO) && (grounded || ground_springs) {
            return Err(
                "both the ground and a moving kinematic body hold the mechanism: its equilibrium moves".into(),
            );
        }
        let damping = has(Effect::Damping);
        let members = level
            .bodies
            .iter()
            .map(|b| {
                let mp = of_body(b, DEFAULT_DENSITY);
                let moves = b.kind == BodyKind::Dynamic;
                Member {
                    name: b.name.clone(),
                    moves: moves && inside[index(&b.name).unwrap_or(0)],
                    mass: mp.mass,
                    inertia: mp.inertia,
                    local_com: mp.com,
                    position: v(b.position),
                    angle: b.angle,
                    velocity: v(b.velocity) - v_support,
                    omega: b.omega,
                    lock_rotation: b.lock_rotation,
                    linear_damping: if damping {
                        b.linear_damping.unwrap_or(0.0)
                    } else {
                        0.0
                    },
                    angular_damping: if damping {
                        b.angular_damping.unwrap_or(0.0)
                    } else {
                        0.0
                    },
                }
            })
            .collect();
        let touches = |a: usize, b: Option<usize>| inside[a] || b.is_some_and(|b| inside[b]);
        let mut m = Mechanism {
            members,
            gravity: if has(Effect::Gravity) {
                v(level.world.gravity.unwrap_or((0.0, -9.81)))
            } else {
                DVec2::ZERO
            },
            support_acceleration: a_support,
            support_velocity: v_support,
            ..Default::default()
        };
        let moving: Vec<usize> = (0..n).filter(|&k| inside[k] && dynamic(k)).collect();
        m.contacts = resting_contacts(level, &moving, m.gravity - a_support)?;
        if has(Effect::Joints) {
            for j in &level.joints {
                let (b1, b2) = (index(&j.body1).unwrap_or(0), index(&j.body2).unwrap_or(0));
                if !touches(b1, Some(b2)) {
                    continue;
                }
                if has(Effect::Motors) && j.motor.is_some() {
                    return Err(format!(
                        "joint \"{}\" has a motor, which the linearization does not model",
                        j.name
                    ));
                }
                m.links.push(Link {
                    kind: j.kind,
                    body1: b1,
                    body2: b2,
                    anchor1: v(j.anchor1),
                    anchor2: v(j.anchor2),
                    axis: v(j.axis).normalize_or(DVec2::X),
                    limits: j.limits,
                });
            }
            for c in &level.couplings {
                let terms: Vec<(usize, Coordinate, f64)> = c
                    .terms
                    .iter()
                    .filter_map(|t| Some((index(&t.body)?, t.coordinate, t.ratio)))
                    .collect();
                if terms.iter().any(|t| inside[t.0]) {
                    m.ratios.push(terms);
                }
            }
        }
        if has(Effect::Springs) {
            for s in &level.springs {
                let b1 = index(&s.body1).unwrap_or(0);
                let b2 = s.body2.as_deref().and_then(index);
                if touches(b1, b2) {
                    m.springs.push(LinearSpring {
                        body1: b1,
                        point1: v(s.point1),
                        body2: b2,
                        point2: v(s.point2),
                        stiffness: s.stiffness,
                        rest_length: s.rest_length,
                        damping: if damping { s.damping } else { 0.0 },
                    });
                }
            }
            for s in &level.torsion_springs {
                let b1 = index(&s.body1).unwrap_or(0);
                let b2 = s.body2.as_deref().and_then(index);
                if touches(b1, b2) {
                    let a2 = b2.map_or(0.0, |k| level.bodies[k].angle);
                    m.torsion_springs.push(TorsionSpring {
                        body1: b1,
                        body2: b2,
                        stiffness: s.stiffness,
                        rest_angle: s.rest_angle.unwrap_or(level.bodies[b1].angle - a2),
                        damping: if damping { s.damping } else { 0.0 },
                    });
                }
            }
        }
        for l in &level.loads {
            let Some(b) = index(&l.body).filter(|&b| inside[b]) else {
                continue;
            };
            if l.follow_body {
                return Err(format!(
                    "load \"{}\" turns with the body (a follower load has no potential)",
                    l.name
                ));
            }
            let force = match &l.force {
                None => DVec2::ZERO,
                Some(Profile::Constant(f)) => v(*f),
                Some(Profile::Table(_)) => {
                    return Err(format!("load \"{}\" changes with time", l.name))
                }
            };
            let torque = match &l.torque {
                None => 0.0,
                Some(Profile::Constant(t)) => *t,
                Some(Profile::Table(_)) => {
                    return Err(format!("load \"{}\" changes with time", l.name))
                }
            };
            m.loads.push(ConstantLoad {
                body: b,
                point: v(l.point),
                force,
                torque,
            });
        }
        Ok(m)
    }

    /// The linearized modes about the equilibrium nearest the start; Err with the reason when
    /// there is no stable equilibrium, the start is too far from it for "small", or the model
    /// is degenerate.
    pub fn small_oscillations(&self) -> Result<SmallOscillations, String> {
        let model = Model::new(self)?;
        model.solve()
    }
}

/// The mechanism in full scaled coordinates.
struct Model<'a> {
    m: &'a Mechanism,
    /// Member index of each coordinate slot (3 coordinates per moving member).
    slots: Vec<usize>,
    /// Slot of each member (None when it does not move).
    slot_of: Vec<Option<usize>>,
    /// The length that turns angles into coordinates: q = L theta.
    l: f64,
    /// The start, q0, and its rate.
    q0: DVector<f64>,
    qdot0: DVector<f64>,
    /// The constraints' values at the start (what they hold).
    g0: DVector<f64>,
}

fn rot(a: f64, p: DVec2) -> DVec2 {
    DVec2::from_angle(a).rotate(p)
}

impl<'a> Model<'a> {
    fn new(m: &'a Mechanism) -> Result<Model<'a>, String> {
        let slots: Vec<usize> = (0..m.members.len())
            .filter(|&k| m.members[k].moves)
            .collect();
        if slots.is_empty() {
            return Err("no body of the mechanism moves".into());
        }
        let mut slot_of = vec![None; m.members.len()];
        for (s, &k) in slots.iter().enumerate() {
            slot_of[k] = Some(s);
            let b = &m.members[k];
            if b.mass.is_nan() || b.mass <= 0.0 || !b.mass.is_finite() {
                return Err(format!("body \"{}\" has no mass", b.name));
            }
            if !b.lock_rotation && (b.inertia.is_nan() || b.inertia <= 0.0) {
                return Err(format!("body \"{}\" has no moment of inertia", b.name));
            }
        }
        // L: the mechanism's size (its bodies' and anchors' spread), at least 1 mm.
        let coms: Vec<DVec2> = m
            .members
            .iter()
            .map(|b| b.position + rot(b.angle, b.local_com))
            .collect();
        let mut l: f64 = 0.0;
        for k in &slots {
            for c in &coms {
                l = l.max((coms[*k] - *c).length());
            }
        }
        for j in &m.links {
            l = l.max(j.anchor1.length()).max(j.anchor2.length());
        }
        for s in &m.springs {
            l = l.max(s.rest_length);
        }
        let l = l.max(1e-3);
        let n = 3 * slots.len();
        let mut q0 = DVector::zeros(n);
        let mut qdot0 = DVector::zeros(n);
        for (s, &k) in slots.iter().enumerate() {
            let b = &m.members[k];
            q0[3 * s] = coms[k].x;
            q0[3 * s + 1] = coms[k].y;
            q0[3 * s + 2] = l * b.angle;
            qdot0[3 * s] = b.velocity.x;
            qdot0[3 * s + 1] = b.velocity.y;
            qdot0[3 * s + 2] = l * b.omega;
        }
        let mut model = Model {
            m,
            slots,
            slot_of,
            l,
            q0,
            qdot0,
            g0: DVector::zeros(0),
        };
        model.g0 = model.raw_constraints(&model.q0.clone());
        Ok(model)
    }

    /// G and angle of member k at q.
    fn pose(&self, q: &DVector<f64>, k: usize) -> (DVec2, f64) {
        match self.slot_of[k] {
            Some(s) => (DVec2::new(q[3 * s], q[3 * s + 1]), q[3 * s + 2] / self.l),
            None => {
                let b = &self.m.members[k];
                (b.position + rot(b.angle, b.local_com), b.angle)
            }
        }
    }

    /// World position of member k's body-frame point p at q.
    fn point(&self, q: &Poses, k: usize, p: DVec2) -> DVec2 {
        let (g, a) = q.0[k];
        g + rot(a, p - self.m.members[k].local_com)
    }

    fn poses(&self, q: &DVector<f64>) -> Poses {
        Poses((0..self.m.members.len()).map(|k| self.pose(q, k)).collect())
    }

    /// The constraint functions (lengths: angle rows times L), not yet less their start values.
    fn raw_constraints(&self, q: &DVector<f64>) -> DVector<f64> {
        let p = self.poses(q);
        let l = self.l;
        let mut g: Vec<f64> = Vec::new();
        for j in &self.m.links {
            let a1 = self.point(&p, j.body1, j.anchor1);
            let a2 = self.point(&p, j.body2, j.anchor2);
            let (th1, th2) = (p.0[j.body1].1, p.0[j.body2].1);
            let normal = rot(th1, j.axis).perp();
            match j.kind {
                JointKind::Revolute => g.extend([a2.x - a1.x, a2.y - a1.y]),
                JointKind::Fixed => g.extend([a2.x - a1.x, a2.y - a1.y, l * (th1 - th2)]),
                JointKind::Prismatic => g.extend([normal.dot(a2 - a1), l * (th1 - th2)]),
                JointKind::PinSlot => g.push(normal.dot(a2 - a1)),
            }
        }
        for terms in &self.m.ratios {
            g.push(
                terms
                    .iter()
                    .map(|&(k, c, r)| {
                        let (gk, ak) = p.0[k];
                        r * match c {
                            Coordinate::X => gk.x,
                            Coordinate::Y => gk.y,
                            Coordinate::Angle => ak,
                        }
                    })
                    .sum(),
            );
        }
        for (s, &k) in self.slots.iter().enumerate() {
            if self.m.members[k].lock_rotation {
                g.push(q[3 * s + 2]);
            }
        }
        // Resting contacts: the distance from the face kept; rolling also keeps the distance
        // rolled along the face plus r theta (RK-8: v_G along the face = -omega r); a flat face
        // keeps its angle.
        for c in &self.m.contacts {
            let (gk, ak) = p.0[c.body];
            let center = self.point(&p, c.body, c.point);
            let along = DVec2::new(c.normal.y, -c.normal.x);
            match c.hold {
                Hold::Rolling { radius } => {
                    g.extend([c.normal.dot(center), along.dot(center) + radius * ak])
                }
                Hold::Sliding => g.push(c.normal.dot(center)),
                Hold::Flat => g.extend([c.normal.dot(gk), l * ak]),
            }
        }
        DVector::from_vec(g)
    }

    fn constraints(&self, q: &DVector<f64>) -> DVector<f64> {
        self.raw_constraints(q) - &self.g0
    }

    /// The constraint Jacobian by central differences (step 1e-6 L: smooth functions of
    /// sines and cosines, error about 1e-12 relative).
    fn jacobian(&self, q: &DVector<f64>) -> DMatrix<f64> {
        let n = q.len();
        let h = 1e-6 * self.l;
        let rows = self.g0.len();
        let mut jac = DMatrix::zeros(rows, n);
        for i in 0..n {
            let mut qp = q.clone();
            let mut qm = q.clone();
            qp[i] += h;
            qm[i] -= h;
            let d = (self.raw_constraints(&qp) - self.raw_constraints(&qm)) / (2.0 * h);
            jac.set_column(i, &d);
        }
        jac
    }

    /// An orthonormal basis of the Jacobian's null space at q (n x d).
    fn null_space(&self, q: &DVector<f64>) -> Result<DMatrix<f64>, String> {
        let n = q.len();
        if self.g0.is_empty() {
            return Ok(DMatrix::identity(n, n));
        }
        // Square it with zero rows so the SVD gives all of V.
        let jac = self.jacobian(q);
        let mut sq = DMatrix::zeros(n.max(jac.nrows()), n);
        sq.view_mut((0, 0), (jac.nrows(), n)).copy_from(&jac);
        let svd = nalgebra::linalg::SVD::try_new(sq, false, true, f64::EPSILON, 0)
            .ok_or("the constraint Jacobian's SVD did not converge")?;
        let vt = svd.v_t.ok_or("no V from the SVD")?;
        let smax = svd.singular_values.max();
        let cols: Vec<DVector<f64>> = (0..svd.singular_values.len())
            .filter(|&i| svd.singular_values[i] <= 1e-7 * smax.max(1e-300))
            .map(|i| vt.row(i).transpose())
            .collect();
        if cols.is_empty() {
            return Err("the joints leave the mechanism no motion".into());
        }
        Ok(DMatrix::from_columns(&cols))
    }

    /// Gauss-Newton minimal-norm projection onto g = 0.
    fn project(&self, q: &DVector<f64>) -> Result<DVector<f64>, String> {
        if !q.iter().all(|x| x.is_finite()) {
            return Err("a configuration is not finite".into());
        }
        let mut q = q.clone();
        if self.g0.is_empty() {
            return Ok(q);
        }
        let tol = 1e-13 * self.l;
        let mut last = f64::INFINITY;
        for _ in 0..40 {
            let g = self.constraints(&q);
            let r = g.amax();
            if r <= tol || (r >= last && r < 1e-9 * self.l) {
                return Ok(q);
            }
            last = r;
            let jac = self.jacobian(&q);
            let svd = nalgebra::linalg::SVD::try_new(jac, true, true, f64::EPSILON, 0)
                .ok_or("the constraint Jacobian's SVD did not converge")?;
            let eps = 1e-9 * svd.singular_values.max();
            let dq = svd.solve(&g, eps).map_err(|e| format!("projection: {e}"))?;
            q -= dq;
        }
        let r = self.constraints(&q).amax();
        if r <= 1e-9 * self.l {
            Ok(q)
        } else {
            Err(format!(
                "the constraints cannot be closed near the start (residual {r:.2e} m)"
            ))
        }
    }

    /// The potential V(q) (gravity in the support's frame, springs, constant loads), measured
    /// from the start so no large absolute height enters its rounding.
    fn potential(&self, q: &DVector<f64>) -> f64 {
        let p = self.poses(q);
        let p0 = self.poses(&self.q0);
        let g_eff = self.m.gravity - self.m.support_acceleration;
        let mut v = 0.0;
        for &k in &self.slots {
            v -= self.m.members[k].mass * g_eff.dot(p.0[k].0 - p0.0[k].0);
        }
        for s in &self.m.springs {
            let a = self.point(&p, s.body1, s.point1);
            let b = match s.body2 {
                Some(k) => self.point(&p, k, s.point2),
                None => s.point2,
            };
            let x = (b - a).length() - s.rest_length;
            v += 0.5 * s.stiffness * x * x;
        }
        for s in &self.m.torsion_springs {
            let th = p.0[s.body1].1 - s.body2.map_or(0.0, |k| p.0[k].1);
            let x = th - s.rest_angle;
            v += 0.5 * s.stiffness * x * x;
        }
        for ld in &self.m.loads {
            let at = self.point(&p, ld.body, ld.point);
            let at0 = self.point(&p0, ld.body, ld.point);
            v -= ld.force.dot(at - at0) + ld.torque * (p.0[ld.body].1 - p0.0[ld.body].1);
        }
        v
    }

    /// V along the chart at base with null space nb: V(project(base + nb s)).
    fn chart_v(
        &self,
        base: &DVector<f64>,
        nb: &DMatrix<f64>,
        s: &DVector<f64>,
    ) -> Result<f64, String> {
        Ok(self.potential(&self.project(&(base + nb * s))?))
    }

    /// Gradient and Hessian of V along the chart at s = 0, central differences of step h.
    fn derivatives(
        &self,
        base: &DVector<f64>,
        nb: &DMatrix<f64>,
    ) -> Result<(DVector<f64>, DMatrix<f64>), String> {
        let d = nb.ncols();
        let h = 1e-4 * self.l;
        let v0 = self.potential(base);
        let e = |i: usize| {
            let mut x = DVector::zeros(d);
            x[i] = 1.0;
            x
        };
        let mut grad = DVector::zeros(d);
        let mut hess = DMatrix::zeros(d, d);
        for i in 0..d {
            let vp = self.chart_v(base, nb, &(e(i) * h))?;
            let vm = self.chart_v(base, nb, &(e(i) * -h))?;
            grad[i] = (vp - vm) / (2.0 * h);
            hess[(i, i)] = (vp - 2.0 * v0 + vm) / (h * h);
            for j in 0..i {
                let f = |a: f64, b: f64| self.chart_v(base, nb, &(e(i) * (a * h) + e(j) * (b * h)));
                let hij =
                    (f(1.0, 1.0)? - f(1.0, -1.0)? - f(-1.0, 1.0)? + f(-1.0, -1.0)?) / (4.0 * h * h);
                hess[(i, j)] = hij;
                hess[(j, i)] = hij;
            }
        }
        Ok((grad, hess))
    }

    /// The stiffness scale below which a direction counts as free (zero stiffness).
    fn free_tol(hess: &DMatrix<f64>) -> f64 {
        1e-6 * hess.amax().max(1e-300)
    }

    /// Newton steps on V along the chart from the start to the nearest minimum.
    fn equilibrium(&self) -> Result<DVector<f64>, String> {
        let mut q = self.project(&self.q0)?;
        for _ in 0..100 {
            let nb = self.null_space(&q)?;
            let (grad, hess) = self.derivatives(&q, &nb)?;
            let eig = nalgebra::linalg::SymmetricEigen::try_new(hess.clone(), 1e-15, 1000)
                .ok_or("the stiffness eigenproblem did not converge")?;
            let tol = Self::free_tol(&hess);
            let gscale = grad.amax();
            let mut step = DVector::zeros(nb.ncols());
            for i in 0..nb.ncols() {
                let u = eig.eigenvectors.column(i);
                let gi = u.dot(&grad);
                let k = eig.eigenvalues[i];
                if k.abs() > tol {
                    // Downhill whatever the curvature's sign: a maximum is walked away from.
                    step -= u * (gi / k.abs());
                } else if gi.abs() > 1e-9 * gscale.max(1e-300) {
                    // No curvature: downhill by the trust radius.
                    step -= u * (gi.signum() * 0.25 * self.l);
                }
            }
            // A trust region of L/4 and a line search on V.
            let len = step.norm();
            if len > 0.25 * self.l {
                step *= 0.25 * self.l / len;
            }
            let v_here = self.potential(&q);
            let mut t = 1.0;
            let mut next = None;
            for _ in 0..40 {
                let cand = self.project(&(&q + &nb * (&step * t)))?;
                if self.potential(&cand) <= v_here + 1e-14 * v_here.abs().max(1.0) {
                    next = Some(cand);
                    break;
                }
                t *= 0.5;
            }
            let Some(next) = next else {
                break;
            };
            let moved = (&next - &q).norm();
            q = next;
            if moved < 1e-11 * self.l {
                break;
            }
        }
        // Converged: the gradient's work over L is a millionth of the stiffness's.
        let nb = self.null_space(&q)?;
        let (grad, hess) = self.derivatives(&q, &nb)?;
        if grad.amax() > 1e-6 * hess.amax().max(1e-300) * self.l {
            return Err(format!(
                "no equilibrium near the start: the potential keeps falling (gradient {:.3e} N along the free motions)",
                grad.amax()
            ));
        }
        Ok(q)
    }

    /// The energy-integral period along the mode's path at energy e above the equilibrium (see
    /// `SmallOscillations::amplitude_period`): the path is followed from q by steps of M-metric
    /// length ds = reach / 2000 (reach = sqrt(2 e) / omega, the linear amplitude), each step
    /// along the last secant and projected back onto the constraints, so s is the path's
    /// M-arclength and m(s) = 1; T = 2 int ds / sqrt(2 (e - V(s))) with V linear between the
    /// steps (each piece integrated exactly: ds sqrt 2 / (sqrt r_a + sqrt r_b), r = e - V;
    /// error of order (ds / reach)^2).
    fn path_period(
        &self,
        q: &DVector<f64>,
        dir: &DVector<f64>,
        m_full: &DMatrix<f64>,
        e: f64,
        omega: f64,
    ) -> Result<f64, String> {
        let v_eq = self.potential(q);
        let m_norm = |d: &DVector<f64>| (d.transpose() * m_full * d)[(0, 0)].max(0.0).sqrt();
        let reach = (2.0 * e).sqrt() / omega;
        let step = reach / 2000.0;
        let mut t = 0.0;
        for sign in [1.0, -1.0] {
            let mut here = q.clone();
            let mut tangent = dir * (sign / m_norm(dir).max(1e-300));
            let mut r_prev = e;
            let mut turned = false;
            for _ in 0..40_000 {
                let next = self.project(&(&here + &tangent * step))?;
                let chord = &next - &here;
                let ds = m_norm(&chord);
                if ds <= 0.0 {
                    return Err("the mode's path stalls".into());
                }
                let r = e - (self.potential(&next) - v_eq);
                if r <= 0.0 {
                    // The turning point inside this piece, V linear across it.
                    t += ds * (r_prev / (r_prev - r)) * 2f64.sqrt() / r_prev.sqrt();
                    turned = true;
                    break;
                }
                if r > r_prev {
                    return Err(
                        "the swing goes over the top: the start's energy carries it past the potential's crest"
                            .into(),
                    );
                }
                t += ds * 2f64.sqrt() / (r_prev.sqrt() + r.sqrt());
                r_prev = r;
                tangent = chord / ds;
                here = next;
            }
            if !turned {
                return Err("the swing does not turn back within 20 times its linear reach".into());
            }
        }
        // The time from one turning point to the other, twice.
        Ok(2.0 * t)
    }

    // Not yet split into named steps (issue 44): the linearization, eigenproblem and amplitude period of one mechanism.
    #[allow(clippy::too_many_lines)]
    fn solve(&self) -> Result<SmallOscillations, String> {
        let q = self.equilibrium()?;
        let nb = self.null_space(&q)?;
        let d = nb.ncols();
        let (_, k_r) = self.derivatives(&q, &nb)?;
        // M and C in full scaled coordinates.
        let n = q.len();
        let mut m_full = DMatrix::zeros(n, n);
        let mut c_full = DMatrix::zeros(n, n);
        let l2 = self.l * self.l;
        for (s, &k) in self.slots.iter().enumerate() {
            let b = &self.m.members[k];
            m_full[(3 * s, 3 * s)] = b.mass;
            m_full[(3 * s + 1, 3 * s + 1)] = b.mass;
            m_full[(3 * s + 2, 3 * s + 2)] = b.inertia / l2;
            c_full[(3 * s, 3 * s)] = b.mass * b.linear_damping;
            c_full[(3 * s + 1, 3 * s + 1)] = b.mass * b.linear_damping;
            c_full[(3 * s + 2, 3 * s + 2)] = b.inertia * b.angular_damping / l2;
        }
        // Dampers: c grad(l) grad(l)^T for the rate of each spring's length or angle.
        let h = 1e-6 * self.l;
        let rate_gradient = |f: &dyn Fn(&DVector<f64>) -> f64| {
            DVector::from_iterator(
                n,
                (0..n).map(|i| {
                    let mut qp = q.clone();
                    let mut qm = q.clone();
                    qp[i] += h;
                    qm[i] -= h;
                    (f(&qp) - f(&qm)) / (2.0 * h)
                }),
            )
        };
        for s in self.m.springs.iter().filter(|s| s.damping != 0.0) {
            let length = |x: &DVector<f64>| {
                let p = self.poses(x);
                let a = self.point(&p, s.body1, s.point1);
                let b = match s.body2 {
                    Some(k) => self.point(&p, k, s.point2),
                    None => s.point2,
                };
                (b - a).length()
            };
            let gr = rate_gradient(&length);
            c_full += &gr * gr.transpose() * s.damping;
        }
        for s in self.m.torsion_springs.iter().filter(|s| s.damping != 0.0) {
            let angle = |x: &DVector<f64>| {
                let p = self.poses(x);
                p.0[s.body1].1 - s.body2.map_or(0.0, |k| p.0[k].1)
            };
            let gr = rate_gradient(&angle);
            c_full += &gr * gr.transpose() * s.damping;
        }
        let m_r = nb.transpose() * &m_full * &nb;
        let c_r = nb.transpose() * &c_full * &nb;
        let k_r = (&k_r + k_r.transpose()) * 0.5;
        // K phi = w^2 M phi through M = L L^T: (L^-1 K L^-T) y = w^2 y, phi = L^-T y.
        let chol = nalgebra::linalg::Cholesky::new(m_r.clone())
            .ok_or("the reduced mass matrix is not positive definite")?;
        let lm = chol.l();
        let lm_inv = lm
            .clone()
            .try_inverse()
            .ok_or("the reduced mass matrix is singular")?;
        let a = &lm_inv * &k_r * lm_inv.transpose();
        let a = (&a + a.transpose()) * 0.5;
        let eig = nalgebra::linalg::SymmetricEigen::try_new(a, 1e-15, 1000)
            .ok_or("the mode eigenproblem did not converge")?;
        let w2max = eig.eigenvalues.amax().max(1e-300);
        let tol = 1e-6 * w2max;
        if let Some(k) = (0..d).find(|&i| eig.eigenvalues[i] < -tol) {
            let falls = &nb * (lm_inv.transpose() * eig.eigenvectors.column(k));
            return Err(format!(
                "the equilibrium nearest the start is unstable (omega^2 = {:.3e} 1/s^2 < 0): it falls away moving {}",
                eig.eigenvalues[k],
                self.largest_motion(&falls)
            ));
        }
        if eig.eigenvalues.max() <= tol || eig.eigenvalues.max() <= 0.0 {
            return Err("nothing restores the mechanism: every direction is free".into());
        }
        // The start in the chart, and in modal coordinates.
        let s0 = nb.transpose() * (&self.q0 - &q);
        let sdot0 = nb.transpose() * &self.qdot0;
        let offset = s0.norm();
        // Damped eigenvalues of [0 I; -M^-1 K  -M^-1 C].
        let damped: Option<Vec<nalgebra::Complex<f64>>> = if c_r.amax() > 0.0 {
            let m_inv = chol.inverse();
            let mut big = DMatrix::zeros(2 * d, 2 * d);
            big.view_mut((0, d), (d, d)).fill_with_identity();
            big.view_mut((d, 0), (d, d)).copy_from(&(-&m_inv * &k_r));
            big.view_mut((d, d), (d, d)).copy_from(&(-&m_inv * &c_r));
            let schur = nalgebra::linalg::Schur::try_new(big, 1e-15, 10000)
                .ok_or("the damped eigenproblem did not converge")?;
            Some(schur.complex_eigenvalues().iter().copied().collect())
        } else {
            None
        };
        let mut used = vec![false; damped.as_ref().map_or(0, |v| v.len())];
        let mut order: Vec<usize> = (0..d).filter(|&i| eig.eigenvalues[i] > tol).collect();
        order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
        let free_motions = d - order.len();
        let mut modes = Vec::new();
        let mut energies = Vec::new();
        for &i in &order {
            let w2 = eig.eigenvalues[i];
            let w = w2.sqrt();
            let y = eig.eigenvectors.column(i);
            let phi = lm_inv.transpose() * y;
            let eta = (phi.transpose() * &m_r * &s0)[(0, 0)];
            let etadot = (phi.transpose() * &m_r * &sdot0)[(0, 0)];
            energies.push(0.5 * (etadot * etadot + w2 * eta * eta));
            let omega_d = match &damped {
                None => Some(w),
                Some(lams) => {
                    let best = (0..lams.len())
                        .filter(|&k| !used[k] && lams[k].im >= 0.0)
                        .min_by(|&a, &b| {
                            (lams[a].norm() - w)
                                .abs()
                                .total_cmp(&(lams[b].norm() - w).abs())
                        });
                    best.and_then(|k| {
                        used[k] = true;
                        (lams[k].im > 1e-9 * w).then_some(lams[k].im)
                    })
                }
            };
            let full = &nb * &phi;
            let shape = (0..self.m.members.len())
                .map(|k| match self.slot_of[k] {
                    Some(s) => (
                        DVec2::new(full[3 * s], full[3 * s + 1]),
                        full[3 * s + 2] / self.l,
                    ),
                    None => (DVec2::ZERO, 0.0),
                })
                .collect();
            modes.push((
                Mode {
                    omega: w,
                    period: 2.0 * PI / w,
                    omega_d,
                    damped_period: omega_d.map(|wd| 2.0 * PI / wd),
                    shape,
                    energy_share: 0.0,
                },
                phi,
            ));
        }
        let total: f64 = energies.iter().sum();
        let mut amplitude_period = None;
        let mut period_error = 0.0;
        if total > 0.0 {
            for (mode, e) in modes.iter_mut().zip(&energies) {
                mode.0.energy_share = e / total;
            }
            let (k, _) = energies
                .iter()
                .enumerate()
                .max_by(|a, b| a.1.total_cmp(b.1))
                .unwrap_or((0, &0.0));
            // The start's oscillation energy, exact in V: T0 less the free motions' drift,
            // plus V(q0) - V(q_eq).
            // (The start's rate as the joints allow it: its part along the null space.)
            let t0 = 0.5 * (sdot0.transpose() * &m_r * &sdot0)[(0, 0)];
            let drift: f64 = (0..d)
                .filter(|&i| eig.eigenvalues[i] <= tol)
                .map(|i| {
                    let phi = lm_inv.transpose() * eig.eigenvectors.column(i);
                    let etadot = (phi.transpose() * &m_r * &sdot0)[(0, 0)];
                    0.5 * etadot * etadot
                })
                .sum();
            let e = t0 - drift + self.potential(&self.q0) - self.potential(&q);
            if e > 0.0 {
                let (mode, phi) = &modes[k];
                let t_path = self.path_period(&q, &(&nb * phi), &m_full, e, mode.omega)?;
                period_error = (t_path / mode.period - 1.0).abs();
                amplitude_period = Some(t_path);
            }
        }
        let eq_poses = self.poses(&q).0;
        Ok(SmallOscillations {
            equilibrium: eq_poses,
            modes: modes.into_iter().map(|(m, _)| m).collect(),
            free_motions,
            offset,
            amplitude_period,
            period_error,
        })
    }
}

impl Model<'_> {
    /// Which member a motion `full` (full coordinates) moves most, and along what: a platform on
    /// a compressed spring with no guide falls sideways ("platform" along x), which the note
    /// names, so that the reason is not mistaken for the free body next to it (n14_20).
    fn largest_motion(&self, full: &DVector<f64>) -> String {
        let mut best = (0.0, String::new());
        for (k, b) in self.m.members.iter().enumerate() {
            let Some(s) = self.slot_of[k] else { continue };
            for (c, what) in ["along x", "along y", "turning"].iter().enumerate() {
                let size = full[3 * s + c].abs();
                if size > best.0 {
                    best = (size, format!("\"{}\" {what}", b.name));
                }
            }
        }
        best.1
    }
}

/// Every member's (G, angle) at one q.
struct Poses(Vec<(DVec2, f64)>);
