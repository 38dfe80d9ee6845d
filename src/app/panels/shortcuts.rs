//! The keyboard shortcuts (listed in the status bar): play/pause, step, reset, time scale, fit,
//! the mouse tools, clearing the selection, undo/redo/delete for the editor, and screenshots.

use super::super::editor::EditorCommand;
use super::super::overlays::Overlays;
use super::super::physics::Physics;
use super::super::playback::{restart, step_back, toggle_play};
use super::super::tools::{Tool, ToolState};
use super::super::user_files;
use super::super::view::View;
use super::UiState;
use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};

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
        // Named by level and time, with a counter where the name is taken; the status line
        // says where it went once it is written, or why it could not be.
        let path = user_files::screenshot_path(&phys.scene.file, phys.snapshot().time);
        ui.message = Some((format!("taking a screenshot for {}", path.display()), true));
        commands.spawn(Screenshot::primary_window()).observe(
            move |shot: On<ScreenshotCaptured>, mut ui: ResMut<UiState>| {
                let result = user_files::save_screenshot(&shot.image, &path);
                if let Err(e) = &result {
                    warn!("{e}");
                }
                ui.message = Some(match result {
                    Ok(m) => (m, true),
                    Err(e) => (e, false),
                });
            },
        );
    }
}
