//! Advice for a level that fails at its settings: the cheapest solver settings, in a bounded
//! search, at which every check and question passes, or that none within the bound does.
//!
//! A failing level is rerun at finer settings: the step divided by 1, 2, 4, 8 or 16, the
//! substeps multiplied by the same, and the engine in f64 where the level ran in f32. Each
//! candidate's cost is estimated against the level's own run (steps x substeps, f64 at
//! [`F64_COST`] times f32) and candidates are tried cheapest first, up to [`MAX_COST_RATIO`] times
//! the level's own cost and [`SEARCH_BUDGET`] times it over the whole search, and within
//! [`SEARCH_COST_S`] over the whole search, counted in the run budget's estimated seconds
//! (`runner::budget`'s price model of a run, the same on every machine), not in wall time: a
//! candidate is not started when the estimates of the runs tried plus its own would pass it.
//! So the same level gets the same advice on an idle machine and on a busy one (before
//! 2026-12-06 the bound was 2 s of wall time, and a busy machine turned settings into "none
//! within"), and a level of a second or more (a loop at 1/4800 s) is searched only as far as
//! the bound allows: the advice then says that the bound ran out, not that no setting passes.
//! The first that passes is the advice; it is a real run's verdict, so rerunning the level with
//! the advised settings passes (tests/suite/study/advice.rs). When none within 32x passes, the failure
//! does not go away with accuracy within the bound: an engine limit (docs/known-gaps.md) or a
//! wrong expected answer.

use super::gaps;
use crate::level::{Precision, Scene};
use crate::questions::{QuestionResult, CANNOT_BE_READ};
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

/// The whole search's cost, in the run budget's estimated seconds (`runner::budget::Estimate`:
/// each candidate priced as `rigidlab check` would price its run): no candidate is started whose
/// estimate, added to those of the candidates tried, would pass it. An estimate is not a
/// measurement, so the search's verdict depends on the level alone, not on how busy the machine
/// is. Chosen so that a search the bound stops takes about what the 2 s wall-time bound it
/// replaced allowed, on an idle 2-core machine: docs/cli.md has the measurement.
pub const SEARCH_COST_S: f64 = 2.0;

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
/// search. Found by the tenth new user (tests/newuser/n10_11b: a `center_of_percussion` check
/// on a bar that rests on a peg was searched through to 32x and then blamed on the engine).
/// So is a question whose quantity cannot be read in the scene at all (its note starts with
/// [`CANNOT_BE_READ`]: a `ModePeriod` where the linearization refuses the scene; n14's probe was
/// searched to its bound, "none within", even at 60 s).
pub fn beyond_settings(r: &LevelReport) -> Option<String> {
    if r.error.is_some() {
        return None;
    }
    let unreadable = |q: &&QuestionResult| q.note.starts_with(CANNOT_BE_READ);
    let failing_q: Vec<_> = r.questions.iter().filter(|q| !q.passed).collect();
    if !failing_q.iter().all(unreadable) {
        return None;
    }
    let failing: Vec<_> = r.checks.iter().filter(|c| !c.passed).collect();
    let judged_none = (!failing.is_empty() || !failing_q.is_empty())
        && failing
            .iter()
            .all(|c| c.samples == 0 && c.note.starts_with("cannot judge"));
    judged_none.then(|| {
        let which: Vec<_> = failing
            .iter()
            .map(|c| format!("{} on {} ({})", c.kind, c.subject, c.note))
            .collect();
        let checks = match which.len() {
            0 => None,
            1 => Some(format!("the check {} cannot judge the scene", which[0])),
            _ => Some(format!(
                "the checks {} cannot judge the scene",
                which.join("; ")
            )),
        };
        let questions = (!failing_q.is_empty()).then(|| {
            let ids: Vec<_> = failing_q
                .iter()
                .map(|q| format!("`{}` ({})", q.id, q.note))
                .collect();
            format!("question {}", ids.join(", "))
        });
        let what: Vec<String> = checks.into_iter().chain(questions).collect();
        format!(
            "no setting changes this: {}; remove {} or change the scene",
            what.join("; "),
            if failing_q.is_empty() {
                "the check"
            } else {
                "what cannot be read"
            }
        )
    })
}

/// The advice for a level whose run at the options `opts` (the command line's overrides of
/// the level's settings) gave the report `own` (None when the run stopped early): a level whose
/// every failure no setting can change ([`beyond_settings`]) gets that said, any other the
/// search within [`SEARCH_COST_S`].
pub fn advise(scene: &Scene, opts: &Options, own: Option<&LevelReport>) -> Advice {
    advise_within(scene, opts, own, SEARCH_COST_S)
}

/// [`advise`] with the search's bound `cost_s` (estimated seconds) instead of
/// [`SEARCH_COST_S`] (`rigidlab check --advice-cost S`).
pub fn advise_within(
    scene: &Scene,
    opts: &Options,
    own: Option<&LevelReport>,
    cost_s: f64,
) -> Advice {
    if let Some(why) = own.and_then(beyond_settings) {
        return Advice::NoneWithin {
            none_within: 0.0,
            why,
            within_estimated_seconds: None,
            known_gaps: Vec::new(),
        };
    }
    let precision = opts.precision.unwrap_or(scene.level.world.precision);
    let own_settings = Settings::resolve(&scene.level, opts, precision);
    let failed_wall_ms = own.map_or(0.0, |r| r.wall_ms);
    // A level failed by its questions' analysis alone: the first finer setting tells whether
    // the analysis comes to the answer with accuracy; if not, no setting helps.
    let mut tried = None;
    if let Some(alone) = own.and_then(failed_by_analysis_alone) {
        let c = first_finer(own_settings.precision);
        let options = candidate_options(&own_settings, opts, &c);
        let estimate = Estimate::of(&scene.level, &options, Mode::Check, None);
        if estimate.fits() && estimate.seconds <= cost_s {
            let finer = runner::run_graded(scene, &options, &HashMap::new(), |_| {}).ok();
            if let Some(why) = finer
                .as_ref()
                .and_then(|f| analysis_does_not_fit(&alone, f, &own_settings, &options))
            {
                return Advice::NoneWithin {
                    none_within: 0.0,
                    why,
                    within_estimated_seconds: None,
                    known_gaps: Vec::new(),
                };
            }
            tried = Some(Tried {
                candidate: c,
                report: finer,
                seconds: estimate.seconds,
            });
        }
    }
    let advice = search(scene, opts, &own_settings, failed_wall_ms, cost_s, tried);
    name_gaps(advice, &gaps::matching(&scene.level))
}

/// The advice with the published gaps the scene matches named (`study::gaps`), when the search
/// ended without a passing setting: in `why` and in the JSON's `known_gaps`. Advice that found
/// settings is left as it is.
fn name_gaps(advice: Advice, matched: &[gaps::KnownGap]) -> Advice {
    match advice {
        Advice::NoneWithin {
            none_within,
            why,
            within_estimated_seconds,
            ..
        } if !matched.is_empty() => Advice::NoneWithin {
            none_within,
            why: format!("{why}{}", gaps::sentence(matched)),
            within_estimated_seconds,
            known_gaps: gaps::refs(matched),
        },
        other => other,
    }
}

/// A candidate already run before the search (the first finer setting, for the analysis):
/// its verdict, and its estimated seconds, already spent.
struct Tried {
    candidate: Candidate,
    report: Option<LevelReport>,
    seconds: f64,
}

/// The first finer setting, against which an analysis that fails is judged: the step halved
/// (dt / 2, the level's substeps and precision), which halves both the engine's substep and the
/// sampling the questions' finite differences and windows read.
fn first_finer(precision: Precision) -> Candidate {
    Candidate {
        dt_div: 2,
        sub_mul: 1,
        precision,
        cost_ratio: 2.0,
    }
}

/// How much an analysis's error must shrink when the step is halved for accuracy to count as
/// helping it: an error first order in the step halves (ratio 0.5), a second-order one
/// quarters; an error that keeps more than 3/4 of itself does not converge with the step at
/// any useful rate, so it is not the step's (a formula whose assumption the scene breaks).
pub const ANALYSIS_SHRINK: f64 = 0.75;

/// The questions of a report that fail on their analysis alone, when they are all its failures:
/// each reads the engine within its tolerance of the stated answer and the analysis (the
/// textbook formula on the engine's state) outside it; the run did not stop, and any check that
/// fails cannot judge the scene ([`beyond_settings`]). None otherwise. An analysis whose
/// assumptions the scene breaks, as its quantity checks them, is "not applicable" and the
/// question is graded on the engine alone (docs/levels.md), so it never fails a question here:
/// what fails here is an analysis whose assumptions were not caught.
pub fn failed_by_analysis_alone(r: &LevelReport) -> Option<Vec<&QuestionResult>> {
    if r.error.is_some()
        || r.checks
            .iter()
            .any(|c| !c.passed && (c.samples != 0 || !c.note.starts_with("cannot judge")))
    {
        return None;
    }
    let failing: Vec<&QuestionResult> = r.questions.iter().filter(|q| !q.passed).collect();
    let alone = |q: &&QuestionResult| {
        q.rel_error <= q.tolerance && q.analysis_rel_error.is_some_and(|a| a > q.tolerance)
    };
    (!failing.is_empty() && failing.iter().all(alone)).then_some(failing)
}

/// Why no setting helps, when the same questions fail on their analysis alone at the first
/// finer setting (`finer`, run at `finer_opts`) as at the level's (`alone`), and none's analysis
/// error shrank by more than [`ANALYSIS_SHRINK`]: the engine agrees with the answer at both, the
/// analysis disagrees at both by as much. None when accuracy may still help.
fn analysis_does_not_fit(
    alone: &[&QuestionResult],
    finer: &LevelReport,
    own: &Settings,
    finer_opts: &Options,
) -> Option<String> {
    let finer_alone = failed_by_analysis_alone(finer)?;
    if finer_alone.len() != alone.len() {
        return None;
    }
    let mut reasons = Vec::new();
    for q in alone {
        let f = finer_alone.iter().find(|f| f.id == q.id)?;
        let (e0, e1) = (q.analysis_rel_error?, f.analysis_rel_error?);
        if e1 < ANALYSIS_SHRINK * e0 {
            return None;
        }
        let note = if q.note.is_empty() {
            String::new()
        } else {
            format!("; its note: {}", q.note)
        };
        reasons.push(format!(
            "question `{}`: the analysis reads {} {u} against the stated answer {} {u} (error \
             {:.2e}, tolerance {:.1e}) at dt {} s and {} {u} ({:.2e}) at dt {} s, while the engine \
             reads {} {u} ({:.2e}) and {} {u} ({:.2e}){note}",
            q.id,
            q.analysis.unwrap_or(f64::NAN),
            q.expected,
            e0,
            q.tolerance,
            own.dt,
            f.analysis.unwrap_or(f64::NAN),
            e1,
            finer_opts.dt.unwrap_or(own.dt),
            q.engine,
            q.rel_error,
            f.engine,
            f.rel_error,
            u = q.unit,
        ));
    }
    Some(format!(
        "the analysis does not fit this scene; no setting helps: {}. The engine agrees with the \
         answer and the analysis (the textbook formula on the engine's state) does not, by as \
         much with the step halved, so the formula assumes what this scene does not hold: check \
         the quantity's assumptions (docs/levels.md), or ask for a quantity whose formula fits",
        reasons.join("; ")
    ))
}

/// The search itself: candidates cheapest first, each run and graded, until one passes or a
/// bound is reached.
fn search(
    scene: &Scene,
    opts: &Options,
    own: &Settings,
    failed_wall_ms: f64,
    cost_s: f64,
    mut tried: Option<Tried>,
) -> Advice {
    let mut spent = 0.0;
    // The estimated seconds of the candidates run so far (the one tried before, if any).
    let mut spent_s = tried.as_ref().map_or(0.0, |t| t.seconds);
    let mut searched_to = 0.0;
    // The first candidate the cost bound left untried, with its estimated seconds.
    let mut cut: Option<(Candidate, f64)> = None;
    let none = HashMap::new();
    for c in candidates(own.precision) {
        if spent + c.cost_ratio > SEARCH_BUDGET {
            break;
        }
        let options = candidate_options(own, opts, &c);
        // A candidate past the run budget is not tried (runner::budget).
        let estimate = Estimate::of(&scene.level, &options, Mode::Check, None);
        if !estimate.fits() {
            break;
        }
        // Nor one whose estimate would take the search past its bound: the candidates come
        // cheapest first, so none after it would fit either.
        let run_before = tried.as_ref().is_some_and(|t| t.candidate == c);
        if !run_before && spent_s + estimate.seconds > cost_s {
            cut = Some((c, estimate.seconds));
            break;
        }
        // The candidate run before the search is not run (nor paid for) again.
        let ran = match tried.take_if(|t| t.candidate == c) {
            Some(t) => t.report,
            None => {
                spent_s += estimate.seconds;
                runner::run_graded(scene, &options, &none, |_| {}).ok()
            }
        };
        spent += c.cost_ratio;
        let Some(r) = ran else {
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
        // The bound ran out before the cost ratios did: say so, and what to try by hand.
        Some((c, predicted)) => Advice::NoneWithin {
            none_within: searched_to,
            why: format!(
                "none passes within the search's bound of {cost_s} s of estimated runs ({}): \
                 the next, --dt {} --substeps {} --precision {} ({}x the level's cost), is \
                 estimated at {predicted:.2} s; run it yourself (or give `--advice-cost`), the \
                 search stopped at its bound, not on a limit",
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
            within_estimated_seconds: Some(cost_s),
            known_gaps: Vec::new(),
        },
        None => Advice::NoneWithin {
            none_within: searched_to,
            why: format!(
                "no finer step, more substeps{f64_too} up to {searched_to}x the level's cost \
                 passes: the failure does not shrink with accuracy, an engine limit \
                 (docs/known-gaps.md) or an expected answer to recheck"
            ),
            within_estimated_seconds: None,
            known_gaps: Vec::new(),
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
