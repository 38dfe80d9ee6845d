//! A velocity motor winding a cable holds its rate: the cable's pull reaches rapier's solver,
//! where the motor answers it (sim/coupling_tension.rs).
//!
//! Until 2026-12-06 the cable (a coupling, projected after each rapier call) pulled the drum
//! back after the motor had brought the bare drum to its rate, by the load's impulse F h
//! through the drum's share of the pair's mobility: the drum settled short of its rate, by
//! F h r^2 / I where joint readings split the step into calls of h = dt / substeps (16.5% on
//! tests/newuser/linkages/n11_09 at 1/240 s and 4 substeps), by more in one call per step. Closed form here: an ideal motor (no force limit) holds omega0 once the
//! start-up has passed; the cable, r dtheta = dx, then carries the load at v = r omega0, with
//! tension T = F (a constant resisting force; the block does not accelerate) and the motor's
//! torque T r (the drum does not accelerate either).

use crate::common;

use rigidlab::sim::{Options, Simulation};

/// Steps `level` at `substeps` to `t` and returns the block's velocity (x, y), the cable's
/// tension (its impulse over the step) and the motor's torque, averaged over the last 0.05 s.
fn haul(level: &str, substeps: usize, t: f64) -> ((f64, f64), f64, f64) {
    let opts = Options {
        substeps: Some(substeps),
        ..Options::default()
    };
    let mut sim = Simulation::new(&common::parse(level), &opts);
    let (mut tension, mut torque, mut n) = (0.0, 0.0, 0.0);
    let mut v = (0.0, 0.0);
    while sim.snapshot().time < t - 1e-9 {
        let s = sim.step().expect("runs");
        if s.time > t - 0.05 {
            tension += s.couplings[0].impulse.abs() / s.dt;
            torque += s.joints[0].motor_impulse.abs() / s.dt;
            n += 1.0;
        }
        let b = &s.bodies[2];
        v = (b.velocity.x, b.velocity.y);
    }
    (v, tension / n, torque / n)
}

/// Tolerance 1e-3 of the closed form: f32 rounding and the settled transient. Before
/// 2026-12-06 the blocks here moved at 0.377 and 0.191 m/s for 1 and 0.6 at 4 and 8 substeps
/// alike (these scenes read no joint, so each step is one rapier call: h = dt).
const TOL: f64 = 1e-3;

fn assert_near(what: &str, value: f64, expected: f64, substeps: usize) {
    let off = (value - expected).abs() / expected.abs();
    assert!(
        off < TOL,
        "{what} at {substeps} substeps: {value} for {expected} ({off:.2e} > {TOL:.0e})"
    );
}

/// A drum (2 kg disc, r = 0.1 m: I = 0.01 kg m^2) on a pin, its motor at 10 rad/s, hauls a
/// 20 kg block against F = 150 N on a smooth plane (top view, no gravity), both started at the
/// cable's speed 1 m/s: v = 1 m/s, T = 150 N, M = 15 N m.
#[test]
fn a_motor_hauling_a_block_by_a_cable_holds_its_rate() {
    let level = r#"Level(title: "haul", effects: [joints, motors],
        world: (dt: 0.004166666666666667, substeps: 4, duration: 1.0),
        bodies: [
          (name: "ground", kind: fixed),
          (name: "drum", shape: Circle(radius: 0.1), mass: 2.0, position: (3.0, 1.0), omega: 10.0),
          (name: "block", shape: Box(width: 0.4, height: 0.2), mass: 20.0, position: (0.0, 0.0), velocity: (1.0, 0.0), lock_rotation: true),
        ],
        joints: [(name: "axle", kind: revolute, body1: "ground", body2: "drum", anchor1: (3.0, 1.0), motor: Velocity(target: 10.0))],
        couplings: [(name: "cable", terms: [(body: "block", coordinate: x, ratio: 1.0), (body: "drum", coordinate: angle, ratio: -0.1)])],
        loads: [(name: "F", body: "block", force: Constant((-150.0, 0.0)))])"#;
    for substeps in [4, 8] {
        let ((vx, _), tension, torque) = haul(level, substeps, 0.5);
        assert_near("v", vx, 1.0, substeps);
        assert_near("T", tension, 150.0, substeps);
        assert_near("M", torque, 15.0, substeps);
    }
}

/// Its twin starts differently: a hoist, everything at rest. A drum (2 kg, r = 0.15 m:
/// I = 0.0225 kg m^2), its motor at 4 rad/s, winds up a hanging 10 kg block: the ideal motor
/// jerks the pair to speed in the first call, then v = r omega0 = 0.6 m/s up, T = m g =
/// 98.1 N, M = m g r = 14.715 N m.
#[test]
fn a_motor_hoisting_a_block_from_rest_holds_its_rate() {
    let level = r#"Level(title: "hoist", effects: [gravity, joints, motors],
        world: (dt: 0.004166666666666667, substeps: 4, duration: 1.0),
        bodies: [
          (name: "ground", kind: fixed),
          (name: "drum", shape: Circle(radius: 0.15), mass: 2.0, position: (0.0, 3.0)),
          (name: "block", shape: Box(width: 0.2, height: 0.2), mass: 10.0, position: (0.15, 0.0), lock_rotation: true),
        ],
        joints: [(name: "axle", kind: revolute, body1: "ground", body2: "drum", anchor1: (0.0, 3.0), motor: Velocity(target: 4.0))],
        couplings: [(name: "cable", terms: [(body: "block", coordinate: y, ratio: 1.0), (body: "drum", coordinate: angle, ratio: -0.15)])])"#;
    for substeps in [4, 8] {
        let ((_, vy), tension, torque) = haul(level, substeps, 0.5);
        assert_near("v", vy, 0.6, substeps);
        assert_near("T", tension, 10.0 * 9.81, substeps);
        assert_near("M", torque, 10.0 * 9.81 * 0.15, substeps);
    }
}
