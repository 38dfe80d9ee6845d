//! The reference trajectory (src/analysis/reference.rs) against answers found without it: closed
//! forms (the elliptic-integral pendulum period PL-5, the damped spring-mass, the slider's
//! normal force), a one-coordinate solve written here (the pendulum's angle), and the
//! conservation laws (energy of an undamped mechanism, the constraints themselves).
//!
//! Tolerances: the integration runs at rtol 1e-10, atol 1e-12 over a few seconds, and the
//! projections hold the constraints to 1e-14; the global error of DOP853 at that tolerance stays
//! within about 1e-10 relative for these smooth, non-chaotic motions, so values are held to
//! 1e-8 (relative or absolute in m, rad, N) and energies to 1e-9 relative: two orders of margin,
//! while any wrong mass, lever arm, sign or reaction term moves them by percents.

use glam::DVec2;
use rigidlab::analysis::closed_forms::{elliptic_k, pendulum_period};
use rigidlab::analysis::reference::{Reference, Trajectory};
use rigidlab::level::Level;
use std::f64::consts::PI;
use std::path::Path;

const G: f64 = 9.81;

fn level(ron: &str) -> Level {
    rigidlab::level::parse(Path::new("test.ron"), ron)
        .expect("level parses")
        .level
}

fn reference(ron: &str, times: &[f64]) -> Trajectory {
    Reference::of_level(&level(ron))
        .expect("the scene fits the reference")
        .integrate(times)
        .expect("integrates")
}

fn close(got: f64, want: f64, tol: f64, what: &str) {
    let err = (got - want).abs() / want.abs().max(1.0);
    assert!(
        got.is_finite() && err <= tol,
        "{what}: got {got}, want {want} (err {err:.3e} > {tol:.0e})"
    );
}

/// A bob (m = 1 kg, I_G = 1e-9 kg m^2) on a pin 1 m from it, released from rest level with the
/// pivot (phi0 = 90 degrees from the downward vertical).
fn pendulum_90(i_g: f64) -> String {
    format!(
        r#"Level(title: "t", effects: [gravity, joints],
          bodies: [(name: "ground", kind: fixed),
                   (name: "bob", mass: 1.0, inertia: {i_g:e}, position: (1.0, 0.0))],
          joints: [(name: "pin", kind: revolute, body1: "ground", body2: "bob", anchor2: (-1.0, 0.0))])"#
    )
}

/// phi'' = -(m g l / I_O) sin phi by classical RK4 with h = 1e-4 s: its global error is
/// O(h^4) ~ 1e-16 times the derivatives' size, far below the 1e-8 tolerance.
fn rk4_pendulum(p: f64, phi0: f64, t: f64) -> (f64, f64) {
    let f = |phi: f64, w: f64| (w, -p * phi.sin());
    let steps = (t / 1e-4).round() as usize;
    let h = t / steps as f64;
    let (mut phi, mut w) = (phi0, 0.0);
    for _ in 0..steps {
        let k1 = f(phi, w);
        let k2 = f(phi + 0.5 * h * k1.0, w + 0.5 * h * k1.1);
        let k3 = f(phi + 0.5 * h * k2.0, w + 0.5 * h * k2.1);
        let k4 = f(phi + h * k3.0, w + h * k3.1);
        phi += h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
        w += h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
    }
    (phi, w)
}

/// The angle from the downward vertical of a point at `r` from the pivot at the origin.
fn phi_of(r: DVec2) -> f64 {
    r.x.atan2(-r.y)
}

/// Simple pendulum from 90 degrees. Period (PL-5): T = 4 sqrt(I_O / (m g l)) K(sin 45 deg) with
/// I_O = m l^2 + I_G. After one period the bob is back at rest at 90 degrees: the reference's
/// omega at T, divided by the angular acceleration there (m g l / I_O), is its period error,
/// held to 1e-9 relative. The angle at 0.7 s and 1.9 s is held to 1e-8 rad against the RK4
/// solve of the one-coordinate equation above.
#[test]
fn simple_pendulum_from_90_degrees() {
    let i_o = 1.0 + 1e-9;
    let p = G / i_o;
    let period = pendulum_period(i_o, 1.0, G, 1.0, PI / 2.0);
    let tr = reference(&pendulum_90(1e-9), &[0.7, 1.9, period]);
    for (k, t) in [0.7, 1.9].into_iter().enumerate() {
        let (phi, w) = rk4_pendulum(p, PI / 2.0, t);
        let bob = tr.instants[k].bodies[1];
        close(phi_of(bob.com), phi, 1e-8, &format!("phi({t})"));
        close(bob.omega, w, 1e-8, &format!("omega({t})"));
    }
    let end = tr.instants[2].bodies[1];
    let period_error = end.omega.abs() / p / period;
    eprintln!(
        "simple pendulum: period error {period_error:.2e}, {} evaluations",
        tr.evaluations
    );
    assert!(period_error < 1e-9, "period error {period_error:.3e}");
    close(phi_of(end.com), PI / 2.0, 1e-8, "phi(T)");
    // The constraint held: the bob stays 1 m from the pivot.
    close(end.com.length(), 1.0, 1e-12, "|r|");
}

/// The pin's reaction at the bottom of the swing, reached at T/4 from release at 90 degrees:
/// energy gives I_O w^2 / 2 = m g l, and the bob's G moves on the circle of radius l, so
/// T - m g = m l w^2 (PN-2): T = m g (1 + 2 m l^2 / I_O), which is 3 m g for a particle.
/// The reaction on the bob points up the rod (+y).
#[test]
fn pin_reaction_at_the_bottom_of_the_swing() {
    let i_o = 1.0 + 1e-9;
    let quarter = 0.25 * pendulum_period(i_o, 1.0, G, 1.0, PI / 2.0);
    let tr = reference(&pendulum_90(1e-9), &[quarter]);
    let r = tr.instants[0].reactions[0];
    let tension = G * (1.0 + 2.0 / i_o);
    close(r.force.y, tension, 1e-8, "T");
    close(r.force.x, 0.0, 1e-8, "horizontal reaction");
    close(tension / (3.0 * G), 1.0, 1e-8, "T / 3 m g");
    close(r.couple, 0.0, 1e-12, "a pin has no couple");
}

/// A bar (m = 3 kg, 1.2 m long, I_G = m L^2 / 12 from its Box shape with thickness 0.04 m,
/// I_G = m (L^2 + h^2) / 12) pinned at one end, released at 150 degrees from hanging. d = 0.6 m,
/// I_O = I_G + m d^2. Energy T + V is conserved (no damping): held to 1e-9 relative of m g d
/// at 40 times over 6 s. Period (PL-5): T = 4 sqrt(I_O / (m g d)) K(sin 75 deg); omega at T
/// over the angular acceleration there gives the period error, held to 1e-9.
#[test]
fn physical_pendulum_at_large_amplitude() {
    let (m, l, h) = (3.0, 1.2, 0.04);
    let i_g = m * (l * l + h * h) / 12.0;
    let d = l / 2.0;
    let i_o = i_g + m * d * d;
    let phi0 = 150f64.to_radians();
    // The bar's axis from the pin to G points at phi0 from the downward vertical.
    let g0 = DVec2::new(d * phi0.sin(), -d * phi0.cos());
    let angle = (g0.y).atan2(g0.x);
    let ron = format!(
        r#"Level(title: "t", effects: [gravity, joints],
          bodies: [(name: "ground", kind: fixed),
                   (name: "bar", shape: Box(width: {l}, height: {h}), mass: {m},
                    position: ({}, {}), angle: {angle})],
          joints: [(name: "pin", kind: revolute, body1: "ground", body2: "bar", anchor2: ({}, 0.0))])"#,
        g0.x, g0.y, -d
    );
    let period = pendulum_period(i_o, m, G, d, phi0);
    let mut times: Vec<f64> = (1..=40).map(|k| 0.15 * k as f64).collect();
    times.push(period);
    let tr = reference(&ron, &times);
    let energy = |b: &rigidlab::analysis::reference::BodyMotion| {
        0.5 * m * b.velocity.length_squared() + 0.5 * i_g * b.omega * b.omega + m * G * b.com.y
    };
    let e0 = m * G * g0.y;
    let worst = tr
        .instants
        .iter()
        .map(|x| (energy(&x.bodies[1]) - e0).abs() / (m * G * d))
        .fold(0.0, f64::max);
    eprintln!("physical pendulum: energy error {worst:.2e} of m g d");
    for x in &tr.instants {
        let e = energy(&x.bodies[1]);
        assert!(
            (e - e0).abs() <= 1e-9 * m * G * d,
            "energy at {}: {e} vs {e0}",
            x.t
        );
    }
    let end = tr.instants.last().unwrap().bodies[1];
    let alpha = m * G * d * phi0.sin() / i_o;
    let period_error = end.omega.abs() / alpha / period;
    eprintln!("physical pendulum: period error {period_error:.2e}");
    assert!(period_error < 1e-9, "period error {period_error:.3e}");
    // An independent check of the elliptic form itself: K(sin 75 deg) = 2.7680631453
    // (Abramowitz & Stegun 17.1, modular angle 75 degrees).
    close(
        elliptic_k(75f64.to_radians().sin()),
        2.768_063_145_3,
        1e-10,
        "K",
    );
}

/// A double pendulum of two point-like bobs (1 kg each, I_G = 1e-3 kg m^2) on 1 m links,
/// released from (90, 45) degrees: chaotic, so no closed form, but energy is conserved (no
/// damping, ideal pins): held to 1e-9 relative of m g l over 10 s, and the constraints'
/// drift before each projection stays below 1e-9 m.
#[test]
fn double_pendulum_energy_and_drift() {
    let s45 = 0.5f64.sqrt();
    let ron = format!(
        r#"Level(title: "t", effects: [gravity, joints],
          bodies: [(name: "ground", kind: fixed),
                   (name: "a", mass: 1.0, inertia: 1e-3, position: (1.0, 0.0)),
                   (name: "b", mass: 1.0, inertia: 1e-3, position: ({}, {}))],
          joints: [(name: "p1", kind: revolute, body1: "ground", body2: "a", anchor2: (-1.0, 0.0)),
                   (name: "p2", kind: revolute, body1: "a", body2: "b", anchor2: ({}, {}))])"#,
        1.0 + s45,
        -s45,
        -s45,
        s45
    );
    let times: Vec<f64> = (1..=100).map(|k| 0.1 * k as f64).collect();
    let tr = reference(&ron, &times);
    let energy = |x: &rigidlab::analysis::reference::Instant| -> f64 {
        x.bodies[1..]
            .iter()
            .map(|b| 0.5 * b.velocity.length_squared() + 0.5e-3 * b.omega * b.omega + G * b.com.y)
            .sum()
    };
    let e0 = G * -s45;
    let worst = tr
        .instants
        .iter()
        .map(|x| (energy(x) - e0).abs() / G)
        .fold(0.0, f64::max);
    eprintln!(
        "double pendulum over 10 s: energy error {worst:.2e} of m g l, drift {:.2e} m, {} evaluations",
        tr.drift, tr.evaluations
    );
    for x in &tr.instants {
        assert!(
            (energy(x) - e0).abs() <= 1e-9 * G,
            "energy at {}: {} vs {e0}",
            x.t,
            energy(x)
        );
        // The links keep their length.
        close(x.bodies[1].com.length(), 1.0, 1e-12, "link 1");
        close(
            (x.bodies[2].com - x.bodies[1].com).length(),
            1.0,
            1e-12,
            "link 2",
        );
    }
    assert!(tr.drift < 1e-9, "drift {:.3e} m", tr.drift);
    // It did move far from the start (a swing, not a stuck integration).
    assert!(tr.instants.iter().any(|x| x.bodies[2].com.y < -1.5));
}

/// A damped spring-mass: m = 2 kg, k = 50 N/m, c = 4 N s/m, no gravity, started 0.1 m past the
/// spring's rest length at rest. m x'' + c x' + k x = 0: omega_n = 5, zeta omega_n = c/2m = 1,
/// omega_d = sqrt(24); x(t) = e^{-t} (0.1 cos w_d t + (0.1 / w_d) sin w_d t).
#[test]
fn damped_spring_mass_closed_form() {
    let ron = r#"Level(title: "t", effects: [springs, damping],
          bodies: [(name: "block", shape: Circle(radius: 0.05), mass: 2.0, lock_rotation: true,
                    position: (1.1, 0.0))],
          springs: [(name: "s", body1: "block", point2: (0.0, 0.0), stiffness: 50.0,
                     rest_length: 1.0, damping: 4.0)])"#;
    let times = [0.1, 0.37, 1.0, 2.5];
    let tr = reference(ron, &times);
    let wd = 24f64.sqrt();
    for (x, t) in tr.instants.iter().zip(times) {
        let e = (-t).exp();
        let want = e * (0.1 * (wd * t).cos() + 0.1 / wd * (wd * t).sin());
        close(x.bodies[0].com.x - 1.0, want, 1e-9, &format!("x({t})"));
        // x'(t) = -e^{-t} (0.1 (1 + w_d^2) / w_d) sin w_d t, the derivative of the above.
        let want_rate = -e * 0.1 * (1.0 + wd * wd) / wd * (wd * t).sin();
        close(x.bodies[0].velocity.x, want_rate, 1e-9, &format!("v({t})"));
        close(x.bodies[0].com.y, 0.0, 1e-12, "y");
    }
}

/// A block (m = 2 kg) on a slider along a 30 degree incline from the ground's origin, held by a
/// spring (k = 80 N/m, rest 1 m) from that origin along the axis, started at s0 = 1.2 m at rest.
/// Along the axis m s'' = -k (s - 1) - m g sin 30: s(t) = s_eq + (s0 - s_eq) cos(w t) with
/// w = sqrt(k/m), s_eq = 1 - m g sin 30 / k. Across it the slider's normal force balances
/// gravity's component: N = m g cos 30 on the block, along the axis's normal (-sin 30, cos 30).
#[test]
fn slider_with_a_spring_closed_form() {
    let (m, k, beta): (f64, f64, f64) = (2.0, 80.0, PI / 6.0);
    let u = DVec2::new(beta.cos(), beta.sin());
    let s0 = 1.2;
    let p0 = u * s0;
    let ron = format!(
        r#"Level(title: "t", effects: [gravity, joints, springs],
          bodies: [(name: "ground", kind: fixed),
                   (name: "block", shape: Box(width: 0.2, height: 0.1), mass: {m},
                    position: ({}, {}), angle: {beta})],
          joints: [(name: "rail", kind: prismatic, body1: "ground", body2: "block",
                    axis: ({}, {}))],
          springs: [(name: "s", body1: "block", point2: (0.0, 0.0), stiffness: {k},
                     rest_length: 1.0)])"#,
        p0.x, p0.y, u.x, u.y
    );
    let times = [0.2, 0.55, 1.3];
    let tr = reference(&ron, &times);
    let w = (k / m).sqrt();
    let s_eq = 1.0 - m * G * beta.sin() / k;
    for (x, t) in tr.instants.iter().zip(times) {
        let b = x.bodies[1];
        let want = s_eq + (s0 - s_eq) * (w * t).cos();
        close(b.com.dot(u), want, 1e-9, &format!("s({t})"));
        close(b.com.perp_dot(u), 0.0, 1e-12, "on the line");
        close(b.angle, beta, 1e-12, "no turn");
        let r = x.reactions[0];
        let normal = DVec2::new(-beta.sin(), beta.cos());
        close(r.force.dot(normal), m * G * beta.cos(), 1e-8, "N");
        close(r.force.dot(u), 0.0, 1e-8, "no force along the slide");
    }
}

/// A load moving a free block is integrated exactly, a time table included: F = 4 N along x
/// from 0 to 1 s ramping linearly to 0 at 2 s, on m = 2 kg (no gravity). a = 2 m/s^2 until 1 s,
/// then 2 (2 - t): v(1) = 2, x(1) = 1, and after it v(t) = 4 t - t^2 - 1, so v(2) = 3 m/s and
/// x(2) = 1 + [2 t^2 - t^3 / 3 - t]_1^2 = 1 + 8/3 = 3.6667 m.
#[test]
fn tabulated_load_on_a_free_block() {
    let ron = r#"Level(title: "t", effects: [],
          bodies: [(name: "block", shape: Circle(radius: 0.1), mass: 2.0)],
          loads: [(name: "push", body: "block", force: Table([(0.0, (4.0, 0.0)), (1.0, (4.0, 0.0)), (2.0, (0.0, 0.0))]))])"#;
    let tr = reference(ron, &[2.0]);
    let b = tr.instants[0].bodies[0];
    close(b.velocity.x, 3.0, 1e-9, "v(2)");
    close(b.com.x, 3.0 + 2.0 / 3.0, 1e-9, "x(2)");
}

/// What is outside the reference says so: a blow, a joint limit.
#[test]
fn refuses_impulsive_scenes() {
    let blow = level(
        r#"Level(title: "t", effects: [],
          bodies: [(name: "block", shape: Circle(radius: 0.1), mass: 2.0)],
          events: [Impulse(name: "kick", at: 0.5, body: "block", impulse: (1.0, 0.0))])"#,
    );
    let e = Reference::of_level(&blow).unwrap_err();
    assert!(e.contains("kick"), "{e}");
    let limited = level(
        r#"Level(title: "t", effects: [gravity, joints],
          bodies: [(name: "ground", kind: fixed),
                   (name: "bob", mass: 1.0, inertia: 1e-3, position: (1.0, 0.0))],
          joints: [(name: "pin", kind: revolute, body1: "ground", body2: "bob",
                    anchor2: (-1.0, 0.0), limits: (-0.5, 0.5))])"#,
    );
    let e = Reference::of_level(&limited).unwrap_err();
    assert!(e.contains("limits"), "{e}");
}
