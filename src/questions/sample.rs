//! The moment a question is read at: the sample's snapshot with the ones around it
//! ([`Sample`]), the circumstance of the reading ([`Occasion`]), and what a reading holds
//! ([`Reading`]).
//!
//! The probe reads each snapshot one step late, so that every sample has the steps on both sides
//! of it: accelerations are central differences of the velocities and "mean over the step" forces
//! are centered on the sample (the mean of the two steps around it).

use super::impact_solution::{Blow, Impact};
use crate::snapshot::{BodyState, Snapshot};
use glam::DVec2;
use std::sync::Arc;

/// The sample and the snapshots on both sides of it.
#[derive(Clone, Copy)]
pub(super) struct Sample<'a> {
    pub prev: Option<&'a Arc<Snapshot>>,
    pub cur: &'a Arc<Snapshot>,
    pub next: Option<&'a Arc<Snapshot>>,
    /// The snapshots within the quantity's averaging window around the sample (at least cur).
    /// Shared: every question of a run reads the same snapshots (`runner::Observers`).
    pub window: &'a [Arc<Snapshot>],
}

impl Sample<'_> {
    /// Central difference of a per-snapshot value over time (one-sided at the ends).
    pub fn rate(&self, f: impl Fn(&Snapshot) -> Option<f64>) -> Option<f64> {
        let (a, b) = match (self.prev, self.next) {
            (Some(p), Some(n)) => (p, n),
            (Some(p), None) => (p, self.cur),
            (None, Some(n)) => (self.cur, n),
            (None, None) => return None,
        };
        let dt = b.time - a.time;
        if dt <= 0.0 {
            return None;
        }
        Some((f(b)? - f(a)?) / dt)
    }

    /// The snapshots whose steps straddle the sample: this step and the next one.
    pub fn steps(&self) -> impl Iterator<Item = &Snapshot> {
        std::iter::once(self.cur)
            .chain(self.next)
            .map(|s| &**s)
            .filter(|s| !s.is_initial())
    }

    /// The mean of a per-step impulse divided by dt (a force) over the steps of the window, or,
    /// without a window, over the two steps around the sample.
    pub fn windowed(&self, f: impl Fn(&Snapshot) -> Option<DVec2>) -> Option<DVec2> {
        if self.window.len() <= 2 {
            return self.centered(f);
        }
        // The window's first snapshot only bounds the first step.
        let (mut sum, mut n) = (DVec2::ZERO, 0.0);
        for s in self.window.iter().skip(1).filter(|s| !s.is_initial()) {
            sum += f(s)? / s.dt;
            n += 1.0;
        }
        (n > 0.0).then(|| sum / n)
    }

    /// The mean over the two steps around the sample of a per-step impulse, divided by dt: a force.
    pub fn centered(&self, f: impl Fn(&Snapshot) -> Option<DVec2>) -> Option<DVec2> {
        let (mut sum, mut n) = (DVec2::ZERO, 0.0);
        for s in self.steps() {
            sum += f(s)? / s.dt;
            n += 1.0;
        }
        (n > 0.0).then(|| sum / n)
    }
}

/// A quantity read at one sample: the engine's value and the textbook analysis, if any.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Reading {
    /// Time of the reading, s.
    pub t: f64,
    pub engine: f64,
    pub analysis: Option<f64>,
}

impl Reading {
    /// No reading: the question's event never came.
    pub const MISSING: Reading = Reading {
        t: f64::NAN,
        engine: f64::NAN,
        analysis: None,
    };

    /// The reading a fraction `f` of the way from `a` to `b` (a crossing between two samples).
    pub fn lerp(a: Reading, b: Reading, f: f64) -> Reading {
        Reading {
            t: a.t + (b.t - a.t) * f,
            engine: a.engine + (b.engine - a.engine) * f,
            analysis: match (a.analysis, b.analysis) {
                (Some(x), Some(y)) => Some(x + (y - x) * f),
                _ => None,
            },
        }
    }
}

/// The circumstance of a reading: velocity analyses read the impulse-momentum solution of the
/// impact or blow the question is about.
#[derive(Clone, Copy)]
pub(super) enum Occasion<'a> {
    Plain,
    PreImpact(&'a Impact),
    PostImpact(&'a Impact),
    AfterBlow(&'a Blow),
}

impl Occasion<'_> {
    /// The state the impact or blow solution gives body i at the sample `s` (None when plain).
    pub fn solved_state(&self, i: usize, s: &Snapshot) -> Option<BodyState> {
        match self {
            Occasion::Plain => None,
            Occasion::PreImpact(imp) => Some(imp.pre[i].clone()),
            // The textbook's "just after the impact": the solution at the touching instant.
            Occasion::PostImpact(imp) => Some(imp.post[i].clone()),
            Occasion::AfterBlow(b) => Some(b.post_at(i, s.time, s.gravity)),
        }
    }
}
