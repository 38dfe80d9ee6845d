//! Under a question, rigidlab's measured value (issue 42, the student trial of 2026-12-07:
//! "rigidlab measured this run; answer first to see it" showed under questions already
//! answered). Not yet answered: "answer first". Answered right: the value. Answered wrong: not
//! "answer first" (it was answered) but that the value shows once the answer is right or with
//! the solution: the value would give the answer away, and the solution asked for marks the
//! level "solved with help". Predict first's results or the solution shown: the value, since
//! they have given it already. The left column is drawn into a bare egui context at 1280x800
//! after the run has reached its end (the value is measured there).

use bevy_egui::egui;
use rigidlab::app::panels::{grade, Browser, Exercise, SHOWN_WHEN_RIGHT};
use rigidlab::app::{LiveChecks, Run};
use rigidlab::sim::Options;

use crate::common;
use crate::common::app::{all_text, left_column};

/// The hoop rolling down its incline (one question, 1.05 s), run to its end with the live
/// checks watching as the window's do.
fn finished() -> (Run, LiveChecks) {
    let mut phys = Run::new(
        common::load("levels/kinetics/classic_rolling_hoop.ron"),
        Options::default(),
    );
    let mut live = LiveChecks::new(&phys);
    while !phys.at_end() {
        assert!(phys.advance());
        live.observe(&phys);
    }
    assert!(
        live.answers.is_some(),
        "the run's values are measured at its end"
    );
    (phys, live)
}

/// The left column's texts for `ex`.
fn column(phys: &Run, live: &LiveChecks, ex: &mut Exercise) -> Vec<String> {
    let ctx = egui::Context::default();
    let texts = left_column(&ctx, &mut Browser::default(), (phys, live), ex, Vec::new());
    all_text(&texts).into_iter().map(String::from).collect()
}

fn says_answer_first(texts: &[String]) -> bool {
    texts.iter().any(|t| t.contains("answer first to see it"))
}

fn shows_value(texts: &[String]) -> bool {
    texts
        .iter()
        .any(|t| t.contains("rigidlab measured") && t.contains(" at t = "))
}

/// Every question answered with `factor` times its answer and checked.
fn answered(phys: &Run, factor: f64) -> Exercise {
    let questions = &phys.sim.level.questions;
    let mut ex = Exercise::default();
    ex.start(questions.len());
    for (k, q) in questions.iter().enumerate() {
        ex.answers[k] = format!("{}", factor * q.expected);
        ex.grades[k] = Some(grade(q, &ex.answers[k]));
    }
    ex
}

#[test]
fn an_answered_question_never_says_answer_first() {
    let (phys, live) = finished();
    // Not answered yet.
    let mut ex = Exercise::default();
    ex.start(phys.sim.level.questions.len());
    let texts = column(&phys, &live, &mut ex);
    assert!(
        says_answer_first(&texts) && !shows_value(&texts),
        "{texts:?}"
    );
    // Right (the level's own answers): the values.
    let texts = column(&phys, &live, &mut answered(&phys, 1.0));
    assert!(
        shows_value(&texts) && !says_answer_first(&texts),
        "{texts:?}"
    );
    // Wrong (twice the answers, far outside any tolerance): graded, so not "answer first",
    // and the values are not given away.
    let mut wrong = answered(&phys, 2.0);
    let texts = column(&phys, &live, &mut wrong);
    assert!(!says_answer_first(&texts), "{texts:?}");
    assert!(!shows_value(&texts), "{texts:?}");
    assert!(texts.iter().any(|t| t == SHOWN_WHEN_RIGHT), "{texts:?}");
    // The solution asked for: it gives the answers, so the values show.
    let mut help = false;
    wrong.hints.reveal(&mut help);
    let texts = column(&phys, &live, &mut wrong);
    assert!(shows_value(&texts), "{texts:?}");
}

/// Predict first's results show each prediction beside the run's values, right or wrong: the
/// questions under them show the values too, not "answer first" under a prediction made.
#[test]
fn after_predict_firsts_results_the_value_shows_under_a_wrong_prediction() {
    let (phys, live) = finished();
    let mut ex = answered(&phys, 2.0);
    ex.revealed = true;
    let texts = column(&phys, &live, &mut ex);
    assert!(
        shows_value(&texts) && !says_answer_first(&texts),
        "{texts:?}"
    );
}
