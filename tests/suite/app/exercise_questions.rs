//! Questions written in the window, headless (MinimalPlugins): a teacher builds a rolling-disc
//! exercise from a new scene with the editor's commands alone (an incline, a disc on it, two
//! questions: one answer computed from the analysis, one typed from the textbook), previews a
//! question, rewrites and removes one, meets the validator's refusal, saves, and
//! `rigidlab check` passes the saved level.

use crate::common;

use bevy::prelude::*;
use common::app::{editor_app as app, level, send};
use rigidlab::app::editor::{Editor, EditorCommand};
use rigidlab::app::panels::questions_editor::QuestionForm;
use rigidlab::editor::{Edit, NewShape, Property};
use rigidlab::sim::Options;
use std::process::Command;

/// The form's "add question" (or "rewrite") button.
fn ask(app: &mut App, f: &QuestionForm) -> (String, bool) {
    let c = f.command(level(app)).unwrap();
    send(app, c)
}

/// The form as the teacher fills it in the build panel.
fn form(
    id: &str,
    quantity: &str,
    at: &str,
    expected: &str,
    compute: bool,
    tol: &str,
) -> QuestionForm {
    QuestionForm {
        id: id.into(),
        ask: format!("{id} of the disc"),
        quantity: quantity.into(),
        at: at.into(),
        expected: expected.into(),
        compute,
        tolerance: tol.into(),
        why: "rapier's soft friction lets the contact creep: measured below 2e-3".into(),
        ..Default::default()
    }
}

/// The exercise's scene, built with the Build panel's edits: a 30 degree incline, a 0.2 m disc
/// of 1 kg resting on it with friction 0.6, 1 s long, at the library's rolling step. Returns
/// the incline's angle.
fn rolling_disc_scene(app: &mut App) -> f64 {
    let theta = 30f64.to_radians();
    let (note, ok) = send(
        app,
        EditorCommand::Apply(Edit::AddIncline {
            at: (-2.0, 0.0),
            angle: theta,
            length: 4.0,
        }),
    );
    assert!(ok, "{note}");
    // A disc of r = 0.2 m resting on the slope 3.5 m up from its lower corner: the contact point
    // (-2, 0) + 3.5 (cos 30, sin 30), the center r along the outward normal (-sin 30, cos 30).
    let r = 0.2;
    let c = (
        -2.0 + 3.5 * theta.cos() - r * theta.sin(),
        3.5 * theta.sin() + r * theta.cos(),
    );
    let (note, ok) = send(
        app,
        EditorCommand::Apply(Edit::AddBody {
            shape: NewShape::Disc { radius: r },
            at: c,
            mass: 1.0,
        }),
    );
    assert!(ok, "{note}");
    for e in [
        Edit::Set {
            body: "disc1".into(),
            property: Property::Friction(0.6),
        },
        Edit::SetDuration(1.0),
        // The library's rolling disc's step (levels/kinetics/classic_rolling_disc.ron): at the
        // new scene's 1/60 s the engine's acceleration is 0.6% off, past a 0.5% tolerance.
        Edit::SetStep {
            dt: 1.0 / 240.0,
            substeps: 4,
        },
    ] {
        let (note, ok) = send(app, EditorCommand::Apply(e));
        assert!(ok, "{note}");
    }

    theta
}

#[test]
fn a_rolling_disc_exercise_written_in_the_window_passes_check() {
    let mut app = app();
    let theta = rolling_disc_scene(&mut app);

    // A field the form cannot read is said at once, before any command.
    let bad = form("accel", "Speed(disc1", "End", "", true, "0.005");
    let why = bad.command(level(&app)).unwrap_err();
    assert!(why.starts_with("quantity:"), "{why}");

    // The validator's refusal comes back as the editor's note, and nothing changes.
    let ghost = form("ghost", "Speed(\"nobody\")", "End", "1.0", false, "0.01");
    let (why, ok) = ask(&mut app, &ghost);
    assert!(!ok && why.contains("nobody"), "{why}");
    assert!(level(&app).questions.is_empty());

    // The preview: the engine's and the analysis's values, before anything is saved. Rolling
    // without slip (RK-8 with 6/1): a = g sin(theta) / (1 + k_G^2/r^2) = 9.81 * 0.5 / 1.5 =
    // 3.27 m/s^2 for a uniform disc (k_G^2 = r^2/2).
    let a_theory = 9.81 * theta.sin() / 1.5;
    let accel = form(
        "accel",
        "RollingAcceleration(body: \"disc1\", ground: \"incline1\")",
        "Time(0.5)",
        "",
        true,
        "0.005",
    );
    let (q, compute) = accel.question(level(&app)).unwrap();
    assert!(compute);
    assert_eq!(q.unit, "m/s^2", "an empty unit is the quantity's SI unit");
    let (note, ok) = send(&mut app, EditorCommand::Preview(Box::new(q)));
    assert!(ok, "{note}");
    assert!(
        note.contains("engine") && note.contains("analysis"),
        "{note}"
    );
    let preview = app.world().resource::<Editor>().preview.clone().unwrap();
    let r = preview.1.unwrap();
    // Both readings against the closed form: the analysis reads theta from the engine's
    // contact normal (the wedge's face is at 30 degrees exactly), the engine's value is a
    // central difference of v (f32 rounding of v over 2 dt). Measured 2026-11-27: analysis
    // 1.76e-4, engine 8.0e-6 (tests/suite/questions/rolling_applies.rs reads the same 1.9e-4, 1.1e-5);
    // bounds 5e-4 and 5e-5, a 2.8x and a 6x margin.
    assert!(
        (r.analysis.unwrap() - a_theory).abs() / a_theory < 5e-4,
        "{r:?}"
    );
    assert!((r.engine - a_theory).abs() / a_theory < 5e-5, "{r:?}");

    // Asked with "compute it": the expected answer is the analysis's value.
    let (note, ok) = ask(&mut app, &accel);
    assert!(ok, "{note}");
    let asked = &level(&app).questions[0];
    assert_eq!(asked.expected, r.analysis.unwrap());

    // The second typed from the textbook: after rolling s = 1 m, T = m g sin(theta) s (friction
    // does no work without slip) = 1 * 9.81 * 0.5 * 1 = 4.905 J. First with a wrong unit the
    // validator refuses, then rewritten.
    let mut ke = form(
        "ke_1m",
        "KineticEnergy(\"disc1\")",
        "Crossing(of: Distance(\"disc1\"), value: 1.0)",
        "4.905",
        false,
        "0.004",
    );
    ke.unit = "m/s".into();
    let (why, ok) = ask(&mut app, &ke);
    assert!(!ok, "a kinetic energy in m/s was taken: {why}");
    ke.unit = String::new();
    let (note, ok) = ask(&mut app, &ke);
    assert!(ok, "{note}");
    assert_eq!(level(&app).questions.len(), 2);

    // A third, removed again; the second rewritten in place (its tolerance).
    let extra = form("extra", "Speed(\"disc1\")", "End", "1.0", false, "0.01");
    assert!(ask(&mut app, &extra).1);
    assert_eq!(level(&app).questions.len(), 3);
    let (note, ok) = send(
        &mut app,
        EditorCommand::Apply(Edit::RemoveQuestion { id: "extra".into() }),
    );
    assert!(ok, "{note}");
    let mut rewrite = QuestionForm::from_question(1, &level(&app).questions[1]);
    assert_eq!(rewrite.expected, "4.905");
    rewrite.tolerance = "0.005".into();
    let (note, ok) = ask(&mut app, &rewrite);
    assert!(ok, "{note}");
    let qs = &level(&app).questions;
    assert_eq!(qs.len(), 2);
    assert_eq!((qs[1].id.as_str(), qs[1].tolerance), ("ke_1m", 0.005));

    let dir = std::env::temp_dir().join(format!("rigidlab-questions-app-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let path = dir.join("rolling-disc.ron");
    let (note, ok) = send(&mut app, EditorCommand::Save(path.clone()));
    assert!(ok, "{note}");
    let out = Command::new(env!("CARGO_BIN_EXE_rigidlab"))
        .args(["check", path.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "rigidlab check failed the saved exercise:\n{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    // And the runner itself: both questions read and passed.
    let scene = rigidlab::level::load(&path).unwrap();
    let report =
        rigidlab::runner::run_graded(&scene, &Options::default(), &Default::default(), |_| {})
            .unwrap();
    assert_eq!(report.questions.len(), 2);
    assert!(
        report.questions.iter().all(|q| q.passed),
        "{:?}",
        report.questions
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The checks panel's line shows the reading that failed: a question fails on the engine or on
/// the analysis, and a FAIL beside an error within tolerance would contradict itself (issue 33:
/// the engine at 5.03e-3 shown, the analysis failing at 1.6e-2 against 1e-2).
#[test]
fn a_failed_question_shows_the_failing_reading() {
    use rigidlab::app::panels::checks::shown_error;
    let mut q = rigidlab::questions::QuestionResult {
        id: "q".into(),
        ask: String::new(),
        unit: "m/s".into(),
        expected: 1.0,
        analysis: Some(1.016),
        engine: 1.00503,
        rel_error: 5.03e-3,
        analysis_rel_error: Some(1.6e-2),
        analysis_source: String::new(),
        tolerance: 1e-2,
        passed: false,
        time: 1.0,
        why: String::new(),
        note: String::new(),
        student: None,
    };
    assert_eq!(shown_error(&q), ("analysis", 1.6e-2));
    // The engine failing is the engine's line, whatever the analysis did.
    q.rel_error = 2e-2;
    assert_eq!(shown_error(&q), ("engine", 2e-2));
    // Both within: the engine's, as before.
    q.rel_error = 5.03e-3;
    q.analysis_rel_error = Some(1e-3);
    assert_eq!(shown_error(&q), ("engine", 5.03e-3));
    // A NaN analysis error counts as failing (it never passes).
    q.analysis_rel_error = Some(f64::NAN);
    assert_eq!(shown_error(&q).0, "analysis");
}

/// The preview is where the teacher sees the values before deciding the answer: it runs with
/// the expected answer still blank, and then judges the answer typed (or the analysis's) by the
/// check's own rule, naming the reading that fails.
#[test]
fn the_preview_needs_no_answer_and_judges_the_one_typed() {
    use rigidlab::app::panels::questions_editor::{short_number, verdict};
    let mut app = app();
    let theta = rolling_disc_scene(&mut app);
    // The kinetic energy after rolling 1 m, T = m g sin(theta) s = 4.905 J (friction does no
    // work without slip).
    let mut ke = form(
        "ke_1m",
        "KineticEnergy(\"disc1\")",
        "Crossing(of: Distance(\"disc1\"), value: 1.0)",
        "",
        false,
        "0.01",
    );
    assert!(ke.question(level(&app)).is_err(), "added without an answer");
    let q = ke
        .preview(level(&app))
        .expect("the preview refused a blank answer");
    let (note, ok) = send(&mut app, EditorCommand::Preview(Box::new(q)));
    assert!(ok, "{note}");
    let r = app
        .world()
        .resource::<Editor>()
        .preview
        .clone()
        .unwrap()
        .1
        .unwrap();
    assert_eq!(ke.expected_for(&r), None, "a blank answer judged");
    // The textbook's answer passes; one 5% off fails on the engine's reading.
    let t = 9.81 * theta.sin();
    ke.expected = format!("{t}");
    let v = r.with_expected(ke.expected_for(&r).unwrap());
    assert!(v.passed, "{}", verdict(&v));
    assert!(verdict(&v).ends_with("passes"), "{}", verdict(&v));
    ke.expected = format!("{}", t * 1.05);
    let v = r.with_expected(ke.expected_for(&r).unwrap());
    assert!(!v.passed);
    assert!(
        verdict(&v).contains("FAILS on the engine"),
        "{}",
        verdict(&v)
    );
    // "compute it": the analysis's value, which passes by construction where the engine agrees.
    ke.compute = true;
    assert_eq!(ke.expected_for(&r), r.analysis);
    // Numbers in the list: six significant digits.
    assert_eq!(short_number(3.2788686771027526), "3.27887");
    assert_eq!(short_number(4.905), "4.905");
    assert_eq!(short_number(1500.0), "1500");
    assert_eq!(short_number(2.5e-7), "2.50000e-7");
}
