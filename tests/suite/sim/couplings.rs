//! The ratio constraint (pulleys, cables, gears) and welds created at first contact.

use crate::common;

use common::parse as scene;
use rigidlab::level::parse;
use rigidlab::sim::{Engine, Options, Simulation};
use std::path::Path;

const G: f64 = 9.81;

/// Atwood machine with a massless pulley at height 5 m: the cable is 10 m long when both
/// blocks hang at y = 0, so `y_A + y_B = 0` (the pulley's half turn is a constant).
fn atwood(ma: f64, mb: f64, duration: f64) -> String {
    format!(
        r#"Level(title: "atwood", effects: [gravity, joints],
        world: (dt: 0.016666666666666666, duration: {duration}),
        bodies: [
            (name: "A", shape: Box(width: 0.2, height: 0.2), mass: {ma}, position: (0.5, 0.0), lock_rotation: true),
            (name: "B", shape: Box(width: 0.2, height: 0.2), mass: {mb}, position: (-0.5, 0.0), lock_rotation: true),
        ],
        couplings: [(name: "cable", terms: [(body: "A", coordinate: y, ratio: 1.0), (body: "B", coordinate: y, ratio: 1.0)])])"#
    )
}

#[test]
fn atwood_machine_tension_and_acceleration_match_the_textbook() {
    // a = (mA - mB) g / (mA + mB) (A down), T = 2 mA mB g / (mA + mB).
    let (ma, mb) = (3.0, 1.0);
    let mut sim = Simulation::new(&scene(&atwood(ma, mb, 1.0)), &Options::default());
    let a = (ma - mb) * G / (ma + mb);
    let t_expected = 2.0 * ma * mb * G / (ma + mb);
    for _ in 0..60 {
        let s = sim.step().unwrap();
        let tension = s.couplings[0].impulse / s.dt;
        // The velocity projection is exact for one linear coupling: only f32 rounding remains.
        assert!(
            (tension - t_expected).abs() < 1e-4 * t_expected,
            "T = {tension}, expected {t_expected}"
        );
    }
    let s = sim.snapshot();
    assert!(
        (s.bodies[0].velocity.y + a * s.time).abs() < 1e-4 * a,
        "v_A = {}",
        s.bodies[0].velocity.y
    );
    assert!((s.bodies[1].velocity.y - a * s.time).abs() < 1e-4 * a);
}

#[test]
fn cable_length_holds_to_1e6_over_10_seconds() {
    // Nearly balanced so the blocks stay within a few metres of the origin over 10 s.
    for precision in ["f32", "f64"] {
        let sc = scene(&atwood(1.01, 1.0, 10.0));
        let mut sim: Box<dyn Engine> = match precision {
            "f32" => Box::new(Simulation::new(&sc, &Options::default())),
            _ => Box::new(rigidlab::sim64::Simulation::new(&sc, &Options::default())),
        };
        let mut worst: f64 = 0.0;
        for _ in 0..sim.total_steps() {
            let s = sim.step().unwrap();
            // f64::max would drop a NaN drift: it must be measured.
            let drift = s.couplings[0].drift.abs();
            assert!(
                drift.is_finite(),
                "{precision}: drift {drift} at t = {}",
                s.time
            );
            worst = worst.max(drift);
        }
        let moved = sim.snapshot().bodies[0].com.y.abs();
        assert!(moved > 1.0, "the blocks moved {moved} m");
        // Length 10 m: 1e-6 of it is 1e-5 m.
        assert!(worst < 1e-5, "{precision}: worst drift {worst:.2e} m");
    }
}

/// Atwood machine over a massive pulley, pinned at the origin: a uniform disc M, radius r;
/// blocks A (right) and B (left). The cable does not slip, so y_A - r theta = const (A on the
/// right rises when the pulley turns CCW) and y_B + r theta = const. Textbook:
/// a = (mA - mB) g / (mA + mB + I / r^2), I = M r^2 / 2; T_A = mA (g - a), T_B = mB (g + a);
/// the pulley's diagram, with a_G = 0: R_axle = M g + T_A + T_B (up), when the cable runs
/// `over` it.
fn massive_pulley_atwood(ma: f64, mb: f64, m: f64, r: f64, over: bool, world: &str) -> String {
    let over = if over {
        r#", over: Some("pulley")"#
    } else {
        ""
    };
    format!(
        r#"Level(title: "atwood pulley", effects: [gravity, joints],
        world: ({world}),
        bodies: [
            (name: "ground", kind: fixed),
            (name: "pulley", shape: Circle(radius: {r}), mass: {m}),
            (name: "A", shape: Box(width: 0.2, height: 0.2), mass: {ma}, position: ({r}, -1.0), lock_rotation: true),
            (name: "B", shape: Box(width: 0.2, height: 0.2), mass: {mb}, position: (-{r}, -1.0), lock_rotation: true),
        ],
        joints: [(name: "axle", kind: revolute, body1: "ground", body2: "pulley")],
        couplings: [
            (name: "right", terms: [(body: "A", coordinate: y, ratio: 1.0), (body: "pulley", coordinate: angle, ratio: -{r})]{over}),
            (name: "left", terms: [(body: "B", coordinate: y, ratio: 1.0), (body: "pulley", coordinate: angle, ratio: {r})]{over}),
        ])"#
    )
}

/// Runs the massive-pulley Atwood machine and checks the tensions, the axle's reaction (the
/// pulley's weight alone, or with both strands when the cable runs `over` the pulley), and the
/// motion at the end.
fn check_massive_pulley(ma: f64, mb: f64, m: f64, r: f64, over: bool, world: &str) {
    let text = massive_pulley_atwood(ma, mb, m, r, over, world);
    let mut sim = Simulation::new(&scene(&text), &Options::default());
    let i = 0.5 * m * r * r;
    let a = (ma - mb) * G / (ma + mb + i / (r * r));
    let (ta, tb) = (ma * (G - a), mb * (G + a));
    let axle_expected = if over { m * G + ta + tb } else { m * G };
    for k in 0..sim.total_steps() {
        let s = sim.step().unwrap();
        let (t1, t2) = (s.couplings[0].impulse / s.dt, s.couplings[1].impulse / s.dt);
        // Two couplings share the pulley: Gauss-Seidel converges to 1e-12 per step.
        assert!(
            (t1 - ta).abs() < 1e-3 * ta && (t2 - tb).abs() < 1e-3 * tb,
            "{world}: T_A {t1} vs {ta}, T_B {t2} vs {tb}"
        );
        assert!(s.couplings.iter().all(|c| c.drift.abs() < 1e-5));
        // The strands reach the axle one rapier call after the cable takes them: the first
        // call of the run carries the weight alone; from the second step on the tensions are
        // steady and the reaction is exact up to f32 (1e-4 of it: rapier's joint in f32).
        if k == 0 && over {
            continue;
        }
        let axle = s.joints[0].impulse_on_body2 / s.dt;
        assert!(
            (axle.y - axle_expected).abs() < 1e-4 * axle_expected && axle.x.abs() < 1e-4,
            "{world}, step {}: axle {axle:?}, expected (0, {axle_expected})",
            k + 1
        );
    }
    let s = sim.snapshot();
    let va = s.bodies[2].velocity.y;
    assert!(
        (va + a * s.time).abs() < 1e-3 * a * s.time,
        "v_A {va}, expected {}",
        -a * s.time
    );
    // Rolling without slip on the rim: omega = -v_A / r ... A goes down, the pulley turns CW.
    assert!((s.bodies[1].omega - va / r).abs() < 1e-3 * (va / r).abs());
}

#[test]
fn atwood_machine_with_a_massive_pulley() {
    // Without `over`, a coupling acts only on the coordinates it names: the axle carries M g.
    check_massive_pulley(
        4.0,
        2.0,
        2.0,
        0.25,
        false,
        "dt: 0.016666666666666666, duration: 1.0",
    );
}

#[test]
fn a_cable_over_a_pulley_loads_its_axle_with_both_strands_at_any_settings() {
    // Issue 14's machine: 3 kg and 2 kg over a 2 kg disc of radius 0.1 m. a = 9.81 / 6 =
    // 1.635 m/s^2, T_A = 3 (9.81 - 1.635) = 24.525 N, T_B = 2 (9.81 + 1.635) = 22.89 N,
    // R_axle = 19.62 + 24.525 + 22.89 = 67.035 N.
    for world in [
        "dt: 0.016666666666666666, duration: 1.0",
        "dt: 0.016666666666666666, substeps: 1, duration: 1.0",
        "dt: 0.016666666666666666, substeps: 16, duration: 1.0",
        "dt: 0.004166666666666667, substeps: 4, duration: 1.0",
    ] {
        check_massive_pulley(3.0, 2.0, 2.0, 0.1, true, world);
    }
}

#[test]
fn over_names_the_pulley_and_not_a_body_the_cable_pulls() {
    let text = massive_pulley_atwood(3.0, 2.0, 2.0, 0.1, true, "dt: 0.01, duration: 1.0").replacen(
        r#"over: Some("pulley")"#,
        r#"over: Some("A")"#,
        1,
    );
    let e = parse(Path::new("test.ron"), &text).unwrap_err().to_string();
    assert!(
        e.contains("which one of its x or y terms also pulls"),
        "{e}"
    );
    let text = massive_pulley_atwood(3.0, 2.0, 2.0, 0.1, true, "dt: 0.01, duration: 1.0").replacen(
        r#"over: Some("pulley")"#,
        r#"over: Some("wheel")"#,
        1,
    );
    let e = parse(Path::new("test.ron"), &text).unwrap_err().to_string();
    assert!(e.contains("\"wheel\", which does not exist"), "{e}");
}

#[test]
fn bullet_embeds_in_a_hanging_bar_conserving_angular_momentum_about_the_pin() {
    // Bar: M = 4 kg, L = 1.2 m, pinned at its top; bullet m = 0.05 kg at v = 30 m/s strikes
    // d = 0.9 m below the pin and sticks. H_O = m v d before; after, (I_O + m d^2) omega with
    // I_O = M L^2 / 3 (parallel axis). omega = m v d / (M L^2/3 + m d^2) = 1.35 / 1.9605 = 0.6886 rad/s.
    let text = r#"Level(title: "bullet", effects: [contacts, joints, ccd],
        world: (dt: 0.004166666666666667, duration: 0.2),
        bodies: [
            (name: "pin", kind: fixed),
            (name: "bar", shape: Box(width: 0.1, height: 1.2), mass: 4.0, position: (0.0, -0.6)),
            (name: "bullet", shape: Circle(radius: 0.01), mass: 0.05, inertia: 2e-6, position: (-0.3, -0.9), velocity: (30.0, 0.0)),
        ],
        joints: [(name: "pivot", kind: revolute, body1: "pin", body2: "bar", anchor2: (0.0, 0.6))],
        events: [WeldOnContact(name: "embed", body1: "bar", body2: "bullet")])"#;
    let mut sim = Simulation::new(&scene(text), &Options::default());
    sim.run(|_| {}).unwrap();
    let s = sim.snapshot();
    assert_eq!(s.joints.len(), 2, "the weld was created");
    let (m, v, d, mb, l) = (0.05, 30.0, 0.9, 4.0, 1.2);
    let omega = m * v * d / (mb * l * l / 3.0 + m * d * d);
    let bar = &s.bodies[1];
    // Within 0.2 s the bar turns about 0.14 rad, so gravity is off and omega stays constant.
    // Tolerance 2%: the soft contact and weld resolve the impact over a couple of steps.
    assert!(
        (bar.omega - omega).abs() < 0.02 * omega,
        "omega {} vs {omega}",
        bar.omega
    );
    // The bullet moves with the bar: its velocity is omega x r about the pin.
    let bullet = &s.bodies[2];
    let r = bullet.com; // pin at origin
    let v_rigid = glam::DVec2::new(-bar.omega * r.y, bar.omega * r.x);
    assert!((bullet.velocity - v_rigid).length() < 0.02 * v_rigid.length());
}

#[test]
fn a_coupling_needs_the_joints_effect() {
    let text = atwood(1.0, 1.0, 1.0).replace("effects: [gravity, joints]", "effects: [gravity]");
    let e = parse(Path::new("a.ron"), &text).unwrap_err();
    assert!(e.to_string().contains("add `joints`"), "{e}");
}

/// Two meshing gears on fixed axles 0.3 m apart, no gravity: gear 1 (pitch radius 0.1 m,
/// I1 = 0.01) driven by a couple M = 1 N m, gear 2 (0.2 m, I2 = 0.08). The coupling
/// 0.1 angle1 + 0.2 angle2 = const (they counter-rotate). Gear 1: I1 a1 = M - r1 F; gear 2:
/// I2 a2 = r2 F with r1 a1 = -r2 a2, so a1 = M / (I1 + I2 (r1/r2)^2) = 1 / 0.03 rad/s^2 and the
/// tooth force F = (M - I1 a1) / r1 = 6.667 N, across the line of centers: each axle bears F.
#[test]
fn meshing_gears_load_both_axles_with_the_tooth_force() {
    let (r1, r2, i1, i2, m) = (0.1f64, 0.2f64, 0.01f64, 0.08f64, 1.0f64);
    let a1 = m / (i1 + i2 * (r1 / r2).powi(2));
    let f = (m - i1 * a1) / r1;
    for world in [
        "dt: 0.016666666666666666, duration: 0.5",
        "dt: 0.004166666666666667, substeps: 16, duration: 0.5",
    ] {
        let text = format!(
            r#"Level(title: "gears", effects: [joints],
            world: ({world}),
            bodies: [
                (name: "ground", kind: fixed),
                (name: "g1", shape: Circle(radius: {r1}), mass: 1.0, inertia: {i1}),
                (name: "g2", shape: Circle(radius: {r2}), mass: 2.0, inertia: {i2}, position: (0.3, 0.0)),
            ],
            joints: [
                (name: "a1", kind: revolute, body1: "ground", body2: "g1"),
                (name: "a2", kind: revolute, body1: "ground", body2: "g2", anchor1: (0.3, 0.0)),
            ],
            loads: [(name: "M", body: "g1", torque: Constant({m}))],
            couplings: [(name: "mesh", terms: [(body: "g1", coordinate: angle, ratio: {r1}), (body: "g2", coordinate: angle, ratio: {r2})], gears: true)])"#
        );
        let mut sim = Simulation::new(&scene(&text), &Options::default());
        for k in 0..sim.total_steps() {
            let s = sim.step().unwrap();
            assert!(
                (s.bodies[1].omega - a1 * s.time).abs() < 1e-3 * a1 * s.time,
                "{world}"
            );
            if k == 0 {
                continue; // the tooth force reaches the axles one rapier call late
            }
            // Each axle bears the tooth force: equal and opposite, across the line of centers.
            let (ax1, ax2) = (
                s.joints[0].impulse_on_body2 / s.dt,
                s.joints[1].impulse_on_body2 / s.dt,
            );
            assert!(
                (ax1.length() - f).abs() < 1e-3 * f && (ax2.length() - f).abs() < 1e-3 * f,
                "{world}, step {}: axles {ax1:?} {ax2:?}, expected {f} N each",
                k + 1
            );
            assert!(
                (ax1 + ax2).length() < 1e-3 * f,
                "equal and opposite: {ax1:?} {ax2:?}"
            );
            assert!(
                ax1.x.abs() < 1e-3 * f,
                "across the line of centers: {ax1:?}"
            );
        }
    }
    // The ratios must be the pitch radii.
    let bad = "Level(title: \"g\", effects: [joints], bodies: [(name: \"g1\", shape: Circle(radius: 0.1), mass: 1.0), (name: \"g2\", shape: Circle(radius: 0.2), mass: 1.0, position: (0.5, 0.0))], couplings: [(name: \"mesh\", terms: [(body: \"g1\", coordinate: angle, ratio: 0.1), (body: \"g2\", coordinate: angle, ratio: 0.2)], gears: true)])";
    let e = parse(Path::new("g.ron"), bad).unwrap_err().to_string();
    assert!(e.contains("but their centers are 0.5 m apart"), "{e}");
}
