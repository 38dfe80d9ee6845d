//! A joint whose anchors do not meet at t = 0 is a located error that says by how much and which
//! body position closes it (issue 13: an angle typed in degrees snapped a body with 1.8e9 N).

use rigidlab::level::parse;
use std::path::Path;

fn pendulum(angle: &str, joint_kind: &str, axis: &str) -> String {
    pendulum_at("-0.5", angle, joint_kind, axis)
}

fn pendulum_at(y: &str, angle: &str, joint_kind: &str, axis: &str) -> String {
    format!(
        r#"Level(
  title: "pendulum", effects: [gravity, joints],
  bodies: [
    (name: "pin", kind: fixed),
    (name: "bar", shape: Box(width: 0.05, height: 1.0), mass: 1.0, position: (0.0, {y}), angle: {angle}),
  ],
  joints: [
    (name: "pivot", kind: {joint_kind}, body1: "pin", body2: "bar", anchor2: (0.0, 0.5), axis: {axis}),
  ],
)"#
    )
}

#[test]
fn anchors_that_meet_are_accepted() {
    parse(
        Path::new("ok.ron"),
        &pendulum("0.0", "revolute", "(1.0, 0.0)"),
    )
    .unwrap();
}

#[test]
fn an_angle_in_degrees_opens_the_pin_and_is_located() {
    // 30 "degrees" as radians: the bar's top anchor is at 0.5 (-sin 30, cos 30) - (0, 0.5).
    let text = pendulum("30.0", "revolute", "(1.0, 0.0)");
    let e = parse(Path::new("levels/bad.ron"), &text).expect_err("the pin is open");
    let shown = e.to_string();
    let line = text.lines().position(|l| l.contains("anchor2")).unwrap() + 1;
    assert_eq!(e.line, line, "{shown}");
    let (s, c) = 30f64.sin_cos();
    let gap = (-0.5 * s).hypot(0.5 * c - 0.5);
    assert!(shown.contains(&format!("{gap:.4} m apart")), "{shown}");
    // Keeping the anchor (0, 0.5) on the turned bar, its position must be -R(30) (0, 0.5).
    assert!(
        shown.contains(&format!("position: ({:.6}, {:.6})", 0.5 * s, -0.5 * c)),
        "{shown}"
    );
    assert!(shown.contains("radians"), "{shown}");
}

#[test]
fn a_slider_may_start_anywhere_along_its_axis_but_not_off_it() {
    // A vertical slide: the bar's anchor 1 m below the pin's is its coordinate, not a gap.
    parse(
        Path::new("ok.ron"),
        &pendulum_at("-1.5", "0.0", "prismatic", "(0.0, 1.0)"),
    )
    .expect("along the axis is the joint's coordinate");
    // A horizontal slide: the same offset is across the axis.
    parse(
        Path::new("bad.ron"),
        &pendulum_at("-1.5", "0.0", "prismatic", "(1.0, 0.0)"),
    )
    .expect_err("across the axis the anchors must meet");
}
