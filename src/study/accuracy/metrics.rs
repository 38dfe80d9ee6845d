//! Pure measures over snapshots: the quantities the accuracy study compares.
//!
//! Everything here takes plain data (snapshots, body states, level definitions) and
//! returns numbers; nothing touches the engine.

use crate::analysis::energy::BodyMass;
use crate::analysis::momentum;
use crate::level::{BodyKind, Effect, EventDef, JointDef, JointKind, Level};
use crate::snapshot::{BodyState, JointState, Snapshot};
use glam::DVec2;

/// A body's mass properties, taken from the level (constant over a run).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MassProps {
    /// m, kg (0 for fixed and kinematic bodies).
    pub mass: f64,
    /// I_G, kg m^2 (0 when rotation is locked or the body is not dynamic).
    pub inertia: f64,
    /// Mass center G in the body frame, m.
    pub local_com: DVec2,
}

/// Mass properties of every body of a level, in the snapshot's body order, computed from the
/// level's shapes, densities and overrides (`sim::mass_properties`) rather than read back from
/// the engine: the study's measures then do not depend on when the engine refreshes them.
pub fn mass_props(level: &Level) -> Vec<MassProps> {
    level
        .bodies
        .iter()
        .map(|b| {
            if b.kind != BodyKind::Dynamic {
                return MassProps::default();
            }
            let mp = crate::sim::mass_properties(b);
            MassProps {
                mass: mp.mass() as f64,
                inertia: if b.lock_rotation {
                    0.0
                } else {
                    mp.principal_inertia() as f64
                },
                local_com: DVec2::new(mp.local_com.x as f64, mp.local_com.y as f64),
            }
        })
        .collect()
}

/// The bodies that carry mass, with their properties and mass-center positions.
fn massive<'a>(
    s: &'a [BodyState],
    m: &'a [MassProps],
) -> impl Iterator<Item = (&'a BodyState, &'a MassProps, DVec2)> + 'a {
    s.iter()
        .zip(m)
        .filter(|(_, m)| m.mass > 0.0)
        .map(|(b, m)| (b, m, b.world_point(m.local_com)))
}

/// The level's mass data for the scene totals of `analysis::energy`: m, I_G and G from the
/// textbook shape formulas; massless bodies (fixed, kinematic) count for nothing.
pub fn textbook_mass(m: &[MassProps]) -> impl Fn(usize, &BodyState) -> BodyMass + Copy + '_ {
    move |i, b| match m.get(i) {
        Some(p) if p.mass > 0.0 => BodyMass {
            m: p.mass,
            i_g: p.inertia,
            r_g: b.world_point(p.local_com),
        },
        _ => BodyMass {
            m: 0.0,
            i_g: 0.0,
            r_g: b.com,
        },
    }
}

/// Linear momentum L = sum of m v_G (IM-1), kg m/s.
pub fn linear_momentum(s: &Snapshot, m: &[MassProps]) -> DVec2 {
    massive(&s.bodies, m)
        .map(|(b, m, _)| momentum::linear_momentum(m.mass, b.velocity))
        .sum()
}

/// Size of the momentum carried by the bodies, sum of m |v_G| (the scale of a momentum error).
pub fn momentum_scale(s: &Snapshot, m: &[MassProps]) -> f64 {
    massive(&s.bodies, m)
        .map(|(b, m, _)| m.mass * b.velocity.length())
        .sum()
}

/// Angular momentum about the origin H_O = sum of (r_G x m v_G + I_G w) (IM-5 with H_G = I_G w, MK eq. 6/13), kg m^2/s.
pub fn angular_momentum(s: &Snapshot, m: &[MassProps]) -> f64 {
    massive(&s.bodies, m)
        .map(|(b, m, g)| {
            momentum::angular_momentum_about(m.mass, m.inertia, g, b.velocity, b.omega, DVec2::ZERO)
        })
        .sum()
}

/// Size of the angular momentum, sum of |r_G x m v_G| + |I_G w|.
pub fn angular_momentum_scale(s: &Snapshot, m: &[MassProps]) -> f64 {
    massive(&s.bodies, m)
        .map(|(b, m, g)| g.perp_dot(m.mass * b.velocity).abs() + (m.inertia * b.omega).abs())
        .sum()
}

/// Mass-weighted RMS distance between two poses (a, b) of one body, m.
///
/// A point at rho from G moves by dr_G + (R(a) - R(b)) rho. Averaged over the mass the cross term
/// vanishes (sum m rho = 0, MP-4) and |(R(a) - R(b)) rho|^2 = 2 |rho|^2 (1 - cos d_theta), whose mass
/// average is 2 k^2 (1 - cos d_theta) with k^2 = I_G / m (MP-3). So the distance is
/// sqrt(|dr_G|^2 + 2 k^2 (1 - cos d_theta)): position and orientation error in one length.
pub fn body_deviation(a: &BodyState, b: &BodyState, m: &MassProps) -> f64 {
    let k2 = if m.mass > 0.0 {
        m.inertia / m.mass
    } else {
        0.0
    };
    let d_theta = a.angle - b.angle;
    let dg = a.world_point(m.local_com) - b.world_point(m.local_com);
    (dg.length_squared() + 2.0 * k2 * (1.0 - d_theta.cos())).sqrt()
}

/// The largest [`body_deviation`] over the dynamic bodies of two states of one scene, m.
pub fn scene_deviation(a: &[BodyState], b: &[BodyState], m: &[MassProps]) -> f64 {
    a.iter()
        .zip(b)
        .zip(m)
        .filter(|(_, m)| m.mass > 0.0)
        .map(|((x, y), m)| body_deviation(x, y, m))
        .fold(0.0, f64::max)
}

/// A body state between two samples, `s` in [0, 1] (linear in position, velocity and angle).
pub fn lerp_body(a: &BodyState, b: &BodyState, s: f64) -> BodyState {
    // Angles are reported in (-pi, pi]: interpolate the short way round.
    let mut d = b.angle - a.angle;
    if d > std::f64::consts::PI {
        d -= std::f64::consts::TAU;
    } else if d < -std::f64::consts::PI {
        d += std::f64::consts::TAU;
    }
    BodyState {
        name: a.name.clone(),
        position: a.position.lerp(b.position, s),
        angle: a.angle + d * s,
        com: a.com.lerp(b.com, s),
        velocity: a.velocity.lerp(b.velocity, s),
        omega: a.omega + (b.omega - a.omega) * s,
        ..a.clone()
    }
}

/// How far apart a joint's two anchors are where the joint says they coincide, m.
///
/// Pins and welds lock both directions, so it is the full distance; sliders and pin-in-slot
/// joints lock only the direction normal to their axis (the axis turns with body1).
pub fn joint_separation(j: &JointState, def: &JointDef, body1_angle: f64) -> f64 {
    let d = j.anchor - j.anchor1;
    match def.kind {
        JointKind::Revolute | JointKind::Fixed => d.length(),
        JointKind::Prismatic | JointKind::PinSlot => {
            let axis = DVec2::new(def.axis.0, def.axis.1).normalize_or_zero();
            let axis = DVec2::from_angle(body1_angle).rotate(axis);
            d.perp_dot(axis).abs()
        }
    }
}

/// The largest anchor separation over a snapshot's joints, m (None without joints).
pub fn max_joint_separation(s: &Snapshot, level: &Level) -> Option<f64> {
    let mut out: Option<f64> = None;
    for j in &s.joints {
        let Some(def) = level.joints.iter().find(|d| d.name == j.name) else {
            continue;
        };
        let sep = joint_separation(j, def, s.bodies[j.body1].angle);
        out = Some(out.map_or(sep, |m: f64| m.max(sep)));
    }
    out
}

/// Least-squares slope of y against t (the drift rate, robust to the oscillation within a period).
pub fn slope(t: &[f64], y: &[f64]) -> Option<f64> {
    let n = t.len().min(y.len());
    if n < 2 {
        return None;
    }
    let (mt, my) = (
        t[..n].iter().sum::<f64>() / n as f64,
        y[..n].iter().sum::<f64>() / n as f64,
    );
    let (mut sty, mut stt) = (0.0, 0.0);
    for i in 0..n {
        sty += (t[i] - mt) * (y[i] - my);
        stt += (t[i] - mt) * (t[i] - mt);
    }
    (stt > 0.0).then(|| sty / stt)
}

/// The period of a regular oscillation, from the times of the kinetic energy's local minima
/// (the turning points: two per period). None unless at least three minima come at
/// regular intervals (spread within 10 %): a chaotic or monotonic motion has no period.
pub fn oscillation_period(t: &[f64], ke: &[f64]) -> Option<f64> {
    let n = t.len().min(ke.len());
    let peak = ke[..n].iter().cloned().fold(0.0, f64::max);
    if peak <= 0.0 {
        return None;
    }
    let mut minima = Vec::new();
    for i in 1..n.saturating_sub(1) {
        // A turning point: KE falls to near zero relative to its peak and rises again.
        if ke[i] <= ke[i - 1] && ke[i] < ke[i + 1] && ke[i] < 0.05 * peak {
            minima.push(t[i]);
        }
    }
    if minima.len() < 3 {
        return None;
    }
    let gaps: Vec<f64> = minima.windows(2).map(|w| w[1] - w[0]).collect();
    let mut sorted = gaps.clone();
    sorted.sort_by(f64::total_cmp);
    let median = sorted[sorted.len() / 2];
    let spread = sorted[sorted.len() - 1] - sorted[0];
    (median > 0.0 && spread <= 0.1 * median).then_some(2.0 * median)
}

/// What a level conserves, from its declared effects and definitions (not from a run).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Conserved {
    /// Contact-free, frictionless, undamped, unloaded, no motors or events (WE-14: T + V = const).
    pub energy: bool,
    /// Directions in which the external impulse is zero (IM-4): none, the one normal to gravity, or both.
    pub momentum: Option<MomentumAxes>,
    /// No external moment about the origin (IM-8): gravity off and nothing attached to the ground.
    pub angular_momentum: bool,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MomentumAxes {
    /// Only the component along this unit direction is conserved (normal to gravity).
    Along(DVec2),
    Both,
}

impl Conserved {
    pub fn any(&self) -> bool {
        self.energy || self.momentum.is_some() || self.angular_momentum
    }
}

/// Decides what a level conserves.
pub fn conserved(level: &Level) -> Conserved {
    let has = |e: Effect| level.effects.contains(&e);
    let grounded: Vec<bool> = level
        .bodies
        .iter()
        .map(|b| b.kind != BodyKind::Dynamic)
        .collect();
    let index = |name: &str| level.bodies.iter().position(|b| b.name == name);
    let is_ground = |name: &str| index(name).is_none_or(|i| grounded[i]);
    // Anything that can push on the system from outside: a joint or spring to a non-dynamic body,
    // a contact with a non-dynamic body that has a shape, a load, an event.
    let joint_to_ground = has(Effect::Joints)
        && level
            .joints
            .iter()
            .any(|j| is_ground(&j.body1) || is_ground(&j.body2));
    let spring_to_ground = has(Effect::Springs)
        && level
            .springs
            .iter()
            .any(|s| is_ground(&s.body1) || s.body2.as_deref().is_none_or(&is_ground));
    let contact_with_ground = has(Effect::Contacts)
        && level
            .bodies
            .iter()
            .any(|b| b.kind != BodyKind::Dynamic && b.shape.is_some());
    let moving_kinematic = level.bodies.iter().any(|b| {
        b.kind == BodyKind::Kinematic
            && (b.velocity != (0.0, 0.0) || b.omega != 0.0 || b.motion.is_some())
    });
    let external = joint_to_ground
        || spring_to_ground
        || contact_with_ground
        || moving_kinematic
        || !level.loads.is_empty()
        || level
            .events
            .iter()
            .any(|e| matches!(e, EventDef::Impulse { .. }))
        || has(Effect::Damping);
    let gravity = if has(Effect::Gravity) {
        let g = level.world.gravity.unwrap_or((0.0, -9.81));
        DVec2::new(g.0, g.1)
    } else {
        DVec2::ZERO
    };
    let energy = !(has(Effect::Contacts)
        || has(Effect::Friction)
        || has(Effect::Restitution)
        || has(Effect::Motors)
        || has(Effect::Damping)
        || has(Effect::Sleeping))
        && level.loads.is_empty()
        && level.events.is_empty()
        && !moving_kinematic;
    let momentum = if external {
        None
    } else if gravity == DVec2::ZERO {
        Some(MomentumAxes::Both)
    } else {
        Some(MomentumAxes::Along(gravity.normalize().perp()))
    };
    Conserved {
        energy,
        momentum,
        angular_momentum: !external && gravity == DVec2::ZERO,
    }
}

/// The conserved part of the linear momentum.
pub fn conserved_momentum(l: DVec2, axes: MomentumAxes) -> DVec2 {
    match axes {
        MomentumAxes::Both => l,
        MomentumAxes::Along(u) => u * l.dot(u),
    }
}

/// Indices of the points not dominated by another (lower-or-equal cost and error, one strictly):
/// the Pareto front of (cost, error), sorted by cost.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<usize> {
    let mut idx: Vec<usize> = (0..points.len())
        .filter(|&i| points[i].0.is_finite() && points[i].1.is_finite())
        .collect();
    idx.sort_by(|&a, &b| {
        points[a]
            .0
            .total_cmp(&points[b].0)
            .then(points[a].1.total_cmp(&points[b].1))
    });
    let mut front = Vec::new();
    let mut best = f64::INFINITY;
    for i in idx {
        if points[i].1 < best {
            best = points[i].1;
            front.push(i);
        }
    }
    front
}
