//! Couplings (pulleys, cables, gears): ratio constraints rigidlab enforces after each rapier call
//! by projecting velocities and positions, and the impulses that took.

use super::rapier::prelude::*;
use super::world::{to_d, vd, wrap_pi, Simulation};
use crate::level::*;
use crate::snapshot::*;
use glam::DVec2;

impl Simulation {
    pub(super) fn coordinate(&self, body: usize, c: Coordinate) -> (f64, f64, f64) {
        // (q, dq/dt, inverse generalized mass) of a body coordinate.
        let rb = &self.world.bodies[self.bodies[body]];
        let mp = rb.mass_properties();
        let dynamic = rb.is_dynamic();
        let com = *rb.position() * mp.local_mprops.local_com;
        match c {
            Coordinate::X => (
                com.x as f64,
                rb.linvel().x as f64,
                if dynamic {
                    mp.effective_inv_mass.x as f64
                } else {
                    0.0
                },
            ),
            Coordinate::Y => (
                com.y as f64,
                rb.linvel().y as f64,
                if dynamic {
                    mp.effective_inv_mass.y as f64
                } else {
                    0.0
                },
            ),
            Coordinate::Angle => {
                let prev = self.snapshot.bodies[body].angle;
                let q = prev + wrap_pi(rb.rotation().angle() as f64 - prev);
                (
                    q,
                    rb.angvel() as f64,
                    if dynamic {
                        mp.effective_world_inv_inertia as f64
                    } else {
                        0.0
                    },
                )
            }
        }
    }

    pub(super) fn coupling_value(&self, c: &CouplingDef) -> f64 {
        c.terms
            .iter()
            .map(|t| t.ratio * self.coordinate(self.body_index[&t.body], t.coordinate).0)
            .sum()
    }

    /// Enforces every coupling after rapier's step: Gauss-Seidel on velocities (the impulse
    /// lambda that makes sum(c_i v_i) = 0; exact in one pass for a single coupling, iterated for
    /// couplings that share a body), then a position projection that removes the drift without
    /// adding velocity. Returns each coupling's impulse over the step.
    pub(super) fn solve_couplings(&mut self) -> Vec<f64> {
        let n = self.level.couplings.len();
        let mut lambdas = vec![0.0; n];
        if n == 0 || !self.settings.effects.has(Effect::Joints) {
            return lambdas;
        }
        let terms: Vec<Vec<(usize, Coordinate, f64)>> = self
            .level
            .couplings
            .iter()
            .map(|c| {
                c.terms
                    .iter()
                    .map(|t| (self.body_index[&t.body], t.coordinate, t.ratio))
                    .collect()
            })
            .collect();
        let held = self.motor_held_angles();
        for pass in 0..2 {
            // pass 0: velocities; pass 1: positions.
            for _sweep in 0..64 {
                let mut worst: f64 = 0.0;
                for (k, ts) in terms.iter().enumerate() {
                    let (mut num, mut den, mut size) = (0.0_f64, 0.0, 0.0);
                    for &(b, c, r) in ts {
                        let (q, v, w) = self.coordinate(b, c);
                        let x = if pass == 0 { v } else { q };
                        num += r * x;
                        den += r * r * w;
                        size += (r * x).abs();
                    }
                    if den <= 0.0 {
                        continue;
                    }
                    // A coordinate an ideal velocity motor holds does not give (the motor
                    // answers the cable): the others take the whole correction, unless all
                    // the coupling's coordinates are held.
                    let gives = |b: usize, c: Coordinate| !(c == Coordinate::Angle && held[b]);
                    let free: f64 = ts
                        .iter()
                        .filter(|&&(b, c, _)| gives(b, c))
                        .map(|&(b, c, r)| r * r * self.coordinate(b, c).2)
                        .sum();
                    let hold = free > 0.0 && free < den;
                    let den = if hold { free } else { den };
                    // A velocity error below what the engine's precision can hold is left
                    // alone: rapier's f32 velocity would not change, but the impulse would still
                    // be counted in lambda (the massive Atwood pulley's alpha from its diagram
                    // read 2.2e-3 off at 8 substeps from such uncounted-but-recorded sweeps).
                    if pass == 0 && num.abs() <= 4.0 * super::PRECISION.epsilon() * size {
                        continue;
                    }
                    let target = if pass == 0 {
                        0.0
                    } else {
                        self.coupling_rest[k]
                    };
                    let mu = -(num - target) / den;
                    worst = worst.max((num - target).abs());
                    if pass == 0 {
                        lambdas[k] += mu;
                    }
                    for &(b, c, r) in ts {
                        let w = self.coordinate(b, c).2;
                        if pass == 0 && hold && !gives(b, c) {
                            // The motor takes the cable's couple on it: its reading gets it.
                            self.motor_absorbed[b] -= r * mu;
                            continue;
                        }
                        if w == 0.0 {
                            continue;
                        }
                        let d = (r * w * mu) as Real;
                        let rb = &mut self.world.bodies[self.bodies[b]];
                        match (pass, c) {
                            (0, Coordinate::X) => {
                                rb.set_linvel(rb.linvel() + Vector::new(d, 0.0), true)
                            }
                            (0, Coordinate::Y) => {
                                rb.set_linvel(rb.linvel() + Vector::new(0.0, d), true)
                            }
                            (0, Coordinate::Angle) => rb.set_angvel(rb.angvel() + d, true),
                            (_, Coordinate::X) => {
                                rb.set_translation(rb.translation() + Vector::new(d, 0.0), true)
                            }
                            (_, Coordinate::Y) => {
                                rb.set_translation(rb.translation() + Vector::new(0.0, d), true)
                            }
                            (_, Coordinate::Angle) => {
                                // Turn about the mass center, not the body origin.
                                let local_com = rb.mass_properties().local_mprops.local_com;
                                let com = *rb.position() * local_com;
                                let rot = Rotation::new(rb.rotation().angle() + d);
                                rb.set_position(Pose::from_parts(com - rot * local_com, rot), true);
                            }
                        }
                    }
                }
                if worst < 1e-12 {
                    break;
                }
            }
        }
        lambdas
    }

    /// Per body: whether an ideal velocity motor (no force limit) holds its angle, on a pin to a
    /// body that does not move under forces (fixed or kinematic).
    pub(super) fn motor_held_angles(&self) -> Vec<bool> {
        let mut held = vec![false; self.bodies.len()];
        if !self.settings.effects.has(Effect::Motors) {
            return held;
        }
        let still = |name: &str| {
            let i = self.body_index[name];
            self.level.bodies[i].kind != crate::level::BodyKind::Dynamic
        };
        for j in &self.joint_defs {
            let ideal = matches!(
                j.motor,
                Some(Motor::Velocity {
                    max_force: None,
                    ..
                })
            );
            if !ideal || j.kind != JointKind::Revolute {
                continue;
            }
            if still(&j.body1) {
                held[self.body_index[&j.body2]] = true;
            } else if still(&j.body2) {
                held[self.body_index[&j.body1]] = true;
            }
        }
        held
    }

    /// Gives each cable's carrier (the pulley it runs over) the reaction it is owed as a force
    /// held over the coming rapier call of length `h`, so rapier's joints carry it to the
    /// axle, and adds it to `carried` (the step's impulse on each carrier).
    ///
    /// Why one call late: the cable's pull is known only after rapier's call (the coupling is
    /// projected after it), and a velocity kick to the carrier then would show in its velocity
    /// until the next call's joint removed it. Held as a force, the reaction enters rapier's
    /// solver with the carrier's joints: in steady motion (a constant tension) the axle load is
    /// exact, and in a transient it lags the cable by one call (dt / substeps when joint readings
    /// split the step, else dt), the integrator's own order.
    pub(super) fn load_carriers(&mut self, h: f64, carried: &mut [Vec<DVec2>]) {
        for (k, carriers) in self.carriers.iter().enumerate() {
            for (n, &(i, due)) in carriers.iter().enumerate() {
                let rb = &mut self.world.bodies[self.bodies[i]];
                rb.add_force(vd(due / h), true);
                carried[k][n] += due;
            }
        }
    }

    /// Records what each carrier is owed after a rapier call whose couplings took `lambdas`.
    /// Over a pulley: the opposite of the cable's pull on its x and y terms (the cable is
    /// massless). Meshing gears: the tooth force. Gear i's angle term took the couple r_i lambda;
    /// with r_i its pitch radius, that is a force lambda across the line of centers at the pitch
    /// point, sign(r_1) lambda perp(u) on gear 1 (u from gear 1's center to gear 2's) and its
    /// opposite on gear 2, whose linear parts act at the centers: the axles' loads.
    pub(super) fn owe_carriers(&mut self, lambdas: &[f64]) {
        for (k, c) in self.level.couplings.iter().enumerate() {
            if self.carriers[k].is_empty() {
                continue;
            }
            if c.gears {
                let g = |n: usize| self.snapshot_com(self.carriers[k][n].0);
                let u = (g(1) - g(0)).normalize_or(DVec2::X);
                let f1 = c.terms[0].ratio.signum() * lambdas[k] * u.perp();
                self.carriers[k][0].1 = f1;
                self.carriers[k][1].1 = -f1;
                continue;
            }
            let pull: DVec2 = c
                .terms
                .iter()
                .map(|t| match t.coordinate {
                    Coordinate::X => DVec2::new(t.ratio * lambdas[k], 0.0),
                    Coordinate::Y => DVec2::new(0.0, t.ratio * lambdas[k]),
                    Coordinate::Angle => DVec2::ZERO,
                })
                .sum();
            self.carriers[k][0].1 = -pull;
        }
    }

    /// Body i's mass center in rapier's current state.
    fn snapshot_com(&self, i: usize) -> DVec2 {
        let rb = &self.world.bodies[self.bodies[i]];
        to_d(*rb.position() * rb.mass_properties().local_mprops.local_com)
    }

    pub(super) fn coupling_states(
        &self,
        lambdas: &[f64],
        carried: &[Vec<DVec2>],
    ) -> Vec<CouplingState> {
        self.level
            .couplings
            .iter()
            .enumerate()
            .map(|(k, c)| {
                let value = self.coupling_value(c);
                CouplingState {
                    name: c.name.clone(),
                    terms: c
                        .terms
                        .iter()
                        .map(|t| (self.body_index[&t.body], t.coordinate, t.ratio))
                        .collect(),
                    impulse: lambdas[k],
                    value,
                    drift: value - self.coupling_rest[k],
                    carriers: self.carriers[k]
                        .iter()
                        .zip(&carried[k])
                        .map(|(&(i, _), &j)| (i, j))
                        .collect(),
                }
            })
            .collect()
    }
}
