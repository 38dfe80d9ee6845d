//! The impact planner (src/sim/impacts.rs) cuts a rapier call where two bodies are about to
//! touch, so that the contact is made at the touching instant. rapier makes no contact between
//! two bodies a joint joins with its contacts off, which every joint rigidlab builds does, so
//! such a pair must never be planned as an impact. Before 2026-11-27 it was: a four-bar run with
//! all effects on (every body gets its collider, and the links overlap at their pins) had its
//! calls cut as its links closed at the pins, each cut's call at 32 friction sweeps, and cost 5x
//! its declared run for the same motion.

use crate::common;

use rigidlab::level;
use rigidlab::sim::{Options, Simulation};
use std::path::Path;

/// Steps `scene` to its end; the cuts summed over all steps, and how far the named body's mass
/// center moved (a run that never moved proves nothing).
fn cuts_and_travel(scene: &level::Scene, opts: &Options, body: &str) -> (usize, f64) {
    let mut sim = Simulation::new(scene, opts);
    let i = sim.snapshot().body_index(body).expect("the body exists");
    let start = sim.snapshot().bodies[i].position;
    let mut cuts = 0;
    for _ in 0..sim.total_steps() {
        sim.step().unwrap();
        cuts += sim.last_step_cuts;
    }
    let end = sim.snapshot().bodies[i].position;
    (cuts, (end - start).length())
}

#[test]
fn links_a_joint_joins_are_never_cut_for_as_an_impact() {
    let scene = common::load("levels/kinematics/classic_four_bar.ron");
    let all = Options {
        all_effects: true,
        impact_cuts: Some(true),
        ..Default::default()
    };
    let (cuts, moved) = cuts_and_travel(&scene, &all, "coupler");
    assert!(moved > 1e-3, "the coupler moved {moved} m");
    assert_eq!(cuts, 0, "calls cut for pairs rapier never collides");
}

#[test]
fn a_ball_meeting_a_floor_is_cut_for() {
    // The twin: the counter counts. A ball falling 1 cm onto a floor at 2 m/s meets it within
    // its first steps, and the planner cuts a call to make the contact at the touch.
    let text = r#"Level(
  title: "ball onto a floor", effects: [gravity, contacts],
  world: (dt: 0.016666666666666666, substeps: 4, duration: 0.1),
  bodies: [
    (name: "floor", kind: fixed, shape: Box(width: 4.0, height: 1.0), position: (0.0, -0.5)),
    (name: "ball", shape: Circle(radius: 0.1), mass: 1.0, position: (0.0, 0.11), velocity: (0.0, -2.0)),
  ],
)"#;
    let scene = level::parse(Path::new("ball.ron"), text).unwrap_or_else(|e| panic!("{e}"));
    let opts = Options {
        impact_cuts: Some(true),
        ..Default::default()
    };
    let (cuts, moved) = cuts_and_travel(&scene, &opts, "ball");
    assert!(moved > 1e-3, "the ball moved {moved} m");
    assert!(cuts >= 1, "no call was cut for the ball's impact");
}
