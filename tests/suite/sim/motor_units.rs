//! A servo's constants are physical (issue 14): stiffness in N m/rad, damping in N m s/rad.
//! A bar pinned at one end, no gravity, held by a servo to its initial pose against a constant
//! couple M: it settles where k q = M, q = M / k, and the motor's torque is -M (statics).

use rigidlab::level::parse;
use rigidlab::runner;
use rigidlab::sim::Options;
use std::collections::HashMap;
use std::path::Path;

#[test]
fn a_servo_sags_torque_over_stiffness() {
    for (k, substeps) in [(100.0, 1), (100.0, 4), (1000.0, 4), (1.0e4, 8)] {
        let (m, c) = (1.0f64, 20.0f64);
        let text = format!(
            r#"Level(title: "servo", effects: [joints, motors],
            world: (dt: 0.001, substeps: {substeps}, duration: 3.0),
            bodies: [(name: "ground", kind: fixed), (name: "bar", shape: Box(width: 1.0, height: 0.05), mass: 1.0, position: (0.5, 0.0))],
            joints: [(name: "pin", kind: revolute, body1: "ground", body2: "bar", anchor2: (-0.5, 0.0),
                      motor: Position(target: 0.0, stiffness: {k}, damping: {c}))],
            loads: [(name: "M", body: "bar", torque: Constant({m}))],
            questions: [
                (id: "q", ask: "sag", unit: "rad", expected: {q}, tolerance: 1e-3, quantity: Angle("bar"), at: End),
                (id: "torque", ask: "servo torque", unit: "N m", expected: {t}, tolerance: 1e-3, quantity: MotorTorque(joint: "pin"), at: End),
            ])"#,
            q = m / k,
            t = -m,
        );
        let scene = parse(Path::new("servo.ron"), &text).unwrap_or_else(|e| panic!("{e}"));
        let r = runner::run_scene(&scene, &Options::default(), &HashMap::new(), |_| {}).unwrap();
        // Settled after 3 s (the slowest, k = 100 with I_O = 1/3 kg m^2 and c = 20: time
        // constant c / k = 0.2 s); measured within 3.2e-5 of M / k.
        for q in &r.questions {
            assert!(q.passed, "k = {k}, {substeps} substeps: {q:?}");
        }
    }
}
