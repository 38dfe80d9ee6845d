//! The plan of one step's rapier calls: one call of the step's n substeps, n calls of one (split
//! substeps), or for a spinning ball's contact m calls of n / m, each cut in two where an impact
//! falls in it (sim/impacts.rs).

use super::super::impacts::{CallPlan, IMPACT_CALL, MAX_CUTS};
use super::super::world::Simulation;
use super::super::{arc_split, contact_points};
use crate::sim::settings::Substepping;
use std::collections::VecDeque;

/// The rapier calls of one step: planned before the first, cut at impacts as they come.
pub(super) struct CallQueue {
    /// The calls still to make, (length, rapier substeps): n calls of one substep when split,
    /// else one call of n; an impact cut (sim/impacts.rs) divides a call in two.
    pending: VecDeque<(f64, usize)>,
    /// The step's substeps, n.
    pub(super) n: usize,
    /// Whether the step is split into calls of one substep.
    pub(super) split: bool,
    /// Whether it is split for a spinning ball in contact (sim/contact_points.rs, `spin_calls`:
    /// into n calls of one substep, or fewer calls of several).
    pub(super) split_for_spin: bool,
    /// Whether it is split for a smooth ball on an `Arc`'s circle alone (sim/arc_split.rs).
    pub(super) split_for_arc: bool,
    /// Whether it is split because a blow can fall in it, where its joint impulses would
    /// otherwise be reconstructed from one call (sim/joint_sums.rs).
    pub(super) split_for_blow: bool,
    /// The impact plan of the step's one call, made when deciding whether to split it.
    first_plan: Option<CallPlan>,
    /// The calls planned, before any impact cut.
    pub(super) planned: usize,
    /// How many times the impact planner cut a call of this step.
    pub(super) cuts: usize,
    /// A blow (an impulse event) this step: its first call solves friction to convergence, as
    /// an impact's does (sim/impacts.rs, IMPACT_ITERATIONS).
    blow: bool,
    /// Whether the coming call is the short one a cut planned for its contact (then no pair
    /// touching in it is cut again).
    impact_call_next: bool,
    /// Whether the step's impulses are summed over several calls (split, or cut at an impact).
    pub(super) merged: bool,
    /// Whether no call has been made yet.
    first: bool,
    /// The time into the step at which the coming call starts.
    elapsed: f64,
}

/// One rapier call, as planned.
pub(super) struct Call {
    /// Its length, s.
    pub(super) h: f64,
    /// Its rapier substeps.
    pub(super) sub: usize,
    /// rapier's prediction distance for it, when the impact planner set one.
    pub(super) prediction: Option<f64>,
    /// Whether it makes an impact's contact or takes a blow (sim/impacts.rs,
    /// IMPACT_ITERATIONS).
    pub(super) impact_now: bool,
    /// Whether it is the step's first call.
    pub(super) first: bool,
    /// The time into the step at which it starts, s.
    pub(super) start: f64,
}

impl CallQueue {
    /// Whether calls are still to come after the one being made.
    pub(super) fn more_to_come(&self) -> bool {
        !self.pending.is_empty()
    }

    /// Cuts the coming call (`h` long, `sub` substeps) at `t`, where its impact falls: returns
    /// the length of the call now made and whether it is the one that makes the contact.
    fn cut(&mut self, h: f64, sub: usize, t: f64) -> (f64, bool) {
        // The contact is made in a short call after the cut, where rapier's soft contact acts
        // as a nearly rigid one (its softness grows with the call's length), then the rest of
        // the call.
        let impact = (h - t).min(h * IMPACT_CALL);
        if h - t - impact > 0.0 {
            self.pending.push_front((h - t - impact, sub));
        }
        self.cuts += 1;
        self.merged = true;
        if t > 0.0 {
            self.pending.push_front((impact, sub));
            self.impact_call_next = true;
            (t, false)
        } else {
            (impact, true)
        }
    }
}

impl Simulation {
    /// The step's calls before any impact cut.
    pub(super) fn plan_calls(&mut self, dt: f64) -> CallQueue {
        // Split substeps (see `Substepping::Split`): rapier is advanced n times at dt/n with one
        // substep each. Springs are then evaluated before every substep (rapier's own substeps
        // see only the forces set before its step: a spring held over n > 1 substeps is not
        // symplectic and gains energy, x2.5e4 in 10 s at omega dt = 0.5 with 4 substeps), and
        // contact and joint impulses are summed over the n calls into the step's snapshot.
        let n = self.substeps().max(1);
        // A spinning ball's contact is followed exactly only at a call's ends: its step is
        // split into as few calls as keep the turn's residual within the contact's sag
        // (sim/contact_points.rs, `spin_calls`); a smooth ball's chord contact on an arc into
        // one-substep calls (sim/arc_split.rs).
        let first_step = self.snapshot.step == 0;
        let planned = self.settings.substepping == Substepping::Split;
        let round = self.round_colliders.refresh(&self.world);
        let spin_calls = contact_points::spin_calls(
            &self.world,
            &round.balls,
            contact_points::SpinStep {
                dt,
                substeps: n,
                last_call: self.last_call,
                first: first_step,
                strict: self.settings.reads_contact_events,
            },
            self.settings.spin_split,
        );
        let spin = spin_calls > 1;
        let split_for_arc = n > 1
            && !planned
            && !spin
            && arc_split::smooth_ball_rides_arc(&self.world, round, first_step);
        // Joint impulses reconstructed from one call: split where a blow can fall, and where
        // the step's one call meets an impact (sim/joint_sums.rs). A step a spinning ball splits
        // is split whole there: calls of several substeps would each keep only their last
        // substep's joint impulses, which neither sums them nor reconstructs them.
        let reconstructs = n > 1 && self.settings.split_at_blows && !planned && !spin;
        let mut split_for_blow = reconstructs && !split_for_arc && self.blow_may_fall(dt);
        let mut first_plan = None;
        if reconstructs && !split_for_arc && !split_for_blow && self.settings.impact_cuts {
            let plan = self.plan_call(dt, true);
            split_for_blow = plan.cut.is_some();
            first_plan = Some(plan).filter(|_| !split_for_blow);
        }
        let whole =
            planned || split_for_arc || split_for_blow || (spin && self.settings.split_at_blows);
        let calls = if whole { n } else { spin_calls };
        let pending = std::iter::repeat_n((dt / calls as f64, n / calls), calls).collect();
        CallQueue {
            pending,
            n,
            split: (calls == n && n > 1) || planned,
            split_for_spin: spin && !planned,
            split_for_arc,
            split_for_blow,
            first_plan,
            planned: calls,
            cuts: 0,
            blow: !self.snapshot.impulses.is_empty(),
            impact_call_next: false,
            merged: calls > 1 || planned,
            first: true,
            elapsed: 0.0,
        }
    }

    /// The coming call, cut first where an impact falls in it (when impact cuts are on and the
    /// step has cuts left); `None` once the step's calls are made.
    pub(super) fn next_call(&self, calls: &mut CallQueue) -> Option<Call> {
        let (mut h, sub) = calls.pending.pop_front()?;
        let mut prediction = None;
        let impact_call = std::mem::take(&mut calls.impact_call_next);
        let mut impact_now = impact_call || (calls.first && calls.blow);
        if self.settings.impact_cuts && calls.cuts < MAX_CUTS {
            let plan = match calls.first_plan.take() {
                Some(plan) => plan,
                None => self.plan_call(h, !impact_call),
            };
            prediction = Some(plan.prediction);
            if let Some(t) = plan.cut {
                let (made, makes_contact) = calls.cut(h, sub, t);
                h = made;
                impact_now |= makes_contact;
            }
        }
        let call = Call {
            h,
            sub,
            prediction,
            impact_now,
            first: calls.first,
            start: calls.elapsed,
        };
        calls.first = false;
        calls.elapsed += h;
        Some(call)
    }
}
