//! A `CheckSet` runs the probes of `newton_euler`, `kinetic_energy_ic` and
//! `angular_momentum_fixed_point` together, one loop per kind (`checks::kinds::batch`), and
//! `kinetic_energy_ic`'s rolling probes get their contacts from one walk over the step's
//! contacts. The claim is that each probe then does exactly what it does alone (the same
//! operations in the same order): so the set's results must equal, to the last bit, those of
//! each check's probe run on its own (`probe_for`, with its own frame pass and the contact
//! links), in the level's order, refused checks included.

use rigidlab::checks::{probe_for, CheckResult, CheckSet};
use rigidlab::level::{parse, Scene};
use rigidlab::sim::{Options, Simulation};
use std::path::Path;

/// Balls thrown into a box so that they roll on the floor, strike each other and pile up (a
/// body with several contacts, on the floor and on another ball, and steps with none), and two
/// pinned bars; every kind batched, twice on one body, on a moving `other`, refused.
fn scene() -> Scene {
    let mut bodies = String::from(
        r#"(name: "floor", kind: fixed, shape: Box(width: 4.0, height: 0.2), position: (0.0, -0.1)),
        (name: "wall_l", kind: fixed, shape: Box(width: 0.2, height: 3.0), position: (-2.1, 1.5)),
        (name: "wall_r", kind: fixed, shape: Box(width: 0.2, height: 3.0), position: (2.1, 1.5)),
"#,
    );
    for (k, px, a, m) in [(0, 10.0, 0.7, 2.0), (1, 12.0, -1.2, 1.0)] {
        // The bar's top (anchor2, 0.5 m up its axis) on the pin: G = pin - R(a) (0, 0.5).
        let (cx, cy) = (px + 0.5 * f64::sin(a), 5.0 - 0.5 * f64::cos(a));
        bodies += &format!(
            r#"(name: "pin{k}", kind: fixed, position: ({px}, 5.0)),
        (name: "bar{k}", shape: Box(width: 0.04, height: 1.0), mass: {m}, angle: {a}, position: ({cx}, {cy})),
"#
        );
    }
    let mut checks = String::new();
    // ball1 dropped onto ball2 (a contact between two moving bodies), ball0 and ball3 rolling
    // into them.
    for (k, x, y, vx) in [
        (0, -1.5, 0.15, 2.0),
        (1, 0.32, 0.6, 0.0),
        (2, 0.3, 0.15, 0.0),
        (3, 1.2, 0.15, -1.5),
    ] {
        bodies += &format!(
            r#"(name: "ball{k}", shape: Circle(radius: 0.15), mass: 1.0, position: ({x}, {y}), velocity: ({vx}, 0.0), omega: {}, friction: 0.6),
"#,
            -vx / 0.15,
        );
        checks += &format!(
            r#"(kind: newton_euler, body: "ball{k}", tolerance: 1.0, why: "test"),
            (kind: kinetic_energy_ic, body: "ball{k}", other: "floor", tolerance: 1.0, why: "test"),
            (kind: newton_euler, body: "ball{k}", point: (0.0, 0.0), tolerance: 1.0, why: "test"),
"#
        );
    }
    checks += r#"(kind: kinetic_energy_ic, body: "ball1", other: "ball2", tolerance: 1.0, why: "test"),
        (kind: kinetic_energy_ic, body: "ball2", other: "ball1", tolerance: 1.0, why: "test"),
        (kind: kinetic_energy_ic, body: "bar0", point: (10.0, 5.0), tolerance: 1.0, why: "test"),
        (kind: angular_momentum_fixed_point, body: "bar0", point: (10.0, 5.0), tolerance: 1.0, why: "test"),
        (kind: angular_momentum_fixed_point, body: "bar1", tolerance: 1.0, why: "test: O the pivot"),
        (kind: newton_euler, body: "bar1", point: (12.0, 5.0), tolerance: 1.0, why: "test"),
        (kind: work_energy, tolerance: 1.0, why: "test"),
        (kind: angular_momentum_fixed_point, point: (0.0, 0.0), tolerance: 1.0, why: "test"),
"#;
    let ron = format!(
        r#"Level(title: "batched probes", effects: [gravity, contacts, friction, joints],
        world: (dt: 0.016666666666666666, substeps: 4, duration: 2.0),
        bodies: [{bodies}],
        joints: [(name: "j0", kind: revolute, body1: "pin0", body2: "bar0", anchor2: (0.0, 0.5)),
                 (name: "j1", kind: revolute, body1: "pin1", body2: "bar1", anchor2: (0.0, 0.5))],
        checks: [{checks}])"#
    );
    let mut scene = parse(Path::new("batched.ron"), &ron).unwrap_or_else(|e| panic!("{e}"));
    // A check its kind refuses (validation refuses it in a level file), among the others.
    let mut refused = scene.level.checks[1].clone();
    refused.other = None;
    refused.why = "test: refused, no point or other".into();
    scene.level.checks.insert(5, refused);
    scene
}

#[test]
fn a_check_set_gives_each_probes_own_results_to_the_last_bit() {
    let scene = scene();
    let level = &scene.level;
    let mut sim = Simulation::new(&scene, &Options::default());
    let mut set = CheckSet::new(level);
    let mut alone: Vec<_> = level.checks.iter().map(|c| probe_for(level, c)).collect();
    let mut feed = |s: &rigidlab::snapshot::Snapshot| {
        set.observe(s);
        for p in alone.iter_mut() {
            p.observe(s);
        }
    };
    feed(sim.snapshot());
    let steps = (2.0 / level.world.dt).round() as usize;
    for _ in 0..steps {
        feed(sim.step().expect("the level runs"));
    }
    let batched = set.finish();
    let alone: Vec<CheckResult> = alone.into_iter().map(|p| p.finish()).collect();
    assert_eq!(batched.len(), level.checks.len());
    for (k, (b, a)) in batched.iter().zip(&alone).enumerate() {
        assert_eq!(b, a, "check {k} ({} on {})", a.kind, a.subject);
    }
    // The comparison saw what it is about: the balls rolled on the floor for some steps and
    // flew for others (steps skipped), one touched another, and the refused check failed.
    let rolling = &alone[1];
    assert!(rolling.samples > 0, "ball0 never rolled: {}", rolling.note);
    assert!(
        alone
            .iter()
            .any(|r| r.note.contains("steps without contact skipped")),
        "no rolling probe skipped a step"
    );
    let on_a_ball = alone
        .iter()
        .filter(|r| r.subject.contains("with \"ball"))
        .map(|r| r.samples)
        .max();
    assert!(on_a_ball.unwrap_or(0) > 0, "no ball touched another");
    let refused = alone.iter().find(|r| r.why.contains("refused"));
    assert!(refused.is_some_and(|r| !r.passed && r.samples == 0));
}
