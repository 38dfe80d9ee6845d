//! The editor in the app, headless (MinimalPlugins): a pendulum built from nothing with the
//! editor's commands (ground, bar, pin), a property edited, undone and redone, the scene saved,
//! and `rigidlab check` run on the saved level; the run restarts from each edit.

use crate::common;

use bevy::prelude::*;
use common::app::{editor_app as app, phys, send};
use rigidlab::app::editor::{EditorCommand, Placeable};
use rigidlab::app::{PhysicsCommand, Playback};
use rigidlab::editor::{self, Edit, Property};
use rigidlab::level::JointKind;
use std::process::Command;

#[test]
fn build_edit_undo_redo_save_and_check_a_pendulum() {
    let mut app = app();
    // Ground (the new scene has one; a second, lower), a bar placed where a click would put it
    // in a 4 m scene, a pin at its left end to the ground.
    let (note, ok) = send(
        &mut app,
        EditorCommand::Apply(Placeable::Ground.edit_at(glam::DVec2::new(0.0, -1.0), 4.0)),
    );
    assert!(ok, "{note}");
    let bar = Placeable::Bar.edit_at(glam::DVec2::new(0.6, 2.0), 4.0);
    let Edit::AddBody {
        shape: editor::NewShape::Bar { length, .. },
        ..
    } = &bar
    else {
        panic!("{bar:?}")
    };
    assert_eq!(
        *length, 1.0,
        "a bar is 0.3 of a 4 m scene, rounded to 1, 2 or 5: 1 m"
    );
    let (note, ok) = send(&mut app, EditorCommand::Apply(bar));
    assert!(ok, "{note}");
    let (note, ok) = send(
        &mut app,
        EditorCommand::Apply(Edit::AddJoint {
            kind: JointKind::Revolute,
            body1: None,
            body2: "bar1".into(),
            at: (0.1, 2.0),
        }),
    );
    assert!(ok && note.contains("pin1"), "{note}");
    assert_eq!(phys(&app).scene.level.joints.len(), 1);

    // Play a few steps, then edit: the run starts over from the edited scene, paused.
    app.world_mut().resource_mut::<Playback>().paused = false;
    for _ in 0..5 {
        app.update();
    }
    assert!(phys(&app).snapshot().step > 0);
    let (note, ok) = send(
        &mut app,
        EditorCommand::Apply(Edit::Set {
            body: "bar1".into(),
            property: Property::Mass(3.0),
        }),
    );
    assert!(ok, "{note}");
    assert!(app.world().resource::<Playback>().paused && phys(&app).snapshot().is_initial());
    let mass = |app: &App| {
        phys(app)
            .snapshot()
            .bodies
            .iter()
            .find(|b| b.mass > 0.0)
            .map(|b| b.mass)
    };
    assert!(
        (mass(&app).unwrap() - 3.0).abs() < 1e-6,
        "the simulation has not the edited mass"
    );
    send(&mut app, EditorCommand::Undo);
    assert!((mass(&app).unwrap() - 1.0).abs() < 1e-6);
    send(&mut app, EditorCommand::Redo);
    assert!((mass(&app).unwrap() - 3.0).abs() < 1e-6);

    // A refused edit says why and changes nothing.
    let before = phys(&app).scene.level.clone();
    let (why, ok) = send(
        &mut app,
        EditorCommand::Apply(Edit::Delete {
            body: "nobody".into(),
        }),
    );
    assert!(!ok && why.contains("nobody"));
    assert_eq!(phys(&app).scene.level, before);

    let dir = std::env::temp_dir().join(format!("rigidlab-editor-app-{}", std::process::id()));
    // Fresh: a save never replaces a file, so an old one would be the one checked below.
    let _ = std::fs::remove_dir_all(&dir);
    let path = dir.join("saved-levels/pendulum.ron");
    let (note, ok) = send(&mut app, EditorCommand::Save(path.clone()));
    assert!(ok, "{note}");
    let out = Command::new(env!("CARGO_BIN_EXE_rigidlab"))
        .args(["check", path.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "rigidlab check refused the saved scene:\n{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    let saved = rigidlab::level::load(&path).unwrap();
    assert_eq!(saved.level, phys(&app).scene.level);
    assert_eq!(
        saved
            .level
            .bodies
            .iter()
            .find(|b| b.name == "bar1")
            .unwrap()
            .mass,
        Some(3.0)
    );
}

/// Opening another level starts a new history at once: the undo button (which reads
/// `can_undo`) must not offer the last level's edits, nor the panel show their note, before
/// any command is sent (the history used to be cleared only at the next command).
#[test]
fn another_level_starts_with_nothing_to_undo() {
    let mut app = app();
    let (_, ok) = send(
        &mut app,
        EditorCommand::Apply(Edit::AddBody {
            shape: editor::NewShape::Disc { radius: 0.1 },
            at: (0.0, 1.0),
            mass: 1.0,
        }),
    );
    assert!(ok);
    assert!(app
        .world()
        .resource::<rigidlab::app::editor::Editor>()
        .history
        .can_undo());
    let other = rigidlab::level::load(std::path::Path::new(
        "levels/kinetics/pendulum_on_accelerating_cart.ron",
    ))
    .expect("a library level");
    app.world_mut()
        .write_message(PhysicsCommand::Open(Box::new(other)));
    app.update();
    app.update();
    let ed = app.world().resource::<rigidlab::app::editor::Editor>();
    assert!(!ed.history.can_undo(), "the last level's edit is offered");
    assert!(ed.note.is_none(), "{:?}", ed.note);
}
