//! The exercise library (issue 4): every level under `levels/` (except the stress scenes) is
//! run with its questions read by `QuestionProbe::for_level`, and
//! - every question passes (the engine's answer is within the level's stated tolerance);
//! - every question's analysis value (the textbook formula applied to the engine's state)
//!   is within 0.1% of the expected answer (absolute 1e-3 when the expected answer is 0);
//! - a student's right answer (the expected one, and one just inside the student tolerance) is
//!   graded as right, and a wrong one (just outside it) as wrong, without changing the engine's grade.
//!
//! `cargo test --test suite -- questions::library:: --nocapture` prints every question's expected, engine and
//! analysis values.

use crate::common;

use common::rel;
use rigidlab::level::{self, Scene};
use rigidlab::questions::{QuestionProbe, QuestionResult};
use rigidlab::sim::Options;
use rigidlab::simulation::AnySimulation;
use std::path::{Path, PathBuf};

/// The library's exercises: every level under levels/ but the stress scenes.
fn all_levels() -> Vec<PathBuf> {
    common::ron_files("levels", &["stress"])
}

/// Runs a level and returns its question probes, ready to be finished.
fn run(scene: &Scene) -> Vec<QuestionProbe> {
    let mut sim = AnySimulation::new(scene, &Options::default());
    let mut probes: Vec<QuestionProbe> = scene
        .level
        .questions
        .iter()
        .map(|q| QuestionProbe::for_level(&scene.level, q))
        .collect();
    sim.run(|s| {
        for p in probes.iter_mut() {
            p.observe(s);
        }
    })
    .unwrap_or_else(|e| panic!("{}: {e}", scene.file.display()));
    probes
}

/// Runs a level and answers its questions.
fn answer(scene: &Scene) -> Vec<QuestionResult> {
    run(scene).into_iter().map(|p| p.finish(None)).collect()
}

#[test]
fn every_question_of_the_library_passes_and_its_analysis_agrees() {
    let files = all_levels();
    assert!(files.len() >= 35, "the library has {} levels", files.len());
    let mut failures = Vec::new();
    let (mut questions, mut with_analysis) = (0, 0);
    for f in &files {
        let scene = level::load(f).unwrap_or_else(|e| panic!("{e}"));
        let results = answer(&scene);
        println!("{}", f.display());
        for q in &results {
            questions += 1;
            println!(
                "  {:<20} expected {:>13.6} engine {:>13.6} ({:.1e}, tol {:.0e})  analysis {}",
                q.id,
                q.expected,
                q.engine,
                q.rel_error,
                q.tolerance,
                q.analysis.map_or("-".to_string(), |a| format!(
                    "{a:>13.6} ({:.1e})",
                    rel(a, q.expected)
                ))
            );
            if !q.passed {
                failures.push(format!(
                    "{}: question {} engine {} expected {} (rel err {:.2e} > tol {:.1e}) {}",
                    f.display(),
                    q.id,
                    q.engine,
                    q.expected,
                    q.rel_error,
                    q.tolerance,
                    q.note
                ));
            }
            if let Some(a) = q.analysis {
                with_analysis += 1;
                if rel(a, q.expected) > 1e-3 {
                    failures.push(format!(
                        "{}: question {} analysis {} expected {} (rel err {:.2e} > 1e-3)",
                        f.display(),
                        q.id,
                        a,
                        q.expected,
                        rel(a, q.expected)
                    ));
                }
            }
        }
    }
    println!(
        "{} levels, {questions} questions, {with_analysis} with an analysis value",
        files.len()
    );
    // The agreement above holds only where an analysis answers: a change that made analyses
    // "not applicable" would pass it silently. 185 of the 297 library questions had an
    // analysis value on 2026-11-27; a library change that lowers this must lower the floor
    // here on purpose, saying why.
    const ANALYSED_AT_LEAST: usize = 185;
    assert!(
        with_analysis >= ANALYSED_AT_LEAST,
        "only {with_analysis} library questions have an analysis value (at least {ANALYSED_AT_LEAST} had one): \
         an analysis stopped answering"
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn a_student_is_graded_against_the_expected_answer_and_tolerance() {
    let mut graded = 0;
    for f in all_levels() {
        let scene = level::load(&f).unwrap();
        for (q, probe) in scene.level.questions.iter().zip(run(&scene)) {
            let engine = probe.clone().finish(None);
            // Right: the expected answer, and answers 0.9 of the student tolerance off it.
            // Wrong: 1.1 of it off. (Students are graded to their own tolerance, default 1%.)
            let tol = q.student_tolerance;
            let off = |k: f64| {
                if q.expected == 0.0 {
                    k * tol
                } else {
                    q.expected * (1.0 + k * tol)
                }
            };
            for (value, right) in [
                (q.expected, true),
                (off(0.9), true),
                (off(-0.9), true),
                (off(1.1), false),
                (off(-1.1), false),
            ] {
                let r = probe.clone().finish(Some(value));
                let g = r.student.as_ref().expect("the answer is graded");
                assert_eq!(g.answer, value);
                assert_eq!(
                    g.passed,
                    right,
                    "{}: question {} answered {value} (expected {}, student tolerance {}) graded {}",
                    f.display(),
                    q.id,
                    q.expected,
                    tol,
                    g.passed
                );
                // A student's answer never changes the engine's grade.
                assert_eq!(
                    (r.engine.to_bits(), r.passed),
                    (engine.engine.to_bits(), engine.passed)
                );
                graded += 1;
            }
        }
    }
    assert!(graded > 0);
}

#[test]
fn a_wrong_answer_in_a_level_fails_the_engine_question() {
    // The same level with its expected answer moved by 5 tolerances must fail: the questions
    // assert something that could fail.
    let f = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("levels/impact/jh_P9.10.1_rear_end_collision.ron");
    let text = std::fs::read_to_string(&f).unwrap();
    let wrong = text.replacen("expected: 4.7822883720930225", "expected: 4.80", 1);
    assert_ne!(text, wrong, "the level's first expected answer moved");
    let scene = level::parse(&f, &wrong).unwrap();
    let results = answer(&scene);
    assert!(!results[0].passed, "{:?}", results[0]);
    assert!(results[1..].iter().all(|q| q.passed));
}
