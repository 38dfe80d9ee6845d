//! Stage 4: checks (theory against engine, every step). The exercise's questions are their own
//! stage, [`crate::questions`].
//!
//! A check is a [`Probe`]: it sees every snapshot in order, computes the
//! textbook value ("theory") and the engine's value ("engine") independently,
//! and keeps the worst and final errors. `probe_for` maps a level's
//! [`CheckDef`] to a probe.

mod kinds;

use crate::analysis::frame::{FrameAnalysis, FramePass};
use crate::level::{CheckDef, CheckKind, Level};
use crate::snapshot::Snapshot;
use serde::{Deserialize, Serialize};

/// One check's result (the JSON report's `checks[]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CheckResult {
    pub kind: String,
    /// What the check is about (body, joint, point), human readable.
    pub subject: String,
    /// Theory value at the end of the run (or at the event the check is about).
    pub theory: f64,
    /// Engine value at the same moment.
    pub engine: f64,
    pub max_abs_error: f64,
    pub max_rel_error: f64,
    pub final_abs_error: f64,
    pub final_rel_error: f64,
    /// Relative tolerance on `max_rel_error`.
    pub tolerance: f64,
    pub passed: bool,
    /// Number of steps the check compared.
    pub samples: u64,
    /// The scale errors are divided by (documented per kind).
    pub scale: f64,
    /// Why the tolerance is what it is (from the level).
    pub why: String,
    /// What the check measured beyond pass/fail (a known gap, a drift rate).
    pub note: String,
}

impl CheckResult {
    /// What never passes (docs/analysis-and-checks.md): a result that compared no sample, or
    /// whose theory, engine value, errors or scale are not finite, fails, and its note says which
    /// value and why. A value that is not finite reads as null in the JSON report: the note is
    /// what tells that null from a number, so a null never stands for a pass.
    pub fn never_absurd(mut self) -> Self {
        let mut why = Vec::new();
        if self.samples == 0 {
            why.push(
                "it compared nothing (no sample: its body never appeared in the run or its window, \
                 or the event it is about never happened)"
                    .to_string(),
            );
        }
        let values = [
            ("theory", self.theory),
            ("engine", self.engine),
            ("max_abs_error", self.max_abs_error),
            ("max_rel_error", self.max_rel_error),
            ("final_abs_error", self.final_abs_error),
            ("final_rel_error", self.final_rel_error),
            ("scale", self.scale),
        ];
        let bad: Vec<String> = values
            .iter()
            .filter(|(_, v)| !v.is_finite())
            .map(|(n, v)| format!("{n} = {v}"))
            .collect();
        if !bad.is_empty() {
            why.push(format!(
                "not finite: {} (null in the JSON): a value past f64's range (an overflow, or \
                 a division by a step too small to divide by) is no comparison",
                bad.join(", ")
            ));
        }
        if !why.is_empty() {
            self.passed = false;
            let fails = format!("FAILS: {}", why.join("; "));
            self.note = if self.note.is_empty() {
                fails
            } else {
                format!("{fails}; {}", self.note)
            };
        }
        self
    }
}

/// Observes every snapshot of a run.
pub trait Probe {
    /// Called with the initial snapshot (step 0) and then after every step.
    fn observe(&mut self, snap: &Snapshot);
    /// Whether the probe reads the shared per-step [`Frame`](crate::analysis::frame::Frame)
    /// (then [`Probe::observe_frame`] is called instead of [`Probe::observe`]).
    fn wants_frame(&self) -> bool {
        false
    }
    /// [`Probe::observe`] with the step's frame, computed once for all the probes of a run.
    fn observe_frame(&mut self, snap: &Snapshot, _frame: &FrameAnalysis) {
        self.observe(snap)
    }
    /// Whether it reads the snapshots' contacts: a run none of whose readers does leaves them
    /// unread (`sim::Simulation::set_contact_readings`). True unless the probe knows better.
    fn reads_contacts(&self) -> bool {
        true
    }
    /// With [`Probe::wants_frame`]: how much of the shared pass it reads (the step's states and
    /// links, the frame's sums, or the work too). Everything unless the probe knows better.
    fn frame_pass(&self) -> FramePass {
        FramePass::Work
    }
    fn finish(self: Box<Self>) -> CheckResult;
}

/// A level's checks over one run: the probes, and the one per-step analysis pass
/// ([`FrameAnalysis`]) that those reading the free-body diagram share. Only built when a probe
/// needs it, so a level pays for the analysis its checks ask for. The probes of a per-body kind
/// run together, one loop over the kind's probes a step (`kinds::batch`).
pub struct CheckSet {
    groups: Vec<Box<dyn kinds::Group>>,
    /// The level's checks: as many results.
    count: usize,
    frame: Option<FrameAnalysis>,
    /// The most of the pass a probe reads: the pass computes that much.
    pass: FramePass,
}

impl CheckSet {
    pub fn new(level: &Level) -> Self {
        let groups = kinds::groups_for(level);
        let frame = groups
            .iter()
            .any(|g| g.wants_frame())
            .then(FrameAnalysis::new);
        let pass = groups
            .iter()
            .filter(|g| g.wants_frame())
            .map(|g| g.frame_pass())
            .max()
            .unwrap_or(FramePass::Motion);
        CheckSet {
            groups,
            count: level.checks.len(),
            frame,
            pass,
        }
    }

    /// Feeds a snapshot (the initial one first, then one per step, in order) to every check.
    pub fn observe(&mut self, snap: &Snapshot) {
        if let Some(fa) = self.frame.as_mut() {
            fa.observe_as(snap, self.pass);
        }
        for g in self.groups.iter_mut() {
            g.observe(snap, self.frame.as_ref());
        }
    }

    /// Whether a probe of the set reads the snapshots' contacts ([`Probe::reads_contacts`]).
    pub fn reads_contacts(&self) -> bool {
        self.groups.iter().any(|g| g.reads_contacts())
    }

    /// The results, in the level's order.
    pub fn finish(self) -> Vec<CheckResult> {
        let mut results = vec![None; self.count];
        for g in self.groups {
            g.finish(&mut results);
        }
        results
            .into_iter()
            .map(|r| r.expect("every check has its probe"))
            .collect()
    }
}

/// Error bookkeeping shared by probes: absolute error against a scale.
#[derive(Debug, Clone, Default)]
pub struct ErrorTrack {
    pub max_abs: f64,
    pub last_abs: f64,
    pub last_theory: f64,
    pub last_engine: f64,
    pub samples: u64,
    /// Largest |theory| seen, used as the default scale.
    pub max_theory: f64,
}

impl ErrorTrack {
    pub fn add(&mut self, theory: f64, engine: f64) {
        let e = (theory - engine).abs();
        let e = if e.is_nan() { f64::INFINITY } else { e };
        self.max_abs = self.max_abs.max(e);
        self.last_abs = e;
        self.last_theory = theory;
        self.last_engine = engine;
        self.max_theory = self.max_theory.max(theory.abs());
        self.samples += 1;
    }

    /// The result, with relative errors taken against `scale` (a characteristic size of the quantity,
    /// so that errors near a zero crossing are not inflated).
    pub fn result(
        &self,
        def: &CheckDef,
        kind: &str,
        subject: String,
        scale: f64,
        note: String,
    ) -> CheckResult {
        let scale = if scale > 0.0 { scale } else { 1.0 };
        let max_rel = self.max_abs / scale;
        CheckResult {
            kind: kind.to_string(),
            subject,
            theory: self.last_theory,
            engine: self.last_engine,
            max_abs_error: self.max_abs,
            max_rel_error: max_rel,
            final_abs_error: self.last_abs,
            final_rel_error: self.last_abs / scale,
            tolerance: def.tolerance,
            passed: self.samples > 0 && max_rel <= def.tolerance,
            samples: self.samples,
            scale,
            why: def.why.clone(),
            note,
        }
        .never_absurd()
    }
}

/// The name a check kind has in reports.
pub fn kind_name(k: CheckKind) -> &'static str {
    k.name()
}

/// Builds the probe for a check of a level.
pub fn probe_for(level: &Level, def: &CheckDef) -> Box<dyn Probe> {
    kinds::probe_for(level, def)
}
