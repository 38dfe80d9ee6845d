//! A failing level's advice says whether the other engine passes it at the same settings
//! (issue 46), and the report names the engine each run used (`study::other_engine`,
//! `LevelReport::engine`): rapier fails -> Box2D tried, Box2D fails -> rapier tried, a level
//! the other engine refuses gets the refusal with its place in the file.

use crate::common;
use rigidlab::level::PhysicsEngine;
use rigidlab::report::OtherVerdict;
use rigidlab::sim::Options;
use rigidlab::study::other_engine::other_engine;
use std::path::PathBuf;

/// A simple pendulum released at 60 degrees (1 kg disc bob, r = 0.05 m, L = 1 m) at 60 Hz and
/// 4 substeps, its kinetic energy read at the bottom after 9 s. Energy is conserved (no
/// friction, a fixed pin): T = m g L (1 - cos 60 deg) = 4.905 J at every pass of the bottom.
/// rapier's pin loses energy at this step (the issue measured 13.0% of the swing in 10 s on a
/// point bob; this bob, 2026-12-07: 11.8%), Box2D's holds it (0.17%), so the tolerance of 3%
/// sits between the two measured engines, with the 3% itself being what a student reading the
/// swing would call "kept".
const PENDULUM_60HZ: &str = r#"Level(
  title: "A 60 Hz pendulum keeps its swing for 10 s",
  effects: [gravity, joints],
  world: (dt: 0.016666666666666666, substeps: 4, duration: 10.0),
  bodies: [
    (name: "pin", kind: fixed),
    (name: "bob", shape: Circle(radius: 0.05), mass: 1.0, position: (0.8660254037844386, -0.5)),
  ],
  joints: [(name: "pivot", kind: revolute, body1: "pin", body2: "bob", anchor2: (-0.8660254037844386, 0.5))],
  questions: [
    (id: "ke_bottom_late", ask: "Kinetic energy at the bottom after 9 s", unit: "J", expected: 4.905, tolerance: 0.03,
     quantity: KineticEnergy("bob"), at: MinOf(of: Y("bob"), after: 9.0),
     why: "energy conserved: m g L (1 - cos 60 deg)"),
  ],
)
"#;

/// A 0.5 kg block on a 50 N/m spring (omega_n = 10 rad/s) at dt = 0.05 s: its period is
/// 2 pi / omega_n = 0.6283 s, but the symplectic update's is 2 pi / Omega with
/// 2 sin(Omega dt / 2) = omega_n dt, Omega = 10.107 rad/s, 1.05% short: rapier fails the 1e-3
/// tolerance at this step (honestly: a finer step passes), and Box2D refuses the spring.
const SPRING_COARSE: &str = r#"Level(
  title: "Block on a spring at a coarse step",
  effects: [springs],
  world: (dt: 0.05, substeps: 1, duration: 2.0),
  bodies: [
    (name: "block", shape: Box(width: 0.1, height: 0.1), mass: 0.5, position: (0.6, 0.0), lock_rotation: true),
  ],
  springs: [
    (name: "spring", body1: "block", point2: (0.0, 0.0), stiffness: 50.0, rest_length: 0.5),
  ],
  questions: [
    (id: "period", ask: "Period", unit: "s", expected: 0.6283185307179586, tolerance: 1e-3,
     quantity: SpringPeriod("block"), at: End),
  ],
)
"#;

fn write(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rigidlab-other-engine-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join(name);
    std::fs::write(&path, text).expect("writes the level");
    path
}

/// `rigidlab check FILE ARGS` (the advice's search held to a token bound: these tests are
/// about the other engine's line, which runs whatever the bound).
fn check(path: &PathBuf, args: &[&str]) -> (String, i32) {
    let out = common::rigidlab()
        .arg("check")
        .arg(path)
        .args(["--advice-cost", "0.001"])
        .args(args)
        .output()
        .expect("runs rigidlab");
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        out.status.code().unwrap_or(-1),
    )
}

#[test]
fn a_pendulum_rapier_fails_at_60_hz_passes_on_box2d_and_the_advice_says_so() {
    let path = write("pendulum_60hz.ron", PENDULUM_60HZ);
    let (json, code) = check(&path, &["--json"]);
    assert_eq!(code, 1, "rapier fails the level: {json}");
    let v: serde_json::Value = serde_json::from_str(&json).expect("JSON");
    let l = &v["levels"][0];
    assert_eq!(l["engine"], "rapier", "{l}");
    assert_eq!(l["other_engine"]["engine"], "box2d", "{l}");
    assert_eq!(l["other_engine"]["verdict"], "passes", "{l}");
    let (text, _) = check(&path, &[]);
    assert_eq!(text.lines().next(), Some("engine: rapier"), "{text}");
    assert!(
        text.contains("advice: on box2d at the same settings this level passes"),
        "{text}"
    );
    // Run on Box2D, the same level passes: no advice, and the header names Box2D.
    let (text, code) = check(&path, &["--engine", "box2d"]);
    assert_eq!(code, 0, "{text}");
    assert_eq!(text.lines().next(), Some("engine: box2d"), "{text}");
}

/// The library's simple pendulum has a point bob (I_G = 1e-6 kg m^2), on which Box2D's f32 pin
/// gains energy (docs/engines.md: 181.9 m/s at the bottom for 3.132): it fails on Box2D and the
/// advice says rapier passes it at the same settings.
#[test]
fn a_level_box2d_fails_is_tried_on_rapier() {
    let scene = common::load("levels/kinetics/simple_pendulum.ron");
    let opts = Options {
        engine: Some(PhysicsEngine::Box2d),
        ..Options::default()
    };
    let own = common::run(&scene, &opts);
    assert_eq!(own.engine, Some(PhysicsEngine::Box2d));
    assert!(!own.passed, "the point bob fails on Box2D");
    let o = other_engine(&scene, &opts);
    assert_eq!(o.engine, PhysicsEngine::Rapier);
    assert_eq!(o.verdict, OtherVerdict::Passes, "{o:?}");
}

#[test]
fn a_level_the_other_engine_refuses_gets_the_refusal_line() {
    let path = write("spring_coarse.ron", SPRING_COARSE);
    let (json, code) = check(&path, &["--json"]);
    assert_eq!(code, 1, "rapier fails the coarse step: {json}");
    let v: serde_json::Value = serde_json::from_str(&json).expect("JSON");
    let o = &v["levels"][0]["other_engine"];
    assert_eq!(o["engine"], "box2d", "{o}");
    assert_eq!(o["verdict"], "refused", "{o}");
    // The refusal names the feature and where the file asks for it (the spring's line).
    let why = o["why"].as_str().unwrap_or_default();
    let line = SPRING_COARSE
        .lines()
        .position(|l| l.contains("(name: \"spring\""))
        .expect("the spring's line")
        + 1;
    assert!(
        why.contains("spring") && why.contains(&format!("spring_coarse.ron:{line}:")),
        "{why}"
    );
    let (text, _) = check(&path, &[]);
    assert!(
        text.contains("advice: box2d refuses this level: "),
        "{text}"
    );
}
