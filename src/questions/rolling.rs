//! Rolling quantities: a round body rolling on the ground, its acceleration down the slope, the
//! friction it needs, and the least coefficient of friction for rolling.
//!
//! The slope angle and the radius come from the engine's contact at the sample (normal and
//! point); the analyses are the closed forms of `analysis::closed_forms` (RK-8 with 6/1).

use super::meter::{EngineAndAnalysis, Meter};
use super::sample::Sample;
use crate::analysis::closed_forms::{
    rolling_acceleration, rolling_friction, rolling_friction_needed,
};
use crate::analysis::cross;
use crate::level::Quantity;
use glam::DVec2;

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
