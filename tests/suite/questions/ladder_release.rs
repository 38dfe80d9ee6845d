//! When a ladder leaves its wall (issue 13): a uniform ladder of length L on a smooth wall and a
//! smooth floor, released from rest at theta0 to the floor, leaves the wall when
//! sin(theta1) = (2/3) sin(theta0), whatever its k_G (the classic result: the wall force m x_G''
//! vanishes when cos(theta) theta'^2 + sin(theta) theta'' = 0 with the energy integral
//! theta'^2 = (3g/L)(sin theta0 - sin theta)). Its top is then at L sin(theta1), at the time
//!   t1 = integral from theta1 to theta0 of dtheta / sqrt((3g/L)(sin theta0 - sin theta)),
//! computed here with u^2 = sin(theta0) - sin(theta), which removes the end singularity:
//!   t1 = integral from 0 to sqrt(sin(theta0)/3) of 2 du / (cos(theta) sqrt(3g/L)) (Simpson's rule).
//!
//! The run prints, for 60, 70 and 80 degrees and a series of dt, the engine's release height and
//! time against these. A known gap, measured and not hidden: rapier's soft wall contact pushes in
//! bursts as the wall force fades and stops early or late by a few percent, and the error does
//! NOT fall with dt, nor with a 1000 Hz contact (60 degrees: -1.2e-2, +1.6e-4, +2.3e-3, +3.1e-2
//! in height at dt = 1, 0.5, 0.25, 0.1 ms; 70 degrees: -1.7e-3, +1.7e-2, -6.9e-3, +2.9e-2;
//! 80 degrees: +4.4e-3, -9.1e-4, +1.5e-2, +2.8e-2). The test holds the band the engine stays in
//! (height within 3.5%, time within 2.5%), so a change that makes it worse is seen, and says so.

use rigidlab::level;
use rigidlab::runner;
use rigidlab::sim::Options;
use std::collections::HashMap;
use std::path::Path;

const L: f64 = 4.0;
const G: f64 = 9.81;

/// (height of the top, time) at which the ladder leaves the wall, from theory.
fn theory(theta0: f64) -> (f64, f64) {
    let s0 = theta0.sin();
    let s1 = 2.0 / 3.0 * s0;
    let u_max = (s0 - s1).sqrt();
    let n = 20_000;
    let f = |u: f64| 2.0 / ((s0 - u * u).asin().cos() * (3.0 * G / L).sqrt());
    let h = u_max / n as f64;
    let mut sum = f(0.0) + f(u_max);
    for k in 1..n {
        sum += f(k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
    }
    (L * s1, sum * h / 3.0)
}

/// The engine's (height of the top, time) when the wall stops pushing.
fn engine(theta0: f64, dt: f64, contact_hz: Option<f64>) -> (f64, f64) {
    let (c, s) = (theta0.cos(), theta0.sin());
    let hz = contact_hz.map_or(String::new(), |h| format!(", contact_hz: {h}"));
    let text = format!(
        r#"Level(
  title: "ladder", effects: [gravity, contacts],
  world: (dt: {dt}, substeps: 4, duration: 1.2{hz}),
  bodies: [
    (name: "wall", kind: fixed, shape: Segment(a: (-0.02, -1.0), b: (-0.02, 5.0))),
    (name: "floor", kind: fixed, shape: Segment(a: (-1.0, -0.02), b: (6.0, -0.02))),
    (name: "ladder", shape: Capsule(length: {L}, radius: 0.02), mass: 10.0, inertia: 13.333333333333334,
     position: ({x}, {y}), angle: {a}),
  ],
  questions: [
    (id: "h", ask: "top height", unit: "m", expected: 1.0, tolerance: 1.0,
     quantity: PointY(body: "ladder", point: (2.0, 0.0)), at: ContactEnds(body: "ladder", other: "wall")),
    (id: "t", ask: "time", unit: "s", expected: 1.0, tolerance: 1.0,
     quantity: Time, at: ContactEnds(body: "ladder", other: "wall")),
  ],
)"#,
        x = 0.5 * L * c,
        y = 0.5 * L * s,
        a = std::f64::consts::PI - theta0,
    );
    let scene = level::parse(Path::new("ladder.ron"), &text).unwrap_or_else(|e| panic!("{e}"));
    let r = runner::run_scene(&scene, &Options::default(), &HashMap::new(), |_| {}).unwrap();
    (r.questions[0].engine, r.questions[1].engine)
}

#[test]
fn the_ladder_leaves_its_wall_within_the_measured_band_of_the_textbook() {
    for deg in [60.0f64, 70.0, 80.0] {
        let th = deg.to_radians();
        let (h1, t1) = theory(th);
        println!("{deg} deg: theory h1 = {h1:.6} m, t1 = {t1:.6} s");
        for hz in [None, Some(1000.0)] {
            for dt in [1e-3, 5e-4, 2.5e-4, 1e-4] {
                let (h, t) = engine(th, dt, hz);
                assert!(
                    (h / h1 - 1.0).abs() < 3.5e-2,
                    "{deg} deg, dt {dt}: height {h}"
                );
                assert!(
                    (t / t1 - 1.0).abs() < 2.5e-2,
                    "{deg} deg, dt {dt}: time {t}"
                );
                println!(
                    "  dt {dt:.1e} s, contact_hz {hz:?}: h = {h:.5} m ({:+.2e}), t = {t:.5} s ({:+.2e})",
                    h / h1 - 1.0,
                    t / t1 - 1.0
                );
            }
        }
    }
}
