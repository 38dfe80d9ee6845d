//! Every library question whose answer can be negative says what its sign means (issue 42's
//! student trial: about twenty questions asked for a signed angular velocity, acceleration
//! component or work with a negative answer and no word on which way is positive, so a student
//! who computed the right magnitude was told wrong by 200%).
//!
//! The rule, as `levels/kinetics/classic_physical_pendulum_large.ron` and the yo-yo state it:
//! the question's own text (`ask`, printed beside its answer box) names the sign with the word
//! "positive" or "negative": a direction ("counterclockwise positive", "up positive",
//! "positive east") or, for a quantity without a direction, what its sign means ("positive
//! when it adds energy"). The statement is not enough: a student answering the third question
//! reads its line, not the paragraph above.
//!
//! "Can be negative": the expected answer of the level as it opens, and for a level with
//! parameters of its nominal variant and of every corner of the ranges (each parameter at its
//! lowest or highest value: the library's answers are monotonic in each parameter over its
//! range, so an answer negative at some variant is negative at a corner).

use crate::common;
use rigidlab::level::params::{Parameterized, Pick};
use std::path::Path;

/// Whether a question's text says what its sign means.
fn states_sign(ask: &str) -> bool {
    let ask = ask.to_lowercase();
    ask.contains("positive") || ask.contains("negative")
}

/// Each question of the level at `path` as (id, ask, the expected answers over its variants).
fn answers(path: &Path) -> Vec<(String, String, Vec<f64>)> {
    let text = std::fs::read_to_string(path).unwrap();
    let levels = match Parameterized::read(path, &text).unwrap_or_else(|e| panic!("{e}")) {
        None => vec![common::load(path).level],
        Some(p) => std::iter::once(p.indices(&Pick::Nominal))
            .chain(p.corners())
            .map(|idx| p.make(path, &idx).unwrap_or_else(|e| panic!("{e}")).level)
            .collect(),
    };
    levels[0]
        .questions
        .iter()
        .enumerate()
        .map(|(k, q)| {
            let values = levels.iter().map(|l| l.questions[k].expected).collect();
            (q.id.clone(), q.ask.clone(), values)
        })
        .collect()
}

#[test]
fn a_question_that_can_be_answered_negative_states_its_sign() {
    let files = common::ron_files("levels", &[]);
    assert!(files.len() > 100, "the library: {} files", files.len());
    let mut signed = 0;
    let mut missing = Vec::new();
    for f in &files {
        for (id, ask, values) in answers(f) {
            if !values.iter().any(|v| *v < 0.0) {
                continue;
            }
            signed += 1;
            if !states_sign(&ask) {
                let rel = f.strip_prefix(common::repo_path("")).unwrap_or(f);
                missing.push(format!("{}: {id}: {ask:?}", rel.display()));
            }
        }
    }
    // The library had 47 such questions on 2026-12-07: the rule has something to hold.
    assert!(
        signed >= 40,
        "only {signed} questions with a negative answer"
    );
    assert!(
        missing.is_empty(),
        "{} of {signed} questions with a negative answer do not say which way is positive \
         (add \"(counterclockwise positive)\", \"(up positive)\", ... to the ask):\n{}",
        missing.len(),
        missing.join("\n")
    );
}

/// The rule itself: the large pendulum's wording passes, the old one did not.
#[test]
fn the_rule_reads_the_ask() {
    assert!(states_sign(
        "Angular velocity at the vertical, released from the horizontal (counterclockwise positive)"
    ));
    assert!(states_sign(
        "Acceleration of the yo-yo's center, a_y (y up: negative while it falls)"
    ));
    assert!(!states_sign(
        "Angular velocity at the vertical, released from the horizontal"
    ));
}
