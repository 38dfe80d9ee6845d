//! The sandbox's headless app for the window tests (feature `app`): MinimalPlugins with one
//! FixedUpdate per `App::update`, the physics of a new scene (paused) and the editor; the editor
//! commands sent as the panels send them; keyboard messages as the window delivers them.

use bevy::app::ScheduleRunnerPlugin;
use bevy::input::keyboard::{Key, KeyboardInput};
use bevy::input::ButtonState;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use rigidlab::app::editor::{Editor, EditorCommand, EditorPlugin};
use rigidlab::app::{PhysicsPlugin, Run};
use rigidlab::editor;
use rigidlab::level::Level;
use std::path::PathBuf;
use std::time::Duration;

/// The app before its first update (add plugins and resources, then `update`): a new scene
/// (`my-scene.ron`, a ground line), paused, with the editor.
pub fn editor_app_unstarted() -> App {
    let mut app = App::new();
    app.add_plugins(MinimalPlugins.set(ScheduleRunnerPlugin::run_loop(Duration::ZERO)))
        .insert_resource(TimeUpdateStrategy::FixedTimesteps(1))
        .add_plugins(PhysicsPlugin {
            scene: editor::empty_scene(PathBuf::from("my-scene.ron")),
            options: Default::default(),
            paused: true,
        })
        .add_plugins(EditorPlugin);
    app
}

/// [`editor_app_unstarted`], started (its first update run).
pub fn editor_app() -> App {
    let mut app = editor_app_unstarted();
    app.update();
    app
}

/// Sends one editor command and runs a frame: the editor's note and whether it worked.
pub fn send(app: &mut App, c: EditorCommand) -> (String, bool) {
    app.world_mut().write_message(c);
    app.update();
    app.world()
        .resource::<Editor>()
        .note
        .clone()
        .expect("the editor answers every command")
}

pub fn phys(app: &App) -> &Run {
    app.world().resource::<Run>()
}

/// The scene's level on screen.
pub fn level(app: &App) -> &Level {
    &phys(app).scene.level
}

/// A key pressed or released, as the window reports it.
pub fn key(code: KeyCode, key: Key, down: bool) -> KeyboardInput {
    KeyboardInput {
        key_code: code,
        logical_key: key,
        state: if down {
            ButtonState::Pressed
        } else {
            ButtonState::Released
        },
        text: None,
        repeat: false,
        window: Entity::PLACEHOLDER,
    }
}

pub fn ctrl(down: bool) -> KeyboardInput {
    key(KeyCode::ControlLeft, Key::Control, down)
}

pub fn letter(code: KeyCode, c: &str, down: bool) -> KeyboardInput {
    key(code, Key::Character(c.into()), down)
}

/// Ctrl down, the key down and up, Ctrl up: all of it within one frame.
pub fn quick_chord(code: KeyCode, c: &str) -> Vec<KeyboardInput> {
    vec![
        ctrl(true),
        letter(code, c, true),
        letter(code, c, false),
        ctrl(false),
    ]
}
