//! What the overlays and plots show, over the plain snapshot. The formulas are the analysis
//! layer's (`crate::analysis`); this file sums them over a scene and shapes them for the eye.

use crate::analysis::momentum;
use crate::snapshot::{BodyKind, BodyState, Coordinate, Snapshot};
use glam::DVec2;

pub use crate::analysis::energy::body_kinetic_energy;
pub use crate::analysis::kinematics::body_point_velocity as point_velocity;

/// Angular momentum of the scene about a fixed point O, sum of H_O (6/15), N m s, CCW.
pub fn angular_momentum_about(s: &Snapshot, o: DVec2) -> f64 {
    s.bodies
        .iter()
        .map(|b| momentum::angular_momentum_about(b.mass, b.inertia, b.com, b.velocity, b.omega, o))
        .sum()
}

/// Instantaneous center of zero velocity C: v_C = 0 gives r_{C/G} = (k x v_G) / omega (MK art. 5/5).
/// None for pure translation (|omega| tiny against v_G / `size`: the center is at infinity).
pub fn instant_center(b: &BodyState, size: f64) -> Option<DVec2> {
    let w = b.omega;
    let v = b.velocity;
    if w.abs() * size.max(1e-9) <= 1e-6 * v.length().max(1e-12) || w == 0.0 {
        return None;
    }
    Some(b.com + v.perp() / w)
}

/// Mass-center acceleration and angular acceleration by backward difference of the velocities,
/// a_G ~ (v_n - v_{n-1}) / dt: the mean acceleration over the last step (O(dt) behind the instant).
pub fn accelerations(now: &Snapshot, prev: &[(DVec2, f64)], dt: f64) -> Vec<(DVec2, f64)> {
    now.bodies
        .iter()
        .zip(prev)
        .map(|(b, (v0, w0))| {
            if dt > 0.0 {
                ((b.velocity - *v0) / dt, (b.omega - w0) / dt)
            } else {
                (DVec2::ZERO, 0.0)
            }
        })
        .collect()
}

/// What a force on a free-body diagram is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ForceKind {
    Gravity,
    ContactNormal,
    Friction,
    Joint,
    Spring,
    Load,
    /// A coupling's reaction (cable tension, gear tooth force) on the mass center.
    Coupling,
}

impl ForceKind {
    pub fn symbol(self) -> &'static str {
        match self {
            ForceKind::Gravity => "mg",
            ForceKind::ContactNormal => "N",
            ForceKind::Friction => "F",
            ForceKind::Joint => "R",
            ForceKind::Spring => "Fs",
            ForceKind::Load => "P",
            ForceKind::Coupling => "T",
        }
    }
}

/// One force on a body, at its point of application, N.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Force {
    pub kind: ForceKind,
    /// Which one of its kind: the other body (contacts), or the index of the joint, coupling,
    /// spring or load. With `kind` it identifies the force from step to step.
    pub source: usize,
    pub point: DVec2,
    pub force: DVec2,
}

/// The external forces on body `i` during the last step: gravity m g at G, contact normal and
/// friction forces (impulse / dt, one resultant per contact manifold), joint reactions (impulse on
/// body2 / dt, opposite on body1), coupling reactions, spring forces and applied loads. Couples
/// (load torques, joint and coupling couples) are summed separately, N m. This is the free-body
/// diagram (MK art. 6/2), with the mean forces over the step.
pub fn free_body(s: &Snapshot, i: usize) -> (Vec<Force>, f64) {
    let mut out = Vec::new();
    let mut couple = 0.0;
    let b = &s.bodies[i];
    if b.kind != BodyKind::Dynamic {
        return (out, couple);
    }
    if s.gravity != DVec2::ZERO && b.mass > 0.0 {
        out.push(Force {
            kind: ForceKind::Gravity,
            source: 0,
            point: b.com,
            force: s.gravity * b.mass,
        });
    }
    if !s.is_initial() {
        let inv = 1.0 / s.dt;
        for c in &s.contacts {
            let (sign, other) = if c.body2 == i {
                (1.0, c.body1)
            } else if c.body1 == i {
                (-1.0, c.body2)
            } else {
                continue;
            };
            // One resultant per contact manifold, at the normal-impulse-weighted center of its points.
            let pn: f64 = c.points.iter().map(|p| p.normal_impulse).sum();
            let pt: f64 = c.points.iter().map(|p| p.tangent_impulse).sum();
            if c.points.is_empty() || (pn == 0.0 && pt == 0.0) {
                continue;
            }
            let point = if pn > 0.0 {
                c.points
                    .iter()
                    .map(|p| p.point * p.normal_impulse)
                    .sum::<DVec2>()
                    / pn
            } else {
                c.points.iter().map(|p| p.point).sum::<DVec2>() / c.points.len() as f64
            };
            out.push(Force {
                kind: ForceKind::ContactNormal,
                source: other,
                point,
                force: c.normal * pn * inv * sign,
            });
            out.push(Force {
                kind: ForceKind::Friction,
                source: other,
                point,
                force: c.tangent() * pt * inv * sign,
            });
        }
        for (k, j) in s.joints.iter().enumerate() {
            if j.body2 == i {
                out.push(Force {
                    kind: ForceKind::Joint,
                    source: k,
                    point: j.anchor,
                    force: j.impulse_on_body2 * inv,
                });
                couple += j.couple_on_body2 * inv;
            } else if j.body1 == i {
                out.push(Force {
                    kind: ForceKind::Joint,
                    source: k,
                    point: j.anchor1,
                    force: -j.impulse_on_body2 * inv,
                });
                couple -= j.couple_on_body2 * inv;
            }
        }
    }
    if !s.is_initial() {
        // Couplings: term k receives ratio_k * lambda along its coordinate (at G) or as a couple.
        for (k, c) in s.couplings.iter().enumerate() {
            for (body, coord, ratio) in &c.terms {
                if *body != i {
                    continue;
                }
                let q = ratio * c.impulse / s.dt;
                match coord {
                    Coordinate::X => out.push(Force {
                        kind: ForceKind::Coupling,
                        source: k,
                        point: b.com,
                        force: DVec2::new(q, 0.0),
                    }),
                    Coordinate::Y => out.push(Force {
                        kind: ForceKind::Coupling,
                        source: k,
                        point: b.com,
                        force: DVec2::new(0.0, q),
                    }),
                    Coordinate::Angle => couple += q,
                }
            }
        }
    }
    for (k, sp) in s.springs.iter().enumerate() {
        if sp.body1 == i {
            out.push(Force {
                kind: ForceKind::Spring,
                source: k,
                point: sp.point1,
                force: sp.force_on_body1,
            });
        } else if sp.body2 == Some(i) {
            out.push(Force {
                kind: ForceKind::Spring,
                source: k,
                point: sp.point2,
                force: -sp.force_on_body1,
            });
        }
    }
    for (k, l) in s.loads.iter().enumerate() {
        if l.body == i {
            if l.force != DVec2::ZERO {
                out.push(Force {
                    kind: ForceKind::Load,
                    source: k,
                    point: l.point,
                    force: l.force,
                });
            }
            couple += l.torque;
        }
    }
    out.retain(|f| f.force.length_squared() > 0.0);
    (out, couple)
}

/// The free-body diagram averaged over consecutive steps: each force's impulse over the window
/// divided by its duration (the mean force), at its impulse-weighted mean point; couples likewise.
/// With a step much shorter than a frame, rapier delivers contact impulses in bursts (many steps
/// carry none); the mean over a frame is what the eye can follow.
pub fn free_body_mean<'a>(
    snaps: impl IntoIterator<Item = &'a Snapshot>,
    i: usize,
) -> (Vec<Force>, f64) {
    let mut acc: Vec<(Force, f64)> = Vec::new();
    let mut couple = 0.0;
    let mut total_time = 0.0;
    for s in snaps {
        let (forces, c) = free_body(s, i);
        let dt = if s.is_initial() { continue } else { s.dt };
        total_time += dt;
        couple += c * dt;
        for f in forces {
            let w = f.force.length() * dt;
            match acc
                .iter_mut()
                .find(|(g, _)| g.kind == f.kind && g.source == f.source)
            {
                Some((g, wsum)) => {
                    g.force += f.force * dt;
                    g.point += f.point * w;
                    *wsum += w;
                }
                None => acc.push((
                    Force {
                        force: f.force * dt,
                        point: f.point * w,
                        ..f
                    },
                    w,
                )),
            }
        }
    }
    if total_time == 0.0 {
        return (Vec::new(), 0.0);
    }
    let out = acc
        .into_iter()
        .filter(|(_, w)| *w > 0.0)
        .map(|(f, w)| Force {
            force: f.force / total_time,
            point: f.point / w,
            ..f
        })
        .collect();
    (out, couple / total_time)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn body(v: DVec2, w: f64) -> BodyState {
        BodyState {
            name: "b".into(),
            kind: BodyKind::Dynamic,
            position: DVec2::new(1.0, 2.0),
            angle: 0.0,
            com: DVec2::new(1.0, 2.0),
            velocity: v,
            omega: w,
            mass: 2.0,
            inertia: 0.5,
            local_com: DVec2::ZERO,
        }
    }

    #[test]
    fn rolling_wheel_has_its_instant_center_at_the_contact() {
        // A wheel of radius r rolling to the right without slip: v_G = omega r, omega = -v/r (CW).
        let r = 0.5;
        let b = body(DVec2::new(3.0, 0.0), -3.0 / r);
        let c = instant_center(&b, 1.0).unwrap();
        assert!((c - DVec2::new(1.0, 2.0 - r)).length() < 1e-12, "{c}");
        assert!(point_velocity(&b, c).length() < 1e-12);
        // The top point moves at 2 v_G.
        let top = point_velocity(&b, DVec2::new(1.0, 2.0 + r));
        assert!((top - DVec2::new(6.0, 0.0)).length() < 1e-12);
    }

    #[test]
    fn translation_has_no_instant_center() {
        assert!(instant_center(&body(DVec2::new(1.0, 0.0), 0.0), 1.0).is_none());
    }
}
