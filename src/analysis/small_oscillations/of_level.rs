//! The mechanism of a level around one body, phase by phase: the pairs of bodies that act on
//! each other, the connected set, the support it hangs on, its members, its constraints, its
//! springs and its loads.

use super::{ConstantLoad, Link, Mechanism, Member};
use crate::analysis::applied_forces::AppliedForces;
use crate::analysis::links::joined_bodies;
use crate::analysis::mass::of_body;
use crate::analysis::resting_contacts::resting_contacts;
use crate::level::{BodyDef, BodyKind, Coordinate, Effect, Level, Profile, DEFAULT_DENSITY};
use glam::DVec2;

/// Two bodies that act on each other; None for the ground (a spring anchored to it).
type Pair = (usize, Option<usize>);

fn v(p: (f64, f64)) -> DVec2 {
    DVec2::new(p.0, p.1)
}

fn index(level: &Level, name: &str) -> Option<usize> {
    level.bodies.iter().position(|b| b.name == name)
}

fn dynamic(level: &Level, k: usize) -> bool {
    level.bodies[k].kind == BodyKind::Dynamic
}

impl Mechanism {
    /// The mechanism of `level` that holds body `around` (its index in `level.bodies`): the
    /// dynamic bodies joined to it by joints, couplings and springs, and what holds them, with
    /// only the level's declared effects. Err when the scene is outside the model (a motor, a
    /// load that changes or turns, a support that rotates or supports that move apart).
    pub fn of_level(level: &Level, around: usize) -> Result<Mechanism, String> {
        let n = level.bodies.len();
        if around >= n || !dynamic(level, around) {
            return Err("the body is not a dynamic body".into());
        }
        let forces = AppliedForces::of_level(level, &|name| {
            index(level, name).ok_or_else(|| format!("no body \"{name}\""))
        })?;
        let pairs = acting_pairs(level, &forces)?;
        // The connected set of dynamic bodies and what holds them (fixed and kinematic bodies
        // join it but do not pass it on).
        let inside = joined_bodies(
            n,
            [around],
            pairs.iter().filter_map(|&(a, b)| Some((a, b?))),
            |k| dynamic(level, k),
            |_| true,
        );
        let support = Support::of(level, &inside, &pairs)?;
        let mut m = Mechanism {
            members: members(level, &inside, &forces, support.velocity),
            gravity: forces.gravity,
            support_acceleration: support.acceleration,
            support_velocity: support.velocity,
            ..Default::default()
        };
        let moving: Vec<usize> = (0..n).filter(|&k| inside[k] && dynamic(level, k)).collect();
        m.contacts = resting_contacts(level, &moving, m.gravity - support.acceleration)?;
        if level.effects.contains(&Effect::Joints) {
            m.add_constraints(level, &inside)?;
        }
        m.add_springs(&forces, &inside);
        m.add_loads(&forces, &inside)?;
        Ok(m)
    }

    /// The joints and couplings that touch the connected set, as links and ratio constraints.
    fn add_constraints(&mut self, level: &Level, inside: &[bool]) -> Result<(), String> {
        let motors = level.effects.contains(&Effect::Motors);
        for j in &level.joints {
            let (b1, b2) = (
                index(level, &j.body1).unwrap_or(0),
                index(level, &j.body2).unwrap_or(0),
            );
            if !touches(inside, b1, Some(b2)) {
                continue;
            }
            if motors && j.motor.is_some() {
                return Err(format!(
                    "joint \"{}\" has a motor, which the linearization does not model",
                    j.name
                ));
            }
            self.links.push(Link {
                kind: j.kind,
                body1: b1,
                body2: b2,
                anchor1: v(j.anchor1),
                anchor2: v(j.anchor2),
                axis: v(j.axis).normalize_or(DVec2::X),
                limits: j.limits,
            });
        }
        for c in &level.couplings {
            let terms: Vec<(usize, Coordinate, f64)> = c
                .terms
                .iter()
                .filter_map(|t| Some((index(level, &t.body)?, t.coordinate, t.ratio)))
                .collect();
            if terms.iter().any(|t| inside[t.0]) {
                self.ratios.push(terms);
            }
        }
        Ok(())
    }

    /// The linear and torsion springs that touch the connected set.
    fn add_springs(&mut self, forces: &AppliedForces, inside: &[bool]) {
        self.springs.extend(
            forces
                .springs
                .iter()
                .filter(|s| touches(inside, s.body1, s.body2))
                .cloned(),
        );
        self.torsion_springs.extend(
            forces
                .torsion_springs
                .iter()
                .filter(|s| touches(inside, s.body1, s.body2))
                .cloned(),
        );
    }

    /// The loads on the connected set, each constant in world axes (a load that changes or
    /// turns has no potential: refused).
    fn add_loads(&mut self, forces: &AppliedForces, inside: &[bool]) -> Result<(), String> {
        for l in forces.loads.iter().filter(|l| inside[l.body]) {
            if l.follow_body {
                return Err(format!(
                    "load \"{}\" turns with the body (a follower load has no potential)",
                    l.name
                ));
            }
            let force = match &l.force {
                None => DVec2::ZERO,
                Some(Profile::Constant(f)) => v(*f),
                Some(Profile::Table(_)) => {
                    return Err(format!("load \"{}\" changes with time", l.name))
                }
            };
            let torque = match &l.torque {
                None => 0.0,
                Some(Profile::Constant(t)) => *t,
                Some(Profile::Table(_)) => {
                    return Err(format!("load \"{}\" changes with time", l.name))
                }
            };
            self.loads.push(ConstantLoad {
                body: l.body,
                point: l.point,
                force,
                torque,
            });
        }
        Ok(())
    }
}

/// Whether an element between a and b (b None: the ground) acts on the connected set.
fn touches(inside: &[bool], a: usize, b: Option<usize>) -> bool {
    inside[a] || b.is_some_and(|b| inside[b])
}

/// Pairs of bodies that act on each other: a joint's two, a coupling's consecutive terms, a
/// spring's two ends.
fn acting_pairs(level: &Level, forces: &AppliedForces) -> Result<Vec<Pair>, String> {
    let mut pairs: Vec<Pair> = Vec::new();
    if level.effects.contains(&Effect::Joints) {
        for j in &level.joints {
            pairs.push((
                index(level, &j.body1).ok_or("joint body")?,
                index(level, &j.body2),
            ));
        }
        for c in &level.couplings {
            let bodies: Vec<usize> = c
                .terms
                .iter()
                .filter_map(|t| index(level, &t.body))
                .collect();
            for w in bodies.windows(2) {
                pairs.push((w[0], Some(w[1])));
            }
        }
    }
    // Empty without the springs effect.
    pairs.extend(forces.springs.iter().map(|s| (s.body1, s.body2)));
    pairs.extend(forces.torsion_springs.iter().map(|s| (s.body1, s.body2)));
    Ok(pairs)
}

/// What the mechanism hangs on: the velocity and acceleration its kinematic supports share.
struct Support {
    velocity: DVec2,
    acceleration: DVec2,
}

impl Support {
    /// The support: every kinematic body the set hangs on moves with one velocity, unturned.
    fn of(level: &Level, inside: &[bool], pairs: &[Pair]) -> Result<Support, String> {
        let mut support: Option<DVec2> = None;
        let mut support_acceleration: Option<DVec2> = None;
        let mut grounded = false;
        for (_, b) in level.bodies.iter().enumerate().filter(|(k, _)| inside[*k]) {
            match b.kind {
                BodyKind::Dynamic => {}
                BodyKind::Fixed => grounded = true,
                BodyKind::Kinematic => {
                    if b.omega != 0.0 {
                        return Err(format!(
                            "\"{}\", a kinematic body the mechanism hangs on, turns: its frame is not inertial",
                            b.name
                        ));
                    }
                    let ak = frame_acceleration(b)?;
                    let vk = v(b.velocity);
                    if support.is_some_and(|s| (s - vk).length() > 1e-12)
                        || support_acceleration.is_some_and(|s| (s - ak).length() > 1e-12)
                    {
                        return Err(
                            "the kinematic bodies that hold the mechanism move apart".into()
                        );
                    }
                    support = Some(vk);
                    support_acceleration = Some(ak);
                }
            }
        }
        let ground_springs = pairs
            .iter()
            .any(|&(a, b)| inside[a] && b.is_none() && dynamic(level, a));
        let velocity = support.unwrap_or(DVec2::ZERO);
        let acceleration = support_acceleration.unwrap_or(DVec2::ZERO);
        if (velocity != DVec2::ZERO || acceleration != DVec2::ZERO) && (grounded || ground_springs)
        {
            return Err(
                "both the ground and a moving kinematic body hold the mechanism: its equilibrium moves".into(),
            );
        }
        Ok(Support {
            velocity,
            acceleration,
        })
    }
}

/// The acceleration of a kinematic support's frame, from its prescribed motion: a uniform
/// acceleration is a frame where gravity reads g - a; anything else drives the mechanism
/// (forced, not free, vibration) or turns its frame.
fn frame_acceleration(b: &BodyDef) -> Result<DVec2, String> {
    match b.motion {
        None => Ok(DVec2::ZERO),
        Some(m) => match m.uniform_translation() {
            Some(a) => Ok(v(a)),
            None => Err(format!(
                "\"{}\", a kinematic body the mechanism hangs on, has a prescribed {}: the motion is forced, not a free oscillation about an equilibrium",
                b.name,
                match m {
                    crate::level::Motion::Oscillate { .. } => "oscillation",
                    crate::level::Motion::Accelerate { .. } => "rotation",
                }
            )),
        },
    }
}

/// Every body of the level as a member; only the connected set's dynamic bodies move, their
/// velocities relative to the support.
fn members(
    level: &Level,
    inside: &[bool],
    forces: &AppliedForces,
    v_support: DVec2,
) -> Vec<Member> {
    level
        .bodies
        .iter()
        .map(|b| {
            let mp = of_body(b, DEFAULT_DENSITY);
            let moves = b.kind == BodyKind::Dynamic;
            let (linear_damping, angular_damping) = forces.body_damping(b);
            Member {
                name: b.name.clone(),
                moves: moves && inside[index(level, &b.name).unwrap_or(0)],
                mass: mp.mass,
                inertia: mp.inertia,
                local_com: mp.com,
                position: v(b.position),
                angle: b.angle,
                velocity: v(b.velocity) - v_support,
                omega: b.omega,
                lock_rotation: b.lock_rotation,
                linear_damping,
                angular_damping,
            }
        })
        .collect()
}
