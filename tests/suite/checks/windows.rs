//! Every check kind takes a `window: (t1, t2)` (issue 14), and `newton_euler` measures a body at
//! rest against the forces that balance on it.
//!
//! The expected values are closed forms: a free fall lasts sqrt(2 h / g) before it meets the
//! ground; a bar held by two loads about its pin has sum M_O = 0 and the pin's reaction equal
//! and opposite to the loads' sum.

use crate::common;

use common::parse as scene;
use rigidlab::checks::CheckResult;
use rigidlab::sim::Options;

fn checks(text: &str, opts: &Options) -> Vec<CheckResult> {
    common::run(&scene(text), opts).checks
}

/// A ball of radius 0.1 m whose bottom starts 2 m above the ground: it falls for
/// t_land = sqrt(2 * 2 / 9.81) = 0.6386 s, then stops on the ground (e = 0) and rests.
fn drop(checks: &str, world: &str) -> String {
    format!(
        r#"Level(title: "drop", effects: [gravity, contacts],
        world: ({world}),
        bodies: [
            (name: "ground", kind: fixed, shape: Box(width: 4.0, height: 0.2), position: (0.0, -0.1)),
            (name: "ball", shape: Circle(radius: 0.1), mass: 1.0, position: (0.0, 2.1)),
        ],
        checks: [{checks}])"#
    )
}

const T_LAND: f64 = 0.638_550_856_814_101; // sqrt(4 / 9.81)

#[test]
fn constant_acceleration_covers_only_the_flight_in_its_window() {
    assert!((T_LAND - (4.0f64 / 9.81).sqrt()).abs() < 1e-12);
    // Symplectic Euler's position error relative to the drop is h / t (constant.rs): with
    // h = 1/240 s and t >= 0.2 s that is 2.1e-2 at most; the tolerance 3e-2 covers it. The
    // landing stops the ball 2 m below where the closed form keeps it falling by t = 1 s
    // (the closed form is 4.9 m down), so the whole run is off by far more than 3e-2.
    let check = |window: &str| {
        format!(
            r#"(kind: constant_acceleration, body: "ball", {window} tolerance: 3e-2, why: "h / t of symplectic Euler")"#
        )
    };
    for world in [
        "dt: 0.016666666666666666, substeps: 4, duration: 1.0",
        "dt: 0.004166666666666667, substeps: 1, duration: 1.0",
        "dt: 0.004166666666666667, substeps: 8, duration: 1.0",
    ] {
        let text = drop(
            &[
                check(""),
                check("window: (0.0, 0.6),"),
                check("window: (0.2, 0.6),"),
            ]
            .join(", "),
            world,
        );
        let r = checks(&text, &Options::default());
        assert!(
            !r[0].passed && r[0].max_rel_error > 0.3,
            "{world}: the whole run includes the landing: {r:?}"
        );
        assert!(
            r[1].passed,
            "{world}: the flight before landing: {:?}",
            r[1]
        );
        // From t1 = 0.2 s the closed form restarts from the state there: still the same fall.
        assert!(r[2].passed, "{world}: the flight from 0.2 s: {:?}", r[2]);
        assert!(r[1].note.contains("window [0, 0.6]"), "{}", r[1].note);
        // Every step end inside [0, 0.6] is compared (the first one sets the initial state).
        let dt: f64 = world[4..world.find(',').unwrap()].parse().unwrap();
        let steps_in = (0.6 / dt + 1e-9).floor() as u64;
        assert_eq!(r[1].samples, steps_in, "{world}");
    }
}

#[test]
fn a_window_with_nothing_to_compare_fails_and_says_so() {
    // The ball meets the ground once, at t_land; a restitution window after it sees no impact.
    let text = drop(
        r#"(kind: restitution, body: "ball", other: "ground", window: (0.8, 1.0), tolerance: 0.1, why: "w")"#,
        "dt: 0.004166666666666667, duration: 1.0",
    );
    let r = checks(&text, &Options::default());
    assert!(!r[0].passed, "{r:?}");
    assert!(
        r[0].note.contains("no impact began inside the window"),
        "{}",
        r[0].note
    );
}

/// A weightless bar 1 m long, pinned at its left end O = (0, 0), held at rest by two loads:
/// P = 100 N down at the tip and Q = 200 N up at its middle. sum M_O = -100 (1) + 200 (0.5) = 0,
/// so the bar stays at rest and the pin pulls with R = -(P + Q) = 100 N down. The force level
/// of the diagram is the largest force, Q = 200 N; sum F and m a_G are zero.
const STATIC_BAR: &str = r#"Level(title: "static bar", effects: [joints],
    world: (dt: 0.016666666666666666, duration: 1.0),
    bodies: [
        (name: "ground", kind: fixed),
        (name: "bar", shape: Box(width: 1.0, height: 0.05), mass: 2.0, position: (0.5, 0.0)),
    ],
    joints: [(name: "O", kind: revolute, body1: "ground", body2: "bar", anchor1: (0.0, 0.0), anchor2: (-0.5, 0.0))],
    loads: [
        (name: "P", body: "bar", point: (0.5, 0.0), force: Constant((0.0, -100.0))),
        (name: "Q", body: "bar", point: (0.0, 0.0), force: Constant((0.0, 200.0))),
    ],
    checks: [(kind: newton_euler, body: "bar", tolerance: 1e-3, why: "statics: the pin's reaction against the loads, in f32")],
    questions: [(id: "R", ask: "pin reaction", unit: "N", expected: -100.0, tolerance: 1e-3,
        quantity: JointReaction(joint: "O", component: Y), at: Time(0.5))],
)"#;

#[test]
fn newton_euler_measures_a_mechanism_at_rest_against_the_forces_that_balance() {
    let report = common::run(&scene(STATIC_BAR), &Options::default());
    let c = &report.checks[0];
    assert!(c.passed, "{c:?}");
    // The scale is the largest force of the diagram, Q = 200 N (rapier's f32 loads: 1e-6).
    assert!(
        (c.scale - 200.0).abs() < 1e-3,
        "scale {} (note {})",
        c.scale,
        c.note
    );
    assert!(report.questions[0].passed, "{:?}", report.questions[0]);
}
