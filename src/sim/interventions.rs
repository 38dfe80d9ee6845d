//! What the window and the studies do to a running simulation between steps, in plain f64, so
//! that rapier's types stay inside `sim/`: a user's blow with the mouse, and a restart from a
//! reference state (the accuracy study's pieces).

use super::rapier::prelude::*;
use super::world::{vd, Simulation};
use crate::snapshot::{BodyKind, BodyState};
use glam::DVec2;

impl Simulation {
    /// Applies an impulse `j` (N s) at world point `at` to body `i`, between steps: J on the
    /// mass center and the angular impulse r_{P/G} x J (G from the snapshot, current between
    /// steps). Returns whether the body exists.
    pub fn apply_impulse(&mut self, i: usize, at: DVec2, j: DVec2) -> bool {
        let (Some(&h), Some(com)) = (
            self.bodies.get(i),
            self.snapshot.bodies.get(i).map(|b| b.com),
        ) else {
            return false;
        };
        let Some(rb) = self.world.bodies.get_mut(h) else {
            return false;
        };
        rb.apply_impulse(vd(j), true);
        rb.apply_torque_impulse((at - com).perp_dot(j) as Real, true);
        // A blow: the next step's joint impulses are summed substep by substep, not
        // reconstructed from a substep before it (sim/joint_sums.rs).
        self.substeps_seen.clear();
        true
    }

    /// Overwrites every non-fixed body's pose and velocity with `bodies` (by index), as when a
    /// piece of a run restarts from a reference state. rapier's linvel is the mass center's
    /// velocity, as the snapshot's.
    pub fn restart_from(&mut self, bodies: &[BodyState]) {
        // The substep before the restart is not the new state's (sim/joint_sums.rs).
        self.substeps_seen.clear();
        for (h, b) in self.bodies.iter().zip(bodies) {
            if b.kind == BodyKind::Fixed {
                continue;
            }
            let rb = &mut self.world.bodies[*h];
            rb.set_position(Pose::new(vd(b.position), b.angle as Real), true);
            rb.set_linvel(vd(b.velocity), true);
            rb.set_angvel(b.omega as Real, true);
        }
    }
}
