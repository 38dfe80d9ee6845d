//! The keyboard shortcuts (listed in the status bar): play/pause, step, reset, time scale, fit,
//! the mouse tools, clearing the selection, undo/redo/delete for the editor, and screenshots.
//!
//! Chords (Ctrl+Z, Ctrl+Y, Ctrl+Shift+Z, Shift+/) are read from the keyboard's messages in the
//! order they came, with the modifiers held at each key ([`Held`]): a chord pressed and released
//! within one frame (a fast typist, a test driving xdotool) has no modifier down in the frame's
//! key state and did nothing. The keys egui gets go the same way ([`egui_events`], sent by
//! `egui_input.rs` in one order with the pointer's presses).

use super::super::editor::EditorCommand;
use super::super::overlays::Overlays;
use super::super::physics::PhysicsCommand;
use super::super::playback::{play_restarts, Playback};
use super::super::run::Run;
use super::super::tools::{Tool, ToolState};
use super::super::ui::Typing;
use super::super::user_files;
use super::super::view::View;
use super::state::UiState;
use bevy::input::keyboard::{Key, KeyboardInput};
use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};
use bevy_egui::egui;

/// The modifiers held, as the keyboard's messages say, one message at a time.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Held {
    pub ctrl: bool,
    pub shift: bool,
    pub alt: bool,
    /// The Super (Windows, Command) key.
    pub logo: bool,
}

impl Held {
    /// Takes in one key message; true when it was a modifier's.
    pub fn feed(&mut self, e: &KeyboardInput) -> bool {
        let down = e.state.is_pressed();
        let slot = match (&e.logical_key, e.key_code) {
            (Key::Control, _) | (_, KeyCode::ControlLeft | KeyCode::ControlRight) => &mut self.ctrl,
            (Key::Shift, _) | (_, KeyCode::ShiftLeft | KeyCode::ShiftRight) => &mut self.shift,
            (Key::Alt, _) | (_, KeyCode::AltLeft | KeyCode::AltRight) => &mut self.alt,
            (Key::Super | Key::Meta, _) | (_, KeyCode::SuperLeft | KeyCode::SuperRight) => {
                &mut self.logo
            }
            _ => return false,
        };
        *slot = down;
        true
    }

    /// As egui names them (Command is Ctrl, or the Command key on a Mac).
    pub fn egui(&self) -> egui::Modifiers {
        let mac = cfg!(target_os = "macos");
        egui::Modifiers {
            alt: self.alt,
            ctrl: self.ctrl,
            shift: self.shift,
            mac_cmd: mac && self.logo,
            command: if mac { self.logo } else { self.ctrl },
        }
    }
}

/// A shortcut made of a modifier and a key.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Chord {
    Undo,
    Redo,
    Help,
}

/// The chords in `events`, in order, with the modifiers `held` updated message by message.
pub fn chords<'a>(
    held: &mut Held,
    events: impl IntoIterator<Item = &'a KeyboardInput>,
) -> Vec<Chord> {
    let mut out = Vec::new();
    for e in events {
        if held.feed(e) || !e.state.is_pressed() || e.repeat {
            continue;
        }
        let command = held.ctrl || (cfg!(target_os = "macos") && held.logo);
        match e.key_code {
            KeyCode::KeyZ if command => {
                out.push(if held.shift { Chord::Redo } else { Chord::Undo })
            }
            KeyCode::KeyY if command => out.push(Chord::Redo),
            KeyCode::Slash if held.shift && !command => out.push(Chord::Help),
            _ => {}
        }
    }
    out
}

/// The egui events of one key message, the modifiers `held` updated first: text only for a key
/// typed with no Ctrl (Ctrl+A selects all, it does not type "a"; AltGr, Ctrl+Alt, still types).
pub fn egui_events(held: &mut Held, e: &KeyboardInput) -> Vec<egui::Event> {
    held.feed(e);
    let mut out = Vec::new();
    let typing = !(held.logo || held.ctrl) || (!cfg!(target_os = "macos") && held.ctrl && held.alt);
    if typing && e.state.is_pressed() {
        match &e.logical_key {
            Key::Character(c) if !c.chars().any(char::is_control) => {
                out.push(egui::Event::Text(c.to_string()))
            }
            Key::Space => out.push(egui::Event::Text(" ".into())),
            _ => {}
        }
    }
    let physical = bevy_egui::helpers::bevy_to_egui_physical_key(&e.key_code);
    if let Some(key) = bevy_egui::helpers::bevy_to_egui_key(&e.logical_key).or(physical) {
        out.push(egui::Event::Key {
            key,
            physical_key: physical,
            pressed: e.state.is_pressed(),
            repeat: false,
            modifiers: held.egui(),
        });
    }
    out
}

/// What the status line says while keys are not taken as shortcuts: the keyboard is the
/// panels' (a box typed in, a press on a panel).
pub const TYPING_NOTE: &str =
    "keys go to the panels: click the scene (or press Esc) to use the shortcuts";

/// Who owns the keyboard after this frame's mouse presses, before any key of the frame is read
/// as a shortcut: a press on a panel or on a window over the scene gives it to the panels
/// ([`Typing::press`]). egui's own view of the press (which comes after this frame's keys) is
/// taken in after the panels are drawn (`panels/mod.rs`, `tidy_after_frame`).
pub fn follow_presses(
    mouse: Res<ButtonInput<MouseButton>>,
    windows: Query<&Window>,
    view: Res<View>,
    egui_input: Option<Res<bevy_egui::input::EguiWantsInput>>,
    typing: Option<ResMut<Typing>>,
) {
    let Some(mut typing) = typing else {
        return;
    };
    let pressed = mouse.get_just_pressed().next().is_some();
    if !pressed {
        return;
    }
    let cursor = windows.iter().next().and_then(Window::cursor_position);
    let over_egui = egui_input.is_some_and(|e| e.is_pointer_over_area());
    typing.press(pressed, cursor, view.viewport, over_egui);
}

/// The shortcuts, as a Bevy system: only while the keyboard is the scene's, never while a text
/// field has or had it or the last press was on a panel ([`Typing`]), until a click in the
/// scene or Esc.
#[allow(clippy::too_many_arguments)]
pub fn keys(
    keys: Res<ButtonInput<KeyCode>>,
    (mut messages, mut held): (MessageReader<KeyboardInput>, Local<Held>),
    (phys, playback, mut run_commands): (Res<Run>, Res<Playback>, MessageWriter<PhysicsCommand>),
    mut view: ResMut<View>,
    mut ui: ResMut<UiState>,
    mut tools: ResMut<ToolState>,
    mut ov: ResMut<Overlays>,
    mut commands: Commands,
    mut edits: MessageWriter<EditorCommand>,
    egui_input: Option<Res<bevy_egui::input::EguiWantsInput>>,
    (unsaved, typing): (
        Option<Res<super::super::unsaved::Unsaved>>,
        Option<Res<Typing>>,
    ),
) {
    // Read every frame, so the modifiers held stay known while egui has the keyboard.
    let chords = chords(&mut held, messages.read());
    let egui_wants = egui_input.is_some_and(|e| e.wants_any_keyboard_input());
    if !Typing::shortcuts_on(typing.as_deref(), egui_wants) {
        // (The status line says so while it lasts: panels/mod.rs, TYPING_NOTE.)
        return;
    }
    if !super::super::unsaved::not_asking(unsaved) {
        // The unsaved-work question is open: it answers Escape; no edit, undo or run meanwhile.
        return;
    }
    if keys.just_pressed(KeyCode::Space) {
        if play_restarts(&phys, &playback) {
            // The impulse tool's arrow goes with the run it struck.
            tools.last_impulse = None;
        }
        run_commands.write(PhysicsCommand::TogglePlay);
    }
    if keys.just_pressed(KeyCode::KeyS) || keys.just_pressed(KeyCode::ArrowRight) {
        run_commands.write(PhysicsCommand::Step);
    }
    if keys.just_pressed(KeyCode::ArrowLeft) {
        run_commands.write(PhysicsCommand::StepBack);
    }
    if keys.just_pressed(KeyCode::KeyR) {
        tools.last_impulse = None;
        run_commands.write(PhysicsCommand::Restart);
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
    if keys.just_pressed(KeyCode::F1) {
        ui.help = !ui.help;
    }
    for c in chords {
        match c {
            Chord::Undo => {
                edits.write(EditorCommand::Undo);
            }
            Chord::Redo => {
                edits.write(EditorCommand::Redo);
            }
            Chord::Help => ui.help = !ui.help,
        }
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
