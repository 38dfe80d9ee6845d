//! Force quantities: joint reactions and impulses, contact and coupling forces, motor torques.
//!
//! The engine's values are the impulses rapier reports divided by dt, centered on the sample
//! (or averaged over the quantity's window). Analyses: fixed-axis rotation for a pinned body's
//! reaction (PL-8, PL-12), the blow's impulse-momentum solution for a pin impulse (RM-10), and
//! the one-degree-of-freedom power balance for a motor (RE-11).

use super::contact_reading::{contact_component, turned, CURVED, SLIDING};
use super::free_body::{contact_needed, side_impulse};
use super::meter::{EngineAndAnalysis, Meter};
use super::sample::{Occasion, Sample};
use super::snapshot_reading::{is_massive, joint_index, to_local};
use super::step_work::path_work;
use crate::analysis::cross;
use crate::analysis::energy::{fixed_axis_speed_after_work, kinetic_energy_rate, power};
use crate::analysis::impact::{pair_contact, pair_normal_impulse};
use crate::analysis::kinematics::{body_point_velocity, contact_slip};
use crate::analysis::kinetics::fixed_axis_reaction;
use crate::analysis::links::joined_bodies;
use crate::analysis::mass::parallel_axis;
use crate::level::{Component, ContactComponent, JointKind, Quantity};
use crate::snapshot::Snapshot;
use glam::DVec2;

/// How the reason for a one-step force on a curve begins.
const ON_A_CURVE: &str = "the contact is on a curve";

/// What a force quantity accumulates over the run.
#[derive(Clone, Default)]
pub(super) struct State {
    /// For a joint reaction: the path work of loads and springs on the moving body since the
    /// start, J (the pivot reaction's omega from work-energy).
    pub path_work: f64,
    /// The first contact the reference trajectory does not hold (`motion::State`'s).
    pub contact_seen: Option<(f64, String)>,
}

/// Accumulates, for a joint reaction, the path work of loads and springs on the moving body
/// over the step from `prev` to `s` (for the pivot reaction's omega from work-energy), and
/// judges whether the quantity's analysis applies.
pub(super) fn advance(m: &mut Meter, st: &mut State, prev: &Snapshot, s: &Snapshot) {
    if st.contact_seen.is_none() {
        st.contact_seen = super::motion::first_contact(m, s).map(|why| (prev.time, why));
    }
    if let Quantity::ContactForceFrom {
        body,
        other,
        window,
        component,
    } = m.q.clone()
    {
        // On a fixed arc, PN-2 from the state at the instant (`curved_contact`). Elsewhere
        // Newton's analysis reads a_G, which a faceted curve jolts at each vertex: at one
        // step it is the engine's burst, not the textbook's force.
        if let (Some(i), Some(o)) = (m.body_index(s, &body), m.body_index(s, &other)) {
            if super::curved_contact::advance(m, s, i, o, component) {
            } else if window == 0.0
                && m.inapplicable
                    .as_deref()
                    .is_none_or(|w| w.starts_with(ON_A_CURVE))
            {
                // Judged at each step (the last is the one read): a track that curves into a
                // straight run (one Polyline) has a textbook force again on the straight.
                m.inapplicable = turned(prev, s, i, o)
                    .is_some_and(|a| a > CURVED)
                    .then(|| format!("{ON_A_CURVE} (its normal turns from step to step): a faceted track gives the force at its vertices, in bursts, so one step's m a_G is no textbook force; ask with a `window` of several steps"));
            }
        }
    }
    if let Quantity::MotorTorque { joint: j, .. } = &m.q {
        if m.inapplicable.is_none() {
            if let Some(k) = joint_index(s, j) {
                m.inapplicable = friction_on_mechanism(s, k);
            }
        }
    }
    if let Quantity::JointReaction { joint: j, .. } = &m.q {
        if m.inapplicable.is_none() && m.facts.joints.iter().any(|x| &x.name == j && x.motor) {
            m.inapplicable = Some(format!(
                "joint \"{j}\" has a motor: the reaction's analysis leaves the motor's torque out of the body's moment and work"
            ));
        }
        if m.inapplicable.is_none() {
            if let Some(k) = joint_index(s, j) {
                m.inapplicable = reaction_not_applicable(m, s, k);
            }
        }
        if let Some(k) = joint_index(s, j) {
            let jj = &s.joints[k];
            let i = if is_massive(&s.bodies[jj.body2]) {
                jj.body2
            } else {
                jj.body1
            };
            st.path_work += path_work(prev, s, i, true);
        }
    }
}

/// The quantity at the sample.
// A match over every force quantity's reading, one arm per quantity (the family's own state
// is one sum): split, each arm would be a function called once, away from its neighbours.
#[allow(clippy::too_many_lines)]
pub(super) fn read(m: &Meter, st: &State, f: &Sample, occ: Occasion) -> Option<EngineAndAnalysis> {
    let s = f.cur;
    Some(match &m.q {
        Quantity::JointForce(j) => {
            let k = joint_index(s, j)?;
            if s.is_initial() {
                return None;
            }
            (s.joints[k].impulse_on_body2.length() / s.dt, None)
        }
        Quantity::JointReaction {
            joint, component, ..
        } => {
            // The initial snapshot has no joint states yet: take the joint from the first step.
            let js = if s.joints.is_empty() {
                f.next.unwrap_or(s)
            } else {
                s
            };
            let k = joint_index(js, joint)?;
            let j = &js.joints[k];
            let moving_is_2 = is_massive(&s.bodies[j.body2]);
            let on_moving = f.windowed(|x| {
                let jj = x.joints.get(k)?;
                Some(if moving_is_2 {
                    jj.impulse_on_body2
                } else {
                    -jj.impulse_on_body2
                })
            })?;
            let (mb, anchor) = if moving_is_2 {
                (j.body2, j.anchor1)
            } else {
                (j.body1, j.anchor)
            };
            let comp = |r: DVec2| component_of(*component, r, s.bodies[mb].com, anchor);
            (comp(on_moving), pivot_reaction(m, st, f, k).map(comp))
        }
        Quantity::JointImpulse { joint, component } => {
            let k = joint_index(s, joint)?;
            let j = &s.joints[k];
            let moving_is_2 = is_massive(&s.bodies[j.body2]);
            let sign = if moving_is_2 { 1.0 } else { -1.0 };
            let (mb, anchor) = if moving_is_2 {
                (j.body2, j.anchor1)
            } else {
                (j.body1, j.anchor)
            };
            let comp = |r: DVec2| component_of(*component, r, s.bodies[mb].com, anchor);
            let analysis = match occ {
                Occasion::AfterBlow(b) => {
                    // The level's joints are in level order, as the snapshot's are.
                    b.joint_impulse.get(k).map(|x| comp(*x * sign))
                }
                _ => None,
            };
            // rapier reports a joint's reaction as its last substep's impulse times the substep
            // count, which misses a blow the joint absorbs in the first substep: the engine's value
            // is the impulse-momentum balance of the bodies on the joint's moving side instead.
            let engine = match f.prev {
                Some(prev) => side_impulse(prev, s, k, mb),
                None => j.impulse_on_body2 * sign,
            };
            (comp(engine), analysis)
        }
        Quantity::ContactForce(b) => {
            let i = m.body_index(s, b)?;
            if s.is_initial() {
                return None;
            }
            let total: DVec2 = s
                .contacts
                .iter()
                .map(|c| {
                    if c.body2 == i {
                        c.impulse_on_body2()
                    } else if c.body1 == i {
                        -c.impulse_on_body2()
                    } else {
                        DVec2::ZERO
                    }
                })
                .sum();
            (total.length() / s.dt, None)
        }
        Quantity::ContactNormalForce { body: b, other } => {
            let (i, o) = (m.body_index(s, b)?, m.body_index(s, other)?);
            let n =
                f.centered(|x| Some(DVec2::new(pair_normal_impulse(x, i, Some(o), None), 0.0)))?;
            (n.x, None)
        }
        Quantity::ContactForceFrom {
            body: b,
            other,
            component,
            ..
        } => {
            let (i, o) = (m.body_index(s, b)?, m.body_index(s, other)?);
            if s.is_initial() {
                return None;
            }
            // The pair's frame at the sample, n from `other` into `body` (pair_contact(s, o, i)).
            let n = pair_contact(s, o, i)
                .or_else(|| f.next.and_then(|x| pair_contact(x, o, i)))?
                .normal;
            let force = f.windowed(|x| {
                Some(pair_contact(x, o, i).map_or(DVec2::ZERO, |c| c.impulse_on_b))
            })?;
            let analysis = contact_force_analysis(m, f, i, o, n, *component);
            (contact_component(*component, force, n), analysis)
        }
        Quantity::CouplingForce(name) => {
            let k = s
                .couplings
                .iter()
                .position(|c| &c.name == name)
                .or_else(|| {
                    f.next
                        .and_then(|n| n.couplings.iter().position(|c| &c.name == name))
                })?;
            let force = f.centered(|y| Some(DVec2::new(y.couplings.get(k)?.impulse, 0.0)))?;
            // lambda is a multiplier whose sign follows the terms' ratios: term i took
            // ratio_i lambda. With an x or y term (a cable, a pulley, a rack) lambda / dt is
            // the cable's tension, signed: negative is a cable that pushes. With angle terms
            // only (a gear mesh, a belt between drums) each term's couple is r_i lambda, a
            // force lambda at its pitch radius, so the tooth force is abs(lambda) / dt: a
            // pinion driving a gear read -16 N for a 16 N tooth force before.
            let angles_only = s.couplings.get(k).is_some_and(|c| {
                c.terms
                    .iter()
                    .all(|t| t.1 == crate::level::Coordinate::Angle)
            });
            (if angles_only { force.x.abs() } else { force.x }, None)
        }
        Quantity::MotorTorque { joint: j, .. } => {
            let k = joint_index(s, j)?;
            let torque = f.windowed(|x| Some(DVec2::new(x.joints.get(k)?.motor_impulse, 0.0)))?;
            // Over a window, the power balance is averaged over the same samples.
            let analysis = if f.window.len() > 2 {
                let w = f.window;
                let vals: Vec<f64> = (1..w.len() - 1)
                    .filter_map(|i| {
                        let g = Sample {
                            prev: Some(&w[i - 1]),
                            cur: &w[i],
                            next: Some(&w[i + 1]),
                            window: std::slice::from_ref(&w[i]),
                        };
                        motor_effort(m, &g, k)
                    })
                    .collect();
                (!vals.is_empty()).then(|| vals.iter().sum::<f64>() / vals.len() as f64)
            } else {
                motor_effort(m, f, k)
            };
            (torque.x, analysis)
        }
        Quantity::SpringForce(name) => {
            let k = s.springs.iter().position(|x| &x.name == name)?;
            let tension =
                f.centered(|y| Some(DVec2::new(y.springs.get(k)?.tension * y.dt, 0.0)))?;
            // Hooke's law with a viscous damper: k x + c dL/dt, the rate a central difference.
            let analysis = m
                .facts
                .springs
                .iter()
                .find(|x| &x.name == name)
                .and_then(|x| {
                    let rate = f.rate(|y| Some(y.springs.get(k)?.length))?;
                    Some(x.stiffness * s.springs[k].extension + x.damping * rate)
                });
            (tension.x, analysis)
        }
        q => unreachable!("{q:?} is not a force quantity"),
    })
}

/// The textbook's contact force on body i from o, as component `c` (`ContactForceFrom`): while
/// the contact slides (the slip keeps one sign above [`SLIDING`] on both steps around the
/// sample), the friction part is Coulomb's mu N opposing the slip, with the engine's N (WE-6);
/// otherwise, where this contact is body i's only support (no other contact, joint or
/// coupling on it), the force its motion needs beyond the known forces (6/1). On a fixed arc,
/// the normal force on a circular path (PN-2, `curved_contact`) where it answers.
fn contact_force_analysis(
    m: &Meter,
    f: &Sample,
    i: usize,
    o: usize,
    n: DVec2,
    c: ContactComponent,
) -> Option<f64> {
    if let Some(on_arc) = super::curved_contact::analysis(m, f, i, o, n, c) {
        return on_arc;
    }
    let slips: Vec<f64> = [f.prev, Some(f.cur), f.next]
        .into_iter()
        .flatten()
        .filter_map(|x| contact_slip(x, o, i))
        .collect();
    let sliding = slips.len() == 3
        && slips.iter().all(|v| v.abs() > SLIDING)
        && slips.iter().all(|v| (v > &0.0) == (slips[0] > 0.0));
    if sliding && matches!(c, ContactComponent::Tangential | ContactComponent::Friction) {
        let normal = f
            .centered(|x| Some(DVec2::new(pair_normal_impulse(x, i, Some(o), None), 0.0)))?
            .x;
        let friction = m.facts.friction(i, o) * normal;
        return Some(match c {
            ContactComponent::Friction => friction,
            _ => -slips[1].signum() * friction,
        });
    }
    let needed = contact_needed(f, i, o)?;
    Some(contact_component(c, needed, n))
}

/// A vector's component as `Component` names it, with G the moving body's mass center and O the anchor.
pub(super) fn component_of(c: Component, v: DVec2, g: DVec2, o: DVec2) -> f64 {
    let toward = (o - g).normalize_or(DVec2::X);
    match c {
        Component::Magnitude => v.length(),
        Component::X => v.x,
        Component::Y => v.y,
        Component::Normal => v.dot(toward),
        Component::Tangential => v.dot((g - o).perp().normalize_or(DVec2::Y)),
    }
}

/// Why the pivot reaction's analysis (`pivot_reaction`) does not hold for joint k, judged on
/// the step that led to `s` and kept for the run: the pin's other side is kinematic and moving
/// (the axis is not fixed), the turning body is damped (damping's moment and work are in
/// neither sum M_O nor the work-energy omega), or a contact acted on the turning body (omega
/// from the work of gravity, loads, springs and impulse events since the start misses what an
/// impact or friction took; an impulse event's work is booked, `path_work`).
fn reaction_not_applicable(m: &Meter, s: &Snapshot, k: usize) -> Option<String> {
    let j = &s.joints[k];
    let (mb, ob) = if is_massive(&s.bodies[j.body2]) {
        (j.body2, j.body1)
    } else {
        (j.body1, j.body2)
    };
    let (b, o) = (&s.bodies[mb], &s.bodies[ob]);
    if o.kind == crate::level::BodyKind::Kinematic && (o.velocity != DVec2::ZERO || o.omega != 0.0)
    {
        return Some(format!(
            "the pin's other side, body \"{}\", is kinematic and moves: the fixed-axis reaction (PL-8, PL-12) is for a pin fixed in the world",
            o.name
        ));
    }
    if m.facts.bodies.get(mb).is_some_and(|x| x.damped) {
        return Some(format!(
            "body \"{}\" is damped: damping's moment and work are in neither sum M_O nor the work-energy omega",
            b.name
        ));
    }
    let touched = s
        .contacts
        .iter()
        .find(|c| (c.body1 == mb || c.body2 == mb) && c.pushes())?;
    let other = if touched.body1 == mb {
        touched.body2
    } else {
        touched.body1
    };
    Some(format!(
        "body \"{}\" touched body \"{}\" at t = {:.4} s: the fixed-axis reaction holds the pin alone on the body, and the work-energy omega misses the contact's impulse",
        b.name, s.bodies[other].name, s.time
    ))
}

/// Fixed-axis rotation (PL-8, PL-12): the pivot reaction on the moving body,
/// `analysis::kinetics::fixed_axis_reaction`, with the applied forces held around the sample and
/// omega from work-energy (`analysis::energy::fixed_axis_speed_after_work` with the work of
/// gravity, loads and springs since the start), its sign the engine's. Applies when one side of
/// a revolute joint is fixed and the moving body has no other joint or contact.
fn pivot_reaction(m: &Meter, st: &State, f: &Sample, k: usize) -> Option<DVec2> {
    let s = f.cur;
    let js = if s.joints.is_empty() {
        f.next.unwrap_or(s)
    } else {
        s
    };
    let j = js.joints.get(k)?;
    if m.facts
        .joints
        .get(k)
        .is_some_and(|x| x.kind != JointKind::Revolute)
    {
        return None;
    }
    let (mb, o) = if is_massive(&s.bodies[j.body2]) && !is_massive(&s.bodies[j.body1]) {
        (j.body2, j.anchor1)
    } else if is_massive(&s.bodies[j.body1]) && !is_massive(&s.bodies[j.body2]) {
        (j.body1, j.anchor)
    } else {
        return None;
    };
    let alone = js
        .joints
        .iter()
        .filter(|x| x.body1 == mb || x.body2 == mb)
        .count()
        == 1
        && !s.contacts.iter().any(|c| c.body1 == mb || c.body2 == mb)
        && !s
            .couplings
            .iter()
            .any(|c| c.terms.iter().any(|t| t.0 == mb));
    if !alone {
        return None;
    }
    let b = &s.bodies[mb];
    let r = b.com - o;
    let i_o = parallel_axis(b.inertia, b.mass, r.length());
    if i_o <= 0.0 {
        return None;
    }
    // Applied forces held around the sample (centered), their moments about O.
    let (mut force, mut moment) = (b.mass * s.gravity, cross(r, b.mass * s.gravity));
    let mut count = 0.0;
    let (mut fl, mut ml) = (DVec2::ZERO, 0.0);
    for x in f.steps() {
        for l in x.loads.iter().filter(|l| l.body == mb) {
            fl += l.force;
            ml += cross(l.point - o, l.force) + l.torque;
        }
        for sp in &x.springs {
            if sp.body1 == mb {
                fl += sp.force_on_body1;
                ml += cross(sp.applied_at1 - o, sp.force_on_body1) + sp.couple_on_body1;
            } else if sp.body2 == Some(mb) {
                fl -= sp.force_on_body1;
                ml += cross(sp.applied_at2 - o, -sp.force_on_body1) - sp.couple_on_body1;
            }
        }
        count += 1.0;
    }
    if count > 0.0 {
        force += fl / count;
        moment += ml / count;
    }
    // omega from work-energy: gravity's work is m g . (G - G0); loads' and springs' along the path.
    let init = m.init.as_ref()?;
    let b0 = &init.bodies[mb];
    let work = b.mass * s.gravity.dot(b.com - b0.com) + st.path_work;
    let turning = if b.omega < 0.0 { -1.0 } else { 1.0 };
    let omega = fixed_axis_speed_after_work(i_o, b0.omega, work) * turning;
    Some(fixed_axis_reaction(b.mass, i_o, r, force, moment, omega))
}

/// The motor's effort from the textbook: virtual work with the inertia forces (VW-2, VW-5; MK
/// 6/11a), which holds at rest as in motion; where the joints do not make a one-degree-of-freedom
/// mechanism of what the motor drives (a contact, a coupling, a free body), the power balance.
/// Friction at a contact of the mechanism that joint k drives (its dynamic bodies joined through
/// joints and couplings), in the step that led to `s`: its work is in neither the virtual work
/// of the applied forces nor the power balance, which would then give the motor less than it
/// takes (a winch hauling a block on a rough floor read r Q = 2.0 N m for r (Q + mu m g) =
/// 3.18). None when there is none.
fn friction_on_mechanism(s: &Snapshot, k: usize) -> Option<String> {
    let dynamic = |i: usize| s.bodies.get(i).is_some_and(is_massive);
    let j = s.joints.get(k)?;
    let couplings = s.couplings.iter().flat_map(|c| {
        c.terms
            .iter()
            .flat_map(move |a| c.terms.iter().map(move |b| (a.0, b.0)))
    });
    let inside = joined_bodies(
        s.bodies.len(),
        [j.body1, j.body2].into_iter().filter(|&b| dynamic(b)),
        s.joints.iter().map(|x| (x.body1, x.body2)).chain(couplings),
        |_| true,
        dynamic,
    );
    let c = s.contacts.iter().find(|c| {
        (inside[c.body1] || inside[c.body2]) && c.points.iter().any(|p| p.tangent_impulse != 0.0)
    })?;
    Some(format!(
        "friction between \"{}\" and \"{}\" acts on the driven mechanism: its work is in neither the virtual work nor the power balance",
        s.bodies[c.body1].name, s.bodies[c.body2].name
    ))
}

fn motor_effort(m: &Meter, f: &Sample, k: usize) -> Option<f64> {
    virtual_work_effort(m, f, k).or_else(|| power_balance(m, f, k))
}

/// Virtual work for the motor of joint k (`analysis::virtual_work`): the virtual velocities of the
/// mechanism at the sample for a unit rate of the joint, a_G and alpha by central differences of
/// the engine's velocities, the applied forces held over the two steps around the sample.
fn virtual_work_effort(m: &Meter, f: &Sample, k: usize) -> Option<f64> {
    use crate::analysis::virtual_work::{
        actuator_effort, applied_forces, links_of, not_a_mechanism, virtual_velocities,
    };
    let s = f.cur;
    let kinds: Vec<(JointKind, DVec2)> = m.facts.joints.iter().map(|j| (j.kind, j.axis)).collect();
    let links = links_of(s, &kinds);
    let field = virtual_velocities(&s.bodies, &links, k).ok()?;
    if not_a_mechanism(s, &field).is_some() {
        return None;
    }
    let mut acc = Vec::with_capacity(s.bodies.len());
    for (i, b) in s.bodies.iter().enumerate() {
        acc.push(if is_massive(b) {
            let ax = f.rate(|x| Some(x.bodies[i].velocity.x))?;
            let ay = f.rate(|x| Some(x.bodies[i].velocity.y))?;
            (DVec2::new(ax, ay), f.rate(|x| Some(x.bodies[i].omega))?)
        } else {
            (DVec2::ZERO, 0.0)
        });
    }
    let efforts: Vec<f64> = f
        .steps()
        .map(|x| actuator_effort(&s.bodies, &field, applied_forces(x, &links, k), Some(&acc)))
        .collect();
    (!efforts.is_empty()).then(|| efforts.iter().sum::<f64>() / efforts.len() as f64)
}

/// The one-degree-of-freedom power balance (RE-11): the motor's torque (force) times the
/// joint rate equals the rate of change of kinetic energy of every dynamic body minus the
/// power of gravity, loads and springs, all from the engine's state at the sample.
fn power_balance(m: &Meter, f: &Sample, k: usize) -> Option<f64> {
    let s = f.cur;
    let j = &s.joints[k];
    let (b1, b2) = (&s.bodies[j.body1], &s.bodies[j.body2]);
    let kind = m
        .facts
        .joints
        .get(k)
        .map_or(JointKind::Revolute, |x| x.kind);
    let rate = match kind {
        JointKind::Prismatic => {
            let axis = m
                .facts
                .joints
                .get(k)
                .map_or(DVec2::X, |x| DVec2::from_angle(b1.angle).rotate(x.axis));
            (body_point_velocity(b2, j.anchor) - body_point_velocity(b1, j.anchor)).dot(axis)
        }
        _ => b2.omega - b1.omega,
    };
    if rate.abs() < 1e-9 {
        return None;
    }
    let mut dtdt = 0.0;
    let mut applied = 0.0;
    for (i, b) in s.bodies.iter().enumerate() {
        if !is_massive(b) {
            continue;
        }
        let ax = f.rate(|x| Some(x.bodies[i].velocity.x))?;
        let ay = f.rate(|x| Some(x.bodies[i].velocity.y))?;
        let alpha = f.rate(|x| Some(x.bodies[i].omega))?;
        let a_g = DVec2::new(ax, ay);
        dtdt += kinetic_energy_rate(b.mass, b.velocity, a_g, b.inertia, b.omega, alpha);
        applied += b.mass * s.gravity.dot(b.velocity);
    }
    let mut n = 0.0;
    let mut p_held = 0.0;
    for x in f.steps() {
        for l in &x.loads {
            let b = &s.bodies[l.body];
            let p = b.world_point(to_local(&x.bodies[l.body], l.point));
            p_held += power(l.force, body_point_velocity(b, p), l.torque, b.omega);
        }
        for sp in &x.springs {
            let (f, c) = (sp.force_on_body1, sp.couple_on_body1);
            let b1 = &s.bodies[sp.body1];
            p_held += power(f, body_point_velocity(b1, sp.point1), c, b1.omega);
            if let Some(b2) = sp.body2 {
                let b2 = &s.bodies[b2];
                p_held -= power(f, body_point_velocity(b2, sp.point2), c, b2.omega);
            }
        }
        n += 1.0;
    }
    if n > 0.0 {
        applied += p_held / n;
    }
    Some((dtdt - applied) / rate)
}
