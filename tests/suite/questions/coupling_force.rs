//! `CouplingForce` reads in newtons what the coupling transmits (issue 34): a cable's tension,
//! signed (negative would be a cable that pushes), and a gear mesh's tooth force as a magnitude.
//! Before, a pinion driving a gear read -16 N for a 16 N tooth force: the coupling's multiplier
//! lambda, whose sign follows the terms' ratios.

use crate::common;

use common::{parse, run};
use rigidlab::sim::Options;

/// A 0.1 m pinion (I1 = 0.01 kg m^2) driven by the couple `m` meshing with a 0.2 m gear
/// (I2 = 0.08 kg m^2), both on fixed pins. Rolling of the pitch circles, r1 w1 = -r2 w2, and
/// the tooth force F at each pitch radius (6/1 about each pin): M - F r1 = I1 a1 and
/// F r2 = I2 a2, so a1 = M / (I1 + I2 (r1 / r2)^2) = 33.33 rad/s^2 and
/// F = (M - I1 a1) / r1 = 6.667 N for abs(M) = 1 N m, whichever way M turns the pinion.
fn tooth_force(m: f64) -> rigidlab::questions::QuestionResult {
    let (r1, r2, i1, i2) = (0.1f64, 0.2f64, 0.01f64, 0.08f64);
    let a1 = m.abs() / (i1 + i2 * (r1 / r2).powi(2));
    let f = (m.abs() - i1 * a1) / r1;
    let text = format!(
        r#"Level(title: "gears", effects: [joints],
        world: (dt: 0.004166666666666667, substeps: 4, duration: 0.5),
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
        couplings: [(name: "mesh", terms: [(body: "g1", coordinate: angle, ratio: {r1}), (body: "g2", coordinate: angle, ratio: {r2})], gears: true)],
        questions: [(id: "F", ask: "tooth force", unit: "N", expected: {f}, tolerance: 1e-3,
            quantity: CouplingForce("mesh"), at: Time(0.25), why: "6/1 about each pin")])"#
    );
    run(&parse(&text), &Options::default()).questions.remove(0)
}

/// The tooth force is its magnitude in N, 6.667 N either way the pinion is driven (the
/// coupling holds r1 w1 + r2 w2 = 0 exactly, so 1e-3 is ample: `tests/suite/sim/couplings.rs` holds
/// the same pair's axle loads to it).
#[test]
fn a_gear_mesh_reads_its_tooth_force_in_newtons() {
    for m in [1.0, -1.0] {
        let q = tooth_force(m);
        assert!(q.engine > 0.0, "M = {m}: {} N, a magnitude", q.engine);
        assert!(q.passed, "M = {m}: {} N for {} N", q.engine, q.expected);
    }
}

/// A cable keeps its sign: an Atwood machine of 3 kg and 2 kg (unit ratios on the two y
/// coordinates), T = 2 m1 m2 g / (m1 + m2) = 23.544 N, read positive.
#[test]
fn a_cable_reads_its_tension_positive() {
    let (m1, m2, g) = (3.0f64, 2.0f64, 9.81f64);
    let t = 2.0 * m1 * m2 * g / (m1 + m2);
    let text = format!(
        r#"Level(title: "atwood", effects: [gravity, joints],
        world: (dt: 0.004166666666666667, substeps: 4, duration: 0.5),
        bodies: [
            (name: "A", shape: Circle(radius: 0.05), mass: {m1}, position: (-0.5, 0.0)),
            (name: "B", shape: Circle(radius: 0.05), mass: {m2}, position: (0.5, 0.0)),
        ],
        couplings: [(name: "cable", terms: [(body: "A", coordinate: y, ratio: 1.0), (body: "B", coordinate: y, ratio: 1.0)])],
        questions: [(id: "T", ask: "tension", unit: "N", expected: {t}, tolerance: 1e-3,
            quantity: CouplingForce("cable"), at: Time(0.25), why: "6/1 for each block")])"#
    );
    let q = run(&parse(&text), &Options::default()).questions.remove(0);
    assert!(q.passed, "{} N for {t} N", q.engine);
}
