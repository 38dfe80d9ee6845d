//! Force quantities read on the reference trajectory (`analysis::reference`): a joint's
//! reaction from the constraint rows' multipliers, and a rolling contact's normal and friction
//! forces from its two rows' multipliers, at a time where no closed form gives them (a pin of a
//! chain, a pin on a moving support, a disc rolling on a curve).

use super::contact_reading::contact_component;
use super::forces::component_of;
use super::meter::Meter;
use crate::analysis::reference::{ContactReaction, Instant, Reference};
use crate::level::Quantity;
use glam::DVec2;

/// Instants a windowed quantity's mean is taken over (the engine averages its steps over the
/// window): the trapezoid rule on 9 instants across it, none before the start.
const WINDOW_POINTS: usize = 9;

/// The quantity at time t on the reference trajectory (its mean over the quantity's `window`,
/// as the engine's), or why the scene is outside it. `contact_seen`: the first contact of the
/// engine's run the reference does not hold.
pub(super) fn reference_value(
    m: &Meter,
    contact_seen: Option<&(f64, String)>,
    t: f64,
) -> Result<f64, String> {
    let model = match m.facts.reference.as_deref() {
        Some(Ok(model)) => model,
        Some(Err(why)) => return Err(why.clone()),
        None => return Err("no reference trajectory was prepared".into()),
    };
    let window = m.q.averaging_window();
    let times: Vec<f64> = if window > 0.0 {
        (0..WINDOW_POINTS)
            .map(|i| (t + window * (i as f64 / (WINDOW_POINTS - 1) as f64 - 0.5)).max(0.0))
            .collect()
    } else {
        vec![t]
    };
    let last = times.iter().copied().fold(t, f64::max);
    if let Some(why) = model.refused_after_start().filter(|_| last > 0.0) {
        return Err(why.to_string());
    }
    if let Some((_, why)) = contact_seen.filter(|(t0, _)| *t0 < last) {
        return Err(why.clone());
    }
    let tr = model.integrate(&times)?;
    let values = tr
        .instants
        .iter()
        .map(|x| value_at(m, model, x))
        .collect::<Result<Vec<f64>, String>>()?;
    let n = values.len();
    Ok(if n == 1 {
        values[0]
    } else {
        let inner: f64 = values[1..n - 1].iter().sum();
        (inner + 0.5 * (values[0] + values[n - 1])) / (n - 1) as f64
    })
}

/// The quantity at one instant of the reference.
fn value_at(m: &Meter, model: &Reference, x: &Instant) -> Result<f64, String> {
    let index = |name: &str| {
        m.facts
            .level_index(name)
            .filter(|&i| i < x.bodies.len())
            .ok_or_else(|| format!("no body \"{name}\""))
    };
    Ok(match &m.q {
        Quantity::JointReaction {
            joint, component, ..
        } => {
            let (force, g, anchor) = joint_reaction(m, x, joint, |i| model.moves(i))?;
            component_of(*component, force, g, anchor)
        }
        Quantity::JointForce(joint) => joint_reaction(m, x, joint, |i| model.moves(i))?.0.length(),
        Quantity::ContactNormalForce { body, other } => {
            pair(x, index(body)?, index(other)?)?.normal
        }
        Quantity::ContactForceFrom {
            body,
            other,
            component,
            ..
        } => {
            let (i, o) = (index(body)?, index(other)?);
            let (force, n) = force_on(pair(x, i, o)?, i);
            contact_component(*component, force, n)
        }
        Quantity::ContactForce(body) => {
            let i = index(body)?;
            let total: DVec2 = x
                .contacts
                .iter()
                .filter(|c| c.body == i || c.other == i)
                .map(|c| force_on(c, i).0)
                .sum();
            total.length()
        }
        q => return Err(format!("{q:?} is not read on the reference trajectory")),
    })
    .and_then(|v: f64| {
        if v.is_finite() {
            Ok(v)
        } else {
            Err("the reference gave no finite value".into())
        }
    })
}

/// Joint `name`'s reaction on its moving body (the force), that body's G and the joint's
/// anchor, world, as `forces::read` reads the engine's.
fn joint_reaction(
    m: &Meter,
    x: &Instant,
    name: &str,
    moves: impl Fn(usize) -> bool,
) -> Result<(DVec2, DVec2, DVec2), String> {
    let (k, j) = m
        .facts
        .joints
        .iter()
        .enumerate()
        .find(|(_, j)| j.name == name)
        .ok_or_else(|| format!("no joint \"{name}\" in the reference"))?;
    let on2 = x
        .reactions
        .get(k)
        .ok_or_else(|| format!("no reaction for joint \"{name}\""))?
        .force;
    let b2 = x.bodies[j.body2];
    let com2 = m
        .facts
        .bodies
        .get(j.body2)
        .map_or(DVec2::ZERO, |f| f.textbook.com);
    let anchor = b2.com + DVec2::from_angle(b2.angle).rotate(j.anchor2 - com2);
    Ok(if moves(j.body2) {
        (on2, b2.com, anchor)
    } else {
        (-on2, x.bodies[j.body1].com, anchor)
    })
}

/// The rolling contact between bodies a and b.
fn pair(x: &Instant, a: usize, b: usize) -> Result<&ContactReaction, String> {
    x.contacts
        .iter()
        .find(|c| (c.body, c.other) == (a, b) || (c.body, c.other) == (b, a))
        .ok_or_else(|| "the reference holds no rolling contact between the two bodies".into())
}

/// The contact's force on body i and the normal from the other body into i.
fn force_on(c: &ContactReaction, i: usize) -> (DVec2, DVec2) {
    let on_body = c.normal * c.n + c.tangential * c.n.perp();
    if c.body == i {
        (on_body, c.n)
    } else {
        (-on_body, -c.n)
    }
}
