//! The small oscillations of a model, phase by phase (steps 3 to 5 of the module's method): the
//! equilibrium, the linearization about it, the undamped and damped eigenproblems, the modes
//! and the period at the start's amplitude.

use super::{Mode, Model, SmallOscillations};
use glam::DVec2;
use nalgebra::linalg::{Cholesky, SymmetricEigen};
use nalgebra::{Complex, DMatrix, DVector, Dyn};
use std::f64::consts::PI;

/// The equations of motion linearized about the equilibrium, in its chart.
struct Linearized {
    /// The equilibrium.
    q: DVector<f64>,
    /// The chart's basis: the constraint Jacobian's null space at q (n x d).
    nb: DMatrix<f64>,
    /// The mass matrix in full scaled coordinates (the amplitude period's metric).
    m_full: DMatrix<f64>,
    /// M_r = N^T M N, C_r = N^T C N and K_r, the Hessian of V in the chart (symmetrized).
    m_r: DMatrix<f64>,
    c_r: DMatrix<f64>,
    k_r: DMatrix<f64>,
}

/// The undamped eigenproblem K_r phi = omega^2 M_r phi, solved through M_r = L L^T.
struct Undamped {
    chol: Cholesky<f64, Dyn>,
    /// L^-1: a mode's shape is phi = L^-T y for the eigenvector y.
    lm_inv: DMatrix<f64>,
    eig: SymmetricEigen<f64, Dyn>,
    /// omega^2 below which a direction is free (zero stiffness).
    tol: f64,
}

impl Undamped {
    /// The mode shape phi of eigenvector i.
    fn phi(&self, i: usize) -> DVector<f64> {
        self.lm_inv.transpose() * self.eig.eigenvectors.column(i)
    }
}

/// The modes as found, each with its shape phi in the chart, and the start's energy in each.
struct Modes {
    modes: Vec<(Mode, DVector<f64>)>,
    energies: Vec<f64>,
    free_motions: usize,
}

impl Model<'_> {
    pub(super) fn solve(&self) -> Result<SmallOscillations, String> {
        let lin = self.linearize()?;
        let undamped = Undamped::of(&lin, |full| self.largest_motion(full))?;
        // The start in the chart, and in modal coordinates.
        let s0 = lin.nb.transpose() * (&self.q0 - &lin.q);
        let sdot0 = lin.nb.transpose() * &self.qdot0;
        let offset = s0.norm();
        let damped = damped_eigenvalues(&lin, &undamped)?;
        let mut found = self.modes(&lin, &undamped, damped.as_deref(), &s0, &sdot0);
        let (amplitude_period, period_error) =
            self.amplitude_period(&lin, &undamped, &mut found, &sdot0)?;
        let eq_poses = self.poses(&lin.q).0;
        Ok(SmallOscillations {
            equilibrium: eq_poses,
            modes: found.modes.into_iter().map(|(m, _)| m).collect(),
            free_motions: found.free_motions,
            offset,
            amplitude_period,
            period_error,
        })
    }

    /// The stiffness scale below which a direction counts as free (zero stiffness).
    fn free_tol(hess: &DMatrix<f64>) -> f64 {
        1e-6 * hess.amax().max(1e-300)
    }

    /// Newton steps on V along the chart from the start to the nearest minimum.
    fn equilibrium(&self) -> Result<DVector<f64>, String> {
        let mut q = self.project(&self.q0)?;
        for _ in 0..100 {
            let nb = self.null_space(&q)?;
            let (grad, hess) = self.derivatives(&q, &nb)?;
            let eig = SymmetricEigen::try_new(hess.clone(), 1e-15, 1000)
                .ok_or("the stiffness eigenproblem did not converge")?;
            let tol = Self::free_tol(&hess);
            let gscale = grad.amax();
            let mut step = DVector::zeros(nb.ncols());
            for i in 0..nb.ncols() {
                let u = eig.eigenvectors.column(i);
                let gi = u.dot(&grad);
                let k = eig.eigenvalues[i];
                if k.abs() > tol {
                    // Downhill whatever the curvature's sign: a maximum is walked away from.
                    step -= u * (gi / k.abs());
                } else if gi.abs() > 1e-9 * gscale.max(1e-300) {
                    // No curvature: downhill by the trust radius.
                    step -= u * (gi.signum() * 0.25 * self.l);
                }
            }
            // A trust region of L/4 and a line search on V.
            let len = step.norm();
            if len > 0.25 * self.l {
                step *= 0.25 * self.l / len;
            }
            let v_here = self.potential(&q);
            let mut t = 1.0;
            let mut next = None;
            for _ in 0..40 {
                let cand = self.project(&(&q + &nb * (&step * t)))?;
                if self.potential(&cand) <= v_here + 1e-14 * v_here.abs().max(1.0) {
                    next = Some(cand);
                    break;
                }
                t *= 0.5;
            }
            let Some(next) = next else {
                break;
            };
            let moved = (&next - &q).norm();
            q = next;
            if moved < 1e-11 * self.l {
                break;
            }
        }
        // Converged: the gradient's work over L is a millionth of the stiffness's.
        let nb = self.null_space(&q)?;
        let (grad, hess) = self.derivatives(&q, &nb)?;
        if grad.amax() > 1e-6 * hess.amax().max(1e-300) * self.l {
            return Err(format!(
                "no equilibrium near the start: the potential keeps falling (gradient {:.3e} N along the free motions)",
                grad.amax()
            ));
        }
        Ok(q)
    }

    /// The equilibrium, its chart, and M, C and K reduced to the chart.
    fn linearize(&self) -> Result<Linearized, String> {
        let q = self.equilibrium()?;
        let nb = self.null_space(&q)?;
        let (_, k_r) = self.derivatives(&q, &nb)?;
        let (m_full, mut c_full) = self.mass_and_damping(q.len());
        self.add_dampers(&q, &mut c_full);
        let m_r = nb.transpose() * &m_full * &nb;
        let c_r = nb.transpose() * &c_full * &nb;
        let k_r = (&k_r + k_r.transpose()) * 0.5;
        Ok(Linearized {
            q,
            nb,
            m_full,
            m_r,
            c_r,
            k_r,
        })
    }

    /// M and C in full scaled coordinates: the members' masses and inertias, and their own
    /// linear and angular damping.
    fn mass_and_damping(&self, n: usize) -> (DMatrix<f64>, DMatrix<f64>) {
        let mut m_full = DMatrix::zeros(n, n);
        let mut c_full = DMatrix::zeros(n, n);
        let l2 = self.l * self.l;
        for (s, &k) in self.slots.iter().enumerate() {
            let b = &self.m.members[k];
            m_full[(3 * s, 3 * s)] = b.mass;
            m_full[(3 * s + 1, 3 * s + 1)] = b.mass;
            m_full[(3 * s + 2, 3 * s + 2)] = b.inertia / l2;
            c_full[(3 * s, 3 * s)] = b.mass * b.linear_damping;
            c_full[(3 * s + 1, 3 * s + 1)] = b.mass * b.linear_damping;
            c_full[(3 * s + 2, 3 * s + 2)] = b.inertia * b.angular_damping / l2;
        }
        (m_full, c_full)
    }

    /// Dampers: c grad(l) grad(l)^T for the rate of each spring's length or angle, added to C.
    fn add_dampers(&self, q: &DVector<f64>, c_full: &mut DMatrix<f64>) {
        let n = q.len();
        let h = 1e-6 * self.l;
        let rate_gradient = |f: &dyn Fn(&DVector<f64>) -> f64| {
            DVector::from_iterator(
                n,
                (0..n).map(|i| {
                    let mut qp = q.clone();
                    let mut qm = q.clone();
                    qp[i] += h;
                    qm[i] -= h;
                    (f(&qp) - f(&qm)) / (2.0 * h)
                }),
            )
        };
        for s in self.m.springs.iter().filter(|s| s.damping != 0.0) {
            let length = |x: &DVector<f64>| {
                let p = self.poses(x);
                let a = self.point(&p, s.body1, s.point1);
                let b = match s.body2 {
                    Some(k) => self.point(&p, k, s.point2),
                    None => s.point2,
                };
                (b - a).length()
            };
            let gr = rate_gradient(&length);
            *c_full += &gr * gr.transpose() * s.damping;
        }
        for s in self.m.torsion_springs.iter().filter(|s| s.damping != 0.0) {
            let angle = |x: &DVector<f64>| {
                let p = self.poses(x);
                p.0[s.body1].1 - s.body2.map_or(0.0, |k| p.0[k].1)
            };
            let gr = rate_gradient(&angle);
            *c_full += &gr * gr.transpose() * s.damping;
        }
    }

    /// Every oscillating mode, lowest frequency first, with the start's energy in it.
    fn modes(
        &self,
        lin: &Linearized,
        undamped: &Undamped,
        damped: Option<&[Complex<f64>]>,
        s0: &DVector<f64>,
        sdot0: &DVector<f64>,
    ) -> Modes {
        let eig = &undamped.eig;
        let d = lin.nb.ncols();
        let mut matched = DampedMatch::new(damped);
        let mut order: Vec<usize> = (0..d)
            .filter(|&i| eig.eigenvalues[i] > undamped.tol)
            .collect();
        order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
        let free_motions = d - order.len();
        let mut modes = Vec::new();
        let mut energies = Vec::new();
        for &i in &order {
            let w2 = eig.eigenvalues[i];
            let w = w2.sqrt();
            let phi = undamped.phi(i);
            let eta = (phi.transpose() * &lin.m_r * s0)[(0, 0)];
            let etadot = (phi.transpose() * &lin.m_r * sdot0)[(0, 0)];
            energies.push(0.5 * (etadot * etadot + w2 * eta * eta));
            let omega_d = matched.omega_d(w);
            let shape = self.shape(&(&lin.nb * &phi));
            modes.push((
                Mode {
                    omega: w,
                    period: 2.0 * PI / w,
                    omega_d,
                    damped_period: omega_d.map(|wd| 2.0 * PI / wd),
                    shape,
                    energy_share: 0.0,
                },
                phi,
            ));
        }
        Modes {
            modes,
            energies,
            free_motions,
        }
    }

    /// Which member a motion `full` (full coordinates) moves most, and along what: a platform on
    /// a compressed spring with no guide falls sideways ("platform" along x), which the note
    /// names, so that the reason is not mistaken for the free body next to it (n14_20).
    fn largest_motion(&self, full: &DVector<f64>) -> String {
        let mut best = (0.0, String::new());
        for (k, b) in self.m.members.iter().enumerate() {
            let Some(s) = self.slot_of[k] else { continue };
            for (c, what) in ["along x", "along y", "turning"].iter().enumerate() {
                let size = full[3 * s + c].abs();
                if size > best.0 {
                    best = (size, format!("\"{}\" {what}", b.name));
                }
            }
        }
        best.1
    }

    /// Per member: (dx_G, dy_G, dtheta) of a mode's full coordinates.
    fn shape(&self, full: &DVector<f64>) -> Vec<(DVec2, f64)> {
        (0..self.m.members.len())
            .map(|k| match self.slot_of[k] {
                Some(s) => (
                    DVec2::new(full[3 * s], full[3 * s + 1]),
                    full[3 * s + 2] / self.l,
                ),
                None => (DVec2::ZERO, 0.0),
            })
            .collect()
    }

    /// Sets each mode's energy share and returns the period at the start's amplitude along the
    /// most excited mode's path, with its error against the linear period (None, 0 when the
    /// start is at rest in equilibrium).
    fn amplitude_period(
        &self,
        lin: &Linearized,
        undamped: &Undamped,
        found: &mut Modes,
        sdot0: &DVector<f64>,
    ) -> Result<(Option<f64>, f64), String> {
        let total: f64 = found.energies.iter().sum();
        if total > 0.0 {
            for (mode, e) in found.modes.iter_mut().zip(&found.energies) {
                mode.0.energy_share = e / total;
            }
            let (k, _) = found
                .energies
                .iter()
                .enumerate()
                .max_by(|a, b| a.1.total_cmp(b.1))
                .unwrap_or((0, &0.0));
            let e = self.oscillation_energy(lin, undamped, sdot0);
            if e > 0.0 {
                let (mode, phi) = &found.modes[k];
                let t_path =
                    self.path_period(&lin.q, &(&lin.nb * phi), &lin.m_full, e, mode.omega)?;
                return Ok((Some(t_path), (t_path / mode.period - 1.0).abs()));
            }
        }
        Ok((None, 0.0))
    }

    /// The start's oscillation energy, exact in V: T0 less the free motions' drift,
    /// plus V(q0) - V(q_eq).
    fn oscillation_energy(
        &self,
        lin: &Linearized,
        undamped: &Undamped,
        sdot0: &DVector<f64>,
    ) -> f64 {
        // (The start's rate as the joints allow it: its part along the null space.)
        let t0 = 0.5 * (sdot0.transpose() * &lin.m_r * sdot0)[(0, 0)];
        let drift: f64 = (0..lin.nb.ncols())
            .filter(|&i| undamped.eig.eigenvalues[i] <= undamped.tol)
            .map(|i| {
                let phi = undamped.phi(i);
                let etadot = (phi.transpose() * &lin.m_r * sdot0)[(0, 0)];
                0.5 * etadot * etadot
            })
            .sum();
        t0 - drift + self.potential(&self.q0) - self.potential(&lin.q)
    }

    /// The energy-integral period along the mode's path at energy e above the equilibrium (see
    /// `SmallOscillations::amplitude_period`): the path is followed from q by steps of M-metric
    /// length ds = reach / 2000 (reach = sqrt(2 e) / omega, the linear amplitude), each step
    /// along the last secant and projected back onto the constraints, so s is the path's
    /// M-arclength and m(s) = 1; T = 2 int ds / sqrt(2 (e - V(s))) with V linear between the
    /// steps (each piece integrated exactly: ds sqrt 2 / (sqrt r_a + sqrt r_b), r = e - V;
    /// error of order (ds / reach)^2).
    fn path_period(
        &self,
        q: &DVector<f64>,
        dir: &DVector<f64>,
        m_full: &DMatrix<f64>,
        e: f64,
        omega: f64,
    ) -> Result<f64, String> {
        let v_eq = self.potential(q);
        let m_norm = |d: &DVector<f64>| (d.transpose() * m_full * d)[(0, 0)].max(0.0).sqrt();
        let reach = (2.0 * e).sqrt() / omega;
        let step = reach / 2000.0;
        let mut t = 0.0;
        for sign in [1.0, -1.0] {
            let mut here = q.clone();
            let mut tangent = dir * (sign / m_norm(dir).max(1e-300));
            let mut r_prev = e;
            let mut turned = false;
            for _ in 0..40_000 {
                let next = self.project(&(&here + &tangent * step))?;
                let chord = &next - &here;
                let ds = m_norm(&chord);
                if ds <= 0.0 {
                    return Err("the mode's path stalls".into());
                }
                let r = e - (self.potential(&next) - v_eq);
                if r <= 0.0 {
                    // The turning point inside this piece, V linear across it.
                    t += ds * (r_prev / (r_prev - r)) * 2f64.sqrt() / r_prev.sqrt();
                    turned = true;
                    break;
                }
                if r > r_prev {
                    return Err(
                        "the swing goes over the top: the start's energy carries it past the potential's crest"
                            .into(),
                    );
                }
                t += ds * 2f64.sqrt() / (r_prev.sqrt() + r.sqrt());
                r_prev = r;
                tangent = chord / ds;
                here = next;
            }
            if !turned {
                return Err("the swing does not turn back within 20 times its linear reach".into());
            }
        }
        // The time from one turning point to the other, twice.
        Ok(2.0 * t)
    }
}

impl Undamped {
    /// K phi = w^2 M phi through M = L L^T: (L^-1 K L^-T) y = w^2 y, phi = L^-T y. Err when the
    /// equilibrium is unstable or nothing restores the mechanism.
    /// `motion` names the member and direction a full-coordinate motion moves most (the note
    /// says which way an unstable equilibrium falls).
    fn of(lin: &Linearized, motion: impl Fn(&DVector<f64>) -> String) -> Result<Undamped, String> {
        let chol = Cholesky::new(lin.m_r.clone())
            .ok_or("the reduced mass matrix is not positive definite")?;
        let lm = chol.l();
        let lm_inv = lm
            .clone()
            .try_inverse()
            .ok_or("the reduced mass matrix is singular")?;
        let a = &lm_inv * &lin.k_r * lm_inv.transpose();
        let a = (&a + a.transpose()) * 0.5;
        let eig = SymmetricEigen::try_new(a, 1e-15, 1000)
            .ok_or("the mode eigenproblem did not converge")?;
        let w2max = eig.eigenvalues.amax().max(1e-300);
        let tol = 1e-6 * w2max;
        let d = lin.nb.ncols();
        if let Some(k) = (0..d).find(|&i| eig.eigenvalues[i] < -tol) {
            let falls = &lin.nb * (lm_inv.transpose() * eig.eigenvectors.column(k));
            return Err(format!(
                "the equilibrium nearest the start is unstable (omega^2 = {:.3e} 1/s^2 < 0): it falls away moving {}",
                eig.eigenvalues[k],
                motion(&falls)
            ));
        }
        if eig.eigenvalues.max() <= tol || eig.eigenvalues.max() <= 0.0 {
            return Err("nothing restores the mechanism: every direction is free".into());
        }
        Ok(Undamped {
            chol,
            lm_inv,
            eig,
            tol,
        })
    }
}

/// Damped eigenvalues of [0 I; -M^-1 K  -M^-1 C] (None without dampers).
fn damped_eigenvalues(
    lin: &Linearized,
    undamped: &Undamped,
) -> Result<Option<Vec<Complex<f64>>>, String> {
    if lin.c_r.amax() > 0.0 {
        let d = lin.nb.ncols();
        let m_inv = undamped.chol.inverse();
        let mut big = DMatrix::zeros(2 * d, 2 * d);
        big.view_mut((0, d), (d, d)).fill_with_identity();
        big.view_mut((d, 0), (d, d))
            .copy_from(&(-&m_inv * &lin.k_r));
        big.view_mut((d, d), (d, d))
            .copy_from(&(-&m_inv * &lin.c_r));
        let schur = nalgebra::linalg::Schur::try_new(big, 1e-15, 10000)
            .ok_or("the damped eigenproblem did not converge")?;
        Ok(Some(schur.complex_eigenvalues().iter().copied().collect()))
    } else {
        Ok(None)
    }
}

/// Each undamped mode's damped eigenvalue: the unused one of nearest |lambda| in the upper half
/// plane (exact for proportional damping).
struct DampedMatch<'a> {
    lams: Option<&'a [Complex<f64>]>,
    used: Vec<bool>,
}

impl<'a> DampedMatch<'a> {
    fn new(lams: Option<&'a [Complex<f64>]>) -> Self {
        DampedMatch {
            lams,
            used: vec![false; lams.map_or(0, <[_]>::len)],
        }
    }

    /// omega_d of the mode of undamped omega w: w itself without dampers; None when its match
    /// does not oscillate (overdamped) or none is left.
    fn omega_d(&mut self, w: f64) -> Option<f64> {
        let Some(lams) = self.lams else {
            return Some(w);
        };
        let used = &mut self.used;
        let best = (0..lams.len())
            .filter(|&k| !used[k] && lams[k].im >= 0.0)
            .min_by(|&a, &b| {
                (lams[a].norm() - w)
                    .abs()
                    .total_cmp(&(lams[b].norm() - w).abs())
            });
        best.and_then(|k| {
            used[k] = true;
            (lams[k].im > 1e-9 * w).then_some(lams[k].im)
        })
    }
}
