//! Work, energy and power quantities: kinetic energy, the works of gravity, springs, loads and
//! friction, a load's power, and a spring's extension.
//!
//! The engine's works are summed step by step with the step's mean velocity (exact for a rigid
//! body, see `step_work::held_work`); the analyses are the textbook's path-independent forms (10.2.18,
//! 10.2.21, 10.3.2), work-energy (RE-7) and the Coulomb law (WE-6).

use super::contact_reading::SLIDING;
use super::meter::{EngineAndAnalysis, Meter};
use super::sample::{Occasion, Sample};
use super::snapshot_reading::to_local;
use super::step_work::{held_work, path_work};
use crate::analysis::energy::{
    body_kinetic_energy, coulomb_friction_work_on_body, damper_work, friction_pair_loss,
    friction_work_on_body, mechanical_efficiency, power,
};
use crate::analysis::impact::{pair_normal_impulse, pushes_impulsively};
use crate::analysis::kinematics::{body_point_velocity, contact_sag, point_velocity};
use crate::analysis::kinetics::contact_arms_at_start;
use crate::analysis::momentum::{linear_momentum, velocities_after_impulses};
use crate::analysis::Motion;
use crate::level::{JointKind, Quantity};
use crate::snapshot::{BodyKind, BodyState, Snapshot, SpringState};
use glam::DVec2;

/// What a work or power quantity accumulates over the run.
#[derive(Clone)]
pub(super) struct State {
    /// Running sum of the engine's work, J.
    pub engine_sum: f64,
    /// Running sum for the analysis: path work of springs, loads and events on the body
    /// (work-energy analyses), or friction's Coulomb work, J.
    pub analysis_sum: f64,
    /// `LoadWork`: the first load seen (force, couple, point, body angle) and whether it stayed equal.
    pub first_load: Option<(DVec2, f64, DVec2, f64)>,
    pub load_constant: bool,
    /// `Efficiency`: the input's work since the start (engine), J, and, when the input is a
    /// load, its first (force, couple, point, body angle) and whether it stayed equal.
    pub input_work: f64,
    pub input_load: Option<(DVec2, f64, DVec2, f64)>,
    pub input_constant: bool,
}

impl Default for State {
    fn default() -> Self {
        State {
            engine_sum: 0.0,
            analysis_sum: 0.0,
            first_load: None,
            load_constant: true,
            input_work: 0.0,
            input_load: None,
            input_constant: true,
        }
    }
}

/// Accumulates the works over the step from `prev` to `s`.
// A match over every work and power quantity's step, one arm per quantity, each adding to the
// family's `State`: split, each arm would be a function called once, away from its neighbours.
#[allow(clippy::too_many_lines)]
pub(super) fn advance(m: &mut Meter, st: &mut State, prev: &Snapshot, s: &Snapshot) {
    let dt = s.time - prev.time;
    match &m.q {
        Quantity::GravityWork(b) => {
            if let Some(i) = m.body_index(s, b) {
                let (b0, b1) = (&prev.bodies[i], &s.bodies[i]);
                st.engine_sum += b1.mass * s.gravity.dot(0.5 * (b0.velocity + b1.velocity)) * dt;
            }
        }
        Quantity::SpringWork(name) | Quantity::DamperWork(name) => {
            if let Some(sp) = s.springs.iter().find(|x| &x.name == name) {
                let damper = matches!(m.q, Quantity::DamperWork(_));
                let (f, c) = spring_part(sp, damper);
                st.engine_sum += held_work(prev, s, sp.body1, f, sp.applied_at1, c);
                if let Some(b2) = sp.body2 {
                    st.engine_sum += held_work(prev, s, b2, -f, sp.applied_at2, -c);
                }
                if damper {
                    let c = m
                        .facts
                        .springs
                        .iter()
                        .find(|x| &x.name == name)
                        .map_or(0.0, |x| x.damping);
                    let before = prev.springs.iter().find(|x| &x.name == name);
                    if let Some(b) = before {
                        // The rate at the step's start is taken after its blows (they act
                        // there), at its end from the end's state: the trapezoid over the step.
                        let start = |k: usize| after_blows(prev, s, k);
                        let end = |k: usize| (s.bodies[k].velocity, s.bodies[k].omega);
                        let (r0, r1) = (spring_rate(b, prev, start), spring_rate(sp, s, end));
                        st.analysis_sum += damper_work(c, r0, r1, dt);
                    }
                }
            }
        }
        Quantity::Efficiency { input, output } => {
            if let Some(l) = s.loads.iter().find(|l| &l.name == output) {
                st.engine_sum += held_work(prev, s, l.body, l.force, l.point, l.torque);
                note_load(
                    &mut st.first_load,
                    &mut st.load_constant,
                    l,
                    &prev.bodies[l.body],
                );
            }
            if let Some(l) = s.loads.iter().find(|l| &l.name == input) {
                st.input_work += held_work(prev, s, l.body, l.force, l.point, l.torque);
                note_load(
                    &mut st.input_load,
                    &mut st.input_constant,
                    l,
                    &prev.bodies[l.body],
                );
            } else if let Some(j) = s.joints.iter().find(|j| &j.name == input) {
                let slide = m
                    .facts
                    .joints
                    .iter()
                    .find(|x| &x.name == input)
                    .map(|x| (x.kind, x.axis));
                // The motor's work over the step: its impulse times the joint's mean relative
                // rate (WE-7 for a pin's couple, WE-1 along a slider's axis).
                let mean = |k: usize| {
                    let (a, b) = (&prev.bodies[k], &s.bodies[k]);
                    (
                        0.5 * (a.velocity + b.velocity),
                        0.5 * (a.omega + b.omega),
                        b.com,
                    )
                };
                let ((v1, w1, g1), (v2, w2, g2)) = (mean(j.body1), mean(j.body2));
                let rate = match slide {
                    Some((JointKind::Prismatic | JointKind::PinSlot, axis)) => {
                        let axis = DVec2::from_angle(s.bodies[j.body1].angle).rotate(axis);
                        axis.dot(
                            point_velocity(v2, w2, j.anchor - g2)
                                - point_velocity(v1, w1, j.anchor1 - g1),
                        )
                    }
                    _ => w2 - w1,
                };
                st.input_work += j.motor_impulse * rate;
                st.input_constant = false;
            }
        }
        Quantity::LoadWork(name) => {
            if let Some(l) = s.loads.iter().find(|l| &l.name == name) {
                st.engine_sum += held_work(prev, s, l.body, l.force, l.point, l.torque);
                note_load(
                    &mut st.first_load,
                    &mut st.load_constant,
                    l,
                    &prev.bodies[l.body],
                );
            }
        }
        Quantity::FrictionWork { body, other } | Quantity::FrictionLoss { body, other } => {
            if let (Some(i), Some(o)) = (m.body_index(s, body), m.body_index(s, other)) {
                let loss = matches!(m.q, Quantity::FrictionLoss { .. });
                let mu = m.facts.friction(i, o);
                let other_fixed = s.bodies[o].kind == BodyKind::Fixed;
                // A blow in this step acts at its start, before friction slips over the step:
                // friction then slips at the velocities after the blow, not from those before (a
                // ball struck through its centre, tests/newuser/impacts/n11_07b, booked its blow's step
                // at half its slip: 8.2e-3 J of 0.5714 short). Unless the contact itself pushes
                // impulsively (`pushes_impulsively`): then its slip grows with the blow, from the
                // velocities before (a block struck down into its floor, n10_05b).
                let impulsive = pushes_impulsively(
                    pair_normal_impulse(s, i, Some(o), None),
                    pair_normal_impulse(prev, i, Some(o), None),
                );
                let start = |k: usize| {
                    let a = &prev.bodies[k];
                    if impulsive {
                        return (a.velocity, a.omega);
                    }
                    let blows = s.impulses.iter().filter(|e| e.body == k);
                    velocities_after_impulses(
                        a.mass,
                        a.inertia,
                        a.com,
                        (a.velocity, a.omega),
                        blows.map(|e| (e.impulse, e.point, e.angular_impulse)),
                    )
                };
                // Each body at the step's mean velocities (v_G, omega).
                let mean = |k: usize| {
                    let ((v0, w0), b) = (start(k), &s.bodies[k]);
                    (0.5 * (v0 + b.velocity), 0.5 * (w0 + b.omega))
                };
                let (mi, mo) = (mean(i), mean(o));
                let mut before: Option<Vec<Motion>> = None;
                for c in &s.contacts {
                    let i_is_2 = if c.body2 == i && c.body1 == o {
                        true
                    } else if c.body1 == i && c.body2 == o {
                        false
                    } else {
                        continue;
                    };
                    let t = c.tangent();
                    for p in &c.points {
                        // The solver's lever arms (from G), else the point at the step's start.
                        let (arm1, arm2) = p.arms.unwrap_or_else(|| {
                            let b = before.get_or_insert_with(|| {
                                prev.bodies.iter().map(Motion::from).collect()
                            });
                            contact_arms_at_start(s, b, c, p)
                        });
                        let (arm_i, arm_o, sign) = if i_is_2 {
                            (arm2, arm1, 1.0)
                        } else {
                            (arm1, arm2, -1.0)
                        };
                        // The friction impulse on body i, and the body points' mean velocities.
                        let j_t = t * (sign * p.tangent_impulse);
                        let v_i = point_velocity(mi.0, mi.1, arm_i);
                        let v_o = point_velocity(mo.0, mo.1, arm_o);
                        let slip = (v_i - v_o).dot(t);
                        let j_n = p.normal_impulse.max(0.0);
                        if loss {
                            st.engine_sum += friction_pair_loss(j_t, v_i - v_o);
                            st.analysis_sum -= mu * j_n * slip.abs();
                        } else {
                            st.engine_sum += friction_work_on_body(j_t, arm_i, mi);
                            // A slip floor of 1 mm/s: rapier's rolling contacts creep below it.
                            match coulomb_friction_work_on_body(
                                mu,
                                j_n,
                                slip,
                                v_i.dot(t),
                                other_fixed,
                                1e-3,
                            ) {
                                Some(u) => st.analysis_sum += u,
                                None if j_n > 0.0 && m.inapplicable.is_none() => {
                                    m.inapplicable = Some(format!(
                                        "at t = {:.4} s the contact stuck on the moving \"{other}\": static friction has no Coulomb law for its work",
                                        s.time
                                    ));
                                }
                                None => {}
                            }
                        }
                    }
                }
            }
        }
        Quantity::KineticEnergy(b) => {
            if let Some(i) = m.body_index(s, b) {
                // Ground springs enter the analysis through their exact potential instead.
                st.analysis_sum += path_work(prev, s, i, false);
                // At a configuration event the analysis is this work-energy sum; at an impact
                // or a blow it is the impulse solution, which needs none of it.
                if m.configuration_event && !m.impact_instant && m.inapplicable.is_none() {
                    m.inapplicable = unbooked_work(m, prev, s, i);
                }
            }
        }
        _ => {}
    }
}

/// What works on body i in the step to `s` that the work-energy analysis of its kinetic energy
/// does not book (it adds gravity, springs, loads and impulse events only): a joint to a body
/// that moves or with a motor, a coupling, friction, a contact with a body that moves, damping.
/// A block hanging from a cable over a pulley read 1471.5 J against 629.3 J (the cable's work).
fn unbooked_work(m: &Meter, prev: &Snapshot, s: &Snapshot, i: usize) -> Option<String> {
    let name = |k: usize| s.bodies.get(k).map_or("?", |b| b.name.as_str());
    let moves = |k: usize| {
        s.bodies
            .get(k)
            .is_some_and(|b| b.kind != crate::snapshot::BodyKind::Fixed)
    };
    for (k, j) in s.joints.iter().enumerate() {
        if j.body1 != i && j.body2 != i {
            continue;
        }
        let other = if j.body1 == i { j.body2 } else { j.body1 };
        if moves(other) || m.facts.joints.get(k).is_some_and(|x| x.motor) {
            return Some(format!(
                "joint \"{}\" joins the body to \"{}\", which moves, or drives it: its work is not in the work-energy sum (gravity, springs, loads, events)",
                j.name,
                name(other)
            ));
        }
    }
    if let Some(c) = s
        .couplings
        .iter()
        .find(|c| c.terms.iter().any(|t| t.0 == i))
    {
        return Some(format!(
            "coupling \"{}\" acts on the body: its work is not in the work-energy sum (gravity, springs, loads, events)",
            c.name
        ));
    }
    // Friction works only where the contact slides (a body rolling on a fixed incline takes
    // none: its contact point is at rest), on two steps running and by more than 5 % of the
    // body's speed: a rolling disc's first step slips 1.3e-2 m/s as its contact settles, and
    // rapier's rolling contact creeps by up to 0.3 % of v (1e-2 m/s at 3 m/s), working a few
    // 1e-4 of the disc's energy.
    let slides = |o: usize| {
        [prev, s].iter().all(|x| {
            let v = x.bodies[i].velocity.length();
            crate::analysis::kinematics::contact_slip(x, o, i)
                .is_some_and(|w| w.abs() > SLIDING.max(0.05 * v))
        })
    };
    if let Some(c) = s.contacts.iter().find(|c| {
        let other = if c.body1 == i { c.body2 } else { c.body1 };
        (c.body1 == i || c.body2 == i)
            && (moves(other)
                || (c.points.iter().any(|p| p.tangent_impulse != 0.0) && slides(other)))
    }) {
        let other = if c.body1 == i { c.body2 } else { c.body1 };
        return Some(format!(
            "the contact with \"{}\" works on the body (friction while it slides, or a body that moves): its work is not in the work-energy sum",
            name(other)
        ));
    }
    m.facts
        .bodies
        .get(i)
        .filter(|x| x.damped)
        .map(|_| "the body is damped: damping's work is not in the work-energy sum".to_string())
}

/// The quantity at the sample.
pub(super) fn read(m: &Meter, st: &State, f: &Sample, occ: Occasion) -> Option<EngineAndAnalysis> {
    let s = f.cur;
    let init = m.init.as_ref();
    Some(match &m.q {
        Quantity::KineticEnergy(b) => {
            let (i, x) = m.named_body(s, b)?;
            let analysis = init.map(|s0| {
                let b0 = &s0.bodies[i];
                let springs: f64 = s
                    .springs
                    .iter()
                    .zip(&s0.springs)
                    .filter(|(sp, _)| sp.body2.is_none() && sp.body1 == i)
                    .map(|(sp, sp0)| sp0.energy - sp.energy)
                    .sum();
                // Gravity's work along the rigid contact's path: G lifted out of the depth
                // its soft contacts settle to, whose work the contacts absorb (a rolling
                // disc at 0.4 m/s read 5.6e-3 of T high; `contact_sag`).
                let rigid = |y: &Snapshot| y.bodies[i].com - contact_sag(y, i);
                body_kinetic_energy(b0)
                    + x.mass * s.gravity.dot(rigid(s) - rigid(s0))
                    + springs
                    + st.analysis_sum
            });
            let analysis = match occ {
                Occasion::Plain => analysis.filter(|_| m.configuration_event),
                _ => occ.solved_state(i, s).map(|y| body_kinetic_energy(&y)),
            };
            (body_kinetic_energy(x), analysis)
        }
        Quantity::GroupKineticEnergy(names) | Quantity::GroupMomentum(names) => {
            let mut idx = Vec::with_capacity(names.len());
            for n in names {
                idx.push(m.body_index(s, n)?);
            }
            let momentum = matches!(m.q, Quantity::GroupMomentum(_));
            // Sum over the group, of the engine's states or of the impulse solution's.
            let total = |state: &dyn Fn(usize) -> Option<BodyState>| -> Option<f64> {
                let (mut t, mut g) = (0.0, DVec2::ZERO);
                for &i in &idx {
                    let b = state(i)?;
                    t += body_kinetic_energy(&b);
                    g += linear_momentum(b.mass, b.velocity);
                }
                Some(if momentum { g.length() } else { t })
            };
            let engine = total(&|i| Some(s.bodies[i].clone()))?;
            let analysis = match occ {
                Occasion::Plain => None,
                _ => total(&|i| occ.solved_state(i, s)),
            };
            (engine, analysis)
        }
        Quantity::GravityWork(b) => {
            let (i, x) = m.named_body(s, b)?;
            let g0 = init?.bodies[i].com;
            (st.engine_sum, Some(x.mass * s.gravity.dot(x.com - g0)))
        }
        Quantity::SpringWork(name) => {
            let sp = s.springs.iter().find(|x| &x.name == name)?;
            let sp0 = init?.springs.iter().find(|x| &x.name == name)?;
            (st.engine_sum, Some(sp0.energy - sp.energy))
        }
        Quantity::DamperWork(_) => (st.engine_sum, Some(st.analysis_sum)),
        Quantity::SpringExtension(name) => {
            (s.springs.iter().find(|x| &x.name == name)?.extension, None)
        }
        Quantity::LoadWork(name) => {
            let analysis = constant_load_work(s, init?, name, st.first_load, st.load_constant);
            (st.engine_sum, analysis)
        }
        Quantity::Efficiency { input, output } => {
            let init = init?;
            let engine = mechanical_efficiency(-st.engine_sum, st.input_work);
            let analysis = constant_load_work(s, init, output, st.first_load, st.load_constant)
                .zip(constant_load_work(
                    s,
                    init,
                    input,
                    st.input_load,
                    st.input_constant,
                ))
                .map(|(out, inp)| mechanical_efficiency(-out, inp));
            (engine, analysis)
        }
        Quantity::LoadPower(name) => {
            let l = s.loads.iter().find(|l| &l.name == name)?;
            let b = &s.bodies[l.body];
            // The load's point as it is at the sample: l.point is where it was at the step's start.
            let p = b.world_point(to_local(&f.prev?.bodies[l.body], l.point));
            let v_p = body_point_velocity(b, p);
            (power(l.force, v_p, l.torque, b.omega), None)
        }
        Quantity::FrictionWork { .. } | Quantity::FrictionLoss { .. } => {
            (st.engine_sum, Some(st.analysis_sum))
        }
        q => unreachable!("{q:?} is not a work or power quantity"),
    })
}

/// The elastic part (k x) of a spring's held force and couple on body1, or with `damper` its
/// damper part (c dx/dt), split along the line between its ends at the step's start.
/// A body's velocities (v_G, omega) at the start of the step from `prev` to `s`: `prev`'s, with
/// the step's blows, which act at its start.
fn after_blows(prev: &Snapshot, s: &Snapshot, k: usize) -> (DVec2, f64) {
    let a = &prev.bodies[k];
    let blows = s.impulses.iter().filter(|e| e.body == k);
    velocities_after_impulses(
        a.mass,
        a.inertia,
        a.com,
        (a.velocity, a.omega),
        blows.map(|e| (e.impulse, e.point, e.angular_impulse)),
    )
}

/// A spring's rate dL/dt in snapshot `at` (its ends' points), the bodies moving at `vel(k)`:
/// the relative velocity of its ends along its axis (RK-6), or for a torsion spring the
/// relative angular velocity omega1 - omega2. A fixed end (no body) is at rest.
fn spring_rate(sp: &SpringState, at: &Snapshot, vel: impl Fn(usize) -> (DVec2, f64)) -> f64 {
    let motion = |k: usize| {
        let (v, w) = vel(k);
        (v, w, at.bodies[k].com)
    };
    if sp.torsion {
        return vel(sp.body1).1 - sp.body2.map_or(0.0, |k| vel(k).1);
    }
    let end_velocity = |k: Option<usize>, p: DVec2| {
        k.map_or(DVec2::ZERO, |k| {
            let (v, w, g) = motion(k);
            point_velocity(v, w, p - g)
        })
    };
    let axis = (sp.point2 - sp.point1).normalize_or_zero();
    axis.dot(end_velocity(sp.body2, sp.point2) - end_velocity(Some(sp.body1), sp.point1))
}

fn spring_part(sp: &SpringState, damper: bool) -> (DVec2, f64) {
    let (f_d, c_d) = if sp.torsion {
        (DVec2::ZERO, -sp.damper_tension)
    } else {
        let u = (sp.applied_at2 - sp.applied_at1).normalize_or_zero();
        (u * sp.damper_tension, 0.0)
    };
    if damper {
        (f_d, c_d)
    } else {
        (sp.force_on_body1 - f_d, sp.couple_on_body1 - c_d)
    }
}

/// Records a load's first (force, couple, point, body angle) and whether it stays equal.
fn note_load(
    first: &mut Option<(DVec2, f64, DVec2, f64)>,
    constant: &mut bool,
    l: &crate::snapshot::LoadState,
    b0: &BodyState,
) {
    match *first {
        None => *first = Some((l.force, l.torque, l.point, b0.angle)),
        Some((f0, m0, _, _)) => {
            if (l.force - f0).length() > 1e-12 * f0.length().max(1.0)
                || (l.torque - m0).abs() > 1e-12 * m0.abs().max(1.0)
            {
                *constant = false;
            }
        }
    }
}

/// The work of a load that stayed constant, from its first state to `s`: F . (r_P - r_P0) +
/// M (theta - theta0), path independent (10.3.2). None for a load that changed.
fn constant_load_work(
    s: &Snapshot,
    init: &Snapshot,
    name: &str,
    first: Option<(DVec2, f64, DVec2, f64)>,
    constant: bool,
) -> Option<f64> {
    let (force, torque, p0, a0) = first.filter(|_| constant)?;
    let l = s.loads.iter().find(|l| l.name == name)?;
    let b0 = &init.bodies[l.body];
    let b = &s.bodies[l.body];
    let p = b.world_point(to_local(b0, p0));
    Some(force.dot(p - p0) + torque * (b.angle - a0))
}
