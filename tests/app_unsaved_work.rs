//! Unsaved work is asked about before it is thrown away (src/app/unsaved.rs): the editor knows
//! when the scene has edits not saved (an edit undone is none), the window's close button closes
//! at once when there is nothing to lose and asks otherwise, and the question's answers do what
//! they say. Headless: MinimalPlugins, the physics, the editor and the question's plugin, and a
//! bare window entity for the close request.
#![cfg(feature = "app")]

use bevy::app::ScheduleRunnerPlugin;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy::window::WindowCloseRequested;
use rigidlab::app::editor::{Editor, EditorCommand, EditorPlugin};
use rigidlab::app::unsaved::{Answer, Leaving, Unsaved, UnsavedPlugin};
use rigidlab::app::{Physics, PhysicsPlugin};
use rigidlab::editor::{self, Edit, Property};
use std::path::PathBuf;
use std::time::Duration;

fn app() -> App {
    let mut app = App::new();
    app.add_plugins(MinimalPlugins.set(ScheduleRunnerPlugin::run_loop(Duration::ZERO)))
        .insert_resource(TimeUpdateStrategy::FixedTimesteps(1))
        .add_plugins(PhysicsPlugin {
            scene: editor::empty_scene(PathBuf::from("my-scene.ron")),
            options: Default::default(),
            paused: true,
        })
        .add_plugins((EditorPlugin, UnsavedPlugin));
    app.update();
    app
}

fn unsaved(app: &App) -> bool {
    app.world()
        .resource::<Editor>()
        .unsaved(app.world().resource::<Physics>())
}

fn lower_ground(app: &mut App) {
    let name = app.world().resource::<Physics>().scene.level.bodies[0]
        .name
        .clone();
    app.world_mut()
        .write_message(EditorCommand::Apply(Edit::Set {
            body: name,
            property: Property::Position((0.0, -1.0)),
        }));
    app.update();
}

fn close(app: &mut App, window: Entity) {
    app.world_mut()
        .write_message(WindowCloseRequested { window });
    app.update();
}

#[test]
fn the_editor_knows_what_is_unsaved() {
    let mut app = app();
    assert!(!unsaved(&app), "a scene just opened has nothing to lose");
    lower_ground(&mut app);
    assert!(unsaved(&app), "an edit is unsaved work");
    app.world_mut().write_message(EditorCommand::Undo);
    app.update();
    assert!(!unsaved(&app), "the edit undone: the scene is as opened");
    app.world_mut().write_message(EditorCommand::Redo);
    app.update();
    assert!(unsaved(&app));
    // Saved: nothing unsaved (into a fresh folder: a save never replaces a file).
    let dir = std::env::temp_dir().join(format!("rigidlab-unsaved-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    app.world_mut()
        .write_message(EditorCommand::Save(dir.join("scene.ron")));
    app.update();
    let note = app.world().resource::<Editor>().note.clone().unwrap();
    assert!(note.1, "{}", note.0);
    assert!(!unsaved(&app), "saved, still unsaved");
    lower_ground(&mut app);
    let name = app.world().resource::<Physics>().scene.level.bodies[0]
        .name
        .clone();
    app.world_mut()
        .write_message(EditorCommand::Apply(Edit::Set {
            body: name,
            property: Property::Position((0.0, -2.0)),
        }));
    app.update();
    assert!(unsaved(&app), "an edit after the save is unsaved");
    // A new scene is nothing to lose yet.
    app.world_mut().write_message(EditorCommand::New);
    app.update();
    assert!(!unsaved(&app));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn closing_the_window_asks_only_when_there_is_something_to_lose() {
    let mut app = app();
    // Nothing edited: the close button closes.
    let w = app.world_mut().spawn_empty().id();
    close(&mut app, w);
    assert!(app.world().get_entity(w).is_err(), "the window stayed open");
    assert!(app.world().resource::<Unsaved>().asking.is_none());

    // Edited: the window stays and the question is asked.
    let w = app.world_mut().spawn_empty().id();
    lower_ground(&mut app);
    close(&mut app, w);
    assert!(
        app.world().get_entity(w).is_ok(),
        "closed with unsaved edits"
    );
    assert_eq!(
        app.world().resource::<Unsaved>().asking,
        Some(Leaving::Close(w))
    );
    // A second click on the close button keeps the one question.
    close(&mut app, w);
    // Cancel: nothing happens; Discard: the close goes on.
    let mut u = app.world_mut().resource_mut::<Unsaved>();
    assert_eq!(u.answer(Answer::Cancel), None);
    assert!(u.asking.is_none());
    close(&mut app, w);
    let mut u = app.world_mut().resource_mut::<Unsaved>();
    assert_eq!(u.answer(Answer::Discard), Some(Leaving::Close(w)));
    assert!(u.asking.is_none());
}

#[test]
fn opening_another_level_or_a_new_scene_asks_when_there_is_something_to_lose() {
    let other = rigidlab::level::load(std::path::Path::new(
        "levels/kinetics/physical_pendulum.ron",
    ))
    .unwrap();
    let mut u = Unsaved::default();
    // Nothing to lose: go on at once.
    assert_eq!(u.request(false, Leaving::New), Some(Leaving::New));
    assert!(u.asking.is_none());
    // Something to lose: asked; Save and Discard go on with what was asked, Cancel stays.
    let open = Leaving::Open(Box::new(other));
    assert_eq!(u.request(true, open.clone()), None);
    assert_eq!(u.asking, Some(open.clone()));
    // While a question is open a second request does not replace it.
    assert_eq!(u.request(true, Leaving::New), None);
    assert_eq!(u.answer(Answer::Save), Some(open));
    assert_eq!(u.request(true, Leaving::New), None);
    assert_eq!(u.answer(Answer::Cancel), None);
    assert_eq!(u.answer(Answer::Discard), None, "answered twice");
}
