//! Periods of oscillation: a body swinging on a pivot, a body on springs, one mode of a
//! mechanism.
//!
//! The engine's period is the mean time between successive zero crossings of the same
//! direction of a rate (between the extremes of its coordinate): the body's omega for a
//! pendulum, its velocity along its first spring (less its partner's, for a free pair) for a
//! spring mass, the modal rate phi^T M v for a mode.
//!
//! The analysis is always the general method, the equations of motion of the whole scene
//! linearized about its equilibrium (PL-14, `analysis::small_oscillations`: mass, stiffness and
//! damping matrices with the joints, couplings, rolling and smooth resting contacts eliminated):
//! the period of the mode the start excites, at the start's amplitude when the mechanism has
//! one degree of freedom and no damper (the energy integral along it, exact at any swing: the
//! elliptic-integral pendulum period, PL-5), the linearized (damped) period otherwise. Where it
//! cannot be formed or does not fit (no stable equilibrium, several modes excited, a swing too
//! large for "small", a contact that neither rolls nor slides smoothly, a motor), the analysis
//! says why ([`Meter::inapplicable`]) and gives no number.
//!
//! The one-body closed forms (the exact pendulum period with torsion springs to the ground,
//! 2 pi sqrt(m / sum k) and its reduced-mass and damped forms) are kept as cross-checks only,
//! computed where their assumptions, stated as predicates ([`pendulum_breaks`],
//! [`spring_mass_breaks`]), hold; tests hold them to the general method
//! (`QuestionProbe::closed_form_cross_check`).

use super::meter::{EngineAndAnalysis, Meter};
use super::result::CANNOT_BE_READ;
use super::sample::Sample;
use super::snapshot_reading::{joint_index, to_local};
use crate::analysis::closed_forms::{
    damped_period, energy_integral_period, pendulum_period, reduced_mass, spring_mass_period,
};
use crate::analysis::energy::spring_potential;
use crate::analysis::mass::parallel_axis;
use crate::analysis::oscillation::{Crossings, Extremes};
use crate::analysis::small_oscillations::{
    Mechanism, Mode, SmallOscillations, SMALL_AMPLITUDE_PERIOD_ERROR,
};
use crate::level::Quantity;
use crate::level::{BodyKind, JointKind};
use crate::snapshot::Snapshot;
use glam::DVec2;

/// What a period quantity accumulates over the run.
#[derive(Clone, Default)]
pub(super) struct State {
    /// Zero crossings of an oscillating velocity (periods).
    pub crossings: Crossings,
    /// Direction of the spring a `SpringPeriod` body oscillates along.
    pub spring_axis: Option<DVec2>,
    /// The general method's period, from the linearized equations of the whole scene
    /// (PL-14), which is the analysis.
    pub linearized: Option<f64>,
    /// The one-body closed form's period, where its assumptions hold (a cross-check of
    /// `linearized`, never the analysis).
    pub closed_form: Option<f64>,
    /// `ModePeriod`: per snapshot body, the weights (m dx_G, I_G dtheta) of the mode's
    /// modal rate eta' = phi^T M v, and the support's velocity at t = 0 and acceleration.
    pub modal_weights: Option<Vec<(DVec2, f64)>>,
    pub support_motion: (DVec2, DVec2),
    /// `EquilibriumAngle`: the body's angle at its last two extremes (interpolated), and the
    /// equilibrium angle of its mechanism (PL-14), found once.
    pub swing: Extremes,
    pub equilibrium: Option<f64>,
    /// For `SpringPeriod`: the free body at the spring's other end, when the body's springs all
    /// join it to that one (their relative motion is what vibrates).
    pub spring_partner: Option<usize>,
}

/// Follows the oscillating rate over the step from `prev` to `s`.
pub(super) fn advance(m: &mut Meter, st: &mut State, prev: &Snapshot, s: &Snapshot) {
    match &m.q {
        Quantity::PendulumPeriod { body, joint } => {
            if let Some(i) = m.body_index(s, body) {
                if st.crossings.is_empty() {
                    // (The joints' anchors from a stepped snapshot: the initial one has none.)
                    let special = pendulum_breaks(m, s, i, joint);
                    if special.is_none() {
                        st.closed_form = pendulum_theory(m, s, body, joint);
                    }
                    general(m, st, i, special, |shape| shape[i].1);
                    st.crossings.add(prev.time, prev.bodies[i].omega);
                }
                st.crossings.add(s.time, s.bodies[i].omega);
            }
        }
        Quantity::SpringPeriod(body) => {
            if let Some(i) = m.body_index(s, body) {
                // The rate the spring stretches at, along its axis: the body's velocity, less the
                // partner's when both ends are free (a pair drifting on a floor oscillates about
                // its moving mass center, and a body's own velocity may never turn back).
                let rate = |snap: &Snapshot, a: DVec2, partner: Option<usize>| {
                    let v = snap.bodies[i].velocity
                        - partner.map_or(DVec2::ZERO, |j| snap.bodies[j].velocity);
                    v.dot(a)
                };
                if st.spring_axis.is_none() {
                    let init: &Snapshot = m.init.as_deref().unwrap_or(prev);
                    let sp = init
                        .springs
                        .iter()
                        .find(|x| !x.torsion && (x.body1 == i || x.body2 == Some(i)));
                    st.spring_axis = sp.map(|x| (x.point2 - x.point1).normalize_or(DVec2::X));
                    st.spring_partner = spring_partner(init, i);
                    let special = spring_mass_breaks(m, st, init, i);
                    if special.is_none() {
                        st.closed_form = spring_mass_theory(m, st, init, i);
                    }
                    match st.spring_axis {
                        Some(a) => {
                            let partner = st.spring_partner;
                            general(m, st, i, special, |shape| {
                                let own = shape[i].0;
                                (own - partner.map_or(DVec2::ZERO, |j| shape[j].0)).dot(a)
                            });
                            st.crossings
                                .add(prev.time, rate(prev, a, st.spring_partner));
                        }
                        None => m.inapplicable = Some("no linear spring acts on the body".into()),
                    }
                }
                if let Some(a) = st.spring_axis {
                    st.crossings.add(s.time, rate(s, a, st.spring_partner));
                }
            }
        }
        Quantity::ModePeriod { body, mode } => {
            if st.crossings.is_empty() {
                let init: &Snapshot = m.init.as_deref().unwrap_or(prev);
                match mode_of(m, init, body, *mode) {
                    Ok((t, w, support)) => {
                        st.linearized = Some(t);
                        st.modal_weights = Some(w);
                        st.support_motion = support;
                    }
                    Err(e) => m.inapplicable = Some(e),
                }
                if let Some(r) = modal_rate(st, prev) {
                    st.crossings.add(prev.time, r);
                }
            }
            if let Some(r) = modal_rate(st, s) {
                st.crossings.add(s.time, r);
            }
        }
        Quantity::EquilibriumAngle(body) => {
            if let Some(i) = m.body_index(s, body) {
                if st.crossings.is_empty() {
                    st.crossings.add(prev.time, prev.bodies[i].omega);
                    match equilibrium_angle(m, i) {
                        Ok(a) => st.equilibrium = Some(a),
                        Err(e) => m.inapplicable = Some(e),
                    }
                }
                st.crossings.add(s.time, s.bodies[i].omega);
                let (w0, w1) = (prev.bodies[i].omega, s.bodies[i].omega);
                if (w0 > 0.0 && w1 <= 0.0) || (w0 < 0.0 && w1 >= 0.0) {
                    // omega taken linear over the step: it is zero tau into it, and the angle
                    // there is the trapezoid's, theta_prev + w0 tau / 2.
                    let tau = (s.time - prev.time) * w0 / (w0 - w1);
                    st.swing
                        .add(w0 > 0.0, prev.bodies[i].angle + 0.5 * w0 * tau);
                }
            }
        }
        _ => {}
    }
}

/// Mode `index` (0 the slowest) of the mechanism that holds `body`: its period (damped where
/// dampers act), the modal rate's weights per snapshot body, and the support's velocity at
/// t = 0 and acceleration; or why there is no such mode to time.
#[allow(clippy::type_complexity)]
fn mode_of(
    m: &Meter,
    init: &Snapshot,
    body: &str,
    index: usize,
) -> Result<(f64, Vec<(DVec2, f64)>, (DVec2, DVec2)), String> {
    let level = m.facts.level.as_ref().ok_or("the level is not kept")?;
    let around = level
        .bodies
        .iter()
        .position(|b| b.name == body)
        .ok_or("the body is not in the level")?;
    let mech = Mechanism::of_level(level, around)?;
    let osc = mech.small_oscillations()?;
    let mode = osc.modes.get(index).ok_or_else(|| {
        format!(
            "the mechanism has {} oscillating mode(s): mode {index} does not exist (0 is the slowest)",
            osc.modes.len()
        )
    })?;
    // One degree of freedom without dampers: the period at the start's amplitude, exact at any
    // swing, as PendulumPeriod and SpringPeriod take it (a cylinder rolling with springs at its
    // top, 10 mm: 0.609128 s, where the linearized 0.608367 s is 1.25e-3 short; n14_12).
    let period = match amplitude_period_exact(&osc, mode) {
        Some(t) => t,
        None => {
            if osc.period_error > SMALL_AMPLITUDE_PERIOD_ERROR {
                return Err(format!(
                    "the start's swing is not small: along its most excited mode the period at that amplitude differs from the linearized one by {:.2} %, over the {:.1} % bound",
                    100.0 * osc.period_error,
                    100.0 * SMALL_AMPLITUDE_PERIOD_ERROR
                ));
            }
            mode.damped_period
                .ok_or("the mode is overdamped: it does not oscillate")?
        }
    };
    // phi^T M v per body: (m dx_G) . v_G + (I_G dtheta) omega, by name into the snapshot.
    let mut weights = vec![(DVec2::ZERO, 0.0); init.bodies.len()];
    for (k, b) in mech.members.iter().enumerate().filter(|(_, b)| b.moves) {
        let j = m
            .body_index(init, &b.name)
            .ok_or("a body of the mechanism is not in the snapshot")?;
        let (dx, dth) = mode.shape[k];
        weights[j] = (dx * b.mass, dth * b.inertia);
    }
    Ok((
        period,
        weights,
        (mech.support_velocity, mech.support_acceleration),
    ))
}

/// Why a period has no engine value where its family can tell: `ModePeriod` follows the modal
/// rate, whose weights are the linearized scene's mode shape; where the linearization refuses
/// the scene (a puck in an `Arc` bowl) there is no rate to time, at any setting (the probe of
/// n14_04 read NaN with "too few oscillations, no contact, or a missing item").
pub(super) fn why_missing(m: &Meter, st: &State) -> Option<String> {
    match &m.q {
        Quantity::ModePeriod { mode, .. } if st.modal_weights.is_none() => Some(format!(
            "{CANNOT_BE_READ}: the engine's value times mode {mode}'s modal rate phi^T M v, whose weights are the mode shape of the linearized scene, and the linearization gives none here (its reason below)"
        )),
        _ => None,
    }
}

/// The modal rate eta' = phi^T M v at snapshot s, velocities taken relative to the support.
fn modal_rate(st: &State, s: &Snapshot) -> Option<f64> {
    let w = st.modal_weights.as_ref()?;
    let (v0, a) = st.support_motion;
    let vs = v0 + a * s.time;
    Some(
        w.iter()
            .zip(&s.bodies)
            .map(|((mx, ith), b)| mx.dot(b.velocity - vs) + ith * b.omega)
            .sum(),
    )
}

/// The equilibrium angle of body i's mechanism (PL-14's equilibrium, in the frame of a support
/// that may accelerate uniformly: VW-4), or why there is none to compare with.
fn equilibrium_angle(m: &Meter, i: usize) -> Result<f64, String> {
    let level = m.facts.level.as_ref().ok_or("the level is not kept")?;
    let osc = Mechanism::of_level(level, i)?.small_oscillations()?;
    osc.equilibrium
        .get(i)
        .map(|e| e.1)
        .ok_or_else(|| "the body is not a member of its mechanism".into())
}

/// The quantity at the sample.
pub(super) fn read(m: &Meter, st: &State, f: &Sample) -> Option<EngineAndAnalysis> {
    let s = f.cur;
    Some(match &m.q {
        Quantity::PendulumPeriod { .. }
        | Quantity::SpringPeriod(_)
        | Quantity::ModePeriod { .. } => (st.crossings.period(), st.linearized),
        Quantity::EquilibriumAngle(b) => {
            let i = m.body_index(s, b)?;
            // The middle of the last whole swing; a body that has not swung twice is read
            // where it is, if it is still (1e-6 rad/s: far under any swing a question is about).
            let engine = match st.swing.middle() {
                Some(x) => x,
                None if s.bodies[i].omega.abs() < 1e-6 => s.bodies[i].angle,
                None => f64::NAN,
            };
            (engine, st.equilibrium)
        }
        q => unreachable!("{q:?} is not a period"),
    })
}

/// The one-body spring-mass closed form for body i where [`spring_mass_breaks`] holds it:
/// 2 pi sqrt(m / sum k) with the level's k and the engine's m, the reduced mass for a free
/// pair, damped where the springs' dampers act (a cross-check of the general method only).
fn spring_mass_theory(m: &Meter, st: &State, s: &Snapshot, i: usize) -> Option<f64> {
    let springs = || m.facts.springs.iter().filter(|x| !x.torsion && x.holds(i));
    let k: f64 = springs().map(|x| x.stiffness).sum();
    let c: f64 = springs().map(|x| x.damping).sum();
    let mass = match st.spring_partner {
        Some(j) => reduced_mass(s.bodies[i].mass, s.bodies[j].mass),
        None => s.bodies[i].mass,
    };
    if c > 0.0 {
        damped_period(mass, k, c)
    } else {
        (k > 0.0).then(|| spring_mass_period(mass, k))
    }
}

/// The amplitude's lengthening of a one-degree-of-freedom period above which the period at the
/// start's amplitude is the analysis, not the linearized one.
const AMPLITUDE_MATTERS: f64 = 1e-5;

/// The period at the start's amplitude (the energy integral along the one free coordinate),
/// where it is exact and differs from the linearized one: one degree of freedom, no damper, the
/// swing lengthening the period by over [`AMPLITUDE_MATTERS`]. None otherwise.
fn amplitude_period_exact(osc: &SmallOscillations, mode: &Mode) -> Option<f64> {
    let one_dof = osc.modes.len() + osc.free_motions == 1;
    let undamped = mode.damped_period == Some(mode.period);
    if one_dof && undamped && osc.period_error > AMPLITUDE_MATTERS {
        osc.amplitude_period
    } else {
        None
    }
}

/// The general method's period for body i, into `st.linearized`, or why there is none, into
/// `m.inapplicable`. `measured` is the excited mode's component in the coordinate whose rate
/// the engine's zero crossings follow (from the mode's shape, per body (dx_G, dtheta)).
/// `special`: why the one-body closed form does not fit either, when it does not (the note
/// then says both).
fn general(
    m: &mut Meter,
    st: &mut State,
    i: usize,
    special: Option<String>,
    measured: impl Fn(&[(DVec2, f64)]) -> f64,
) {
    match general_period(m, i, measured) {
        Ok(t) => st.linearized = Some(t),
        Err(e) => {
            let general =
                format!("the linearized equations of the scene (PL-14) give no period: {e}");
            m.inapplicable = Some(match special {
                Some(why) => format!("{why}, so the one-body formula does not fit; {general}"),
                None => general,
            })
        }
    }
}

/// The period of the mode the start excites: at the start's amplitude (the energy integral
/// along the one free coordinate, exact at any swing) for one degree of freedom without
/// dampers; else the linearized period, damped where dampers act, when the start is within
/// the small-amplitude bound; otherwise why not.
fn general_period(
    m: &Meter,
    i: usize,
    measured: impl Fn(&[(DVec2, f64)]) -> f64,
) -> Result<f64, String> {
    let level = m.facts.level.as_ref().ok_or("the level is not kept")?;
    let osc = Mechanism::of_level(level, i)?.small_oscillations()?;
    let mode = osc.excited()?;
    let along = measured(&mode.shape);
    let scale: f64 = mode
        .shape
        .iter()
        .map(|(d, a)| d.length() + a.abs())
        .fold(0.0, f64::max);
    if along.abs() <= 1e-6 * scale {
        return Err("the excited mode does not move the coordinate the period is read from".into());
    }
    // One degree of freedom without dampers: the energy integral is the period at the start's
    // amplitude, exact at any swing, where the swing lengthens it measurably (over 1e-5: the
    // integral's own error, (ds / reach)^2 and its turning points, is about 2e-6, so under that
    // the linear period is the nearer).
    if let Some(t) = amplitude_period_exact(&osc, mode) {
        return Ok(t);
    }
    if osc.period_error > SMALL_AMPLITUDE_PERIOD_ERROR {
        return Err(format!(
            "the start's swing is not small: its period at that amplitude (the energy integral along the mode, {:.6} s) differs from the linearized {:.6} s by {:.2} %, over the {:.1} % bound",
            osc.amplitude_period.unwrap_or(f64::NAN),
            mode.period,
            100.0 * osc.period_error,
            100.0 * SMALL_AMPLITUDE_PERIOD_ERROR
        ));
    }
    mode.damped_period
        .ok_or_else(|| "the excited mode is overdamped: it does not oscillate".into())
}

/// The exact large-amplitude period of a body swinging about the joint's fixed anchor, from the
/// engine's initial state: the elliptic integral under gravity alone, the energy integral with
/// the torsion springs that hold the body to the ground.
fn pendulum_theory(m: &Meter, s: &Snapshot, body: &str, joint: &str) -> Option<f64> {
    let i = m.body_index(s, body)?;
    let init = m.init.as_ref()?;
    // The pin where it was at the start (a kinematic pivot moves on): the point of the body
    // at the pin now, placed with the body's start pose.
    let j = &s.joints[joint_index(s, joint)?];
    let at_pin = if j.body2 == i { j.anchor1 } else { j.anchor };
    let b0 = &init.bodies[i];
    let o = b0.position + DVec2::from_angle(b0.angle).rotate(to_local(&s.bodies[i], at_pin));
    // In the frame of a pivot that accelerates uniformly gravity reads g - a (VW-4); the
    // pivot's start velocity drops out: the swing's energy is in omega alone.
    let pivot = if j.body2 == i { j.body1 } else { j.body2 };
    let a = m
        .facts
        .level
        .as_ref()
        .and_then(|l| l.bodies.get(pivot))
        .and_then(|d| d.motion)
        .and_then(|mo| mo.uniform_translation())
        .map_or(DVec2::ZERO, |a| DVec2::new(a.0, a.1));
    let gravity = s.gravity - a;
    let g = gravity.length();
    let r = b0.com - o;
    let d = r.length();
    let i_o = parallel_axis(b0.inertia, b0.mass, d);
    // Torsion springs on the body (to the ground: pendulum_breaks refuses others), each with its
    // deflection at the start and the sign the body's angle enters it with.
    let springs: Vec<(f64, f64, f64)> = m
        .facts
        .springs
        .iter()
        .filter(|x| x.torsion && x.holds(i))
        .filter_map(|x| {
            let now = init
                .springs
                .iter()
                .find(|y| y.torsion && y.name == x.name)?;
            let sign = if x.body1 == i { 1.0 } else { -1.0 };
            Some((x.stiffness, now.extension, sign))
        })
        .collect();
    if springs.is_empty() {
        if g <= 0.0 || d <= 0.0 {
            return None;
        }
        let cos_phi = r.dot(gravity / g) / d;
        let one_minus_cos = (1.0 - cos_phi) + i_o * b0.omega * b0.omega / (2.0 * b0.mass * g * d);
        if one_minus_cos >= 2.0 {
            return None;
        }
        let theta0 = (1.0 - one_minus_cos).clamp(-1.0, 1.0).acos();
        return Some(pendulum_period(i_o, b0.mass, g, d, theta0));
    }
    // phi: OG's angle from straight down (counter-clockwise), which turns with the body.
    let phi0 = if g > 0.0 && d > 0.0 {
        let down = gravity / g;
        down.perp_dot(r).atan2(down.dot(r))
    } else {
        0.0
    };
    let v = |phi: f64| {
        let turned = phi - phi0;
        let elastic: f64 = springs
            .iter()
            .map(|(k, x0, sign)| spring_potential(*k, x0 + sign * turned))
            .sum();
        b0.mass * g * d * (1.0 - phi.cos()) + elastic
    };
    energy_integral_period(i_o, v, phi0, b0.omega, 4.0 * std::f64::consts::PI)
}

/// The pendulum closed form's assumptions, as a predicate: None where they hold, else the first
/// that fails. It is the period of body i swinging on a fixed pin (or one translating uniformly)
/// under gravity and torsion springs to the ground, nothing else: no other joint, linear spring
/// (a spring at the tip adds k L^2 to the restoring moment), load, motor, damping or coupling.
fn pendulum_breaks(m: &Meter, s: &Snapshot, i: usize, joint: &str) -> Option<String> {
    let facts = &m.facts;
    let j = facts.joints.iter().find(|x| x.name == joint)?;
    let body = |k: usize| s.bodies.get(k).map_or("?", |b| b.name.as_str());
    if j.kind != JointKind::Revolute {
        return Some(format!("joint \"{joint}\" is not a pin (revolute)"));
    }
    let pivot = if j.body1 == i { j.body2 } else { j.body1 };
    match s.bodies.get(pivot).map(|b| b.kind) {
        Some(BodyKind::Fixed) | None => {}
        Some(BodyKind::Kinematic) => {
            // A pivot that moves without turning, at a constant velocity or acceleration, is
            // fixed in a frame where gravity reads g - a: the formula holds there.
            let def = facts.level.as_ref().and_then(|l| l.bodies.get(pivot));
            let translates = def.is_some_and(|d| {
                d.omega == 0.0 && d.motion.is_none_or(|mo| mo.uniform_translation().is_some())
            });
            if !translates {
                return Some(format!(
                    "the pin is on \"{}\", a kinematic body the level turns or shakes: the period formula is for a pivot fixed in a frame that does not turn and accelerates uniformly",
                    body(pivot)
                ));
            }
        }
        Some(BodyKind::Dynamic) => {
            return Some(format!(
                "the pin is on \"{}\", a free body: the period formula is for a fixed pivot",
                body(pivot)
            ))
        }
    }
    if j.motor {
        return Some(format!("joint \"{joint}\" has a motor"));
    }
    if let Some(other) = facts
        .joints
        .iter()
        .find(|x| x.name != joint && (x.body1 == i || x.body2 == i))
    {
        return Some(format!("joint \"{}\" also holds the body", other.name));
    }
    for x in facts.springs.iter().filter(|x| x.holds(i)) {
        if !x.torsion {
            return Some(format!(
                "spring \"{}\" acts on the body (the formula takes gravity and torsion springs to the ground)",
                x.name
            ));
        }
        if x.damping != 0.0 {
            return Some(format!(
                "torsion spring \"{}\" has a damper (c = {} N m s/rad): the formula is the undamped period",
                x.name, x.damping
            ));
        }
        let other = if x.body1 == i { x.body2 } else { Some(x.body1) };
        if let Some(o) =
            other.filter(|&o| s.bodies.get(o).is_some_and(|b| b.kind != BodyKind::Fixed))
        {
            return Some(format!(
                "torsion spring \"{}\" joins the body to \"{}\", which moves",
                x.name,
                body(o)
            ));
        }
    }
    if let Some(why) = coupled(s, i, "the pendulum's period") {
        return Some(why);
    }
    let info = facts.bodies.get(i)?;
    if info.damped {
        return Some("the body is damped: the formula is the undamped period".into());
    }
    if let Some(load) = info.loads.first() {
        return Some(format!("load \"{load}\" acts on the body"));
    }
    None
}

/// A coupling (a gear mesh, a rack and pinion, a cable) on body i moves other bodies with it, and
/// their inertia with it, which a one-body period `formula` leaves out: a rack on a spring meshing
/// with a pinion of inertia I vibrates with m + I / r^2, not m (tests/newuser/oscillations/n11_11: 22.5%
/// short). The linearized period holds couplings as constraints.
fn coupled(s: &Snapshot, i: usize, formula: &str) -> Option<String> {
    let c = s
        .couplings
        .iter()
        .find(|c| c.terms.iter().any(|t| t.0 == i))?;
    Some(format!(
        "coupling \"{}\" moves other bodies with the body: {formula} leaves out their inertia",
        c.name
    ))
}

/// The spring-mass closed form's assumptions, as a predicate: None where they hold, else the
/// first that fails. Body i (with its partner, if any) moves along the one line of its linear
/// springs, under them and their dampers alone: every spring joins it to the ground or to one
/// free partner (a second moving body on its springs couples their motions: two modes, neither
/// 2 pi sqrt(m / sum k)), and it rests on nothing (a rolling contact adds I_G / r^2 to m).
fn spring_mass_breaks(m: &Meter, st: &State, s: &Snapshot, i: usize) -> Option<String> {
    let facts = &m.facts;
    let axis = st.spring_axis?;
    let partner = st.spring_partner;
    if let Some(x) = s.springs.iter().find(|x| {
        let other = match (x.body1 == i, x.body2) {
            (true, o) => o,
            (false, Some(b)) if b == i => Some(x.body1),
            _ => return false,
        };
        let moves =
            other.is_some_and(|o| s.bodies.get(o).is_some_and(|b| b.kind != BodyKind::Fixed));
        !x.torsion && moves && other != partner
    }) {
        return Some(format!(
            "spring \"{}\" joins the body to another that moves on other springs or joints: the bodies' motions are coupled (several modes), which 2 pi sqrt(m / sum k) leaves out",
            x.name
        ));
    }
    let rests = facts
        .level
        .as_ref()
        .and_then(|l| {
            let k = l.bodies.iter().position(|b| b.name == s.bodies[i].name)?;
            Mechanism::of_level(l, k).ok()
        })
        .is_some_and(|mech| !mech.contacts.is_empty());
    if rests {
        return Some(
            "the body rests on a face at the start: rolling adds I_G / r^2 to the mass, which 2 pi sqrt(m / sum k) leaves out".into(),
        );
    }
    for x in facts.springs.iter().filter(|x| x.holds(i)) {
        if x.torsion {
            return Some(format!("torsion spring \"{}\" acts on the body", x.name));
        }
        let line = s
            .springs
            .iter()
            .find(|y| !y.torsion && y.name == x.name)
            .map(|y| y.point2 - y.point1);
        if let Some(l) = line.filter(|l| l.length() > 0.0) {
            if axis.perp_dot(l.normalize()).abs() > 1e-6 {
                return Some(format!(
                    "spring \"{}\" is not in line with the others: 2 pi sqrt(m / sum k) adds the stiffnesses of springs in one line",
                    x.name
                ));
            }
        }
    }
    if let Some(j) = facts.joints.iter().find(|x| {
        let free_slider = x.kind == JointKind::Prismatic && !x.motor;
        (x.body1 == i || x.body2 == i) && !free_slider
    }) {
        return Some(format!(
            "joint \"{}\" holds the body (only a slider along the springs leaves the formula's motion)",
            j.name
        ));
    }
    if let Some(why) = coupled(s, i, "2 pi sqrt(m / k)") {
        return Some(why);
    }
    let info = facts.bodies.get(i)?;
    if info.damped {
        return Some("the body is damped (body damping, not a spring's damper)".into());
    }
    if let Some(load) = info.loads.first() {
        return Some(format!("load \"{load}\" acts on the body"));
    }
    None
}

/// The free body at the other end of every spring of body i, when there is one and only one
/// (dynamic, neither jointed nor on another spring): then the pair's relative motion is a single
/// vibration of the reduced mass. None for a body on a spring to the ground (or on several).
fn spring_partner(s: &Snapshot, i: usize) -> Option<usize> {
    let ends = |x: &crate::snapshot::SpringState| -> Option<Option<usize>> {
        if x.torsion {
            return None;
        }
        match (x.body1 == i, x.body2) {
            (true, other) => Some(other),
            (false, Some(b)) if b == i => Some(Some(x.body1)),
            _ => None,
        }
    };
    let mut others = s.springs.iter().filter_map(ends);
    let j = others.next()??;
    if !others.all(|o| o == Some(j)) || s.bodies[j].mass <= 0.0 {
        return None;
    }
    let jointed = s.joints.iter().any(|x| x.body1 == j || x.body2 == j);
    let other_springs = s.springs.iter().any(|x| {
        !x.torsion && (x.body1 == j || x.body2 == Some(j)) && !(x.body1 == i || x.body2 == Some(i))
    });
    (!jointed && !other_springs).then_some(j)
}
