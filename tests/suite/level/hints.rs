//! Hints and the worked solution of a level (issue 42): parsed after the statement, left out of
//! a save when empty, a blank one refused at its line, `{name}` placeholders filled in a level
//! with parameters as the statement's are, and `check` printing the first hint under a wrong
//! answer and the solution when asked.

use crate::common;
use rigidlab::level::{self, LevelError};
use std::path::Path;

/// A falling ball's level with `extra` written after its statement (and `params` as its
/// parameters' list when given).
fn level_with(extra: &str, params: &str) -> String {
    let params = if params.is_empty() {
        String::new()
    } else {
        format!("parameters: [{params}],\n  ")
    };
    format!(
        r#"Level(
  title: "t",
  statement: "A ball falls for 1 s.",
  {extra}
  {params}effects: [gravity],
  world: (duration: 1.0),
  bodies: [(name: "ball", shape: Circle(radius: 0.1), mass: 2.0)],
  questions: [
    (id: "v", ask: "Speed after 1 s", unit: "m/s", expected: 9.81, tolerance: 1e-3,
     quantity: Speed("ball"), at: Time(1.0)),
  ],
)"#
    )
}

fn parse(text: &str) -> Result<level::Scene, LevelError> {
    level::parse(Path::new("h.ron"), text)
}

/// Line and column (1-based) of the first `needle` in `text`.
fn pos(text: &str, needle: &str) -> (usize, usize) {
    let at = text.find(needle).unwrap();
    let line = text[..at].matches('\n').count() + 1;
    (line, at - text[..at].rfind('\n').map_or(0, |i| i + 1) + 1)
}

#[test]
fn hints_and_solution_parse_and_are_left_out_of_a_save_when_empty() {
    let text = level_with(
        r#"hints: ["No force but gravity acts.", "v = g t (PK)."],
  solution: "v = g t
  = 9.81 (1) = 9.81 m/s","#,
        "",
    );
    let l = parse(&text).unwrap().level;
    assert_eq!(l.hints, ["No force but gravity acts.", "v = g t (PK)."]);
    assert_eq!(l.solution.lines().count(), 2, "{:?}", l.solution);
    // A level without them reads as before and saves without them (the editor's saves of
    // today's levels are unchanged).
    let plain = parse(&level_with("", "")).unwrap().level;
    assert!(plain.hints.is_empty() && plain.solution.is_empty());
    let saved = level::to_ron(&plain);
    assert!(
        !saved.contains("hints") && !saved.contains("solution"),
        "{saved}"
    );
    let saved = level::to_ron(&l);
    assert!(
        saved.contains("hints") && saved.contains("solution"),
        "{saved}"
    );
}

#[test]
fn a_blank_hint_or_solution_is_refused_at_its_line() {
    let text = level_with(
        "hints: [\n    \"Gravity alone acts.\",\n    \"  \",\n  ],",
        "",
    );
    let e = parse(&text).unwrap_err();
    assert!(e.message.contains("hint 2 of 2 is empty"), "{e}");
    assert_eq!((e.line, e.col), pos(&text, "\"  \""), "{e}");
    let text = level_with("solution: \" \",", "");
    let e = parse(&text).unwrap_err();
    assert!(e.message.contains("solution is empty"), "{e}");
    assert_eq!((e.line, e.col), pos(&text, "solution:"), "{e}");
    // A field the format does not have: `hint` for `hints`.
    let e = parse(&level_with("hint: [\"x\"],", "")).unwrap_err();
    assert!(e.message.contains("hint"), "{e}");
}

const PARAMS: &str = r#"(name: "m", range: (1.0, 3.0), step: 0.5, unit: "kg"), (name: "t1", list: [1.0, 2.0], unit: "s")"#;

#[test]
fn placeholders_in_hints_and_solution_are_filled_and_unknown_ones_located() {
    let text = level_with(
        r#"hints: ["The {m} ball falls for {t1}."],
  solution: "v = g t = {g} x {t1}","#,
        PARAMS,
    );
    // Nominal: m = 2 kg (the middle of 1 to 3 by 0.5), t1 = 1 s (the list's first).
    let l = parse(&text).unwrap().level;
    assert_eq!(l.hints, ["The 2 kg ball falls for 1 s."]);
    assert_eq!(l.solution, "v = g t = 9.81 m/s^2 x 1 s");
    // A student's variant fills its own values.
    let path = std::env::temp_dir().join(format!("rigidlab-hints-{}.ron", std::process::id()));
    std::fs::write(&path, &text).unwrap();
    let alice = level::load_variant(&path, &level::params::Pick::Indices(vec![4, 1]));
    std::fs::remove_file(&path).unwrap();
    let alice = alice.unwrap().scene.level;
    assert_eq!(alice.hints, ["The 3 kg ball falls for 2 s."]);
    assert_eq!(alice.solution, "v = g t = 9.81 m/s^2 x 2 s");
    // A placeholder that names no parameter, in a hint and in the solution.
    let text = level_with(r#"hints: ["The {mass} ball."],"#, PARAMS);
    let e = parse(&text).unwrap_err();
    assert!(e.message.contains("`{mass}` names no parameter"), "{e}");
    assert_eq!((e.line, e.col), pos(&text, "{mass}"), "{e}");
    let text = level_with(r#"solution: "v = {v0} + g t","#, PARAMS);
    let e = parse(&text).unwrap_err();
    assert_eq!((e.line, e.col), pos(&text, "{v0}"), "{e}");
}

/// `check --answer` with a wrong answer prints the level's first hint under it (and only then),
/// the JSON carries it as the level's `hint`; `--solution` prints the worked solution.
#[test]
fn check_prints_the_first_hint_under_a_wrong_answer_and_the_solution_when_asked() {
    let file = "levels/momentum/bar_struck_at_percussion.ron";
    let l = common::load(file).level;
    assert!(l.hints.len() >= 2 && !l.solution.is_empty());
    let q = &l.questions[0];
    let run = |answer: f64, extra: &[&str]| {
        let answer = format!("{}={answer}", q.id);
        let mut args = vec!["check", file, "--answer", &answer];
        args.extend_from_slice(extra);
        let out = common::rigidlab().args(&args).output().unwrap();
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    // 20 % off is wrong whatever the student tolerance (at most a few %).
    let wrong = run(q.expected * 1.2, &[]);
    assert!(
        wrong.contains(&format!("hint 1: {}", l.hints[0])),
        "{wrong}"
    );
    assert!(!wrong.contains(&l.hints[1]), "only the first hint: {wrong}");
    assert!(!wrong.contains("worked solution"), "{wrong}");
    let right = run(q.expected, &[]);
    assert!(!right.contains("hint 1:"), "{right}");
    let v: serde_json::Value = serde_json::from_str(&run(q.expected * 1.2, &["--json"])).unwrap();
    assert_eq!(v["levels"][0]["hint"].as_str(), Some(l.hints[0].as_str()));
    assert!(v["levels"][0].get("solution").is_none(), "{v}");
    let v: serde_json::Value =
        serde_json::from_str(&run(q.expected, &["--json", "--solution"])).unwrap();
    assert_eq!(
        v["levels"][0]["solution"].as_str(),
        Some(l.solution.as_str())
    );
    assert!(v["levels"][0].get("hint").is_none(), "{v}");
    let shown = run(q.expected, &["--solution"]);
    let first_step = l.solution.lines().next().unwrap().trim();
    assert!(shown.contains("worked solution:"), "{shown}");
    assert!(shown.contains(first_step), "{shown}");
}
