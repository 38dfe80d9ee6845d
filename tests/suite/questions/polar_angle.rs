//! `PolarAngle(body, about)`: the angle of G about a world point, counter-clockwise from +x
//! (issue 41: where a body leaves a cylinder is an angle about its center).

use crate::common;

use common::{parse, run};
use rigidlab::sim::Options;

const G: f64 = 9.81;

/// A disc dropped from rest at G = (x0, y0), read at t about O = (ox, oy): free fall puts G
/// at (x0, y0 - g t^2 / 2), so the angle is atan2(y0 - g t^2/2 - oy, x0 - ox). Tolerance 1e-3:
/// symplectic Euler's fall is short by g h_s t / 2 (h_s = 1/960 s: 1.6e-3 m at 0.3 s), which
/// moves the angle by about 1e-3 rad over a lever of 1 m or more.
fn polar_angle_in_free_fall(x0: f64, y0: f64, o: (f64, f64), t: f64) {
    let want = (y0 - 0.5 * G * t * t - o.1).atan2(x0 - o.0);
    let text = format!(
        r#"Level(title: "polar angle in free fall", effects: [gravity],
        world: (dt: 0.004166666666666667, substeps: 4, duration: 0.5),
        bodies: [(name: "ball", shape: Circle(radius: 0.1), mass: 1.0, position: ({x0}, {y0}))],
        questions: [(id: "phi", ask: "polar angle", unit: "rad", expected: {want}, tolerance: 1e-3,
            quantity: PolarAngle(body: "ball", about: ({ox}, {oy})), at: Time({t}), why: "free fall")])"#,
        ox = o.0,
        oy = o.1,
    );
    let q = run(&parse(&text), &Options::default()).questions.remove(0);
    eprintln!("{} for {want}", q.engine);
    assert!(q.passed, "{q:?}");
}

#[test]
fn polar_angle_of_a_falling_ball() {
    // Above and to the right of O: the first quadrant, 1.0003 rad at 0.3 s.
    polar_angle_in_free_fall(1.0, 2.0, (0.0, 0.0), 0.3);
}

#[test]
fn polar_angle_about_another_point_past_pi() {
    // Left of and below O = (2, 1): the third quadrant, negative (between -pi and -pi/2).
    polar_angle_in_free_fall(-1.0, 0.5, (2.0, 1.0), 0.2);
}
