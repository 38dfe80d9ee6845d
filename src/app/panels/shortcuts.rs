//! The keyboard shortcuts (listed in the status bar): play/pause, step, reset, time scale, fit,
//! the mouse tools, clearing the selection, undo/redo/delete for the editor, and screenshots.

use super::super::editor::EditorCommand;
use super::super::overlays::Overlays;
use super::super::physics::Physics;
use super::super::playback::{restart, step_back, toggle_play};
use super::super::tools::{Tool, ToolState};
use super::super::view::View;
use super::UiState;
use bevy::prelude::*;
use bevy::render::view::screenshot::{save_to_disk, Screenshot};

/// The shortcuts, as a Bevy system (ignored while egui has the keyboard, e.g. in an answer box).
#[allow(clippy::too_many_arguments)]
pub(super) fn keys(
    keys: Res<ButtonInput<KeyCode>>,
    mut phys: ResMut<Physics>,
    mut view: ResMut<View>,
    mut ui: ResMut<UiState>,
    mut tools: ResMut<ToolState>,
    mut ov: ResMut<Overlays>,
    mut commands: Commands,
    mut edits: MessageWriter<EditorCommand>,
    egui_input: Option<Res<bevy_egui::input::EguiWantsInput>>,
) {
    if egui_input.is_some_and(|e| e.wants_any_keyboard_input()) {
        return;
    }
    if keys.just_pressed(KeyCode::Space) {
        toggle_play(&mut phys, &mut tools);
    }
    if keys.just_pressed(KeyCode::KeyS) || keys.just_pressed(KeyCode::ArrowRight) {
        phys.paused = true;
        phys.steps_requested += 1;
    }
    if keys.just_pressed(KeyCode::ArrowLeft) {
        step_back(&mut phys);
    }
    if keys.just_pressed(KeyCode::KeyR) {
        restart(&mut phys, &mut tools);
    }
    if keys.just_pressed(KeyCode::Home) {
        view.fit = true;
        view.follow = None;
    }
    if keys.just_pressed(KeyCode::Minus) {
        ui.time_scale = (ui.time_scale / 2.0).max(1.0 / 64.0);
    }
    if keys.just_pressed(KeyCode::Equal) {
        ui.time_scale = (ui.time_scale * 2.0).min(8.0);
    }
    if keys.just_pressed(KeyCode::Digit1) {
        tools.tool = Tool::Select;
    }
    if keys.just_pressed(KeyCode::Digit2) {
        tools.tool = Tool::Impulse;
    }
    if keys.just_pressed(KeyCode::Digit3) {
        tools.tool = Tool::SetOrigin;
    }
    if keys.just_pressed(KeyCode::Escape) {
        ov.selected = None;
        ov.point = None;
    }
    let shift = keys.any_pressed([KeyCode::ShiftLeft, KeyCode::ShiftRight]);
    if keys.just_pressed(KeyCode::F1) || (shift && keys.just_pressed(KeyCode::Slash)) {
        ui.help = !ui.help;
    }
    let ctrl = keys.any_pressed([KeyCode::ControlLeft, KeyCode::ControlRight]);
    if ctrl && keys.just_pressed(KeyCode::KeyZ) {
        edits.write(if shift {
            EditorCommand::Redo
        } else {
            EditorCommand::Undo
        });
    }
    if ctrl && keys.just_pressed(KeyCode::KeyY) {
        edits.write(EditorCommand::Redo);
    }
    if keys.just_pressed(KeyCode::Delete) {
        if let Some(b) = ov.selected.and_then(|i| phys.scene.level.bodies.get(i)) {
            edits.write(EditorCommand::Apply(crate::editor::Edit::Delete {
                body: b.name.clone(),
            }));
            ov.selected = None;
            ov.point = None;
        }
    }
    if keys.just_pressed(KeyCode::F12) {
        let name = screenshot_path(phys.snapshot().time);
        ui.message = Some((format!("screenshot saved to {name}"), true));
        commands
            .spawn(Screenshot::primary_window())
            .observe(save_to_disk(name));
    }
}

/// Where F12 puts a screenshot: `screenshots/` of the working directory in the window (made if
/// missing), a download in the web page.
fn screenshot_path(t: f64) -> String {
    let name = format!("rigidlab-{t:.3}s.png");
    if cfg!(target_arch = "wasm32") {
        return name;
    }
    match std::fs::create_dir_all("screenshots") {
        Ok(()) => format!("screenshots/{name}"),
        Err(_) => name,
    }
}
