//! Virtual work for a mechanism of one degree of freedom (concepts.md VW-2 to VW-5: ZH 4.3 and
//! 4.22; MK Art. 6/7, eq. 6/11a).
//!
//! **Virtual displacements** (VW-3) are the ones the constraints allow in the frozen
//! configuration. With one degree of freedom they are all multiples of one field: the velocities
//! every body would have if the driving joint moved at unit rate, the solution of the joints'
//! velocity equations with the driver's rate set to 1 ([`virtual_velocities`]). So a body's
//! virtual displacement is (delta r_G, delta theta) = (v_G, omega) delta q, read from the
//! mechanism's geometry alone: it exists at rest, where a power balance is 0 / 0.
//!
//! **Statics** (VW-2): Q + sum_k (F_k . v_Pk + C_k omega_k) = 0, Q the actuator's effort (the
//! torque of a pin's motor on body2, or a slider's force along its axis), the sum over the
//! applied forces F_k at points P_k and couples C_k; ideal joint reactions do no virtual work.
//! **With inertia** (d'Alembert, VW-5; MK 6/11a): the inertia forces -m a_G and couples
//! -I_G alpha join the applied ones, Q = sum_i (m a_G . v_G + I_G alpha omega)_i - sum_k (...).

use super::k_cross;
use crate::level::JointKind;
use crate::snapshot::{BodyState, Snapshot};
use glam::DVec2;

/// How a joint ties its two bodies, for the velocity equations (axes in world coordinates).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Pair {
    /// A pin: the anchor point's velocity is the same on both bodies (2 equations).
    Revolute,
    /// A slider along `axis`: no relative turn, no relative motion across the axis (2).
    Prismatic(DVec2),
    /// A pin in a slot along `axis` on body1: no relative motion across the axis (1).
    PinSlot(DVec2),
    /// A weld: no relative motion at all (3).
    Fixed,
}

/// One joint of the mechanism: its bodies (snapshot indices), the anchor (world) and its pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Link {
    pub body1: usize,
    pub body2: usize,
    pub point: DVec2,
    pub pair: Pair,
}

/// The virtual velocity field: v_G and omega of every body for a unit rate of the driver
/// (zero for bodies the driver does not move and for fixed ones).
#[derive(Debug, Clone, PartialEq)]
pub struct VirtualField {
    pub velocity: Vec<DVec2>,
    pub omega: Vec<f64>,
}

impl VirtualField {
    /// The virtual velocity of the point `p` (world) carried by body `i` whose G is `com`.
    pub fn point_velocity(&self, i: usize, com: DVec2, p: DVec2) -> DVec2 {
        self.velocity[i] + k_cross(self.omega[i], p - com)
    }
}

/// An applied force `force` at `point` (world) and couple `couple` on body `body`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Applied {
    pub body: usize,
    pub force: DVec2,
    pub point: DVec2,
    pub couple: f64,
}

/// The virtual velocity field of the mechanism that `links` make of `bodies`, for a unit rate of
/// link `driver` (a pin's relative rate omega2 - omega1, or a slider's relative speed along its
/// axis). Err says why there is none: the driver is not a pin or slider, the mechanism has more
/// than one degree of freedom, or it is locked.
pub fn virtual_velocities(
    bodies: &[BodyState],
    links: &[Link],
    driver: usize,
) -> Result<VirtualField, String> {
    let d = links.get(driver).ok_or("no such joint")?;
    if matches!(d.pair, Pair::Fixed | Pair::PinSlot(_)) {
        return Err("the driving joint is not a pin or a slider".into());
    }
    // The unknowns: every dynamic body the driver's joints reach through other dynamic bodies.
    let moving = |i: usize| bodies[i].kind == crate::snapshot::BodyKind::Dynamic;
    let mut column = vec![usize::MAX; bodies.len()];
    let mut order = Vec::new();
    let mut stack: Vec<usize> = [d.body1, d.body2]
        .into_iter()
        .filter(|&i| moving(i))
        .collect();
    while let Some(i) = stack.pop() {
        if column[i] != usize::MAX {
            continue;
        }
        column[i] = order.len();
        order.push(i);
        for l in links {
            for (a, b) in [(l.body1, l.body2), (l.body2, l.body1)] {
                if a == i && moving(b) && column[b] == usize::MAX {
                    stack.push(b);
                }
            }
        }
    }
    let n = 3 * order.len();
    // One row per velocity equation: coefficients on (vx, vy, omega) of each body, and the rate.
    let mut rows: Vec<(Vec<f64>, f64)> = Vec::new();
    // The velocity of point p on body i along direction u: u . (v_i + omega_i k x (p - G_i)).
    let along = |row: &mut [f64], i: usize, p: DVec2, u: DVec2, sign: f64| {
        if column[i] == usize::MAX {
            return;
        }
        let c = 3 * column[i];
        let r = p - bodies[i].com;
        row[c] += sign * u.x;
        row[c + 1] += sign * u.y;
        row[c + 2] += sign * u.dot(k_cross(1.0, r));
    };
    let turn = |row: &mut [f64], i: usize, sign: f64| {
        if column[i] != usize::MAX {
            row[3 * column[i] + 2] += sign;
        }
    };
    for (k, l) in links.iter().enumerate() {
        if column[l.body1] == usize::MAX && column[l.body2] == usize::MAX {
            continue;
        }
        let relative = |u: DVec2| {
            let mut row = vec![0.0; n];
            along(&mut row, l.body2, l.point, u, 1.0);
            along(&mut row, l.body1, l.point, u, -1.0);
            row
        };
        let spin = || {
            let mut row = vec![0.0; n];
            turn(&mut row, l.body2, 1.0);
            turn(&mut row, l.body1, -1.0);
            row
        };
        match l.pair {
            Pair::Revolute | Pair::Fixed => {
                rows.push((relative(DVec2::X), 0.0));
                rows.push((relative(DVec2::Y), 0.0));
            }
            Pair::Prismatic(u) | Pair::PinSlot(u) => rows.push((relative(u.perp()), 0.0)),
        }
        if matches!(l.pair, Pair::Fixed | Pair::Prismatic(_)) {
            rows.push((spin(), 0.0));
        }
        if k == driver {
            match l.pair {
                Pair::Revolute => rows.push((spin(), 1.0)),
                Pair::Prismatic(u) => rows.push((relative(u), 1.0)),
                _ => unreachable!("checked above"),
            }
        }
    }
    let x = least_squares(&rows, n).ok_or(
        "the mechanism has more than one degree of freedom: the driver's rate does not fix the other bodies' velocities",
    )?;
    let worst = rows
        .iter()
        .map(|(a, b)| (a.iter().zip(&x).map(|(p, q)| p * q).sum::<f64>() - b).abs())
        .fold(0.0, f64::max);
    if worst > 1e-6 {
        return Err(format!(
            "the mechanism is locked: its joints do not let the driver move (velocity equations off by {worst:.1e})"
        ));
    }
    let mut field = VirtualField {
        velocity: vec![DVec2::ZERO; bodies.len()],
        omega: vec![0.0; bodies.len()],
    };
    for (c, &i) in order.iter().enumerate() {
        field.velocity[i] = DVec2::new(x[3 * c], x[3 * c + 1]);
        field.omega[i] = x[3 * c + 2];
    }
    Ok(field)
}

/// The actuator's effort by virtual work: the torque (N m) of a pin's motor on body2, or the force
/// (N) of a slider's along its axis, that balances the `applied` forces (VW-2) and, given each
/// body's (a_G, alpha), the inertia forces too (d'Alembert, VW-5):
/// Q = sum_i (m a_G . v_G + I_G alpha omega)_i - sum_k (F_k . v_Pk + C_k omega_k).
pub fn actuator_effort(
    bodies: &[BodyState],
    field: &VirtualField,
    applied: impl IntoIterator<Item = Applied>,
    accelerations: Option<&[(DVec2, f64)]>,
) -> f64 {
    let applied_power: f64 = applied
        .into_iter()
        .map(|a| {
            let b = &bodies[a.body];
            a.force.dot(field.point_velocity(a.body, b.com, a.point))
                + a.couple * field.omega[a.body]
        })
        .sum();
    let inertia_power: f64 = accelerations.map_or(0.0, |acc| {
        bodies
            .iter()
            .zip(acc)
            .enumerate()
            .map(|(i, (b, (a_g, alpha)))| {
                b.mass * a_g.dot(field.velocity[i]) + b.inertia * alpha * field.omega[i]
            })
            .sum()
    });
    inertia_power - applied_power
}

/// The mechanism the snapshot's joints make: `kinds` gives the level's joints' kind and slide
/// axis (in body1's frame) in the snapshot's order; joints past them (welds made at run time)
/// are welds.
pub fn links_of(snap: &Snapshot, kinds: &[(JointKind, DVec2)]) -> Vec<Link> {
    snap.joints
        .iter()
        .enumerate()
        .map(|(k, j)| {
            let axis = |a: DVec2| DVec2::from_angle(snap.bodies[j.body1].angle).rotate(a);
            let pair = match kinds.get(k) {
                Some((JointKind::Revolute, _)) => Pair::Revolute,
                Some((JointKind::Prismatic, a)) => Pair::Prismatic(axis(*a)),
                Some((JointKind::PinSlot, a)) => Pair::PinSlot(axis(*a)),
                Some((JointKind::Fixed, _)) | None => Pair::Fixed,
            };
            // A soft pin or weld lets its two anchors part a little under load: the joint is
            // taken halfway between them. A slider's anchors are apart by its coordinate: its
            // point is the one on body2.
            let point = match pair {
                Pair::Revolute | Pair::Fixed => 0.5 * (j.anchor + j.anchor1),
                Pair::Prismatic(_) | Pair::PinSlot(_) => j.anchor,
            };
            Link {
                body1: j.body1,
                body2: j.body2,
                point,
                pair,
            }
        })
        .collect()
}

/// The applied forces of the step that ended at `snap`, as the engine held them: the weights of
/// the dynamic bodies, loads, springs, and the motors of every joint but `driver` (a torque on
/// body2 and its opposite on body1, or a force along a slider's axis).
pub fn applied_forces(snap: &Snapshot, links: &[Link], driver: usize) -> Vec<Applied> {
    let mut out = Vec::new();
    for (i, b) in snap.bodies.iter().enumerate() {
        if b.kind == crate::snapshot::BodyKind::Dynamic && b.mass > 0.0 {
            out.push(Applied {
                body: i,
                force: b.mass * snap.gravity,
                point: b.com,
                couple: 0.0,
            });
        }
    }
    for l in &snap.loads {
        out.push(Applied {
            body: l.body,
            force: l.force,
            point: l.point,
            couple: l.torque,
        });
    }
    for sp in &snap.springs {
        out.push(Applied {
            body: sp.body1,
            force: sp.force_on_body1,
            point: sp.applied_at1,
            couple: sp.couple_on_body1,
        });
        if let Some(b2) = sp.body2 {
            out.push(Applied {
                body: b2,
                force: -sp.force_on_body1,
                point: sp.applied_at2,
                couple: -sp.couple_on_body1,
            });
        }
    }
    if snap.dt > 0.0 {
        for (k, (j, l)) in snap.joints.iter().zip(links).enumerate() {
            if k == driver || j.motor_impulse == 0.0 {
                continue;
            }
            let effort = j.motor_impulse / snap.dt;
            match l.pair {
                Pair::Prismatic(u) => {
                    out.push(Applied {
                        body: j.body2,
                        force: effort * u,
                        point: j.anchor,
                        couple: 0.0,
                    });
                    out.push(Applied {
                        body: j.body1,
                        force: -effort * u,
                        point: j.anchor,
                        couple: 0.0,
                    });
                }
                _ => {
                    out.push(Applied {
                        body: j.body2,
                        force: DVec2::ZERO,
                        point: j.anchor,
                        couple: effort,
                    });
                    out.push(Applied {
                        body: j.body1,
                        force: DVec2::ZERO,
                        point: j.anchor,
                        couple: -effort,
                    });
                }
            }
        }
    }
    out
}

/// Why virtual work does not describe the mechanism in `snap`, if it does not: a body the driver
/// moves touches something (a contact's force is no ideal reaction: it works when the contact
/// slides, and it is not a constraint of the field) or is tied by a coupling.
pub fn not_a_mechanism(snap: &Snapshot, field: &VirtualField) -> Option<String> {
    let moves = |i: usize| field.velocity[i] != DVec2::ZERO || field.omega[i] != 0.0;
    if let Some(c) = snap
        .contacts
        .iter()
        .find(|c| moves(c.body1) || moves(c.body2))
    {
        return Some(format!(
            "virtual work does not apply: \"{}\" and \"{}\" are in contact, and a contact is not an ideal joint",
            snap.bodies[c.body1].name, snap.bodies[c.body2].name
        ));
    }
    if let Some(c) = snap
        .couplings
        .iter()
        .find(|c| c.terms.iter().any(|t| moves(t.0)))
    {
        return Some(format!(
            "virtual work does not apply: coupling \"{}\" ties the mechanism (not among its joints)",
            c.name
        ));
    }
    None
}

/// Solves rows . x = rhs in the least-squares sense (normal equations, Gaussian elimination with
/// partial pivoting); None when the columns are dependent (a free coordinate left).
fn least_squares(rows: &[(Vec<f64>, f64)], n: usize) -> Option<Vec<f64>> {
    let mut m = vec![vec![0.0; n + 1]; n];
    for (a, b) in rows {
        for i in 0..n {
            if a[i] == 0.0 {
                continue;
            }
            for j in 0..n {
                m[i][j] += a[i] * a[j];
            }
            m[i][n] += a[i] * b;
        }
    }
    let scale = (0..n)
        .map(|i| m[i][i].abs())
        .fold(0.0, f64::max)
        .max(1e-300);
    for c in 0..n {
        let p = (c..n).max_by(|&a, &b| m[a][c].abs().total_cmp(&m[b][c].abs()))?;
        if m[p][c].abs() <= 1e-12 * scale {
            return None;
        }
        m.swap(c, p);
        // Row c is read while the others are written: take it out for the sweep.
        let pivot = std::mem::take(&mut m[c]);
        for (r, row) in m.iter_mut().enumerate() {
            if r != c {
                let f = row[c] / pivot[c];
                if f != 0.0 {
                    for (x, p) in row[c..].iter_mut().zip(&pivot[c..]) {
                        *x -= f * p;
                    }
                }
            }
        }
        m[c] = pivot;
    }
    Some((0..n).map(|i| m[i][n] / m[i][i]).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::snapshot::BodyKind;

    fn body(kind: BodyKind, com: DVec2, mass: f64) -> BodyState {
        BodyState {
            name: String::new(),
            kind,
            position: com,
            angle: 0.0,
            com,
            velocity: DVec2::ZERO,
            omega: 0.0,
            mass,
            inertia: 0.0,
            local_com: DVec2::ZERO,
        }
    }

    /// Slider-crank, crank r = 0.1 m at theta from the slide line, rod l = 0.3 m, piston force F
    /// along the line toward the crank: VW-6's static torque M = F r sin(theta) (1 + r cos(theta)
    /// / sqrt(l^2 - r^2 sin^2 theta)), the crank's motor holding against the piston.
    #[test]
    fn slider_crank_static_torque_matches_zh() {
        for theta in [60f64.to_radians(), 120f64.to_radians(), 0.3] {
            let (r, l, f) = (0.1, 0.3, 50.0);
            let b = DVec2::new(r * theta.cos(), r * theta.sin());
            let dx = (l * l - (r * theta.sin()).powi(2)).sqrt();
            let d = DVec2::new(b.x + dx, 0.0);
            let bodies = vec![
                body(BodyKind::Fixed, DVec2::ZERO, 0.0),
                body(BodyKind::Dynamic, b * 0.5, 1.0),
                body(BodyKind::Dynamic, (b + d) * 0.5, 1.0),
                body(BodyKind::Dynamic, d, 1.0),
            ];
            let links = [
                Link {
                    body1: 0,
                    body2: 1,
                    point: DVec2::ZERO,
                    pair: Pair::Revolute,
                },
                Link {
                    body1: 1,
                    body2: 2,
                    point: b,
                    pair: Pair::Revolute,
                },
                Link {
                    body1: 2,
                    body2: 3,
                    point: d,
                    pair: Pair::Revolute,
                },
                Link {
                    body1: 0,
                    body2: 3,
                    point: d,
                    pair: Pair::Prismatic(DVec2::X),
                },
            ];
            let field = virtual_velocities(&bodies, &links, 0).unwrap();
            let push = Applied {
                body: 3,
                force: DVec2::new(-f, 0.0),
                point: d,
                couple: 0.0,
            };
            let m = actuator_effort(&bodies, &field, [push], None);
            // The push toward the crank turns it counter-clockwise for 0 < theta < pi (x_D
            // falls as theta grows), so the motor holds clockwise: M = -(ZH's magnitude).
            let zh = f * r * theta.sin() * (1.0 + r * theta.cos() / dx);
            assert!(
                (m + zh).abs() < 1e-12 * zh.abs().max(1.0),
                "theta {theta}: {m} vs {}",
                -zh
            );
        }
    }

    #[test]
    fn a_free_body_leaves_more_than_one_degree_of_freedom() {
        let bodies = vec![
            body(BodyKind::Fixed, DVec2::ZERO, 0.0),
            body(BodyKind::Dynamic, DVec2::X, 1.0),
            body(BodyKind::Dynamic, DVec2::new(2.0, 0.0), 1.0),
        ];
        // A double pendulum driven at its first pin: the second link swings freely.
        let links = [
            Link {
                body1: 0,
                body2: 1,
                point: DVec2::ZERO,
                pair: Pair::Revolute,
            },
            Link {
                body1: 1,
                body2: 2,
                point: DVec2::new(1.5, 0.0),
                pair: Pair::Revolute,
            },
        ];
        let e = virtual_velocities(&bodies, &links, 0).unwrap_err();
        assert!(e.contains("more than one degree of freedom"), "{e}");
    }
}
