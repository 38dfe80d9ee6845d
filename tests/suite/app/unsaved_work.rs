//! Unsaved work is asked about before it is thrown away (src/app/unsaved.rs): the editor knows
//! when the scene has edits not saved (an edit undone is none), the window's close button closes
//! at once when there is nothing to lose and asks otherwise, and the question's answers do what
//! they say. Headless: MinimalPlugins, the physics, the editor and the question's plugin, and a
//! bare window entity for the close request.

use crate::common;

use bevy::input::InputPlugin;
use bevy::prelude::*;
use bevy::window::WindowCloseRequested;
use common::app::{editor_app_unstarted, quick_chord};
use rigidlab::app::editor::{Editor, EditorCommand};
use rigidlab::app::overlays::Overlays;
use rigidlab::app::panels::shortcuts;
use rigidlab::app::panels::UiState;
use rigidlab::app::tools::ToolState;
use rigidlab::app::unsaved::{Answer, Leaving, Unsaved, UnsavedPlugin};
use rigidlab::app::view::View;
use rigidlab::app::Run;
use rigidlab::editor::{Edit, Property};
use std::path::{Path, PathBuf};

fn app() -> App {
    let mut app = editor_app_unstarted();
    app.add_plugins(UnsavedPlugin);
    app.update();
    app
}

fn unsaved(app: &App) -> bool {
    app.world()
        .resource::<Editor>()
        .unsaved(app.world().resource::<Run>())
}

fn lower_ground(app: &mut App) {
    let name = app.world().resource::<Run>().scene.level.bodies[0]
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
    let name = app.world().resource::<Run>().scene.level.bodies[0]
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
    let other = common::load("levels/kinetics/physical_pendulum.ron");
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

/// A fresh folder for this test's saves (a save never replaces a file).
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rigidlab-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The panel's part: the answer clicked, settled as `src/app/panels/mod.rs` does (the save
/// first, then the action), and the window closed where the action is to close it.
fn click(app: &mut App, answer: Answer, save_as: &Path) -> Result<Option<Leaving>, String> {
    let world = app.world_mut();
    let settled = world.resource_scope(|world, mut u: Mut<Unsaved>| {
        world.resource_scope(|world, mut editor: Mut<Editor>| {
            u.settle(answer, &mut editor, world.resource::<Run>(), save_as)
        })
    });
    if let Ok((Some(Leaving::Close(w)), _)) = &settled {
        world.entity_mut(*w).despawn();
    }
    app.update();
    settled.map(|(go, _)| go)
}

#[test]
fn closing_with_unsaved_edits_waits_for_the_answer_and_each_answer_does_what_it_says() {
    let dir = scratch("unsaved-close");
    let mut app = app();
    let w = app.world_mut().spawn_empty().id();
    lower_ground(&mut app);
    close(&mut app, w);
    // It waits: a hundred frames later the window is there and the question still open.
    for _ in 0..100 {
        app.update();
    }
    assert!(
        app.world().get_entity(w).is_ok(),
        "closed without an answer"
    );
    assert_eq!(
        app.world().resource::<Unsaved>().asking,
        Some(Leaving::Close(w))
    );

    // Cancel: the window stays, the edits stay unsaved, nothing written.
    assert_eq!(
        click(&mut app, Answer::Cancel, &dir.join("a.ron")),
        Ok(None)
    );
    assert!(app.world().get_entity(w).is_ok());
    assert!(unsaved(&app), "cancel lost the edits");
    assert!(!dir.join("a.ron").exists(), "cancel saved");

    // Save into a place that cannot be written (a folder under a plain file): the question
    // stays open with why, and the window stays.
    std::fs::write(dir.join("plain"), "x").unwrap();
    close(&mut app, w);
    let why = click(&mut app, Answer::Save, &dir.join("plain").join("a.ron")).unwrap_err();
    assert!(why.starts_with("not saved"), "{why}");
    assert!(
        app.world().resource::<Unsaved>().asking.is_some(),
        "question dropped"
    );
    assert!(
        app.world().get_entity(w).is_ok(),
        "closed although the save failed"
    );
    assert!(unsaved(&app));

    // Save: the scene is written (and loads back as the scene on screen), then the window goes.
    let saved = dir.join("scene.ron");
    assert_eq!(
        click(&mut app, Answer::Save, &saved),
        Ok(Some(Leaving::Close(w)))
    );
    let back = rigidlab::level::load(&saved).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(back.level, app.world().resource::<Run>().scene.level);
    assert_eq!(
        back.level.bodies[0].position.1, -1.0,
        "the edit was not saved"
    );
    assert!(app.world().get_entity(w).is_err(), "saved but not closed");
    assert!(!unsaved(&app));

    // Discard: nothing written, the window goes.
    let w = app.world_mut().spawn_empty().id();
    lower_ground(&mut app);
    let name = app.world().resource::<Run>().scene.level.bodies[0]
        .name
        .clone();
    app.world_mut()
        .write_message(EditorCommand::Apply(Edit::Set {
            body: name,
            property: Property::Position((0.0, -3.0)),
        }));
    app.update();
    close(&mut app, w);
    assert_eq!(
        click(&mut app, Answer::Discard, &dir.join("discarded.ron")),
        Ok(Some(Leaving::Close(w)))
    );
    assert!(!dir.join("discarded.ron").exists(), "discard saved");
    assert!(
        app.world().get_entity(w).is_err(),
        "discarded but not closed"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// While the question is open the keyboard's shortcuts wait (they edited the scene behind it:
/// Ctrl+Z undid an edit the question was about); its answer given, they work again.
#[test]
fn shortcuts_wait_while_the_question_is_open() {
    let mut app = editor_app_unstarted();
    app.add_plugins((InputPlugin, UnsavedPlugin))
        .init_resource::<View>()
        .init_resource::<UiState>()
        .init_resource::<ToolState>()
        .init_resource::<Overlays>()
        .add_systems(Update, shortcuts::keys);
    app.update();
    let ground_y = |app: &App| {
        app.world().resource::<Run>().scene.level.bodies[0]
            .position
            .1
    };
    let before = ground_y(&app);
    lower_ground(&mut app);
    let w = app.world_mut().spawn_empty().id();
    close(&mut app, w);
    assert!(app.world().resource::<Unsaved>().asking.is_some());
    for m in quick_chord(KeyCode::KeyZ, "z") {
        app.world_mut().write_message(m);
    }
    app.update();
    app.update();
    assert_eq!(
        ground_y(&app),
        -1.0,
        "Ctrl+Z undid the edit behind the question"
    );
    app.world_mut()
        .resource_mut::<Unsaved>()
        .answer(Answer::Cancel);
    for m in quick_chord(KeyCode::KeyZ, "z") {
        app.world_mut().write_message(m);
    }
    app.update();
    app.update();
    assert_eq!(
        ground_y(&app),
        before,
        "Ctrl+Z after the answer did nothing"
    );
}
