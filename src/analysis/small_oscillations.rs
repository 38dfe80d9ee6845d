//! Small oscillations about an equilibrium (PL-14): the periods of a mechanism's modes from its
//! equations of motion linearized about the equilibrium, for any scene of bodies, joints,
//! couplings, springs, torsion springs, dampers, constant loads and gravity.
//!
//! The method, general rather than exercise by exercise:
//! 1. Full coordinates q = (x_G, y_G, L theta) per dynamic body (L, the mechanism's size, makes
//!    every coordinate a length, so one step size and one tolerance serve them all); the joints,
//!    couplings and locked rotations are constraints g(q) = 0.
//! 2. A local chart of the constraint manifold: at a point q* the null space N of the
//!    constraint Jacobian (orthonormal, from its SVD, so redundant constraints are fine), and
//!    q(s) = project(q* + N s), where project is the Gauss-Newton minimal-norm projection
//!    q <- q - G(q)^+ g(q) back onto g = 0.
//! 3. The equilibrium: from the level's initial configuration, Newton steps on V(q(s)) with a
//!    line search, to the minimum of the potential on the manifold nearest the start (a scene
//!    that starts at rest in equilibrium is its own answer after one step).
//! 4. At the equilibrium: M_r = N^T M N, K_r = the Hessian of V(q(s)) at s = 0 by central
//!    differences (the projection's curvature brings in the geometric stiffness a pendulum's
//!    m g d needs), C_r = N^T C N from the dampers.
//! 5. The modes: K_r phi = omega^2 M_r phi (undamped periods 2 pi / omega); with dampers, the
//!    eigenvalues lambda = -sigma +- i omega_d of the first-order system, each matched to the
//!    undamped mode of nearest |lambda| (exact for proportional damping), period 2 pi / omega_d.
//!
//! The mechanism is built from a level in `of_level.rs` (its springs, torsion springs and loads
//! from `applied_forces`, which the reference trajectory shares); steps 3 to 5 are `solve.rs`.
//!
//! The finite-difference step is h = 1e-4 L: the truncation error of the central second
//! difference is about (h / L)^2 = 1e-8 relative, the rounding error about eps V / (K h^2)
//! = 1e-16 x 1e8 = 1e-8 relative with V measured from the start (so no large absolute height
//! enters), and the projection converges to 1e-13 L, well under h^2 / L. Tests hold the periods
//! to 1e-6 relative.
//!
//! A support (the kinematic bodies the mechanism hangs on) moving with constant velocity is an
//! inertial frame; with a constant acceleration a, gravity is replaced by g - a in its frame
//! (`Mechanism::support_acceleration`, from a kinematic support's `Motion::Accelerate`). Contacts, joint limits (unless the equilibrium sits on
//! one) and motors are not in the model: a motor or a time-varying or follower load makes the
//! analysis refuse, with the reason.

use crate::analysis::resting_contacts::{Hold, RestingContact};
use crate::level::{Coordinate, JointKind};
use glam::DVec2;
use nalgebra::{DMatrix, DVector};

mod of_level;
mod solve;

/// One body of the mechanism, as the level gives it at t = 0.
#[derive(Debug, Clone, PartialEq)]
pub struct Member {
    pub name: String,
    /// Whether it is a coordinate of the model (a dynamic body); otherwise it holds its
    /// initial pose in the support's frame (fixed, or a kinematic support).
    pub moves: bool,
    pub mass: f64,
    /// I_G, kg m^2 (MP-1).
    pub inertia: f64,
    /// G in the body frame, m.
    pub local_com: DVec2,
    /// The body frame's origin and angle at t = 0.
    pub position: DVec2,
    pub angle: f64,
    /// v_G and omega at t = 0, relative to the support.
    pub velocity: DVec2,
    pub omega: f64,
    pub lock_rotation: bool,
    /// The body's linear and angular damping, 1/s: forces -m d v and couples -I d omega.
    pub linear_damping: f64,
    pub angular_damping: f64,
}

/// A joint: anchors in the bodies' frames (from the origin), axis in body1's frame (unit).
#[derive(Debug, Clone, PartialEq)]
pub struct Link {
    pub kind: JointKind,
    pub body1: usize,
    pub body2: usize,
    pub anchor1: DVec2,
    pub anchor2: DVec2,
    pub axis: DVec2,
    pub limits: Option<(f64, f64)>,
}

pub use crate::analysis::applied_forces::{LinearSpring, TorsionSpring};

/// A constant force (world axes, at a body-frame point) and couple on a body.
#[derive(Debug, Clone, PartialEq)]
pub struct ConstantLoad {
    pub body: usize,
    pub point: DVec2,
    pub force: DVec2,
    pub torque: f64,
}

/// The mechanism the linearization is taken of: plain data, from a level or by hand.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Mechanism {
    pub members: Vec<Member>,
    pub links: Vec<Link>,
    /// Ratio constraints sum(ratio_i q_i) = const (the couplings), held at their initial value.
    pub ratios: Vec<Vec<(usize, Coordinate, f64)>>,
    pub springs: Vec<LinearSpring>,
    pub torsion_springs: Vec<TorsionSpring>,
    pub loads: Vec<ConstantLoad>,
    pub gravity: DVec2,
    /// The support's constant acceleration a: in its frame gravity is g - a.
    pub support_acceleration: DVec2,
    /// The support's velocity at t = 0 (the members' velocities are relative to it).
    pub support_velocity: DVec2,
    /// The faces the members rest on at the start, held as rolling or smooth contacts.
    pub contacts: Vec<RestingContact>,
}

/// One mode of small oscillation.
#[derive(Debug, Clone, PartialEq)]
pub struct Mode {
    /// Undamped natural circular frequency omega_n, rad/s.
    pub omega: f64,
    /// 2 pi / omega_n, s.
    pub period: f64,
    /// Damped circular frequency omega_d (= omega_n without dampers); None when overdamped.
    pub omega_d: Option<f64>,
    /// 2 pi / omega_d, s: the period the motion shows (None when overdamped).
    pub damped_period: Option<f64>,
    /// Per member: (dx_G, dy_G, dtheta) of the mode shape (mass-normalized in the chart).
    pub shape: Vec<(DVec2, f64)>,
    /// The share of the start's oscillation energy in this mode (0 to 1).
    pub energy_share: f64,
}

/// The linearized motion about the equilibrium.
#[derive(Debug, Clone, PartialEq)]
pub struct SmallOscillations {
    /// Per member: G and angle at the equilibrium.
    pub equilibrium: Vec<(DVec2, f64)>,
    /// The oscillating modes, lowest frequency first.
    pub modes: Vec<Mode>,
    /// Directions of zero stiffness (free motions: a cart's drift on a smooth floor).
    pub free_motions: usize,
    /// How far the start is from the equilibrium, in the chart (m, angles times L).
    pub offset: f64,
    /// The period at the start's amplitude along the most excited mode's path: the energy
    /// integral T = 2 int ds sqrt(m(s) / (2 (E - V(s)))) between the turning points of the path
    /// q(s) = project(q_eq + s phi), with m(s) = |dq/ds|_M^2 and E the start's whole energy
    /// (RE-7). Exact for one degree of freedom (the pendulum's elliptic-integral period, PL-5);
    /// for several, the motion held to the mode's shape. None when the start is at rest in
    /// equilibrium.
    pub amplitude_period: Option<f64>,
    /// |amplitude_period / undamped period - 1|: how far "small" is from the start's swing.
    pub period_error: f64,
}

/// The largest estimated period error for which the linearized period is offered (0.5 %: a
/// pendulum swinging to about 16 degrees).
pub const SMALL_AMPLITUDE_PERIOD_ERROR: f64 = 0.005;

/// The share of the oscillation energy a mode needs for a zero-crossing period to be its period.
pub const DOMINANT_MODE_SHARE: f64 = 0.98;

impl SmallOscillations {
    /// The mode the start excites, when one mode holds at least [`DOMINANT_MODE_SHARE`] of the
    /// oscillation energy (then the zero crossings of any coordinate it moves repeat with its
    /// period); otherwise why not.
    pub fn excited(&self) -> Result<&Mode, String> {
        let best = self
            .modes
            .iter()
            .enumerate()
            .max_by(|a, b| a.1.energy_share.total_cmp(&b.1.energy_share))
            .ok_or("the mechanism has no oscillating mode")?;
        if best.1.energy_share <= 0.0 {
            return Err("the start is at rest in equilibrium: nothing oscillates".into());
        }
        if best.1.energy_share < DOMINANT_MODE_SHARE {
            let shares: Vec<String> = self
                .modes
                .iter()
                .enumerate()
                .map(|(k, m)| format!("mode {} {:.1} %", k + 1, 100.0 * m.energy_share))
                .collect();
            return Err(format!(
                "the start excites several modes ({}): the motion is not periodic with one period; start in one mode's shape",
                shares.join(", ")
            ));
        }
        Ok(best.1)
    }
}

impl Mechanism {
    /// The linearized modes about the equilibrium nearest the start; Err with the reason when
    /// there is no stable equilibrium, the start is too far from it for "small", or the model
    /// is degenerate.
    pub fn small_oscillations(&self) -> Result<SmallOscillations, String> {
        let model = Model::new(self)?;
        model.solve()
    }
}

/// The mechanism in full scaled coordinates.
struct Model<'a> {
    m: &'a Mechanism,
    /// Member index of each coordinate slot (3 coordinates per moving member).
    slots: Vec<usize>,
    /// Slot of each member (None when it does not move).
    slot_of: Vec<Option<usize>>,
    /// The length that turns angles into coordinates: q = L theta.
    l: f64,
    /// The start, q0, and its rate.
    q0: DVector<f64>,
    qdot0: DVector<f64>,
    /// The constraints' values at the start (what they hold).
    g0: DVector<f64>,
}

fn rot(a: f64, p: DVec2) -> DVec2 {
    DVec2::from_angle(a).rotate(p)
}

impl<'a> Model<'a> {
    fn new(m: &'a Mechanism) -> Result<Model<'a>, String> {
        let slots: Vec<usize> = (0..m.members.len())
            .filter(|&k| m.members[k].moves)
            .collect();
        if slots.is_empty() {
            return Err("no body of the mechanism moves".into());
        }
        let mut slot_of = vec![None; m.members.len()];
        for (s, &k) in slots.iter().enumerate() {
            slot_of[k] = Some(s);
            let b = &m.members[k];
            if b.mass.is_nan() || b.mass <= 0.0 || !b.mass.is_finite() {
                return Err(format!("body \"{}\" has no mass", b.name));
            }
            if !b.lock_rotation && (b.inertia.is_nan() || b.inertia <= 0.0) {
                return Err(format!("body \"{}\" has no moment of inertia", b.name));
            }
        }
        // L: the mechanism's size (its bodies' and anchors' spread), at least 1 mm.
        let coms: Vec<DVec2> = m
            .members
            .iter()
            .map(|b| b.position + rot(b.angle, b.local_com))
            .collect();
        let mut l: f64 = 0.0;
        for k in &slots {
            for c in &coms {
                l = l.max((coms[*k] - *c).length());
            }
        }
        for j in &m.links {
            l = l.max(j.anchor1.length()).max(j.anchor2.length());
        }
        for s in &m.springs {
            l = l.max(s.rest_length);
        }
        let l = l.max(1e-3);
        let n = 3 * slots.len();
        let mut q0 = DVector::zeros(n);
        let mut qdot0 = DVector::zeros(n);
        for (s, &k) in slots.iter().enumerate() {
            let b = &m.members[k];
            q0[3 * s] = coms[k].x;
            q0[3 * s + 1] = coms[k].y;
            q0[3 * s + 2] = l * b.angle;
            qdot0[3 * s] = b.velocity.x;
            qdot0[3 * s + 1] = b.velocity.y;
            qdot0[3 * s + 2] = l * b.omega;
        }
        let mut model = Model {
            m,
            slots,
            slot_of,
            l,
            q0,
            qdot0,
            g0: DVector::zeros(0),
        };
        model.g0 = model.raw_constraints(&model.q0.clone());
        Ok(model)
    }

    /// G and angle of member k at q.
    fn pose(&self, q: &DVector<f64>, k: usize) -> (DVec2, f64) {
        match self.slot_of[k] {
            Some(s) => (DVec2::new(q[3 * s], q[3 * s + 1]), q[3 * s + 2] / self.l),
            None => {
                let b = &self.m.members[k];
                (b.position + rot(b.angle, b.local_com), b.angle)
            }
        }
    }

    /// World position of member k's body-frame point p at q.
    fn point(&self, q: &Poses, k: usize, p: DVec2) -> DVec2 {
        let (g, a) = q.0[k];
        g + rot(a, p - self.m.members[k].local_com)
    }

    fn poses(&self, q: &DVector<f64>) -> Poses {
        Poses((0..self.m.members.len()).map(|k| self.pose(q, k)).collect())
    }

    /// The constraint functions (lengths: angle rows times L), not yet less their start values.
    fn raw_constraints(&self, q: &DVector<f64>) -> DVector<f64> {
        let p = self.poses(q);
        let l = self.l;
        let mut g: Vec<f64> = Vec::new();
        for j in &self.m.links {
            let a1 = self.point(&p, j.body1, j.anchor1);
            let a2 = self.point(&p, j.body2, j.anchor2);
            let (th1, th2) = (p.0[j.body1].1, p.0[j.body2].1);
            let normal = rot(th1, j.axis).perp();
            match j.kind {
                JointKind::Revolute => g.extend([a2.x - a1.x, a2.y - a1.y]),
                JointKind::Fixed => g.extend([a2.x - a1.x, a2.y - a1.y, l * (th1 - th2)]),
                JointKind::Prismatic => g.extend([normal.dot(a2 - a1), l * (th1 - th2)]),
                JointKind::PinSlot => g.push(normal.dot(a2 - a1)),
            }
        }
        for terms in &self.m.ratios {
            g.push(
                terms
                    .iter()
                    .map(|&(k, c, r)| {
                        let (gk, ak) = p.0[k];
                        r * match c {
                            Coordinate::X => gk.x,
                            Coordinate::Y => gk.y,
                            Coordinate::Angle => ak,
                        }
                    })
                    .sum(),
            );
        }
        for (s, &k) in self.slots.iter().enumerate() {
            if self.m.members[k].lock_rotation {
                g.push(q[3 * s + 2]);
            }
        }
        // Resting contacts: the distance from the face kept; rolling also keeps the distance
        // rolled along the face plus r theta (RK-8: v_G along the face = -omega r); a flat face
        // keeps its angle.
        for c in &self.m.contacts {
            let (gk, ak) = p.0[c.body];
            let center = self.point(&p, c.body, c.point);
            let along = DVec2::new(c.normal.y, -c.normal.x);
            match c.hold {
                Hold::Rolling { radius } => {
                    g.extend([c.normal.dot(center), along.dot(center) + radius * ak])
                }
                Hold::Sliding => g.push(c.normal.dot(center)),
                Hold::Flat => g.extend([c.normal.dot(gk), l * ak]),
            }
        }
        DVector::from_vec(g)
    }

    fn constraints(&self, q: &DVector<f64>) -> DVector<f64> {
        self.raw_constraints(q) - &self.g0
    }

    /// The constraint Jacobian by central differences (step 1e-6 L: smooth functions of
    /// sines and cosines, error about 1e-12 relative).
    fn jacobian(&self, q: &DVector<f64>) -> DMatrix<f64> {
        let n = q.len();
        let h = 1e-6 * self.l;
        let rows = self.g0.len();
        let mut jac = DMatrix::zeros(rows, n);
        for i in 0..n {
            let mut qp = q.clone();
            let mut qm = q.clone();
            qp[i] += h;
            qm[i] -= h;
            let d = (self.raw_constraints(&qp) - self.raw_constraints(&qm)) / (2.0 * h);
            jac.set_column(i, &d);
        }
        jac
    }

    /// An orthonormal basis of the Jacobian's null space at q (n x d).
    fn null_space(&self, q: &DVector<f64>) -> Result<DMatrix<f64>, String> {
        let n = q.len();
        if self.g0.is_empty() {
            return Ok(DMatrix::identity(n, n));
        }
        // Square it with zero rows so the SVD gives all of V.
        let jac = self.jacobian(q);
        let mut sq = DMatrix::zeros(n.max(jac.nrows()), n);
        sq.view_mut((0, 0), (jac.nrows(), n)).copy_from(&jac);
        let svd = nalgebra::linalg::SVD::try_new(sq, false, true, f64::EPSILON, 0)
            .ok_or("the constraint Jacobian's SVD did not converge")?;
        let vt = svd.v_t.ok_or("no V from the SVD")?;
        let smax = svd.singular_values.max();
        let cols: Vec<DVector<f64>> = (0..svd.singular_values.len())
            .filter(|&i| svd.singular_values[i] <= 1e-7 * smax.max(1e-300))
            .map(|i| vt.row(i).transpose())
            .collect();
        if cols.is_empty() {
            return Err("the joints leave the mechanism no motion".into());
        }
        Ok(DMatrix::from_columns(&cols))
    }

    /// Gauss-Newton minimal-norm projection onto g = 0.
    fn project(&self, q: &DVector<f64>) -> Result<DVector<f64>, String> {
        if !q.iter().all(|x| x.is_finite()) {
            return Err("a configuration is not finite".into());
        }
        let mut q = q.clone();
        if self.g0.is_empty() {
            return Ok(q);
        }
        let tol = 1e-13 * self.l;
        let mut last = f64::INFINITY;
        for _ in 0..40 {
            let g = self.constraints(&q);
            let r = g.amax();
            if r <= tol || (r >= last && r < 1e-9 * self.l) {
                return Ok(q);
            }
            last = r;
            let jac = self.jacobian(&q);
            let svd = nalgebra::linalg::SVD::try_new(jac, true, true, f64::EPSILON, 0)
                .ok_or("the constraint Jacobian's SVD did not converge")?;
            let eps = 1e-9 * svd.singular_values.max();
            let dq = svd.solve(&g, eps).map_err(|e| format!("projection: {e}"))?;
            q -= dq;
        }
        let r = self.constraints(&q).amax();
        if r <= 1e-9 * self.l {
            Ok(q)
        } else {
            Err(format!(
                "the constraints cannot be closed near the start (residual {r:.2e} m)"
            ))
        }
    }

    /// The potential V(q) (gravity in the support's frame, springs, constant loads), measured
    /// from the start so no large absolute height enters its rounding.
    fn potential(&self, q: &DVector<f64>) -> f64 {
        let p = self.poses(q);
        let p0 = self.poses(&self.q0);
        let g_eff = self.m.gravity - self.m.support_acceleration;
        let mut v = 0.0;
        for &k in &self.slots {
            v -= self.m.members[k].mass * g_eff.dot(p.0[k].0 - p0.0[k].0);
        }
        for s in &self.m.springs {
            let a = self.point(&p, s.body1, s.point1);
            let b = match s.body2 {
                Some(k) => self.point(&p, k, s.point2),
                None => s.point2,
            };
            let x = (b - a).length() - s.rest_length;
            v += 0.5 * s.stiffness * x * x;
        }
        for s in &self.m.torsion_springs {
            let th = p.0[s.body1].1 - s.body2.map_or(0.0, |k| p.0[k].1);
            let x = th - s.rest_angle;
            v += 0.5 * s.stiffness * x * x;
        }
        for ld in &self.m.loads {
            let at = self.point(&p, ld.body, ld.point);
            let at0 = self.point(&p0, ld.body, ld.point);
            v -= ld.force.dot(at - at0) + ld.torque * (p.0[ld.body].1 - p0.0[ld.body].1);
        }
        v
    }

    /// V along the chart at base with null space nb: V(project(base + nb s)).
    fn chart_v(
        &self,
        base: &DVector<f64>,
        nb: &DMatrix<f64>,
        s: &DVector<f64>,
    ) -> Result<f64, String> {
        Ok(self.potential(&self.project(&(base + nb * s))?))
    }

    /// Gradient and Hessian of V along the chart at s = 0, central differences of step h.
    fn derivatives(
        &self,
        base: &DVector<f64>,
        nb: &DMatrix<f64>,
    ) -> Result<(DVector<f64>, DMatrix<f64>), String> {
        let d = nb.ncols();
        let h = 1e-4 * self.l;
        let v0 = self.potential(base);
        let e = |i: usize| {
            let mut x = DVector::zeros(d);
            x[i] = 1.0;
            x
        };
        let mut grad = DVector::zeros(d);
        let mut hess = DMatrix::zeros(d, d);
        for i in 0..d {
            let vp = self.chart_v(base, nb, &(e(i) * h))?;
            let vm = self.chart_v(base, nb, &(e(i) * -h))?;
            grad[i] = (vp - vm) / (2.0 * h);
            hess[(i, i)] = (vp - 2.0 * v0 + vm) / (h * h);
            for j in 0..i {
                let f = |a: f64, b: f64| self.chart_v(base, nb, &(e(i) * (a * h) + e(j) * (b * h)));
                let hij =
                    (f(1.0, 1.0)? - f(1.0, -1.0)? - f(-1.0, 1.0)? + f(-1.0, -1.0)?) / (4.0 * h * h);
                hess[(i, j)] = hij;
                hess[(j, i)] = hij;
            }
        }
        Ok((grad, hess))
    }
}

/// Every member's (G, angle) at one q.
struct Poses(Vec<(DVec2, f64)>);
