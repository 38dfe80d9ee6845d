//! A challenge's validation (issue 42, docs/levels.md#challenges): each mistake a teacher can
//! make is refused with the file, line and column of what to fix.

use rigidlab::level;
use std::path::Path;

/// A ball launched at `v`; `challenge` is spliced in as the level's challenge.
fn text(params: &str, challenge: &str) -> String {
    format!(
        r#"Level(
  title: "t",
  parameters: [{params}],
  effects: [gravity],
  world: (duration: 0.5),
  bodies: [
    (name: "ball", shape: Circle(radius: 0.1), velocity: (v, v)),
  ],
  challenge: {challenge},
)"#
    )
}

const V: &str = r#"(name: "v", range: (1.0, 5.0), step: 0.1, unit: "m/s")"#;

fn error(text: &str) -> level::LevelError {
    level::parse(Path::new("c.ron"), text).expect_err("the level must be refused")
}

/// Line and column of the first `needle` in `text` (1-based).
fn pos(text: &str, needle: &str) -> (usize, usize) {
    let at = text.find(needle).unwrap();
    let line = text[..at].matches('\n').count() + 1;
    let col = at - text[..at].rfind('\n').map_or(0, |i| i + 1) + 1;
    (line, col)
}

const GOAL: &str = r#"Reaches(body: "ball", point: (1.0, 0.0), radius: 0.05)"#;

#[test]
fn a_valid_challenge_loads() {
    let t = text(
        V,
        &format!("(control: \"v\", worked: sqrt(g), goal: {GOAL})"),
    );
    let l = level::parse(Path::new("c.ron"), &t).unwrap_or_else(|e| panic!("{e}"));
    assert!((l.level.challenge.unwrap().worked - 9.81f64.sqrt()).abs() < 1e-12);
}

#[test]
fn a_control_that_names_no_parameter_is_located_at_it() {
    let t = text(
        V,
        &format!("(control: \"speed\", worked: 3.0, goal: {GOAL})"),
    );
    let e = error(&t);
    assert!(e.message.contains("\"speed\" names no parameter"), "{e}");
    assert_eq!((e.line, e.col), pos(&t, "control:"), "{e}");
    // A level without parameters: its control can name none either.
    let t = text(V, &format!("(control: \"v\", worked: 3.0, goal: {GOAL})"))
        .replace(&format!("parameters: [{V}],"), "")
        .replace("(v, v)", "(3.0, 3.0)");
    let e = error(&t);
    assert!(e.message.contains("names no parameter"), "{e}");
    assert_eq!((e.line, e.col), pos(&t, "control:"), "{e}");
}

#[test]
fn a_worked_value_out_of_the_range_is_located_at_it() {
    let t = text(V, &format!("(control: \"v\", worked: 7.5, goal: {GOAL})"));
    let e = error(&t);
    assert!(e.message.contains("outside the control's range"), "{e}");
    assert_eq!((e.line, e.col), pos(&t, "worked:"), "{e}");
    // An expression of another parameter out of range at one corner names that corner.
    let params = format!(r#"{V}, (name: "h", range: (0.5, 1.5), step: 0.5, unit: "m")"#);
    let t = text(
        &params,
        &format!("(control: \"v\", worked: sqrt(2*g*h), goal: {GOAL})"),
    );
    let e = error(&t);
    assert!(e.message.contains("h = 1.5 m"), "{e}");
    assert_eq!((e.line, e.col), pos(&t, "worked:"), "{e}");
}

#[test]
fn a_region_with_min_past_max_is_located_at_it() {
    let goal = r#"EndsInside(body: "ball", region: Rect(min: (1.0, 0.0), max: (0.5, 1.0)))"#;
    let t = text(V, &format!("(control: \"v\", worked: 3.0, goal: {goal})"));
    let e = error(&t);
    assert!(e.message.contains("min past max"), "{e}");
    assert_eq!((e.line, e.col), pos(&t, "region:"), "{e}");
}

#[test]
fn a_goal_naming_nothing_is_located_at_it() {
    let goal = r#"Reaches(body: "bal", point: (1.0, 0.0), radius: 0.05)"#;
    let t = text(V, &format!("(control: \"v\", worked: 3.0, goal: {goal})"));
    let e = error(&t);
    assert!(e.message.contains("\"bal\""), "{e}");
    assert_eq!((e.line, e.col), pos(&t, "body: \"bal\""), "{e}");
    let goal = r#"PinFeelsNoBlow(joint: "pin", blow: "blow", tolerance: 0.01)"#;
    let t = text(V, &format!("(control: \"v\", worked: 3.0, goal: {goal})"));
    let e = error(&t);
    assert!(e.message.contains("\"pin\""), "{e}");
}

#[test]
fn a_challenge_variant_saved_without_its_parameters_is_refused() {
    // The window's editor saves the variant on screen, numbers in place of expressions: its
    // control then names no parameter, so the save cannot load back and is refused.
    let scene = crate::common::load("levels/challenges/projectile_into_cup.ron");
    let saved = level::to_ron(&scene.level);
    let e = error(&saved);
    assert!(e.message.contains("names no parameter"), "{e}");
}
