//! Rolling quantities: a round body rolling on the ground, its acceleration down the slope, the
//! friction it needs, and the least coefficient of friction for rolling.
//!
//! The slope angle and the radius come from the engine's contact at the sample (normal and
//! point); the analyses are the closed forms of `analysis::closed_forms` (RK-8 with 6/1).

use super::contact_reading::{also_acting, turned, CURVED, SLIDING};
use super::meter::{EngineAndAnalysis, Meter};
use super::sample::Sample;
use crate::analysis::closed_forms::{
    rolling_acceleration, rolling_friction, rolling_friction_needed,
};
use crate::analysis::cross;
use crate::level::{BodyKind, Quantity};
use crate::snapshot::Snapshot;
use glam::DVec2;

/// Checks the closed forms' assumptions on the step that led to `s` (RK-8 with 6/1: a round
/// body rolling on a fixed straight surface with only its weight and that surface acting), and
/// records the first one the scene breaks: the analysis is then "not applicable".
pub(super) fn advance(m: &mut Meter, prev: &Snapshot, s: &Snapshot) {
    // A reason found once holds for the run, except sliding, which is the state at the step
    // read (a rolling disc's first step can slip 1.3e-2 m/s as the contact settles).
    if m.inapplicable
        .as_deref()
        .is_some_and(|w| !w.starts_with(SLIDES))
    {
        return;
    }
    let (Quantity::RollingAcceleration { body: b, ground }
    | Quantity::RollingFriction { body: b, ground }
    | Quantity::RollingFrictionNeeded { body: b, ground }) = &m.q
    else {
        return;
    };
    let (Some(i), Some(o)) = (m.body_index(s, b), m.body_index(s, ground)) else {
        return;
    };
    let why = if m.facts.bodies.get(i).is_some_and(|x| x.disc.is_none()) {
        Some(format!(
            "body \"{b}\" is not round (its shape is not a Circle): the rolling closed forms take a contact point at a fixed distance r below G, which a box or polygon does not keep"
        ))
    } else if s.bodies[o].kind != BodyKind::Fixed {
        Some("the ground moves: the rolling closed forms are for a fixed slope (a wedge that slides changes the body's acceleration)".to_string())
    } else if let Some(what) = also_acting(s, i, o).or_else(|| {
        m.facts
            .bodies
            .get(i)
            .filter(|x| x.damped)
            .map(|_| "damping")
    }) {
        Some(format!(
            "{what} also acts on the body: the rolling closed forms assume its weight and the ground alone"
        ))
    } else if let Some(slip) =
        crate::analysis::kinematics::contact_slip(s, o, i).filter(|v| v.abs() > SLIDING)
    {
        Some(format!(
            "{SLIDES} (slip {:.3} m/s at t = {:.4} s): the rolling closed forms assume rolling without slipping",
            slip.abs(),
            s.time
        ))
    } else if matches!(m.q, Quantity::RollingFrictionNeeded { .. })
        && turned(prev, s, i, o).is_some_and(|a| a > CURVED)
    {
        Some("the ground curves under the body (its contact normal turns): F/N = tan(theta) k_G^2/(k_G^2 + r^2) takes N = m g cos(theta), which a curve changes by m v^2 / rho".into())
    } else {
        None
    };
    m.inapplicable = why;
}

/// How the reason for a body that slides begins.
const SLIDES: &str = "the body slides on the ground";

/// The quantity at the sample.
pub(super) fn read(m: &Meter, f: &Sample) -> Option<EngineAndAnalysis> {
    let s = f.cur;
    let (Quantity::RollingAcceleration { body: b, ground }
    | Quantity::RollingFriction { body: b, ground }
    | Quantity::RollingFrictionNeeded { body: b, ground }) = &m.q
    else {
        unreachable!("{:?} is not a rolling quantity", m.q)
    };
    let (i, o) = (m.body_index(s, b)?, m.body_index(s, ground)?);
    let roll = rolling_contact(f, i, o)?;
    let x = &s.bodies[i];
    let g = s.gravity.length();
    let k = (x.inertia / x.mass).sqrt();
    Some(match &m.q {
        Quantity::RollingAcceleration { .. } => {
            let ax = f.rate(|y| Some(y.bodies[i].velocity.x))?;
            let ay = f.rate(|y| Some(y.bodies[i].velocity.y))?;
            (
                DVec2::new(ax, ay).dot(roll.downhill),
                Some(rolling_acceleration(g, roll.theta, k, roll.r)),
            )
        }
        Quantity::RollingFriction { .. } => (
            roll.friction.abs(),
            Some(rolling_friction(x.mass, g, roll.theta, k, roll.r)),
        ),
        _ => (
            roll.friction.abs() / roll.normal,
            Some(rolling_friction_needed(roll.theta, k, roll.r)),
        ),
    })
}

/// The rolling contact of a body on the ground at the sample.
struct RollingContact {
    /// Slope angle: between the contact normal and the vertical, rad.
    theta: f64,
    /// |G - contact point|, m.
    r: f64,
    /// Unit vector along the surface, downhill.
    downhill: DVec2,
    /// Centered friction force on the body along `downhill` (N) and normal force (N).
    friction: f64,
    normal: f64,
}

fn rolling_contact(f: &Sample, i: usize, o: usize) -> Option<RollingContact> {
    let s = f.cur;
    let c = s
        .contacts
        .iter()
        .find(|c| (c.body1 == i && c.body2 == o) || (c.body1 == o && c.body2 == i))?;
    // Normal from the ground to the body.
    let n = if c.body2 == i { c.normal } else { -c.normal };
    let p = c.points.iter().map(|x| x.point).sum::<DVec2>() / c.points.len().max(1) as f64;
    let g = s.gravity;
    if g.length() <= 0.0 {
        return None;
    }
    let gh = g.normalize();
    let along = gh - n * gh.dot(n);
    let downhill = along.normalize_or(n.perp());
    let theta = cross(n, -gh).abs().atan2(n.dot(-gh));
    let r = (s.bodies[i].com - p).length();
    let force = f.centered(|x| {
        let c = x
            .contacts
            .iter()
            .find(|c| (c.body1 == i && c.body2 == o) || (c.body1 == o && c.body2 == i))?;
        Some(if c.body2 == i {
            c.impulse_on_body2()
        } else {
            -c.impulse_on_body2()
        })
    })?;
    Some(RollingContact {
        theta,
        r,
        downhill,
        friction: force.dot(downhill),
        normal: force.dot(n),
    })
}
