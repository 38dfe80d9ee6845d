//! Feedback on typical mistakes (issue 43): a question's `mistakes` give a wrong answer within
//! the student tolerance of one its message, in `check --answer` (text and JSON) and in the
//! window's feedback line (the same grading function); and are validated like `expected`.

use crate::common;
use rigidlab::level::{self, QuestionDef};
use rigidlab::questions::grade_answer;
use std::path::Path;

/// The massive-pulley Atwood machine's a_A: expected -3.924 m/s^2; its mistakes (derived in the
/// level's comment) are the pulley's inertia forgotten, (m_A - m_B) g / (m_A + m_B) = -4.905,
/// and the sign, +3.924.
fn atwood_a() -> QuestionDef {
    let scene = common::load("levels/kinetics/classic_atwood_massive_pulley.ron");
    scene.level.questions[0].clone()
}

#[test]
fn an_answer_at_a_mistake_gets_its_message_and_no_other_does() {
    let q = atwood_a();
    assert_eq!(q.id, "a_A");
    // 0.5 % from the forgotten-inertia value -4.905 (within the 1 % student tolerance of it),
    // 25 % from the answer: wrong, with the inertia message.
    let g = grade_answer(&q, -4.905 * 1.005);
    assert!(!g.passed);
    let m = g.mistake.expect("the forgotten inertia must be recognised");
    assert!(m.contains("inertia"), "{m}");
    // The sign mistake gets its own message, not the inertia one.
    let g = grade_answer(&q, 3.924);
    assert!(g.mistake.as_deref().unwrap().contains("sign"), "{g:?}");
    // A right answer gets none, and neither does an unrelated wrong one (2 m/s^2: 49 % from
    // the answer, 59 % from the nearest mistake).
    let right = grade_answer(&q, -3.93);
    assert!(right.passed && right.mistake.is_none(), "{right:?}");
    let other = grade_answer(&q, -2.0);
    assert!(!other.passed && other.mistake.is_none(), "{other:?}");
    // 1.5 % from the mistake's value is outside its 1 % tolerance: no message.
    assert!(grade_answer(&q, -4.905 * 1.015).mistake.is_none());
}

#[cfg(feature = "app")]
#[test]
fn the_window_prints_the_message_the_grading_returns() {
    use rigidlab::app::panels::{grade, grade_message};
    let q = atwood_a();
    let (message, right) = grade_message(&q, &grade(&q, "-4.9"));
    assert!(!right);
    assert!(message.starts_with("not yet: off by"), "{message}");
    assert!(
        message.contains("the pulley's inertia is forgotten"),
        "{message}"
    );
    let (message, right) = grade_message(&q, &grade(&q, "-2"));
    assert!(!right);
    assert!(!message.contains("inertia"), "{message}");
}

/// The parameterized copy's mistake is an expression: at the nominal variant (m_A = 3, m_B = 1,
/// M = 2) it is -(3 - 1) 9.81 / (3 + 1) = -4.905.
#[test]
fn a_mistake_may_be_an_expression_of_the_parameters() {
    let scene = common::load("levels/kinetics/classic_atwood_massive_pulley_param.ron");
    let q = &scene.level.questions[0];
    assert_eq!(q.mistakes.len(), 1);
    common::assert_close!(q.mistakes[0].value, -4.905, 1e-12);
    assert!(grade_answer(q, -4.905).mistake.is_some());
}

/// A one-question level whose answer is 9.81 m/s with the mistakes spliced in.
fn level_with(mistakes: &str) -> String {
    format!(
        r#"Level(
  title: "t",
  statement: "s",
  effects: [gravity],
  world: (duration: 1.0),
  bodies: [(name: "ball", shape: Circle(radius: 0.1))],
  questions: [
    (id: "v", ask: "Speed", unit: "m/s", expected: 9.81, tolerance: 1e-3,
     quantity: Speed("ball"), at: Time(1.0),
     mistakes: [{mistakes}]),
  ],
)"#
    )
}

fn error(text: &str) -> level::LevelError {
    level::parse(Path::new("m.ron"), text).expect_err("the level must be refused")
}

/// Line and column of the first `needle` in `text` (1-based).
fn pos(text: &str, needle: &str) -> (usize, usize) {
    let at = text.find(needle).unwrap();
    let line = text[..at].matches('\n').count() + 1;
    let col = at - text[..at].rfind('\n').map_or(0, |i| i + 1) + 1;
    (line, col)
}

#[test]
fn mistakes_are_validated_where_they_are_written() {
    // Today's levels are unchanged: no `mistakes` is none.
    assert!(common::load("levels/kinematics/free_fall.ron")
        .level
        .questions[0]
        .mistakes
        .is_empty());
    // A mistake 0.5 % from the answer (within the 1 % student tolerance) could never be told
    // apart: refused at its value, the second one's here.
    let text = level_with(r#"(value: 4.905, message: "half"), (value: 9.86, message: "too near")"#);
    let e = error(&text);
    assert!(e.message.contains("mistakes[1]"), "{e}");
    assert!(e.message.contains("could never be told apart"), "{e}");
    assert_eq!((e.line, e.col), pos(&text, "value: 9.86"), "{e}");
    // Not a number, and an empty message.
    let text = level_with(r#"(value: inf, message: "x")"#);
    let e = error(&text);
    assert!(e.message.contains("not a finite number"), "{e}");
    assert_eq!((e.line, e.col), pos(&text, "value: inf"), "{e}");
    let e = error(&level_with(r#"(value: 4.905, message: " ")"#));
    assert!(e.message.contains("empty `message`"), "{e}");
    // A field the format does not have.
    let e = error(&level_with(r#"(value: 4.905, message: "m", hint: "h")"#));
    assert!(e.message.contains("hint"), "{e}");
    // A mistake far enough is accepted.
    let ok = level::parse(
        Path::new("m.ron"),
        &level_with(r#"(value: 4.905, message: "half")"#),
    );
    assert!(ok.is_ok(), "{:?}", ok.err());
}

#[test]
fn check_answer_prints_the_message_and_json_carries_it() {
    let run = |extra: &[&str]| {
        let mut args = vec![
            "check",
            "levels/kinetics/classic_atwood_massive_pulley.ron",
            "--answer",
            "a_A=-4.9",
            "--answer",
            "T_A=17.66",
        ];
        args.extend_from_slice(extra);
        let out = common::rigidlab().args(&args).output().unwrap();
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    let text = run(&[]);
    assert!(
        text.contains("typical mistake: that is (m_A - m_B) g / (m_A + m_B)"),
        "{text}"
    );
    assert_eq!(text.matches("typical mistake").count(), 1, "{text}");
    let v: serde_json::Value = serde_json::from_str(&run(&["--json"])).unwrap();
    let qs = &v["levels"][0]["questions"];
    let a = &qs[0]["student"];
    assert_eq!(a["passed"], false);
    assert!(a["mistake"].as_str().unwrap().contains("inertia"), "{a}");
    // A right answer has no `mistake` field.
    let t = &qs[2]["student"];
    assert_eq!(
        (t["passed"].as_bool(), t.get("mistake")),
        (Some(true), None),
        "{t}"
    );
}

/// The window's question form cannot show `mistakes` nor the student tolerance: rewriting a
/// question through it (a new wording, the same quantity and unit) keeps both; a rewrite to
/// another quantity drops the mistakes, since their values answered the old one.
#[test]
fn a_rewritten_question_keeps_its_mistakes_while_it_asks_the_same_quantity() {
    use rigidlab::editor::{self, Edit};
    let scene = common::load("levels/kinetics/classic_atwood_massive_pulley.ron");
    let mut q = atwood_a();
    q.mistakes.clear();
    q.ask = "Acceleration of block A, y component".into();
    // The form writes 1% as a placeholder; the level's own student tolerance stays.
    let level_student_tolerance = q.student_tolerance;
    q.student_tolerance = level_student_tolerance * 3.0;
    let edit = |q: &QuestionDef| Edit::ReplaceQuestion {
        index: 0,
        question: Box::new(q.clone()),
    };
    let (kept, _) = editor::apply(&scene, &edit(&q)).unwrap();
    assert_eq!(kept.level.questions[0].ask, q.ask);
    assert_eq!(kept.level.questions[0].mistakes, atwood_a().mistakes);
    assert_eq!(
        kept.level.questions[0].student_tolerance,
        level_student_tolerance
    );
    q.quantity = level::Quantity::Ay("B".into());
    let (other, _) = editor::apply(&scene, &edit(&q)).unwrap();
    assert!(other.level.questions[0].mistakes.is_empty());
}
