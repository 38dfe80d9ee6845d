//! One physics step, phase by phase: how rigidlab drives rapier.
//!
//! 1. The declared forces rigidlab applies itself, so that their work is known exactly: impulse
//!    events at the step's start, loads held over it (`forces.rs`).
//! 2. The call plan: one rapier call of n substeps, or n calls of one (split substeps), each cut
//!    where an impact falls in it (`plan.rs`).
//! 3. Each rapier call: its parameters; the loads, carriers' pulls, springs and dampers held over
//!    it (`forces.rs`; the dampers at the call's predicted mean rate, `dampers.rs`); the
//!    prescribed motions, rapier's own step and the couplings projected
//!    after it; the call's impulses summed into the step's (`calls.rs`).
//! 4. The snapshot at the step's end: bodies, the non-finite guard, contacts, welds, joints,
//!    couplings, springs, then the explosion guards (`snapshot.rs`).

mod calls;
mod dampers;
mod forces;
mod plan;
mod snapshot;

use super::world::Simulation;
use crate::sim::options::SimError;
use crate::snapshot::Snapshot;
use calls::StepReadings;

impl Simulation {
    /// Advances one physics step and refreshes the snapshot.
    pub fn step(&mut self) -> Result<&Snapshot, SimError> {
        let dt = self.dt();
        let t0 = self.snapshot.time;
        let step = self.snapshot.step + 1;
        self.energy.record(&self.snapshot);

        self.apply_impulse_events(t0, dt);
        let loads = self.evaluate_loads(t0 + 0.5 * dt);

        let mut calls = self.plan_calls(dt);
        let mut readings = StepReadings::new(self);
        while let Some(call) = self.next_call(&mut calls) {
            self.set_call_parameters(&call);
            self.apply_call_forces(&loads, &call, dt, &mut readings);
            let rows_from = self.run_rapier_call(t0, &call, &calls, &mut readings)?;
            self.read_call_impulses(&call, &calls, rows_from, &mut readings);
        }
        self.close_calls(&calls, dt);

        self.read_step_end_bodies(step, dt, calls.n)?;
        self.read_step_interactions(calls.merged, readings);
        self.guard_energy()?;
        Ok(&self.snapshot)
    }
}
