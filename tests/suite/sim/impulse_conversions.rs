//! Item 4 of the core issue: rapier's impulses converted to per-step reactions, checked against theory.
//!
//! rapier stores the *whole step's* contact impulse but only the *last substep's* joint
//! impulse, along Gram-Schmidt-orthogonalized rows (see `sim::joints`). These tests pin the
//! conversion down with textbook closed forms.

use crate::common;

use rigidlab::sim::{Options, Simulation};

fn sim(text: &str) -> Simulation {
    let scene = common::parse(text);
    Simulation::new(&scene, &Options::default())
}

const G: f64 = 9.81;

fn pendulum(angle0_deg: f64, substeps: usize) -> String {
    // Bob of 2 kg (given mass, tiny radius so I_G is negligible) on a 1.5 m massless pin link.
    let (l, a) = (1.5_f64, angle0_deg.to_radians());
    format!(
        r#"Level(title: "pendulum", effects: [gravity, joints],
        world: (dt: 0.002, substeps: {substeps}, duration: 2.0),
        bodies: [
            (name: "pivot", kind: fixed),
            (name: "bob", shape: Circle(radius: 0.01), mass: 2.0, inertia: 1e-6, position: ({x}, {y})),
        ],
        joints: [(name: "pin", kind: revolute, body1: "pivot", body2: "bob", anchor2: ({ax}, {ay}))])"#,
        x = l * a.sin(),
        y = -l * a.cos(),
        ax = -l * a.sin(),
        ay = l * a.cos(),
    )
}

#[test]
fn hanging_pendulum_at_rest_carries_mg() {
    for substeps in [1, 4, 8] {
        let mut s = sim(&pendulum(0.0, substeps));
        for _ in 0..50 {
            s.step().unwrap();
        }
        let snap = s.snapshot();
        let j = &snap.joints[0];
        let force = j.impulse_on_body2 / snap.dt;
        // Static equilibrium: T = m g upward on the bob. f32 state: relative 1e-4.
        assert!(
            (force.y - 2.0 * G).abs() < 2.0 * G * 1e-4,
            "substeps {substeps}: T = {force:?}, expected (0, {})",
            2.0 * G
        );
        assert!(force.x.abs() < 1e-3, "substeps {substeps}: T = {force:?}");
    }
}

#[test]
fn pendulum_tension_follows_theory_along_the_swing() {
    // Released from 90 degrees: a point-mass pendulum has T = m g (3 cos(theta) - 2 cos(theta0))
    // along the rod toward the pivot (energy: v^2 = 2 g L (cos(theta) - cos(theta0)); radial
    // Newton: T - m g cos(theta) = m v^2 / L). At the bottom this is T = m g + m v^2 / L = 3 m g.
    let m = 2.0;
    let mut s = sim(&pendulum(90.0, 4));
    let mut worst: f64 = 0.0;
    let mut at_bottom = None;
    for _ in 0..1000 {
        let snap = s.step().unwrap().clone();
        let bob = &snap.bodies[1];
        let r = bob.com; // pivot at origin
        let l = r.length();
        let theta = r.x.atan2(-r.y);
        // Use the engine's own speed in the radial law (independent of energy drift).
        let v2 = bob.velocity.length_squared();
        let tension = m * G * theta.cos() + m * v2 / l;
        let expected = -r / l * tension; // on the bob, toward the pivot
        let force = snap.joints[0].impulse_on_body2 / snap.dt;
        // Joint impulses are the last substep's, times substeps: first-order error in h = dt/substeps
        // times the rate of change of T (|dT/dt| <= 3 m g omega ~ 150 N/s here), so ~ 0.05 N.
        let err = (force - expected).length();
        assert!(err.is_finite(), "force {force} against {expected}");
        worst = worst.max(err / (3.0 * m * G));
        if theta.abs() < 0.02 && at_bottom.is_none() {
            at_bottom = Some((force, m * G + m * v2 / l));
        }
    }
    assert!(
        worst < 5e-3,
        "worst relative error of the tension vector {worst:.2e}"
    );
    let (f, t) = at_bottom.expect("the bob passes the bottom within 2 s");
    assert!(
        (f.y - t).abs() < 5e-3 * t,
        "bottom: T = {f:?}, m g + m v^2/L = {t}"
    );
}

#[test]
fn box_resting_on_ground_carries_mg() {
    // A 3 kg box on a fixed ground box: the contact impulse over a step is m g dt.
    let text = r#"Level(title: "box", effects: [gravity, contacts],
        world: (dt: 0.01, duration: 1.0),
        bodies: [
            (name: "ground", kind: fixed, shape: Box(width: 10.0, height: 1.0), position: (0.0, -0.5)),
            (name: "box", shape: Box(width: 0.5, height: 0.5), mass: 3.0, position: (0.0, 0.25)),
        ])"#;
    let mut s = sim(text);
    for _ in 0..100 {
        s.step().unwrap();
    }
    let snap = s.snapshot();
    let on_box: glam::DVec2 = snap
        .contacts
        .iter()
        .map(|c| {
            if snap.bodies[c.body2].name == "box" {
                c.impulse_on_body2()
            } else {
                -c.impulse_on_body2()
            }
        })
        .sum();
    let n = on_box / snap.dt;
    assert!(
        (n.y - 3.0 * G).abs() < 3.0 * G * 1e-4,
        "N = {n:?}, m g = {}",
        3.0 * G
    );
    assert!(n.x.abs() < 1e-3);
}

#[test]
fn naive_reading_of_rapier_joint_impulses_is_wrong_mid_swing() {
    // The trap the conversion exists for: reading `ImpulseJoint::impulses` as world (x, y)
    // times substeps. At 45 degrees on the way down from 90 the rows are far from orthogonal.
    let m = 2.0;
    let mut s = sim(&pendulum(90.0, 4));
    loop {
        let snap = s.step().unwrap().clone();
        let r = snap.bodies[1].com;
        let theta = r.x.atan2(-r.y);
        if theta < 45f64.to_radians() {
            let (_, j) = s.world.impulse_joints.iter().next().unwrap();
            let naive = glam::DVec2::new(j.impulses.x as f64, j.impulses.y as f64) * 4.0 / snap.dt;
            let ours = snap.joints[0].impulse_on_body2 / snap.dt;
            let t = m * G * theta.cos() + m * snap.bodies[1].velocity.length_squared() / r.length();
            let expected = -r / r.length() * t;
            eprintln!(
                "theta {:.1} deg: expected {expected:?}, converted {ours:?}, naive {naive:?}",
                theta.to_degrees()
            );
            assert!((ours - expected).length() < 0.01 * t);
            assert!(
                (naive - expected).length() > 0.1 * t,
                "the naive reading happened to be right"
            );
            break;
        }
    }
}

#[test]
fn an_impulse_at_t0_acts_on_the_textbook_mass_properties() {
    // A free 2 kg, 1 m x 0.2 m bar (I_G = m (a^2 + b^2)/12 = 0.173333 kg m^2), no gravity,
    // struck at t = 0 by J = (0, 3) N s at r = (0.4, 0) from G (RM-10):
    //   v_G = J / m = (0, 1.5) m/s;  w = (r x J) / I_G = 0.4 * 3 / 0.173333 = 6.923077 rad/s.
    // rapier fills in mass properties only inside its first step, so this needs them set at build.
    for contacts in ["", "contacts"] {
        let mut s = sim(&format!(
            r#"Level(title: "blow", effects: [{contacts}],
            world: (dt: 0.016666666666666666, duration: 0.1),
            bodies: [(name: "bar", shape: Box(width: 1.0, height: 0.2), mass: 2.0)],
            events: [Impulse(name: "blow", at: 0.0, body: "bar", point: (0.4, 0.0), impulse: (0.0, 3.0))])"#
        ));
        let b = s.step().unwrap().bodies[0].clone();
        assert!(
            (b.velocity.x).abs() < 1e-6 && (b.velocity.y - 1.5).abs() < 1e-5,
            "{contacts}: v = {}",
            b.velocity
        );
        assert!(
            (b.omega - 6.923077).abs() < 1e-4,
            "{contacts}: w = {}",
            b.omega
        );
    }
}

#[test]
fn capsule_inertia_is_made_good_for_parrys_3d_cap_offset() {
    // parry2d 0.31.1 moves a 2D capsule's half discs by the 3D hemisphere's centroid offset 3r/8
    // instead of the half disc's 4r/(3 pi). For l = 0.6 m, r = 0.1 m at unit density, by hand:
    //   rectangle 0.6 x 0.2: J = 0.12 (0.36 + 0.04)/12 = 4.0e-3
    //   two half discs, each pi r^4/4 - A_s c^2 about its centroid (A_s = pi r^2/2, c = 4r/(3 pi)),
    //   moved 0.3 + c out: 2 (pi r^4/4 + A_s (0.09 + 0.6 c)) = 3.784513e-3
    //   J_exact = 7.784513e-3 m^4; parry's: 4.0e-3 + pi r^4/2 + pi r^2 (0.09 + 0.6 * 3r/8) = 7.691371e-3
    use rigidlab::level::{BodyDef, Shape};
    let shape = Shape::Capsule {
        length: 0.6,
        radius: 0.1,
    };
    let j_exact = 7.784513e-3;
    let parry = rigidlab::sim::shared_shape(&shape)
        .mass_properties(1.0)
        .principal_inertia() as f64;
    // The engine's own figure is short by 1.2% (f32: 7 digits).
    assert!(
        (parry - 7.691371e-3).abs() < 1e-8,
        "parry's capsule J = {parry}"
    );
    let shortfall = (parry - j_exact) / j_exact;
    assert!((shortfall + 0.011965).abs() < 1e-5, "shortfall {shortfall}");
    assert!((rigidlab::sim::capsule_inertia_shortfall(&shape) - (j_exact - parry)).abs() < 1e-8);
    // What rigidlab hands rapier for a 2 kg capsule: m J_exact / A, A = 0.12 + pi 0.01.
    let body: BodyDef = ron::from_str(
        "#![enable(implicit_some)] (name: \"c\", shape: Capsule(length: 0.6, radius: 0.1), mass: 2.0)",
    )
    .unwrap();
    let area = 0.12 + std::f64::consts::PI * 0.01;
    let i_g = rigidlab::sim::mass_properties(&body).principal_inertia() as f64;
    assert!(
        (i_g - 2.0 * j_exact / area).abs() < 1e-6,
        "I_G handed to rapier {i_g}"
    );
}
