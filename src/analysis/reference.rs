//! The reference trajectory: a level's equations of motion integrated in f64 by an adaptive
//! Runge-Kutta method at a tight tolerance, independent of the engine. It is the analysis value
//! of a question that has no closed form on a scene without impacts (a position, a speed or an
//! angle at a time), and a yardstick for the engine anywhere the scene fits it.
//!
//! The model (Lagrange's equations of the first kind, MK 6/1 and 6/3 per body with the joints'
//! reactions as multipliers):
//! - maximal coordinates q = (x_G, y_G, theta) and their rates per dynamic body; fixed and
//!   kinematic bodies follow their prescribed motion (`level::motion`), which enters the
//!   constraints as known positions, velocities and accelerations;
//! - pins, sliders, welds, pins in a slot, couplings (with the load on the pulley a cable runs
//!   over, or on meshing gears' axles, as the engine applies it) and ideal velocity motors are constraints
//!   C(q, t) = 0 written at the acceleration level, J a + b = 0; each right-hand-side evaluation
//!   solves M a + J^T mu = F, J a = -b through the Schur complement (J M^-1 J^T) mu =
//!   J M^-1 F + b (Cholesky, or the SVD's pseudo-inverse when constraints are redundant), and
//!   the reactions are -J^T mu;
//! - the applied forces: gravity, linear springs and their dampers, torsion springs and theirs,
//!   the bodies' damping (-m d v, -I d omega, rapier's continuous model), loads (constant or
//!   tabulated, world-fixed or following the body), translated from the level by
//!   `applied_forces`, which the linearization (`small_oscillations`) shares.
//!
//! Drift: an acceleration-level formulation leaves C and dC/dt to drift by the integration
//! error. Rather than Baumgarte terms (whose gains are a tuning that changes the dynamics), the
//! integration runs in segments of at most [`SEGMENT`] s and, at the end of each, the state is
//! projected back onto C = 0 and dC/dt = 0 in the mass metric (the smallest change of kinetic
//! energy: Gauss-Newton on positions, one linear solve on velocities). The largest |C| found
//! before a projection is reported ([`Trajectory::drift`]): on the double pendulum of the tests
//! it stays under 1e-12 m over 10 s (2026-12-06).
//!
//! Integrator: Dormand-Prince 8(5,3) (`differential-equations`' `dop853`, Hairer-Norsett-Wanner's
//! DOP853) at rtol [`RTOL`], atol [`ATOL`].
//!
//! Rolling contacts (`rolling`): a round body touching a fixed straight face or a fixed `Arc`
//! at the start, with no slip and no normal speed there, rolls without slip (RK-8), held by two
//! rows: the gap stays zero (multiplier -N) and the contact point's velocity along the face is
//! zero (multiplier -F). Both are holonomic on a fixed surface; the gap row is projected with
//! the joints, the tangent row at the velocity level. Every [`CONTACT_SEGMENT`] s the
//! textbook's assumptions are checked along the trajectory (N >= 0, |F| <= mu N with the
//! pair's mu as rapier combines it, the contact point on the face or the arc's sweep); the
//! first failure is located by bisection and the integration stops with the reason and the
//! time ("would slip at t = ... (needs |F|/N = ..., mu = ...)", "leaves the surface",
//! "rolls off the end"). Reactions: [`Instant::reactions`] (joints) and
//! [`Instant::contacts`] (rolling contacts), from the multipliers at the instant.
//!
//! Refused, with the reason ("not applicable: ..."): events (a blow or a weld on contact is an
//! impact), joint limits (one-sided stops), joints that start apart, position motors, motors with
//! a force limit, bodies without mass, more than
//! [`MAX_MOVING_BODIES`] dynamic bodies; after t = 0, a touch at the start it cannot hold (a body
//! that is not round, a moving other body, a corner, a slip or a normal speed at the start).
//! Contacts made later are not modelled: the caller must make sure none happens (the questions
//! check that the engine's run had none but the rolling ones before the reading).

mod rolling;

use crate::analysis::applied_forces::{AppliedForces, LinearSpring, Load, TorsionSpring};
use crate::analysis::mass::of_body;
use crate::analysis::{cross, k_cross};
use crate::level::motion::{pose_at, rate_at};
use crate::level::{
    BodyDef, BodyKind, Coordinate, Effect, EventDef, JointKind, Level, Motor, DEFAULT_DENSITY,
};
use crate::sim::profiles::{scalar_profile_at, vector_profile_at};
use differential_equations::prelude::*;
use glam::DVec2;
use nalgebra::{DMatrix, DVector};

/// Relative tolerance of the integration.
pub const RTOL: f64 = 1e-10;
/// Absolute tolerance (m, rad, m/s, rad/s).
pub const ATOL: f64 = 1e-12;
/// The longest stretch integrated between two projections onto the constraints, s.
pub const SEGMENT: f64 = 0.05;
/// The longest stretch between two checks of the rolling contacts' assumptions, s (a
/// violation found at a check is then located by bisection).
pub const CONTACT_SEGMENT: f64 = 0.01;
/// The most dynamic bodies the reference integrates (its linear algebra is dense).
pub const MAX_MOVING_BODIES: usize = 40;
/// What a report calls the reference.
pub const LABEL: &str = "reference trajectory (Dop853, rtol 1e-10)";

/// One body: its mass properties and either its coordinate slot or its prescribed motion.
#[derive(Debug, Clone)]
struct Body {
    def: BodyDef,
    slot: Option<usize>,
    mass: f64,
    inertia: f64,
    /// G in the body frame, m.
    com: DVec2,
    /// Damping rates, 1/s.
    linear_damping: f64,
    angular_damping: f64,
}

/// A body's motion at an instant: G, angle, their rates, and the known part of the
/// acceleration (a prescribed body's; zero for a dynamic one, whose acceleration is unknown).
#[derive(Debug, Clone, Copy)]
struct Now {
    slot: Option<usize>,
    g: DVec2,
    angle: f64,
    v: DVec2,
    omega: f64,
    a: DVec2,
    alpha: f64,
}

impl Now {
    /// The offset from G of the body-frame point p (given from the body origin).
    fn offset(&self, com: DVec2, p: DVec2) -> DVec2 {
        DVec2::from_angle(self.angle).rotate(p - com)
    }
    fn point_velocity(&self, d: DVec2) -> DVec2 {
        self.v + k_cross(self.omega, d)
    }
    /// The known part of the acceleration of the point at offset d: a + alpha k x d - omega^2 d
    /// (RK-10), with a and alpha zero for a dynamic body.
    fn point_known_acceleration(&self, d: DVec2) -> DVec2 {
        self.a + k_cross(self.alpha, d) - self.omega * self.omega * d
    }
}

/// What a constraint holds.
#[derive(Debug, Clone)]
enum Rule {
    /// w . (p2 - p1) = 0 for a fixed world direction w (a pin's or a weld's x and y rows).
    Points { w: DVec2 },
    /// n(theta1) . (p2 - p1) = c0, n turning with body1 (a slider's or a slot's line).
    Line { n_local: DVec2, c0: f64 },
    /// theta1 - theta2 = c0 (a weld's or a slider's relative angle).
    Angle { c0: f64 },
    /// The rate of the joint coordinate is `target` (an ideal velocity motor): theta2 - theta1
    /// for a pin, the slide along the axis for a slider. No position-level form.
    Rate {
        axis_local: Option<DVec2>,
        target: f64,
    },
    /// sum ratio_i q_i = c0 (a coupling), with the bodies that bear its cable's or its teeth's
    /// reaction.
    Ratio {
        terms: Vec<(usize, Coordinate, f64)>,
        c0: f64,
        carrier: Carrier,
    },
    /// Rolling contact `index` (`rolling`): its `normal` row (the gap stays zero; multiplier
    /// -N) or its tangent row (the contact point's velocity along the face is zero; -F).
    Roll { index: usize, normal: bool },
}

/// Who bears a coupling's reaction besides its terms' bodies (as the engine applies it,
/// `sim::couplings`): the pulley a cable runs over takes the opposite of the cable's pull on
/// the x and y terms at its G; meshing gears take the tooth force lambda sign(r_1) perp(u) (u
/// from gear 1's G to gear 2's) on gear 1 and its opposite on gear 2.
#[derive(Debug, Clone, Copy)]
enum Carrier {
    None,
    Over(usize),
    Gears(usize, usize, f64),
}

#[derive(Debug, Clone)]
struct Constraint {
    /// Index of the joint in the level (None for couplings).
    joint: Option<usize>,
    body1: usize,
    body2: usize,
    anchor1: DVec2,
    anchor2: DVec2,
    rule: Rule,
}

/// One row's value, rate, Jacobian row (over the 3n dynamic coordinates) and bias b
/// (C'' = J a + b), and the generalized force its multiplier puts on a carrier beyond J^T
/// (a coupling's pulley or gears; None for every other row).
struct Row {
    value: Option<f64>,
    rate: f64,
    j: Vec<f64>,
    bias: f64,
    carried: Option<Vec<f64>>,
}

/// A level's equations of motion, ready to integrate.
#[derive(Debug, Clone)]
pub struct Reference {
    bodies: Vec<Body>,
    /// Level index of each slot's body.
    slots: Vec<usize>,
    constraints: Vec<Constraint>,
    springs: Vec<LinearSpring>,
    torsions: Vec<TorsionSpring>,
    loads: Vec<Load>,
    gravity: DVec2,
    joint_count: usize,
    /// The rolling contacts found at the start (`rolling`).
    rolling: Vec<rolling::Rolling>,
    /// Why a touch at the start is outside the reference (then only t = 0 is read).
    untouched: Option<String>,
}

/// A body's state in the reference: G, angle and their rates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyMotion {
    pub com: DVec2,
    pub angle: f64,
    pub velocity: DVec2,
    pub omega: f64,
}

/// A joint's reaction on its body2: the force (world axes) at body2's anchor and the couple.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Reaction {
    pub force: DVec2,
    pub couple: f64,
}

/// A rolling contact's force on its round body at an instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactReaction {
    /// The round body's and the surface's level indices.
    pub body: usize,
    pub other: usize,
    /// The unit normal from the surface into the body, and the contact point, world.
    pub n: DVec2,
    pub point: DVec2,
    /// The normal force N along n (positive: a push) and the friction force F along t = k x n.
    pub normal: f64,
    pub tangential: f64,
}

/// The reference at one instant: every level body's motion, every level joint's reaction and
/// every rolling contact's force.
#[derive(Debug, Clone, PartialEq)]
pub struct Instant {
    pub t: f64,
    pub bodies: Vec<BodyMotion>,
    pub reactions: Vec<Reaction>,
    pub contacts: Vec<ContactReaction>,
}

/// The states at the requested times, and the integration's bookkeeping.
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory {
    pub instants: Vec<Instant>,
    /// The largest |C| (m for point rows, rad for angle rows, the coupling's units) found at a
    /// segment's end before its projection.
    pub drift: f64,
    /// Right-hand-side evaluations.
    pub evaluations: usize,
}

fn v2(p: (f64, f64)) -> DVec2 {
    DVec2::new(p.0, p.1)
}

impl Reference {
    /// The equations of motion of the whole level under its effects; Err("...") with the reason
    /// when the scene is outside the model (see the module's list).
    pub fn of_level(level: &Level) -> Result<Reference, String> {
        let has = |e: Effect| level.effects.contains(&e);
        let index = |n: &str| {
            level
                .bodies
                .iter()
                .position(|b| b.name == n)
                .ok_or_else(|| format!("no body \"{n}\""))
        };
        refuse_events(level)?;
        let forces = AppliedForces::of_level(level, &index)?;
        let bodies = collect_bodies(level, &forces)?;
        let slots: Vec<usize> = (0..bodies.len())
            .filter(|&k| bodies[k].slot.is_some())
            .collect();
        let mut r = Reference {
            bodies,
            slots,
            constraints: Vec::new(),
            springs: forces.springs,
            torsions: forces.torsion_springs,
            loads: forces.loads,
            gravity: forces.gravity,
            joint_count: level.joints.len(),
            rolling: Vec::new(),
            untouched: None,
        };
        // A touch the reference cannot hold leaves the start itself readable (t = 0).
        match rolling::rolling_contacts(level) {
            Ok(found) => r.rolling = found,
            Err(why) => r.untouched = Some(why),
        }
        if has(Effect::Joints) {
            for (k, j) in level.joints.iter().enumerate() {
                r.add_joint(
                    k,
                    j,
                    index(&j.body1)?,
                    index(&j.body2)?,
                    has(Effect::Motors),
                )?;
            }
            for c in &level.couplings {
                r.add_coupling(c, &index)?;
            }
        }
        if let Err(why) = r.add_rolling() {
            r.constraints
                .retain(|c| !matches!(c.rule, Rule::Roll { .. }));
            r.rolling.clear();
            r.untouched = Some(why);
        }
        Ok(r)
    }

    /// Why a reading after t = 0 is outside the reference because of a touch at the start it
    /// cannot hold (a body that is not round, a slip at the start...), if one is.
    pub fn refused_after_start(&self) -> Option<&str> {
        self.untouched.as_deref()
    }

    /// The longest stretch integrated between two projections: [`CONTACT_SEGMENT`] where the
    /// model rolls, else [`SEGMENT`] (the integrator restarts at each: the run budget prices it).
    pub fn stretch(&self) -> f64 {
        if self.rolling.is_empty() {
            SEGMENT
        } else {
            CONTACT_SEGMENT
        }
    }

    /// The constraint rows the model solves at each evaluation (a pin's two, a coupling's one,
    /// a rolling contact's two...).
    pub fn row_count(&self) -> usize {
        self.constraints.len()
    }

    /// Whether level body i is a dynamic body of the reference (one it integrates).
    pub fn moves(&self, i: usize) -> bool {
        self.bodies.get(i).is_some_and(|b| b.slot.is_some())
    }

    /// Whether the reference holds the contact of bodies a and b (level indices) as rolling.
    pub fn rolls(&self, a: usize, b: usize) -> bool {
        self.rolling
            .iter()
            .any(|c| (c.body, c.surface_body) == (a, b) || (c.body, c.surface_body) == (b, a))
    }

    /// The rolling contacts' rows, once their start is checked: the disc touches (the
    /// projection closes the level's rounding) and neither approaches, lifts off nor slips
    /// (slip or normal speed within 1e-6 of the disc's speed, at least 1e-6 m/s).
    fn add_rolling(&mut self) -> Result<(), String> {
        for (index, c) in self.rolling.iter().enumerate() {
            for normal in [true, false] {
                self.constraints.push(Constraint {
                    joint: None,
                    body1: c.surface_body,
                    body2: c.body,
                    anchor1: DVec2::ZERO,
                    anchor2: c.center,
                    rule: Rule::Roll { index, normal },
                });
            }
        }
        let y = self.initial_state();
        let now = self.state_now(0.0, &y);
        let rows = self.rows(&now);
        for (row, c) in rows.iter().zip(&self.constraints) {
            let Rule::Roll { index, normal } = c.rule else {
                continue;
            };
            let x = &now[c.body2];
            let tol = 1e-6 * x.v.length().max(1.0);
            let pair = &self.rolling[index].pair;
            if row.rate.abs() > tol {
                return Err(if normal {
                    format!(
                        "{pair} {} at the start ({:.3e} m/s along the normal): an impact or a lift-off is outside the reference",
                        if row.rate < 0.0 { "approaches" } else { "moves off" },
                        row.rate.abs()
                    )
                } else {
                    format!(
                        "{pair} slips at the start (slip speed {:.3e} m/s): sliding friction is outside the reference",
                        row.rate.abs()
                    )
                });
            }
        }
        Ok(())
    }

    fn add_joint(
        &mut self,
        k: usize,
        j: &crate::level::JointDef,
        b1: usize,
        b2: usize,
        motors: bool,
    ) -> Result<(), String> {
        let name = &j.name;
        if j.starts_apart {
            return Err(format!(
                "joint \"{name}\" starts apart (the engine snaps it shut: an impulsive start)"
            ));
        }
        if j.limits.is_some() {
            return Err(format!(
                "joint \"{name}\" has limits (a one-sided stop is an impact)"
            ));
        }
        let axis = v2(j.axis).normalize_or(DVec2::X);
        let (a1, a2) = (self.bodies[b1].def.angle, self.bodies[b2].def.angle);
        let base = Constraint {
            joint: Some(k),
            body1: b1,
            body2: b2,
            anchor1: v2(j.anchor1),
            anchor2: v2(j.anchor2),
            rule: Rule::Angle { c0: a1 - a2 },
        };
        let with = |rule: Rule| Constraint {
            rule,
            ..base.clone()
        };
        let points = [
            with(Rule::Points { w: DVec2::X }),
            with(Rule::Points { w: DVec2::Y }),
        ];
        let line = with(Rule::Line {
            n_local: axis.perp(),
            c0: 0.0,
        });
        match j.kind {
            JointKind::Revolute => self.constraints.extend(points),
            JointKind::Fixed => {
                self.constraints.extend(points);
                self.constraints.push(base.clone());
            }
            JointKind::Prismatic => {
                self.constraints.push(line);
                self.constraints.push(base.clone());
            }
            JointKind::PinSlot => self.constraints.push(line),
        }
        if let (true, Some(m)) = (motors, &j.motor) {
            match m {
                Motor::Velocity {
                    target,
                    max_force: None,
                } => {
                    let axis_local = match j.kind {
                        JointKind::Revolute => None,
                        JointKind::Prismatic => Some(axis),
                        _ => {
                            return Err(format!(
                                "joint \"{name}\" is a {} with a motor",
                                j.kind.describe()
                            ))
                        }
                    };
                    self.constraints.push(with(Rule::Rate {
                        axis_local,
                        target: *target,
                    }));
                }
                Motor::Velocity { .. } => {
                    return Err(format!(
                        "joint \"{name}\"'s motor has a force limit (it may saturate)"
                    ))
                }
                Motor::Position { .. } => {
                    return Err(format!(
                    "joint \"{name}\" has a position motor (a servo the reference does not model)"
                ))
                }
            }
        }
        Ok(())
    }

    fn add_coupling(
        &mut self,
        c: &crate::level::CouplingDef,
        index: &dyn Fn(&str) -> Result<usize, String>,
    ) -> Result<(), String> {
        let terms: Vec<(usize, Coordinate, f64)> = c
            .terms
            .iter()
            .map(|t| Ok((index(&t.body)?, t.coordinate, t.ratio)))
            .collect::<Result<_, String>>()?;
        let carrier = match (&c.over, c.gears) {
            (Some(over), _) => Carrier::Over(index(over)?),
            (None, true) if terms.len() == 2 => {
                Carrier::Gears(terms[0].0, terms[1].0, terms[0].2.signum())
            }
            _ => Carrier::None,
        };
        let mut rule = Rule::Ratio {
            terms,
            c0: 0.0,
            carrier,
        };
        let now: Vec<Now> = self.state_now(0.0, &self.initial_state());
        if let Rule::Ratio { terms, c0, .. } = &mut rule {
            *c0 = terms
                .iter()
                .map(|&(k, c, r)| r * coordinate(&now[k], c))
                .sum();
        }
        self.constraints.push(Constraint {
            joint: None,
            body1: 0,
            body2: 0,
            anchor1: DVec2::ZERO,
            anchor2: DVec2::ZERO,
            rule,
        });
        Ok(())
    }

    /// The number of coordinates, 3 per dynamic body.
    fn n(&self) -> usize {
        3 * self.slots.len()
    }

    /// The level's start: positions then velocities.
    fn initial_state(&self) -> Vec<f64> {
        let n = self.n();
        let mut y = vec![0.0; 2 * n];
        for (s, &k) in self.slots.iter().enumerate() {
            let b = &self.bodies[k];
            let turn = DVec2::from_angle(b.def.angle);
            let g = v2(b.def.position) + turn.rotate(b.com);
            // The level gives the body origin's velocity; G's adds omega k x (G - origin).
            let v = v2(b.def.velocity) + k_cross(b.def.omega, turn.rotate(b.com));
            y[3 * s..3 * s + 3].copy_from_slice(&[g.x, g.y, b.def.angle]);
            y[n + 3 * s..n + 3 * s + 3].copy_from_slice(&[v.x, v.y, b.def.omega]);
        }
        y
    }

    /// Every body's motion at t in state y.
    fn state_now(&self, t: f64, y: &[f64]) -> Vec<Now> {
        let n = self.n();
        self.bodies
            .iter()
            .map(|b| match b.slot {
                Some(s) => Now {
                    slot: Some(s),
                    g: DVec2::new(y[3 * s], y[3 * s + 1]),
                    angle: y[3 * s + 2],
                    v: DVec2::new(y[n + 3 * s], y[n + 3 * s + 1]),
                    omega: y[n + 3 * s + 2],
                    a: DVec2::ZERO,
                    alpha: 0.0,
                },
                None => prescribed(b, t),
            })
            .collect()
    }

    /// The constraint rows for the bodies' motion `now`.
    fn rows(&self, now: &[Now]) -> Vec<Row> {
        let n = self.n();
        self.constraints
            .iter()
            .map(|c| self.row(c, now, n))
            .collect()
    }

    fn row(&self, c: &Constraint, now: &[Now], n: usize) -> Row {
        let mut j = vec![0.0; n];
        let mut add = |s: Option<usize>, i: usize, x: f64| {
            if let Some(s) = s {
                j[3 * s + i] += x;
            }
        };
        let (n1, n2) = (&now[c.body1], &now[c.body2]);
        let d1 = n1.offset(self.bodies[c.body1].com, c.anchor1);
        let d2 = n2.offset(self.bodies[c.body2].com, c.anchor2);
        let (p1, p2) = (n1.g + d1, n2.g + d2);
        let (vp1, vp2) = (n1.point_velocity(d1), n2.point_velocity(d2));
        let known = n2.point_known_acceleration(d2) - n1.point_known_acceleration(d1);
        // Adds w . (a_P2 - a_P1)'s unknown part to the row; returns its known part.
        let point_terms = |w: DVec2, add: &mut dyn FnMut(Option<usize>, usize, f64)| {
            add(n2.slot, 0, w.x);
            add(n2.slot, 1, w.y);
            add(n2.slot, 2, w.dot(d2.perp()));
            add(n1.slot, 0, -w.x);
            add(n1.slot, 1, -w.y);
            add(n1.slot, 2, -w.dot(d1.perp()));
            w.dot(known)
        };
        let mut carried = None;
        let (value, rate, bias) = match &c.rule {
            Rule::Points { w } => {
                let b = point_terms(*w, &mut add);
                (Some(w.dot(p2 - p1)), w.dot(vp2 - vp1), b)
            }
            Rule::Line { n_local, c0 } => {
                let (value, rate, bias) = line_row(n1, *n_local, p2 - p1, vp2 - vp1);
                let b = point_terms(DVec2::from_angle(n1.angle).rotate(*n_local), &mut add);
                // n'' . Delta's alpha1 term: alpha1 (k x n) . Delta.
                let nw = DVec2::from_angle(n1.angle).rotate(*n_local);
                add(n1.slot, 2, nw.perp().dot(p2 - p1));
                (Some(value - c0), rate, bias + b)
            }
            Rule::Angle { c0 } => {
                add(n1.slot, 2, 1.0);
                add(n2.slot, 2, -1.0);
                (
                    Some(n1.angle - n2.angle - c0),
                    n1.omega - n2.omega,
                    n1.alpha - n2.alpha,
                )
            }
            Rule::Rate { axis_local, target } => match axis_local {
                None => {
                    add(n2.slot, 2, 1.0);
                    add(n1.slot, 2, -1.0);
                    (None, n2.omega - n1.omega - target, n2.alpha - n1.alpha)
                }
                Some(u) => {
                    let (_, rate, bias) = line_row(n1, *u, p2 - p1, vp2 - vp1);
                    let uw = DVec2::from_angle(n1.angle).rotate(*u);
                    let b = point_terms(uw, &mut add);
                    add(n1.slot, 2, uw.perp().dot(p2 - p1));
                    (None, rate - target, bias + b)
                }
            },
            Rule::Ratio { terms, c0, carrier } => {
                carried = carried_force(*carrier, terms, now, n);
                let mut value = -c0;
                let (mut rate, mut bias) = (0.0, 0.0);
                for &(k, c, r) in terms {
                    let b = &now[k];
                    let i = match c {
                        Coordinate::X => 0,
                        Coordinate::Y => 1,
                        Coordinate::Angle => 2,
                    };
                    add(b.slot, i, r);
                    value += r * coordinate(b, c);
                    rate += r * [b.v.x, b.v.y, b.omega][i];
                    bias += r * [b.a.x, b.a.y, b.alpha][i];
                }
                (Some(value), rate, bias)
            }
            Rule::Roll { index, normal } => {
                let rc = &self.rolling[*index];
                let (c_pos, v_c) = (n2.g + d2, vp2);
                let fr = rc.surface.frame(c_pos, v_c, rc.radius);
                let w2 = n2.omega * n2.omega;
                if *normal {
                    // gap'' = n . a_C + curvature, a_C = a_G + alpha k x d - omega^2 d.
                    add(n2.slot, 0, fr.n.x);
                    add(n2.slot, 1, fr.n.y);
                    add(n2.slot, 2, fr.n.dot(d2.perp()));
                    (
                        Some(fr.gap),
                        fr.n.dot(v_c),
                        fr.curvature - w2 * fr.n.dot(d2),
                    )
                } else {
                    // t . v_P = 0 for the material point P at d_c = d - r n from G; its rate
                    // t . a_G + alpha t . perp(d_c) + t' . v_P - omega^2 t . d (t . perp(n') = 0).
                    let t = fr.n.perp();
                    let dc = d2 - rc.radius * fr.n;
                    let vp = n2.v + k_cross(n2.omega, dc);
                    add(n2.slot, 0, t.x);
                    add(n2.slot, 1, t.y);
                    add(n2.slot, 2, t.dot(dc.perp()));
                    (None, t.dot(vp), fr.n_rate.perp().dot(vp) - w2 * t.dot(d2))
                }
            }
        };
        Row {
            value,
            rate,
            j,
            bias,
            carried,
        }
    }

    /// The applied forces on the coordinates (F_x, F_y, M_G per dynamic body) at t.
    fn forces(&self, t: f64, now: &[Now]) -> Vec<f64> {
        let mut f = vec![0.0; self.n()];
        let mut push = |k: usize, force: DVec2, d: DVec2, couple: f64| {
            if let Some(s) = now[k].slot {
                f[3 * s] += force.x;
                f[3 * s + 1] += force.y;
                f[3 * s + 2] += cross(d, force) + couple;
            }
        };
        for (k, b) in self.bodies.iter().enumerate() {
            if b.slot.is_some() {
                let x = &now[k];
                let damping = -b.mass * b.linear_damping * x.v;
                push(k, b.mass * self.gravity + damping, DVec2::ZERO, 0.0);
                push(
                    k,
                    DVec2::ZERO,
                    DVec2::ZERO,
                    -b.inertia * b.angular_damping * x.omega,
                );
            }
        }
        for s in &self.springs {
            // MK 3/5 with a dashpot: the pull on body1 toward body2 is k (L - L0) + c L'.
            let x1 = &now[s.body1];
            let d1 = x1.offset(self.bodies[s.body1].com, s.point1);
            let (p1, v1) = (x1.g + d1, x1.point_velocity(d1));
            let (p2, v2_, d2) = match s.body2 {
                Some(k) => {
                    let x2 = &now[k];
                    let d2 = x2.offset(self.bodies[k].com, s.point2);
                    (x2.g + d2, x2.point_velocity(d2), d2)
                }
                None => (s.point2, DVec2::ZERO, DVec2::ZERO),
            };
            let r = p2 - p1;
            let length = r.length();
            let u = if length > 0.0 {
                r / length
            } else {
                DVec2::ZERO
            };
            let pull = s.stiffness * (length - s.rest_length) + s.damping * u.dot(v2_ - v1);
            push(s.body1, pull * u, d1, 0.0);
            if let Some(k) = s.body2 {
                push(k, -pull * u, d2, 0.0);
            }
        }
        for s in &self.torsions {
            let (a2, w2) = s.body2.map_or((0.0, 0.0), |k| (now[k].angle, now[k].omega));
            let x1 = &now[s.body1];
            let m = -s.stiffness * (x1.angle - a2 - s.rest_angle) - s.damping * (x1.omega - w2);
            push(s.body1, DVec2::ZERO, DVec2::ZERO, m);
            if let Some(k) = s.body2 {
                push(k, DVec2::ZERO, DVec2::ZERO, -m);
            }
        }
        for l in &self.loads {
            let x = &now[l.body];
            let d = x.offset(self.bodies[l.body].com, l.point);
            let mut force = l
                .force
                .as_ref()
                .map_or(DVec2::ZERO, |p| v2(vector_profile_at(p, t)));
            if l.follow_body {
                force = DVec2::from_angle(x.angle).rotate(force);
            }
            let couple = l.torque.as_ref().map_or(0.0, |p| scalar_profile_at(p, t));
            push(l.body, force, d, couple);
        }
        f
    }

    /// The inverse mass matrix's diagonal (a locked rotation has an infinite inertia).
    fn inverse_mass(&self) -> DVector<f64> {
        let mut w = DVector::zeros(self.n());
        for (s, &k) in self.slots.iter().enumerate() {
            let b = &self.bodies[k];
            w[3 * s] = 1.0 / b.mass;
            w[3 * s + 1] = 1.0 / b.mass;
            w[3 * s + 2] = if b.def.lock_rotation {
                0.0
            } else {
                1.0 / b.inertia
            };
        }
        w
    }

    /// The accelerations and the multipliers mu (reactions -J^T mu) at t in state y.
    fn accelerations(&self, t: f64, y: &[f64]) -> (DVector<f64>, Vec<Row>, DVector<f64>) {
        let now = self.state_now(t, y);
        let f = DVector::from_vec(self.forces(t, &now));
        let w = self.inverse_mass();
        let rows = self.rows(&now);
        let free = f.component_mul(&w);
        if rows.is_empty() {
            return (free, rows, DVector::zeros(0));
        }
        let jac = jacobian(&rows, self.n());
        let jw = scale_columns(&jac, &w);
        let rhs = &jac * &free + DVector::from_iterator(rows.len(), rows.iter().map(|r| r.bias));
        if rows.iter().all(|r| r.carried.is_none()) {
            let mu = solve_spd(&jw * jac.transpose(), rhs);
            let acc = free - jw.transpose() * &mu;
            return (acc, rows, mu);
        }
        // A carrier's load makes the generalized reaction P^T lambda with P = J + K (K the
        // carried columns): M a + P^T mu = F, J a = -b gives (J W P^T) mu = J W F + b, no
        // longer symmetric: LU, or the SVD's least-squares solution if it is singular.
        let p = DMatrix::from_fn(rows.len(), self.n(), |i, k| {
            rows[i].j[k] + rows[i].carried.as_ref().map_or(0.0, |c| c[k])
        });
        let pw = scale_columns(&p, &w);
        let a_mat = &jac * pw.transpose();
        let mu = a_mat
            .clone()
            .lu()
            .solve(&rhs)
            .filter(|x| x.iter().all(|v| v.is_finite()))
            .unwrap_or_else(|| {
                let scale = a_mat.amax().max(f64::MIN_POSITIVE);
                a_mat
                    .svd(true, true)
                    .solve(&rhs, 1e-12 * scale)
                    .unwrap_or_else(|_| DVector::zeros(rhs.len()))
            });
        let acc = free - pw.transpose() * &mu;
        (acc, rows, mu)
    }

    /// Projects y onto C = 0 and dC/dt = 0 at t in the mass metric; returns max |C| before.
    fn project(&self, t: f64, y: &mut [f64]) -> f64 {
        let n = self.n();
        let w = self.inverse_mass();
        let mut before = None;
        for _ in 0..20 {
            let now = self.state_now(t, y);
            let rows = self.rows(&now);
            let held: Vec<&Row> = rows.iter().filter(|r| r.value.is_some()).collect();
            let c: Vec<f64> = held.iter().map(|r| r.value.unwrap_or(0.0)).collect();
            let worst = c.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
            before.get_or_insert(worst);
            if worst < 1e-14 || held.is_empty() {
                break;
            }
            let jac = DMatrix::from_fn(held.len(), n, |i, k| held[i].j[k]);
            let dq = correction(&jac, &w, DVector::from_vec(c));
            for i in 0..n {
                y[i] -= dq[i];
            }
        }
        let now = self.state_now(t, y);
        let rows = self.rows(&now);
        if !rows.is_empty() {
            let jac = jacobian(&rows, n);
            let rate = DVector::from_iterator(rows.len(), rows.iter().map(|r| r.rate));
            let dv = correction(&jac, &w, rate);
            for i in 0..n {
                y[n + i] -= dv[i];
            }
        }
        before.unwrap_or(0.0)
    }

    /// The reference at the given times (any order, each >= 0): integrated from the level's
    /// start, projected onto the constraints at the start (the level's anchors meet within 0.1
    /// mm, not exactly) and at each segment's end. Err when the integrator fails.
    pub fn integrate(&self, times: &[f64]) -> Result<Trajectory, String> {
        if let Some(why) = self
            .untouched
            .as_ref()
            .filter(|_| times.iter().any(|t| *t != 0.0))
        {
            return Err(why.clone());
        }
        let mut order: Vec<usize> = (0..times.len()).collect();
        order.sort_by(|&a, &b| times[a].total_cmp(&times[b]));
        let mut y = self.initial_state();
        let mut t = 0.0;
        self.project(t, &mut y);
        if let Some(why) = self.violation(t, &y) {
            return Err(why);
        }
        let stretch = self.stretch();
        let mut drift: f64 = 0.0;
        let mut evaluations = 0;
        let mut out: Vec<Option<Instant>> = vec![None; times.len()];
        for &i in &order {
            let target = times[i];
            if !(target.is_finite() && target >= 0.0) {
                return Err(format!("cannot integrate to t = {target}"));
            }
            while t < target {
                let t1 = (t + stretch).min(target);
                let (mut y1, evals) = self.segment(t, t1, &y)?;
                evaluations += evals;
                drift = drift.max(self.project(t1, &mut y1));
                if self.violation(t1, &y1).is_some() {
                    return Err(self.first_violation(t, &y, t1));
                }
                y = y1;
                t = t1;
            }
            out[i] = Some(self.instant(t, &y));
        }
        Ok(Trajectory {
            instants: out.into_iter().map(|x| x.expect("every time")).collect(),
            drift,
            evaluations,
        })
    }

    /// Why the state y at t is outside the textbook's rolling without slip, where a rolling
    /// contact's normal force is negative (the disc would leave the surface), its friction
    /// exceeds mu N (it would slip), or its contact point has run off the surface's end. The
    /// forces are the multipliers', judged within 1e-9 of the disc's weight (round-off).
    fn violation(&self, t: f64, y: &[f64]) -> Option<String> {
        if self.rolling.is_empty() {
            return None;
        }
        let now = self.state_now(t, y);
        let (_, _, mu) = self.accelerations(t, y);
        for (c, rc) in self.contact_forces(&now, &mu).iter().zip(&self.rolling) {
            let x = &now[rc.body];
            let d = x.offset(self.bodies[rc.body].com, rc.center);
            let on = rc.surface.frame(x.g + d, x.v, rc.radius).on_surface;
            let (name, surface) = (
                &self.bodies[rc.body].def.name,
                &self.bodies[rc.surface_body].def.name,
            );
            let weight = self.bodies[rc.body].mass * self.gravity.length();
            let round_off = 1e-9 * (weight + c.normal.abs()) + 1e-12;
            if c.normal < -round_off {
                return Some(format!(
                    "outside the reference: \"{name}\" leaves the surface of \"{surface}\" at t = {t:.5} s (rolling on it needs a normal force of {:.4e} N, a pull)",
                    c.normal
                ));
            }
            if c.tangential.abs() > rc.mu * c.normal + round_off {
                let ratio = if c.normal > 0.0 {
                    format!("{:.4}", c.tangential.abs() / c.normal)
                } else {
                    "inf".into()
                };
                return Some(format!(
                    "outside the reference: \"{name}\" would slip on \"{surface}\" at t = {t:.5} s (needs |F|/N = {ratio}, mu = {})",
                    rc.mu
                ));
            }
            if !on {
                return Some(format!(
                    "outside the reference: \"{name}\" rolls off the end of \"{surface}\" at t = {t:.5} s"
                ));
            }
        }
        None
    }

    /// The first violation (`violation`) between t0 (state y0, none there) and t1 (one),
    /// located by bisection to 1e-10 of the stretch.
    fn first_violation(&self, t0: f64, y0: &[f64], t1: f64) -> String {
        let at = |t: f64| -> Option<(Vec<f64>, Option<String>)> {
            let (mut y, _) = self.segment(t0, t, y0).ok()?;
            self.project(t, &mut y);
            let why = self.violation(t, &y);
            Some((y, why))
        };
        let (mut lo, mut hi) = (t0, t1);
        for _ in 0..34 {
            let mid = 0.5 * (lo + hi);
            match at(mid) {
                Some((_, Some(_))) => hi = mid,
                Some((_, None)) => lo = mid,
                None => break,
            }
        }
        at(hi)
            .and_then(|(_, why)| why)
            .unwrap_or_else(|| format!("outside the reference from t = {hi:.5} s"))
    }

    /// The rolling contacts' forces on their discs in the motion `now`, from the multipliers.
    fn contact_forces(&self, now: &[Now], mu: &DVector<f64>) -> Vec<ContactReaction> {
        let mut out = Vec::with_capacity(self.rolling.len());
        for (r, c) in self.constraints.iter().enumerate() {
            let Rule::Roll {
                index,
                normal: true,
            } = c.rule
            else {
                continue;
            };
            let rc = &self.rolling[index];
            let x = &now[rc.body];
            let d = x.offset(self.bodies[rc.body].com, rc.center);
            let fr = rc.surface.frame(x.g + d, x.point_velocity(d), rc.radius);
            // The tangent row follows the normal row (`add_rolling`); reactions are -J^T mu.
            out.push(ContactReaction {
                body: rc.body,
                other: rc.surface_body,
                n: fr.n,
                point: x.g + d - rc.radius * fr.n,
                normal: -mu[r],
                tangential: -mu[r + 1],
            });
        }
        out
    }

    fn segment(&self, t0: f64, t1: f64, y: &[f64]) -> Result<(Vec<f64>, usize), String> {
        let system = System(self);
        let method = ExplicitRungeKutta::dop853()
            .rtol(RTOL)
            .atol(ATOL)
            .max_steps(100_000);
        let solution = IVP::ode(&system, t0, t1, y.to_vec())
            .method(method)
            .solve()
            .map_err(|e| format!("the integrator stopped: {e:?}"))?;
        let evals = solution.evals.function;
        let (_, y1) = solution
            .last()
            .map_err(|e| format!("the integrator gave no state: {e}"))?;
        Ok((y1.clone(), evals))
    }

    /// The motions and reactions at t in state y.
    fn instant(&self, t: f64, y: &[f64]) -> Instant {
        let now = self.state_now(t, y);
        let (_, rows, mu) = self.accelerations(t, y);
        let mut reactions = vec![Reaction::default(); self.joint_count];
        for (r, (row, c)) in rows.iter().zip(&self.constraints).enumerate() {
            let Some(k) = c.joint else { continue };
            let lambda = -mu[r];
            let (j2, d2) = (
                self.row_on(c, row, c.body2, &now, lambda),
                now[c.body2].offset(self.bodies[c.body2].com, c.anchor2),
            );
            // The row's generalized force on body2 (F, M_G) as a force at the anchor and a couple.
            reactions[k].force += j2.0;
            reactions[k].couple += j2.1 - cross(d2, j2.0);
        }
        Instant {
            t,
            bodies: now
                .iter()
                .map(|x| BodyMotion {
                    com: x.g,
                    angle: x.angle,
                    velocity: x.v,
                    omega: x.omega,
                })
                .collect(),
            reactions,
            contacts: self.contact_forces(&now, &mu),
        }
    }

    /// The generalized force lambda J_row on body k: (force, moment about G). For a prescribed
    /// body (no slot) it is the row's coefficients computed as if it moved: the same rows
    /// written with the bodies' roles only (a pin's force on body2 is lambda w).
    fn row_on(
        &self,
        c: &Constraint,
        row: &Row,
        k: usize,
        now: &[Now],
        lambda: f64,
    ) -> (DVec2, f64) {
        if let Some(s) = now[k].slot {
            return (
                lambda * DVec2::new(row.j[3 * s], row.j[3 * s + 1]),
                lambda * row.j[3 * s + 2],
            );
        }
        // body2 is not a coordinate: its row coefficients, written out.
        let x2 = &now[k];
        let d2 = x2.offset(self.bodies[k].com, c.anchor2);
        let w = match &c.rule {
            Rule::Points { w } => *w,
            Rule::Line { n_local, .. } => DVec2::from_angle(now[c.body1].angle).rotate(*n_local),
            Rule::Rate {
                axis_local: Some(u),
                ..
            } => DVec2::from_angle(now[c.body1].angle).rotate(*u),
            Rule::Angle { .. } => return (DVec2::ZERO, -lambda),
            Rule::Rate {
                axis_local: None, ..
            } => return (DVec2::ZERO, lambda),
            Rule::Ratio { .. } | Rule::Roll { .. } => return (DVec2::ZERO, 0.0),
        };
        (lambda * w, lambda * cross(d2, w))
    }
}

/// A line row: value n . Delta, rate d/dt (n . Delta) and the known part of its second
/// derivative beyond n . Delta'' (n'' . Delta with alpha1's known part, + 2 n' . Delta').
/// n = R(theta1) n_local: n' = omega1 k x n, n'' = alpha1 k x n - omega1^2 n.
fn line_row(n1: &Now, n_local: DVec2, delta: DVec2, delta_rate: DVec2) -> (f64, f64, f64) {
    let n = DVec2::from_angle(n1.angle).rotate(n_local);
    let n_rate = k_cross(n1.omega, n);
    let value = n.dot(delta);
    let rate = n_rate.dot(delta) + n.dot(delta_rate);
    let known =
        (k_cross(n1.alpha, n) - n1.omega * n1.omega * n).dot(delta) + 2.0 * n_rate.dot(delta_rate);
    (value, rate, known)
}

/// The generalized force per unit multiplier a coupling puts on its carriers ([`Carrier`]):
/// None when it has none, or none of them is a coordinate.
fn carried_force(
    carrier: Carrier,
    terms: &[(usize, Coordinate, f64)],
    now: &[Now],
    n: usize,
) -> Option<Vec<f64>> {
    let mut k = vec![0.0; n];
    let mut put = |body: usize, f: DVec2| {
        if let Some(s) = now[body].slot {
            k[3 * s] += f.x;
            k[3 * s + 1] += f.y;
        }
    };
    match carrier {
        Carrier::None => return None,
        Carrier::Over(c) => {
            // The opposite of the cable's pull r_i lambda on the x and y terms.
            let pull: DVec2 = terms
                .iter()
                .map(|&(_, coord, r)| match coord {
                    Coordinate::X => DVec2::new(r, 0.0),
                    Coordinate::Y => DVec2::new(0.0, r),
                    Coordinate::Angle => DVec2::ZERO,
                })
                .sum();
            put(c, -pull);
        }
        Carrier::Gears(g1, g2, sign) => {
            let u = (now[g2].g - now[g1].g).normalize_or(DVec2::X);
            put(g1, sign * u.perp());
            put(g2, -sign * u.perp());
        }
    }
    k.iter().any(|x| *x != 0.0).then_some(k)
}

fn coordinate(b: &Now, c: Coordinate) -> f64 {
    match c {
        Coordinate::X => b.g.x,
        Coordinate::Y => b.g.y,
        Coordinate::Angle => b.angle,
    }
}

/// A fixed or kinematic body's motion at t (its G's pose, rates and acceleration).
fn prescribed(b: &Body, t: f64) -> Now {
    let fixed = b.def.kind == BodyKind::Fixed;
    // A fixed body stays where the level puts it, whatever velocity it declares.
    let (origin, angle, rate) = if fixed {
        (v2(b.def.position), b.def.angle, None)
    } else {
        let pose = pose_at(&b.def, t);
        (v2(pose.linear), pose.angular, Some(rate_at(&b.def, t)))
    };
    let c = DVec2::from_angle(angle).rotate(b.com);
    let (v, omega) = rate.map_or((DVec2::ZERO, 0.0), |r| (v2(r.linear), r.angular));
    let (a, alpha) = match (fixed, b.def.motion) {
        (false, Some(m)) => {
            let acc = m.acceleration_at(t);
            (v2(acc.linear), acc.angular)
        }
        _ => (DVec2::ZERO, 0.0),
    };
    Now {
        slot: None,
        g: origin + c,
        angle,
        v: v + k_cross(omega, c),
        omega,
        a: a + k_cross(alpha, c) - omega * omega * c,
        alpha,
    }
}

fn refuse_events(level: &Level) -> Result<(), String> {
    match level.events.first() {
        None => Ok(()),
        Some(EventDef::Impulse { name, at, .. }) => Err(format!(
            "the blow \"{name}\" at t = {at} s is an impulsive event"
        )),
        Some(EventDef::WeldOnContact { name, .. }) => {
            Err(format!("the weld on contact \"{name}\" needs a contact"))
        }
    }
}

fn collect_bodies(level: &Level, forces: &AppliedForces) -> Result<Vec<Body>, String> {
    let mut slot = 0;
    let mut bodies = Vec::with_capacity(level.bodies.len());
    for b in &level.bodies {
        let mp = of_body(b, DEFAULT_DENSITY);
        let moves = b.kind == BodyKind::Dynamic;
        if moves {
            if !(mp.mass.is_finite() && mp.mass > 0.0) {
                return Err(format!("body \"{}\" has no mass", b.name));
            }
            let has_inertia = mp.inertia.is_finite() && mp.inertia > 0.0;
            if !b.lock_rotation && !has_inertia {
                return Err(format!("body \"{}\" has no moment of inertia", b.name));
            }
        }
        let (linear_damping, angular_damping) = forces.body_damping(b);
        bodies.push(Body {
            def: b.clone(),
            slot: moves.then(|| {
                slot += 1;
                slot - 1
            }),
            mass: mp.mass,
            inertia: mp.inertia,
            com: mp.com,
            linear_damping,
            angular_damping,
        });
    }
    if slot > MAX_MOVING_BODIES {
        return Err(format!(
            "the scene has {slot} dynamic bodies; the reference integrates at most {MAX_MOVING_BODIES}"
        ));
    }
    if slot == 0 {
        return Err("no body of the scene moves".into());
    }
    Ok(bodies)
}

fn jacobian(rows: &[Row], n: usize) -> DMatrix<f64> {
    DMatrix::from_fn(rows.len(), n, |i, k| rows[i].j[k])
}

fn scale_columns(m: &DMatrix<f64>, w: &DVector<f64>) -> DMatrix<f64> {
    let mut out = m.clone();
    for (k, mut col) in out.column_iter_mut().enumerate() {
        col *= w[k];
    }
    out
}

/// Solves A x = b for the symmetric positive semi-definite A = J W J^T: Cholesky, or the SVD's
/// minimum-norm solution when constraints are redundant (a closed loop's repeated rows).
fn solve_spd(a: DMatrix<f64>, b: DVector<f64>) -> DVector<f64> {
    if let Some(ch) = a.clone().cholesky() {
        let x = ch.solve(&b);
        if x.iter().all(|v| v.is_finite()) {
            return x;
        }
    }
    let scale = a.amax().max(f64::MIN_POSITIVE);
    a.svd(true, true)
        .solve(&b, 1e-12 * scale)
        .unwrap_or_else(|_| DVector::zeros(b.len()))
}

/// The mass-metric correction W J^T (J W J^T)^+ r that removes the residual r of J x = r.
fn correction(jac: &DMatrix<f64>, w: &DVector<f64>, r: DVector<f64>) -> DVector<f64> {
    let jw = scale_columns(jac, w);
    let a = &jw * jac.transpose();
    jw.transpose() * solve_spd(a, r)
}

/// The first-order system y' = (v, a(t, q, v)) the integrator sees.
struct System<'a>(&'a Reference);

impl ODE<f64, Vec<f64>> for System<'_> {
    fn diff(&self, t: f64, y: &Vec<f64>, dydt: &mut Vec<f64>) {
        let n = self.0.n();
        let (acc, _, _) = self.0.accelerations(t, y);
        dydt[..n].copy_from_slice(&y[n..]);
        for i in 0..n {
            dydt[n + i] = acc[i];
        }
    }
}
