//! What Box2D does not run is refused before the run, at the level item that asks for it
//! (file, line, column, the feature and the engine), exit 2; never run wrong (issue 46).

use rigidlab::level::{self, PhysicsEngine};
use rigidlab::runner::{self, RunError};
use rigidlab::sim::Options;
use std::collections::HashMap;
use std::path::Path;

const BASE: &str = r#"Level(
  title: "refused",
  effects: [gravity, contactsEFFECTS],
  world: (engine: box2d),
  bodies: [
    (name: "ground", kind: fixed, shape: Box(width: 4.0, height: 0.2)),
    (name: "block", shape: Box(width: 0.2, height: 0.2), mass: 1.0, position: (0.0, 1.0)),
  ],
"#;

/// The level: BASE with its extra effects and `extra` items.
fn level_text(effects: &str, extra: &str) -> String {
    format!("{}{extra})", BASE.replace("EFFECTS", effects))
}

/// The error of running the level (a file named `refused.ron`) on the level's engine.
fn refusal(effects: &str, extra: &str) -> level::LevelError {
    let dir = std::env::temp_dir().join(format!("rigidlab-box2d-refusal-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let file = dir.join("refused.ron");
    let text = level_text(effects, extra);
    std::fs::write(&file, &text).expect("write level");
    let scene = level::load(&file).unwrap_or_else(|e| panic!("{e}"));
    let err = runner::run_file(&file, &Options::default(), &HashMap::new());
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(scene.level.world.engine, PhysicsEngine::Box2d);
    match err {
        Err(RunError::Level(e)) => e,
        Err(other) => panic!("not a located refusal: {other}"),
        Ok(_) => panic!("Box2D ran a level it must refuse:\n{text})"),
    }
}

/// Line (1-based) of the first line holding `needle` in the file `refusal` writes.
fn line_of(effects: &str, extra: &str, needle: &str) -> usize {
    let text = level_text(effects, extra);
    1 + text
        .lines()
        .position(|l| l.contains(needle))
        .expect("needle in text")
}

#[test]
fn a_spring_is_refused_at_its_item() {
    let extra = r#"  springs: [
    (name: "s", body1: "block", point2: (0.0, 2.0), stiffness: 100.0, rest_length: 1.0),
  ],
"#;
    let e = refusal(", springs", extra);
    assert_eq!(e.line, line_of(", springs", extra, "name: \"s\""), "{e}");
    assert!(e.col > 0, "{e}");
    let text = e.to_string();
    assert!(
        text.contains("spring") && text.contains("box2d engine"),
        "{text}"
    );
    assert!(e.file.ends_with("refused.ron"), "{e}");
}

#[test]
fn a_joint_motor_is_refused_at_its_field() {
    let extra = r#"  joints: [
    (name: "hinge", kind: revolute, body1: "ground", body2: "block", anchor2: (0.0, -1.0),
     motor: Some(Velocity(target: 1.0))),
  ],
"#;
    let e = refusal(", joints, motors", extra);
    assert_eq!(e.line, line_of(", joints, motors", extra, "motor:"), "{e}");
    assert!(e.to_string().contains("joint motor"), "{e}");
}

#[test]
fn a_curved_track_is_refused_at_its_body() {
    let text = level_text("", "").replace(
        r#"(name: "ground", kind: fixed, shape: Box(width: 4.0, height: 0.2)),"#,
        r#"(name: "ground", kind: fixed, shape: Arc(radius: 2.0, start: -3.0, end: 0.0, side: inside)),"#,
    );
    let dir = std::env::temp_dir().join(format!("rigidlab-box2d-arc-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let file = dir.join("arc.ron");
    std::fs::write(&file, &text).expect("write level");
    let err = runner::run_file(&file, &Options::default(), &HashMap::new());
    let _ = std::fs::remove_dir_all(&dir);
    let Err(RunError::Level(e)) = err else {
        panic!("an Arc ran on Box2D");
    };
    let line = 1 + text
        .lines()
        .position(|l| l.contains("Arc("))
        .expect("arc line");
    assert_eq!(e.line, line, "{e}");
    assert!(e.to_string().contains("Arc track"), "{e}");
}

#[test]
fn the_engine_field_is_read_and_written_only_when_not_rapier() {
    let on_box2d = level::parse(
        Path::new("e.ron"),
        r#"Level(title: "t", world: (engine: box2d), bodies: [(name: "b", kind: fixed)])"#,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(on_box2d.level.world.engine, PhysicsEngine::Box2d);
    assert!(level::to_ron(&on_box2d.level).contains("engine: box2d"));
    let on_rapier = level::parse(
        Path::new("r.ron"),
        r#"Level(title: "t", bodies: [(name: "b", kind: fixed)])"#,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(on_rapier.level.world.engine, PhysicsEngine::Rapier);
    assert!(!level::to_ron(&on_rapier.level).contains("engine"));
}
