//! Box2D's readings against closed forms (issue 46), as the rapier ones are held
//! (`closed_forms.rs`, `joint_reaction_particle.rs`, `impulse_conversions.rs`): a resting box's
//! normal force, a released pendulum's tension along its swing, an impact's e, a blow through a
//! pin. Expected values come from the textbook, never from Box2D's output.

use crate::common;
use glam::DVec2;
use rigidlab::sim::box2d::Simulation;
use rigidlab::sim::Options;
use rigidlab::snapshot::Snapshot;

const G: f64 = 9.81;

fn box2d(text: &str) -> Simulation {
    Simulation::new(&common::parse(text), &Options::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// A 2 kg box resting on a fixed ground: once settled, the floor pushes m g up, every step.
///
/// Over a step, impulse-momentum on the box gives N dt - m g dt = m (v_y1 - v_y0): the
/// reading must close that balance to f32 rounding (the impulses are f32 sums of 4 calls over
/// the box's 2 points, each rounded to 6e-8 of itself; allowed 1e-5 of m g dt), and once the
/// box is at rest (|dv| below 1e-6 m/s a step) N must be m g to 2e-5 (the balance's 1e-5 plus
/// what it leaves: m dv / dt = 1.2e-4 N at most, 6e-6 of m g). Measured 2026-12-07: 9.0e-8
/// and 1.1e-6.
#[test]
fn a_resting_box_is_pushed_up_by_m_g() {
    let m = 2.0;
    let mut sim = box2d(&format!(
        r#"Level(title: "box on the floor", effects: [gravity, contacts],
  world: (dt: 0.016666666666666666, substeps: 4, duration: 2.0),
  bodies: [
    (name: "ground", kind: fixed, shape: Box(width: 10.0, height: 1.0), position: (0.0, -0.5)),
    (name: "box", shape: Box(width: 1.0, height: 0.5), mass: {m}, position: (0.0, 0.25)),
  ])"#
    ));
    let mut before = sim.snapshot().bodies[1].clone();
    let (mut worst_balance, mut worst_rest, mut resting_steps) = (0.0_f64, 0.0_f64, 0);
    for _ in 0..sim.total_steps() {
        let s = sim.step().expect("runs");
        let n = common::normal_contact_force(s, 1);
        let after = &s.bodies[1];
        let balance =
            (n.y * s.dt - m * G * s.dt - m * (after.velocity.y - before.velocity.y)).abs();
        worst_balance = worst_balance.max(balance / (m * G * s.dt));
        if s.time > 0.5 && (after.velocity.y - before.velocity.y).abs() < 1e-6 {
            worst_rest = worst_rest.max((n.y - m * G).abs() / (m * G));
            resting_steps += 1;
            // One contact with its two corners, the step's four calls summed into them.
            let points: Vec<usize> = s.contacts.iter().map(|c| c.points.len()).collect();
            assert_eq!(points, [2], "t = {:.3}: contacts {points:?}", s.time);
        }
        before = after.clone();
    }
    assert!(
        resting_steps > 60,
        "the box came to rest in {resting_steps} steps only"
    );
    assert!(
        worst_balance < 1e-5,
        "impulse-momentum off by {worst_balance:.2e} of m g dt"
    );
    assert!(
        worst_rest < 2e-5,
        "resting normal force off m g by {worst_rest:.2e}"
    );
}

/// A simple pendulum (1 kg bob, L = 1 m, released from rest at theta0 = 60 degrees): its pin
/// pulls along G -> O with T = m omega^2 L + m g cos(theta) (radial Newton, 6/1), which for the
/// released pendulum is m g (3 cos theta - 2 cos theta0) with energy conserved. The bob is a
/// disc of radius 0.05 m, so I_G / (m L^2) = 1.25e-3: its energy gives
/// omega^2 = 2 m g L (cos theta - cos theta0) / (m L^2 + I_G).
///
/// The reading (the step's impulse over dt, a mean force) is compared with the mean of the
/// closed form at the step's two ends (its mean to O(dt^2): 2e-5 of m g at 1/240 s), over the
/// first swing (1 s). Allowed: 2e-3 of m g, from Box2D's energy drift over that swing (the
/// issue measured 0.75% of the swing energy lost in 10 s at 60 Hz, about 7.5e-4 in 1 s; a
/// relative energy error e_E changes omega^2 L by e_E 2 g (1 - cos theta0) = e_E g, so 7.5e-4
/// of energy is 7.5e-4 of m g), with the soft joint's drift of the anchor (Box2D corrects it
/// at 60 Hz). Measured 2026-12-07: 7.9e-4 of m g.
#[test]
fn a_released_pendulum_pulls_its_pin_with_m_g_3cos_minus_2cos() {
    let (m, l, r) = (1.0, 1.0, 0.05);
    let theta0 = 60f64.to_radians();
    let i_g = 0.5 * m * r * r;
    let (x, y) = (l * theta0.sin(), -l * theta0.cos());
    let mut sim = box2d(&format!(
        r#"Level(title: "pendulum", effects: [gravity, joints],
  world: (dt: 0.004166666666666667, substeps: 4, duration: 1.0),
  bodies: [
    (name: "pin", kind: fixed),
    (name: "bob", shape: Circle(radius: {r}), mass: {m}, position: ({x}, {y})),
  ],
  joints: [(name: "pivot", kind: revolute, body1: "pin", body2: "bob", anchor2: ({}, {}))],
)"#,
        -x, -y
    ));
    let tension = |com: DVec2| {
        let cos = -com.y / com.length();
        let omega2 = 2.0 * m * G * l * (cos - theta0.cos()) / (m * l * l + i_g);
        m * omega2 * l + m * G * cos
    };
    let textbook = |com: DVec2| {
        let cos = -com.y / com.length();
        m * G * (3.0 * cos - 2.0 * theta0.cos())
    };
    let mut before = sim.snapshot().bodies[1].com;
    let (mut worst, mut lowest_swing) = (0.0_f64, 0.0_f64);
    for _ in 0..sim.total_steps() {
        let s = sim.step().expect("runs");
        let com = s.bodies[1].com;
        let toward_pin = (-(0.5 * (com + before))).normalize();
        let read = s.joints[0].impulse_on_body2.dot(toward_pin) / s.dt;
        let theory = 0.5 * (tension(com) + tension(before));
        worst = worst.max((read - theory).abs() / (m * G));
        lowest_swing = lowest_swing.max(textbook(com));
        before = com;
    }
    // The swing went through the bottom, where the textbook's tension is its largest, 2 m g.
    assert!(
        lowest_swing > 1.99 * m * G,
        "the bob never reached the bottom"
    );
    assert!(
        worst < 2e-3,
        "tension off its closed form by {worst:.2e} of m g"
    );
}

/// A ball (e = 0.8, frictionless) dropped from 1 m onto a fixed floor. Box2D bounces a contact
/// at the end of a call to -e times the normal speed it approached with at the call's start;
/// with one substep per step that is the step's: v_y1 = -e v_y0. The reading holds the
/// impulse-momentum balance of that step: J = m (v_y1 - v_y0) + m g dt. f32 velocities and
/// impulses: allowed 1e-6 relative (8 ulps; measured 2026-12-07: e to 1e-7, J to 2.5e-8).
/// (The approach speed is the one at the step's start, up to one step of gravity short of
/// sqrt(2 g h) at touching: a speculative contact bounces before the ball touches; engines.md.)
#[test]
fn an_impact_bounces_with_its_e_and_reads_its_impulse() {
    let (m, e) = (0.5, 0.8);
    let mut sim = box2d(&format!(
        r#"Level(title: "bounce", effects: [gravity, contacts, restitution],
  world: (dt: 0.004166666666666667, substeps: 1, duration: 1.0),
  bodies: [
    (name: "floor", kind: fixed, shape: Segment(a: (-5.0, 0.0), b: (5.0, 0.0))),
    (name: "ball", shape: Circle(radius: 0.1), mass: {m}, restitution: {e}, position: (0.0, 1.1)),
  ])"#
    ));
    let mut before = sim.snapshot().bodies[1].velocity.y;
    let mut bounced = None;
    for _ in 0..sim.total_steps() {
        let s = sim.step().expect("runs");
        let after = s.bodies[1].velocity.y;
        if before < 0.0 && after > 0.0 {
            let j = common::normal_contact_force(s, 1).y * s.dt;
            bounced = Some((before, after, j, s.dt));
            break;
        }
        before = after;
    }
    let (v0, v1, j, dt) = bounced.expect("the ball bounced");
    // It fell about 1 m: the approach speed is near sqrt(2 g h) = 4.43 m/s.
    assert!((v0.abs() - (2.0 * G).sqrt()).abs() < 0.1, "approach {v0}");
    let e_read = -v1 / v0;
    assert!(
        (e_read - e).abs() < 1e-6 * e,
        "e read {e_read}, expected {e}"
    );
    let balance = m * (v1 - v0) + m * G * dt;
    assert!(
        (j - balance).abs() < 1e-6 * balance,
        "impulse {j} against {balance}"
    );
}

/// A blow P = 1 N s, square to a bar pinned at its end O (m = 2 kg, L = 1 m, no gravity): the
/// bar turns at omega = P d / I_O and the pin gives R = m omega L / 2 - P along the blow, zero
/// at the center of percussion d = I_O / (m L / 2) (PL-8, 6/5). The pin's impulse is read over
/// the blow's step; besides R it carries the centripetal pull m omega^2 (L / 2) dt across the
/// bar, whose part along the blow is at most that times the step's turn omega dt (6e-5 N s
/// here), and the soft joint's pull back of its anchor, which drifts by the turn's arc
/// (L / 2) (omega dt)^2 / 2 = 1e-5 m a step: allowed 1e-4 P plus the centripetal part.
/// Measured 2026-12-07: 4e-5 N s at the end, 1e-5 at the center of percussion.
#[test]
fn a_blow_through_a_pin_gives_its_textbook_reaction() {
    let (m, l, h, p) = (2.0, 1.0, 0.05, 1.0);
    let i_o = m * (l * l + h * h) / 12.0 + m * (l / 2.0) * (l / 2.0);
    let percussion = i_o / (m * l / 2.0);
    for d in [l, percussion, 0.25 * l] {
        let mut sim = box2d(&format!(
            r#"Level(title: "struck bar", effects: [joints],
  world: (dt: 0.004166666666666667, substeps: 4, duration: 0.1),
  bodies: [
    (name: "pin", kind: fixed),
    (name: "bar", shape: Box(width: {l}, height: {h}), mass: {m}, position: ({}, 0.0)),
  ],
  joints: [(name: "O", kind: revolute, body1: "pin", body2: "bar", anchor2: ({}, 0.0))],
  events: [Impulse(name: "blow", at: 0.0, body: "bar", point: ({}, 0.0), impulse: (0.0, {p}))],
)"#,
            l / 2.0,
            -l / 2.0,
            d - l / 2.0
        ));
        let s: &Snapshot = sim.step().expect("runs");
        let omega = p * d / i_o;
        let r = m * omega * l / 2.0 - p;
        let read = s.joints[0].impulse_on_body2.y;
        let allowed = 1e-4 * p + m * omega * omega * (l / 2.0) * s.dt * omega * s.dt;
        assert!(
            (read - r).abs() < allowed,
            "d = {d}: pin impulse {read:.5} N s, textbook {r:.5} N s (allowed {allowed:.1e})"
        );
        assert!(
            (s.bodies[1].omega - omega).abs() < 1e-4 * omega,
            "omega {}",
            s.bodies[1].omega
        );
    }
}
