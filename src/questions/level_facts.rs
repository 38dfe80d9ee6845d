//! What the questions need to know about the level beyond the snapshots: the restitution and
//! friction each body declares (under the level's effects), disc radii, and the joints' kinds
//! and geometry. The impact and blow solutions, friction's work and the joint analyses read
//! them; the engine's state comes from the snapshots.

use crate::analysis::curved_path::PathSide;
use crate::analysis::reference::Reference;
use crate::level::{Effect, JointKind, Level, Quantity, When};
use crate::snapshot::{BodyState, Snapshot};
use glam::DVec2;
use std::collections::HashMap;

/// A body's declared contact coefficients and shape, as far as the questions use them.
#[derive(Debug, Clone)]
pub(super) struct BodyInfo {
    /// Restitution e (0 unless the level has the `restitution` effect).
    pub restitution: f64,
    /// Friction coefficient mu (0 unless the level has the `friction` effect).
    pub friction: f64,
    /// Radius of a disc centered on the body origin (for the exact line of centers of an impact).
    pub disc: Option<f64>,
    /// The textbook mass properties (the shape's formula with the level's mass or density).
    pub textbook: crate::analysis::mass::MassProps,
    /// The body has linear or angular damping.
    pub damped: bool,
    /// The level's loads on the body (by name).
    pub loads: Vec<String>,
    /// A fixed body's circular track (`Shape::Arc`), for the normal force on a curve.
    pub arc: Option<ArcTrack>,
}

/// A fixed circular track (`Shape::Arc` on a fixed body), in world axes.
#[derive(Debug, Clone, Copy)]
pub(super) struct ArcTrack {
    pub center: DVec2,
    pub radius: f64,
    /// The arc's first angle about the center (world, rad) and its sweep, counter-clockwise.
    pub start: f64,
    pub sweep: f64,
    /// Which side bodies ride: inside the circle or outside it.
    pub side: PathSide,
    /// One facet's turn, rad (`level::curves::facet_angle`).
    pub facet: f64,
}

impl ArcTrack {
    /// The track of body `b`, when it is a fixed body whose shape is an arc.
    fn of(b: &crate::level::BodyDef) -> Option<ArcTrack> {
        use crate::level::{curves, ArcSide, BodyKind, Shape};
        let Some(Shape::Arc {
            center,
            radius,
            start,
            end,
            side,
            chord_error,
        }) = &b.shape
        else {
            return None;
        };
        if b.kind != BodyKind::Fixed {
            return None;
        }
        let turn = DVec2::from_angle(b.angle);
        Some(ArcTrack {
            center: DVec2::new(b.position.0, b.position.1)
                + turn.rotate(DVec2::new(center.0, center.1)),
            radius: *radius,
            start: start + b.angle,
            sweep: end - start,
            side: match side {
                ArcSide::Inside => PathSide::Inside,
                ArcSide::Outside => PathSide::Outside,
            },
            facet: curves::facet_angle(*radius, curves::chord_error(*radius, *chord_error)),
        })
    }

    /// Whether the ray from the center along `d` meets the arc (within its sweep).
    pub fn spans(&self, d: DVec2) -> bool {
        let from_start = (d.y.atan2(d.x) - self.start).rem_euclid(std::f64::consts::TAU);
        self.sweep >= std::f64::consts::TAU - 1e-9 || from_start <= self.sweep
    }
}

/// A spring of the level (linear or torsion), as the analyses' preconditions read it.
#[derive(Debug, Clone)]
pub(super) struct SpringInfo {
    pub name: String,
    pub torsion: bool,
    pub body1: usize,
    /// None: the other end is held by the ground.
    pub body2: Option<usize>,
    /// k, N/m or N m/rad.
    pub stiffness: f64,
    /// c, N s/m or N m s/rad.
    pub damping: f64,
}

impl SpringInfo {
    /// Whether body i is one of the spring's ends.
    pub fn holds(&self, i: usize) -> bool {
        self.body1 == i || self.body2 == Some(i)
    }
}

/// A joint's kind, bodies and geometry, in the level's order (the snapshots' order too).
#[derive(Debug, Clone)]
pub(super) struct JointInfo {
    pub name: String,
    pub kind: JointKind,
    pub body1: usize,
    pub body2: usize,
    /// The anchor in body2's frame, m.
    pub anchor2: DVec2,
    /// The slide axis in body1's frame (unit).
    pub axis: DVec2,
    /// The joint has a motor.
    pub motor: bool,
}

/// Level data some analyses need beyond the snapshot (declared coefficients, joint geometry).
#[derive(Debug, Clone)]
pub struct LevelFacts {
    pub(super) bodies: Vec<BodyInfo>,
    /// The level's joints (empty without the `joints` effect).
    pub(super) joints: Vec<JointInfo>,
    /// The level's springs, linear then torsion (empty without the `springs` effect).
    pub(super) springs: Vec<SpringInfo>,
    /// Each body's index by name, in the level's order (which the run's snapshots keep).
    names: HashMap<String, usize>,
    /// The level itself, kept when a period question may need the whole mechanism
    /// (the linearized period, `analysis::small_oscillations`).
    pub(super) level: Option<std::sync::Arc<Level>>,
    /// The level's equations of motion for the reference trajectory (`analysis::reference`),
    /// built when a question reads a motion quantity at a time, or why the scene is outside them.
    pub(super) reference: Option<std::sync::Arc<Result<Reference, String>>>,
}

impl LevelFacts {
    pub fn of(level: &Level) -> LevelFacts {
        let has = |e: Effect| level.effects.contains(&e);
        let index = |n: &str| level.bodies.iter().position(|b| b.name == n).unwrap_or(0);
        let v = |p: (f64, f64)| DVec2::new(p.0, p.1);
        LevelFacts {
            bodies: level
                .bodies
                .iter()
                .map(|b| BodyInfo {
                    restitution: if has(Effect::Restitution) {
                        b.restitution.unwrap_or(0.0)
                    } else {
                        0.0
                    },
                    friction: if has(Effect::Friction) {
                        b.friction.unwrap_or(0.0)
                    } else {
                        0.0
                    },
                    disc: b.disc_radius(),
                    textbook: crate::analysis::mass::of_body(b, crate::level::DEFAULT_DENSITY),
                    damped: has(Effect::Damping)
                        && (b.linear_damping.unwrap_or(0.0) != 0.0
                            || b.angular_damping.unwrap_or(0.0) != 0.0),
                    loads: level
                        .loads
                        .iter()
                        .filter(|l| l.body == b.name)
                        .map(|l| l.name.clone())
                        .collect(),
                    arc: ArcTrack::of(b),
                })
                .collect(),
            joints: if has(Effect::Joints) {
                level
                    .joints
                    .iter()
                    .map(|j| JointInfo {
                        name: j.name.clone(),
                        kind: j.kind,
                        body1: index(&j.body1),
                        body2: index(&j.body2),
                        anchor2: v(j.anchor2),
                        axis: v(j.axis).normalize_or(DVec2::X),
                        motor: has(Effect::Motors) && j.motor.is_some(),
                    })
                    .collect()
            } else {
                Vec::new()
            },
            springs: if has(Effect::Springs) {
                let linear = level.springs.iter().map(|x| SpringInfo {
                    name: x.name.clone(),
                    torsion: false,
                    body1: index(&x.body1),
                    body2: x.body2.as_deref().map(index),
                    stiffness: x.stiffness,
                    damping: if has(Effect::Damping) { x.damping } else { 0.0 },
                });
                let torsion = level.torsion_springs.iter().map(|x| SpringInfo {
                    name: x.name.clone(),
                    torsion: true,
                    body1: index(&x.body1),
                    body2: x.body2.as_deref().map(index),
                    stiffness: x.stiffness,
                    damping: if has(Effect::Damping) { x.damping } else { 0.0 },
                });
                linear.chain(torsion).collect()
            } else {
                Vec::new()
            },
            names: {
                let mut names = HashMap::with_capacity(level.bodies.len());
                for (i, b) in level.bodies.iter().enumerate() {
                    // The first of a name, as a scan finds it.
                    names.entry(b.name.clone()).or_insert(i);
                }
                names
            },
            level: level
                .questions
                .iter()
                .any(|q| q.quantity.family() == crate::level::QuantityFamily::Periods)
                .then(|| std::sync::Arc::new(level.clone())),
            reference: level
                .questions
                .iter()
                .any(|q| {
                    served_by_reference(&q.quantity) && matches!(q.at, When::Time(_) | When::End)
                })
                .then(|| std::sync::Arc::new(Reference::of_level(level))),
        }
    }

    /// Body `name`'s index in the level.
    pub fn level_index(&self, name: &str) -> Option<usize> {
        self.names.get(name).copied()
    }

    /// Body `name`'s index in `s`, as `Snapshot::body_index` finds it: the level's index when
    /// the snapshot has that body there (a question reads its body every step, and a scan of
    /// every name per question made 100 questions on 100 bodies cost O(N^2) a step), else a scan.
    pub fn body_index(&self, s: &Snapshot, name: &str) -> Option<usize> {
        match self.names.get(name) {
            Some(&i) if s.bodies.get(i).is_some_and(|b| b.name == name) => Some(i),
            _ => s.body_index(name),
        }
    }

    /// Body `name` of `s` with its index (see [`LevelFacts::body_index`]).
    pub fn named_body<'a>(&self, s: &'a Snapshot, name: &str) -> Option<(usize, &'a BodyState)> {
        self.body_index(s, name).map(|i| (i, &s.bodies[i]))
    }

    /// Where joint `name` holds its bodies in `s`, world: its anchor on body2 as the level
    /// gives it. For a snapshot that reports no joints (the initial state: the engine reports
    /// them from the first step on).
    pub fn joint_anchor(&self, s: &Snapshot, name: &str) -> Option<DVec2> {
        let j = self.joints.iter().find(|j| j.name == name)?;
        Some(s.bodies.get(j.body2)?.world_point(j.anchor2))
    }

    /// The pair's restitution as rapier combines it (the larger of the two, see `sim::build`).
    pub fn restitution(&self, a: usize, b: usize) -> f64 {
        let e = |i: usize| self.bodies.get(i).map_or(0.0, |x| x.restitution);
        e(a).max(e(b))
    }

    /// The pair's friction coefficient as rapier combines it (the larger of the two).
    pub fn friction(&self, a: usize, b: usize) -> f64 {
        let m = |i: usize| self.bodies.get(i).map_or(0.0, |x| x.friction);
        m(a).max(m(b))
    }
}

/// The quantities the reference trajectory (`analysis::reference`) gives an analysis value
/// for, read at a time: positions, angles and velocities of bodies and body points, joint
/// reactions and rolling contacts' forces.
pub fn served_by_reference(q: &Quantity) -> bool {
    matches!(
        q,
        Quantity::X(_)
            | Quantity::Y(_)
            | Quantity::Angle(_)
            | Quantity::Vx(_)
            | Quantity::Vy(_)
            | Quantity::Speed(_)
            | Quantity::Omega(_)
            | Quantity::Direction(_)
            | Quantity::PointX { .. }
            | Quantity::PointY { .. }
            | Quantity::PointSpeed { .. }
            | Quantity::RelativeDistance(..)
            | Quantity::RelativeSpeed(..)
            | Quantity::RelativeAngle(..)
            | Quantity::RelativePointSpeed { .. }
            | Quantity::JointReaction { .. }
            | Quantity::JointForce(_)
            | Quantity::ContactNormalForce { .. }
            | Quantity::ContactForceFrom { .. }
            | Quantity::ContactForce(_)
    )
}
