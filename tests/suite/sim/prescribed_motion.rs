//! Kinematic bodies with a prescribed motion (issue 34): the body follows its motion, a pendulum
//! hung on a uniformly accelerating support swings about tan(phi) = a / g with the period of
//! the field g - a, and an analysis that cannot hold on a shaking support says so.

use rigidlab::level::{motion, parse};
use rigidlab::runner;
use rigidlab::sim::{Options, Simulation};
use std::collections::HashMap;
use std::path::Path;

const G: f64 = 9.81;

fn questions(text: &str) -> Vec<rigidlab::questions::QuestionResult> {
    let scene = parse(Path::new("prescribed.ron"), text).unwrap_or_else(|e| panic!("{e}"));
    runner::run_scene(&scene, &Options::default(), &HashMap::new(), |_| {})
        .unwrap()
        .questions
}

/// A kinematic plate whose center of mass is off its origin (a compound of one box 0.3 m out),
/// shaken and turned: its origin and angle are the motion's at every step's end, and the
/// snapshot's velocity is G's from the motion's rates. Bounds: f32 positions near 1 m round to
/// 6e-8 m; the rates rapier integrates are rounded to f32 too, and over 1000 steps the pose
/// drifts by at most a few hundred such roundings (2e-5 m, 2e-5 rad).
#[test]
fn a_kinematic_body_follows_its_prescribed_motion() {
    for motion_text in [
        "Oscillate(amplitude: (0.2, 0.1), angular_amplitude: 0.5, omega: 7.0, phase: 0.4)",
        "Accelerate(acceleration: (1.5, -0.5), angular: 2.0)",
    ] {
        let text = format!(
            r#"Level(title: "shaker", effects: [gravity, contacts],
            world: (dt: 0.002, substeps: 4, duration: 2.0),
            bodies: [
                (name: "plate", kind: kinematic, position: (0.5, 1.0), angle: 0.2, velocity: (0.1, 0.0),
                 omega: 0.3, shape: Compound(parts: [(shape: Box(width: 0.2, height: 0.1), offset: (0.3, 0.0), angle: 0.0)]),
                 motion: {motion_text}),
            ])"#
        );
        let scene = parse(Path::new("shaker.ron"), &text).unwrap_or_else(|e| panic!("{e}"));
        let def = scene.level.bodies[0].clone();
        let mut sim = Simulation::new(&scene, &Options::default());
        for _ in 0..1000 {
            let s = sim.step().unwrap();
            let b = &s.bodies[0];
            let want = motion::pose_at(&def, s.time);
            let err = ((b.position.x - want.linear.0).powi(2)
                + (b.position.y - want.linear.1).powi(2))
            .sqrt();
            assert!(
                err < 2e-5,
                "{motion_text}: origin off by {err:.2e} m at t = {}",
                s.time
            );
            assert!(
                (b.angle - want.angular).abs() < 2e-5,
                "{motion_text}: angle at t = {}",
                s.time
            );
            // G's velocity: v_O + omega k x (G - O), from the motion's rates at the step's end.
            let rate = motion::rate_at(&def, s.time);
            let arm = b.com - b.position;
            let vg = (
                rate.linear.0 - rate.angular * arm.y,
                rate.linear.1 + rate.angular * arm.x,
            );
            // The arm is read from rapier's pose (its angle within 2e-5 rad, 0.3 m long), and
            // omega is at most 4.3 rad/s here: 3e-5 m/s.
            assert!((b.velocity.x - vg.0).abs() < 3e-5 && (b.velocity.y - vg.1).abs() < 3e-5);
            assert!((b.omega - rate.angular).abs() < 1e-12);
        }
    }
}

/// A 1 kg disc (r = 0.05 m) on a massless link l = 1 m, pinned to a cart accelerating at a. In
/// the cart's frame gravity reads g_eff = g - a: the bob hangs along g_eff, at body angle
/// beta = atan2(-a_x, g + a_y) (its G at pin + l (sin beta, -cos beta)), and swings about it
/// with T = 2 pi sqrt(I_O / (m |g_eff| l)), I_O = m r^2 / 2 + m l^2. Twins: a cart accelerating
/// sideways, one accelerating up and left (|g_eff| = 11.0 m/s^2). Each bob starts 0.08 rad from
/// its equilibrium at rest relative to the cart (which starts at rest): the swing lengthens the
/// period by about 0.08^2 / 16 = 0.04 %. Tolerances: 1e-3 for the period (the swing's 0.04 % and
/// the engine's step), 1e-3 rad for the angle (the middle of a swing in a uniform field is its
/// equilibrium at any amplitude; measured 1e-4 rad at 4 substeps).
#[test]
fn a_pendulum_on_an_accelerating_cart_swings_about_tan_phi_equals_a_over_g() {
    for (ax, ay) in [(3.0f64, 0.0f64), (-2.0, 1.0)] {
        let beta = (-ax).atan2(G + ay);
        let g_eff = ((G + ay).powi(2) + ax * ax).sqrt();
        let i_o = 0.5 * 0.05f64.powi(2) + 1.0;
        let period = 2.0 * std::f64::consts::PI * (i_o / g_eff).sqrt();
        let start = beta + 0.08;
        let (x, y) = (start.sin(), -start.cos());
        let text = format!(
            r#"Level(title: "cart", effects: [gravity, joints],
            world: (dt: 0.002, substeps: 4, duration: 5.0),
            bodies: [
                (name: "cart", kind: kinematic, shape: Box(width: 0.4, height: 0.2),
                 motion: Accelerate(acceleration: ({ax}, {ay}))),
                (name: "bob", shape: Circle(radius: 0.05), mass: 1.0, angle: {start}, position: ({x}, {y})),
            ],
            joints: [(name: "pin", kind: revolute, body1: "cart", body2: "bob", anchor2: (0.0, 1.0))],
            questions: [
                (id: "beta", ask: "equilibrium", unit: "rad", expected: {beta}, tolerance: 1e-3,
                 quantity: EquilibriumAngle("bob"), at: End, why: "symmetric swing"),
                (id: "T", ask: "period", unit: "s", expected: {period}, tolerance: 1e-3,
                 quantity: PendulumPeriod(body: "bob", joint: "pin"), at: End, why: "0.04 % swing"),
            ])"#
        );
        let q = questions(&text);
        for r in &q {
            assert!(r.passed, "a = ({ax}, {ay}): {r:?}");
        }
        // The analyses, to their own precision (1e-6): the equilibrium angle is the
        // linearized mechanism's; the period is the pendulum's exact one in the field g_eff at
        // the 0.08 rad swing, T0 (2 / pi) K(sin(0.04)) (PL-5), K by the arithmetic-geometric
        // mean: K(k) = pi / (2 AGM(1, sqrt(1 - k^2))).
        let angle = q[0].analysis.unwrap_or_else(|| panic!("{:?}", q[0]));
        assert!((angle - beta).abs() < 1e-6, "{:?}", q[0]);
        let k = 0.04f64.sin();
        let (mut x, mut y) = (1.0f64, (1.0 - k * k).sqrt());
        for _ in 0..10 {
            (x, y) = (0.5 * (x + y), (x * y).sqrt());
        }
        let exact = period / x;
        let t = q[1].analysis.unwrap_or_else(|| panic!("{:?}", q[1]));
        assert!(
            (t - exact).abs() < 1e-6 * exact,
            "{t} against {exact}: {:?}",
            q[1]
        );
    }
}

/// A pendulum on a support shaken sideways is driven, not free: neither the fixed-pivot period
/// nor the linearized one applies, and the question says why (graded on the engine alone). The
/// same for its equilibrium angle.
#[test]
fn a_shaken_support_has_no_free_period() {
    let q = questions(
        r#"Level(title: "shaken", effects: [gravity, joints],
        world: (dt: 0.002, substeps: 4, duration: 4.0),
        bodies: [
            (name: "cart", kind: kinematic, shape: Box(width: 0.4, height: 0.2),
             motion: Oscillate(amplitude: (0.02, 0.0), omega: 3.0)),
            (name: "bob", shape: Circle(radius: 0.05), mass: 1.0, angle: 0.1, position: (0.0998334, -0.9950042)),
        ],
        joints: [(name: "pin", kind: revolute, body1: "cart", body2: "bob", anchor2: (0.0, 1.0))],
        questions: [
            (id: "T", ask: "period", unit: "s", expected: 2.0, tolerance: 1.0,
             quantity: PendulumPeriod(body: "bob", joint: "pin"), at: End, why: "read"),
            (id: "beta", ask: "equilibrium", unit: "rad", expected: 0.0, tolerance: 1.0,
             quantity: EquilibriumAngle("bob"), at: End, why: "read"),
        ])"#,
    );
    for r in &q {
        assert_eq!(r.analysis, None, "{r:?}");
        assert!(r.note.contains("prescribed oscillation"), "{}", r.note);
    }
}

/// A prescribed motion on a body that is not kinematic, or an oscillation without a frequency,
/// is refused at its line with how to fix it.
#[test]
fn a_bad_prescribed_motion_is_refused_where_it_is() {
    for (body, want) in [
        (
            r#"(name: "b", shape: Circle(radius: 0.1), motion: Accelerate(acceleration: (1.0, 0.0)))"#,
            "kind: kinematic",
        ),
        (
            r#"(name: "b", kind: kinematic, shape: Circle(radius: 0.1), motion: Oscillate(amplitude: (1.0, 0.0), omega: 0.0))"#,
            "omega",
        ),
    ] {
        let text = format!("Level(title: \"bad\",\n bodies: [\n {body},\n ])");
        let e = parse(Path::new("bad.ron"), &text).unwrap_err();
        assert_eq!(e.line, 3, "{e}");
        assert!(e.to_string().contains(want), "{e}");
    }
}
