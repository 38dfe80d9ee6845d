//! One pass over a step: what the textbook computes for every body and for the scene.
//!
//! [`FrameAnalysis::observe`] takes the snapshots in order and returns a [`Frame`]: per body its
//! kinetic energy (6/9), momenta (6/12, 6/13), instantaneous center (RK-11), accelerations by
//! finite differences, the free-body diagram's force and moment sums and the Newton-Euler
//! residuals (6/1); for the scene T, V_g, V_e, G and H about the origin (6/18, 6/19). It costs
//! O(bodies + contacts + joints) per step, for the app's overlays, the CSV and the benchmark.

use super::energy::{gravity_potential, kinetic_energy};
use super::kinematics::{acceleration_fd, angular_acceleration_fd, instantaneous_center};
use super::kinetics::{for_each_body_impulse, Before, ContactArms};
use super::momentum::{angular_momentum_about, angular_momentum_g, linear_momentum};
use super::Motion;
use crate::snapshot::Snapshot;
use glam::DVec2;

/// One body's textbook quantities at the end of a step (zero for bodies without mass).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct BodyFrame {
    /// T = 1/2 m v_G^2 + 1/2 I_G w^2 (6/9), J.
    pub kinetic_energy: f64,
    /// G = m v_G (6/12), N s.
    pub linear_momentum: DVec2,
    /// H_G = I_G w (6/13), N m s.
    pub angular_momentum_g: f64,
    /// The instantaneous center of zero velocity (RK-11); None in translation.
    pub instantaneous_center: Option<DVec2>,
    /// a_G and alpha by finite differences over the step (`FD`).
    pub acceleration: DVec2,
    pub angular_acceleration: f64,
    /// Sum of forces and of moments about G from the free-body diagram (impulse / dt), N and N m.
    pub force: DVec2,
    pub moment_g: f64,
    /// sum F - m a_G and sum M_G - I_G alpha (6/1).
    pub force_residual: DVec2,
    pub moment_residual: f64,
}

/// The whole scene at the end of a step.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Frame {
    pub time: f64,
    /// Indexed like `Snapshot::bodies`.
    pub bodies: Vec<BodyFrame>,
    /// Sum of T, J.
    pub kinetic_energy: f64,
    /// Sum of V_g = -m g . r_G, J (WE-13).
    pub gravity_potential: f64,
    /// Sum of the springs' V_e = 1/2 k x^2, J.
    pub elastic_potential: f64,
    /// System G (6/18), N s.
    pub linear_momentum: DVec2,
    /// System H about the world origin (6/19), N m s; move it with `momentum::transfer_angular_momentum`.
    pub angular_momentum_origin: f64,
}

/// Computes a [`Frame`] per snapshot, keeping what it needs from the previous one.
#[derive(Debug, Clone, Default)]
pub struct FrameAnalysis {
    substeps: usize,
    before: Vec<Motion>,
    arms: ContactArms,
    frame: Frame,
}

impl FrameAnalysis {
    /// `substeps`: the solver's substeps per step (where gravity acts within the step).
    pub fn new(substeps: usize) -> Self {
        FrameAnalysis {
            substeps,
            ..Default::default()
        }
    }

    /// The frame of `snap` (the snapshots must come in order, the initial one first).
    pub fn observe(&mut self, snap: &Snapshot) -> &Frame {
        let n = snap.bodies.len();
        let f = &mut self.frame;
        f.time = snap.time;
        f.bodies.clear();
        f.bodies.resize(n, BodyFrame::default());
        f.kinetic_energy = 0.0;
        f.gravity_potential = 0.0;
        f.linear_momentum = DVec2::ZERO;
        f.angular_momentum_origin = 0.0;
        f.elastic_potential = snap.springs.iter().map(|s| s.energy).sum();
        let stepped = snap.dt > 0.0 && self.before.len() == n;
        if stepped {
            self.arms.update(Before::All(&self.before), snap);
            let bodies = &mut f.bodies;
            for_each_body_impulse(&self.before, snap, self.substeps, Some(&self.arms), |imp| {
                let b = &mut bodies[imp.body];
                b.force += imp.impulse;
                b.moment_g += imp.moment_about_g();
            });
        }
        for (i, b) in snap.bodies.iter().enumerate() {
            if b.mass <= 0.0 {
                continue;
            }
            let bf = &mut f.bodies[i];
            bf.kinetic_energy = kinetic_energy(b.mass, b.velocity, b.inertia, b.omega);
            bf.linear_momentum = linear_momentum(b.mass, b.velocity);
            bf.angular_momentum_g = angular_momentum_g(b.inertia, b.omega);
            bf.instantaneous_center = instantaneous_center(b.com, b.velocity, b.omega, 1e9);
            if stepped {
                let m0 = &self.before[i];
                bf.acceleration = acceleration_fd(m0.velocity, b.velocity, snap.dt);
                bf.angular_acceleration = angular_acceleration_fd(m0.omega, b.omega, snap.dt);
                bf.force /= snap.dt;
                bf.moment_g /= snap.dt;
                bf.force_residual = bf.force - b.mass * bf.acceleration;
                bf.moment_residual = bf.moment_g - b.inertia * bf.angular_acceleration;
            }
            f.kinetic_energy += bf.kinetic_energy;
            f.gravity_potential += gravity_potential(b.mass, snap.gravity, b.com);
            f.linear_momentum += bf.linear_momentum;
            f.angular_momentum_origin +=
                angular_momentum_about(b.mass, b.inertia, b.com, b.velocity, b.omega, DVec2::ZERO);
        }
        self.before.resize(n, Motion::default());
        for (m, b) in self.before.iter_mut().zip(&snap.bodies) {
            *m = Motion::from(b);
        }
        &self.frame
    }
}
