//! A level's probes as a `CheckSet` runs them: the probes of a kind that reads the shared frame
//! pass together, in one loop over a `Vec` of that kind (a [`Batch`]), the others one by one,
//! each result returned in its check's place.
//!
//! 250 per-body probes each behind its own `Box<dyn Probe>` cost a virtual call, a pointer
//! chase to a heap block of its own and the kind's per-step set-up per probe per step; in a
//! batch the probes lie side by side and a kind can share work between them
//! (`kinetic_energy_ic` walks the step's contacts once for all its probes instead of each
//! looking up its body's). A probe computes exactly what it computes alone: the same
//! operations in the same order, so results do not change (benches/analysis.rs, line B).

use super::energy::kinetic_energy_ic;
use super::kinetics::newton_euler;
use super::momentum::angular_momentum_fixed_point_of;
use super::{probe_for, FrameProbe};
use crate::analysis::frame::{FrameAnalysis, FramePass};
use crate::checks::{CheckResult, Probe};
use crate::level::{CheckKind, Level};
use crate::snapshot::Snapshot;

/// How the probes of one kind run together in a [`Batch`].
pub(super) trait Together: FrameProbe + Sized {
    /// What the kind keeps for all its probes between steps (an index of them, scratch).
    type Shared: Default;

    /// Every probe's [`FrameProbe::observe_frame`] for the step, in one loop unless the kind
    /// shares work between its probes.
    fn observe_all(
        probes: &mut [Self],
        _shared: &mut Self::Shared,
        s: &Snapshot,
        fa: &FrameAnalysis,
    ) {
        for p in probes {
            p.observe_frame(s, fa);
        }
    }
}

/// One or more of a level's probes, run by a `CheckSet`.
pub(crate) trait Group {
    /// Whether it reads the shared frame pass, and how much of it.
    fn wants_frame(&self) -> bool;
    fn frame_pass(&self) -> FramePass;
    fn reads_contacts(&self) -> bool;
    /// One snapshot; `fa` is the set's frame pass when it runs one (then for a probe that
    /// wants it, already past this snapshot).
    fn observe(&mut self, snap: &Snapshot, fa: Option<&FrameAnalysis>);
    /// Its results, each into `results[k]` for the level's k-th check.
    fn finish(self: Box<Self>, results: &mut [Option<CheckResult>]);
}

/// A probe on its own.
struct Single {
    slot: usize,
    probe: Box<dyn Probe>,
}

impl Group for Single {
    fn wants_frame(&self) -> bool {
        self.probe.wants_frame()
    }
    fn frame_pass(&self) -> FramePass {
        self.probe.frame_pass()
    }
    fn reads_contacts(&self) -> bool {
        self.probe.reads_contacts()
    }
    fn observe(&mut self, snap: &Snapshot, fa: Option<&FrameAnalysis>) {
        match fa {
            Some(fa) if self.probe.wants_frame() => self.probe.observe_frame(snap, fa),
            _ => self.probe.observe(snap),
        }
    }
    fn finish(self: Box<Self>, results: &mut [Option<CheckResult>]) {
        results[self.slot] = Some(self.probe.finish());
    }
}

/// The probes of one kind, side by side, with the level's check index of each.
pub(super) struct Batch<P: Together> {
    slots: Vec<usize>,
    probes: Vec<P>,
    shared: P::Shared,
}

impl<P: Together> Default for Batch<P> {
    fn default() -> Self {
        Batch {
            slots: Vec::new(),
            probes: Vec::new(),
            shared: P::Shared::default(),
        }
    }
}

impl<P: Together> Batch<P> {
    fn push(&mut self, slot: usize, probe: P) {
        self.slots.push(slot);
        self.probes.push(probe);
    }
}

impl<P: Together> Group for Batch<P> {
    fn wants_frame(&self) -> bool {
        true
    }
    fn frame_pass(&self) -> FramePass {
        let passes = self.probes.iter().map(FrameProbe::frame_pass);
        passes.max().unwrap_or(FramePass::Motion)
    }
    /// As a [`FrameProbe`] on its own (`Framed`): it may.
    fn reads_contacts(&self) -> bool {
        true
    }
    fn observe(&mut self, snap: &Snapshot, fa: Option<&FrameAnalysis>) {
        let fa = fa.expect("a batch reads the frame: the set runs the pass");
        P::observe_all(&mut self.probes, &mut self.shared, snap, fa);
    }
    fn finish(self: Box<Self>, results: &mut [Option<CheckResult>]) {
        for (slot, p) in self.slots.into_iter().zip(self.probes) {
            results[slot] = Some(p.finish());
        }
    }
}

/// The level's checks as groups: `newton_euler`, `kinetic_energy_ic` and
/// `angular_momentum_fixed_point` probes in a batch per kind (the per-body checks a level puts
/// on many bodies), every other probe, and a check its kind refuses, on its own.
pub(crate) fn groups_for(level: &Level) -> Vec<Box<dyn Group>> {
    let mut groups: Vec<Box<dyn Group>> = Vec::new();
    let mut newton = Batch::default();
    let mut energy = Batch::default();
    let mut momentum = Batch::default();
    for (slot, def) in level.checks.iter().enumerate() {
        let alone = match def.kind {
            CheckKind::NewtonEuler => newton_euler(level, def).map(|p| newton.push(slot, p)),
            CheckKind::KineticEnergyIc => {
                kinetic_energy_ic(level, def).map(|p| energy.push(slot, p))
            }
            CheckKind::AngularMomentumFixedPoint => {
                angular_momentum_fixed_point_of(level, def).map(|p| momentum.push(slot, p))
            }
            _ => Err(probe_for(level, def)),
        };
        if let Err(probe) = alone {
            groups.push(Box::new(Single { slot, probe }));
        }
    }
    push_batch(&mut groups, newton);
    push_batch(&mut groups, energy);
    push_batch(&mut groups, momentum);
    groups
}

fn push_batch<P: Together + 'static>(groups: &mut Vec<Box<dyn Group>>, batch: Batch<P>) {
    if !batch.probes.is_empty() {
        groups.push(Box::new(batch));
    }
}
