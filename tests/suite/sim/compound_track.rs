//! A compound smooth track as one `Track` (issue 41; level/track.rs, sim/track_shape.rs): the n15
//! user's ramp into a loop (tests/newuser/curved, n15_01a/b), written as pieces, carries a smooth
//! puck without the strike it met where a ramp `Arc` ended on a separate `Segment` floor
//! (docs/known-gaps.md, "A body crossing from one fixed track body to another").
//!
//! The scene: a quarter-circle ramp R = 2 about (0, 2) ridden inside from (-2, 2) down to (0, 0),
//! a floor to (1, 0), a loop R = 0.6 about (1, 0.6) turning 3 pi / 2 from its bottom; a smooth
//! puck r = 0.05 m, m = 0.3 kg released from rest with G at y0 on the ramp (G's path radius on
//! the loop rho = 0.55 m; G's lowest level y = r). Energy (RE-7; the contacts are smooth and the
//! track fixed, so they do no work): v^2 = 2 g (y0 - y), so on the floor (y = r) and at the
//! loop's top (y = 1.2 - r).
//!
//! Tolerance of the speeds, 1e-3 relative, at the library loop's settings (1/4800 s, 4
//! substeps: levels/energy/curve_loop_the_loop.ron):
//! - a ball on an `Arc` keeps its energy within 2.8e-4 over the library loop at these settings
//!   (docs/known-gaps.md); an energy error e shows in v on the floor as e / 2 and at the top as
//!   e / 2 x v_floor^2 / v_top^2 (3.0 for the 3 rho start, 3.7 for 2.75 rho): 5.1e-4 at most;
//! - the soft contact's sag, delta = a / (2 pi 60 Hz)^2 for a contact acceleration a (1.9e-4 m
//!   at the ramp's bottom, a = g + v^2 / 1.95 = 26 m/s^2; 6.9e-5 m on the floor), moves G off
//!   the textbook's height: g delta / v^2 < 1e-4 of v.
//!
//! So 1e-3 holds the textbook with twice the margin, and the joint strike (1% of the energy,
//! 5e-3 of the speed on the floor, measured by the n15 user at every setting) fails it fivefold.
//!
//! The joint itself: the energy E = m v^2 / 2 + m g y_G from just before the ramp's end (G at
//! x = -0.05) to the floor's far end (x = 0.9, after the 7.7 mm hop a strike gives has landed)
//! may change only by the sag's spring energy, at most N delta / 2 = 7.4e-4 J of the 4.9 J of
//! kinetic energy (1.5e-4): the bound is 1e-3 of the kinetic energy on the floor. The separate
//! bodies' build is run beside it and must still exceed it (the gap stays published).

use crate::common;

use common::parse;
use glam::DVec2;
use rigidlab::level::Scene;
use rigidlab::runner;
use rigidlab::sim::Options;
use std::collections::HashMap;

const G: f64 = 9.81;
const M: f64 = 0.3;
const R_PUCK: f64 = 0.05;
/// G's height at the loop's top.
const Y_TOP: f64 = 1.2 - R_PUCK;

/// The n15 track written as `Arc` and `Line` pieces.
const TRACK_ARCS: &str = "Track(start: (-2.0, 2.0), pieces: [Arc(center: (0.0, 2.0), sweep: 1.5707963267948966), Line(to: (1.0, 0.0)), Arc(center: (1.0, 0.6), sweep: 4.71238898038469)])";
/// The same track written from its heading with `Turn`s (down, then turning left).
const TRACK_TURNS: &str = "Track(start: (-2.0, 2.0), heading: -1.5707963267948966, pieces: [Turn(radius: 2.0, angle: 1.5707963267948966), Line(to: (1.0, 0.0)), Turn(radius: 0.6, angle: 4.71238898038469)])";

/// The n15 user's first build: three fixed bodies abutting at (0, 0) and (1, 0).
const SEPARATE: &str = r#"(name: "ramp", kind: fixed, shape: Arc(center: (0.0, 2.0), radius: 2.0, start: 3.141592653589793, end: 4.71238898038469, side: inside)),
    (name: "floor", kind: fixed, shape: Segment(a: (0.0, 0.0), b: (1.0, 0.0))),
    (name: "loop", kind: fixed, shape: Arc(center: (1.0, 0.6), radius: 0.6, start: -1.5707963267948966, end: 3.141592653589793, side: inside))"#;

/// A scene at the library loop's settings with the puck released at `at` (G on the ramp's
/// circle of radius 1.95 about (0, 2)).
fn scene(track_bodies: &str, at: (f64, f64)) -> Scene {
    parse(&format!(
        r#"Level(
  title: "ramp, floor and loop",
  effects: [gravity, contacts],
  world: (dt: 0.00020833333333333335, substeps: 4, duration: 1.6),
  bodies: [
    {track_bodies},
    (name: "puck", shape: Circle(radius: 0.05), mass: 0.3, position: ({}, {})),
  ],
)"#,
        at.0, at.1
    ))
}

fn one_track(shape: &str, at: (f64, f64)) -> Scene {
    scene(
        &format!(r#"(name: "track", kind: fixed, shape: {shape})"#),
        at,
    )
}

/// G and its velocity at every step.
fn path(scene: &Scene) -> Vec<(DVec2, DVec2)> {
    let i = common::body_index(&scene.level, "puck");
    let mut out = Vec::new();
    runner::run_scene(scene, &Options::default(), &HashMap::new(), |s| {
        out.push((s.bodies[i].com, s.bodies[i].velocity));
    })
    .unwrap();
    out
}

/// What the tests read from a run.
#[derive(Debug)]
struct Readings {
    v_floor: f64,
    v_top: f64,
    /// The energy lost from x = -0.05 to x = 0.9, over the kinetic energy on the floor.
    joint_drop: f64,
}

fn read(p: &[(DVec2, DVec2)], y0: f64) -> Readings {
    let energy = |(g, v): (DVec2, DVec2)| 0.5 * M * v.length_squared() + M * G * g.y;
    let first_past = |x: f64| *p.iter().find(|(g, _)| g.x >= x).expect("reaches x");
    let floor = first_past(0.5);
    // The loop's top: the highest G once in the loop (x past its bottom).
    let entered = p
        .iter()
        .position(|(g, _)| g.x >= 1.0)
        .expect("enters the loop");
    let top = p[entered..]
        .iter()
        .max_by(|a, b| a.0.y.total_cmp(&b.0.y))
        .copied()
        .unwrap();
    assert!(
        (top.0.y - Y_TOP).abs() < 1e-3,
        "the puck did not ride to the loop's top: highest G {:?}",
        top.0
    );
    let kinetic_floor = M * G * (y0 - R_PUCK);
    Readings {
        v_floor: floor.1.length(),
        v_top: top.1.length(),
        joint_drop: (energy(first_past(-0.05)) - energy(first_past(0.9))) / kinetic_floor,
    }
}

fn check_track(shape: &str, at: (f64, f64)) -> Readings {
    let y0 = at.1;
    let r = read(&path(&one_track(shape, at)), y0);
    let v_floor = (2.0 * G * (y0 - R_PUCK)).sqrt();
    let v_top = (2.0 * G * (y0 - Y_TOP)).sqrt();
    println!("{shape}\n  from y0 {y0}: {r:?}; textbook v_floor {v_floor}, v_top {v_top}");
    assert!(
        common::rel(r.v_floor, v_floor) < 1e-3,
        "v_floor {} for {v_floor}",
        r.v_floor
    );
    assert!(
        common::rel(r.v_top, v_top) < 1e-3,
        "v_top {} for {v_top}",
        r.v_top
    );
    assert!(r.joint_drop.abs() < 1e-3, "joint: {:e}", r.joint_drop);
    r
}

/// Released from 3 rho above G's lowest level (y0 = 1.7): one `Track` meets the textbook on the
/// floor and at the loop's top, and crosses the ramp's joint with no strike; the same scene
/// as three abutting bodies loses more than the bound there.
#[test]
fn one_track_from_3_rho_crosses_the_joint_without_a_strike() {
    let at = (-1.9267848867997692, 1.7);
    check_track(TRACK_ARCS, at);
    let separate = read(&path(&scene(SEPARATE, at)), at.1);
    println!("separate bodies from 3 rho: {separate:?}");
    assert!(
        separate.joint_drop > 1e-3,
        "the separate bodies' joint strike is gone ({:e}): update docs/known-gaps.md",
        separate.joint_drop
    );
}

/// The twin: released from 2.75 rho (y0 = 1.5625), the track written with `Turn`s from a
/// heading instead of centers.
#[test]
fn one_track_from_2_75_rho_written_with_turns() {
    check_track(TRACK_TURNS, (-1.9002878071492222, 1.5625));
}
