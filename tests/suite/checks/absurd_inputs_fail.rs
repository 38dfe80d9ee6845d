//! Nothing absurd passes (issue 32; docs/analysis-and-checks.md, "What never passes"): a check
//! whose theory, engine value or residual is not finite fails and says which; a check that
//! compared nothing fails; a spring far too stiff for the step is warned about before the run,
//! and the run stops when rapier's speed cap, not the spring, holds the body.
//!
//! Expected values come from the rule or from the formulas, never from the engine's output:
//! - dt = 5e-324 s: 1 / dt overflows f64, so every force the free-body diagram reads (impulse / dt)
//!   is infinite;
//! - gravity 1e300 m/s^2 is past f32's range (3.4e38): the engine's state cannot hold it;
//! - I_O = I_G + m d^2 about a point 1e155 m away is 1 kg x 1e310 m^2, past f64's 1.8e308;
//! - a 0.5 kg block on a spring k with h = dt / substeps = 1e-4 s has k h^2 / m = 2e-8 k: 2e7 at
//!   k = 1e15 (far above symplectic Euler's stability bound of 4), and its spring, stretched
//!   0.1 m, asks a speed change k 0.1 h / m = 2e-5 k m/s per substep: 2e10 m/s at 1e15, past
//!   rapier's 400 m/s cap; 2e25 m/s at 1e30, whose square overflows f32 (rapier then scales the
//!   velocity by 400 / inf = 0 and the block never moves).

use crate::common;

use common::{parse, rigidlab, run};
use rigidlab::checks::CheckResult;
use rigidlab::level;
use rigidlab::sim::{Options, Simulation};
use std::path::{Path, PathBuf};

fn temp_dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rigidlab-absurd-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn write(text: &str, tag: &str) -> PathBuf {
    let f = temp_dir(tag).join(format!("{tag}.ron"));
    std::fs::write(&f, text).unwrap();
    f
}

/// `rigidlab check FILE --json --no-advice`: exit code and the parsed report.
fn check_json(file: &Path) -> (i32, serde_json::Value) {
    let out = rigidlab()
        .args(["check", file.to_str().unwrap(), "--json", "--no-advice"])
        .output()
        .unwrap();
    let json = serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!(
            "{e}: {}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        )
    });
    (out.status.code().unwrap(), json)
}

fn newton_euler_level(world: &str) -> String {
    format!(
        r#"Level(title: "absurd", effects: [gravity],
  world: {world},
  bodies: [(name: "b", shape: Box(width: 0.1, height: 0.1), mass: 1.0)],
  checks: [(kind: newton_euler, body: "b", tolerance: 1e-3, why: "test")])"#
    )
}

/// The one check of a level's JSON report fails, and its note says that `value` is not finite.
fn assert_fails_not_finite(code: i32, json: &serde_json::Value, value: &str) {
    let c = &json["levels"][0]["checks"][0];
    assert_eq!(code, 1, "{json:#}");
    assert_eq!(c["passed"], false, "{c:#}");
    let note = c["note"].as_str().unwrap();
    assert!(
        note.contains("not finite") && note.contains(&format!("{value} = ")),
        "{note}"
    );
    // A null in the JSON is explained by the note, and the relative error is never 0.
    assert_ne!(c["max_rel_error"], serde_json::json!(0.0), "{c:#}");
}

#[test]
fn newton_euler_at_dt_5e_324_fails() {
    // 4 steps of the smallest subnormal dt: 1/dt = inf.
    let text = newton_euler_level("(dt: 5e-324, substeps: 1, duration: 2e-323)");
    let r = run(&parse(&text), &Options::default());
    let c = &r.checks[0];
    assert!(!c.passed, "{c:?}");
    assert!(!c.max_abs_error.is_finite(), "{c:?}");
    let (code, json) = check_json(&write(&text, "tiny_dt"));
    assert_fails_not_finite(code, &json, "max_abs_error");
}

#[test]
fn newton_euler_under_gravity_1e300_fails() {
    let text = newton_euler_level("(dt: 0.01, substeps: 1, duration: 0.1, gravity: (0.0, -1e300))");
    let (code, json) = check_json(&write(&text, "huge_g"));
    assert_fails_not_finite(code, &json, "max_abs_error");
}

#[test]
fn mass_properties_about_a_point_1e155_away_fails() {
    let text = r#"Level(title: "far point", effects: [],
  world: (dt: 0.01, substeps: 1, duration: 0.1),
  bodies: [(name: "b", shape: Box(width: 0.1, height: 0.1), mass: 1.0)],
  checks: [(kind: mass_properties, body: "b", point: (1e155, 0.0), tolerance: 1e-3, why: "test")])"#;
    let r = run(&parse(text), &Options::default());
    assert!(!r.checks[0].passed, "{:?}", r.checks[0]);
    assert_eq!(r.checks[0].theory, f64::INFINITY, "I_O = 1e310 overflows");
    let (code, json) = check_json(&write(text, "far_point"));
    assert_fails_not_finite(code, &json, "theory");
    // The same check about a point 1 m away passes: I_O = 1/600 + 1 kg m^2 is finite.
    let near = text.replace("(1e155, 0.0)", "(1.0, 0.0)");
    assert!(run(&parse(&near), &Options::default()).checks[0].passed);
}

fn result(samples: u64, theory: f64) -> CheckResult {
    CheckResult {
        kind: "newton_euler".into(),
        subject: "body \"b\"".into(),
        theory,
        engine: 1.0,
        max_abs_error: 0.0,
        max_rel_error: 0.0,
        final_abs_error: 0.0,
        final_rel_error: 0.0,
        tolerance: 1e-3,
        passed: true,
        samples,
        scale: 1.0,
        why: String::new(),
        note: "measured".into(),
    }
}

#[test]
fn the_rule_on_a_result() {
    // Finite and compared: untouched.
    assert_eq!(result(3, 1.0).never_absurd(), result(3, 1.0));
    // Nothing compared: fails, and says so.
    let r = result(0, 1.0).never_absurd();
    assert!(!r.passed && r.note.contains("compared nothing"), "{r:?}");
    // A NaN or infinite value: fails, naming it, the probe's own note kept.
    for v in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let r = result(3, v).never_absurd();
        assert!(!r.passed, "{r:?}");
        assert!(
            r.note.contains(&format!("theory = {v}")) && r.note.ends_with("measured"),
            "{r:?}"
        );
    }
}

#[test]
fn an_energy_check_on_a_body_that_never_moved_fails() {
    // No gravity, no force, at rest: T = 0 and no energy flows at every step, so the checks
    // compare 0 with 0, which is no agreement.
    let text = r#"Level(title: "still", effects: [],
  world: (dt: 0.01, substeps: 1, duration: 0.1),
  bodies: [(name: "b", shape: Box(width: 0.1, height: 0.1), mass: 1.0)],
  checks: [
    (kind: kinetic_energy_g, body: "b", tolerance: 1e-3, why: "test"),
    (kind: work_energy, body: "b", tolerance: 1e-3, why: "test"),
  ])"#;
    let r = run(&parse(text), &Options::default());
    for c in &r.checks {
        assert!(!c.passed && c.note.contains("compared nothing"), "{c:?}");
    }
    // Set moving at 1 m/s, the same body has T = 1/2 m v^2 = 0.5 J to compare: both pass.
    let moving = text.replace("mass: 1.0)", "mass: 1.0, velocity: (1.0, 0.0))");
    let r = run(&parse(&moving), &Options::default());
    assert!(r.checks.iter().all(|c| c.passed), "{:?}", r.checks);
}

fn spring_level(k: &str) -> String {
    format!(
        r#"Level(title: "stiff spring", effects: [springs],
  world: (dt: 0.0001, substeps: 1, duration: 0.1),
  bodies: [(name: "block", shape: Box(width: 0.1, height: 0.1), mass: 0.5, position: (0.6, 0.0), lock_rotation: true)],
  springs: [(name: "spring", body1: "block", point2: (0.0, 0.0), stiffness: {k}, rest_length: 0.5)],
  checks: [
    (kind: kinetic_energy_g, body: "block", tolerance: 1e-2, why: "test"),
    (kind: work_energy, body: "block", tolerance: 1e-2, why: "test"),
  ])"#
    )
}

#[test]
fn a_spring_at_k_1e15_stops_at_the_speed_cap() {
    let scene = parse(&spring_level("1e15"));
    let err = Simulation::new(&scene, &Options::default())
        .run(|_| {})
        .unwrap_err();
    let msg = err.to_string();
    assert!(
        msg.contains("speed cap") && msg.contains("exploded"),
        "{msg}"
    );
    assert_eq!(err.body, "block");
    // Within PINNED_STEPS = 10 steps of the first step at the cap (the first step: a speed
    // change of 2e10 m/s).
    assert!(err.step <= 20, "fired at step {}", err.step);
    let (code, json) = check_json(&write(&spring_level("1e15"), "k1e15"));
    assert_eq!(code, 1, "{json:#}");
    assert!(json["levels"][0]["error"]
        .as_str()
        .unwrap()
        .contains("speed cap"));
}

#[test]
fn a_body_cruising_at_the_speed_cap_runs_on() {
    // Falling at v0, g takes it to the 400 m/s cap in (400 - v0) / g and it falls on at the cap:
    // steady motion, not an explosion. Near the origin at v0 = 395 m/s (the cap at 0.51 s of
    // 2 s; each step's 6.7 m resolved), and 1e5 m down at dt = 1e-5 s in 4 substeps and
    // v0 = 399.95 m/s (the cap at 5.1 ms of 10 ms), where a substep's 1 mm is less than half
    // an f32 ulp of the position (7.8 mm): the position does not change at all, which must not
    // read as a body thrown back and forth at the cap.
    for (y, v0, dt, substeps, duration) in [
        ("0.0", "395.0", "0.016666666666666666", 1, "2.0"),
        ("-1e5", "399.95", "1e-5", 4, "0.01"),
    ] {
        let text = format!(
            r#"Level(title: "falling at the cap", effects: [gravity],
  world: (dt: {dt}, substeps: {substeps}, duration: {duration}),
  bodies: [(name: "b", shape: Circle(radius: 0.1), mass: 1.0, position: (0.0, {y}), velocity: (0.0, -{v0}))])"#
        );
        let mut sim = Simulation::new(&parse(&text), &Options::default());
        let mut at_cap = 0;
        let run = sim.run(|s| {
            if s.bodies[0].velocity.length() > 399.99 {
                at_cap += 1;
            }
        });
        assert!(run.is_ok(), "y = {y}: {run:?}");
        assert!(at_cap > 10, "y = {y}: {at_cap} steps at the cap");
    }
}

#[test]
fn a_spring_at_k_1e30_that_moves_nothing_stops() {
    let scene = parse(&spring_level("1e30"));
    let err = Simulation::new(&scene, &Options::default())
        .run(|_| {})
        .unwrap_err();
    let msg = err.to_string();
    assert!(
        msg.contains("has not moved") && msg.contains("spring \"spring\""),
        "{msg}"
    );
    let (code, json) = check_json(&write(&spring_level("1e30"), "k1e30"));
    assert_eq!(code, 1, "{json:#}");
}

#[test]
fn a_spring_too_stiff_for_the_step_is_warned_about_where_its_stiffness_is() {
    for (k, ratio) in [("1e15", "2.000e7"), ("1e30", "2.000e22")] {
        let text = spring_level(k);
        let file = write(&text, &format!("warn{k}"));
        let (_, warnings) = level::load_with_warnings(&file).unwrap();
        assert_eq!(warnings.len(), 1, "{warnings:?}");
        // Located at the spring's `stiffness:`.
        let (line, col) = text
            .lines()
            .enumerate()
            .find_map(|(i, l)| l.find("stiffness").map(|c| (i + 1, c + 1)))
            .unwrap();
        let w = warnings[0].to_string();
        assert!(
            w.contains(&format!("{}:{line}:{col}:", file.display()))
                && w.contains(&format!("k h^2 / m = {ratio}")),
            "{w}"
        );
        // `check` prints it on stderr.
        let out = rigidlab()
            .args(["check", file.to_str().unwrap(), "--no-advice"])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains("warning: spring \"spring\": k h^2 / m"),
            "{err}"
        );
    }
    // At k = 50 N/m, k h^2 / m = 1e-6: no warning, and the level runs to its end.
    let text = spring_level("50.0");
    let (_, warnings) = level::load_with_warnings(&write(&text, "soft")).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    assert!(Simulation::new(&parse(&text), &Options::default())
        .run(|_| {})
        .is_ok());
}
