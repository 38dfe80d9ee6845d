//! Impulse-momentum for a set of rigid bodies, joints and contacts hit by impulses (RM-10,
//! IM-9 to IM-12, MK 6/8): the textbook's "just after the blow" or "just after the impact" for
//! a whole mechanism at once.
//!
//! Each constraint (a joint's point or angle, a coupling, a contact's normal with its
//! restitution) is one [`ConstraintRow`]: a linear combination of the bodies' velocities that
//! must reach a target value after the blow. [`solve_impulses`] finds the multiplier impulse of
//! every row (Gaussian elimination on the rows' effective-mass matrix) and applies
//! m dv = sum J, I_G domega = sum (r x J) to each body.

use super::cross;
use crate::level::{BodyKind, Coordinate, JointKind};
use crate::snapshot::BodyState;
use glam::DVec2;

/// One row of an impulse-momentum solve: sum over entries (body, lin, ang) of
/// lin . v_body + ang * omega_body must equal `target` after the blow.
#[derive(Debug, Clone)]
pub struct ConstraintRow {
    pub entries: Vec<(usize, DVec2, f64)>,
    pub target: f64,
}

/// Whether a body takes impulses: dynamic, with mass (fixed, kinematic and massless bodies do not).
pub fn is_massive(b: &BodyState) -> bool {
    b.kind == BodyKind::Dynamic && b.mass > 0.0
}

/// Inverse mass and inverse inertia (0 for fixed, kinematic and rotation-locked bodies).
pub fn inverse_mass(b: &BodyState) -> (f64, f64) {
    if !is_massive(b) {
        return (0.0, 0.0);
    }
    (
        1.0 / b.mass,
        if b.inertia > 0.0 {
            1.0 / b.inertia
        } else {
            0.0
        },
    )
}

/// A row keeping the velocity of point p along d equal on both bodies (body2 minus body1).
pub fn point_row(
    s: &[BodyState],
    i1: usize,
    i2: usize,
    p: DVec2,
    d: DVec2,
    target: f64,
) -> ConstraintRow {
    ConstraintRow {
        entries: vec![
            (i1, -d, -cross(p - s[i1].com, d)),
            (i2, d, cross(p - s[i2].com, d)),
        ],
        target,
    }
}

/// The row's combination of the bodies' velocities in state `s`.
pub fn row_velocity(r: &ConstraintRow, s: &[BodyState]) -> f64 {
    r.entries
        .iter()
        .map(|(b, lin, ang)| lin.dot(s[*b].velocity) + ang * s[*b].omega)
        .sum()
}

/// The rows of one joint between bodies `body1` and `body2` (target: no relative velocity):
/// the anchor point along x and y for a pin or weld, across the axis for a slider or pin in a
/// slot, and the relative angle for a weld or slider. `anchor2` is the anchor in body2's frame,
/// `axis` the slide axis in body1's frame.
pub fn joint_rows(
    s: &[BodyState],
    kind: JointKind,
    body1: usize,
    body2: usize,
    anchor2: DVec2,
    axis: DVec2,
) -> Vec<ConstraintRow> {
    let (b1, b2) = (&s[body1], &s[body2]);
    let p2 = b2.world_point(anchor2);
    let axis = DVec2::from_angle(b1.angle).rotate(axis);
    let angle_row = ConstraintRow {
        entries: vec![(body1, DVec2::ZERO, -1.0), (body2, DVec2::ZERO, 1.0)],
        target: 0.0,
    };
    let mut rows = Vec::new();
    match kind {
        JointKind::Revolute | JointKind::Fixed => {
            rows.push(point_row(s, body1, body2, p2, DVec2::X, 0.0));
            rows.push(point_row(s, body1, body2, p2, DVec2::Y, 0.0));
            if kind == JointKind::Fixed {
                rows.push(angle_row);
            }
        }
        JointKind::Prismatic => {
            rows.push(point_row(s, body1, body2, p2, axis.perp(), 0.0));
            rows.push(angle_row);
        }
        JointKind::PinSlot => rows.push(point_row(s, body1, body2, p2, axis.perp(), 0.0)),
    }
    rows
}

/// The linear impulse a joint's rows gave body2, from their multipliers `lambda` (in the order
/// [`joint_rows`] builds them); `body1_angle` and `axis` (body1's frame) orient a slider's row.
pub fn joint_impulse(kind: JointKind, body1_angle: f64, axis: DVec2, lambda: &[f64]) -> DVec2 {
    match kind {
        JointKind::Revolute | JointKind::Fixed => DVec2::new(lambda[0], lambda[1]),
        JointKind::Prismatic | JointKind::PinSlot => {
            DVec2::from_angle(body1_angle).rotate(axis).perp() * lambda[0]
        }
    }
}

/// The row of a coupling (pulley, cable, gear): sum of ratio x coordinate rate stays zero.
pub fn coupling_row(terms: &[(usize, Coordinate, f64)]) -> ConstraintRow {
    ConstraintRow {
        entries: terms
            .iter()
            .map(|&(b, coord, ratio)| match coord {
                Coordinate::X => (b, DVec2::X * ratio, 0.0),
                Coordinate::Y => (b, DVec2::Y * ratio, 0.0),
                Coordinate::Angle => (b, DVec2::ZERO, ratio),
            })
            .collect(),
        target: 0.0,
    }
}

/// Impulse-momentum for a set of rigid bodies hit by impulses (RM-10, IM-9 to IM-12, MK 6/8):
/// every constraint row reaches its target velocity by a multiplier impulse lambda, and
/// m dv = sum J, I_G domega = sum (r x J) for each body. `ext` holds (body, impulse, angular
/// impulse about G). Returns the states after the blow and the multipliers.
pub fn solve_impulses(
    s: &[BodyState],
    rows: &[ConstraintRow],
    ext: &[(usize, DVec2, f64)],
) -> (Vec<BodyState>, Vec<f64>) {
    let inv: Vec<(f64, f64)> = s.iter().map(inverse_mass).collect();
    let mut u = s.to_vec();
    for (b, j, ang) in ext {
        u[*b].velocity += *j * inv[*b].0;
        u[*b].omega += ang * inv[*b].1;
    }
    let n = rows.len();
    let mut k = vec![vec![0.0; n + 1]; n];
    for (r, row_r) in rows.iter().enumerate() {
        for (c, row_c) in rows.iter().enumerate() {
            let mut sum = 0.0;
            for (b1, l1, a1) in &row_r.entries {
                for (b2, l2, a2) in &row_c.entries {
                    if b1 == b2 {
                        sum += l1.dot(*l2) * inv[*b1].0 + a1 * a2 * inv[*b1].1;
                    }
                }
            }
            k[r][c] = sum;
        }
        k[r][n] = row_r.target - row_velocity(row_r, &u);
    }
    let lambda = gauss(k);
    for (row, l) in rows.iter().zip(&lambda) {
        for (b, lin, ang) in &row.entries {
            u[*b].velocity += *lin * (l * inv[*b].0);
            u[*b].omega += ang * l * inv[*b].1;
        }
    }
    (u, lambda)
}

/// Solves the augmented system [K | b] by Gaussian elimination with partial pivoting; rows that
/// are redundant (zero pivot) get a zero multiplier.
fn gauss(mut a: Vec<Vec<f64>>) -> Vec<f64> {
    let n = a.len();
    let scale = (0..n)
        .map(|i| a[i][i].abs())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let mut pivot_ok = vec![true; n];
    for c in 0..n {
        let p = (c..n)
            .max_by(|&x, &y| a[x][c].abs().total_cmp(&a[y][c].abs()))
            .unwrap_or(c);
        a.swap(c, p);
        if a[c][c].abs() < 1e-12 * scale {
            pivot_ok[c] = false;
            continue;
        }
        let pivot: Vec<f64> = a[c][c..=n].to_vec();
        for (r, row) in a.iter_mut().enumerate() {
            if r != c {
                let f = row[c] / pivot[0];
                if f != 0.0 {
                    for (x, p) in row[c..=n].iter_mut().zip(&pivot) {
                        *x -= f * p;
                    }
                }
            }
        }
    }
    (0..n)
        .map(|i| if pivot_ok[i] { a[i][n] / a[i][i] } else { 0.0 })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn impulse_solve_of_two_equal_balls() {
        // Direct central impact, e = 1, equal masses: the velocities swap (IM-9).
        let mk = |x: f64, v: f64| BodyState {
            name: String::new(),
            kind: BodyKind::Dynamic,
            position: DVec2::new(x, 0.0),
            angle: 0.0,
            com: DVec2::new(x, 0.0),
            velocity: DVec2::new(v, 0.0),
            omega: 0.0,
            mass: 2.0,
            inertia: 0.0,
            local_com: DVec2::ZERO,
        };
        let s = vec![mk(0.0, 3.0), mk(1.0, 0.0)];
        let mut row = point_row(&s, 0, 1, DVec2::new(0.5, 0.0), DVec2::X, 0.0);
        row.target = -row_velocity(&row, &s);
        let (post, l) = solve_impulses(&s, &[row], &[]);
        assert!((post[0].velocity.x - 0.0).abs() < 1e-12);
        assert!((post[1].velocity.x - 3.0).abs() < 1e-12);
        assert!((l[0] - 6.0).abs() < 1e-12);
    }
}
