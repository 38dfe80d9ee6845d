//! The snapshot at the step's end: the bodies read and guarded first, then what acted between
//! them over the step, then the explosion guards on the whole.

use super::super::readings::place_at_step_end;
use super::super::world::Simulation;
use super::calls::StepReadings;
use crate::sim::options::SimError;
use crate::snapshot::*;

impl Simulation {
    /// The bodies at the step's end; a non-finite pose or rate stops the run.
    pub(super) fn read_step_end_bodies(
        &mut self,
        step: u64,
        dt: f64,
        substeps: usize,
    ) -> Result<(), SimError> {
        self.snapshot.step = step;
        self.snapshot.time = step as f64 * dt;
        self.snapshot.dt = dt;
        self.snapshot.substeps = substeps;
        self.read_bodies();
        self.prescribed_rates();
        self.guard()
    }

    /// The step's contacts, welds, joints, couplings and springs: summed over its calls when
    /// `merged` (split or cut), else read from rapier's one call.
    pub(super) fn read_step_interactions(&mut self, merged: bool, readings: StepReadings) {
        if !readings.contacts_wanted {
            self.snapshot.contacts.clear();
        } else if merged {
            let mut contacts = readings.contacts;
            place_at_step_end(&mut contacts, &self.snapshot.bodies);
            self.snapshot.contacts = contacts;
        } else {
            self.read_contacts();
        }
        self.weld_on_contact();
        // Welds created now get their first impulses next step.
        if merged {
            self.snapshot.joints = readings.joints;
        } else if self.settings.split_at_blows {
            self.read_reconstructed_joints();
        } else {
            self.read_joints();
        }
        self.book_motor_absorbed();
        self.snapshot.couplings = self.coupling_states(&readings.lambdas, &readings.carried);
        self.snapshot.springs = self.springs_at_step_end(readings.springs);
    }

    /// Spring state: forces held during the step (`held`), length and energy at its end.
    fn springs_at_step_end(&self, held: Vec<SpringState>) -> Vec<SpringState> {
        let end = self.spring_states(false);
        held.into_iter()
            .zip(end)
            .map(|(held, now)| SpringState {
                force_on_body1: held.force_on_body1,
                tension: held.tension,
                damper_tension: held.damper_tension,
                couple_on_body1: held.couple_on_body1,
                applied_at1: held.applied_at1,
                applied_at2: held.applied_at2,
                ..now
            })
            .collect()
    }

    /// Counts the step's work into the energy guard, then stops a run that exploded or that
    /// rapier's speed cap holds (`sim::explosion_guard`).
    pub(super) fn guard_energy(&mut self) -> Result<(), SimError> {
        self.energy.add_work(&self.snapshot);
        self.energy_guard()?;
        self.speed_cap_guard()
    }
}
