//! The level's applied force elements as the analysis's own equations of motion read them:
//! gravity, the bodies' damping, linear springs, torsion springs and loads, each with its body
//! indices resolved and its defaults filled in, under the level's declared effects.
//!
//! One home for the translation, so that the reference trajectory (`reference`) and the
//! linearization (`small_oscillations`) see the same forces, and a new force element is added
//! once. What each model then refuses (a load that changes with time has no potential) stays
//! with the model.

use crate::level::{BodyDef, Effect, Level, Profile, TorsionSpringDef};
use glam::DVec2;

/// A linear spring-damper: body1's point (its frame) to body2's point (its frame), or to a
/// ground point (world frame) when `body2` is None.
#[derive(Debug, Clone, PartialEq)]
pub struct LinearSpring {
    pub body1: usize,
    pub point1: DVec2,
    pub body2: Option<usize>,
    pub point2: DVec2,
    pub stiffness: f64,
    pub rest_length: f64,
    pub damping: f64,
}

/// A torsion spring-damper on theta = angle1 - angle2 (angle2 = 0 for the ground).
#[derive(Debug, Clone, PartialEq)]
pub struct TorsionSpring {
    pub body1: usize,
    pub body2: Option<usize>,
    pub stiffness: f64,
    pub rest_angle: f64,
    pub damping: f64,
}

/// A load as the level gives it: a force (world axes, or turning with the body when
/// `follow_body`) at a body-frame point, and a couple, each constant or tabulated in time.
#[derive(Debug, Clone, PartialEq)]
pub struct Load {
    pub name: String,
    pub body: usize,
    pub point: DVec2,
    pub force: Option<Profile<(f64, f64)>>,
    pub torque: Option<Profile<f64>>,
    pub follow_body: bool,
}

/// Every applied force element of a level, in the level's order.
#[derive(Debug, Clone, PartialEq)]
pub struct AppliedForces {
    /// Gravity, m/s^2 (zero without the `gravity` effect).
    pub gravity: DVec2,
    /// Whether the `damping` effect is on: the springs' dampers and the bodies' damping act.
    pub damping: bool,
    /// Empty without the `springs` effect.
    pub springs: Vec<LinearSpring>,
    /// Empty without the `springs` effect.
    pub torsion_springs: Vec<TorsionSpring>,
    pub loads: Vec<Load>,
}

fn v2(p: (f64, f64)) -> DVec2 {
    DVec2::new(p.0, p.1)
}

impl AppliedForces {
    /// The force elements of `level`, bodies resolved by `index` (its error is returned as is).
    pub fn of_level(
        level: &Level,
        index: &dyn Fn(&str) -> Result<usize, String>,
    ) -> Result<AppliedForces, String> {
        let has = |e: Effect| level.effects.contains(&e);
        let damping = has(Effect::Damping);
        let mut forces = AppliedForces {
            gravity: if has(Effect::Gravity) {
                v2(level.world.gravity.unwrap_or((0.0, -9.81)))
            } else {
                DVec2::ZERO
            },
            damping,
            springs: Vec::new(),
            torsion_springs: Vec::new(),
            loads: Vec::new(),
        };
        let dashpot = |c: f64| if damping { c } else { 0.0 };
        if has(Effect::Springs) {
            for s in &level.springs {
                forces.springs.push(LinearSpring {
                    body1: index(&s.body1)?,
                    point1: v2(s.point1),
                    body2: s.body2.as_deref().map(index).transpose()?,
                    point2: v2(s.point2),
                    stiffness: s.stiffness,
                    rest_length: s.rest_length,
                    damping: dashpot(s.damping),
                });
            }
            for s in &level.torsion_springs {
                let body1 = index(&s.body1)?;
                let body2 = s.body2.as_deref().map(index).transpose()?;
                forces.torsion_springs.push(TorsionSpring {
                    body1,
                    body2,
                    stiffness: s.stiffness,
                    rest_angle: rest_angle(level, s, body1, body2),
                    damping: dashpot(s.damping),
                });
            }
        }
        for l in &level.loads {
            forces.loads.push(Load {
                name: l.name.clone(),
                body: index(&l.body)?,
                point: v2(l.point),
                force: l.force.clone(),
                torque: l.torque.clone(),
                follow_body: l.follow_body,
            });
        }
        Ok(forces)
    }

    /// A body's linear and angular damping rates, 1/s (zero without the `damping` effect): the
    /// force -m d v and the couple -I d omega, rapier's continuous model.
    pub fn body_damping(&self, b: &BodyDef) -> (f64, f64) {
        if self.damping {
            (
                b.linear_damping.unwrap_or(0.0),
                b.angular_damping.unwrap_or(0.0),
            )
        } else {
            (0.0, 0.0)
        }
    }
}

/// A torsion spring's rest angle: the level's, or the relative angle its bodies start at (so an
/// unset rest angle leaves the start unloaded).
fn rest_angle(level: &Level, s: &TorsionSpringDef, body1: usize, body2: Option<usize>) -> f64 {
    let a2 = body2.map_or(0.0, |k| level.bodies[k].angle);
    s.rest_angle.unwrap_or(level.bodies[body1].angle - a2)
}
