//! A challenge's goal judged on the run (issue 42; the format in level/format/challenge.rs):
//! where a body ends, whether it stays in a region or reaches a point, a quantity read as a
//! question reads it, or a pin's share of a blow. Each gives success or a measured miss, and
//! never success on what it could not measure: a reading that is not finite, or a body that
//! never moved.

use super::level_facts::LevelFacts;
use super::probe::QuestionProbe;
use crate::level::{blow_size, ChallengeDef, Goal, Level, V2};
use crate::snapshot::Snapshot;
use glam::DVec2;
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// A body whose mass center has travelled less than this over the run never moved, m: a goal
/// on it is not met, whatever region it sits in (no level's scene is smaller than a millimetre).
pub const STILL: f64 = 1e-6;

/// A challenge's result (the JSON report's `challenge`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ChallengeResult {
    /// The control's name (its `--answer` id), the value the run was made with and its unit,
    /// and its worked (closed-form) value in that unit.
    pub control: String,
    pub value: f64,
    pub unit: String,
    pub worked: f64,
    /// Whether `value` is the student's (`--answer`), else the worked value's run.
    pub student: bool,
    /// The goal in words.
    pub goal: String,
    pub success: bool,
    /// How far the run missed: m for a position goal (0 when met); the reading less the goal's
    /// value, in the quantity's unit, for `Reads`; the pin's impulse as a fraction of the blow's
    /// for `PinFeelsNoBlow`. Null when nothing could be measured.
    pub miss: f64,
    pub miss_unit: String,
    /// What was measured: the goal's reading (`Reads`, `PinFeelsNoBlow`), else the body's
    /// distance to the region or the point.
    pub measured: f64,
    /// The run's time of the measurement, s.
    pub time: f64,
    /// Where the miss is drawn: the body's G at the measurement, and the nearest point of the
    /// region (or the goal's point) it missed; None for a reading.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at: Option<V2>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub target: Option<V2>,
    /// Why nothing could be measured, or what else the reading says.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub note: String,
    /// Which way a missed run went, where the goal's kind has a way ([`miss_way`]): "past the
    /// goal", "short of the goal", "above the point", "below the goal's value"; empty where it
    /// has none (a body that left a region, a pin's share of a blow) or the run was met. The
    /// window's verdict; not in the JSON report.
    #[serde(skip)]
    pub way: String,
}

impl ChallengeResult {
    /// The verdict in words: "success", or "missed by 0.12 m" with which way the run went and
    /// which way the control was off ("missed by 0.085 m, passed above the point: v0 too high").
    pub fn verdict(&self) -> String {
        if self.success {
            "success".into()
        } else if self.miss.is_finite() {
            let unit = if self.miss_unit.is_empty() {
                String::new()
            } else {
                format!(" {}", self.miss_unit)
            };
            let way = if self.way.is_empty() {
                String::new()
            } else {
                format!(", {}", self.way)
            };
            let control = self
                .control_way()
                .map_or(String::new(), |w| format!(": {} too {w}", self.control));
            format!(
                "missed by {}{unit}{way}{control}",
                crate::level::params::textbook(self.miss.abs(), 0)
            )
        } else {
            "missed: nothing could be measured".into()
        }
    }

    /// Which way the control was off, "high" or "low": the worked value meets the goal (`check`
    /// of the level alone runs it and must pass), so a run that missed with a value above it
    /// had it too high. None where the value is the worked one or either is not a number.
    pub fn control_way(&self) -> Option<&'static str> {
        if !(self.value.is_finite() && self.worked.is_finite()) || self.value == self.worked {
            return None;
        }
        Some(if self.value > self.worked {
            "high"
        } else {
            "low"
        })
    }
}

/// One challenge's goal watching a run.
pub struct ChallengeProbe {
    def: ChallengeDef,
    /// A goal read as a question (`Reads`, `PinFeelsNoBlow`), and the blow's size for the latter.
    question: Option<QuestionProbe>,
    blow: f64,
    /// A position goal's body: its index in the snapshots, its path so far and last G.
    body: Option<usize>,
    path: f64,
    last: Option<(f64, DVec2)>,
    /// The goal's measure so far: (distance, time, G there).
    best: Option<(f64, f64, DVec2)>,
    /// A position goal's body's G at the first snapshot (which way it went, for "past").
    start: Option<DVec2>,
}

impl ChallengeProbe {
    pub fn new(level: &Level, facts: Arc<LevelFacts>, def: &ChallengeDef) -> Self {
        let question = def
            .goal
            .as_question(level)
            .map(|q| QuestionProbe::sharing(facts, &q));
        let blow = match &def.goal {
            Goal::PinFeelsNoBlow { blow, .. } => blow_size(level, blow),
            _ => f64::NAN,
        };
        ChallengeProbe {
            def: def.clone(),
            question,
            blow,
            body: None,
            path: 0.0,
            last: None,
            best: None,
            start: None,
        }
    }

    /// Whether the goal still reads snapshots.
    pub fn is_done(&self) -> bool {
        self.question.as_ref().is_some_and(QuestionProbe::is_done)
    }

    /// Observes a snapshot shared with the run's questions (the initial one in f64).
    pub fn observe_shared(&mut self, s: &Arc<Snapshot>) {
        if let Some(q) = self.question.as_mut() {
            q.observe_shared(s);
            return;
        }
        let Some(name) = self.def.goal.body() else {
            return;
        };
        if self.body.is_none() {
            self.body = s.bodies.iter().position(|b| b.name == name);
        }
        let Some(g) = self.body.and_then(|i| s.bodies.get(i)).map(|b| b.com) else {
            return;
        };
        self.start.get_or_insert(g);
        let from = self.last.map(|(_, p)| p);
        if let Some(p) = from {
            self.path += (g - p).length();
        }
        self.measure(s.time, from, g);
        self.last = Some((s.time, g));
    }

    /// A position goal's measure at this snapshot, kept when it is the one the goal judges by.
    fn measure(&mut self, t: f64, from: Option<DVec2>, g: DVec2) {
        let (d, at) = match &self.def.goal {
            Goal::EndsInside { region, .. } => (region.distance((g.x, g.y)), g),
            Goal::StaysInside { region, .. } => (region.distance((g.x, g.y)), g),
            Goal::Reaches { point, radius, .. } => {
                // The straight path since the last step, at its point nearest the goal's.
                let p = DVec2::new(point.0, point.1);
                let near = from.map_or(g, |a| nearest_on_segment(a, g, p));
                (((near - p).length() - radius).max(0.0), near)
            }
            _ => return,
        };
        let keep = match (&self.def.goal, self.best) {
            (_, None) | (Goal::EndsInside { .. }, _) => true,
            (Goal::StaysInside { .. }, Some((b, ..))) => d > b,
            (_, Some((b, ..))) => d < b,
        };
        if keep {
            self.best = Some((d, t, at));
        }
    }

    /// The goal's verdict, with the control's fields left for the caller (`set_control`).
    pub fn finish(self) -> ChallengeResult {
        let mut r = ChallengeResult {
            control: self.def.control.clone(),
            value: f64::NAN,
            unit: String::new(),
            worked: f64::NAN,
            student: false,
            goal: self.def.goal.describe(),
            success: false,
            miss: f64::NAN,
            miss_unit: String::new(),
            measured: f64::NAN,
            time: f64::NAN,
            at: None,
            target: None,
            note: String::new(),
            way: String::new(),
        };
        match (self.question, &self.def.goal) {
            (Some(q), Goal::PinFeelsNoBlow { tolerance, .. }) => {
                let read = q.finish(None);
                let share = read.engine.abs() / self.blow;
                r.measured = read.engine;
                r.miss = share;
                r.success = share.is_finite() && share <= *tolerance;
                r.time = read.time;
                r.note = unread(&read);
                r.miss_unit = "of the blow's impulse".into();
            }
            (Some(q), _) => {
                let read = q.finish(None);
                r.measured = read.engine;
                r.miss = read.engine - read.expected;
                r.miss_unit = read.unit.clone();
                r.success = read.engine.is_finite() && read.rel_error <= read.tolerance;
                r.time = read.time;
                r.note = unread(&read);
            }
            (None, goal) => position_verdict(&mut r, goal, self.best, self.path),
        }
        r.way = miss_way(&r, &self.def.goal, self.start);
        if r.note.is_empty() && !r.measured.is_finite() {
            r.note = format!("the reading is {}: not measured, so not met", r.measured);
        }
        r
    }
}

/// Why a goal's reading is missing (the question's note), or nothing when it was read: the
/// question's notes on its analysis do not concern a goal, judged on the engine alone.
fn unread(read: &super::result::QuestionResult) -> String {
    if read.engine.is_finite() {
        String::new()
    } else {
        read.note.clone()
    }
}

/// A position goal's verdict from its measure and the body's path.
fn position_verdict(
    r: &mut ChallengeResult,
    goal: &Goal,
    best: Option<(f64, f64, DVec2)>,
    path: f64,
) {
    r.miss_unit = "m".into();
    let Some((d, t, at)) = best else {
        r.note = format!("the body {} is not in the run", goal.body().unwrap_or("?"));
        return;
    };
    r.measured = d;
    r.miss = d;
    r.time = t;
    r.at = Some((at.x, at.y));
    r.target = Some(match goal {
        Goal::EndsInside { region, .. } | Goal::StaysInside { region, .. } => {
            region.nearest((at.x, at.y))
        }
        Goal::Reaches { point, .. } => *point,
        _ => (at.x, at.y),
    });
    // A NaN path (a body whose state was not finite) counts as not moved.
    if path.is_nan() || path <= STILL {
        r.note = format!(
            "the body never moved (its mass center travelled {path:.1e} m): a goal is met by a motion"
        );
        return;
    }
    r.success = d == 0.0;
}

/// Which way a missed run went, where the goal's kind has one: a body that ends outside a
/// region went past it or stopped short of it (the miss along its travel from where it
/// started); a body that missed a point passed above or below it (or beside it, left or right,
/// where its travel is more up or down than across), the miss taken across its travel; a reading says what it read beside the goal's value.
/// Empty for a body that left the region it had to stay in (it may leave on any side) and a
/// pin's share of a blow (a size, no sign), and for a run met or not measured.
pub fn miss_way(r: &ChallengeResult, goal: &Goal, start: Option<DVec2>) -> String {
    if r.success || !r.miss.is_finite() || r.miss == 0.0 {
        return String::new();
    }
    let off = match (r.at, r.target) {
        (Some(a), Some(t)) => Some((DVec2::new(a.0, a.1), DVec2::new(t.0, t.1))),
        _ => None,
    };
    match (goal, off) {
        (Goal::EndsInside { .. }, Some((at, target))) => {
            let travel = start.map_or(DVec2::ZERO, |s| at - s);
            if (at - target).dot(travel) > 0.0 {
                "ended past the goal".into()
            } else {
                "ended short of the goal".into()
            }
        }
        (Goal::Reaches { .. }, Some((at, target))) => {
            // The miss across the body's travel (from its start to where it came nearest): a
            // projectile coming down on a cup at 45 degrees misses as much along x as along y,
            // but across its path it plainly passed over or under the mouth.
            let d = match start.map(|s| at - s).filter(|t| t.length() > 0.0) {
                Some(t) => {
                    let n = t.perp().normalize();
                    n * n.dot(at - target)
                }
                None => at - target,
            };
            let side = if d.y.abs() >= d.x.abs() {
                if d.y > 0.0 {
                    "above"
                } else {
                    "below"
                }
            } else if d.x > 0.0 {
                "right of"
            } else {
                "left of"
            };
            format!("passed {side} the point")
        }
        (Goal::Reads { .. }, _) => {
            // The numbers, not "above" or "below": a reading is signed (an acceleration
            // downwards, a polar angle) while the challenge's words may speak of a size or of
            // another angle, so "below" read backwards to a student (the trial of 2026-12-07).
            let goal = r.measured - r.miss;
            format!(
                "read {} {} for the goal's {}",
                sig4(r.measured),
                r.miss_unit,
                sig4(goal)
            )
        }
        _ => String::new(),
    }
}

/// The point of the segment a-b nearest p.
fn nearest_on_segment(a: DVec2, b: DVec2, p: DVec2) -> DVec2 {
    let ab = b - a;
    let len2 = ab.length_squared();
    if len2 == 0.0 {
        return a;
    }
    a + ab * ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
}

impl ChallengeResult {
    /// The control's fields: its name, the value the run was made with, its unit and its
    /// worked value (both in that unit), and whether the value is the student's.
    pub fn set_control(&mut self, c: &crate::level::params::Control, value: f64, student: bool) {
        self.control = c.name.clone();
        self.value = value;
        self.unit = c.unit.clone();
        self.worked = c.worked;
        self.student = student;
    }
}

/// `x` with four significant digits, as the verdicts print their values.
fn sig4(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let digits = (3 - x.abs().log10().floor() as i32).max(0) as usize;
    format!("{x:.digits$}")
}
