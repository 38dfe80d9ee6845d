//! The reference trajectory (src/analysis/reference.rs) with rolling contacts and reactions
//! (issue 41): a round body rolling without slip on a fixed face or arc is held as a
//! constraint, so motion questions at a time on a rolling scene get an analysis; the rolling
//! contact's normal and friction forces and a pin's reaction are read from the constraint
//! multipliers; and where the textbook's rolling stops holding (the friction needed exceeds
//! mu N) the note says when, instead of a value. Before, every one of these questions had no
//! analysis: "the reference trajectory models no contact", and a pin on a moving support had
//! neither the fixed-axis formula nor the reference.
//!
//! Tolerances: the reference integrates at rtol 1e-10 and projects onto the constraints, so it
//! meets the closed forms to about 1e-9 relative; 1e-7 leaves room for the RK4 solves here
//! (h = 1e-4 s, global error under 1e-10) and the level's digits. The engine is graded at the
//! questions' own tolerances, which these tests do not judge.

use crate::common;

use common::{parse, run};
use rigidlab::analysis::reference::LABEL;
use rigidlab::questions::QuestionResult;
use rigidlab::sim::Options;
use std::f64::consts::PI;

const G: f64 = 9.81;

fn questions(text: &str) -> Vec<QuestionResult> {
    run(&parse(text), &Options::default()).questions
}

/// The reference's analysis of question `id`, which must be labelled as the reference's.
fn reference(qs: &[QuestionResult], id: &str) -> f64 {
    let q = qs.iter().find(|q| q.id == id).expect("the question");
    assert_eq!(q.analysis_source, LABEL, "{q:?}");
    q.analysis.expect("the reference gives the analysis")
}

fn near(a: f64, want: f64, rel: f64, what: &str) {
    // Printed for docs/analysis-and-checks.md's table (`-- --nocapture`).
    eprintln!("{what}: {:.1e}", (a - want).abs() / want.abs().max(1.0));
    assert!(
        (a - want).abs() <= rel * want.abs().max(1.0),
        "{what}: analysis {a} vs hand answer {want}"
    );
}

/// q'' = f(q) from (q0, w0) by classical RK4 (h = 1e-4 s), solved here without the reference;
/// returns (q, q') at t, or the first time q crosses `stop` (linear between steps).
fn rk4(f: impl Fn(f64) -> f64, q0: f64, w0: f64, t: f64, stop: Option<f64>) -> (f64, f64, f64) {
    let h: f64 = 1e-4;
    let (mut q, mut w, mut now) = (q0, w0, 0.0);
    while now < t - 1e-12 {
        let h = h.min(t - now);
        let k1 = (w, f(q));
        let k2 = (w + 0.5 * h * k1.1, f(q + 0.5 * h * k1.0));
        let k3 = (w + 0.5 * h * k2.1, f(q + 0.5 * h * k2.0));
        let k4 = (w + h * k3.1, f(q + h * k3.0));
        let q1 = q + h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
        w += h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
        if let Some(s) = stop {
            if (q - s) * (q1 - s) <= 0.0 {
                return (s, w, now + h * (s - q) / (q1 - q));
            }
        }
        q = q1;
        now += h;
    }
    (q, w, now)
}

/// The time in a note's "at t = ... s".
fn time_in(note: &str) -> f64 {
    let from = note.find("at t = ").expect("a time in the note") + 7;
    note[from..].split(' ').next().unwrap().parse().unwrap()
}

/// A uniform disc (m = 2 kg, r = 0.25 m, k_G^2 = r^2 / 2) on a fixed slab whose top face
/// rises at theta through the origin, its center `s0` m up the face, moving up it at `v0`
/// (rolling: omega = -v0 / r), read at `t`.
fn incline(theta: f64, mu: f64, s0: f64, v0: f64, t: f64) -> String {
    let (c, s) = (theta.cos(), theta.sin());
    let (r, m) = (0.25, 2.0);
    let center = (s0 * c - r * s, s0 * s + r * c);
    let q = |id: &str, quantity: &str, unit: &str| {
        format!(
            r#"(id: "{id}", ask: "{id}", unit: "{unit}", expected: 1.0, tolerance: 1e9, quantity: {quantity}, at: Time({t}), why: "t"),"#
        )
    };
    format!(
        r#"Level(title: "incline", effects: [gravity, contacts, friction], world: (dt: 0.002, substeps: 4, duration: {dur}),
          bodies: [(name: "slope", kind: fixed, shape: Box(width: 12.0, height: 1.0), angle: {theta},
                    position: ({px}, {py})),
                   (name: "disc", shape: Circle(radius: {r}), mass: {m}, position: ({cx}, {cy}),
                    velocity: ({vx}, {vy}), omega: {w}, friction: {mu})],
          questions: [{q1}{q2}{q3}{q4}])"#,
        dur = t + 0.05,
        px = 0.5 * s,
        py = -0.5 * c,
        cx = center.0,
        cy = center.1,
        vx = v0 * c,
        vy = v0 * s,
        w = -v0 / r,
        q1 = q("x", "X(\"disc\")", "m"),
        q2 = q("speed", "Speed(\"disc\")", "m/s"),
        q3 = q("omega", "Omega(\"disc\")", "rad/s"),
        q4 = q(
            "normal",
            "ContactNormalForce(body: \"disc\", other: \"slope\")",
            "N"
        ),
    )
}

/// Rolling down a 20 degree incline from rest (RK-8 with 6/1): a = g sin(theta) / (1 +
/// k_G^2 / r^2) = 2/3 g sin(theta), s(t) = s0 - a t^2 / 2, v = a t, omega = v / r
/// (counter-clockwise rolling down to the left), N = m g cos(theta). (The friction F = m g
/// sin(theta) k_G^2 / (r^2 + k_G^2) on a straight face keeps its analysis from Newton-Euler on
/// the engine's motion, `ContactForceFrom`; the bowl below reads it on the reference.)
#[test]
fn a_disc_rolling_down_an_incline_reads_the_reference() {
    let th = 20f64.to_radians();
    let t = 0.8;
    let qs = questions(&incline(th, 0.5, 2.0, 0.0, t));
    let a = 2.0 / 3.0 * G * th.sin();
    let s = 2.0 - 0.5 * a * t * t;
    near(
        reference(&qs, "x"),
        s * th.cos() - 0.25 * th.sin(),
        1e-7,
        "x",
    );
    near(reference(&qs, "speed"), a * t, 1e-7, "speed");
    near(reference(&qs, "omega"), a * t / 0.25, 1e-7, "omega");
    near(reference(&qs, "normal"), 2.0 * G * th.cos(), 1e-7, "N");
}

/// Its twin starts rolling up the incline at 1.5 m/s: s(t) = s0 + v0 t - a t^2 / 2, v = v0 -
/// a t (still going up at 0.5 s: v = 0.382 m/s), omega = -v / r, N = m g cos(theta).
#[test]
fn a_disc_rolling_up_an_incline_reads_the_reference() {
    let th = 20f64.to_radians();
    let (t, v0) = (0.5, 1.5);
    let qs = questions(&incline(th, 0.5, 1.0, v0, t));
    let a = 2.0 / 3.0 * G * th.sin();
    let s = 1.0 + v0 * t - 0.5 * a * t * t;
    near(
        reference(&qs, "x"),
        s * th.cos() - 0.25 * th.sin(),
        1e-7,
        "x",
    );
    near(reference(&qs, "speed"), v0 - a * t, 1e-7, "speed");
    near(reference(&qs, "omega"), -(v0 - a * t) / 0.25, 1e-7, "omega");
    near(reference(&qs, "normal"), 2.0 * G * th.cos(), 1e-7, "N");
}

/// On a 30 degree incline rolling needs F / N = tan(30) k_G^2 / (r^2 + k_G^2) = tan(30) / 3 =
/// 0.1925 from the start; with mu = 0.1 the disc slides: the reference refuses, saying when
/// and how much friction rolling would need, and gives no value.
#[test]
fn a_disc_that_needs_more_friction_than_mu_n_is_refused_with_the_time() {
    let qs = questions(&incline(30f64.to_radians(), 0.1, 2.0, 0.0, 0.5));
    let q = qs.iter().find(|q| q.id == "speed").unwrap();
    assert_eq!(q.analysis, None, "{q:?}");
    assert!(q.analysis_source.is_empty());
    let want = format!(
        "needs |F|/N = {:.4}, mu = 0.1",
        30f64.to_radians().tan() / 3.0
    );
    assert!(
        q.note.contains("would slip on \"slope\"") && q.note.contains(&want),
        "{}",
        q.note
    );
    assert_eq!(time_in(&q.note), 0.0, "{}", q.note);
}

/// A disc (m = 1 kg, r = 0.1 m) in a circular bowl of R = 1 m: its center moves on rho = R - r
/// = 0.9 m, rolling gives rho phi' = r w and (1 + k_G^2 / r^2) rho phi'' = -g sin(phi) (RE-7,
/// RK-8): a pendulum of length 1.5 rho, small-oscillation period 2 pi sqrt((R - r)(1 +
/// k_G^2 / r^2) / g) = 2.3309 s. Along the path (PN-2): N = m g cos(phi) + m rho phi'^2 and
/// the tangential equation m rho phi'' = -m g sin(phi) + F gives F = m g sin(phi) / 3.
fn bowl(phi0: f64, v0: f64, t: f64) -> (Vec<QuestionResult>, f64, f64) {
    let rho = 0.9;
    let q = |id: &str, quantity: &str, unit: &str| {
        format!(
            r#"(id: "{id}", ask: "{id}", unit: "{unit}", expected: 1.0, tolerance: 1e9, quantity: {quantity}, at: Time({t}), why: "t"),"#
        )
    };
    let qs = questions(&format!(
        r#"Level(title: "bowl", effects: [gravity, contacts, friction], world: (dt: 0.001, substeps: 4, duration: {dur}),
          bodies: [(name: "bowl", kind: fixed, shape: Arc(center: (0.0, 1.0), radius: 1.0, start: {start}, end: {end}, side: inside)),
                   (name: "disc", shape: Circle(radius: 0.1), mass: 1.0, position: ({cx}, {cy}),
                    velocity: ({vx}, {vy}), omega: {w}, friction: 0.8)],
          questions: [{q1}{q2}{q3}{q4}])"#,
        dur = t + 0.05,
        start = PI,
        end = 2.0 * PI,
        cx = rho * phi0.sin(),
        cy = 1.0 - rho * phi0.cos(),
        vx = v0 * phi0.cos(),
        vy = v0 * phi0.sin(),
        w = -v0 / 0.1,
        q1 = q("speed", "Speed(\"disc\")", "m/s"),
        q2 = q("y", "Y(\"disc\")", "m"),
        q3 = q(
            "normal",
            "ContactNormalForce(body: \"disc\", other: \"bowl\")",
            "N"
        ),
        q4 = q(
            "friction",
            "ContactForceFrom(body: \"disc\", other: \"bowl\", component: Friction)",
            "N"
        ),
    ));
    let (phi, w, _) = rk4(|p| -G * p.sin() / (1.5 * rho), phi0, v0 / rho, t, None);
    (qs, phi, w)
}

fn check_bowl(phi0: f64, v0: f64, t: f64) {
    let rho = 0.9;
    let (qs, phi, w) = bowl(phi0, v0, t);
    let (speed, y) = (reference(&qs, "speed"), reference(&qs, "y"));
    near(speed, rho * w.abs(), 1e-7, "speed");
    near(y, 1.0 - rho * phi.cos(), 1e-7, "y");
    // Energy (RE-7): 3/4 m v^2 - 3/4 m v0^2 = m g (y0 - y), from the reference's own y and v.
    let y0 = 1.0 - rho * phi0.cos();
    near(
        0.75 * (speed * speed - v0 * v0),
        G * (y0 - y),
        1e-8,
        "energy",
    );
    near(
        reference(&qs, "normal"),
        G * phi.cos() + rho * w * w,
        1e-7,
        "N",
    );
    near(
        reference(&qs, "friction"),
        G * phi.sin().abs() / 3.0,
        1e-7,
        "F",
    );
}

/// Released from rest at 0.3 rad, read at 0.4 s (before the bottom, T/4 ~ 0.58 s).
#[test]
fn a_disc_rolling_in_a_bowl_reads_the_reference() {
    check_bowl(0.3, 0.0, 0.4);
}

/// Its twin starts at the bottom rolling at 0.8 m/s, read at 0.9 s (past its turning point).
#[test]
fn a_disc_rolling_from_the_bottom_of_a_bowl_reads_the_reference() {
    check_bowl(0.0, 0.8, 0.9);
}

/// A disc (r = 0.1 m) rolling over a hump, the outside of R = 1 m (rho = 1.1 m), from 0.1 rad
/// off the top at rest: (3/2) rho phi'' = g sin(phi), and energy gives rho phi'^2 = 4/3 g
/// (cos(phi0) - cos(phi)). Then N = m g cos(phi) - m rho phi'^2 and F = m g sin(phi) / 3, so
/// F / N = sin(phi) / (7 cos(phi) - 4 cos(phi0)): it reaches mu = 0.5 before N reaches zero
/// (cos(phi) = 4/7 cos(phi0)). The slip angle from that equation (bisection), its time from
/// RK4; the reference reads the question at 0.2 s (before) and refuses at 1.2 s (after).
#[test]
fn a_disc_slips_off_a_hump_when_its_friction_runs_out() {
    let (rho, phi0, mu) = (1.1, 0.1f64, 0.5);
    let ratio = |p: f64| p.sin() / (7.0 * p.cos() - 4.0 * phi0.cos());
    let (mut lo, mut hi) = (phi0, (4.0 / 7.0 * phi0.cos()).acos());
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if ratio(mid) < mu {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let (_, _, t_slip) = rk4(|p| G * p.sin() / (1.5 * rho), phi0, 0.0, 5.0, Some(lo));
    let level = |t: f64| {
        format!(
            r#"Level(title: "hump", effects: [gravity, contacts, friction], world: (dt: 0.001, substeps: 4, duration: 1.3),
              bodies: [(name: "hump", kind: fixed, shape: Arc(center: (0.0, 0.0), radius: 1.0, start: 0.0, end: {pi}, side: outside)),
                       (name: "disc", shape: Circle(radius: 0.1), mass: 1.0, position: ({cx}, {cy}), friction: {mu})],
              questions: [(id: "x", ask: "x", unit: "m", expected: 0.1, tolerance: 1e9, quantity: X("disc"), at: Time({t}), why: "t")])"#,
            pi = PI,
            cx = -rho * phi0.sin(),
            cy = rho * phi0.cos(),
        )
    };
    let before = questions(&level(0.2));
    let (phi, _, _) = rk4(|p| G * p.sin() / (1.5 * rho), phi0, 0.0, 0.2, None);
    near(
        reference(&before, "x"),
        -rho * phi.sin(),
        1e-7,
        "x before the slip",
    );
    let after = questions(&level(1.2));
    let q = &after[0];
    assert_eq!(q.analysis, None, "{q:?}");
    assert!(q.note.contains("would slip on \"hump\""), "{}", q.note);
    eprintln!("slip time: {:.1e} s off", (time_in(&q.note) - t_slip).abs());
    assert!(
        (time_in(&q.note) - t_slip).abs() < 1e-4,
        "slip at {} s, hand answer {t_slip} s: {}",
        time_in(&q.note),
        q.note
    );
}

/// A uniform bar (m = 2 kg, L = 1 m, I_G = m L^2 / 12) pinned at its end to a kinematic cart
/// moving at a constant `cart` velocity (an inertial frame: the same reactions as a fixed pin,
/// but not the fixed-axis formula's "pin fixed in the world"), released at theta0 below the
/// horizontal. With theta clockwise below the horizontal, I_O theta'' = m g (L/2) cos(theta):
/// theta'' = 3 g cos(theta) / (2 L); r = G - O = L/2 (cos, -sin); the pin's reaction on the bar
/// R = m r'' + (0, m g) (6/1).
fn bar(theta0: f64, cart: (f64, f64), t: f64) -> Vec<QuestionResult> {
    let q = |id: &str, c: &str| {
        format!(
            r#"(id: "{id}", ask: "{id}", unit: "N", expected: 1.0, tolerance: 1e9, quantity: JointReaction(joint: "pin", component: {c}), at: Time({t}), why: "t"),"#
        )
    };
    questions(&format!(
        r#"Level(title: "bar", effects: [gravity, joints], world: (dt: 0.001, substeps: 4, duration: {dur}),
          bodies: [(name: "cart", kind: kinematic, velocity: ({cvx}, {cvy})),
                   (name: "bar", shape: Box(width: 1.0, height: 0.02), mass: 2.0, inertia: {ig},
                    position: ({gx}, {gy}), angle: {ang}, velocity: ({cvx}, {cvy}))],
          joints: [(name: "pin", kind: revolute, body1: "cart", body2: "bar", anchor2: (-0.5, 0.0))],
          questions: [{q1}{q2}])"#,
        dur = t + 0.05,
        cvx = cart.0,
        cvy = cart.1,
        ig = 2.0 / 12.0,
        gx = 0.5 * theta0.cos(),
        gy = -0.5 * theta0.sin(),
        ang = -theta0,
        q1 = q("rx", "X"),
        q2 = q("ry", "Y"),
    ))
}

fn bar_reaction(theta: f64, w: f64) -> (f64, f64) {
    let (m, l) = (2.0, 1.0);
    let acc = 3.0 * G * theta.cos() / (2.0 * l);
    let (s, c) = theta.sin_cos();
    let ax = 0.5 * l * (-acc * s - w * w * c);
    let ay = 0.5 * l * (-acc * c + w * w * s);
    (m * ax, m * ay + m * G)
}

/// Released from the horizontal, the bar is horizontal again, at rest, after half a swing: T/2
/// = 2 sqrt(2 L / (3 g)) K(sin 45 deg) (PL-5 with I_O / (m g d) = 2 L / (3 g); K(1/sqrt 2) =
/// 1.854074677301372). There alpha = 3 g / (2 L), a_G = 3 g / 4 down: R = m g / 4 up, no x.
#[test]
fn a_bar_pendulum_pin_reaction_at_the_horizontal_is_a_quarter_weight() {
    let half = 2.0 * (2.0 / (3.0 * G)).sqrt() * 1.854_074_677_301_372;
    let qs = bar(0.0, (0.5, 0.0), half);
    near(reference(&qs, "ry"), 2.0 * G / 4.0, 1e-7, "R_y");
    assert!(reference(&qs, "rx").abs() < 1e-6, "R_x");
}

/// Its twin starts 30 degrees below the horizontal on a cart rising at 0.4 m/s, read at 0.3 s:
/// theta and theta' from RK4, then R = m r'' + (0, m g).
#[test]
fn a_bar_pendulum_pin_reaction_at_a_time_reads_the_reference() {
    let th0 = 30f64.to_radians();
    let t = 0.3;
    let qs = bar(th0, (0.0, 0.4), t);
    let (theta, w, _) = rk4(|q| 3.0 * G * q.cos() / 2.0, th0, 0.0, t, None);
    let (rx, ry) = bar_reaction(theta, w);
    near(reference(&qs, "rx"), rx, 1e-7, "R_x");
    near(reference(&qs, "ry"), ry, 1e-7, "R_y");
}
