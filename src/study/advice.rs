//! Advice for a level that fails at its settings: the cheapest solver settings, in a bounded
//! search, at which every check and question passes, or that none within the bound does.
//!
//! A failing level is rerun at finer settings: the step divided by 1, 2, 4, 8 or 16, the
//! substeps multiplied by the same, and the engine in f64 where the level ran in f32. Each
//! candidate's cost is estimated against the level's own run (steps x substeps, f64 at
//! [`F64_COST`] times f32) and candidates are tried cheapest first, up to [`MAX_COST_RATIO`] times
//! the level's own cost and [`SEARCH_BUDGET`] times it over the whole search, and within
//! [`SEARCH_SECONDS`] of wall time over the whole search: a candidate is not started when the
//! time spent plus its predicted time (the failing run's measured wall time times its cost
//! ratio, or `runner::budget`'s estimate when the failing run was not timed) would pass it. So
//! a level of a second or more (a loop at 1/4800 s) is searched only as far as a second allows,
//! and the advice says that the time ran out, not that no setting passes. The first that
//! passes is the advice; it is a real run's verdict, so rerunning the level with the advised
//! settings passes (tests/suite/study/advice.rs). When none within 32x passes, the failure does not
//! go away with accuracy within the bound: an engine limit (docs/known-gaps.md) or a wrong
//! expected answer.

use crate::clock::Instant;
use crate::level::{Precision, Scene};
use crate::report::{Advice, AdvisedSettings, LevelReport};
use crate::runner::{self, Estimate, Mode};
use crate::sim::{Options, Settings};
use std::collections::HashMap;

/// The costliest candidate tried, as a multiple of the level's own run.
pub const MAX_COST_RATIO: f64 = 32.0;

/// The whole search's cost, as a multiple of the level's own run: at most this much is spent
/// on a level that no candidate makes pass. Every candidate up to [`MAX_COST_RATIO`] together
/// costs 424x (256x in f32, 168x in f64), so a level none passes is searched through.
pub const SEARCH_BUDGET: f64 = 512.0;

/// The whole search's wall time, s: no candidate is started that would end past it (predicted
/// from the failing run's wall time times the candidate's cost ratio). Measured 2026-11-26 on
/// 2 cores: `rigidlab check tests/newuser/*/*.ron` (113 levels, 29 failing) took 4 min 59 s with
/// the search bounded only by cost ratios and the 600 s run budget (n7_01's loop at 1/4800 s,
/// 2.2 s a run, and n7_05's puck in a ring, 1.9 s, searched for minutes each); see
/// docs/teacher.md for the time with this bound.
pub const SEARCH_SECONDS: f64 = 2.0;

/// The wall time of an f64 run against the same run in f32 (rapier2d-f64 against rapier2d:
/// 1.2x to 1.3x over the library, docs/accuracy.md).
pub const F64_COST: f64 = 1.25;

/// One candidate: the step divided by `dt_div`, substeps multiplied by `sub_mul`, precision.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Candidate {
    dt_div: u32,
    sub_mul: u32,
    precision: Precision,
    cost_ratio: f64,
}

/// The candidates, cheapest first (ties: more substeps before a smaller step, which keeps the
/// level's sampling instants; f32 before f64).
fn candidates(own: Precision) -> Vec<Candidate> {
    let precisions: &[Precision] = match own {
        Precision::F32 => &[Precision::F32, Precision::F64],
        Precision::F64 => &[Precision::F64],
    };
    let mut out = Vec::new();
    for &precision in precisions {
        for dt_div in [1u32, 2, 4, 8, 16] {
            for sub_mul in [1u32, 2, 4, 8, 16] {
                let factor = if precision == own { 1.0 } else { F64_COST };
                let cost_ratio = f64::from(dt_div * sub_mul) * factor;
                if (dt_div, sub_mul, precision) != (1, 1, own) && cost_ratio <= MAX_COST_RATIO {
                    out.push(Candidate {
                        dt_div,
                        sub_mul,
                        precision,
                        cost_ratio,
                    });
                }
            }
        }
    }
    out.sort_by(|a, b| {
        a.cost_ratio
            .total_cmp(&b.cost_ratio)
            .then(a.dt_div.cmp(&b.dt_div))
            .then((a.precision != own).cmp(&(b.precision != own)))
    });
    out
}

/// Whether the engine's run failed: a check or a question (not a student's answer), or the run
/// stopped. A level failed only by a student's wrong answer needs no advice.
pub fn engine_failed(r: &LevelReport) -> bool {
    r.error.is_some() || r.checks.iter().any(|c| !c.passed) || r.questions.iter().any(|q| !q.passed)
}

/// Why no setting can make the level pass, when every failure of its report is a check that
/// cannot judge the scene (its formula's assumption broken: `checks::kinds::cannot_judge`,
/// whose note starts "cannot judge"): finer settings cannot change that, so there is nothing to
/// search. Found by the tenth new user (tests/newuser/impacts/n10_11b: a `center_of_percussion` check
/// on a bar that rests on a peg was searched through to 32x and then blamed on the engine).
pub fn beyond_settings(r: &LevelReport) -> Option<String> {
    if r.error.is_some() || r.questions.iter().any(|q| !q.passed) {
        return None;
    }
    let failing: Vec<_> = r.checks.iter().filter(|c| !c.passed).collect();
    let judged_none = !failing.is_empty()
        && failing
            .iter()
            .all(|c| c.samples == 0 && c.note.starts_with("cannot judge"));
    judged_none.then(|| {
        let which: Vec<_> = failing
            .iter()
            .map(|c| format!("{} on {} ({})", c.kind, c.subject, c.note))
            .collect();
        format!(
            "no setting changes this: {} the scene; remove the check or change the scene",
            if which.len() == 1 {
                format!("the check {} cannot judge", which[0])
            } else {
                format!("the checks {} cannot judge", which.join("; "))
            }
        )
    })
}

/// The advice for a level whose run failed at the options `opts` (the command line's
/// overrides of the level's settings) in `failed_wall_ms` (0 when it stopped early or was not
/// timed: candidates' times are then `runner::budget`'s estimates).
pub fn advise(scene: &Scene, opts: &Options, failed_wall_ms: f64) -> Advice {
    advise_within(scene, opts, failed_wall_ms, SEARCH_SECONDS)
}

/// [`advise`] with the search's wall time `seconds` instead of [`SEARCH_SECONDS`]
/// (`rigidlab check --advice-seconds S`).
pub fn advise_within(scene: &Scene, opts: &Options, failed_wall_ms: f64, seconds: f64) -> Advice {
    let started = Instant::now();
    let precision = opts.precision.unwrap_or(scene.level.world.precision);
    let own = Settings::resolve(&scene.level, opts, precision);
    let mut spent = 0.0;
    let mut searched_to = 0.0;
    // The first candidate the time bound left untried, with its predicted seconds.
    let mut cut: Option<(Candidate, f64)> = None;
    let none = HashMap::new();
    for c in candidates(own.precision) {
        if spent + c.cost_ratio > SEARCH_BUDGET {
            break;
        }
        let options = candidate_options(&own, opts, &c);
        // A candidate past the run budget is not tried (runner::budget).
        let estimate = Estimate::of(&scene.level, &options, Mode::Check, None);
        if !estimate.fits() {
            break;
        }
        // Nor one that would end past the search's wall time: the candidates come cheapest
        // first, so none after it would fit either.
        let predicted = if failed_wall_ms > 0.0 {
            failed_wall_ms / 1000.0 * c.cost_ratio
        } else {
            estimate.seconds
        };
        if started.elapsed().as_secs_f64() + predicted > seconds {
            cut = Some((c, predicted));
            break;
        }
        spent += c.cost_ratio;
        let Ok(r) = runner::run_graded(scene, &options, &none, |_| {}) else {
            searched_to = c.cost_ratio;
            continue;
        };
        if !engine_failed(&r) {
            return Advice::Settings {
                settings: AdvisedSettings {
                    dt: own.dt / f64::from(c.dt_div),
                    substeps: own.substeps * c.sub_mul as usize,
                    precision: c.precision,
                },
                cost_ratio: c.cost_ratio,
                wall_ratio: (failed_wall_ms > 0.0).then(|| r.wall_ms / failed_wall_ms),
            };
        }
        searched_to = c.cost_ratio;
    }
    let f64_too = if own.precision == Precision::F32 {
        " or f64"
    } else {
        ""
    };
    match cut {
        // The time ran out before the cost bound: say so, and what to try by hand.
        Some((c, predicted)) => Advice::NoneWithin {
            none_within: searched_to,
            why: format!(
                "none passes within the search's {seconds} s ({}): the next, \
                 --dt {} --substeps {} --precision {} ({}x the level's cost), would take about \
                 {predicted:.1} s; run it yourself (or give `--advice-seconds`), the search \
                 stopped on time, not on a limit",
                if searched_to > 0.0 {
                    format!("tried up to {searched_to}x the level's cost")
                } else {
                    "no finer setting fits in it".to_string()
                },
                own.dt / f64::from(c.dt_div),
                own.substeps * c.sub_mul as usize,
                match c.precision {
                    Precision::F32 => "f32",
                    Precision::F64 => "f64",
                },
                c.cost_ratio,
            ),
            within_seconds: Some(seconds),
        },
        None => Advice::NoneWithin {
            none_within: searched_to,
            why: format!(
                "no finer step, more substeps{f64_too} up to {searched_to}x the level's cost \
                 passes: the failure does not shrink with accuracy, an engine limit \
                 (docs/known-gaps.md) or an expected answer to recheck"
            ),
            within_seconds: None,
        },
    }
}

/// A candidate's settings as run options over the level's own (solver iterations kept).
fn candidate_options(own: &Settings, opts: &Options, c: &Candidate) -> Options {
    Options {
        dt: Some(own.dt / f64::from(c.dt_div)),
        substeps: Some(own.substeps * c.sub_mul as usize),
        solver_iterations: Some(own.solver_iterations),
        precision: Some(c.precision),
        ..opts.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn candidates_are_cheapest_first_and_bounded() {
        let c = candidates(Precision::F32);
        assert!(c.windows(2).all(|w| w[0].cost_ratio <= w[1].cost_ratio));
        assert!(c
            .iter()
            .all(|x| x.cost_ratio > 1.0 && x.cost_ratio <= MAX_COST_RATIO));
        // f64 at the level's own step and substeps comes first (1.25x), then 2x substeps.
        assert_eq!(
            (c[0].dt_div, c[0].sub_mul, c[0].precision),
            (1, 1, Precision::F64)
        );
        assert_eq!(
            (c[1].dt_div, c[1].sub_mul, c[1].precision),
            (1, 2, Precision::F32)
        );
        assert_eq!((c[2].dt_div, c[2].sub_mul), (2, 1));
        // A level already in f64 is never advised f32.
        assert!(candidates(Precision::F64)
            .iter()
            .all(|x| x.precision == Precision::F64));
    }
}
