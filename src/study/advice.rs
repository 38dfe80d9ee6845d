//! Advice for a level that fails at its settings: the cheapest solver settings, in a bounded
//! search, at which every check and question passes, or that none within the bound does.
//!
//! A failing level is rerun at finer settings: the step divided by 1, 2, 4, 8 or 16, the
//! substeps multiplied by the same, and the engine in f64 where the level ran in f32. Each
//! candidate's cost is estimated against the level's own run (steps x substeps, f64 at
//! [`F64_COST`] times f32) and candidates are tried cheapest first, up to [`MAX_COST_RATIO`] times
//! the level's own cost and [`SEARCH_BUDGET`] times it over the whole search, and within the
//! time budget of one run (`runner::budget`) over the whole search. The first that
//! passes is the advice; it is a real run's verdict, so rerunning the level with the advised
//! settings passes (tests/study_advice.rs). When none passes, the failure does not go away with
//! accuracy within the bound: an engine limit (docs/known-gaps.md) or a wrong expected answer.

use crate::level::{Precision, Scene};
use crate::report::{Advice, AdvisedSettings, LevelReport};
use crate::runner::{self, Estimate, Mode, TIME_BUDGET_S};
use crate::sim::{Options, Settings};
use std::collections::HashMap;

/// The costliest candidate tried, as a multiple of the level's own run.
pub const MAX_COST_RATIO: f64 = 32.0;

/// The whole search's cost, as a multiple of the level's own run: at most this much is spent
/// on a level that no candidate makes pass. Every candidate up to [`MAX_COST_RATIO`] together
/// costs 424x (256x in f32, 168x in f64), so a level none passes is searched through.
pub const SEARCH_BUDGET: f64 = 512.0;

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

/// The advice for a level whose run failed at the options `opts` (the command line's
/// overrides of the level's settings) in `failed_wall_ms` (0 when it stopped early).
pub fn advise(scene: &Scene, opts: &Options, failed_wall_ms: f64) -> Advice {
    let precision = opts.precision.unwrap_or(scene.level.world.precision);
    let own = Settings::resolve(&scene.level, opts, precision);
    let mut spent = 0.0;
    let mut spent_s = 0.0;
    let mut searched_to = 0.0;
    let none = HashMap::new();
    for c in candidates(own.precision) {
        if spent + c.cost_ratio > SEARCH_BUDGET {
            break;
        }
        let options = Options {
            dt: Some(own.dt / f64::from(c.dt_div)),
            substeps: Some(own.substeps * c.sub_mul as usize),
            solver_iterations: Some(own.solver_iterations),
            precision: Some(c.precision),
            ..opts.clone()
        };
        // A candidate past the run budget is not tried, and the whole search stays within the
        // time budget of one run (runner::budget): the candidates come cheapest first.
        let estimate = Estimate::of(&scene.level, &options, Mode::Check, None);
        if !estimate.fits() || spent_s + estimate.seconds > TIME_BUDGET_S {
            break;
        }
        spent += c.cost_ratio;
        spent_s += estimate.seconds;
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
    Advice::NoneWithin {
        none_within: searched_to,
        why: format!(
            "no finer step, more substeps{} up to {searched_to}x the level's cost passes: \
             the failure does not shrink with accuracy, an engine limit (docs/known-gaps.md) \
             or an expected answer to recheck",
            if own.precision == Precision::F32 {
                " or f64"
            } else {
                ""
            }
        ),
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
