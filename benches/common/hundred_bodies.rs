//! The 100-body scene the benchmarks share (benches/analysis.rs, benches/runner.rs): 50 bars
//! swinging on pins (joints) and 50 balls falling into a box and piling up (contacts, friction),
//! 5 s at 1/60 s with 4 substeps, with scene checks (`work_energy`, `impulse_momentum` and
//! `angular_momentum_fixed_point` about the origin) and 250 per-body checks; and the same scene
//! with every per-body check kind on every body ([`every_kind_ron`]).

#![allow(dead_code)]

use std::fmt::Write;

pub const BARS: usize = 50;
pub const BALLS: usize = 50;

pub fn scene_ron() -> String {
    let mut bodies = String::new();
    let mut joints = String::new();
    let mut checks = String::new();
    // The box for the balls: floor and two walls.
    bodies += r#"(name: "floor", kind: fixed, shape: Box(width: 4.0, height: 0.2), position: (0.0, -0.1)),
        (name: "wall_l", kind: fixed, shape: Box(width: 0.2, height: 6.0), position: (-2.1, 3.0)),
        (name: "wall_r", kind: fixed, shape: Box(width: 0.2, height: 6.0), position: (2.1, 3.0)),
"#;
    for k in 0..BALLS {
        let (x, y) = (-1.6 + 0.36 * (k % 10) as f64, 0.5 + 0.4 * (k / 10) as f64);
        let _ = writeln!(
            bodies,
            r#"(name: "ball{k}", shape: Circle(radius: 0.15), mass: 1.0, position: ({x}, {y}), friction: 0.4),"#
        );
        let _ = writeln!(
            checks,
            r#"(kind: newton_euler, body: "ball{k}", tolerance: 1.0, why: "bench"),"#
        );
        let _ = writeln!(
            checks,
            r#"(kind: kinetic_energy_ic, body: "ball{k}", other: "floor", tolerance: 1.0, why: "bench"),"#
        );
    }
    for k in 0..BARS {
        // Pins 1.5 m apart, far from the box; each bar starts 45 degrees out.
        let px = 10.0 + 1.5 * k as f64;
        let a = std::f64::consts::FRAC_PI_4;
        let (cx, cy) = (px + 0.5 * a.sin(), 5.0 - 0.5 * a.cos());
        let _ = writeln!(
            bodies,
            r#"(name: "pin{k}", kind: fixed, position: ({px}, 5.0)),"#
        );
        let _ = writeln!(
            bodies,
            r#"(name: "bar{k}", shape: Box(width: 0.04, height: 1.0), mass: 2.0, angle: {a}, position: ({cx}, {cy})),"#
        );
        let _ = writeln!(
            joints,
            r#"(name: "j{k}", kind: revolute, body1: "pin{k}", body2: "bar{k}", anchor2: (0.0, 0.5)),"#
        );
        let _ = writeln!(
            checks,
            r#"(kind: newton_euler, body: "bar{k}", tolerance: 1.0, why: "bench"),"#
        );
        let _ = writeln!(
            checks,
            r#"(kind: kinetic_energy_ic, body: "bar{k}", point: ({px}, 5.0), tolerance: 1.0, why: "bench"),"#
        );
        let _ = writeln!(
            checks,
            r#"(kind: angular_momentum_fixed_point, body: "bar{k}", point: ({px}, 5.0), tolerance: 1.0, why: "bench"),"#
        );
    }
    checks += r#"(kind: work_energy, tolerance: 1.0, why: "bench"),
(kind: impulse_momentum, point: (0.0, 0.0), tolerance: 1.0, why: "bench"),
(kind: angular_momentum_fixed_point, point: (0.0, 0.0), tolerance: 1.0, why: "bench"),
"#;
    format!(
        r#"Level(title: "bench: 100 bodies", effects: [gravity, contacts, friction, joints],
        world: (dt: 0.016666666666666666, substeps: 4, duration: 5.0),
        bodies: [{bodies}], joints: [{joints}], checks: [{checks}])"#
    )
}

/// C's level: the scene with every per-body check kind on every body (see the module doc).
pub fn every_kind_ron() -> String {
    let mut checks = String::new();
    let mut add = |body: &str, extra: &str, kinds: &[&str]| {
        for kind in kinds {
            let _ = writeln!(
                checks,
                r#"(kind: {kind}, body: "{body}", {extra}tolerance: 1.0, why: "bench"),"#
            );
        }
    };
    let anywhere = [
        "mass_properties",
        "constant_acceleration",
        "kinetic_energy_g",
        "newton_euler",
        "work_energy",
        "impulse_momentum",
        "restitution",
    ];
    for k in 0..BALLS {
        let ball = format!("ball{k}");
        add(&ball, "", &anywhere);
        add(&ball, r#"other: "floor", "#, &["kinetic_energy_ic"]);
        add(
            &ball,
            "point: (0.0, 0.0), ",
            &["angular_momentum_fixed_point", "newton_euler"],
        );
    }
    for k in 0..BARS {
        let (bar, pin) = (
            format!("bar{k}"),
            format!("point: ({}, 5.0), ", 10.0 + 1.5 * k as f64),
        );
        add(&bar, "", &anywhere);
        add(
            &bar,
            &pin,
            &[
                "kinetic_energy_ic",
                "angular_momentum_fixed_point",
                "newton_euler",
            ],
        );
        add(&bar, "", &["center_of_percussion"]);
    }
    let scene = scene_ron();
    let start = scene.find("checks: [").expect("the scene has checks");
    format!("{}checks: [{checks}])", &scene[..start]).replace(
        "effects: [gravity, contacts, friction, joints]",
        "effects: [gravity, contacts, friction, joints, restitution]",
    )
}
