//! Work, energy and power quantities: kinetic energy, the works of gravity, springs, loads and
//! friction, a load's power, and a spring's extension.
//!
//! The engine's works are summed step by step with the step's mean velocity (exact for a rigid
//! body, see [`held_work`]); the analyses are the textbook's path-independent forms (10.2.18,
//! 10.2.21, 10.3.2), work-energy (RE-7) and the Coulomb law (WE-6).

use super::meter::{EngineAndAnalysis, Meter};
use super::sample::{Occasion, Sample};
use super::snapshot_reading::to_local;
use crate::analysis::energy::{body_kinetic_energy, power};
use crate::analysis::kinematics::{body_point_velocity, slip_velocity};
use crate::analysis::momentum::linear_momentum;
use crate::analysis::Motion;
use crate::level::Quantity;
use crate::snapshot::{BodyState, Snapshot};
use glam::DVec2;

/// Accumulates the works over the step from `prev` to `s`.
pub(super) fn advance(m: &mut Meter, prev: &Snapshot, s: &Snapshot) {
    let dt = s.time - prev.time;
    match &m.q {
        Quantity::GravityWork(b) => {
            if let Some(i) = m.body_index(s, b) {
                let (b0, b1) = (&prev.bodies[i], &s.bodies[i]);
                m.engine_sum += b1.mass * s.gravity.dot(0.5 * (b0.velocity + b1.velocity)) * dt;
            }
        }
        Quantity::SpringWork(name) => {
            if let Some(sp) = s.springs.iter().find(|x| &x.name == name) {
                let c = sp.couple_on_body1;
                m.engine_sum += held_work(prev, s, sp.body1, sp.force_on_body1, sp.applied_at1, c);
                if let Some(b2) = sp.body2 {
                    m.engine_sum += held_work(prev, s, b2, -sp.force_on_body1, sp.applied_at2, -c);
                }
            }
        }
        Quantity::LoadWork(name) => {
            if let Some(l) = s.loads.iter().find(|l| &l.name == name) {
                let b0 = &prev.bodies[l.body];
                m.engine_sum += held_work(prev, s, l.body, l.force, l.point, l.torque);
                match m.first_load {
                    None => m.first_load = Some((l.force, l.torque, l.point, b0.angle)),
                    Some((f0, m0, _, _)) => {
                        if (l.force - f0).length() > 1e-12 * f0.length().max(1.0)
                            || (l.torque - m0).abs() > 1e-12 * m0.abs().max(1.0)
                        {
                            m.load_constant = false;
                        }
                    }
                }
            }
        }
        Quantity::FrictionWork { body, other } => {
            if let (Some(i), Some(o)) = (m.body_index(s, body), m.body_index(s, other)) {
                let mu = m.facts.friction(i, o);
                // Each body at the step's mean velocities, where it is at the step's end.
                let mid = |k: usize| {
                    Motion::mid(&Motion::from(&prev.bodies[k]), &Motion::from(&s.bodies[k]))
                };
                let (mi, mo) = (mid(i), mid(o));
                for c in &s.contacts {
                    let sign = if c.body2 == i && c.body1 == o {
                        1.0
                    } else if c.body1 == i && c.body2 == o {
                        -1.0
                    } else {
                        continue;
                    };
                    let t = c.tangent();
                    for p in &c.points {
                        let slip = slip_velocity(&mo, &mi, p.point, c.normal);
                        m.engine_sum += sign * p.tangent_impulse * mi.velocity_at(p.point).dot(t);
                        m.analysis_sum -= mu * p.normal_impulse.max(0.0) * slip.abs();
                    }
                }
            }
        }
        Quantity::KineticEnergy(b) => {
            if let Some(i) = m.body_index(s, b) {
                // Ground springs enter the analysis through their exact potential instead.
                m.analysis_sum += path_work(prev, s, i, false);
            }
        }
        _ => {}
    }
}

/// The quantity at the sample.
pub(super) fn read(m: &Meter, f: &Sample, occ: Occasion) -> Option<EngineAndAnalysis> {
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
                body_kinetic_energy(b0)
                    + x.mass * s.gravity.dot(x.com - b0.com)
                    + springs
                    + m.analysis_sum
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
            (m.engine_sum, Some(x.mass * s.gravity.dot(x.com - g0)))
        }
        Quantity::SpringWork(name) => {
            let sp = s.springs.iter().find(|x| &x.name == name)?;
            let sp0 = init?.springs.iter().find(|x| &x.name == name)?;
            (m.engine_sum, Some(sp0.energy - sp.energy))
        }
        Quantity::SpringExtension(name) => {
            (s.springs.iter().find(|x| &x.name == name)?.extension, None)
        }
        Quantity::LoadWork(name) => {
            let analysis = match (m.first_load, m.load_constant) {
                (Some((force, torque, p0, a0)), true) => {
                    let l = s.loads.iter().find(|l| &l.name == name)?;
                    let b0 = &init?.bodies[l.body];
                    let b = &s.bodies[l.body];
                    let p = b.world_point(to_local(b0, p0));
                    Some(force.dot(p - p0) + torque * (b.angle - a0))
                }
                _ => None,
            };
            (m.engine_sum, analysis)
        }
        Quantity::LoadPower(name) => {
            let l = s.loads.iter().find(|l| &l.name == name)?;
            let b = &s.bodies[l.body];
            // The load's point as it is at the sample: l.point is where it was at the step's start.
            let p = b.world_point(to_local(&f.prev?.bodies[l.body], l.point));
            let v_p = body_point_velocity(b, p);
            (power(l.force, v_p, l.torque, b.omega), None)
        }
        Quantity::FrictionWork { .. } => (m.engine_sum, Some(m.analysis_sum)),
        q => unreachable!("{q:?} is not a work or power quantity"),
    })
}

/// Work done on body i over the step from `prev` to `s` by its loads and by the springs attached
/// to it (the held force times the displacement of its point; ground springs only with `ground`).
pub(super) fn path_work(prev: &Snapshot, s: &Snapshot, i: usize, ground: bool) -> f64 {
    let mut w = 0.0;
    for l in s.loads.iter().filter(|l| l.body == i) {
        w += held_work(prev, s, i, l.force, l.point, l.torque);
    }
    // An event's impulse J at P does J . v_P,mid (exact for a free rigid body, see held_work).
    for e in s.impulses.iter().filter(|e| e.body == i) {
        let dt = s.time - prev.time;
        if dt > 0.0 {
            w += held_work(prev, s, i, e.impulse / dt, e.point, e.angular_impulse / dt);
        }
    }
    for sp in &s.springs {
        if sp.body2.is_none() && !ground {
            continue;
        }
        if sp.body1 == i {
            w += held_work(
                prev,
                s,
                i,
                sp.force_on_body1,
                sp.applied_at1,
                sp.couple_on_body1,
            );
        } else if sp.body2 == Some(i) {
            w += held_work(
                prev,
                s,
                i,
                -sp.force_on_body1,
                sp.applied_at2,
                -sp.couple_on_body1,
            );
        }
    }
    w
}

/// Work of a force F (and couple M) held over the step from `prev` to `s` on body i, applied at
/// the world point p (its position at the start of the step): U = (F . v_P,mid + M omega_mid) dt
/// with the step's mean velocity, which makes the works of a step add up to its change of kinetic
/// energy exactly (the analysis layer's `work_of_impulse`, WE-9 per step).
fn held_work(prev: &Snapshot, s: &Snapshot, i: usize, f: DVec2, p: DVec2, m: f64) -> f64 {
    let (b0, b1) = (&prev.bodies[i], &s.bodies[i]);
    let dt = s.time - prev.time;
    let v0 = body_point_velocity(b0, p);
    let v1 = body_point_velocity(b1, b1.world_point(to_local(b0, p)));
    power(f, 0.5 * (v0 + v1), m, 0.5 * (b0.omega + b1.omega)) * dt
}
