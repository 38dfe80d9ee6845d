//! The rapier calls of one step: each call's parameters, rapier's own step with the prescribed
//! motions and the couplings around it, and the call's impulses summed into the step's.

use super::super::contact_points::RoundContactPoints;
use super::super::impacts::IMPACT_ITERATIONS;
use super::super::rapier::prelude::*;
use super::super::readings::{merge_contacts, merge_joints, JointPoses};
use super::super::world::Simulation;
use super::plan::{Call, CallQueue};
use crate::sim::options::SimError;
use crate::snapshot::*;
use glam::DVec2;

/// What a step's rapier calls read, summed over them into the step's snapshot.
pub(super) struct StepReadings {
    /// Whether the step's contacts are read (`Simulation::set_contact_readings`).
    pub(super) contacts_wanted: bool,
    /// Each coupling's impulse over the step.
    pub(super) lambdas: Vec<f64>,
    /// The impulse each coupling's carriers were loaded with over the step (sim/couplings.rs).
    pub(super) carried: Vec<Vec<DVec2>>,
    /// The springs' forces as the step's mean (its impulse / dt), with the first call's points.
    pub(super) springs: Vec<SpringState>,
    /// Joint and contact impulses summed over the calls, when they are read after each.
    pub(super) joints: Vec<JointState>,
    pub(super) contacts: Vec<ContactState>,
}

impl StepReadings {
    /// Nothing read yet.
    pub(super) fn new(sim: &Simulation) -> Self {
        StepReadings {
            contacts_wanted: sim.contacts_wanted(),
            lambdas: vec![0.0; sim.level.couplings.len()],
            carried: sim
                .carriers
                .iter()
                .map(|c| vec![DVec2::ZERO; c.len()])
                .collect(),
            springs: Vec::new(),
            joints: Vec::new(),
            contacts: Vec::new(),
        }
    }

    /// Adds one call's spring states, weighted by its share `weight` of the step.
    pub(super) fn add_springs(&mut self, mut now: Vec<SpringState>, weight: f64, first: bool) {
        // The snapshot reports the mean force over the step (its impulse / dt).
        for sp in now.iter_mut() {
            sp.force_on_body1 *= weight;
            sp.tension *= weight;
            sp.damper_tension *= weight;
            sp.couple_on_body1 *= weight;
        }
        if first {
            self.springs = now;
        } else {
            for (a, b) in self.springs.iter_mut().zip(&now) {
                a.force_on_body1 += b.force_on_body1;
                a.tension += b.tension;
                a.damper_tension += b.damper_tension;
                a.couple_on_body1 += b.couple_on_body1;
            }
        }
    }
}

impl Simulation {
    /// rapier's parameters for one call: its length, substeps, prediction distance and friction
    /// sweeps.
    pub(super) fn set_call_parameters(&mut self, call: &Call) {
        self.last_call = call.h;
        let p = &mut self.world.integration_parameters;
        p.dt = call.h as Real;
        p.num_solver_iterations = call.sub;
        p.normalized_prediction_distance = call
            .prediction
            .map_or(self.prediction_distance, |x| x as Real);
        // An impact's call and the one after it solve friction to convergence.
        p.num_internal_stabilization_iterations = if call.impact_now || self.after_impact {
            self.settings.solver_iterations.max(IMPACT_ITERATIONS)
        } else {
            self.settings.solver_iterations
        };
        self.after_impact = call.impact_now;
    }

    /// One rapier call from `t0 + call.start`: the prescribed motions' rates, rapier's step, and
    /// the couplings projected after it. Returns the poses the call's joint rows were built
    /// from, when its impulses may be read along them.
    pub(super) fn run_rapier_call(
        &mut self,
        t0: f64,
        call: &Call,
        calls: &CallQueue,
        readings: &mut StepReadings,
    ) -> Result<Option<Vec<JointPoses>>, SimError> {
        // rapier builds a substep's joint rows from the poses it starts from: keep them,
        // so the call's impulses (all of one substep) are read along the very rows they
        // acted on.
        let rows_from =
            (calls.split || calls.merged || self.settings.impact_cuts).then(|| self.joint_poses());
        self.prescribe_velocities(t0 + call.start, t0 + call.start + call.h)?;
        // Round bodies' friction acts on their rims, not halfway into an overlap
        // (sim/contact_points.rs).
        self.world.step_with_events(
            &RoundContactPoints {
                call_dt: call.h as Real,
                gravity: self.world.gravity,
            },
            &(),
        );
        let mut call_lambdas = self.solve_couplings();
        self.close_coupling_call(&mut call_lambdas, call.h, call.impact_now);
        self.owe_carriers(&call_lambdas);
        for (l, x) in readings.lambdas.iter_mut().zip(call_lambdas) {
            *l += x;
        }
        Ok(rows_from)
    }

    /// Sums the call's contact and joint impulses into the step's, when the step has several
    /// calls (a call of several rapier substeps holds the last one's joint impulses only).
    pub(super) fn read_call_impulses(
        &mut self,
        call: &Call,
        calls: &CallQueue,
        rows_from: Option<Vec<JointPoses>>,
        readings: &mut StepReadings,
    ) {
        let Some(poses) = rows_from.filter(|_| calls.split || calls.merged || calls.more_to_come())
        else {
            return;
        };
        if readings.contacts_wanted {
            self.read_contacts_with(true);
            merge_contacts(&mut readings.contacts, &self.snapshot.contacts);
        }
        self.read_joints_scaled(call.sub as f64, Some(&poses));
        if self.settings.split_at_blows && !calls.more_to_come() {
            self.keep_last_substep(call.sub);
        }
        merge_joints(&mut readings.joints, &self.snapshot.joints);
    }

    /// Counts how the step was called (`Settings::as_run` reports it), and gives rapier back the
    /// step's own length and substeps.
    pub(super) fn close_calls(&mut self, calls: &CallQueue, dt: f64) {
        self.last_step_cuts = calls.cuts;
        self.calls.steps += 1;
        self.calls.calls += calls.planned as u64;
        if calls.split_for_arc {
            self.calls.split_for_arc += 1;
        } else if calls.split_for_blow {
            self.calls.split_for_blow += 1;
        } else if calls.split_for_spin {
            self.calls.split_for_spin += 1;
        }
        if calls.cuts > 0 {
            self.calls.cut += 1;
        }
        let p = &mut self.world.integration_parameters;
        p.dt = dt as Real;
        p.num_solver_iterations = calls.n;
    }
}
