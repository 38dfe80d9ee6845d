//! summary.md's "Which engine is cheaper for which class of scene": computed from the rows of a
//! sweep over two engines (`--engine rapier,box2d`), never written by hand.
//!
//! Per level run on both engines, the engine that meets the level's tolerance more cheaply: the
//! cost of each engine's cheapest declared-effects setting meeting every graded check and
//! question (`summary::cheapest_meeting`), or the only engine meeting it at any swept setting.
//! Per class of scene (the study's classes, `plan::class`): how many levels each engine wins, the
//! median cost ratio where both meet, and, for every level run on both (graded or not), the
//! median cost ratio at the level's own settings. Levels Box2D refuses are counted per class.

use super::summary::{baseline, cheapest_meeting, median, num};
use super::LevelStudy;
use crate::level::PhysicsEngine;
use std::fmt::Write as _;

/// The classes in the order the table lists them.
pub const CLASSES: [&str; 4] = ["contact", "joint", "contact+joint", "contact-free"];

/// Who meets a level's tolerance more cheaply.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// Both meet it; the first engine's cheapest setting costs less (ties go to neither).
    FirstCheaper,
    SecondCheaper,
    Tie,
    OnlyFirst,
    OnlySecond,
    Neither,
    /// The level grades nothing (no tolerance to meet).
    Ungraded,
}

/// One class's count over the levels run on both engines.
#[derive(Debug, Clone, Default)]
pub struct ClassTally {
    pub levels: usize,
    pub refused: usize,
    pub first_cheaper: usize,
    pub second_cheaper: usize,
    pub ties: usize,
    pub only_first: usize,
    pub only_second: usize,
    pub neither: usize,
    pub ungraded: usize,
    /// second / first cost of the cheapest setting meeting the tolerance, where both meet.
    pub meet_ratios: Vec<f64>,
    /// second / first cost at the level's own settings.
    pub own_ratios: Vec<f64>,
}

impl ClassTally {
    /// The levels the first (second) engine wins: cheaper where both meet, or the only one.
    pub fn wins(&self) -> (usize, usize) {
        (
            self.first_cheaper + self.only_first,
            self.second_cheaper + self.only_second,
        )
    }
}

/// Who meets the level's tolerance more cheaply, from its two studies' rows.
pub fn outcome(a: &LevelStudy, b: &LevelStudy) -> Outcome {
    let graded = |st: &LevelStudy| st.rows.iter().any(|r| r.meets_tolerance.is_some());
    if !graded(a) && !graded(b) {
        return Outcome::Ungraded;
    }
    let cost = |st: &LevelStudy| cheapest_meeting(st).and_then(|r| r.cost_us_per_sim_s);
    match (cost(a), cost(b)) {
        (Some(x), Some(y)) if x < y => Outcome::FirstCheaper,
        (Some(x), Some(y)) if y < x => Outcome::SecondCheaper,
        (Some(_), Some(_)) => Outcome::Tie,
        (Some(_), None) => Outcome::OnlyFirst,
        (None, Some(_)) => Outcome::OnlySecond,
        (None, None) => Outcome::Neither,
    }
}

/// The engines of the study in the order they first appear (the plan's order).
fn engines(studies: &[LevelStudy]) -> Vec<PhysicsEngine> {
    let mut v = Vec::new();
    for st in studies {
        if !v.contains(&st.engine) {
            v.push(st.engine);
        }
    }
    v
}

/// Per class: the tally of the levels run on both `first` and `second`, and those `second`
/// refused (a skipped entry "refused by `<second>`" of a level `first` ran).
pub fn tally(
    studies: &[LevelStudy],
    skipped: &[(String, String)],
    first: PhysicsEngine,
    second: PhysicsEngine,
) -> Vec<(&'static str, ClassTally)> {
    let refused_by = format!("refused by {}", second.name());
    CLASSES
        .iter()
        .map(|&class| {
            let mut t = ClassTally::default();
            for a in studies
                .iter()
                .filter(|st| st.engine == first && st.class == class)
            {
                let Some(b) = studies
                    .iter()
                    .find(|st| st.engine == second && st.name == a.name)
                else {
                    if skipped
                        .iter()
                        .any(|(n, why)| *n == a.name && why.starts_with(&refused_by))
                    {
                        t.refused += 1;
                    }
                    continue;
                };
                t.levels += 1;
                match outcome(a, b) {
                    Outcome::FirstCheaper => t.first_cheaper += 1,
                    Outcome::SecondCheaper => t.second_cheaper += 1,
                    Outcome::Tie => t.ties += 1,
                    Outcome::OnlyFirst => t.only_first += 1,
                    Outcome::OnlySecond => t.only_second += 1,
                    Outcome::Neither => t.neither += 1,
                    Outcome::Ungraded => t.ungraded += 1,
                }
                let cost = |st: &LevelStudy| cheapest_meeting(st).and_then(|r| r.cost_us_per_sim_s);
                if let (Some(x), Some(y)) = (cost(a), cost(b)) {
                    t.meet_ratios.push(y / x);
                }
                let own = |st: &LevelStudy| baseline(st).and_then(|r| r.cost_us_per_sim_s);
                if let (Some(x), Some(y)) = (own(a), own(b)) {
                    t.own_ratios.push(y / x);
                }
            }
            (class, t)
        })
        .filter(|(_, t)| t.levels + t.refused > 0)
        .collect()
}

/// The class's verdict: the engine winning more levels; without a graded level decided, the
/// engine cheaper at the levels' own settings (median ratio); else "no verdict".
pub fn verdict(t: &ClassTally, first: PhysicsEngine, second: PhysicsEngine) -> String {
    let (a, b) = t.wins();
    let decided = a + b;
    if a > b {
        format!("**{}** ({a} of {decided} levels decided)", first.name())
    } else if b > a {
        format!("**{}** ({b} of {decided} levels decided)", second.name())
    } else if decided > 0 {
        format!("even ({a} levels each)")
    } else {
        match median(t.own_ratios.clone()) {
            Some(r) if r < 1.0 => format!(
                "**{}** at the levels' own settings (cost x{r:.2}; no tolerance decides)",
                second.name()
            ),
            Some(r) if r > 1.0 => format!(
                "**{}** at the levels' own settings ({} costs x{r:.2}; no tolerance decides)",
                first.name(),
                second.name()
            ),
            _ => "no verdict (nothing decided)".into(),
        }
    }
}

/// The section, when the study ran two engines.
pub fn section(s: &mut String, studies: &[LevelStudy], skipped: &[(String, String)]) {
    let e = engines(studies);
    let (Some(&first), Some(&second)) = (e.first(), e.get(1)) else {
        return;
    };
    let (a, b) = (first.name(), second.name());
    let _ = writeln!(s, "\n## Which engine is cheaper for which class of scene\n");
    let _ = writeln!(
        s,
        "Computed from the rows above. Per level run on both engines: the cost of each engine's cheapest \
         declared-effects setting that meets every graded check and question of the level; the engine \
         that meets it cheaper wins the level, as does the only engine that meets it at any swept setting. \
         {b} runs in f32 only and has no PGS-iterations knob: its sweep is dt, substeps and effects. \
         Cost ratios are {b} / {a} (below 1: {b} is cheaper), medians over the class.\n"
    );
    let _ = writeln!(
        s,
        "| class | levels on both | refused by {b} | both meet: {a} cheaper | both meet: {b} cheaper | only {a} meets | only {b} meets | neither meets | grades nothing | cost {b}/{a}, cheapest meeting | cost {b}/{a}, level's settings | cheaper engine |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|---|---|");
    let rows = tally(studies, skipped, first, second);
    for (class, t) in &rows {
        let _ = writeln!(
            s,
            "| {class} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            t.levels,
            t.refused,
            t.first_cheaper,
            t.second_cheaper,
            t.only_first,
            t.only_second,
            t.neither,
            t.ungraded,
            num(median(t.meet_ratios.clone())),
            num(median(t.own_ratios.clone())),
            verdict(t, first, second),
        );
    }
    let _ = writeln!(s);
    for (class, t) in &rows {
        let (wa, wb) = t.wins();
        let _ = writeln!(
            s,
            "- {class} scenes: {}; {a} wins {wa}, {b} wins {wb} of {} levels run on both ({} refused by {b}).",
            verdict(t, first, second),
            t.levels,
            t.refused
        );
    }
    let _ = writeln!(s);
}
