//! The linearized small-oscillation analysis (PL-14, src/analysis/small_oscillations.rs)
//! against hand answers: each scene's expected frequencies are derived in its comment from the
//! textbook's equations, never read from the code under test.
//!
//! Tolerance: 1e-6 relative on frequencies and periods unless said otherwise. The method's own
//! error is the central second difference's, (h/L)^2 = 1e-8 with h = 1e-4 L, plus rounding of
//! about 1e-8 (the module's header); a point bob here carries I_G = 1e-9 kg m^2 against
//! m l^2 = 1 kg m^2, a further 1e-9. 1e-6 leaves two orders of margin and still fails on any
//! wrong mass, stiffness or geometry term (each changes the answers by percents).

use rigidlab::analysis::small_oscillations::{Mechanism, SmallOscillations};
use std::path::Path;

fn modes_of(ron: &str, body: &str) -> Result<SmallOscillations, String> {
    let scene = rigidlab::level::parse(Path::new("test.ron"), ron).expect("level parses");
    let i = scene
        .level
        .bodies
        .iter()
        .position(|b| b.name == body)
        .expect("body");
    Mechanism::of_level(&scene.level, i)?.small_oscillations()
}

fn close(got: f64, want: f64, rel: f64, what: &str) {
    assert!(
        got.is_finite() && (got - want).abs() <= rel * want.abs(),
        "{what}: got {got}, want {want} (rel err {:.3e} > {rel:.0e})",
        (got - want).abs() / want.abs()
    );
}

/// A damped spring-mass: m = 2 kg on a spring k = 50 N/m with a damper c = 4 N s/m, no gravity.
/// m x'' + c x' + k x = 0: omega_n = sqrt(k/m) = 5 rad/s,
/// omega_d = sqrt(k/m - (c/2m)^2) = sqrt(25 - 1) = sqrt(24) = 4.898979 rad/s,
/// damped period 2 pi / sqrt(24) = 1.282550 s. The block is a particle (rotation locked) and the
/// spring is at its rest length at equilibrium, so sideways it has no stiffness: one free motion.
#[test]
fn damped_spring_mass() {
    let s = modes_of(
        r#"Level(title: "t", effects: [springs, damping],
          bodies: [(name: "block", shape: Circle(radius: 0.05), mass: 2.0, lock_rotation: true,
                    position: (1.1, 0.0))],
          springs: [(name: "s", body1: "block", point2: (0.0, 0.0), stiffness: 50.0,
                     rest_length: 1.0, damping: 4.0)])"#,
        "block",
    )
    .unwrap();
    assert_eq!(s.modes.len(), 1, "{s:?}");
    assert_eq!(s.free_motions, 1, "{s:?}");
    let m = &s.modes[0];
    close(m.omega, 5.0, 1e-6, "omega_n");
    close(m.omega_d.unwrap(), 24f64.sqrt(), 1e-6, "omega_d");
    close(
        m.damped_period.unwrap(),
        2.0 * std::f64::consts::PI / 24f64.sqrt(),
        1e-6,
        "T_d",
    );
    // The equilibrium is the spring's rest length: G at (1, 0).
    close(s.equilibrium[0].0.x, 1.0, 1e-9, "x_eq");
    close(s.offset, 0.1, 1e-6, "offset from equilibrium");
}

/// Two springs at 60 degrees holding a block (particle, m = 2 kg, no gravity), both at rest
/// length at equilibrium, k = 100 N/m each, along e1 = (1, 0) and e2 = (cos 60, sin 60).
/// Stiffness K = sum k e e^T. Along the bisector (30 degrees) each spring's stretch is
/// cos 30 of the step: k_eff = 2 k cos^2 30 = 150 N/m; across it k_eff = 2 k sin^2 30 = 50 N/m;
/// K has no cross term between these directions (the bisector is a symmetry axis), so the modes
/// are omega^2 = 50/2 = 25 (omega = 5) and 150/2 = 75 (omega = 8.660254). Started 1 mm along
/// the bisector, all the energy is in the stiff mode.
#[test]
fn two_springs_at_an_angle() {
    let (c, s60) = (0.5f64, 0.75f64.sqrt());
    let (dx, dy) = (0.001 * 0.75f64.sqrt(), 0.001 * 0.5);
    let ron = format!(
        r#"Level(title: "t", effects: [springs],
          bodies: [(name: "block", shape: Circle(radius: 0.05), mass: 2.0, lock_rotation: true,
                    position: ({dx}, {dy}))],
          springs: [(name: "a", body1: "block", point2: (-1.0, 0.0), stiffness: 100.0, rest_length: 1.0),
                    (name: "b", body1: "block", point2: ({}, {}), stiffness: 100.0, rest_length: 1.0)])"#,
        -c, -s60
    );
    let s = modes_of(&ron, "block").unwrap();
    assert_eq!(s.modes.len(), 2, "{s:?}");
    close(s.modes[0].omega, 5.0, 1e-6, "soft mode");
    close(s.modes[1].omega, 75f64.sqrt(), 1e-6, "stiff mode");
    // The soft mode moves across the bisector: its shape is perpendicular to (cos 30, sin 30).
    let shape = s.modes[0].shape[0].0.normalize();
    assert!(
        shape.dot(glam::DVec2::new(0.75f64.sqrt(), 0.5)).abs() < 1e-6,
        "{shape}"
    );
    let excited = s.excited().unwrap();
    close(excited.omega, 75f64.sqrt(), 1e-6, "excited mode");
}

/// A double pendulum of two point bobs m = 1 kg on massless rods l = 1 m (I_G = 1e-9 kg m^2),
/// g = 9.81. Linearized: [2 1; 1 1] theta'' + (g/l) [2 0; 0 1] theta = 0, whose
/// det(K - w^2 M) = 0 gives w^4 - 4 (g/l) w^2 + 2 (g/l)^2 = 0:
/// omega^2 = (g/l)(2 -+ sqrt 2) = 5.746626 and 33.473374 1/s^2.
#[test]
fn double_pendulum_modes() {
    let s = modes_of(
        r#"Level(title: "t", effects: [gravity, joints],
          bodies: [(name: "ground", kind: fixed),
                   (name: "bob1", mass: 1.0, inertia: 1e-9, position: (0.0, -1.0), omega: 0.01),
                   (name: "bob2", mass: 1.0, inertia: 1e-9, position: (0.0, -2.0))],
          joints: [(name: "p1", kind: revolute, body1: "ground", body2: "bob1", anchor2: (0.0, 1.0)),
                   (name: "p2", kind: revolute, body1: "bob1", body2: "bob2", anchor2: (0.0, 1.0))])"#,
        "bob2",
    )
    .unwrap();
    assert_eq!(s.modes.len(), 2, "{s:?}");
    let g = 9.81;
    close(
        s.modes[0].omega.powi(2),
        g * (2.0 - 2f64.sqrt()),
        1e-6,
        "w1^2",
    );
    close(
        s.modes[1].omega.powi(2),
        g * (2.0 + 2f64.sqrt()),
        1e-6,
        "w2^2",
    );
    // The low mode swings both bobs one way (theta2 / theta1 = sqrt 2), the high one opposite.
    let (a1, a2) = (s.modes[0].shape[1].1, s.modes[0].shape[2].1);
    close(a2 / a1, 2f64.sqrt(), 1e-5, "low mode shape");
    let (b1, b2) = (s.modes[1].shape[1].1, s.modes[1].shape[2].1);
    close(b2 / b1, -(2f64.sqrt()), 1e-5, "high mode shape");
}

/// A slender bar (m = 1.5 kg, 0.6 m, I_G = 0.045 kg m^2) hanging from a pin at its end with a
/// torsion spring k_t = 2 N m/rad to the ground, relaxed hanging: I_O theta'' = -(m g d + k_t)
/// theta, omega^2 = (m g d + k_t) / I_O with d = 0.3 m, I_O = 0.045 + 1.5 (0.09) = 0.18:
/// (1.5 (9.81)(0.3) + 2) / 0.18 = 6.4145 / 0.18 = 35.636111 1/s^2.
/// With the spring relaxed 0.3 rad away from hanging, the equilibrium phi solves
/// m g d sin phi = k_t (0.3 - phi) and omega^2 = (m g d cos phi + k_t) / I_O (solved below by
/// Newton on that scalar equation, independently of the module).
#[test]
fn torsion_spring_pendulum() {
    let level = |rest: f64| {
        format!(
            r#"Level(title: "t", effects: [gravity, joints, springs],
              bodies: [(name: "ground", kind: fixed),
                       (name: "bar", shape: Box(width: 0.6, height: 0.02), mass: 1.5, inertia: 0.045,
                        angle: -1.5707963267948966, position: (0.0, -0.3), omega: 0.05)],
              joints: [(name: "pin", kind: revolute, body1: "ground", body2: "bar", anchor2: (-0.3, 0.0))],
              torsion_springs: [(name: "coil", body1: "bar", stiffness: 2.0,
                                 rest_angle: Some({rest}))])"#
        )
    };
    let mgd = 1.5 * 9.81 * 0.3;
    let s = modes_of(&level(-std::f64::consts::FRAC_PI_2), "bar").unwrap();
    assert_eq!(s.modes.len(), 1, "{s:?}");
    close(
        s.modes[0].omega.powi(2),
        (mgd + 2.0) / 0.18,
        1e-6,
        "relaxed",
    );

    let mut phi: f64 = 0.1;
    for _ in 0..50 {
        let f = mgd * phi.sin() - 2.0 * (0.3 - phi);
        phi -= f / (mgd * phi.cos() + 2.0);
    }
    let s = modes_of(&level(-std::f64::consts::FRAC_PI_2 + 0.3), "bar").unwrap();
    close(
        s.modes[0].omega.powi(2),
        (mgd * phi.cos() + 2.0) / 0.18,
        1e-6,
        "preloaded",
    );
    close(
        s.equilibrium[1].1,
        -std::f64::consts::FRAC_PI_2 + phi,
        1e-7,
        "equilibrium angle",
    );
}

/// A pendulum (point bob m = 1 kg, l = 1 m) pinned to a cart of M = 3 kg that slides freely on
/// a horizontal slider. Momentum conservation M x' + m (x' + l theta') = 0 (linearized) and the
/// bob's moment equation give theta'' = -g (M + m) / (M l) theta:
/// omega^2 = 9.81 (4) / 3 = 13.08 1/s^2; the cart's drift is one free motion.
#[test]
fn pendulum_on_a_cart() {
    let s = modes_of(
        r#"Level(title: "t", effects: [gravity, joints],
          bodies: [(name: "ground", kind: fixed),
                   (name: "cart", shape: Box(width: 0.4, height: 0.2), mass: 3.0),
                   (name: "bob", mass: 1.0, inertia: 1e-9, position: (0.0, -1.0), omega: 0.02,
                    velocity: (0.02, 0.0))],
          joints: [(name: "rail", kind: prismatic, body1: "ground", body2: "cart", axis: (1.0, 0.0)),
                   (name: "pin", kind: revolute, body1: "cart", body2: "bob", anchor2: (0.0, 1.0))])"#,
        "bob",
    )
    .unwrap();
    assert_eq!(s.modes.len(), 1, "{s:?}");
    assert_eq!(s.free_motions, 1, "{s:?}");
    close(s.modes[0].omega.powi(2), 9.81 * 4.0 / 3.0, 1e-6, "w^2");
}

/// The amplitude bound: a simple pendulum (l = 1 m) released at theta0 = 0.3 rad has the exact
/// period 4 sqrt(l/g) K(sin(theta0/2)) (PL-5, closed_forms::pendulum_period), longer than
/// 2 pi sqrt(l/g) by theta0^2/16 + 11 theta0^4/3072 = 0.5654 %.
#[test]
fn amplitude_bound_matches_the_exact_period() {
    let s = modes_of(
        r#"Level(title: "t", effects: [gravity, joints],
          bodies: [(name: "ground", kind: fixed),
                   (name: "bob", mass: 1.0, inertia: 1e-9, angle: 0.3,
                    position: (0.29552020666133955, -0.955336489125606))],
          joints: [(name: "pin", kind: revolute, body1: "ground", body2: "bob", anchor2: (0.0, 1.0))])"#,
        "bob",
    )
    .unwrap();
    let t0 = 2.0 * std::f64::consts::PI / 9.81f64.sqrt();
    close(s.modes[0].period, t0, 1e-6, "small-amplitude period");
    let exact = rigidlab::analysis::closed_forms::pendulum_period(1.0, 1.0, 9.81, 1.0, 0.3);
    // The path's energy integral is the exact period for one degree of freedom: 400 midpoints
    // of a smooth integrand (error ~ (pi/800)^2 / 24 ~ 1e-6) and the chart's m(s) from a
    // central difference (1e-10), so 1e-5.
    close(
        s.amplitude_period.unwrap(),
        exact,
        1e-5,
        "period at amplitude",
    );
    close(s.period_error, exact / t0 - 1.0, 1e-3, "period error");
}

/// Where the linearization does not apply, it says why: a block on a spring that falls off a
/// slope of potential (a free body under gravity: no equilibrium), an inverted pendulum held at
/// its top (unstable), a motor.
#[test]
fn not_applicable_with_reasons() {
    let free_fall = modes_of(
        r#"Level(title: "t", effects: [gravity],
          bodies: [(name: "b", shape: Circle(radius: 0.1), mass: 1.0)])"#,
        "b",
    );
    let why = free_fall.unwrap_err();
    assert!(why.contains("equilibrium"), "{why}");

    // A bar balanced upright on a pin with a weak torsion spring (k_t = 1 < m g d = 4.4):
    // the equilibrium found is the hanging one, reached by walking downhill, not the start.
    let s = modes_of(
        r#"Level(title: "t", effects: [gravity, joints],
          bodies: [(name: "ground", kind: fixed),
                   (name: "bar", shape: Box(width: 0.6, height: 0.02), mass: 1.5, inertia: 0.045,
                    angle: 1.5, position: (0.021221, 0.299248))],
          joints: [(name: "pin", kind: revolute, body1: "ground", body2: "bar", anchor2: (-0.3, 0.0))])"#,
        "bar",
    )
    .unwrap();
    // Hanging: omega^2 = m g d / I_O = 4.4145 / 0.18.
    close(
        s.modes[0].omega.powi(2),
        4.4145 / 0.18,
        1e-6,
        "found hanging",
    );
    assert!(
        s.period_error > 0.005,
        "a swing from near the top is not small: {s:?}"
    );

    let motor = rigidlab::level::parse(
        Path::new("t.ron"),
        r#"Level(title: "t", effects: [gravity, joints, motors],
          bodies: [(name: "ground", kind: fixed),
                   (name: "bob", mass: 1.0, inertia: 1e-9, position: (0.0, -1.0))],
          joints: [(name: "pin", kind: revolute, body1: "ground", body2: "bob", anchor2: (0.0, 1.0),
                    motor: Some(Velocity(target: 1.0, max_force: Some(1.0))))])"#,
    )
    .unwrap();
    let why = Mechanism::of_level(&motor.level, 1).unwrap_err();
    assert!(why.contains("motor"), "{why}");
}
