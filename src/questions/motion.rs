//! Motion quantities: where bodies and body points are, how fast they move and accelerate,
//! how far they travel, and the time of an event.
//!
//! Positions and velocities are the engine's state. At an impact or a blow, velocity analyses
//! are the impulse-momentum solution's (`sample::Occasion`); accelerations' analyses are
//! Newton-Euler on the engine's free-body diagram (6/1, see `free_body`).

use super::free_body::{external_moment_about, newton_euler};
use super::meter::{EngineAndAnalysis, Meter};
use super::sample::{Occasion, Sample};
use crate::analysis::k_cross;
use crate::analysis::kinematics::{body_point_velocity, contact_slip, point_acceleration};
use crate::analysis::momentum::angular_momentum_about;
use crate::level::Quantity;
use crate::snapshot::{BodyState, Snapshot};
use glam::DVec2;

/// What a motion quantity accumulates over the run.
#[derive(Clone, Default)]
pub(super) struct State {
    /// Distance travelled so far, m (`Distance`).
    pub engine_sum: f64,
    /// The angular impulse about the fixed point so far (`AngularMomentumAbout`'s analysis).
    pub analysis_sum: f64,
    /// The first contact that pushed in the run that the reference trajectory does not hold
    /// (`analysis::reference` holds rolling contacts found at the start only): the start of
    /// the step it pushed in, and which bodies, said for a note. The reference does not apply
    /// to a reading after that.
    pub contact_seen: Option<(f64, String)>,
}

/// Accumulates the distance travelled over the step from `prev` to `s`.
pub(super) fn advance(m: &mut Meter, st: &mut State, prev: &Snapshot, s: &Snapshot) {
    if st.contact_seen.is_none() {
        st.contact_seen = first_contact(m, s).map(|why| (prev.time, why));
    }
    if m.inapplicable.is_none() {
        m.inapplicable = damped_free_body(m, s);
    }
    match &m.q {
        Quantity::Distance(b) => {
            if let Some(i) = m.body_index(s, b) {
                st.engine_sum += (s.bodies[i].com - prev.bodies[i].com).length();
            }
        }
        Quantity::AngularMomentumAbout { body, point } => {
            if let Some(i) = m.body_index(s, body) {
                // The step's angular impulse about the fixed O (6/17).
                let o = DVec2::new(point.0, point.1);
                st.analysis_sum += external_moment_about(prev, s, i, o);
            }
        }
        _ => {}
    }
}

/// The engine's free-body diagram (`free_body`) has no damping force (rapier scales a damped
/// body's velocities every substep): Newton-Euler's analyses of a damped body's accelerations
/// and angular momentum do not apply. A free disc with linear damping 1/s read its a_x -1.21
/// m/s^2 against an analysis of 0.
fn damped_free_body(m: &Meter, s: &Snapshot) -> Option<String> {
    let names: Vec<&String> = match &m.q {
        Quantity::Ax(b)
        | Quantity::Ay(b)
        | Quantity::Accel(b)
        | Quantity::Alpha(b)
        | Quantity::PointAccel { body: b, .. }
        | Quantity::AngularMomentumAbout { body: b, .. } => vec![b],
        Quantity::RelativeAccel(a, b) => vec![a, b],
        _ => return None,
    };
    let damped = names.into_iter().find(|b| {
        m.body_index(s, b)
            .and_then(|i| m.facts.bodies.get(i))
            .is_some_and(|x| x.damped)
    })?;
    Some(format!(
        "body \"{damped}\" is damped: Newton-Euler's analysis reads the engine's free-body diagram, which has no damping force"
    ))
}

/// The quantity at the sample.
pub(super) fn read(m: &Meter, st: &State, f: &Sample, occ: Occasion) -> Option<EngineAndAnalysis> {
    let s = f.cur;
    let body = |name: &str| m.named_body(s, name);
    let solved = |i: usize| occ.solved_state(i, s);
    Some(match &m.q {
        Quantity::X(b) => (body(b)?.1.com.x, None),
        Quantity::Y(b) => (body(b)?.1.com.y, None),
        Quantity::Angle(b) => (body(b)?.1.angle, None),
        Quantity::Vx(b) => {
            let (i, x) = body(b)?;
            (x.velocity.x, solved(i).map(|y| y.velocity.x))
        }
        Quantity::Vy(b) => {
            let (i, x) = body(b)?;
            (x.velocity.y, solved(i).map(|y| y.velocity.y))
        }
        Quantity::Speed(b) => {
            let (i, x) = body(b)?;
            (x.velocity.length(), solved(i).map(|y| y.velocity.length()))
        }
        Quantity::Omega(b) => {
            let (i, x) = body(b)?;
            (x.omega, solved(i).map(|y| y.omega))
        }
        Quantity::Direction(b) => {
            let (i, x) = body(b)?;
            let dir = |v: DVec2| v.y.atan2(v.x);
            (dir(x.velocity), solved(i).map(|y| dir(y.velocity)))
        }
        Quantity::Distance(_) => (st.engine_sum, None),
        Quantity::Time => (s.time, None),
        Quantity::Ax(b) | Quantity::Ay(b) | Quantity::Accel(b) => {
            let i = m.body_index(s, b)?;
            let ax = f.rate(|x| Some(x.bodies[i].velocity.x))?;
            let ay = f.rate(|x| Some(x.bodies[i].velocity.y))?;
            let newton = newton_euler(f, i).map(|(a, _)| a);
            let pick = |a: DVec2| match &m.q {
                Quantity::Ax(_) => a.x,
                Quantity::Ay(_) => a.y,
                _ => a.length(),
            };
            (pick(DVec2::new(ax, ay)), newton.map(pick))
        }
        Quantity::Alpha(b) => {
            let i = m.body_index(s, b)?;
            let alpha = f.rate(|x| Some(x.bodies[i].omega))?;
            (alpha, newton_euler(f, i).map(|(_, al)| al))
        }
        Quantity::PointX { body: b, point } => {
            (body(b)?.1.world_point(DVec2::new(point.0, point.1)).x, None)
        }
        Quantity::PointY { body: b, point } => {
            (body(b)?.1.world_point(DVec2::new(point.0, point.1)).y, None)
        }
        Quantity::PolarAngle { body: b, about } => {
            let r = body(b)?.1.com - DVec2::new(about.0, about.1);
            (r.y.atan2(r.x), None)
        }
        Quantity::PointSpeed { body: b, point } => {
            let (i, x) = body(b)?;
            let local = DVec2::new(point.0, point.1);
            let speed = |y: &BodyState| body_point_velocity(y, y.world_point(local)).length();
            (speed(x), solved(i).map(|y| speed(&y)))
        }
        Quantity::PointAccel { body: b, point } => {
            let (i, x) = body(b)?;
            let local = DVec2::new(point.0, point.1);
            // The material point's velocity in each snapshot, differenced.
            let vp = |y: &Snapshot| {
                let b = &y.bodies[i];
                body_point_velocity(b, b.world_point(local))
            };
            let ax = f.rate(|y| Some(vp(y).x))?;
            let ay = f.rate(|y| Some(vp(y).y))?;
            // RK-10 with a_G and alpha from Newton-Euler on the free-body diagram.
            let analysis = newton_euler(f, i).map(|(a_g, alpha)| {
                point_acceleration(a_g, alpha, x.omega, x.world_point(local) - x.com).length()
            });
            (DVec2::new(ax, ay).length(), analysis)
        }
        Quantity::RelativeDistance(a, b) => ((body(b)?.1.com - body(a)?.1.com).length(), None),
        Quantity::RelativeSpeed(a, b) => {
            ((body(b)?.1.velocity - body(a)?.1.velocity).length(), None)
        }
        Quantity::RelativeAngle(a, b) => (body(b)?.1.angle - body(a)?.1.angle, None),
        Quantity::RelativeAccel(a, b) => {
            let (ia, ib) = (body(a)?.0, body(b)?.0);
            let accel = |i: usize| -> Option<DVec2> {
                let ax = f.rate(|x| Some(x.bodies[i].velocity.x))?;
                let ay = f.rate(|x| Some(x.bodies[i].velocity.y))?;
                Some(DVec2::new(ax, ay))
            };
            let (ea, eb) = (accel(ia)?, accel(ib)?);
            // Newton-Euler (6/1) for a body with mass; a fixed or kinematic body's own motion.
            let theory = |i: usize, own: DVec2| {
                if s.bodies[i].kind == crate::snapshot::BodyKind::Dynamic {
                    newton_euler(f, i).map(|(a, _)| a)
                } else {
                    Some(own)
                }
            };
            let analysis = theory(ia, ea)
                .zip(theory(ib, eb))
                .map(|(x, y)| (y - x).length());
            ((eb - ea).length(), analysis)
        }
        Quantity::AngularMomentumAbout { body: b, point } => {
            let (i, x) = body(b)?;
            let o = DVec2::new(point.0, point.1);
            let h = |y: &BodyState| {
                angular_momentum_about(y.mass, y.inertia, y.com, y.velocity, y.omega, o)
            };
            let analysis = m.init.as_ref().map(|s0| h(&s0.bodies[i]) + st.analysis_sum);
            (h(x), analysis)
        }
        Quantity::RelativePointSpeed {
            body: b,
            point,
            of,
            of_point,
        } => {
            let (x, y) = (body(b)?.1, body(of)?.1);
            let p = x.world_point(DVec2::new(point.0, point.1));
            let q = y.world_point(DVec2::new(of_point.0, of_point.1));
            let engine = (body_point_velocity(x, p) - body_point_velocity(y, q)).length();
            // Two points of one rigid body: v_P/Q = omega k x r_P/Q (RK-5).
            let analysis = (b == of).then(|| k_cross(x.omega, p - q).length());
            (engine, analysis)
        }
        Quantity::SlipSpeed { body: b, other } => {
            let (i, o) = (body(b)?.0, body(other)?.0);
            (contact_slip(s, o, i).map_or(f64::NAN, f64::abs), None)
        }
        q => unreachable!("{q:?} is not a motion quantity"),
    })
}

/// The first contact of `s` that pushed and that the reference trajectory does not hold as a
/// rolling contact, said for a note.
pub(super) fn first_contact(m: &Meter, s: &Snapshot) -> Option<String> {
    let held = |a: usize, b: usize| match m.facts.reference.as_deref() {
        Some(Ok(model)) => model.rolls(a, b),
        _ => false,
    };
    let c = s
        .contacts
        .iter()
        .find(|c| c.pushes() && !held(c.body1, c.body2))?;
    let name = |i: usize| s.bodies.get(i).map_or("?", |b| b.name.as_str());
    Some(format!(
        "\"{}\" and \"{}\" touched at t = {:.4} s (the reference trajectory holds only rolling contacts found at the start)",
        name(c.body1),
        name(c.body2),
        s.time
    ))
}

/// The quantity at time t on the reference trajectory (the level's equations of motion
/// integrated independently of the engine), or why the scene is outside it.
pub(super) fn reference_value(m: &Meter, st: &State, t: f64) -> Result<f64, String> {
    let model = match m.facts.reference.as_deref() {
        Some(Ok(model)) => model,
        Some(Err(why)) => return Err(why.clone()),
        None => return Err("no reference trajectory was prepared".into()),
    };
    // The reference's own reason first (a touch at the start it cannot hold), then a contact
    // that pushed in a step that began before the reading (the meter follows the whole run,
    // so a later one is seen too, and does not matter).
    if let Some(why) = model.refused_after_start().filter(|_| t > 0.0) {
        return Err(why.to_string());
    }
    if let Some((_, why)) = st.contact_seen.as_ref().filter(|(t0, _)| *t0 < t) {
        return Err(why.clone());
    }
    let tr = model.integrate(&[t])?;
    let x = &tr.instants[0];
    let index = |name: &str| {
        m.facts
            .level_index(name)
            .filter(|&i| i < x.bodies.len())
            .ok_or_else(|| format!("no body \"{name}\""))
    };
    let body = |name: &str| index(name).map(|i| (i, x.bodies[i]));
    // A body-frame point (from the body origin) in the world, and its velocity.
    let point = |i: usize, local: (f64, f64)| {
        let b = x.bodies[i];
        let com = m
            .facts
            .bodies
            .get(i)
            .map_or(DVec2::ZERO, |f| f.textbook.com);
        let d = DVec2::from_angle(b.angle).rotate(DVec2::new(local.0, local.1) - com);
        (b.com + d, b.velocity + k_cross(b.omega, d))
    };
    Ok(match &m.q {
        Quantity::X(b) => body(b)?.1.com.x,
        Quantity::Y(b) => body(b)?.1.com.y,
        Quantity::Angle(b) => body(b)?.1.angle,
        Quantity::Vx(b) => body(b)?.1.velocity.x,
        Quantity::Vy(b) => body(b)?.1.velocity.y,
        Quantity::Speed(b) => body(b)?.1.velocity.length(),
        Quantity::Omega(b) => body(b)?.1.omega,
        Quantity::Direction(b) => {
            let v = body(b)?.1.velocity;
            v.y.atan2(v.x)
        }
        Quantity::PointX { body: b, point: p } => point(index(b)?, *p).0.x,
        Quantity::PointY { body: b, point: p } => point(index(b)?, *p).0.y,
        Quantity::PointSpeed { body: b, point: p } => point(index(b)?, *p).1.length(),
        Quantity::RelativeDistance(a, b) => (body(b)?.1.com - body(a)?.1.com).length(),
        Quantity::RelativeSpeed(a, b) => (body(b)?.1.velocity - body(a)?.1.velocity).length(),
        Quantity::RelativeAngle(a, b) => body(b)?.1.angle - body(a)?.1.angle,
        Quantity::RelativePointSpeed {
            body: b,
            point: p,
            of,
            of_point,
        } => (point(index(b)?, *p).1 - point(index(of)?, *of_point).1).length(),
        q => return Err(format!("{q:?} is not read on the reference trajectory")),
    })
}
