//! Key chords are read from the keyboard's messages in order (src/app/panels/shortcuts.rs):
//! Ctrl+Z and Ctrl+Y pressed and released within one frame undo and redo (they did nothing:
//! the frame's key state had no Ctrl down at its end), and Ctrl+A reaches egui as "select all",
//! not as the letter a. Headless: MinimalPlugins, Bevy's input plugin, the editor.

use crate::common;

use bevy::input::keyboard::Key;
use bevy::input::InputPlugin;
use bevy::prelude::*;
use bevy_egui::egui;
use common::app::{ctrl, editor_app_unstarted, key, letter, quick_chord};
use rigidlab::app::editor::{Editor, EditorCommand};
use rigidlab::app::overlays::Overlays;
use rigidlab::app::panels::shortcuts::{self, chords, egui_events, Chord, Held};
use rigidlab::app::panels::UiState;
use rigidlab::app::tools::ToolState;
use rigidlab::app::view::View;
use rigidlab::app::Run;
use rigidlab::editor::{Edit, Property};

#[test]
fn chords_are_read_in_order() {
    let mut held = Held::default();
    assert_eq!(
        chords(&mut held, &quick_chord(KeyCode::KeyZ, "z")),
        [Chord::Undo]
    );
    assert_eq!(held, Held::default(), "Ctrl stays down after its release");
    assert_eq!(
        chords(&mut held, &quick_chord(KeyCode::KeyY, "y")),
        [Chord::Redo]
    );
    // Ctrl released before Z: no chord (the order matters, not the frame).
    let late = [
        ctrl(true),
        ctrl(false),
        letter(KeyCode::KeyZ, "z", true),
        letter(KeyCode::KeyZ, "z", false),
    ];
    assert!(chords(&mut held, &late).is_empty());
    // Ctrl+Shift+Z is redo; Ctrl held over two frames still makes the chord.
    let shift = |d| key(KeyCode::ShiftLeft, Key::Shift, d);
    assert!(chords(&mut held, &[ctrl(true), shift(true)]).is_empty());
    assert_eq!(
        chords(&mut held, &[letter(KeyCode::KeyZ, "Z", true)]),
        [Chord::Redo]
    );
}

#[test]
fn ctrl_a_selects_all_and_types_nothing() {
    let mut held = Held::default();
    let events: Vec<egui::Event> = quick_chord(KeyCode::KeyA, "a")
        .iter()
        .flat_map(|e| egui_events(&mut held, e))
        .collect();
    assert!(
        !events.iter().any(|e| matches!(e, egui::Event::Text(_))),
        "Ctrl+A typed text: {events:?}"
    );
    assert!(
        events.iter().any(|e| matches!(
            e,
            egui::Event::Key { key: egui::Key::A, pressed: true, modifiers, .. } if modifiers.command
        )),
        "no Ctrl+A key for egui: {events:?}"
    );
    // A plain a still types.
    let typed = egui_events(&mut held, &letter(KeyCode::KeyA, "a", true));
    assert!(typed.contains(&egui::Event::Text("a".into())), "{typed:?}");
}

#[test]
fn undo_and_redo_pressed_within_one_frame_work_in_the_app() {
    let mut app = editor_app_unstarted();
    app.add_plugins(InputPlugin)
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
    let name = app.world().resource::<Run>().scene.level.bodies[0]
        .name
        .clone();
    app.world_mut()
        .write_message(EditorCommand::Apply(Edit::Set {
            body: name,
            property: Property::Position((0.0, before - 1.0)),
        }));
    app.update();
    assert_eq!(ground_y(&app), before - 1.0, "the edit was not applied");

    let note = |app: &App| app.world().resource::<Editor>().note.clone().unwrap().0;
    for m in quick_chord(KeyCode::KeyZ, "z") {
        app.world_mut().write_message(m);
    }
    app.update();
    app.update();
    assert_eq!(note(&app), "undone");
    assert_eq!(ground_y(&app), before);
    for m in quick_chord(KeyCode::KeyY, "y") {
        app.world_mut().write_message(m);
    }
    app.update();
    app.update();
    assert_eq!(note(&app), "redone");
    assert_eq!(ground_y(&app), before - 1.0);
}
